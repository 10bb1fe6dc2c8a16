/* neuv operators IN [--k K] [--hks N] [--json] [--no-cache]
 * Computes (or loads from the cache) the geometry operators of a mesh and
 * reports the Laplacian eigenvalues, the time of each part and the cache file. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/commands.h"
#include "core/json_writer.h"
#include "core/timer.h"
#include "geometry/operator_cache.h"
#include "mesh/clean.h"

#define OPERATORS_USAGE "operators IN [--k K] [--hks N] [--json] [--no-cache]"

typedef struct run_info {
    const char *path;
    int nv_in, nf_in;
    double load_s, clean_s;
    const char *cache_path;
    int cache_hit;
} run_info;

static void print_table(const run_info *r, const operators *o)
{
    printf("%s: %d vertices, %d faces", r->path, o->nv, r->nf_in);
    if (o->nv != r->nv_in) printf(" (%d vertices before cleaning)", r->nv_in);
    printf("\n");
    printf("eigenvalues (k = %d, L phi = lambda M phi):\n", o->k);
    int head = o->k < 8 ? o->k : 8;
    for (int a = 0; a < head; a++) printf("  lambda[%d] = %.10g\n", a, o->evals[a]);
    if (o->k > head + 1) printf("  ...\n");
    if (o->k > head) printf("  lambda[%d] = %.10g\n", o->k - 1, o->evals[o->k - 1]);
    printf("HKS times: %d from %.6g to %.6g\n", o->n_hks, o->hks_times[0], o->hks_times[o->n_hks - 1]);
    printf("seconds:\n");
    printf("  %-10s %.3f\n", "load", r->load_s);
    printf("  %-10s %.3f\n", "clean", r->clean_s);
    if (r->cache_hit) {
        printf("  %-10s %.3f\n", "cache", o->seconds.cache_load);
    } else {
        printf("  %-10s %.3f\n", "laplacian", o->seconds.laplacian);
        printf("  %-10s %.3f\n", "factor", o->seconds.factor);
        printf("  %-10s %.3f\n", "eigen", o->seconds.eigen);
        printf("  %-10s %.3f\n", "gradients", o->seconds.gradients);
        printf("  %-10s %.3f\n", "hks", o->seconds.hks);
    }
    printf("  %-10s %.3f\n", "operators", o->seconds.total);
    if (r->cache_path) printf("cache: %s (%s)\n", r->cache_path, r->cache_hit ? "hit" : "miss, written");
    else printf("cache: off\n");
}

static int print_json(const run_info *r, const operators *o)
{
    json_writer w;
    json_init(&w);
    json_begin_object(&w);
    json_key(&w, "version"); json_string(&w, neuv_version());
    json_key(&w, "input"); json_string(&w, r->path);
    json_key(&w, "vertices"); json_int(&w, o->nv);
    json_key(&w, "faces"); json_int(&w, r->nf_in);
    json_key(&w, "k"); json_int(&w, o->k);
    json_key(&w, "eigenvalues");
    json_begin_array(&w);
    for (int a = 0; a < o->k; a++) json_number(&w, o->evals[a]);
    json_end_array(&w);
    json_key(&w, "hks_times");
    json_begin_array(&w);
    for (int j = 0; j < o->n_hks; j++) json_number(&w, o->hks_times[j]);
    json_end_array(&w);
    json_key(&w, "seconds");
    json_begin_object(&w);
    json_key(&w, "load"); json_number(&w, r->load_s);
    json_key(&w, "clean"); json_number(&w, r->clean_s);
    json_key(&w, "laplacian"); json_number(&w, o->seconds.laplacian);
    json_key(&w, "factor"); json_number(&w, o->seconds.factor);
    json_key(&w, "eigen"); json_number(&w, o->seconds.eigen);
    json_key(&w, "gradients"); json_number(&w, o->seconds.gradients);
    json_key(&w, "hks"); json_number(&w, o->seconds.hks);
    json_key(&w, "cache_load"); json_number(&w, o->seconds.cache_load);
    json_key(&w, "operators"); json_number(&w, o->seconds.total);
    json_end_object(&w);
    json_key(&w, "cache");
    json_begin_object(&w);
    json_key(&w, "path");
    if (r->cache_path) json_string(&w, r->cache_path); else json_null(&w);
    json_key(&w, "hit"); json_bool(&w, r->cache_hit);
    json_end_object(&w);
    json_end_object(&w);
    return cli_print_json(&w);
}

int cmd_operators(int argc, char **argv)
{
    const char *in = NULL;
    int json = 0, no_cache = 0, bad = 0;
    operators_params p = operators_default_params();
    for (int i = 1; i < argc && !bad; i++) {
        if (cli_arg_global(argc, argv, &i, &bad)) continue;
        if (cli_arg_int(argc, argv, &i, "--k", &p.k, &bad)) continue;
        if (cli_arg_int(argc, argv, &i, "--hks", &p.n_hks, &bad)) continue;
        if (!strcmp(argv[i], "--json")) { json = 1; continue; }
        if (!strcmp(argv[i], "--no-cache")) { no_cache = 1; continue; }
        if (argv[i][0] == '-' && argv[i][1]) return cli_error(NULL, "operators: unknown option '%s'", argv[i]);
        if (in) return cli_error(NULL, "operators: one input file expected, got '%s' and '%s'", in, argv[i]);
        in = argv[i];
    }
    if (bad) return 2;
    if (!in) return cli_error(NULL, "usage: neuv " OPERATORS_USAGE);
    if (p.k < 1 || p.k > 4096) return cli_error(NULL, "--k must be between 1 and 4096, got %d", p.k);
    if (p.n_hks < 1 || p.n_hks > 1024) return cli_error(NULL, "--hks must be between 1 and 1024, got %d", p.n_hks);

    run_info r;
    memset(&r, 0, sizeof r);
    r.path = in;
    double t0 = now_seconds();
    neuv_mesh *m = NULL;
    neuv_status st = neuv_mesh_load(in, &m);
    if (st != NEUV_OK) return cli_fail(in, st);
    r.load_s = now_seconds() - t0;
    r.nv_in = m->nv;
    if (m->nf == 0) {
        mesh_free(m);
        return cli_error(in, "no faces: operators need a triangle mesh, not a point cloud");
    }
    t0 = now_seconds();
    mesh_clean_report rep;
    st = mesh_clean(m, NULL, &rep);
    if (st != NEUV_OK) { mesh_free(m); return cli_fail(in, st); }
    r.clean_s = now_seconds() - t0;
    r.nf_in = m->nf;

    operators o;
    char *cache_path = NULL;
    st = operators_get(m, &p, !no_cache, &o, &cache_path, &r.cache_hit);
    mesh_free(m);
    if (st != NEUV_OK) return cli_fail(in, st);
    r.cache_path = cache_path;
    int rc = 0;
    if (json) rc = print_json(&r, &o);
    else print_table(&r, &o);
    neuv_free(cache_path);
    operators_free(&o);
    return rc;
}
