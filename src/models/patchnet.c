/* PatchNet: see patchnet.h.
 *
 * Decisions (measured, see bench/RESULTS.md "PatchNet (issue 6)"):
 *   - Input features default to HKS and vertex normals (issue 20, item 5).
 *     HKS alone is rigid-motion and scale invariant, so the patches follow
 *     intrinsic shape parts, but it cannot tell apart parts that a symmetry
 *     of the surface exchanges (a cube's six sides get identical inputs, and
 *     L_cos stays at 1: no learning); the normals can, and they are what
 *     L_cos measures. xyz also can, but its charts move with the pose.
 *     Measured on the cube (sides found for 10 of 10 seeds, HKS 0) and on
 *     every shared mesh (bench/RESULTS.md, "PatchNet on the cube").
 *   - An emptied patch is re-seeded during training (patchnet_split.h). */
#include "models/patchnet.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/log.h"
#include "core/mem.h"
#include "core/rng.h"
#include "core/timer.h"
#include "geometry/heat_geodesics.h"
#include "losses/patch_losses.h"
#include "models/patchnet_split.h"
#include "nn/adam.h"

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
    o->features = DIFFUSION_NET_HKS_NORMALS;
    o->seed = 1;
    o->geo_sources = 128;
    o->plateau_window = 25;
    o->plateau_tol = 1e-3;
    o->lr = 1e-3f;
    o->min_area_share = 0.002;
    o->merge_distortion = 1.03;
    o->min_convexity = 0.8;
    o->empty_share = 0.1;
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
    st = heat_geodesics_diameter(hg, &diam);
    if (!(diam > 0) || !isfinite(diam)) diam = 1;
    /* A block of sources at a time in float64, so that only the float rows
     * are #S by #F (a float64 copy of all of them was twice that again). */
    const int block = HEAT_GEODESICS_BLOCK;
    double *d = st ? NULL : mem_alloc(sizeof(double) * (size_t)m->nf * (s < block ? s : block));
    if (!st && !d) st = error_nomem("L_geo distances");
    for (int b0 = 0; !st && b0 < s; b0 += block) {
        int k = s - b0 < block ? s - b0 : block;
        st = heat_geodesics_face_distances(hg, m, src + b0, k, d);
        /* Column-major #F by k is row-major k by #F: rows b0.. of dist. */
        float *rows = dist + (size_t)b0 * m->nf;
        for (size_t i = 0; !st && i < (size_t)m->nf * k; i++) {
            double v = d[i] / diam;
            rows[i] = (float)(isfinite(v) ? (v < 0 ? 0 : v) : 1.0);
        }
    }
    heat_geodesics_free(hg);
    mem_free(d);
    return st;
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

/* The training loss of one shape: L_cos + L_geo on the softmax output.
 * Outputs: *P, *hidden (may be NULL), *Lc, *Lg (the two terms). */
static nn_tensor *patchnet_loss(nn_ctx *ctx, const patchnet_model *model, const train_shape *t, nn_tensor **P,
                                nn_tensor **hidden, nn_tensor **Lc, nn_tensor **Lg)
{
    int nf = t->m->nf;
    nn_tensor *xin = nn_view(ctx, t->m->nv, t->dim, t->x);
    nn_tensor *a = nn_view(ctx, nf, 1, t->area);
    nn_tensor *n = nn_view(ctx, nf, 3, t->normal);
    nn_tensor *D = nn_view(ctx, t->S, nf, t->dist);
    nn_tensor *p = patchnet_forward(ctx, model, &t->g, xin, hidden);
    if (P) *P = p;
    *Lc = patch_loss_cos(ctx, p, a, n);
    *Lg = patch_loss_geo(ctx, p, a, t->src, t->S, D);
    return nn_add(ctx, *Lc, *Lg);
}

static int param_index(const nn_params *ps, const nn_tensor *p)
{
    for (int i = 0; i < ps->n; i++)
        if (ps->t[i] == p) return i;
    return -1;
}

