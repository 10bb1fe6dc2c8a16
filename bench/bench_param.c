/* The parameterization networks on spot.obj against LSCM on the same charts,
 * plus the paper's two ablations (no L_iso; per-vertex features instead of
 * the pooled ψ).
 *
 *   cmake --build build --target bench_param && ./build/bench/bench_param [mesh] [charts-K] [threads]
 *   ./build/bench/bench_param MESH K THREADS one NAME key=value...   (one configuration, for tuning)
 *       keys: width depth iters lambda_angle lambda_area warmup late_angle late_area
 *             psi=pooled|vertex iso=0|1 seed face_points iso_pairs min_iters paper=1
 *
 * Charts: "auto" (default) = the pipeline's PatchNet charts and DiffusionNet
 * features (cached in bench_param_<mesh>.charts); a number K = k-means of the
 * unit face normals then charts_from_labels, with the feature-free ψ. Each
 * network map is checked per chart with chart_uv_check_run, as the repair
 * stage does, and failing charts are replaced by LSCM. Each configuration runs once (a
 * training run is seconds to minutes; medians would multiply that); LSCM is
 * the reference measured in the same run. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "charts/charts.h"
#include "core/timer.h"
#include "flatten/lscm.h"
#include "flatten/uv_refine.h"
#include "geometry/operator_cache.h"
#include "geometry/operators.h"
#include "metrics/chart_uv_check.h"
#include "models/patchnet.h"
#include "mesh/clean.h"
#include "mesh/shapes.h"
#include "metrics/uv_metrics.h"
#include "models/param_net.h"
#include "nn/nn.h"
#include "segment/patchnet_segment.h"

/* Upper half of a unit UV sphere (z >= 0): a curved disk. */
static neuv_mesh *test_cap(void)
{
    neuv_mesh *s = shape_uv_sphere(32, 16, 1.0);
    if (!s) return NULL;
    int *keep = calloc((size_t)s->nv, sizeof(int)), nv = 0, nf = 0;
    for (int f = 0; f < s->nf; f++) {
        double z = (s->pos[3 * s->tri[3 * f] + 2] + s->pos[3 * s->tri[3 * f + 1] + 2] + s->pos[3 * s->tri[3 * f + 2] + 2]) / 3;
        if (z > 0) { nf++; for (int k = 0; k < 3; k++) keep[s->tri[3 * f + k]] = 1; }
    }
    for (int v = 0; v < s->nv; v++) keep[v] = keep[v] ? nv++ : -1;
    neuv_mesh *c = mesh_create(nv, nf, 0);
    for (int v = 0; v < s->nv; v++)
        if (keep[v] >= 0) for (int q = 0; q < 3; q++) c->pos[3 * keep[v] + q] = s->pos[3 * v + q];
    nf = 0;
    for (int f = 0; f < s->nf; f++) {
        double z = (s->pos[3 * s->tri[3 * f] + 2] + s->pos[3 * s->tri[3 * f + 1] + 2] + s->pos[3 * s->tri[3 * f + 2] + 2]) / 3;
        if (z > 0) { for (int k = 0; k < 3; k++) c->tri[3 * nf + k] = keep[s->tri[3 * f + k]]; nf++; }
    }
    free(keep);
    mesh_free(s);
    return c;
}

static int kmeans_normals(const neuv_mesh *m, int k, int *label)
{
    double *n = malloc((size_t)m->nf * 3 * sizeof(double)), *c = malloc((size_t)k * 3 * sizeof(double));
    double *dmin = malloc((size_t)m->nf * sizeof(double));
    if (!n || !c || !dmin) return -1;
    for (int f = 0; f < m->nf; f++) mesh_face_normal(m, f, n + 3 * f);
    memcpy(c, n, 3 * sizeof(double));
    for (int f = 0; f < m->nf; f++) dmin[f] = INFINITY;
    for (int j = 1; j < k; j++) {
        int far = 0;
        for (int f = 0; f < m->nf; f++) {
            const double *p = n + 3 * f, *q = c + 3 * (j - 1);
            double d = (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]);
            if (d < dmin[f]) dmin[f] = d;
            if (dmin[f] > dmin[far]) far = f;
        }
        memcpy(c + 3 * j, n + 3 * far, 3 * sizeof(double));
    }
    for (int round = 0; round < 10; round++) {
        for (int f = 0; f < m->nf; f++) {
            double best = -INFINITY;
            for (int j = 0; j < k; j++) {
                double d = n[3 * f] * c[3 * j] + n[3 * f + 1] * c[3 * j + 1] + n[3 * f + 2] * c[3 * j + 2];
                if (d > best) { best = d; label[f] = j; }
            }
        }
        memset(c, 0, (size_t)k * 3 * sizeof(double));
        for (int f = 0; f < m->nf; f++)
            for (int q = 0; q < 3; q++) c[3 * label[f] + q] += n[3 * f + q] * mesh_face_area(m, f);
        for (int j = 0; j < k; j++) {
            double l = sqrt(c[3 * j] * c[3 * j] + c[3 * j + 1] * c[3 * j + 1] + c[3 * j + 2] * c[3 * j + 2]);
            if (l > 0) for (int q = 0; q < 3; q++) c[3 * j + q] /= l;
        }
    }
    free(n); free(c); free(dmin);
    return 0;
}

