/* Training of the parameterization networks on all charts of a shape
 * (Pokhariya et al. 2022, section 3.2). See param_net.h for the choices. */
#include "models/param_net.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "charts/charts.h"
#include "core/error.h"
#include "core/log.h"
#include "core/mem.h"
#include "core/rng.h"
#include "core/timer.h"
#include "flatten/lscm.h"
#include "geometry/heat_geodesics.h"
#include "losses/param_losses.h"
#include "models/param_output_solve.h"
#include "nn/adam.h"

int param_net_dense_vertices(const param_mlp *f, const param_net_options *o)
{
    double n = o->solve_subdivide_dense * (param_head_size(f) / 2);
    return n > 0 && n < INT_MAX ? (int)ceil(n) : 0;
}

void param_net_default_options(param_net_options *o, param_preset preset)
{
    *o = (param_net_options){0};
    o->width = 96;
    o->depth = 4;
    o->leaky_slope = 0.01f;
    /* fast: measured deviations from the paper (bench/RESULTS.md, spot with the
     * pipeline's 19 charts, 800 iterations): Adam 3e-3 (1e-3 underfits in the
     * budget), λ_angle 1 (qce_mean 1.153 against 1.209 with 0.1 at width 64;
     * 3 folds faces even with the barrier), width 96 (1.114; 128: 1.100 at
     * 1.6x the time), and the fold barrier λ_fold 100, ε 0.05 (without it 6 of
     * 19 charts fold; with λ_fold 1, 5). */
    o->lr = 3e-3f;
    o->lambda[0] = 1; o->lambda[1] = 1; o->lambda[2] = 1; o->lambda[3] = 0.001;
    o->lambda_fold = 100;
    o->fold_eps = 0.05;
    o->sigma = 0.2;
    o->radius = 0.6;
    o->iters = 800;
    o->min_iters = 300;
    o->plateau_window = 100;
    o->plateau_tol = 0.005;
    o->face_points = 1024;
    o->iso_pairs = 4096;
    /* 2^23 pairs (128 MiB): every chart of a mesh up to ~2900 vertices keeps
     * all its pairs, as before this budget existed; bench/RESULTS.md
     * ("Memory at any size") has the measurements. */
    o->iso_pair_budget = 1L << 23;
    o->psi_mode = PARAM_PSI_POOLED;
    o->seed = 1;
    /* The networks' own map (bench/RESULTS.md, "The networks' own map"):
     * the first 200 steps also pull MLP_f towards each chart's LSCM map
     * (weight 10), and after Adam the output layer is solved for the
     * conformal energy, shared and per chart; each chart's head with a fold
     * barrier (weight 1e4 below 5% of the chart's mean |det J|), then for the
     * scale-free conformal energy when its map is unfolded. */
    o->warm_iters = 200;
    o->lambda_warm = 10;
    o->solve_steps = 40;
    o->solve_anchor = 1e-3;
    o->solve_fold = 1e4;
    o->solve_fold_eps = 0.05;
    o->solve_mips = 20;
    o->head_fourier = 64;
    o->solve_subdivide = 1;
    /* Half of each face's conformal energy on its four sub-faces: a head
     * solved at the vertices alone can bend between them (a small chart has
     * few vertices for its output layer's weights), which a finer
     * triangulation shows (bench/RESULTS.md, "Heads judged between the
     * vertices": spot's model on its jittered subdivision, mean UV distance
     * to the source atlas 2.08e-4 -> 8.4e-5). */
    o->solve_subdivide_energy = 0.5;
    /* Charts of at least 4 vertices per output-layer feature (1680 at the
     * fast preset's 420) keep the energy at their vertices: measured in
     * bench/RESULTS.md, "Dense charts judged at their vertices". */
    o->solve_subdivide_dense = 4;
    o->chart_heads = 1;
    o->solve_refit = 1;
    if (preset == PARAM_PRESET_PAPER) {
        o->width = 464;
        o->depth = 8;
        o->iters = 2000;
        o->lr = 1e-3f;
        o->lambda[2] = 0.001;
        /* the paper's training only */
        o->warm_iters = 0;
        o->solve_steps = 0;
        o->chart_heads = 0;
        o->solve_refit = 0;
        o->head_fourier = 0;
    }
}

/* Everything training needs, all charts concatenated: chart vertices are
 * numbered 0..nv-1 over the charts in order (a mesh vertex on a seam appears
 * once per chart holding it). Positions are normalized per chart. */
typedef struct train_data {
    int n_charts;
    int nv, nf;
    int *vmesh;        /* nv: mesh vertex */
    int *vchart;       /* nv: chart */
    float *x;          /* nv by 3, normalized */
    int *tri;          /* nf by 3, chart-vertex indices */
    int *fmesh;        /* nf: mesh face */
    int *fchart;       /* nf */
    double *fcum;      /* nf: cumulative normalized area (face sampling) */
    param_corners corners;
    float *cos3d, *area3d;
    float *frame_inv, *conf_w; /* nf by 4, nf: conformal-energy targets (when solve_steps > 0) */
    float *target;     /* nv by 2: the charts' LSCM maps in their frames (warm start; solve_refit) */
    geodesic_pairs pairs;   /* chart-vertex indices, normalized distances */
    float *feat;       /* nv by psi_dim per-vertex ψ (per-vertex mode) */
    float *psi;        /* n_charts by psi_dim (pooled mode) */
    int psi_dim;
    double *center, *scale, *rot;
    /* ψ standardization: computed over this data's rows, or given (a model
     * applied to new charts must see them standardized as in training). */
    const double *given_shift, *given_mul;
    double *shift, *mul;   /* psi_dim each: standardized = (raw - shift) * mul */
    int skip_pairs;        /* inference: normalization only, no L_iso pairs */
    int iso_sources;       /* L_iso source vertices per chart (iso_pair_budget); 0: all */
} train_data;

static void train_data_free(train_data *d)
{
    mem_free(d->vmesh); mem_free(d->vchart); mem_free(d->x); mem_free(d->tri); mem_free(d->fmesh); mem_free(d->fchart);
    mem_free(d->fcum); param_corners_free(&d->corners); mem_free(d->cos3d); mem_free(d->area3d);
    mem_free(d->frame_inv); mem_free(d->conf_w); mem_free(d->target);
    geodesic_pairs_free(&d->pairs); mem_free(d->feat); mem_free(d->psi); mem_free(d->center); mem_free(d->scale); mem_free(d->rot);
    mem_free(d->shift); mem_free(d->mul);
    memset(d, 0, sizeof *d);
}

static neuv_status pairs_append(geodesic_pairs *p, int i, int j, double dist)
{
    if (p->n == p->cap) {
        size_t cap = p->cap ? 2 * p->cap : 1024;
        int *ni = mem_realloc(p->i, cap * sizeof(int));
        if (ni) p->i = ni;
        int *nj = mem_realloc(p->j, cap * sizeof(int));
        if (nj) p->j = nj;
        double *nd = mem_realloc(p->d, cap * sizeof(double));
        if (nd) p->d = nd;
        if (!ni || !nj || !nd) return error_nomem("geodesic pairs");
        p->cap = cap;
    }
    p->i[p->n] = i; p->j[p->n] = j; p->d[p->n] = dist;
    p->n++;
    return NEUV_OK;
}

/* Vertex normals (area-weighted face normals), for the feature-free ψ. */
static neuv_status vertex_normals(const neuv_mesh *m, double **out)
{
    double *n = mem_alloc(sizeof(double) * (size_t)m->nv * 3);
    if (!n) return error_nomem("vertex normals");
    mesh_vertex_normals(m, n);
    *out = n;
    return NEUV_OK;
}

