/* PatchNet: see patchnet.h.
 *
 * Decisions (measured, see bench/RESULTS.md "PatchNet (issue 6)"):
 *   - Input features default to HKS: rigid-motion and scale invariant, so the
 *     same surface posed differently gets the same patches, and the patches
 *     follow intrinsic shape parts; xyz trains to similar losses but its
 *     charts move with the pose.
 *   - Auto K splits failing charts with charts_split instead of retraining
 *     with a larger K: one LSCM per new chart costs milliseconds, a retrain
 *     costs the whole training time again, and the split loop always
 *     terminates on a disk that flattens (small enough charts are nearly flat).
 *   - After the split loop, adjacent charts merge back while the union
 *     flattens with qce_mean < 1.03 and fills >= 0.8 of its UV convex hull:
 *     merging up to the split limit 1.15 left spot with 2 charts, qce_mean
 *     1.12 and packing 0.55; 1.05 gave 7 charts and qce_mean 1.049, too
 *     close to the 1.05 bar; without the convexity rule cow packed at 0.24
 *     (bench/RESULTS.md "Charts quality (issues 6-7)"). */
#include "models/patchnet.h"

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
#include "losses/patch_losses.h"
#include "metrics/uv_metrics.h"
#include "nn/adam.h"
#include "unwrap/chart_uv_check.h"
#include "atlas/convex_hull.h"

void patchnet_default_options(patchnet_options *o)
{
    memset(o, 0, sizeof *o);
    o->charts = 0;
    o->max_distortion = 1.15;
    o->max_charts = 64;
    o->initial_charts = 8;
    o->iters = 300;
    o->blocks = 2;
    o->width = 32;
    o->k_eig = 64;
    o->features = DIFFUSION_NET_HKS;
    o->seed = 1;
    o->geo_sources = 128;
    o->plateau_window = 25;
    o->plateau_tol = 1e-3;
    o->lr = 1e-3f;
    o->min_area_share = 0.002;
    o->merge_distortion = 1.03;
    o->min_convexity = 0.8;
}

neuv_status patchnet_apply_preset(patchnet_options *o, const char *preset)
{
    if (!strcmp(preset, "fast")) {
        o->blocks = 2; o->width = 32; o->iters = 300; o->geo_sources = 128;
    } else if (!strcmp(preset, "paper")) {
        o->blocks = 4; o->width = 128; o->iters = 2000; o->geo_sources = 256;
    } else {
        return error_set(NEUV_ERR_INPUT, "unknown preset '%s' (expected fast or paper)", preset);
    }
    o->k_eig = 64;
    return NEUV_OK;
}

neuv_status patchnet_model_create(patchnet_model *model, const patchnet_options *o, int in_dim, int k)
{
    memset(model, 0, sizeof *model);
    nn_params_init(&model->params);
    if (k < 1) return error_set(NEUV_ERR_INPUT, "PatchNet: number of patches must be >= 1, got %d", k);
    diffusion_net_config cfg = {.in = in_dim, .width = o->width, .out = k, .blocks = o->blocks,
                                .seed = o->seed};
    neuv_status st = diffusion_net_create(&model->net, &cfg, &model->params, "patchnet");
    if (st) { nn_params_free(&model->params); return st; }
    model->k = k;
    model->k_eig = o->k_eig;
    model->features = o->features;
    model->in_dim = in_dim;
    return NEUV_OK;
}

neuv_status patchnet_model_create_for_mesh(patchnet_model *model, const patchnet_options *o, const neuv_mesh *m,
                                           const operators *ops, int k)
{
    memset(model, 0, sizeof *model);
    nn_params_init(&model->params);
    float *x = NULL;
    int dim = 0;
    neuv_status st = diffusion_net_input_features(m, ops, o->features, &x, &dim);
    mem_free(x);
    return st ? st : patchnet_model_create(model, o, dim, k);
}

void patchnet_model_free(patchnet_model *model)
{
    if (!model) return;
    diffusion_net_free(&model->net);
    nn_params_free(&model->params);
}

