/* Public models: a saved unwrap of one surface or a category model, loaded,
 * saved, applied to an atlas's mesh, trained over several shapes. */
#include <string.h>

#include "neuv/neuv.h"
#include "api/api_atlas.h"
#include "core/error.h"
#include "core/log.h"
#include "core/mem.h"
#include "unwrap/unwrap_apply.h"
#include "unwrap/unwrap_category.h"
#include "unwrap/unwrap_internal.h"
#include "unwrap/unwrap_model.h"

struct neuv_model {
    unwrap_model *model;
};

static neuv_status wrap(unwrap_model *md, neuv_model **out)
{
    neuv_model *m = mem_calloc(1, sizeof *m);
    if (!m) { unwrap_model_free(md); return error_nomem("the model"); }
    m->model = md;
    *out = m;
    return NEUV_OK;
}

neuv_status neuv_model_load(const char *path, neuv_model **out)
{
    if (!out) return error_set(NEUV_ERR_INPUT, "neuv_model_load: no output pointer");
    *out = NULL;
    if (!path || !*path) return error_set(NEUV_ERR_INPUT, "no model file name given");
    unwrap_model *md = NULL;
    neuv_status s = unwrap_model_load(path, &md);
    return s == NEUV_OK ? wrap(md, out) : s;
}

neuv_status neuv_model_save(const neuv_model *m, const char *path)
{
    if (!m || !m->model) return error_set(NEUV_ERR_INPUT, "neuv_model_save: no model");
    if (!path || !*path) return error_set(NEUV_ERR_INPUT, "no model file name given");
    return unwrap_model_save(m->model, path);
}

void neuv_model_free(neuv_model *m)
{
    if (!m) return;
    unwrap_model_free(m->model);
    mem_free(m);
}

int neuv_model_is_category(const neuv_model *m) { return m && m->model && m->model->category; }

neuv_status neuv_atlas_take_model(neuv_atlas *a, neuv_model **out)
{
    if (!out) return error_set(NEUV_ERR_INPUT, "neuv_atlas_take_model: no output pointer");
    *out = NULL;
    unwrap_model *md = NULL;
    neuv_status s = api_atlas_take_model(a, &md);
    return s == NEUV_OK ? wrap(md, out) : s;
}

/* Refuses the options that do not apply to the model's kind, and those out
 * of range: none is ignored. The messages name the options as the struct
 * does (the command line maps them to its flags). */
static neuv_status check_apply_options(const unwrap_model *md, const neuv_apply_options *o)
{
    if (!md->category) {
        const char *given = o->finetune > 0 ? "finetune" : o->refine >= 0 ? "refine" : o->shared_layer ? "shared_layer"
                            : o->allow_overlaps ? "allow_overlaps" : NULL;
        if (given)
            return error_set(NEUV_ERR_INPUT, "%s applies to category models: a surface model is applied by inference "
                             "only and keeps its source's maps", given);
        if (o->resolution != 0 || o->padding != -1)
            return error_set(NEUV_ERR_INPUT, "%s applies to category models: a surface model keeps its source's layout "
                             "(%d px square, %d px gutter)", o->resolution != 0 ? "resolution" : "padding",
                             md->resolution, md->padding);
        if (o->keep_model)
            return error_set(NEUV_ERR_INPUT, "keep_model applies to a category model with finetune: a surface model is "
                             "applied, not trained, so it would be the same model again");
        return NEUV_OK;
    }
    if (o->lscm_baseline) return error_set(NEUV_ERR_INPUT, "lscm_baseline needs a surface model, not a category model");
    if (o->check_inference)
        return error_set(NEUV_ERR_INPUT, "check_inference needs a surface model, not a category model");
    if (o->finetune < 0 || o->finetune > 1000000) return error_set(NEUV_ERR_INPUT, "finetune must be in 0..1000000");
    if (o->shared_layer && o->finetune > 0)
        return error_set(NEUV_ERR_INPUT, "shared_layer is for inference; finetune trains the networks");
    if (o->keep_model && o->finetune <= 0)
        return error_set(NEUV_ERR_INPUT, "keep_model with a category model needs finetune > 0: inference trains no "
                         "networks of this shape's to keep");
    if (o->refine < -1 || o->refine > 1000000) return error_set(NEUV_ERR_INPUT, "refine must be -1, 0 or a step count");
    if (o->resolution != 0 && (o->resolution < 64 || o->resolution > 16384))
        return error_set(NEUV_ERR_INPUT, "resolution must be in 64..16384");
    int resolution = o->resolution != 0 ? o->resolution : md->resolution;
    if (o->padding != -1 && (o->padding < 0 || o->padding > resolution / 8))
        return error_set(NEUV_ERR_INPUT, "padding must be in 0..resolution/8 (%d)", resolution / 8);
    return NEUV_OK;
}