/* The chart's frame (rows of R): z along its area-weighted mean normal, x along
 * the principal axis of its vertices projected on the tangent plane. In this
 * frame every chart is a roughly flat disk facing +z, so the networks start
 * from maps that are alike for all charts (orthographic projection is already
 * a fair map) instead of one arbitrary orientation per chart. */
static void chart_frame(const neuv_mesh *sub, const double cen[3], double R[9])
{
    double n[3] = {0, 0, 0};
    for (int f = 0; f < sub->nf; f++) {
        double fn[3], a = mesh_face_area(sub, f);
        mesh_face_normal(sub, f, fn);
        for (int q = 0; q < 3; q++) n[q] += a * fn[q];
    }
    double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(l > 1e-12)) { n[0] = 0; n[1] = 0; n[2] = 1; l = 1; }
    for (int q = 0; q < 3; q++) n[q] /= l;
    /* Any tangent basis (t1, t2), then rotated to the principal axis. */
    double a[3] = {1, 0, 0};
    if (fabs(n[0]) > 0.9) { a[0] = 0; a[1] = 1; }
    double t1[3], t2[3], dt = a[0] * n[0] + a[1] * n[1] + a[2] * n[2];
    for (int q = 0; q < 3; q++) t1[q] = a[q] - dt * n[q];
    l = sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
    for (int q = 0; q < 3; q++) t1[q] /= l;
    t2[0] = n[1] * t1[2] - n[2] * t1[1];
    t2[1] = n[2] * t1[0] - n[0] * t1[2];
    t2[2] = n[0] * t1[1] - n[1] * t1[0];
    double sxx = 0, sxy = 0, syy = 0;
    for (int v = 0; v < sub->nv; v++) {
        double p[3] = {sub->pos[3 * v] - cen[0], sub->pos[3 * v + 1] - cen[1], sub->pos[3 * v + 2] - cen[2]};
        double u = p[0] * t1[0] + p[1] * t1[1] + p[2] * t1[2], w = p[0] * t2[0] + p[1] * t2[1] + p[2] * t2[2];
        sxx += u * u; sxy += u * w; syy += w * w;
    }
    double th = 0.5 * atan2(2 * sxy, sxx - syy), cs = cos(th), sn = sin(th);
    for (int q = 0; q < 3; q++) {
        R[q] = cs * t1[q] + sn * t2[q];
        R[3 + q] = -sn * t1[q] + cs * t2[q];
        R[6 + q] = n[q];
    }
}

/* The warm-start target of one chart (param_net.h, warm_iters): its LSCM map
 * scaled to the chart's 3D area, then turned (and mirrored if that fits
 * better) and moved onto the orthographic projection of the chart in its
 * frame, in normalized units. The projection is what a fresh MLP_f of the
 * normalized position is closest to, so the target asks for the least change
 * of orientation and place, the same way on every chart. A chart LSCM cannot
 * flatten (a solver failure) gets the projection itself. */
static neuv_status chart_lscm_target(const neuv_mesh *sub, const double cen[3], double scale, const double R[9],
                                     float *target)
{
    int n = sub->nv;
    double *uv = mem_alloc(sizeof(double) * 2 * (size_t)n), *pj = mem_alloc(sizeof(double) * 2 * (size_t)n);
    if (!uv || !pj) { mem_free(uv); mem_free(pj); return error_nomem("warm-start target"); }
    for (int v = 0; v < n; v++) {
        const double *p = sub->pos + 3 * v;
        double d0 = p[0] - cen[0], d1 = p[1] - cen[1], d2 = p[2] - cen[2];
        pj[2 * v] = scale * (R[0] * d0 + R[1] * d1 + R[2] * d2);
        pj[2 * v + 1] = scale * (R[3] * d0 + R[4] * d1 + R[5] * d2);
    }
    neuv_status s = lscm(sub, uv);
    if (s == NEUV_ERR_NOMEM) { mem_free(uv); mem_free(pj); return s; }
    if (s != NEUV_OK) memcpy(uv, pj, sizeof(double) * 2 * (size_t)n);
    double a3 = 0, auv = 0;
    for (int f = 0; f < sub->nf; f++) {
        const int *t = sub->tri + 3 * f;
        const double *a = uv + 2 * t[0], *b = uv + 2 * t[1], *c = uv + 2 * t[2];
        auv += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
        a3 += mesh_face_area(sub, f);
    }
    double k = fabs(auv) > 0 ? scale * sqrt(a3 / fabs(auv)) : 1;
    double mu[2] = {0, 0}, mp[2] = {0, 0};
    for (int v = 0; v < n; v++)
        for (int q = 0; q < 2; q++) { mu[q] += uv[2 * v + q] / n; mp[q] += pj[2 * v + q] / n; }
    /* Best rotation of (mirrored) centred UVs onto the centred projection. */
    double best_res = INFINITY, best_c = 1, best_s = 0, best_m = 1;
    for (int mir = 0; mir < 2; mir++) {
        double sg = mir ? -1 : 1, sxx = 0, sxy = 0, res = 0;
        for (int v = 0; v < n; v++) {
            double u0 = sg * k * (uv[2 * v] - mu[0]), u1 = k * (uv[2 * v + 1] - mu[1]);
            double p0 = pj[2 * v] - mp[0], p1 = pj[2 * v + 1] - mp[1];
            sxx += u0 * p0 + u1 * p1;
            sxy += u0 * p1 - u1 * p0;
        }
        double l = sqrt(sxx * sxx + sxy * sxy), c = l > 0 ? sxx / l : 1, sn = l > 0 ? sxy / l : 0;
        for (int v = 0; v < n; v++) {
            double u0 = sg * k * (uv[2 * v] - mu[0]), u1 = k * (uv[2 * v + 1] - mu[1]);
            double e0 = c * u0 - sn * u1 - (pj[2 * v] - mp[0]), e1 = sn * u0 + c * u1 - (pj[2 * v + 1] - mp[1]);
            res += e0 * e0 + e1 * e1;
        }
        if (res < best_res) { best_res = res; best_c = c; best_s = sn; best_m = sg; }
    }
    for (int v = 0; v < n; v++) {
        double u0 = best_m * k * (uv[2 * v] - mu[0]), u1 = k * (uv[2 * v + 1] - mu[1]);
        target[2 * v] = (float)(best_c * u0 - best_s * u1 + mp[0]);
        target[2 * v + 1] = (float)(best_s * u0 + best_c * u1 + mp[1]);
    }
    mem_free(uv); mem_free(pj);
    return NEUV_OK;
}