/* Per-face constants of the losses: areas #F by 1, unit normals #F by 3. */
static neuv_status face_area_normal(const neuv_mesh *m, float **area, float **normal)
{
    *area = mem_alloc(sizeof(float) * (size_t)m->nf);
    *normal = mem_alloc(sizeof(float) * 3 * (size_t)m->nf);
    if (!*area || !*normal) return error_nomem("face areas");
    for (int f = 0; f < m->nf; f++) {
        double n[3];
        (*area)[f] = (float)mesh_face_area(m, f);
        mesh_face_normal(m, f, n);
        for (int d = 0; d < 3; d++) (*normal)[3 * f + d] = (float)n[d];
    }
    return NEUV_OK;
}

/* S source faces drawn uniformly without replacement (partial Fisher-Yates,
 * seeded), sorted so the distance rows are in face order. */
static int cmp_int(const void *a, const void *b) { int x = *(const int *)a, y = *(const int *)b; return (x > y) - (x < y); }

static neuv_status sample_sources(int nf, int s, uint64_t seed, int *out)
{
    int *perm = mem_alloc(sizeof(int) * (size_t)nf);
    if (!perm) return error_nomem("L_geo sources");
    for (int i = 0; i < nf; i++) perm[i] = i;
    rng r;
    rng_seed(&r, seed ^ 0x9e3779b97f4a7c15ull);
    for (int i = 0; i < s; i++) {
        int j = i + rng_below(&r, nf - i);
        int t = perm[i]; perm[i] = perm[j]; perm[j] = t;
    }
    memcpy(out, perm, sizeof(int) * (size_t)s);
    mem_free(perm);
    qsort(out, (size_t)s, sizeof(int), cmp_int);
    return NEUV_OK;
}

/* D rows for the sources: #S by #F, geodesic distance / geodesic diameter.
 * Faces in another component (infinite distance) count as 1, the farthest
 * apart two faces of one component can be. */
static neuv_status source_distances(const neuv_mesh *m, const int *src, int s, float *dist)
{
    heat_geodesics *hg = NULL;
    neuv_status st = heat_geodesics_create(m, 1.0, &hg);
    if (st) return st;
    double diam = 0;
    double *d = mem_alloc(sizeof(double) * (size_t)m->nf * s);
    if (!d) { heat_geodesics_free(hg); return error_nomem("L_geo distances"); }
    st = heat_geodesics_diameter(hg, &diam);
    if (!st) st = heat_geodesics_face_distances(hg, m, src, s, d);
    heat_geodesics_free(hg);
    if (st) { mem_free(d); return st; }
    if (!(diam > 0) || !isfinite(diam)) diam = 1;
    /* Column-major #F by #S is row-major #S by #F. */
    for (size_t i = 0; i < (size_t)m->nf * s; i++) {
        double v = d[i] / diam;
        dist[i] = (float)(isfinite(v) ? (v < 0 ? 0 : v) : 1.0);
    }
    mem_free(d);
    return NEUV_OK;
}

/* Face logits -> softmax P (#F by K) for a model on one mesh. */
static nn_tensor *patchnet_forward(nn_ctx *ctx, const patchnet_model *model, const diffusion_net_geometry *g,
                                   nn_tensor *x, nn_tensor **hidden)
{
    nn_tensor *v = diffusion_net_forward(ctx, &model->net, g, x, hidden);
    return nn_softmax_rows(ctx, diffusion_net_vertices_to_faces(ctx, g, v));
}

/* What training needs of one shape: its DiffusionNet geometry, input
 * features, loss constants and the L_geo source distances. */
typedef struct train_shape {
    const neuv_mesh *m;
    diffusion_net_geometry g;
    int g_ready;
    float *x, *area, *normal, *dist;
    int *src, S, dim;
} train_shape;

static void train_shape_free(train_shape *t)
{
    if (t->g_ready) diffusion_net_geometry_free(&t->g);
    mem_free(t->x); mem_free(t->area); mem_free(t->normal); mem_free(t->dist); mem_free(t->src);
    memset(t, 0, sizeof *t);
}

