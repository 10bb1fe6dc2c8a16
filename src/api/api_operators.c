/* Public geometry operators of a mesh (`neuv operators`): computed on a
 * cleaned copy, or read from the on-disk cache. */
#include <string.h>

#include "neuv/neuv.h"
#include "api/api_json.h"
#include "core/error.h"
#include "core/log.h"
#include "core/mem.h"
#include "core/timer.h"
#include "geometry/operator_cache.h"
#include "mesh/clean.h"

struct neuv_operators {
    operators ops;
    int faces;          /* of the cleaned mesh */
    double clean_seconds;
    char *cache_path;   /* NULL: the cache was off */
    int cache_hit;
};

void neuv_operator_options_init(neuv_operator_options *o)
{
    operators_params p = operators_default_params();
    memset(o, 0, sizeof *o);
    o->k = p.k;
    o->hks = p.n_hks;
    o->use_cache = 1;
}

static neuv_status compute(const neuv_mesh *mesh, const neuv_operator_options *o, neuv_operators *r)
{
    if (mesh->nf == 0) return error_set(NEUV_ERR_INPUT, "no faces: operators need a triangle mesh, not a point cloud");
    neuv_mesh *m = mesh_clone(mesh);
    if (!m) return error_nomem("the mesh");
    double t0 = now_seconds();
    mesh_clean_report rep;
    neuv_status s = mesh_clean(m, NULL, &rep);
    r->clean_seconds = now_seconds() - t0;
    r->faces = m->nf;
    operators_params p = operators_default_params();
    p.k = o->k;
    p.n_hks = o->hks;
    if (s == NEUV_OK) s = operators_get(m, &p, o->use_cache, &r->ops, &r->cache_path, &r->cache_hit);
    mesh_free(m);
    return s;
}

neuv_status neuv_operators_compute(const neuv_mesh *mesh, const neuv_operator_options *o, const neuv_callbacks *cb,
                                   neuv_operators **out)
{
    if (!out) return error_set(NEUV_ERR_INPUT, "neuv_operators_compute: no output pointer");
    *out = NULL;
    if (!mesh) return error_set(NEUV_ERR_INPUT, "neuv_operators_compute: no mesh");
    neuv_operator_options def;
    if (!o) { neuv_operator_options_init(&def); o = &def; }
    if (o->k < 1 || o->k > 4096) return error_set(NEUV_ERR_INPUT, "k must be between 1 and 4096, got %d", o->k);
    if (o->hks < 1 || o->hks > 1024) return error_set(NEUV_ERR_INPUT, "hks must be between 1 and 1024, got %d", o->hks);
    neuv_operators *r = mem_calloc(1, sizeof *r);
    if (!r) return error_nomem("the operators");
    log_scope scope;
    log_scope_open(&scope, cb);
    neuv_status s = compute(mesh, o, r);
    log_scope_close(&scope);
    if (s != NEUV_OK) { neuv_operators_free(r); return s; }
    *out = r;
    return NEUV_OK;
}

void neuv_operators_free(neuv_operators *r)
{
    if (!r) return;
    operators_free(&r->ops);
    mem_free(r->cache_path);
    mem_free(r);
}

void neuv_operators_get_info(const neuv_operators *r, neuv_operators_info *out)
{
    if (!out) return;
    memset(out, 0, sizeof *out);
    if (!r) return;
    const operators *o = &r->ops;
    out->vertices = o->nv;
    out->faces = r->faces;
    out->k = o->k;
    out->eigenvalues = o->evals;
    out->hks_count = o->n_hks;
    out->hks_times = o->hks_times;
    out->seconds_clean = r->clean_seconds;
    out->seconds_laplacian = o->seconds.laplacian;
    out->seconds_factor = o->seconds.factor;
    out->seconds_eigen = o->seconds.eigen;
    out->seconds_gradients = o->seconds.gradients;
    out->seconds_hks = o->seconds.hks;
    out->seconds_cache_load = o->seconds.cache_load;
    out->seconds_operators = o->seconds.total;
    out->cache_path = r->cache_path;
    out->cache_hit = r->cache_hit;
}

char *neuv_operators_json(const neuv_operators *r, const char *input_name, double load_seconds)
{
    if (!r) { error_set(NEUV_ERR_INPUT, "neuv_operators_json: no operators"); return NULL; }
    const operators *o = &r->ops;
    json_writer w;
    json_init(&w);
    json_begin_object(&w);
    json_key(&w, "version"); json_string(&w, neuv_version());
    json_key(&w, "input"); json_string(&w, input_name ? input_name : "");
    json_key(&w, "vertices"); json_int(&w, o->nv);
    json_key(&w, "faces"); json_int(&w, r->faces);
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
    json_key(&w, "load"); json_number(&w, load_seconds);
    json_key(&w, "clean"); json_number(&w, r->clean_seconds);
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
    return api_json_finish(&w);
}