static int compare_int(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

/* One chart: normalization, geodesic pairs, and its rows of the concatenated arrays. */
static neuv_status add_chart(const neuv_mesh *m, const int *face_chart, int c, const param_net_options *o,
                             train_data *d, int *nv_used, int *nf_used)
{
    neuv_mesh *sub = NULL;
    int *vmap = NULL, *fmap = NULL;
    heat_geodesics *hg = NULL;
    double *dist = NULL;
    geodesic_pairs pp = {0};
    neuv_status s = chart_submesh(m, face_chart, c, &sub, &vmap, &fmap);
    if (s == NEUV_ERR_NOMEM) return s;
    if (s != NEUV_OK) return error_set(NEUV_ERR_INPUT, "chart %d has no face", c);
    double cen[3] = {0, 0, 0}, atot = 0;
    for (int f = 0; f < sub->nf; f++) {
        double a = mesh_face_area(sub, f);
        for (int k = 0; k < 3; k++)
            for (int q = 0; q < 3; q++) cen[q] += a * sub->pos[3 * sub->tri[3 * f + k] + q] / 3;
        atot += a;
    }
    if (!(atot > 0)) { s = error_set(NEUV_ERR_INPUT, "chart %d has zero area", c); goto done; }
    for (int q = 0; q < 3; q++) cen[q] /= atot;
    int v0 = 0;
    double best = INFINITY, rmax = 0;
    for (int v = 0; v < sub->nv; v++) {
        const double *p = sub->pos + 3 * v;
        double r2 = (p[0] - cen[0]) * (p[0] - cen[0]) + (p[1] - cen[1]) * (p[1] - cen[1]) +
                    (p[2] - cen[2]) * (p[2] - cen[2]);
        if (r2 < best) { best = r2; v0 = v; }
        if (r2 > rmax) rmax = r2;
    }
    rmax = sqrt(rmax);
    dist = mem_alloc((size_t)sub->nv * sizeof(double));
    if (!dist) { s = error_nomem("chart distances"); goto done; }
    s = heat_geodesics_create(sub, 1.0, &hg);
    if (s != NEUV_OK) goto done;
    s = heat_geodesics_from_vertex(hg, v0, dist);
    if (s != NEUV_OK) goto done;
    double rgeo = 0;
    for (int v = 0; v < sub->nv; v++)
        if (isfinite(dist[v]) && dist[v] > rgeo) rgeo = dist[v];
    /* The heat method can fall short on a tiny chart; never below the Euclidean radius. */
    if (rgeo < rmax) rgeo = rmax;
    double scale = o->radius / rgeo;
    d->center[3 * c] = cen[0]; d->center[3 * c + 1] = cen[1]; d->center[3 * c + 2] = cen[2];
    d->scale[c] = scale;
    double *R = d->rot + 9 * c;
    chart_frame(sub, cen, R);
    if (!d->skip_pairs) {
        /* Every vertex a source, or a seeded sample of iso_sources of them
         * (partial Fisher-Yates), sorted so that the pairs come out as from all. */
        int ns = d->iso_sources > 0 && d->iso_sources < sub->nv ? d->iso_sources : sub->nv;
        int *src = mem_alloc(sizeof(int) * (size_t)sub->nv);
        if (!src) { s = error_nomem("L_iso sources"); goto done; }
        for (int v = 0; v < sub->nv; v++) src[v] = v;
        if (ns < sub->nv) {
            rng r;
            rng_seed(&r, o->seed * 0x9E3779B97F4A7C15ull + (uint64_t)c + 1);
            for (int k = 0; k < ns; k++) {
                int j = k + rng_below(&r, sub->nv - k), t = src[k];
                src[k] = src[j];
                src[j] = t;
            }
            qsort(src, (size_t)ns, sizeof(int), compare_int);
        }
        s = heat_geodesics_pairs_from(hg, o->sigma / scale, src, ns, &pp);
        mem_free(src);
    }
    if (s != NEUV_OK) goto done;
    int vb = *nv_used, fb = *nf_used;
    for (size_t k = 0; k < pp.n; k++) {
        s = pairs_append(&d->pairs, vb + pp.i[k], vb + pp.j[k], pp.d[k] * scale);
        if (s != NEUV_OK) goto done;
    }
    for (int v = 0; v < sub->nv; v++) {
        d->vmesh[vb + v] = vmap[v];
        d->vchart[vb + v] = c;
        const double *p = sub->pos + 3 * v;
        for (int q = 0; q < 3; q++)
            d->x[3 * (vb + v) + q] = (float)(scale * (R[3 * q] * (p[0] - cen[0]) + R[3 * q + 1] * (p[1] - cen[1]) +
                                                      R[3 * q + 2] * (p[2] - cen[2])));
    }
    for (int f = 0; f < sub->nf; f++) {
        for (int k = 0; k < 3; k++) d->tri[3 * (fb + f) + k] = vb + sub->tri[3 * f + k];
        d->fmesh[fb + f] = fmap[f];
        d->fchart[fb + f] = c;
    }
    if (d->target) {
        s = chart_lscm_target(sub, cen, scale, R, d->target + 2 * (size_t)vb);
        if (s != NEUV_OK) goto done;
    }
    *nv_used += sub->nv;
    *nf_used += sub->nf;
done:
    geodesic_pairs_free(&pp);
    heat_geodesics_free(hg);
    mem_free(dist); mem_free(vmap); mem_free(fmap);
    mesh_free(sub);
    return s;
}

/* Standardizes ψ rows in place (d->shift, d->mul keep how; given ones are
 * applied as they are): every column to zero mean and unit variance
 * over the rows, then every row scaled by 1/sqrt(dim) so that a ψ row has an
 * RMS norm of about 1 whatever its dimension. Why: DiffusionNet features are
 * O(5) in magnitude (spot: mean |f| 4.7, 64 pooled numbers); fed raw, the ψ
 * half of the first layer outweighs the normalized position (|x| <= 0.6) by
 * ~30x at initialization, the output tanh saturates and the map collapses to
 * one point per chart (measured: every chart of spot degenerate, L_cycle
 * stuck at 1.1). A column that does not vary (one chart) becomes 0. */
static neuv_status psi_standardize(float *rows, long n, int dim, train_data *d)
{
    d->shift = mem_alloc(sizeof(double) * (size_t)dim);
    d->mul = mem_alloc(sizeof(double) * (size_t)dim);
    if (!d->shift || !d->mul) return error_nomem("psi standardization");
    double inv = 1.0 / sqrt((double)dim);
    for (int k = 0; k < dim; k++) {
        double mean, mul;
        if (d->given_shift) {
            mean = d->given_shift[k];
            mul = d->given_mul[k];
        } else {
            double var = 0;
            mean = 0;
            for (long i = 0; i < n; i++) mean += rows[i * dim + k];
            mean /= (double)n;
            for (long i = 0; i < n; i++) var += (rows[i * dim + k] - mean) * (rows[i * dim + k] - mean);
            double sd = sqrt(var / (double)n);
            mul = sd > 1e-8 ? inv / sd : 0;
        }
        d->shift[k] = mean;
        d->mul[k] = mul;
        for (long i = 0; i < n; i++) rows[i * dim + k] = (float)((rows[i * dim + k] - mean) * mul);
    }
    return NEUV_OK;
}

/* ψ rows: pooled per chart, or per chart vertex (see param_net.h). */
static neuv_status build_psi(const neuv_mesh *m, const float *feat, int dim, param_psi_mode mode, train_data *d)
{
    double lo[3], hi[3];
    mesh_bounding_box(m, lo, hi);
    double mid[3], half = 0;
    for (int q = 0; q < 3; q++) { mid[q] = 0.5 * (lo[q] + hi[q]); half += (hi[q] - lo[q]) * (hi[q] - lo[q]); }
    half = 0.5 * sqrt(half);
    if (!(half > 0)) half = 1;
    double *vn = NULL;
    if (!feat) {
        neuv_status s = vertex_normals(m, &vn);
        if (s != NEUV_OK) return s;
    }
    /* The per-vertex rows first (also the source of the pooled code). */
    int pd = feat ? dim : 6;
    float *rows = mem_alloc((size_t)d->nv * (size_t)pd * sizeof(float));
    if (!rows) { mem_free(vn); return error_nomem("psi rows"); }
    for (int v = 0; v < d->nv; v++) {
        int mv = d->vmesh[v];
        float *r = rows + (size_t)v * pd;
        if (feat) memcpy(r, feat + (size_t)mv * dim, (size_t)dim * sizeof(float));
        else
            for (int q = 0; q < 3; q++) {
                r[q] = (float)((m->pos[3 * mv + q] - mid[q]) / half);
                r[3 + q] = (float)vn[3 * mv + q];
            }
    }
    mem_free(vn);
    if (mode == PARAM_PSI_PER_VERTEX) {
        d->feat = rows;
        d->psi_dim = pd;
        return psi_standardize(rows, d->nv, pd, d);
    }
    /* Pooled: features → [mean, max]; no features → [centroid, mean normal]
     * (the centroid and normal are themselves means, a max adds nothing). */
    int od = feat ? 2 * dim : 6;
    d->psi = mem_calloc((size_t)d->n_charts * (size_t)od, sizeof(float));
    int *cnt = mem_calloc((size_t)d->n_charts, sizeof(int));
    if (!d->psi || !cnt) { mem_free(rows); mem_free(cnt); return error_nomem("psi"); }
    double *acc = mem_calloc((size_t)d->n_charts * (size_t)pd, sizeof(double));
    if (!acc) { mem_free(rows); mem_free(cnt); return error_nomem("psi"); }
    for (int v = 0; v < d->nv; v++) {
        int c = d->vchart[v];
        const float *r = rows + (size_t)v * pd;
        float *p = d->psi + (size_t)c * od;
        for (int k = 0; k < pd; k++) {
            acc[(size_t)c * pd + k] += r[k];
            if (feat && (cnt[c] == 0 || r[k] > p[dim + k])) p[dim + k] = r[k];
        }
        cnt[c]++;
    }
    for (int c = 0; c < d->n_charts; c++)
        for (int k = 0; k < pd; k++)
            d->psi[(size_t)c * od + k] = (float)(acc[(size_t)c * pd + k] / (cnt[c] ? cnt[c] : 1));
    mem_free(acc); mem_free(cnt); mem_free(rows);
    d->psi_dim = od;
    return psi_standardize(d->psi, d->n_charts, od, d);
}

/* norm: a model whose ψ standardization the rows take (NULL: computed over
 * them); skip_pairs: no L_iso pairs (inference). */
static neuv_status train_data_build(const neuv_mesh *m, const int *face_chart, int n_charts, const float *feat,
                                    int dim, const param_net_options *o, const param_net_model *norm,
                                    int skip_pairs, train_data *d)
{
    memset(d, 0, sizeof *d);
    d->n_charts = n_charts;
    d->skip_pairs = skip_pairs;
    if (norm) { d->given_shift = norm->psi_shift; d->given_mul = norm->psi_mul; }
    /* Chart vertex count: one per (chart, vertex) pair. */
    int *seen = mem_alloc((size_t)m->nv * sizeof(int));
    if (!seen) return error_nomem("chart vertices");
    for (int v = 0; v < m->nv; v++) seen[v] = -1;
    int *order = mem_alloc((size_t)m->nf * sizeof(int)), *start = mem_calloc((size_t)n_charts + 1, sizeof(int));
    if (!order || !start) { mem_free(seen); mem_free(order); mem_free(start); return error_nomem("chart faces"); }
    for (int f = 0; f < m->nf; f++) start[face_chart[f] + 1]++;
    for (int c = 0; c < n_charts; c++) start[c + 1] += start[c];
    int *pos = mem_alloc((size_t)(n_charts + 1) * sizeof(int));
    if (!pos) { mem_free(seen); mem_free(order); mem_free(start); return error_nomem("chart faces"); }
    memcpy(pos, start, (size_t)(n_charts + 1) * sizeof(int));
    for (int f = 0; f < m->nf; f++) order[pos[face_chart[f]]++] = f;
    mem_free(pos);
    long nv = 0;
    for (int c = 0; c < n_charts; c++)
        for (int k = start[c]; k < start[c + 1]; k++)
            for (int q = 0; q < 3; q++) {
                int v = m->tri[3 * order[k] + q];
                if (seen[v] != c) { seen[v] = c; nv++; }
            }
    mem_free(seen); mem_free(order); mem_free(start);
    d->nv = (int)nv;
    if (o->iso_pair_budget > 0) {
        long per = o->iso_pair_budget / (nv > 0 ? nv : 1);
        d->iso_sources = per < 64 ? 64 : per > INT_MAX ? INT_MAX : (int)per;
    }
    d->nf = m->nf;
    d->vmesh = mem_alloc((size_t)nv * sizeof(int));
    d->vchart = mem_alloc((size_t)nv * sizeof(int));
    d->x = mem_alloc((size_t)nv * 3 * sizeof(float));
    d->tri = mem_alloc((size_t)m->nf * 3 * sizeof(int));
    d->fmesh = mem_alloc((size_t)m->nf * sizeof(int));
    d->fchart = mem_alloc((size_t)m->nf * sizeof(int));
    d->fcum = mem_alloc((size_t)m->nf * sizeof(double));
    d->cos3d = mem_alloc((size_t)m->nf * 3 * sizeof(float));
    d->area3d = mem_alloc((size_t)m->nf * sizeof(float));
    d->center = mem_alloc((size_t)n_charts * 3 * sizeof(double));
    d->scale = mem_alloc((size_t)n_charts * sizeof(double));
    d->rot = mem_alloc((size_t)n_charts * 9 * sizeof(double));
    if (!d->rot || !d->vmesh || !d->vchart || !d->x || !d->tri || !d->fmesh || !d->fchart || !d->fcum || !d->cos3d ||
        !d->area3d || !d->center || !d->scale)
        return error_nomem("training data");
    /* The charts' LSCM maps: the warm start's targets in training, and the
     * second start of a head that folds (solve_refit), in training,
     * fine-tuning and inference alike. */
    int warm = !skip_pairs && o->warm_iters > 0 && o->lambda_warm > 0 && !o->init;
    int refit = o->solve_refit && o->solve_steps > 0 && o->solve_fold > 0 && (o->chart_heads || o->infer_heads);
    if (warm || refit) {
        d->target = mem_alloc((size_t)nv * 2 * sizeof(float));
        if (!d->target) return error_nomem("warm-start targets");
    }
    if ((!skip_pairs || o->infer_heads) && o->solve_steps > 0) {
        d->frame_inv = mem_alloc((size_t)m->nf * 4 * sizeof(float));
        d->conf_w = mem_alloc((size_t)m->nf * sizeof(float));
        if (!d->frame_inv || !d->conf_w) return error_nomem("conformal targets");
    }
    int nv_used = 0, nf_used = 0;
    for (int c = 0; c < n_charts; c++) {
        neuv_status s = add_chart(m, face_chart, c, o, d, &nv_used, &nf_used);
        if (s != NEUV_OK) return s;
        log_progress("param", 0.0, "setup chart %d/%d", c + 1, n_charts);
    }
    neuv_status s = param_corners_build(d->tri, d->nf, &d->corners);
    if (s != NEUV_OK) return s;
    /* Targets in normalized units: from the normalized float positions, in double. */
    double *xn = mem_alloc((size_t)nv * 3 * sizeof(double));
    if (!xn) return error_nomem("training data");
    for (long i = 0; i < nv * 3; i++) xn[i] = d->x[i];
    param_corner_targets(xn, &d->corners, d->cos3d, d->area3d);
    if (d->frame_inv) param_conformal_targets(xn, &d->corners, d->frame_inv, d->conf_w);
    mem_free(xn);
    double acc = 0;
    for (int f = 0; f < d->nf; f++) { acc += d->area3d[f]; d->fcum[f] = acc; }
    return build_psi(m, feat, dim, o->psi_mode, d);
}

/* Signed UV area of each face from a #V by 2 float array. */
static double face_area_uv(const float *uv, const int *t)
{
    const float *a = uv + 2 * t[0], *b = uv + 2 * t[1], *c = uv + 2 * t[2];
    return 0.5 * ((double)(b[0] - a[0]) * (c[1] - a[1]) - (double)(b[1] - a[1]) * (c[0] - a[0]));
}

/* Orientation of each chart (+1 / -1) from the sign of its total signed UV area. */
static void chart_orientation(const train_data *d, const float *uv, double *chart_sum, float *orient)
{
    for (int c = 0; c < d->n_charts; c++) chart_sum[c] = 0;
    for (int f = 0; f < d->nf; f++) chart_sum[d->fchart[f]] += face_area_uv(uv, d->tri + 3 * f);
    for (int f = 0; f < d->nf; f++) orient[f] = chart_sum[d->fchart[f]] < 0 ? -1.0f : 1.0f;
}

static int sample_face(const train_data *d, rng *r)
{
    double t = rng_uniform(r) * d->fcum[d->nf - 1];
    int lo = 0, hi = d->nf - 1;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (d->fcum[mid] > t) hi = mid; else lo = mid + 1;
    }
    return lo;
}

