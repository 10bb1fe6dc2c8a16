/* Training a category model: see unwrap_category.h. */
#include "unwrap/unwrap_category.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/log.h"
#include "core/mem.h"
#include "core/timer.h"
#include "geometry/operator_cache.h"
#include "geometry/operators.h"
#include "mesh/clean.h"
#include "models/param_net.h"
#include "models/patchnet.h"
#include "nn/nn.h"
#include "segment/patchnet_segment.h"
#include "unwrap/memory_budget.h"
#include "unwrap/unwrap_internal.h"

#define CATEGORY_PSI_NOISE 0.5

int category_default_patch_iters(int n_shapes)
{
    return n_shapes * 40 > 300 ? n_shapes * 40 : 300;
}

/* Every shape's state during training. */
typedef struct category_shape {
    neuv_mesh *mesh;          /* cleaned copy */
    operators ops;
    int *face_chart, n_charts;
    float *features;
    int feature_dim;
} category_shape;

static void category_shape_free(category_shape *c)
{
    mesh_free(c->mesh);
    operators_free(&c->ops);
    mem_free(c->face_chart);
    mem_free(c->features);
}

/* The shapes side by side as one mesh (each a component), with chart ids and
 * vertex features offset to match. */
static neuv_status join_shapes(const category_shape *sh, int n, neuv_mesh **joined, int **face_chart, int *n_charts,
                               float **features)
{
    int nv = 0, nf = 0, dim = sh[0].feature_dim;
    for (int i = 0; i < n; i++) { nv += sh[i].mesh->nv; nf += sh[i].mesh->nf; }
    neuv_mesh *m = mesh_create(nv, nf, 0);
    int *fc = mem_alloc(sizeof(int) * (size_t)nf);
    float *ft = mem_alloc(sizeof(float) * (size_t)nv * (size_t)dim);
    if (!m || !fc || !ft) { mesh_free(m); mem_free(fc); mem_free(ft); return error_nomem("the joined shapes"); }
    int vb = 0, fb = 0, cb = 0;
    for (int i = 0; i < n; i++) {
        const neuv_mesh *s = sh[i].mesh;
        memcpy(m->pos + 3 * (size_t)vb, s->pos, sizeof(double) * 3 * (size_t)s->nv);
        memcpy(ft + (size_t)vb * dim, sh[i].features, sizeof(float) * (size_t)s->nv * dim);
        for (int f = 0; f < s->nf; f++) {
            for (int k = 0; k < 3; k++) m->tri[3 * (size_t)(fb + f) + k] = vb + s->tri[3 * f + k];
            fc[fb + f] = cb + sh[i].face_chart[f];
        }
        vb += s->nv;
        fb += s->nf;
        cb += sh[i].n_charts;
    }
    *joined = m;
    *face_chart = fc;
    *n_charts = cb;
    *features = ft;
    return NEUV_OK;
}

static neuv_status prepare_shape(const neuv_mesh *in, int index, int use_cache, category_shape *c)
{
    /* The pipeline's own cleaning (unwrap_internal.h), so that a shape is
     * trained on as an unseen shape will be unwrapped. */
    neuv_status s = unwrap_clean_copy(in, &c->mesh, NULL, NULL);
    if (s == NEUV_ERR_INPUT) {
        char why[256];
        snprintf(why, sizeof why, "%s", neuv_last_error());
        return error_set(NEUV_ERR_INPUT, "shape %d: %s", index + 1, why);
    }
    if (s != NEUV_OK) return s;
    operators_params op = operators_default_params();
    return operators_get(c->mesh, &op, use_cache, &c->ops, NULL, NULL);
}

