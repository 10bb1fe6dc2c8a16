/* neuv remesh IN -o OUT [--simplify R] [--subdivide N [--loop]] [--jitter] [--seed S]
 * neuv remesh IN -o OUT (--isotropic L | --faces N) [--jitter] [--seed S]
 * Another discretization of the same surface: simplification (meshoptimizer),
 * midpoint or Loop subdivision, and jitter within the surface, applied in
 * that order (at least one of them); or an isotropic remeshing (CGAL) that
 * shares no vertex with the input off its feature and boundary polylines,
 * optionally jittered.
 * The input is cleaned first. */
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/commands.h"

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

    double t0 = cli_now_seconds();
    neuv_mesh *m = NULL;
    neuv_clean_report rep;
    int rc = cli_load_clean(in, &m, &rep);
    if (rc) return rc;
    neuv_status st;
    if (!cli_opts.quiet)
        printf("%s: %d vertices, %d faces%s\n", in, neuv_mesh_vertex_count(m), neuv_mesh_face_count(m),
               neuv_mesh_has_uv(m) ? ", with UVs" : "");
    if (have_simplify) {
        neuv_mesh *s;
        if ((st = neuv_mesh_simplify(m, ratio, cli_callbacks(), &s))) { neuv_mesh_free(m); return cli_fail(in, st); }
        if (!cli_opts.quiet)
            printf("  simplify %g: %d -> %d faces (target %.0f)\n", ratio, neuv_mesh_face_count(m),
                   neuv_mesh_face_count(s), ratio * neuv_mesh_face_count(m));
        neuv_mesh_free(m);
        m = s;
    }
    if (have_subdivide) {
        neuv_mesh *s;
        if ((st = neuv_mesh_subdivide(m, rounds, loop ? NEUV_SUBDIVIDE_LOOP : NEUV_SUBDIVIDE_MIDPOINT, &s))) {
            neuv_mesh_free(m);
            return cli_fail(in, st);
        }
        if (!cli_opts.quiet)
            printf("  subdivide %d (%s): %d -> %d faces\n", rounds, loop ? "loop" : "midpoint", neuv_mesh_face_count(m),
                   neuv_mesh_face_count(s));
        neuv_mesh_free(m);
        m = s;
    }
    if (have_isotropic || have_faces) {
        neuv_isotropic_options io;
        neuv_isotropic_report ir;
        neuv_isotropic_options_init(&io);
        io.edge_length = have_isotropic ? edge_length : 0;
        io.faces = have_faces ? target_faces : 0;
        neuv_mesh *s;
        if ((st = neuv_mesh_remesh_isotropic(m, &io, cli_callbacks(), &s, &ir))) {
            neuv_mesh_free(m);
            return cli_fail(in, st);
        }
        char target[64] = "";
        if (have_faces) snprintf(target, sizeof target, " (target %d, %d round%s)", target_faces, ir.rounds,
                                 ir.rounds == 1 ? "" : "s");
        if (!cli_opts.quiet) printf("  isotropic: %d -> %d faces%s, edge length %.4g, %d feature edges kept (%d in the input), "
               "max distance to the input %.2g of the bounding-box diagonal\n", ir.faces_in, ir.faces_out, target,
               ir.edge_length, ir.feature_edges_out, ir.feature_edges_in,
               ir.diagonal > 0 ? ir.max_distance / ir.diagonal : 0.0);
        neuv_mesh_free(m);
        m = s;
    }
    if (jitter) {
        neuv_jitter_report jr;
        if ((st = neuv_mesh_jitter(m, (unsigned long long)(unsigned)seed, &jr))) {
            neuv_mesh_free(m);
            return cli_fail(in, st);
        }
        if (!cli_opts.quiet) printf("  jitter (seed %d): %d vertices moved, %d slid along the boundary, %d kept, %d edges flipped, "
               "max deviation %.3g\n", seed, jr.moved_vertices, jr.slid_vertices, jr.fixed_vertices, jr.flipped_edges,
               jr.max_deviation);
    }
    if ((st = neuv_mesh_save(m, out))) { neuv_mesh_free(m); return cli_fail(out, st); }
    if (!cli_opts.quiet)
        printf("%s: %d vertices, %d faces%s (%.3f s)\n", out, neuv_mesh_vertex_count(m), neuv_mesh_face_count(m),
               neuv_mesh_has_uv(m) ? ", with UVs" : "", cli_now_seconds() - t0);
    neuv_mesh_free(m);
    return 0;
}