typedef struct step_buffers {
    int np, nq;          /* points per step (vertices + face points), pairs per step */
    float *x;            /* np by 3 */
    int *row;            /* np: chart (pooled) */
    float *feat;         /* np by psi_dim (per-vertex) */
    int *pi, *pj;        /* nq */
    float *g;            /* nq */
    float *orient;       /* nf */
    double *chart_sum;   /* n_charts */
    int *vertex_rows;    /* nv: 0..nv-1 (the chart vertices among the step's points) */
} step_buffers;

static void step_buffers_free(step_buffers *b)
{
    mem_free(b->x); mem_free(b->row); mem_free(b->feat); mem_free(b->pi); mem_free(b->pj); mem_free(b->g); mem_free(b->orient);
    mem_free(b->chart_sum); mem_free(b->vertex_rows);
}

/* Face points per step: the option's count, but no more than the charts have
 * vertices (at least an eighth of the count), so that a small mesh does not
 * spend most of each step on points that sample its few flat triangles many
 * times over (bench/RESULTS.md, "Face points on small meshes": the single
 * triangle 2.8 -> 0.8 s at one thread, qce unchanged). A mesh with as many
 * chart vertices as the count is unchanged. */
static int step_face_points(const train_data *d, const param_net_options *o)
{
    int n = o->face_points > 0 ? o->face_points : 0;
    int floor_n = n / 8;
    if (d->nv < n) n = d->nv > floor_n ? d->nv : floor_n;
    return n;
}

