/* Time per PatchNet training iteration (forward, L_cos + L_geo, backward,
 * Adam) on real meshes, and the achieved GFLOP/s of its dense products
 * against plain cblas_sgemm measured in the same run.
 *
 * FLOPs counted per iteration (dense products only; element-wise work and
 * the sparse gradient products are extra time the rate must absorb):
 *   forward, per block: diffusion 2·(2·V·k·C), rotations 4·(2·V·C²),
 *   MLP 2·V·3C·C + 2·V·C²; plus first 2·V·in·C, last 2·V·C·K, L_geo 2·S·F·K;
 *   backward of every product: twice its forward. Total = 3 × forward.
 * Reference: cblas_sgemm of the MLP's shape (V by 3C times 3C by C) and of a
 * 1024³ square, medians of several calls.
 *
 * Usage: bench_patchnet [MESH ...] [--iters N] [--runs R] [--preset fast|paper] [--threads T]
 * (defaults: spot.obj and stanford-bunny.obj from $NEUV_SHARED or ../shared, 10 iterations, 3 runs) */
#include <cblas.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/timer.h"
#include "geometry/operator_cache.h"
#include "mesh/clean.h"
#include "models/patchnet.h"

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *t, int n)
{
    qsort(t, (size_t)n, sizeof(double), cmp_double);
    return n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]);
}

/* Median seconds of one cblas_sgemm m by k times k by n. */
static double sgemm_seconds(int m, int n, int k, int reps)
{
    float *a = malloc(sizeof(float) * (size_t)m * k), *b = malloc(sizeof(float) * (size_t)k * n),
          *c = malloc(sizeof(float) * (size_t)m * n);
    for (size_t i = 0; i < (size_t)m * k; i++) a[i] = (float)(i % 7) * 0.1f;
    for (size_t i = 0; i < (size_t)k * n; i++) b[i] = (float)(i % 5) * 0.1f;
    double t[16];
    if (reps > 16) reps = 16;
    for (int r = 0; r < reps; r++) {
        double t0 = now_seconds();
        cblas_sgemm(CblasRowMajor, CblasNoTrans, CblasNoTrans, m, n, k, 1.0f, a, k, b, n, 0.0f, c, n);
        t[r] = now_seconds() - t0;
    }
    free(a); free(b); free(c);
    return median(t, reps);
}

int main(int argc, char **argv)
{
    const char *meshes[16];
    int nm = 0, iters = 10, runs = 3, threads = 0;
    const char *preset = "fast";
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--iters") && i + 1 < argc) iters = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--runs") && i + 1 < argc) runs = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--threads") && i + 1 < argc) threads = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--preset") && i + 1 < argc) preset = argv[++i];
        else if (nm < 16) meshes[nm++] = argv[i];
    }
    static char def[2][4096];
    if (!nm) {
        const char *root = getenv("NEUV_SHARED");
        if (!root) root = "../shared";
        snprintf(def[0], sizeof def[0], "%s/meshes/spot.obj", root);
        snprintf(def[1], sizeof def[1], "%s/meshes/stanford-bunny.obj", root);
        meshes[0] = def[0];
        meshes[1] = def[1];
        nm = 2;
    }
    if (runs < 1 || runs > 15 || iters < 1) { fprintf(stderr, "bench_patchnet: bad --runs or --iters\n"); return 2; }
    if (threads > 0) nn_set_threads(threads);
    patchnet_options o;
    patchnet_default_options(&o);
    if (patchnet_apply_preset(&o, preset)) { fprintf(stderr, "bench_patchnet: %s\n", neuv_last_error()); return 2; }
    o.charts = 8;
    o.iters = iters;
    o.plateau_window = iters + 1; /* never stop early: every run does the same work */
    printf("PatchNet training iteration, preset %s (%d blocks x %d, k %d, K %d, S %d), %d threads, median of %d runs x %d iterations\n",
           preset, o.blocks, o.width, o.k_eig, o.charts, o.geo_sources, nn_get_threads(), runs, iters);
    double peak = sgemm_seconds(1024, 1024, 1024, 5);
    printf("cblas_sgemm 1024^3: %.1f GFLOP/s\n", 2.0 * 1024 * 1024 * 1024 / peak * 1e-9);
    for (int mi = 0; mi < nm; mi++) {
        neuv_mesh *m = NULL;
        if (neuv_mesh_load(meshes[mi], NULL, &m) || mesh_clean(m, NULL, NULL)) {
            fprintf(stderr, "%s: %s\n", meshes[mi], neuv_last_error());
            mesh_free(m);
            continue;
        }
        operators ops;
        operators_params p = operators_default_params();
        if (operators_get(m, &p, 1, &ops, NULL, NULL)) {
            fprintf(stderr, "%s: %s\n", meshes[mi], neuv_last_error());
            mesh_free(m);
            continue;
        }
        double t[16];
        int in_dim = o.features == DIFFUSION_NET_HKS ? ops.n_hks : 3;
        for (int r = 0; r < runs; r++) {
            patchnet_model model;
            patchnet_report rep;
            memset(&rep, 0, sizeof rep);
            if (patchnet_model_create(&model, &o, in_dim, o.charts) || patchnet_train(&model, m, &ops, &o, &rep)) {
                fprintf(stderr, "%s: %s\n", meshes[mi], neuv_last_error());
                return 1;
            }
            t[r] = rep.train_seconds / rep.iterations;
            patchnet_model_free(&model);
        }
        double it = median(t, runs);
        double V = m->nv, F = m->nf, C = o.width, k = ops.k < o.k_eig ? ops.k : o.k_eig, K = o.charts;
        double S = o.geo_sources < F ? o.geo_sources : F;
        double fwd = o.blocks * (4 * V * k * C + 8 * V * C * C + 6 * V * C * C + 2 * V * C * C)
                     + 2 * V * in_dim * C + 2 * V * C * K + 2 * S * F * K;
        double flops = 3 * fwd;
        double ref = sgemm_seconds(m->nv, o.width, 3 * o.width, 7);
        double ref_rate = 2.0 * V * 3 * C * C / ref;
        printf("%s: %d vertices, %d faces: %.2f ms/iteration (%.1f it/s), %.3f GFLOP/iteration, %.2f GFLOP/s; "
               "sgemm %dx%dx%d %.2f GFLOP/s -> %.1f%% of it, %.1f%% of the 1024^3 rate\n",
               meshes[mi], m->nv, m->nf, it * 1e3, 1 / it, flops * 1e-9, flops / it * 1e-9, m->nv, 3 * o.width,
               o.width, ref_rate * 1e-9, 100.0 * flops / it / ref_rate,
               100.0 * flops / it / (2.0 * 1024 * 1024 * 1024 / peak));
        operators_free(&ops);
        mesh_free(m);
    }
    return 0;
}