/* Metrics of per-corner UVs (#F by 3 by 2) on a copy of m. */
static int corner_metrics(const neuv_mesh *m, const double *corner_uv, uv_metrics *mt)
{
    neuv_mesh *c = mesh_clone(m);
    int *tri_uv = malloc((size_t)m->nf * 3 * sizeof(int));
    if (!c || !tri_uv) return -1;
    for (int i = 0; i < 3 * m->nf; i++) tri_uv[i] = i;
    int ok = mesh_set_uv(c, 3 * m->nf, corner_uv, tri_uv) == NEUV_OK && uv_metrics_compute(c, mt) == NEUV_OK;
    free(tri_uv);
    mesh_free(c);
    return ok ? 0 : -1;
}


/* The pipeline's charts and features: operators, PatchNet (default options,
 * seed 1), as `neuv unwrap` computes them; cached in `cache` (a binary file:
 * nf, n_charts, dim, face_chart, features) because PatchNet takes seconds. */
static int pipeline_charts(const neuv_mesh *m, const char *cache, int *chart, int *nc, float **feat, int *dim)
{
    FILE *fp = fopen(cache, "rb");
    int hdr[3];
    if (fp && fread(hdr, sizeof hdr, 1, fp) == 1 && hdr[0] == m->nf) {
        *nc = hdr[1]; *dim = hdr[2];
        *feat = hdr[2] > 0 ? malloc((size_t)m->nv * hdr[2] * sizeof(float)) : NULL;
        int ok = fread(chart, sizeof(int), (size_t)m->nf, fp) == (size_t)m->nf &&
                 (!*feat || fread(*feat, sizeof(float), (size_t)m->nv * hdr[2], fp) == (size_t)m->nv * hdr[2]);
        fclose(fp);
        if (ok) return 0;
        free(*feat);
    } else if (fp) fclose(fp);
    operators ops;
    memset(&ops, 0, sizeof ops);
    operators_params op = operators_default_params();
    patchnet_options po;
    patchnet_default_options(&po);
    po.seed = 1;
    if (operators_get(m, &op, 1, &ops, NULL, NULL) != NEUV_OK ||
        patchnet_segment(m, &ops, &po, chart, nc, feat, dim, NULL) != NEUV_OK)
        return -1;
    operators_free(&ops);
    fp = fopen(cache, "wb");
    if (fp) {
        hdr[0] = m->nf; hdr[1] = *nc; hdr[2] = *feat ? *dim : 0;
        fwrite(hdr, sizeof hdr, 1, fp);
        fwrite(chart, sizeof(int), (size_t)m->nf, fp);
        if (*feat) fwrite(*feat, sizeof(float), (size_t)m->nv * *dim, fp);
        fclose(fp);
    }
    return 0;
}

/* What the pipeline's repair stage sees: per chart, the corner UVs copied to
 * the chart's vertices and chart_uv_check_run; failing charts are replaced by
 * LSCM in `corner_uv` (as the repair stage does) so that the metrics after
 * this call are those of the repaired atlas. */
typedef struct chart_tally { int ok, flipped, degenerate, crossings; double area_ok, area; } chart_tally;