static neuv_status train_shape_init(train_shape *t, const patchnet_model *model, const neuv_mesh *m,
                                    const operators *ops, const patchnet_options *o, uint64_t seed)
{
    memset(t, 0, sizeof *t);
    if (!m || !ops || m->nf < 1) return error_set(NEUV_ERR_INPUT, "PatchNet: mesh has no faces");
    t->m = m;
    int nf = m->nf;
    t->S = o->geo_sources < 1 ? 128 : o->geo_sources;
    if (t->S > nf) t->S = nf;
    neuv_status st = diffusion_net_geometry_create(m, ops, model->k_eig, &t->g);
    if (st) return st;
    t->g_ready = 1;
    if ((st = diffusion_net_input_features(m, ops, model->features, &t->x, &t->dim))) return st;
    if (t->dim != model->in_dim)
        return error_set(NEUV_ERR_INPUT, "PatchNet: model expects %d input channels, features have %d", model->in_dim,
                         t->dim);
    if ((st = face_area_normal(m, &t->area, &t->normal))) return st;
    t->src = mem_alloc(sizeof(int) * (size_t)t->S);
    t->dist = mem_alloc(sizeof(float) * (size_t)t->S * nf);
    if (!t->src || !t->dist) return error_nomem("PatchNet training");
    if ((st = sample_sources(nf, t->S, seed, t->src))) return st;
    return source_distances(m, t->src, t->S, t->dist);
}

neuv_status patchnet_train(patchnet_model *model, const neuv_mesh *m, const operators *ops,
                           const patchnet_options *o, patchnet_report *rep)
{
    const neuv_mesh *ms[1] = {m};
    const operators *os[1] = {ops};
    return patchnet_train_shapes(model, ms, os, 1, o, rep);
}