/* Fills one step's inputs: every chart vertex, then face points drawn anew. */
static void draw_step(const train_data *d, const param_net_options *o, rng *r, step_buffers *b)
{
    int nv = d->nv, pd = d->psi_dim;
    for (int i = nv; i < b->np; i++) {
        int f = sample_face(d, r);
        double r1 = sqrt(rng_uniform(r)), r2 = rng_uniform(r);
        double w[3] = {1 - r1, r1 * (1 - r2), r1 * r2};
        const int *t = d->tri + 3 * f;
        for (int q = 0; q < 3; q++)
            b->x[3 * i + q] = (float)(w[0] * d->x[3 * t[0] + q] + w[1] * d->x[3 * t[1] + q] + w[2] * d->x[3 * t[2] + q]);
        b->row[i] = d->fchart[f];
        if (o->psi_mode == PARAM_PSI_PER_VERTEX)
            for (int k = 0; k < pd; k++)
                b->feat[(size_t)i * pd + k] = (float)(w[0] * d->feat[(size_t)t[0] * pd + k] +
                                                      w[1] * d->feat[(size_t)t[1] * pd + k] +
                                                      w[2] * d->feat[(size_t)t[2] * pd + k]);
    }
    if ((size_t)b->nq == d->pairs.n) return; /* all pairs, filled once */
    for (int k = 0; k < b->nq; k++) {
        size_t p = (size_t)(rng_uniform(r) * (double)d->pairs.n);
        if (p >= d->pairs.n) p = d->pairs.n - 1;
        b->pi[k] = d->pairs.i[p]; b->pj[k] = d->pairs.j[p]; b->g[k] = (float)d->pairs.d[p];
    }
}

static neuv_status step_buffers_init(const train_data *d, const param_net_options *o, step_buffers *b)
{
    memset(b, 0, sizeof *b);
    b->np = d->nv + step_face_points(d, o);
    b->nq = d->pairs.n < (size_t)o->iso_pairs || o->iso_pairs <= 0 ? (int)d->pairs.n : o->iso_pairs;
    int nq = b->nq > 0 ? b->nq : 1;
    b->x = mem_alloc((size_t)b->np * 3 * sizeof(float));
    b->row = mem_alloc((size_t)b->np * sizeof(int));
    b->pi = mem_alloc((size_t)nq * sizeof(int));
    b->pj = mem_alloc((size_t)nq * sizeof(int));
    b->g = mem_alloc((size_t)nq * sizeof(float));
    b->orient = mem_alloc((size_t)d->nf * sizeof(float));
    b->chart_sum = mem_alloc((size_t)d->n_charts * sizeof(double));
    b->vertex_rows = mem_alloc((size_t)(d->nv > 0 ? d->nv : 1) * sizeof(int));
    if (!b->vertex_rows) return error_nomem("training step buffers");
    for (int i = 0; i < d->nv; i++) b->vertex_rows[i] = i;
    if (o->psi_mode == PARAM_PSI_PER_VERTEX) b->feat = mem_alloc((size_t)b->np * d->psi_dim * sizeof(float));
    if (!b->x || !b->row || !b->pi || !b->pj || !b->g || !b->orient || !b->chart_sum ||
        (o->psi_mode == PARAM_PSI_PER_VERTEX && !b->feat))
        return error_nomem("training step buffers");
    memcpy(b->x, d->x, (size_t)d->nv * 3 * sizeof(float));
    memcpy(b->row, d->vchart, (size_t)d->nv * sizeof(int));
    if (b->feat) memcpy(b->feat, d->feat, (size_t)d->nv * d->psi_dim * sizeof(float));
    if ((size_t)b->nq == d->pairs.n)
        for (int k = 0; k < b->nq; k++) {
            b->pi[k] = d->pairs.i[k]; b->pj[k] = d->pairs.j[k]; b->g[k] = (float)d->pairs.d[k];
        }
    return NEUV_OK;
}

static neuv_status check_input(const neuv_mesh *m, const int *face_chart, int n_charts, const float *feat,
                               int dim, const param_net_options *o, const double *corner_uv)
{
    if (!m || !face_chart || !corner_uv || m->nf < 1)
        return error_set(NEUV_ERR_INPUT, "parameterization needs a mesh with faces, charts and an output array");
    if (n_charts < 1) return error_set(NEUV_ERR_INPUT, "parameterization needs at least one chart (got %d)", n_charts);
    if (feat && dim < 1) return error_set(NEUV_ERR_INPUT, "vertex features given with dimension %d", dim);
    for (int f = 0; f < m->nf; f++)
        if (face_chart[f] < 0 || face_chart[f] >= n_charts)
            return error_set(NEUV_ERR_INPUT, "face %d has chart %d outside 0..%d", f, face_chart[f], n_charts - 1);
    if (o->width < 1 || o->depth < 1 || o->iters < 1 || !(o->lr > 0) || !(o->sigma > 0) || !(o->radius > 0) ||
        !(o->radius < 1))
        return error_set(NEUV_ERR_INPUT, "bad parameterization options (width %d, depth %d, iters %d, radius %g)",
                         o->width, o->depth, o->iters, o->radius);
    return NEUV_OK;
}

