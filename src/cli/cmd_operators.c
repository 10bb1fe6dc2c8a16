/* neuv operators IN [--k K] [--hks N] [--json] [--no-cache]
 * Computes (or loads from the cache) the geometry operators of a mesh and
 * reports the Laplacian eigenvalues, the time of each part and the cache file. */
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/commands.h"

#define OPERATORS_USAGE "operators IN [--k K] [--hks N] [--json] [--no-cache]"

static void print_table(const char *path, int nv_in, double load_s, const neuv_operators_info *o)
{
    printf("%s: %d vertices, %d faces", path, o->vertices, o->faces);
    if (o->vertices != nv_in) printf(" (%d vertices before cleaning)", nv_in);
    printf("\n");
    printf("eigenvalues (k = %d, L phi = lambda M phi):\n", o->k);
    int head = o->k < 8 ? o->k : 8;
    for (int a = 0; a < head; a++) printf("  lambda[%d] = %.10g\n", a, o->eigenvalues[a]);
    if (o->k > head + 1) printf("  ...\n");
    if (o->k > head) printf("  lambda[%d] = %.10g\n", o->k - 1, o->eigenvalues[o->k - 1]);
    printf("HKS times: %d from %.6g to %.6g\n", o->hks_count, o->hks_times[0], o->hks_times[o->hks_count - 1]);
    printf("seconds:\n");
    printf("  %-10s %.3f\n", "load", load_s);
    printf("  %-10s %.3f\n", "clean", o->seconds_clean);
    if (o->cache_hit) {
        printf("  %-10s %.3f\n", "cache", o->seconds_cache_load);
    } else {
        printf("  %-10s %.3f\n", "laplacian", o->seconds_laplacian);
        printf("  %-10s %.3f\n", "factor", o->seconds_factor);
        printf("  %-10s %.3f\n", "eigen", o->seconds_eigen);
        printf("  %-10s %.3f\n", "gradients", o->seconds_gradients);
        printf("  %-10s %.3f\n", "hks", o->seconds_hks);
    }
    printf("  %-10s %.3f\n", "operators", o->seconds_operators);
    if (o->cache_path) printf("cache: %s (%s)\n", o->cache_path, o->cache_hit ? "hit" : "miss, written");
    else printf("cache: off\n");
}

int cmd_operators(int argc, char **argv)
{
    const char *in = NULL;
    int json = 0, bad = 0;
    neuv_operator_options p;
    neuv_operator_options_init(&p);
    for (int i = 1; i < argc && !bad; i++) {
        if (cli_arg_global(argc, argv, &i, &bad)) continue;
        if (cli_arg_int(argc, argv, &i, "--k", &p.k, &bad)) continue;
        if (cli_arg_int(argc, argv, &i, "--hks", &p.hks, &bad)) continue;
        if (!strcmp(argv[i], "--json")) { json = 1; continue; }
        if (!strcmp(argv[i], "--no-cache")) { p.use_cache = 0; continue; }
        if (argv[i][0] == '-' && argv[i][1]) return cli_error(NULL, "operators: unknown option '%s'", argv[i]);
        if (in) return cli_error(NULL, "operators: one input file expected, got '%s' and '%s'", in, argv[i]);
        in = argv[i];
    }
    if (bad) return 2;
    if (!in) return cli_error(NULL, "usage: neuv " OPERATORS_USAGE);
    if (p.k < 1 || p.k > 4096) return cli_error(NULL, "--k must be between 1 and 4096, got %d", p.k);
    if (p.hks < 1 || p.hks > 1024) return cli_error(NULL, "--hks must be between 1 and 1024, got %d", p.hks);

    double t0 = cli_now_seconds();
    neuv_mesh *m = NULL;
    neuv_status st = neuv_mesh_load(in, cli_callbacks(), &m);
    if (st != NEUV_OK) return cli_fail(in, st);
    double load_s = cli_now_seconds() - t0;
    int nv_in = neuv_mesh_vertex_count(m);
    neuv_operators *ops = NULL;
    st = neuv_operators_compute(m, &p, cli_callbacks(), &ops);
    neuv_mesh_free(m);
    if (st != NEUV_OK) return cli_fail(in, st);
    int rc = 0;
    if (json) {
        rc = cli_print_document(neuv_operators_json(ops, in, load_s));
    } else {
        neuv_operators_info info;
        neuv_operators_get_info(ops, &info);
        print_table(in, nv_in, load_s, &info);
    }
    neuv_operators_free(ops);
    return rc;
}