neuv_status unwrap_category_train(const neuv_mesh *const *meshes, int n, const neuv_unwrap_options *opts,
                                  int patch_iters, unwrap_model **out, category_train_report *rep)
{
    *out = NULL;
    category_train_report local;
    if (!rep) rep = &local;
    memset(rep, 0, sizeof *rep);
    neuv_unwrap_options o;
    if (opts) o = *opts;
    else neuv_unwrap_options_init(&o);
    if (n < 1 || !meshes) return error_set(NEUV_ERR_INPUT, "a category model needs at least one shape");
    if (o.method != NEUV_METHOD_NEURAL)
        return error_set(NEUV_ERR_INPUT, "a category model is made of networks: the method must be neural");
    if (patch_iters < 0) return error_set(NEUV_ERR_INPUT, "PatchNet steps must be positive");
    nn_set_threads(o.threads);
    double t_start = now_seconds(), t = t_start;
    rep->shapes = n;

    category_shape *sh = mem_calloc((size_t)n, sizeof *sh);
    unwrap_model *md = mem_calloc(1, sizeof *md);
    const neuv_mesh **ms = mem_alloc(sizeof *ms * (size_t)n);
    const operators **os = mem_alloc(sizeof *os * (size_t)n);
    neuv_mesh *joined = NULL;
    int *joined_chart = NULL, joined_charts = 0;
    float *joined_features = NULL;
    double *corner_uv = NULL;
    neuv_status s = NEUV_OK;
    if (!sh || !md || !ms || !os) { s = error_nomem("the shapes"); goto done; }
    double all_faces = 0;
    for (int i = 0; i < n; i++) all_faces += meshes[i] ? meshes[i]->nf : 0;
    char what[48];
    snprintf(what, sizeof what, n == 1 ? "the %d shape" : "the %d shapes", n);
    if ((s = memory_check_training(all_faces, o.max_memory_mb, what,
                                   "train on fewer or simplified shapes (neuv remesh --simplify) or raise the budget "
                                   "(--max-memory MIB; library: max_memory_mb)")) != NEUV_OK)
        goto done;
    for (int i = 0; i < n && s == NEUV_OK; i++) {
        log_progress("operators", (double)i / n, "shape %d of %d", i + 1, n);
        if (!meshes[i] || meshes[i]->nf == 0) s = error_set(NEUV_ERR_INPUT, "shape %d has no faces", i + 1);
        else s = prepare_shape(meshes[i], i, o.use_cache, &sh[i]);
        if (s == NEUV_OK) { ms[i] = sh[i].mesh; os[i] = &sh[i].ops; rep->faces += sh[i].mesh->nf; }
    }
    if (s != NEUV_OK) goto done;
    rep->seconds_operators = now_seconds() - t;

    /* PatchNet over all shapes. */
    t = now_seconds();
    patchnet_options po;
    patchnet_default_options(&po);
    if (o.preset == NEUV_PRESET_PAPER) patchnet_apply_preset(&po, "paper");
    po.charts = o.charts;
    po.max_distortion = o.max_distortion;
    po.seed = o.seed;
    po.iters = patch_iters > 0 ? patch_iters : category_default_patch_iters(n);
    int k = o.charts > 0 ? o.charts : po.initial_charts;
    md->patchnet = mem_calloc(1, sizeof *md->patchnet);
    if (!md->patchnet) { s = error_nomem("the model"); goto done; }
    if ((s = patchnet_model_create_for_mesh(md->patchnet, &po, sh[0].mesh, &sh[0].ops, k)) != NEUV_OK) goto done;
    patchnet_report prep;
    memset(&prep, 0, sizeof prep);
    if ((s = patchnet_train_shapes(md->patchnet, ms, os, n, &po, &prep)) != NEUV_OK) goto done;
    rep->patch_k = k;
    rep->patch_iterations = prep.iterations;
    rep->patch_loss = prep.loss;
    rep->seconds_patches = now_seconds() - t;

    /* Each shape's charts and features, as an unseen shape will get them. */
    t = now_seconds();
    for (int i = 0; i < n && s == NEUV_OK; i++) {
        log_progress("charts", (double)i / n, "shape %d of %d", i + 1, n);
        sh[i].face_chart = mem_alloc(sizeof(int) * (size_t)sh[i].mesh->nf);
        if (!sh[i].face_chart) { s = error_nomem("charts"); break; }
        s = patchnet_charts_from_model(md->patchnet, sh[i].mesh, &sh[i].ops, &po, sh[i].face_chart, &sh[i].n_charts,
                                       &sh[i].features, &sh[i].feature_dim, NULL);
        operators_free(&sh[i].ops);
        if (s == NEUV_OK) rep->charts += sh[i].n_charts;
    }
    if (s != NEUV_OK) goto done;
    rep->seconds_charts = now_seconds() - t;

    /* The parameterization networks over every chart of every shape. */
    t = now_seconds();
    if ((s = join_shapes(sh, n, &joined, &joined_chart, &joined_charts, &joined_features)) != NEUV_OK) goto done;
    corner_uv = mem_alloc(sizeof(double) * 6 * (size_t)joined->nf);
    if (!corner_uv) { s = error_nomem("UVs"); goto done; }
    param_net_options pp;
    param_net_default_options(&pp, o.preset == NEUV_PRESET_PAPER ? PARAM_PRESET_PAPER : PARAM_PRESET_FAST);
    pp.seed = o.seed;
    pp.keep_model = 1;
    /* Measured on the bent-capsule family (bench/RESULTS.md, "Category
     * models"): ψ noise 0.5 (0.25 and 1.0 generalized worse), twice the
     * per-shape steps with no plateau stop (the loss keeps falling slowly
     * past the per-shape plateau, and the unseen members' qce_mean with it). */
    pp.psi_noise = CATEGORY_PSI_NOISE;
    pp.iters = o.iters > 0 ? o.iters : 2 * pp.iters;
    pp.min_iters = pp.iters;
    /* Unseen charts have no head of their own: the shared output layer is what generalizes. */
    pp.chart_heads = 0;
    param_net_report pr;
    memset(&pr, 0, sizeof pr);
    s = param_net_flatten(joined, joined_chart, joined_charts, joined_features, sh[0].feature_dim, &pp, corner_uv, &pr);
    if (s != NEUV_OK) goto done;
    md->param = pr.model;
    rep->param_iterations = pr.iters;
    rep->param_loss = pr.loss;
    rep->seconds_param = now_seconds() - t;

    md->category = 1;
    md->category_shapes = n;
    md->charts_auto = o.charts <= 0;
    md->max_distortion = o.max_distortion;
    md->method = NEUV_METHOD_NEURAL;
    md->preset = o.preset;
    md->seed = o.seed;
    md->refine = o.refine;
    md->resolution = o.resolution;
    md->padding = o.padding;
    rep->seconds = now_seconds() - t_start;
done:
    for (int i = 0; sh && i < n; i++) category_shape_free(&sh[i]);
    mem_free(sh);
    mem_free(ms);
    mem_free(os);
    mesh_free(joined);
    mem_free(joined_chart);
    mem_free(joined_features);
    mem_free(corner_uv);
    if (s == NEUV_OK) *out = md;
    else unwrap_model_free(md);
    return s;
}