/* Cosine decay from the base rate to base x lr_final over the iteration cap:
 * the iso pairs and face points are resampled every step, and a constant rate
 * keeps that noise in the weights to the end. */
typedef struct lr_cosine { double final_ratio; int iters; } lr_cosine;

static float lr_cosine_at(void *user, long step, float base_lr)
{
    const lr_cosine *c = user;
    double t = c->iters > 1 ? (double)(step - 1) / (c->iters - 1) : 1;
    if (t > 1) t = 1;
    return (float)(base_lr * (c->final_ratio + (1 - c->final_ratio) * 0.5 * (1 + cos(3.14159265358979323846 * t))));
}

/* The networks' map at every chart vertex, each chart turned
 * counter-clockwise (mirror[c] = 1 when u was negated), as per-corner UVs in
 * mesh units; also the faces that are still clockwise and the RMS cycle error. */
static neuv_status map_vertices(nn_ctx *ctx, const param_net_model *model, const train_data *d, int use_heads,
                                int *mirror, double *gain, double *corner_uv, int *flipped, double *cycle_rms)
{
    int pooled = model->psi_mode == PARAM_PSI_POOLED;
    double *chart_sum = mem_alloc((size_t)d->n_charts * sizeof(double));
    float *orient = mem_alloc((size_t)(d->nf > 0 ? d->nf : 1) * sizeof(float));
    if (!chart_sum || !orient) { mem_free(chart_sum); mem_free(orient); return error_nomem("chart orientation"); }
    nn_ctx_reset(ctx);
    nn_tensor *x = nn_from(ctx, d->nv, 3, d->x);
    nn_tensor *psi = pooled ? nn_view(ctx, d->n_charts, d->psi_dim, d->psi) : nn_from(ctx, d->nv, d->psi_dim, d->feat);
    nn_tensor *uv;
    if (use_heads && model->heads) {
        /* Each chart through its own output layer (param_output_solve.h). */
        nn_tensor *h = param_mlp_head_features(ctx, &model->f, x, psi, pooled ? d->vchart : NULL);
        uv = h ? nn_new(ctx, d->nv, 2) : NULL;
        if (uv) param_heads_apply(&model->f, h->data, d->nv, d->vchart, model->heads, uv->data);
    } else {
        uv = param_mlp_forward(ctx, &model->f, x, psi, pooled ? d->vchart : NULL);
    }
    nn_tensor *xr = uv ? param_mlp_forward(ctx, &model->g, uv, psi, pooled ? d->vchart : NULL) : NULL;
    if (!uv || !xr) { mem_free(chart_sum); mem_free(orient); return nn_ctx_status(ctx); }
    double cyc = 0;
    for (long i = 0; i < (long)d->nv * 3; i++) cyc += (double)(xr->data[i] - x->data[i]) * (xr->data[i] - x->data[i]);
    *cycle_rms = sqrt(cyc / d->nv);
    chart_orientation(d, uv->data, chart_sum, orient);
    for (int c = 0; c < d->n_charts; c++) mirror[c] = chart_sum[c] < 0;
    /* Each chart scaled to its own 3D area (a similarity: no angle or
     * injectivity changes). The networks' map need not keep a chart's size
     * (measured: beetle's charts came out at 0.07 of their area), and the
     * packing, the refinement and the texel density all expect charts at
     * their true size. */
    double *a3 = mem_calloc((size_t)d->n_charts, sizeof(double));
    if (!a3) { mem_free(chart_sum); mem_free(orient); return error_nomem("chart scale"); }
    for (int f = 0; f < d->nf; f++) a3[d->fchart[f]] += d->area3d[f];
    for (int c = 0; c < d->n_charts; c++)
        gain[c] = fabs(chart_sum[c]) > 0 && a3[c] > 0 ? sqrt(a3[c] / fabs(chart_sum[c])) : 1;
    mem_free(a3);
    *flipped = 0;
    for (int f = 0; f < d->nf; f++) {
        double a = face_area_uv(uv->data, d->tri + 3 * f) * orient[f];
        if (a <= 0) (*flipped)++;
        int c = d->fchart[f], mf = d->fmesh[f];
        double sc = d->scale[c] / gain[c], sign = mirror[c] ? -1 : 1;
        for (int k = 0; k < 3; k++) {
            const float *p = uv->data + 2 * d->tri[3 * f + k];
            corner_uv[6 * mf + 2 * k] = sign * p[0] / sc;
            corner_uv[6 * mf + 2 * k + 1] = p[1] / sc;
        }
    }
    mem_free(chart_sum);
    mem_free(orient);
    return NEUV_OK;
}

/* Starts training from a trained model's weights (fine-tuning): the
 * configurations must match. */
static neuv_status copy_weights(const param_net_model *from, param_net_model *to, int psi_dim)
{
    if (from->psi_dim != psi_dim || from->params.n != to->params.n || from->psi_mode != to->psi_mode ||
        from->f.width != to->f.width || from->f.depth != to->f.depth)
        return error_set(NEUV_ERR_INPUT, "fine-tuning: the model's networks (width %d, depth %d, psi %d) differ from "
                                         "these options (width %d, depth %d, psi %d)",
                         from->f.width, from->f.depth, from->psi_dim, to->f.width, to->f.depth, psi_dim);
    for (int k = 0; k < to->params.n; k++) {
        const nn_tensor *a = from->params.t[k];
        nn_tensor *b = to->params.t[k];
        if (a->rows != b->rows || a->cols != b->cols || strcmp(a->name, b->name) != 0)
            return error_set(NEUV_ERR_INPUT, "fine-tuning: weight '%s' differs from the model's '%s'", b->name, a->name);
        memcpy(b->data, a->data, sizeof(float) * (size_t)a->rows * a->cols);
    }
    return NEUV_OK;
}