/* Re-seeds an emptied patch by splitting the worst one (models/patchnet_split.h).
 * The move is always kept, as k-means keeps a re-seeded empty cluster: the
 * split raises the loss at first where the new column also shifts other
 * patches' faces, and training settles it (on the cube a kept-if-better rule
 * found the sides for 9 of 10 seeds, always keeping for 10 of 10). Adam's
 * moments of the two output columns, which now mean other patches, restart. */
static neuv_status reseed_empty_patch(nn_ctx *ctx, patchnet_model *model, nn_adam *adam, const train_shape *t,
                                      const patchnet_options *o, int *kept)
{
    *kept = 0;
    nn_tensor *P, *hidden, *Lc, *Lg;
    nn_tensor *L = patchnet_loss(ctx, model, t, &P, &hidden, &Lc, &Lg);
    if (!isfinite(L->data[0])) return NEUV_OK; /* the training step reports it */
    nn_linear *last = &model->net.last;
    int K = last->out, C = last->in;
    patchnet_split move;
    patchnet_split_empty(P->data, hidden->data, &t->g, t->area, t->normal, K, C, o->empty_share / K, 4.0,
                         last->w->data, last->b->data, &move);
    if (move.empty < 0) return NEUV_OK;
    *kept = 1;
    int iw = param_index(adam->params, last->w), ib = param_index(adam->params, last->b);
    int cols[2] = {move.empty, move.split};
    for (int c = 0; c < 2; c++) {
        for (int i = 0; iw >= 0 && i < C; i++) adam->m[iw][(size_t)i * K + cols[c]] = adam->v[iw][(size_t)i * K + cols[c]] = 0;
        if (ib >= 0) adam->m[ib][cols[c]] = adam->v[ib][cols[c]] = 0;
    }
    log_message(NEUV_LOG_DEBUG, "PatchNet: patch %d was empty; re-seeded with %.1f%% of the area from patch %d",
                move.empty, 100 * move.moved_share, move.split);
    return NEUV_OK;
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
    int it = 0, plateaued = 0, reseeds = 0, hold_plateau_until = 0;
    double lc = 0, lg = 0;
    for (it = 0; it < iters; it++) {
        /* One shape per step, in turn: every step is one shape's full loss. */
        const train_shape *t = &sh[it % n_shapes];
        nn_ctx_reset(ctx);
        diffusion_net_clamp_times(&model->net);
        /* Every W steps (while W more are left), an emptied patch is re-seeded. */
        if (o->empty_share > 0 && (it + 1) % W == 0 && it + 2 * W < iters) {
            int kept = 0;
            if ((st = reseed_empty_patch(ctx, model, &adam, t, o, &kept))) goto done;
            if (kept) { reseeds++; hold_plateau_until = it + 2 * W; }
            nn_ctx_reset(ctx);
        }
        nn_tensor *Lc, *Lg;
        nn_tensor *L = patchnet_loss(ctx, model, t, NULL, NULL, &Lc, &Lg);
        nn_params_zero_grad(&model->params);
        if ((st = nn_backward(ctx, L))) goto done;
        if (!isfinite(L->data[0])) { st = error_set(NEUV_ERR_INTERNAL, "PatchNet: loss is not finite at iteration %d", it); goto done; }
        nn_adam_step(&adam);
        hist[it] = L->data[0];
        lc = Lc->data[0];
        lg = Lg->data[0];
        if ((it % 10 == 0 || it == iters - 1) &&
            log_progress("patches", (double)(it + 1) / iters, "iter %d loss %.4f", it + 1, hist[it]))
            { st = error_cancelled(); goto done; }
        /* Plateau: the mean of the last W losses improves on the W before by
         * less than plateau_tol of the earlier mean. */
        if (it + 1 >= 2 * W && it >= hold_plateau_until) {
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
        rep->reseeds = reseeds;
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