neuv_status patchnet_train_shapes(patchnet_model *model, const neuv_mesh *const *meshes,
                                  const operators *const *ops, int n_shapes, const patchnet_options *o,
                                  patchnet_report *rep)
{
    patchnet_options def;
    if (!o) { patchnet_default_options(&def); o = &def; }
    if (n_shapes < 1) return error_set(NEUV_ERR_INPUT, "PatchNet: no shapes to train on");
    train_shape *sh = mem_calloc((size_t)n_shapes, sizeof *sh);
    if (!sh) return error_nomem("PatchNet training");
    neuv_status st = NEUV_OK;
    nn_ctx *ctx = NULL;
    nn_adam adam;
    int adam_ready = 0;
    double *hist = NULL;
    int iters = o->iters > 0 ? o->iters : 300;
    double t0 = now_seconds();
    /* Shape i draws its L_geo sources with seed + i (one shape: the seed itself). */
    for (int i = 0; i < n_shapes && !st; i++) {
        st = train_shape_init(&sh[i], model, meshes[i], ops[i], o, o->seed + (uint64_t)i);
        if (n_shapes > 1) log_progress("patches", 0, "geodesics of shape %d of %d", i + 1, n_shapes);
    }
    if (st) goto done;
    double t_geo = now_seconds() - t0;
    hist = mem_alloc(sizeof(double) * (size_t)iters);
    if (!hist) { st = error_nomem("PatchNet training"); goto done; }
    nn_adam_config acfg = nn_adam_defaults();
    acfg.lr = o->lr > 0 ? o->lr : 1e-3f;
    if ((st = nn_adam_init(&adam, &model->params, &acfg))) goto done;
    adam_ready = 1;
    ctx = nn_ctx_create(0);
    if (!ctx) { st = error_nomem("PatchNet arena"); goto done; }
    /* The plateau windows hold whole rounds over the shapes, whose losses differ. */
    int W = o->plateau_window > 0 ? o->plateau_window : 25;
    W = (W + n_shapes - 1) / n_shapes * n_shapes;
    double t1 = now_seconds();
    int it = 0, plateaued = 0;
    double lc = 0, lg = 0;
    for (it = 0; it < iters; it++) {
        /* One shape per step, in turn: every step is one shape's full loss. */
        const train_shape *t = &sh[it % n_shapes];
        int nf = t->m->nf;
        nn_ctx_reset(ctx);
        diffusion_net_clamp_times(&model->net);
        nn_tensor *xin = nn_view(ctx, t->m->nv, t->dim, t->x);
        nn_tensor *a = nn_view(ctx, nf, 1, t->area);
        nn_tensor *n = nn_view(ctx, nf, 3, t->normal);
        nn_tensor *D = nn_view(ctx, t->S, nf, t->dist);
        nn_tensor *P = patchnet_forward(ctx, model, &t->g, xin, NULL);
        nn_tensor *Lc = patch_loss_cos(ctx, P, a, n);
        nn_tensor *Lg = patch_loss_geo(ctx, P, a, t->src, t->S, D);
        nn_tensor *L = nn_add(ctx, Lc, Lg);
        nn_params_zero_grad(&model->params);
        if ((st = nn_backward(ctx, L))) goto done;
        if (!isfinite(L->data[0])) { st = error_set(NEUV_ERR_INTERNAL, "PatchNet: loss is not finite at iteration %d", it); goto done; }
        nn_adam_step(&adam);
        hist[it] = L->data[0];
        lc = Lc->data[0];
        lg = Lg->data[0];
        if (it % 10 == 0 || it == iters - 1)
            log_progress("patches", (double)(it + 1) / iters, "iter %d loss %.4f", it + 1, hist[it]);
        /* Plateau: the mean of the last W losses improves on the W before by
         * less than plateau_tol of the earlier mean. */
        if (it + 1 >= 2 * W) {
            double prev = 0, cur = 0;
            for (int j = it + 1 - 2 * W; j < it + 1 - W; j++) prev += hist[j];
            for (int j = it + 1 - W; j <= it; j++) cur += hist[j];
            if (prev - cur < o->plateau_tol * fabs(prev)) { it++; plateaued = 1; break; }
        }
    }
    double t_train = now_seconds() - t1;
    diffusion_net_clamp_times(&model->net);
    if (rep) {
        rep->k = model->k;
        rep->iterations = it;
        rep->plateaued = plateaued;
        rep->loss = it > 0 ? hist[it - 1] : NAN;
        rep->loss_cos = lc;
        rep->loss_geo = lg;
        rep->geodesic_seconds = t_geo;
        rep->train_seconds = t_train;
        rep->iters_per_second = t_train > 0 ? it / t_train : 0;
    }
done:
    if (ctx) nn_ctx_free(ctx);
    if (adam_ready) nn_adam_free(&adam);
    for (int i = 0; i < n_shapes; i++) train_shape_free(&sh[i]);
    mem_free(sh);
    mem_free(hist);
    return st;
}

neuv_status patchnet_infer_features(const patchnet_model *model, const neuv_mesh *m, const operators *ops,
                                    int *face_label, float **vertex_features, int *feature_dim)
{
    if (vertex_features) *vertex_features = NULL;
    if (feature_dim) *feature_dim = 0;
    diffusion_net_geometry g;
    neuv_status st = diffusion_net_geometry_create(m, ops, model->k_eig, &g);
    if (st) return st;
    float *x = NULL;
    int dim = 0;
    nn_ctx *ctx = NULL;
    if ((st = diffusion_net_input_features(m, ops, model->features, &x, &dim))) goto done;
    if (dim != model->in_dim) {
        st = error_set(NEUV_ERR_INPUT, "PatchNet: model expects %d input channels, features have %d", model->in_dim, dim);
        goto done;
    }
    ctx = nn_ctx_create(0);
    if (!ctx) { st = error_nomem("PatchNet arena"); goto done; }
    nn_tensor *hidden = NULL;
    nn_tensor *P = patchnet_forward(ctx, model, &g, nn_view(ctx, m->nv, dim, x), &hidden);
    if ((st = nn_ctx_status(ctx))) goto done;
    if (face_label)
        for (int f = 0; f < m->nf; f++) {
            const float *p = P->data + (size_t)f * model->k;
            int best = 0;
            for (int j = 1; j < model->k; j++)
                if (p[j] > p[best]) best = j;
            face_label[f] = best;
        }
    if (vertex_features) {
        size_t n = (size_t)hidden->rows * hidden->cols;
        float *vf = mem_alloc(sizeof(float) * n);
        if (!vf) { st = error_nomem("PatchNet vertex features"); goto done; }
        memcpy(vf, hidden->data, sizeof(float) * n);
        *vertex_features = vf;
        if (feature_dim) *feature_dim = hidden->cols;
    }
done:
    if (ctx) nn_ctx_free(ctx);
    diffusion_net_geometry_free(&g);
    mem_free(x);
    return st;
}