neuv_status param_net_flatten(const neuv_mesh *m, const int *face_chart, int n_charts,
                              const float *vertex_features, int feature_dim,
                              const param_net_options *opts, double *corner_uv, param_net_report *rep)
{
    param_net_options defaults;
    if (!opts) { param_net_default_options(&defaults, PARAM_PRESET_FAST); opts = &defaults; }
    const param_net_options *o = opts;
    param_net_report local;
    if (!rep) rep = &local;
    memset(rep, 0, sizeof *rep);
    neuv_status s = check_input(m, face_chart, n_charts, vertex_features, feature_dim, o, corner_uv);
    if (s != NEUV_OK) return s;
    nn_set_threads(o->threads);
    double t0 = now_seconds();

    train_data d;
    step_buffers b = {0};
    nn_adam adam = {0};
    nn_ctx *ctx = NULL;
    param_net_model *model = mem_calloc(1, sizeof *model);
    if (!model) return error_nomem("parameterization model");
    nn_params_init(&model->params);
    s = train_data_build(m, face_chart, n_charts, vertex_features, feature_dim, o, o->init, 0, &d);
    if (s != NEUV_OK) goto done;
    rep->pairs = (long)d.pairs.n;
    s = step_buffers_init(&d, o, &b);
    if (s != NEUV_OK) goto done;
    rep->face_points = b.np - d.nv;

    rng r;
    rng_seed(&r, o->seed * 0x9E3779B97F4A7C15ull + 17);
    s = param_mlp_create(&model->f, 3, d.psi_dim, o->width, 2, o->depth, o->leaky_slope, &r, &model->params, "f");
    if (s == NEUV_OK)
        s = param_mlp_create(&model->g, 2, d.psi_dim, o->width, 3, o->depth, o->leaky_slope, &r, &model->params, "g");
    model->psi_mode = o->psi_mode;
    model->f.fourier = o->init ? o->init->f.fourier : o->head_fourier;
    if (s == NEUV_OK && o->init) s = copy_weights(o->init, model, d.psi_dim);
    if (s != NEUV_OK) goto done;
    model->psi_dim = d.psi_dim;
    model->n_charts = n_charts;
    rep->parameters = 0;
    for (int k = 0; k < model->params.n; k++)
        if (model->params.t[k]->name[0] == 'f')
            rep->parameters += (long)model->params.t[k]->rows * model->params.t[k]->cols;
    nn_adam_config ac = nn_adam_defaults();
    ac.lr = o->lr;
    lr_cosine sched = {o->lr_final, o->iters};
    if (o->lr_final > 0) { ac.schedule = lr_cosine_at; ac.schedule_user = &sched; }
    s = nn_adam_init(&adam, &model->params, &ac);
    if (s != NEUV_OK) goto done;
    ctx = nn_ctx_create(0);
    if (!ctx) { s = error_nomem("training context"); goto done; }
    double t1 = now_seconds();
    rep->setup_seconds = t1 - t0;

    int pooled = o->psi_mode == PARAM_PSI_POOLED;
    rng noise;
    rng_seed(&noise, o->seed ^ 0x5eedf00dull);
    double window_sum = 0, prev_window = INFINITY;
    int it;
    for (it = 0; it < o->iters; it++) {
        draw_step(&d, o, &r, &b);
        nn_ctx_reset(ctx);
        nn_tensor *x = nn_from(ctx, b.np, 3, b.x);
        nn_tensor *psi = pooled ? nn_view(ctx, n_charts, d.psi_dim, d.psi) : nn_from(ctx, b.np, d.psi_dim, b.feat);
        if (pooled && o->psi_noise > 0) {
            psi = nn_from(ctx, n_charts, d.psi_dim, d.psi);
            /* Standardized columns have standard deviation 1/sqrt(dim). */
            double sd = o->psi_noise / sqrt((double)d.psi_dim);
            if (psi)
                for (long k = 0; k < (long)n_charts * d.psi_dim; k++) psi->data[k] += (float)(sd * rng_normal(&noise));
        }
        const int *row = pooled ? b.row : NULL;
        nn_tensor *uv = param_mlp_forward(ctx, &model->f, x, psi, row);
        nn_tensor *xr = param_mlp_forward(ctx, &model->g, uv, psi, row);
        if (!uv || !xr) { s = nn_ctx_status(ctx); goto done; }
        /* The orientation each chart has now: L_area compares signed areas against it. */
        chart_orientation(&d, uv->data, b.chart_sum, b.orient);
        double la = o->lambda[2], lr_ = o->lambda[3];
        if (o->warmup_iters > 0 && it >= o->warmup_iters) {
            if (o->lambda_late[0] > 0) la = o->lambda_late[0];
            if (o->lambda_late[1] > 0) lr_ = o->lambda_late[1];
        }
        nn_tensor *lc = param_loss_cycle(ctx, x, xr);
        nn_tensor *li = b.nq > 0 ? param_loss_iso(ctx, uv, b.pi, b.pj, nn_from(ctx, b.nq, 1, b.g), b.nq)
                                 : nn_fill(ctx, 1, 1, 0);
        nn_tensor *lang = param_loss_angle(ctx, uv, &d.corners, nn_view(ctx, 3 * d.nf, 1, d.cos3d));
        nn_tensor *lar = param_loss_area(ctx, uv, &d.corners, nn_view(ctx, d.nf, 1, d.area3d),
                                         nn_view(ctx, d.nf, 1, b.orient));
        nn_tensor *loss = nn_add(ctx, nn_add(ctx, nn_scale(ctx, lc, (float)o->lambda[0]), nn_scale(ctx, li, (float)o->lambda[1])),
                                 nn_add(ctx, nn_scale(ctx, lang, (float)la), nn_scale(ctx, lar, (float)lr_)));
        nn_tensor *lfold = NULL;
        if (o->lambda_fold > 0) {
            lfold = param_loss_fold_barrier(ctx, uv, &d.corners, nn_view(ctx, d.nf, 1, d.area3d),
                                            nn_view(ctx, d.nf, 1, b.orient), (float)o->fold_eps);
            loss = nn_add(ctx, loss, nn_scale(ctx, lfold, (float)o->lambda_fold));
        }
        nn_tensor *lwarm = NULL;
        if (d.target && it < o->warm_iters && o->lambda_warm > 0 && !o->init) { /* fine-tuning starts from the model instead */
            lwarm = param_loss_cycle(ctx, nn_view(ctx, d.nv, 2, d.target), nn_gather_rows(ctx, uv, b.vertex_rows, d.nv));
            loss = nn_add(ctx, loss, nn_scale(ctx, lwarm, (float)o->lambda_warm));
        }
        nn_params_zero_grad(&model->params);
        s = nn_backward(ctx, loss);
        if (s != NEUV_OK) goto done;
        if (!isfinite(loss->data[0])) { s = error_set(NEUV_ERR_INTERNAL, "parameterization loss is not finite at iteration %d", it); goto done; }
        nn_adam_step(&adam);
        rep->loss = loss->data[0];
        rep->loss_cycle = lc->data[0]; rep->loss_iso = li->data[0];
        rep->loss_angle = lang->data[0]; rep->loss_area = lar->data[0];
        rep->loss_barrier = lfold ? lfold->data[0] : 0;
        rep->loss_warm = lwarm ? lwarm->data[0] : 0;
        if ((it % 10 == 0 || it == o->iters - 1) &&
            log_progress("param", (double)(it + 1) / o->iters, "iter %d loss %.5f", it + 1, rep->loss))
            { s = error_cancelled(); goto done; }
        /* Plateau: the mean loss of a window improved by less than plateau_tol on the
         * previous one. The angle/area weights change at warm-up, so windows restart there. */
        if ((it == o->warmup_iters && o->warmup_iters > 0) || (it == o->warm_iters && o->warm_iters > 0)) {
            window_sum = 0;
            prev_window = INFINITY;
        }
        window_sum += rep->loss;
        int w = o->plateau_window > 0 ? o->plateau_window : 0;
        if (w > 0 && (it + 1) % w == 0) {
            double mean = window_sum / w;
            window_sum = 0;
            if (it + 1 >= o->min_iters && it + 1 < o->iters && it + 1 > o->warmup_iters && it + 1 > o->warm_iters &&
                prev_window - mean < o->plateau_tol * prev_window) {
                rep->stopped_on_plateau = 1;
                it++;
                break;
            }
            prev_window = mean;
        }
    }
    rep->iters = it;
    /* The training step's arena (every face's loss terms) is not needed by
     * the solves; a fresh context holds the final map below. */
    nn_ctx_free(ctx);
    ctx = NULL;
    if (o->solve_steps > 0 && o->depth >= 2) {
        param_solve_data sd = {d.nv, d.nf, n_charts, d.x, d.x, 3, d.vchart, pooled ? d.psi : d.feat, d.psi_dim,
                               !pooled, d.tri, d.fchart, d.frame_inv, d.conf_w, 0, 0, NULL, 0, NULL, 0, 0};
        param_solve_report sr, hr;
        memset(&hr, 0, sizeof hr);
        s = param_output_solve_conformal(&model->f, &sd, o->solve_anchor, o->solve_steps, &sr);
        if (s == NEUV_OK && o->chart_heads) {
            model->heads = mem_alloc(sizeof(float) * (size_t)n_charts * param_head_size(&model->f));
            if (!model->heads) s = error_nomem("chart heads");
            else {
                param_solve_data hd = sd;
                hd.fold_weight = o->solve_fold;
                hd.fold_eps = o->solve_fold_eps;
                hd.mips_steps = o->solve_mips;
                if (o->solve_refit && d.target) { hd.fit_uv = d.target; hd.fit_nv = d.nv; }
                param_solve_subdivided sub;
                memset(&sub, 0, sizeof sub);
                if (o->solve_subdivide && o->solve_fold > 0 && pooled) {
                    s = param_solve_subdivide(&hd, o->solve_subdivide_energy, param_net_dense_vertices(&model->f, o), &sub);
                    if (s == NEUV_OK) hd = sub.d;
                }
                if (s == NEUV_OK)
                    s = param_output_solve_heads(&model->f, &hd, o->solve_anchor, o->solve_steps, model->heads, &hr);
                param_solve_subdivided_free(&sub);
            }
        }
        if (s == NEUV_OK) s = param_output_solve_inverse(&model->g, &model->f, model->heads, &sd);
        if (s != NEUV_OK) goto done;
        rep->solve_energy_before = sr.energy_before;
        rep->solve_energy_after = model->heads ? hr.energy_after : sr.energy_after;
        rep->solve_steps = sr.steps;
        rep->heads_improved = hr.heads_improved;
        rep->heads_refit = hr.heads_refit;
    }
    rep->train_seconds = now_seconds() - t1;
    ctx = nn_ctx_create(0);
    if (!ctx) { s = error_nomem("parameterization map"); goto done; }

    /* Final map at the vertices, oriented counter-clockwise per chart. */
    model->mirror = mem_alloc((size_t)n_charts * sizeof(int));
    if (!model->mirror) { s = error_nomem("chart orientation"); goto done; }
    model->uv_gain = mem_alloc((size_t)n_charts * sizeof(double));
    if (!model->uv_gain) { s = error_nomem("chart scale"); goto done; }
    s = map_vertices(ctx, model, &d, 1, model->mirror, model->uv_gain, corner_uv, &rep->flipped, &rep->cycle_rms);
    if (s != NEUV_OK) goto done;
    model->center = d.center; d.center = NULL;
    model->scale = d.scale; d.scale = NULL;
    model->rot = d.rot; d.rot = NULL;
    model->psi = d.psi; d.psi = NULL;
    model->psi_shift = d.shift; d.shift = NULL;
    model->psi_mul = d.mul; d.mul = NULL;
    s = NEUV_OK;
done:
    nn_ctx_free(ctx);
    nn_adam_free(&adam);
    step_buffers_free(&b);
    train_data_free(&d);
    if (s == NEUV_OK && o->keep_model) rep->model = model;
    else param_net_model_free(model);
    rep->seconds = now_seconds() - t0;
    return s;
}

