/* neuv remesh IN -o OUT [--simplify R] [--subdivide N [--loop]] [--jitter] [--seed S]
 * neuv remesh IN -o OUT (--isotropic L | --faces N) [--jitter] [--seed S]
 * Another discretization of the same surface: simplification (meshoptimizer),
 * midpoint or Loop subdivision, and jitter within the surface, applied in
 * that order (at least one of them); or an isotropic remeshing (CGAL) that
 * shares no vertex with the input off its feature and boundary polylines,
 * optionally jittered.
 * The input is cleaned first. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/commands.h"
#include "core/timer.h"
#include "mesh/clean.h"
#include "remesh/isotropic_remesh.h"
#include "remesh/jitter.h"
#include "remesh/simplify.h"
#include "remesh/subdivide.h"

#define REMESH_USAGE "usage: neuv remesh IN -o OUT (--simplify R | --subdivide N [--loop] | --isotropic L | --faces N) " \
                     "[--jitter] [--seed S]"

int cmd_remesh(int argc, char **argv)
{
    const char *in = NULL, *out = NULL;
    double ratio = -1, edge_length = 0;
    int rounds = 0, loop = 0, jitter = 0, seed = 1, have_simplify = 0, have_subdivide = 0, bad = 0;
    int target_faces = 0, have_isotropic = 0, have_faces = 0;
    for (int i = 1; i < argc && !bad; i++) {
        if (cli_arg_global(argc, argv, &i, &bad)) continue;
        if (cli_arg_str(argc, argv, &i, "-o", &out, &bad)) continue;
        if (cli_arg_double(argc, argv, &i, "--simplify", &ratio, &bad)) { have_simplify = 1; continue; }
        if (cli_arg_int(argc, argv, &i, "--subdivide", &rounds, &bad)) { have_subdivide = 1; continue; }
        if (cli_arg_double(argc, argv, &i, "--isotropic", &edge_length, &bad)) { have_isotropic = 1; continue; }
        if (cli_arg_int(argc, argv, &i, "--faces", &target_faces, &bad)) { have_faces = 1; continue; }
        if (cli_arg_int(argc, argv, &i, "--seed", &seed, &bad)) continue;
        if (!strcmp(argv[i], "--loop")) { loop = 1; continue; }
        if (!strcmp(argv[i], "--jitter")) { jitter = 1; continue; }
        if (argv[i][0] == '-' && argv[i][1]) return cli_error(NULL, "remesh: unknown option '%s'", argv[i]);
        if (in) return cli_error(NULL, "remesh: one input file expected, got '%s' and '%s'", in, argv[i]);
        in = argv[i];
    }
    if (bad) return 2;
    if (!in || !out) return cli_error(NULL, REMESH_USAGE);
    if (!have_simplify && !have_subdivide && !have_isotropic && !have_faces && !jitter)
        return cli_error(NULL, "remesh: nothing to do: give --simplify R, --subdivide N, --isotropic L, --faces N "
                               "or --jitter");
    if (have_isotropic && have_faces)
        return cli_error(NULL, "--isotropic L and --faces N are two ways to give the same target: give one");
    if ((have_isotropic || have_faces) && (have_simplify || have_subdivide))
        return cli_error(NULL, "--%s builds a new triangulation: it does not combine with --simplify or --subdivide",
                         have_isotropic ? "isotropic" : "faces");
    if (have_isotropic && !(edge_length > 0))
        return cli_error(NULL, "--isotropic expects an edge length > 0, got %g", edge_length);
    if (have_faces && target_faces < 4) return cli_error(NULL, "--faces expects at least 4 faces, got %d", target_faces);
    if (have_simplify && !(ratio > 0 && ratio <= 1))
        return cli_error(NULL, "--simplify expects a ratio in (0, 1], got %g", ratio);
    if (have_subdivide && (rounds < 1 || rounds > 5))
        return cli_error(NULL, "--subdivide expects 1 to 5 rounds, got %d", rounds);
    if (loop && !have_subdivide) return cli_error(NULL, "--loop needs --subdivide N");
    if (cli_check_output_not_input(out, in)) return 2;

    double t0 = now_seconds();
    neuv_mesh *m = NULL;
    neuv_clean_report rep;
    int rc = cli_load_clean(in, &m, &rep);
    if (rc) return rc;
    neuv_status st;
    if (!cli_opts.quiet) printf("%s: %d vertices, %d faces%s\n", in, m->nv, m->nf, m->nuv > 0 ? ", with UVs" : "");
    if (have_simplify) {
        neuv_mesh *s;
        if ((st = mesh_simplify(m, ratio, &s))) { mesh_free(m); return cli_fail(in, st); }
        if (!cli_opts.quiet) printf("  simplify %g: %d -> %d faces (target %.0f)\n", ratio, m->nf, s->nf, ratio * m->nf);
        mesh_free(m);
        m = s;
    }
    if (have_subdivide) {
        neuv_mesh *s;
        if ((st = mesh_subdivide(m, rounds, loop ? SUBDIVIDE_LOOP : SUBDIVIDE_MIDPOINT, &s))) {
            mesh_free(m);
            return cli_fail(in, st);
        }
        if (!cli_opts.quiet) printf("  subdivide %d (%s): %d -> %d faces\n", rounds, loop ? "loop" : "midpoint", m->nf, s->nf);
        mesh_free(m);
        m = s;
    }
    if (have_isotropic || have_faces) {
        isotropic_options io;
        isotropic_report ir;
        isotropic_default_options(&io);
        io.target_edge_length = have_isotropic ? edge_length : 0;
        io.target_faces = have_faces ? target_faces : 0;
        neuv_mesh *s;
        if ((st = mesh_remesh_isotropic(m, &io, &s, &ir))) { mesh_free(m); return cli_fail(in, st); }
        double lo[3], hi[3];
        mesh_bounding_box(m, lo, hi);
        double diag = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                           (hi[2] - lo[2]) * (hi[2] - lo[2]));
        char target[64] = "";
        if (have_faces) snprintf(target, sizeof target, " (target %d, %d round%s)", target_faces, ir.rounds,
                                 ir.rounds == 1 ? "" : "s");
        if (!cli_opts.quiet) printf("  isotropic: %d -> %d faces%s, edge length %.4g, %d feature edges kept (%d in the input), "
               "max distance to the input %.2g of the bounding-box diagonal\n", ir.faces_in, ir.faces_out, target,
               ir.edge_length, ir.feature_edges_out, ir.feature_edges_in, diag > 0 ? ir.max_distance / diag : 0.0);
        mesh_free(m);
        m = s;
    }
    if (jitter) {
        jitter_report jr;
        if ((st = mesh_jitter(m, (uint64_t)(uint32_t)seed, NULL, &jr))) { mesh_free(m); return cli_fail(in, st); }
        if (!cli_opts.quiet) printf("  jitter (seed %d): %d vertices moved, %d slid along the boundary, %d kept, %d edges flipped, "
               "max deviation %.3g\n", seed, jr.moved_vertices, jr.slid_vertices, jr.fixed_vertices, jr.flipped_edges,
               jr.max_deviation);
    }
    if ((st = neuv_mesh_save(m, out))) { mesh_free(m); return cli_fail(out, st); }
    if (!cli_opts.quiet) printf("%s: %d vertices, %d faces%s (%.3f s)\n", out, m->nv, m->nf, m->nuv > 0 ? ", with UVs" : "",
           now_seconds() - t0);
    mesh_free(m);
    return 0;
}