neuv_status patchnet_infer(const patchnet_model *model, const neuv_mesh *m, const operators *ops, int *face_label)
{
    return patchnet_infer_features(model, m, ops, face_label, NULL, NULL);
}

/* LSCM of chart `id` alone: qce_mean, the flipped or degenerate faces,
 * and the boundary self-crossings (chart_uv_check: the self-overlaps the
 * repair stage would otherwise split later). crossings may be NULL. */
/* UV area over the area of its convex hull: 1 for a convex footprint,
 * small for a snake or a comb, which the packer cannot nest. */
static double uv_convexity(const neuv_mesh *sub, const double *uv)
{
    int *hull = mem_alloc(sizeof(int) * (size_t)sub->nv);
    if (!hull) return -1;
    int h = convex_hull_2d(uv, sub->nv, hull);
    double hull_area = 0, area = 0;
    for (int i = 0; i < h; i++) {
        const double *p = uv + 2 * hull[i], *r = uv + 2 * hull[(i + 1) % h];
        hull_area += p[0] * r[1] - p[1] * r[0];
    }
    for (int f = 0; f < sub->nf; f++) {
        const double *a = uv + 2 * sub->tri[3 * f], *b = uv + 2 * sub->tri[3 * f + 1], *c = uv + 2 * sub->tri[3 * f + 2];
        area += (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    }
    mem_free(hull);
    if (h < 0) return -1;
    return hull_area > 0 ? fabs(area) / hull_area : 1.0;
}

/* LSCM's qce_mean and flipped faces on chart `id`; with `crossings`, also
 * its boundary self-crossings and (convexity, when not NULL) the share of
 * its UV footprint's convex hull that the footprint fills. */
static neuv_status chart_lscm_judge(const neuv_mesh *m, const int *face_chart, int id, double *qce_mean,
                                    int *flipped, int *crossings, double *convexity)
{
    if (convexity) *convexity = 1.0;
    *qce_mean = INFINITY;
    *flipped = 0;
    if (crossings) *crossings = 0;
    neuv_mesh *sub = NULL;
    int *vmap = NULL, *fmap = NULL;
    neuv_status st = chart_submesh(m, face_chart, id, &sub, &vmap, &fmap);
    if (st) return st;
    mem_free(vmap);
    mem_free(fmap);
    double *uv = mem_alloc(sizeof(double) * 2 * (size_t)sub->nv);
    if (!uv) { mesh_free(sub); return error_nomem("chart UVs"); }
    st = lscm(sub, uv);
    if (st == NEUV_ERR_NOMEM) { mem_free(uv); mesh_free(sub); return st; }
    if (st == NEUV_OK) {
        /* A chart LSCM cannot flatten stays at qce INFINITY: the split loop
         * then cuts it smaller. */
        st = mesh_set_uv(sub, sub->nv, uv, sub->tri);
        uv_metrics mt;
        if (!st) st = uv_metrics_compute(sub, &mt);
        if (!st) {
            *qce_mean = isfinite(mt.qce_mean) ? mt.qce_mean : INFINITY;
            *flipped = mt.flipped + mt.degenerate_uv;
        }
        if (!st && crossings) {
            chart_uv_check chk;
            int ok = chart_uv_check_run(sub, uv, &chk);
            if (ok < 0) st = NEUV_ERR_NOMEM;
            else *crossings = chk.boundary_crossings;
            double cvx = convexity ? uv_convexity(sub, uv) : 1.0;
            if (!st && cvx < 0) st = NEUV_ERR_NOMEM;
            if (!st && convexity) *convexity = cvx;
        }
        if (st == NEUV_ERR_NOMEM) { mem_free(uv); mesh_free(sub); return error_nomem("chart check"); }
    }
    mem_free(uv);
    mesh_free(sub);
    return NEUV_OK;
}

neuv_status patchnet_chart_lscm_quality(const neuv_mesh *m, const int *face_chart, int id, double *qce_mean,
                                        int *flipped)
{
    return chart_lscm_judge(m, face_chart, id, qce_mean, flipped, NULL, NULL);
}

/* Grows a per-chart array to n entries (new entries: dirty). */
static neuv_status grow_quality(double **q, int **flip, int **dirty, int *cap, int n)
{
    if (n <= *cap) return NEUV_OK;
    int c = *cap ? *cap : 16;
    while (c < n) c *= 2;
    double *nq = mem_realloc(*q, sizeof(double) * (size_t)c);
    if (!nq) return error_nomem("chart qualities");
    *q = nq;
    int *nfl = mem_realloc(*flip, sizeof(int) * (size_t)c);
    if (!nfl) return error_nomem("chart qualities");
    *flip = nfl;
    int *nd = mem_realloc(*dirty, sizeof(int) * (size_t)c);
    if (!nd) return error_nomem("chart qualities");
    *dirty = nd;
    for (int i = *cap; i < c; i++) { nd[i] = 1; nq[i] = INFINITY; nfl[i] = 0; }
    *cap = c;
    return NEUV_OK;
}

/* Merges adjacent charts back together while the union still flattens:
 * the split loop and the argmax both cut more than needed (a split can go
 * across a chart that one of its neighbours could take whole). Pairs are
 * tried longest shared boundary first, each chart in one merge per round;
 * a merge stands when the union is a disk whose LSCM has qce_mean below
 * `limit`, no flipped face, no boundary self-crossing, and a UV footprint
 * filling at least min_cvx of its convex hull (snakes and combs pack badly). The surviving
 * ids are compacted in order, with their qualities. */
static neuv_status merge_charts(const neuv_mesh *m, double limit, double min_cvx, int *face_chart,
                                int *n_charts, double *q, int *flip, int *merges)
{
    int nf = m->nf;
    int *gone = NULL, *moved = NULL, *order = NULL;
    double *len = NULL;
    neuv_status st = NEUV_OK;
    for (;;) {
        chart_adjacency adj;
        if ((st = chart_adjacency_build(m, face_chart, &adj))) break;
        int nc = *n_charts;
        mem_free(gone); mem_free(moved); mem_free(order); mem_free(len);
        gone = mem_calloc((size_t)nc, sizeof(int));
        moved = mem_alloc(sizeof(int) * (size_t)nf);
        order = mem_alloc(sizeof(int) * (size_t)(adj.n > 0 ? adj.n : 1));
        len = mem_alloc(sizeof(double) * (size_t)(adj.n > 0 ? adj.n : 1));
        if (!gone || !moved || !order || !len) { chart_adjacency_free(&adj); st = error_nomem("chart merge"); break; }
        /* Insertion order by length, descending (ties: pair order), stable. */
        for (int i = 0; i < adj.n; i++) {
            int j = i;
            while (j > 0 && adj.length[order[j - 1]] < adj.length[i]) { order[j] = order[j - 1]; j--; }
            order[j] = i;
        }
        int any = 0;
        for (int r = 0; r < adj.n && !st; r++) {
            int a = adj.a[order[r]], b = adj.b[order[r]];
            if (gone[a] || gone[b] || gone[a] < 0 || gone[b] < 0) continue;
            int n = 0;
            for (int f = 0; f < nf; f++)
                if (face_chart[f] == b) { face_chart[f] = a; moved[n++] = f; }
            int disk = chart_is_disk(m, face_chart, a);
            double qa = INFINITY;
            int fl = 1, cross = 1;
            double cvx = 0;
            if (disk < 0) st = error_nomem("chart merge");
            else if (disk) st = chart_lscm_judge(m, face_chart, a, &qa, &fl, &cross, &cvx);
            if (!st && disk == 1 && qa < limit && fl == 0 && cross == 0 && cvx >= min_cvx) {
                q[a] = qa;
                flip[a] = 0;
                gone[b] = 1;
                gone[a] = -1; /* changed: no second merge this round */
                any = 1;
                (*merges)++;
            } else {
                for (int i = 0; i < n; i++) face_chart[moved[i]] = b;
            }
        }
        chart_adjacency_free(&adj);
        if (st || !any) break;
        /* Compact: new id = old id minus the merged-away ids below it. */
        int k = 0;
        for (int c = 0; c < nc; c++) {
            int keep = gone[c] != 1;
            if (keep) { q[k] = q[c]; flip[k] = flip[c]; gone[c] = k++; }
            else gone[c] = -2;
        }
        for (int f = 0; f < nf; f++) face_chart[f] = gone[face_chart[f]];
        *n_charts = k;
    }
    mem_free(gone); mem_free(moved); mem_free(order); mem_free(len);
    return st;
}

/* The chart check and split loop (auto K), or only the check (fixed K). */
static neuv_status refine_charts(const neuv_mesh *m, const patchnet_options *o, int *face_chart, int *n_charts,
                                 patchnet_report *rep)
{
    double t0 = now_seconds();
    double *q = NULL;
    int *flip = NULL, *dirty = NULL, cap = 0, splits = 0;
    int *count = NULL;
    neuv_status st = grow_quality(&q, &flip, &dirty, &cap, *n_charts);
    int auto_k = o->charts <= 0;
    int max_charts = o->max_charts > 0 ? o->max_charts : 64;
    while (!st) {
        for (int c = 0; c < *n_charts && !st; c++)
            if (dirty[c]) {
                int cross = 0;
                st = chart_lscm_judge(m, face_chart, c, &q[c], &flip[c], &cross, NULL);
                /* A self-overlapping boundary fails like a flip. */
                flip[c] += cross;
                dirty[c] = 0;
            }
        if (st || !auto_k) break;
        /* Failing charts, worst first, each split once this round. */
        mem_free(count);
        count = mem_calloc((size_t)*n_charts, sizeof(int));
        if (!count) { st = error_nomem("chart sizes"); break; }
        for (int f = 0; f < m->nf; f++) count[face_chart[f]]++;
        int any = 0;
        for (;;) {
            int worst = -1;
            double wq = 0;
            for (int c = 0; c < *n_charts; c++) {
                if (dirty[c] || count[c] < 2) continue;
                int fails = !(q[c] < o->max_distortion) || flip[c] > 0;
                double score = flip[c] > 0 ? INFINITY : q[c];
                if (fails && (worst < 0 || score > wq)) { worst = c; wq = score; }
            }
            if (worst < 0 || *n_charts >= max_charts) break;
            int before = *n_charts;
            if ((st = charts_split(m, face_chart, n_charts, worst))) break;
            if ((st = grow_quality(&q, &flip, &dirty, &cap, *n_charts))) break;
            dirty[worst] = 1;
            for (int c = before; c < *n_charts; c++) dirty[c] = 1;
            splits++;
            any = 1;
        }
        if (!any) break;
        log_progress("charts", 1.0, "%d charts after %d splits", *n_charts, splits);
    }
    /* Merging back is stricter than the split loop (see patchnet.c's header
     * and bench/RESULTS.md): a union passes under merge_distortion and
     * min_convexity, or the mean distortion and the packing suffer. */
    int merges = 0;
    if (!st && auto_k && o->merge_distortion > 0)
        st = merge_charts(m, o->merge_distortion, o->min_convexity, face_chart, n_charts, q, flip, &merges);
    if (!st && rep) {
        rep->merges = merges;
        rep->splits = splits;
        rep->charts = *n_charts;
        rep->worst_qce = 0;
        rep->flipped = 0;
        for (int c = 0; c < *n_charts; c++) {
            if (q[c] > rep->worst_qce) rep->worst_qce = q[c];
            rep->flipped += flip[c];
        }
        rep->chart_check_seconds = now_seconds() - t0;
    }
    mem_free(q); mem_free(flip); mem_free(dirty); mem_free(count);
    return st;
}

neuv_status patchnet_charts_from_model(const patchnet_model *model, const neuv_mesh *m, const operators *ops,
                                      const patchnet_options *o, int *face_chart, int *n_charts,
                                      float **vertex_features, int *feature_dim, patchnet_report *rep)
{
    patchnet_options def;
    if (!o) { patchnet_default_options(&def); o = &def; }
    if (vertex_features) *vertex_features = NULL;
    if (feature_dim) *feature_dim = 0;
    patchnet_report local;
    if (!rep) { rep = &local; memset(rep, 0, sizeof *rep); }
    int *label = mem_alloc(sizeof(int) * (size_t)m->nf);
    if (!label) return error_nomem("patch labels");
    neuv_status st = patchnet_infer_features(model, m, ops, label, vertex_features, feature_dim);
    if (!st) {
        charts_options copt;
        charts_default_options(&copt);
        if (o->min_area_share > 0) copt.min_area_share = o->min_area_share;
        st = charts_from_labels(m, label, &copt, face_chart, n_charts, NULL);
    }
    if (!st) {
        rep->label_charts = *n_charts;
        st = refine_charts(m, o, face_chart, n_charts, rep);
    }
    mem_free(label);
    if (st && vertex_features) { mem_free(*vertex_features); *vertex_features = NULL; }
    return st;
}

neuv_status patchnet_segment_model(const neuv_mesh *m, const operators *ops, const patchnet_options *o,
                                   int *face_chart, int *n_charts, float **vertex_features, int *feature_dim,
                                   patchnet_report *rep, patchnet_model *model_out)
{
    double t0 = now_seconds();
    patchnet_options def;
    if (!o) { patchnet_default_options(&def); o = &def; }
    if (vertex_features) *vertex_features = NULL;
    if (feature_dim) *feature_dim = 0;
    if (model_out) memset(model_out, 0, sizeof *model_out);
    if (!m || !ops || m->nf < 1) return error_set(NEUV_ERR_INPUT, "PatchNet: mesh has no faces");
    patchnet_report local;
    if (!rep) rep = &local;
    memset(rep, 0, sizeof *rep);
    int k = o->charts > 0 ? o->charts : (o->initial_charts > 0 ? o->initial_charts : 8);
    if (k > m->nf) k = m->nf;
    patchnet_model model;
    neuv_status st = patchnet_model_create_for_mesh(&model, o, m, ops, k);
    if (st) return st;
    if ((st = patchnet_train(&model, m, ops, o, rep))) goto done;
    if ((st = patchnet_charts_from_model(&model, m, ops, o, face_chart, n_charts, vertex_features, feature_dim,
                                         rep)))
        goto done;
    rep->seconds = now_seconds() - t0;
done:
    if (!st && model_out) *model_out = model;
    else patchnet_model_free(&model);
    return st;
}

neuv_status patchnet_segment(const neuv_mesh *m, const operators *ops, const patchnet_options *o,
                             int *face_chart, int *n_charts, float **vertex_features, int *feature_dim,
                             patchnet_report *rep)
{
    return patchnet_segment_model(m, ops, o, face_chart, n_charts, vertex_features, feature_dim, rep, NULL);
}