static int check_and_repair(const neuv_mesh *m, const int *chart, int nc, double *corner_uv, chart_tally *t)
{
    memset(t, 0, sizeof *t);
    for (int c = 0; c < nc; c++) {
        neuv_mesh *sub; int *vmap, *fmap;
        if (chart_submesh(m, chart, c, &sub, &vmap, &fmap) != NEUV_OK) return -1;
        double *uv = malloc((size_t)sub->nv * 2 * sizeof(double));
        if (!uv) return -1;
        for (int f = 0; f < sub->nf; f++)
            for (int k = 0; k < 3; k++)
                for (int q = 0; q < 2; q++) uv[2 * sub->tri[3 * f + k] + q] = corner_uv[6 * fmap[f] + 2 * k + q];
        chart_uv_check chk;
        int ok = chart_uv_check_run(sub, uv, &chk);
        if (ok < 0) return -1;
        t->ok += ok;
        double ca = 0;
        for (int f = 0; f < sub->nf; f++) ca += mesh_face_area(sub, f);
        t->area += ca;
        if (ok) t->area_ok += ca;
        if (!ok && getenv("BENCH_VERBOSE"))
            fprintf(stderr, "    chart %d (%d faces): %d flipped, %d degenerate, %d crossings\n", c, sub->nf, chk.flipped,
                    chk.degenerate, chk.boundary_crossings);
        t->flipped += chk.flipped; t->degenerate += chk.degenerate; t->crossings += chk.boundary_crossings;
        if (!ok && lscm(sub, uv) != NEUV_OK) return -1;
        if (!ok)
            for (int f = 0; f < sub->nf; f++)
                for (int k = 0; k < 3; k++)
                    for (int q = 0; q < 2; q++) corner_uv[6 * fmap[f] + 2 * k + q] = uv[2 * sub->tri[3 * f + k] + q];
        free(uv); free(vmap); free(fmap); mesh_free(sub);
    }
    return 0;
}

static int lscm_charts(const neuv_mesh *m, const int *chart, int nc, double *corner_uv)
{
    for (int c = 0; c < nc; c++) {
        neuv_mesh *sub; int *vmap, *fmap;
        if (chart_submesh(m, chart, c, &sub, &vmap, &fmap) != NEUV_OK) return -1;
        double *uv = malloc((size_t)sub->nv * 2 * sizeof(double));
        if (!uv || lscm(sub, uv) != NEUV_OK) return -1;
        for (int f = 0; f < sub->nf; f++)
            for (int k = 0; k < 3; k++)
                for (int q = 0; q < 2; q++) corner_uv[6 * fmap[f] + 2 * k + q] = uv[2 * sub->tri[3 * f + k] + q];
        free(uv); free(vmap); free(fmap); mesh_free(sub);
    }
    return 0;
}

static const float *g_feat; /* pipeline features (NULL: feature-free ψ) */
static int g_dim;
static uv_refine_options g_refine; /* iters 0: no vertex refinement */

static void print_row(const char *name, double sec, int iters, int nc, const chart_tally *t, const uv_metrics *raw,
                      const uv_metrics *fin, const param_net_report *rep)
{
    if (rep)
        printf("| %s | %.1f | %d | %d/%d (area %.3f) | %d | %d | %d | %.4f | %.4f | %.4f |\n", name, sec, iters, t->ok, nc,
               t->area > 0 ? t->area_ok / t->area : 0, t->flipped, t->degenerate, t->crossings, raw->qce_mean,
               fin->qce_mean, fin->ase_abs_mean);
    else
        printf("| %s | %.2f | – | – | %d | – | – | %.4f | %.4f | %.4f |\n", name, sec, raw->flipped, raw->qce_mean,
               raw->qce_mean, raw->ase_abs_mean);
    if (rep)
        fprintf(stderr, "  %s: params/MLP %ld, pairs %ld, plateau %d, loss %.5f (cycle %.2e iso %.2e angle %.2e area %.2e barrier %.2e warm %.2e), solve %d steps E %.3e -> %.3e, heads %d (refit %d), cycle_rms %.4f, setup %.2fs, train %.2fs\n",
                name, rep->parameters, rep->pairs, rep->stopped_on_plateau, rep->loss, rep->loss_cycle,
                rep->loss_iso, rep->loss_angle, rep->loss_area, rep->loss_barrier, rep->loss_warm, rep->solve_steps, rep->solve_energy_before, rep->solve_energy_after, rep->heads_improved, rep->heads_refit, rep->cycle_rms, rep->setup_seconds,
                rep->train_seconds);
    fflush(stdout);
}