neuv_status neuv_atlas_apply_model(neuv_atlas *a, const neuv_model *m, const neuv_apply_options *o)
{
    if (!a) return error_set(NEUV_ERR_INPUT, "no atlas");
    if (!m || !m->model) return error_set(NEUV_ERR_INPUT, "no model");
    const neuv_mesh *mesh = api_atlas_input(a);
    if (!mesh) return error_set(NEUV_ERR_INPUT, "no mesh added to the atlas");
    neuv_apply_options def;
    if (!o) { neuv_apply_options_init(&def); o = &def; }
    neuv_status s = check_apply_options(m->model, o);
    if (s != NEUV_OK) return s;
    log_scope scope;
    log_scope_open(&scope, api_atlas_callbacks(a));
    struct neuv_unwrap_result *r = NULL;
    unwrap_model *kept = NULL;
    if (m->model->category) {
        neuv_unwrap_options u;
        neuv_unwrap_options_init(&u);
        u.threads = o->threads;
        u.use_cache = o->use_cache;
        u.allow_overlaps = o->allow_overlaps;
        /* The refinement and the packing are the model's unless the options
         * set them: on a shallow copy, so that the caller's model (which
         * other threads may be applying) is only read. */
        unwrap_model settings = *m->model;
        if (o->refine >= 0) settings.refine = o->refine;
        if (o->resolution != 0) settings.resolution = o->resolution;
        if (o->padding != -1) settings.padding = o->padding;
        s = unwrap_with_category(mesh, &settings, &u, o->finetune, o->shared_layer, o->keep_model, &r);
        /* The fine-tuned networks move into a surface model of this shape. */
        if (s == NEUV_OK && o->keep_model) {
            s = unwrap_model_from_result(r, &kept);
            if (s != NEUV_OK) { neuv_unwrap_result_free(r); r = NULL; }
        }
    } else {
        unwrap_apply_options ao = {o->threads, o->use_cache, o->check_inference, 0, o->lscm_baseline, 0, 0, NULL};
        s = unwrap_apply(mesh, m->model, &ao, &r);
    }
    log_scope_close(&scope);
    if (s != NEUV_OK) return s;
    return api_atlas_adopt(a, r, kept);
}

neuv_status neuv_train_category(const neuv_mesh *const *meshes, int n, const neuv_unwrap_options *o, int patch_iters,
                                const neuv_callbacks *cb, neuv_model **out, neuv_train_report *report)
{
    if (!out) return error_set(NEUV_ERR_INPUT, "neuv_train_category: no output pointer");
    *out = NULL;
    if (!meshes || n < 1) return error_set(NEUV_ERR_INPUT, "no shapes to train on");
    for (int i = 0; i < n; i++)
        if (!meshes[i]) return error_set(NEUV_ERR_INPUT, "shape %d is missing", i);
    if (patch_iters < 0) return error_set(NEUV_ERR_INPUT, "patch_iters must be 0 (default) or a step count");
    log_scope scope;
    log_scope_open(&scope, cb);
    unwrap_model *md = NULL;
    category_train_report rep;
    memset(&rep, 0, sizeof rep);
    neuv_status s = unwrap_category_train(meshes, n, o, patch_iters, &md, &rep);
    log_scope_close(&scope);
    if (s != NEUV_OK) return s;
    if (report) {
        memset(report, 0, sizeof *report);
        report->shapes = rep.shapes;
        report->faces = rep.faces;
        report->charts = rep.charts;
        report->patch_iterations = rep.patch_iterations;
        report->param_iterations = rep.param_iterations;
        report->patch_loss = rep.patch_loss;
        report->param_loss = rep.param_loss;
        report->patch_k = rep.patch_k;
        report->seconds_operators = rep.seconds_operators;
        report->seconds_patches = rep.seconds_patches;
        report->seconds_charts = rep.seconds_charts;
        report->seconds_param = rep.seconds_param;
        report->seconds = rep.seconds;
    }
    return wrap(md, out);
}
