/* neuv remesh IN -o OUT [--simplify R] [--subdivide N [--loop]] [--jitter] [--seed S]
 * Another discretization of the same surface: simplification (meshoptimizer),
 * midpoint or Loop subdivision, and jitter within the surface, applied in
 * that order (at least one of them). The input is cleaned first. */
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/commands.h"
#include "core/timer.h"
#include "mesh/clean.h"
#include "remesh/jitter.h"
#include "remesh/simplify.h"
#include "remesh/subdivide.h"

#define REMESH_USAGE "usage: neuv remesh IN -o OUT (--simplify R | --subdivide N [--loop]) [--jitter] [--seed S]"

int cmd_remesh(int argc, char **argv)
{
    const char *in = NULL, *out = NULL;
    double ratio = -1;
    int rounds = 0, loop = 0, jitter = 0, seed = 1, have_simplify = 0, have_subdivide = 0, bad = 0;
    for (int i = 1; i < argc && !bad; i++) {
        if (cli_arg_global(argc, argv, &i, &bad)) continue;
        if (cli_arg_str(argc, argv, &i, "-o", &out, &bad)) continue;
        if (cli_arg_double(argc, argv, &i, "--simplify", &ratio, &bad)) { have_simplify = 1; continue; }
        if (cli_arg_int(argc, argv, &i, "--subdivide", &rounds, &bad)) { have_subdivide = 1; continue; }
        if (cli_arg_int(argc, argv, &i, "--seed", &seed, &bad)) continue;
        if (!strcmp(argv[i], "--loop")) { loop = 1; continue; }
        if (!strcmp(argv[i], "--jitter")) { jitter = 1; continue; }
        if (argv[i][0] == '-' && argv[i][1]) return cli_error(NULL, "remesh: unknown option '%s'", argv[i]);
        if (in) return cli_error(NULL, "remesh: one input file expected, got '%s' and '%s'", in, argv[i]);
        in = argv[i];
    }
    if (bad) return 2;
    if (!in || !out) return cli_error(NULL, REMESH_USAGE);
    if (!have_simplify && !have_subdivide && !jitter)
        return cli_error(NULL, "remesh: nothing to do: give --simplify R, --subdivide N or --jitter");
    if (have_simplify && !(ratio > 0 && ratio <= 1))
        return cli_error(NULL, "--simplify expects a ratio in (0, 1], got %g", ratio);
    if (have_subdivide && (rounds < 1 || rounds > 5))
        return cli_error(NULL, "--subdivide expects 1 to 5 rounds, got %d", rounds);
    if (loop && !have_subdivide) return cli_error(NULL, "--loop needs --subdivide N");
    if (cli_check_output_not_input(out, in)) return 2;

    double t0 = now_seconds();
    neuv_mesh *m = NULL;
    mesh_clean_report rep;
    int rc = cli_load_clean(in, &m, &rep);
    if (rc) return rc;
    neuv_status st;
    printf("%s: %d vertices, %d faces%s\n", in, m->nv, m->nf, m->nuv > 0 ? ", with UVs" : "");
    if (have_simplify) {
        neuv_mesh *s;
        if ((st = mesh_simplify(m, ratio, &s))) { mesh_free(m); return cli_fail(in, st); }
        printf("  simplify %g: %d -> %d faces (target %.0f)\n", ratio, m->nf, s->nf, ratio * m->nf);
        mesh_free(m);
        m = s;
    }
    if (have_subdivide) {
        neuv_mesh *s;
        if ((st = mesh_subdivide(m, rounds, loop ? SUBDIVIDE_LOOP : SUBDIVIDE_MIDPOINT, &s))) {
            mesh_free(m);
            return cli_fail(in, st);
        }
        printf("  subdivide %d (%s): %d -> %d faces\n", rounds, loop ? "loop" : "midpoint", m->nf, s->nf);
        mesh_free(m);
        m = s;
    }
    if (jitter) {
        jitter_report jr;
        if ((st = mesh_jitter(m, (uint64_t)(uint32_t)seed, NULL, &jr))) { mesh_free(m); return cli_fail(in, st); }
        printf("  jitter (seed %d): %d vertices moved, %d slid along the boundary, %d kept, %d edges flipped, "
               "max deviation %.3g\n", seed, jr.moved_vertices, jr.slid_vertices, jr.fixed_vertices, jr.flipped_edges,
               jr.max_deviation);
    }
    if ((st = neuv_mesh_save(m, out))) { mesh_free(m); return cli_fail(out, st); }
    printf("%s: %d vertices, %d faces%s (%.3f s)\n", out, m->nv, m->nf, m->nuv > 0 ? ", with UVs" : "",
           now_seconds() - t0);
    mesh_free(m);
    return 0;
}