/* A head per chart of `d` (charts the model never saw), solved as in
 * training: the shared output layer, then the fold barrier (on the faces
 * split in four too) and the scale-free energy, over the model's features. */
static neuv_status solve_new_heads(const param_net_model *model, const train_data *d, const param_net_options *o,
                                   float *heads)
{
    param_solve_data sd = {d->nv, d->nf, d->n_charts, d->x, d->x, 3, d->vchart, d->psi, d->psi_dim, 0, d->tri,
                           d->fchart, d->frame_inv, d->conf_w, o->solve_fold, o->solve_fold_eps, NULL, o->solve_mips, NULL, 0, 0};
    param_solve_subdivided sub;
    memset(&sub, 0, sizeof sub);
    neuv_status s = NEUV_OK;
    if (o->solve_refit && d->target) { sd.fit_uv = d->target; sd.fit_nv = d->nv; }
    if (o->solve_subdivide && o->solve_fold > 0 &&
        (s = param_solve_subdivide(&sd, o->solve_subdivide_energy, param_net_dense_vertices(&model->f, o), &sub)) == NEUV_OK)
        sd = sub.d;
    if (s == NEUV_OK) s = param_output_solve_heads(&model->f, &sd, o->solve_anchor, o->solve_steps, heads, NULL);
    param_solve_subdivided_free(&sub);
    return s;
}

neuv_status param_net_infer(const param_net_model *model, const neuv_mesh *m, const int *face_chart, int n_charts,
                            const float *vertex_features, int feature_dim, int solve_heads, double *corner_uv,
                            param_net_report *rep, param_net_model **shape_model)
{
    param_net_report local;
    if (!rep) rep = &local;
    memset(rep, 0, sizeof *rep);
    if (shape_model) *shape_model = NULL;
    if (!model || !model->psi_shift || !model->psi_mul || model->psi_mode != PARAM_PSI_POOLED)
        return error_set(NEUV_ERR_INPUT, "this parameterization model holds no ψ standardization: it can only map "
                                         "the charts it was trained on");
    int want = vertex_features ? 2 * feature_dim : 6;
    if (want != model->psi_dim)
        return error_set(NEUV_ERR_INPUT, "the model's ψ has %d numbers, these charts' features give %d", model->psi_dim,
                         want);
    param_net_options o;
    param_net_default_options(&o, PARAM_PRESET_FAST);
    o.width = model->f.width;
    o.depth = model->f.depth;
    o.infer_heads = solve_heads && model->f.depth >= 2;
    neuv_status s = check_input(m, face_chart, n_charts, vertex_features, feature_dim, &o, corner_uv);
    if (s != NEUV_OK) return s;
    double t0 = now_seconds();
    train_data d;
    nn_ctx *ctx = NULL;
    int *mirror = mem_alloc((size_t)n_charts * sizeof(int));
    if (!mirror) return error_nomem("chart orientation");
    s = train_data_build(m, face_chart, n_charts, vertex_features, feature_dim, &o, model, 1, &d);
    if (s == NEUV_OK) {
        ctx = nn_ctx_create(0);
        if (!ctx) s = error_nomem("parameterization inference");
    }
    /* Charts the model never saw: the shared output layer, not its own
     * charts' heads; or heads solved for these charts. */
    double *gain = s == NEUV_OK ? mem_alloc((size_t)n_charts * sizeof(double)) : NULL;
    if (s == NEUV_OK && !gain) s = error_nomem("chart scale");
    param_net_model with = *model;
    with.heads = NULL;
    if (s == NEUV_OK && o.infer_heads) {
        with.heads = mem_alloc(sizeof(float) * (size_t)n_charts * param_head_size(&model->f));
        s = with.heads ? solve_new_heads(model, &d, &o, with.heads) : error_nomem("chart heads");
    }
    if (s == NEUV_OK)
        s = map_vertices(ctx, &with, &d, with.heads != NULL, mirror, gain, corner_uv, &rep->flipped, &rep->cycle_rms);
    if (s == NEUV_OK && shape_model && with.heads) {
        /* These charts' own frames, ψ, orientation, gains and heads over the model's networks. */
        param_net_model *v = mem_alloc(sizeof *v);
        if (!v) {
            s = error_nomem("shape model");
        } else {
            *v = *model;
            v->borrowed = 1;
            v->n_charts = n_charts;
            v->psi = d.psi; d.psi = NULL;
            v->center = d.center; d.center = NULL;
            v->scale = d.scale; d.scale = NULL;
            v->rot = d.rot; d.rot = NULL;
            v->mirror = mirror; mirror = NULL;
            v->uv_gain = gain; gain = NULL;
            v->heads = with.heads; with.heads = NULL;
            *shape_model = v;
        }
    }
    mem_free(with.heads);
    mem_free(gain);
    nn_ctx_free(ctx);
    train_data_free(&d);
    mem_free(mirror);
    rep->seconds = now_seconds() - t0;
    return s;
}