static int run(const neuv_mesh *m, const int *chart, int nc, const char *name, const param_net_options *o)
{
    double *uv = malloc((size_t)m->nf * 6 * sizeof(double));
    param_net_report rep;
    double t0 = now_seconds();
    if (!uv || param_net_flatten(m, chart, nc, g_feat, g_dim, o, uv, &rep) != NEUV_OK) {
        fprintf(stderr, "%s: %s\n", name, neuv_last_error());
        return 1;
    }
    uv_metrics raw, fin;
    chart_tally tally;
    if (corner_metrics(m, uv, &raw)) return 1;
    uv_refine_report rr;
    if (uv_refine(m, chart, nc, &g_refine, uv, &rr) != NEUV_OK) {
        fprintf(stderr, "%s: %s\n", name, neuv_last_error());
        return 1;
    }
    if (g_refine.iters > 0)
        fprintf(stderr, "  %s: refinement %d steps, %d charts reverted, loss %.5f -> %.5f, %.2fs\n", name, rr.iters,
                rr.charts_reverted, rr.loss_start, rr.loss_end, rr.seconds);
    double t = now_seconds() - t0;
    if (check_and_repair(m, chart, nc, uv, &tally) || corner_metrics(m, uv, &fin)) return 1;
    print_row(name, t, rep.iters, nc, &tally, &raw, &fin, &rep);
    free(uv);
    return 0;
}

static void apply_key(param_net_options *o, const char *kv)
{
    const char *eq = strchr(kv, '=');
    if (!eq) return;
    double v = atof(eq + 1);
    size_t n = (size_t)(eq - kv);
#define KEY(s) (n == strlen(s) && !strncmp(kv, s, n))
    if (KEY("paper")) param_net_default_options(o, PARAM_PRESET_PAPER);
    else if (KEY("width")) o->width = (int)v;
    else if (KEY("depth")) o->depth = (int)v;
    else if (KEY("iters")) o->iters = (int)v;
    else if (KEY("min_iters")) o->min_iters = (int)v;
    else if (KEY("lambda_angle")) o->lambda[2] = v;
    else if (KEY("lambda_area")) o->lambda[3] = v;
    else if (KEY("warmup")) o->warmup_iters = (int)v;
    else if (KEY("late_angle")) o->lambda_late[0] = v;
    else if (KEY("late_area")) o->lambda_late[1] = v;
    else if (KEY("iso")) o->lambda[1] = v;
    else if (KEY("seed")) o->seed = (uint64_t)v;
    else if (KEY("face_points")) o->face_points = (int)v;
    else if (KEY("iso_pairs")) o->iso_pairs = (int)v;
    else if (KEY("radius")) o->radius = v;
    else if (KEY("lr")) o->lr = (float)v;
    else if (KEY("fold")) o->lambda_fold = v;
    else if (KEY("lr_final")) o->lr_final = v;
    else if (KEY("fold_eps")) o->fold_eps = v;
    else if (KEY("warm")) o->warm_iters = (int)v;
    else if (KEY("lambda_warm")) o->lambda_warm = v;
    else if (KEY("solve")) o->solve_steps = (int)v;
    else if (KEY("heads")) o->chart_heads = (int)v;
    else if (KEY("anchor")) o->solve_anchor = v;
    else if (KEY("solve_fold")) o->solve_fold = v;
    else if (KEY("solve_fold_eps")) o->solve_fold_eps = v;
    else if (KEY("solve_mips")) o->solve_mips = (int)v;
    else if (KEY("refit")) o->solve_refit = (int)v;
    else if (KEY("head_fourier")) o->head_fourier = (int)v;
    else if (KEY("subdivide")) o->solve_subdivide = (int)v;
    else if (KEY("refine")) g_refine.iters = (int)v;
    else if (KEY("refine_lr")) g_refine.lr = v;
    else if (KEY("refine_iso")) g_refine.lambda_iso = v;
    else if (KEY("refine_angle")) g_refine.lambda_angle = v;
    else if (KEY("refine_conf")) g_refine.lambda_conformal = v;
    else if (KEY("refine_area")) g_refine.lambda_area = v;
    else if (KEY("refine_fold")) g_refine.lambda_fold = v;
    else if (KEY("psi")) o->psi_mode = !strcmp(eq + 1, "vertex") ? PARAM_PSI_PER_VERTEX : PARAM_PSI_POOLED;
    else fprintf(stderr, "unknown key %s\n", kv);
#undef KEY
}

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : "../shared/meshes/spot.obj";
    const char *charts_arg = argc > 2 ? argv[2] : "auto";
    int k = atoi(charts_arg);
    int threads = argc > 3 ? atoi(argv[3]) : 1;
    nn_set_threads(threads);
    uv_refine_default_options(&g_refine);
    g_refine.iters = 0;
    neuv_mesh *m = NULL;
    if (!strcmp(path, "grid")) m = shape_grid(16, 16, 1.0, 1.0, 0); /* tuning shapes, one chart each (K = 1) */
    else if (!strcmp(path, "cap")) m = test_cap();
    if (!m && (neuv_mesh_load(path, NULL, &m) != NEUV_OK || mesh_clean(m, NULL, NULL) != NEUV_OK)) {
        fprintf(stderr, "%s: %s\n", path, neuv_last_error());
        return 1;
    }
    int *label = malloc((size_t)m->nf * sizeof(int)), *chart = malloc((size_t)m->nf * sizeof(int)), nc;
    float *feat = NULL;
    if (!label || !chart) return 1;
    if (!strcmp(charts_arg, "auto")) {
        /* The pipeline's charts and DiffusionNet features. */
        const char *base = strrchr(path, '/');
        char cache[512];
        snprintf(cache, sizeof cache, "bench_param_%s.charts", base ? base + 1 : path);
        if (pipeline_charts(m, cache, chart, &nc, &feat, &g_dim)) {
            fprintf(stderr, "charts: %s\n", neuv_last_error());
            return 1;
        }
        g_feat = feat;
    } else if ((k > 1 ? kmeans_normals(m, k, label) : (memset(label, 0, (size_t)m->nf * sizeof(int)), 0)) ||
               charts_from_labels(m, label, NULL, chart, &nc, NULL) != NEUV_OK) {
        fprintf(stderr, "charts: %s\n", neuv_last_error());
        return 1;
    }
    printf("%s: %d vertices, %d faces, %d charts (%s), ψ from %s, %d threads\n\n", path, m->nv, m->nf, nc,
           g_feat ? "PatchNet, as neuv unwrap" : "k-means of face normals", g_feat ? "DiffusionNet features" : "chart centroid and normal", threads);
    printf("| configuration | seconds | iterations | injective charts | flipped | degenerate | boundary crossings | qce_mean (network) | qce_mean (after repair) | ase_abs_mean (after repair) |\n|---|---|---|---|---|---|---|---|---|---|\n");
    double *uv = malloc((size_t)m->nf * 6 * sizeof(double));
    double t0 = now_seconds();
    if (!uv || lscm_charts(m, chart, nc, uv)) { fprintf(stderr, "lscm: %s\n", neuv_last_error()); return 1; }
    double tl = now_seconds() - t0;
    uv_metrics mt;
    if (corner_metrics(m, uv, &mt)) return 1;
    print_row("LSCM (reference)", tl, 0, nc, NULL, &mt, &mt, NULL);
    free(uv);

    param_net_options o;
    param_net_default_options(&o, PARAM_PRESET_FAST);
    if (argc > 5 && !strcmp(argv[4], "one")) {
        for (int i = 6; i < argc; i++) apply_key(&o, argv[i]);
        return run(m, chart, nc, argv[5], &o);
    }
    int rc = run(m, chart, nc, "neural fast", &o);
    param_net_options a = o;
    a.lambda[1] = 0;
    rc |= run(m, chart, nc, "fast, no L_iso (ablation)", &a);
    a = o;
    a.psi_mode = PARAM_PSI_PER_VERTEX;
    rc |= run(m, chart, nc, "fast, per-vertex ψ (ablation)", &a);
    if (argc > 4) {
        param_net_options p;
        param_net_default_options(&p, PARAM_PRESET_PAPER);
        p.iters = atoi(argv[4]);
        rc |= run(m, chart, nc, "neural paper", &p);
    }
    free(label); free(chart); free(feat); mesh_free(m);
    return rc;
}
