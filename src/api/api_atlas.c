/* The public atlas: meshes added from arrays, the pipeline's stages run
 * (and run again) one by one or all at once, the packed atlas given back
 * per mesh. Every call reports to the atlas's own callbacks. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "neuv/neuv.h"
#include "api/api_atlas.h"
#include "api/api_options.h"
#include "core/error.h"
#include "core/log.h"
#include "core/mem.h"
#include "mesh/mesh.h"
#include "metrics/uv_metrics.h"
#include "nn/nn.h"
#include "unwrap/unwrap_apply.h"
#include "unwrap/unwrap_internal.h"
#include "unwrap/unwrap_model.h"

_Static_assert((int)NEUV_SOURCE_COUNT == (int)CHART_SOURCE_COUNT, "public and internal chart sources differ");
_Static_assert(sizeof(neuv_metrics) == sizeof(uv_metrics), "public and internal metrics differ");

/* One added mesh's packed atlas, built on demand from the result. */
typedef struct atlas_output {
    int built;
    int vertex_count, index_count;
    int *xref;
    double *uvs;
    unsigned int *indices;
    int *face_chart;
} atlas_output;

struct neuv_atlas {
    neuv_callbacks callbacks;
    neuv_mesh *input;          /* the added meshes, one after the other */
    int n_meshes;
    int *vertex_start;         /* n_meshes + 1: first vertex of each mesh in input */
    int *face_start;           /* n_meshes + 1 */
    int stage;                 /* 0 none, 1 charts, 2 parameterized, 3 packed */
    neuv_unwrap_options opts;  /* the options of the stages run */
    struct neuv_unwrap_result *after_charts, *after_param; /* what a stage runs again from */
    float *features;           /* DiffusionNet features of after_charts' mesh */
    int feature_dim;
    struct neuv_unwrap_result *result; /* the packed atlas */
    unwrap_model *model;       /* generate with keep_model: the model, until taken */
    int *face_origin;          /* result->mesh->nf: input face of each cleaned face */
    int *corner_origin;        /* 3 per cleaned face: input vertex of each corner */
    atlas_output *outputs;     /* n_meshes */
};

static void clear_outputs(neuv_atlas *a)
{
    for (int i = 0; a->outputs && i < a->n_meshes; i++) {
        atlas_output *o = &a->outputs[i];
        mem_free(o->xref);
        mem_free(o->uvs);
        mem_free(o->indices);
        mem_free(o->face_chart);
        memset(o, 0, sizeof *o);
    }
    mem_free(a->face_origin);
    mem_free(a->corner_origin);
    a->face_origin = a->corner_origin = NULL;
}

/* Discards the stages from `stage` on (1: everything). */
static void discard_from(neuv_atlas *a, int stage)
{
    clear_outputs(a);
    neuv_unwrap_result_free(a->result);
    a->result = NULL;
    unwrap_model_free(a->model);
    a->model = NULL;
    if (stage <= 2) {
        neuv_unwrap_result_free(a->after_param);
        a->after_param = NULL;
    }
    if (stage <= 1) {
        neuv_unwrap_result_free(a->after_charts);
        a->after_charts = NULL;
        mem_free(a->features);
        a->features = NULL;
        a->feature_dim = 0;
    }
    if (a->stage >= stage) a->stage = stage - 1;
}

neuv_status neuv_atlas_create(neuv_atlas **out)
{
    if (!out) return error_set(NEUV_ERR_INPUT, "neuv_atlas_create: no output pointer");
    *out = NULL;
    neuv_atlas *a = mem_calloc(1, sizeof *a);
    if (!a) return error_nomem("the atlas");
    neuv_unwrap_options_init(&a->opts);
    *out = a;
    return NEUV_OK;
}

void neuv_atlas_destroy(neuv_atlas *a)
{
    if (!a) return;
    discard_from(a, 1);
    mem_free(a->outputs);
    mesh_free(a->input);
    mem_free(a->vertex_start);
    mem_free(a->face_start);
    mem_free(a);
}

void neuv_atlas_set_callbacks(neuv_atlas *a, const neuv_callbacks *cb)
{
    if (!a) return;
    if (cb) a->callbacks = *cb;
    else memset(&a->callbacks, 0, sizeof a->callbacks);
}

neuv_status neuv_atlas_add_loaded_mesh(neuv_atlas *a, const neuv_mesh *m)
{
    if (!a || !m) return error_set(NEUV_ERR_INPUT, "neuv_atlas_add_loaded_mesh: no atlas or no mesh");
    if (m->nf <= 0) return error_set(NEUV_ERR_INPUT, "the mesh has no faces");
    int nv0 = a->input ? a->input->nv : 0, nf0 = a->input ? a->input->nf : 0;
    if ((long long)nv0 + m->nv > INT32_MAX / 3 || (long long)nf0 + m->nf > INT32_MAX / 3)
        return error_set(NEUV_ERR_INPUT, "too many vertices or faces for one atlas");
    /* The UVs of the added meshes are not carried: the atlas makes its own. */
    neuv_mesh *joined = mesh_create(nv0 + m->nv, nf0 + m->nf, 0);
    int *vs = mem_realloc(a->vertex_start, sizeof(int) * (size_t)(a->n_meshes + 2));
    if (vs) a->vertex_start = vs;
    int *fs = mem_realloc(a->face_start, sizeof(int) * (size_t)(a->n_meshes + 2));
    if (fs) a->face_start = fs;
    atlas_output *outs = mem_realloc(a->outputs, sizeof *outs * (size_t)(a->n_meshes + 1));
    if (outs) a->outputs = outs;
    if (!joined || !vs || !fs || !outs) { mesh_free(joined); return error_nomem("the mesh"); }
    discard_from(a, 1);
    if (a->input) {
        memcpy(joined->pos, a->input->pos, sizeof(double) * 3 * (size_t)nv0);
        memcpy(joined->tri, a->input->tri, sizeof(int) * 3 * (size_t)nf0);
    }
    memcpy(joined->pos + 3 * (size_t)nv0, m->pos, sizeof(double) * 3 * (size_t)m->nv);
    for (size_t c = 0; c < 3 * (size_t)m->nf; c++) joined->tri[3 * (size_t)nf0 + c] = m->tri[c] + nv0;
    if (mesh_join_marks(joined, a->input, m) != NEUV_OK) { mesh_free(joined); return error_nomem("the mesh"); }
    mesh_free(a->input);
    a->input = joined;
    a->vertex_start[a->n_meshes] = nv0;
    a->face_start[a->n_meshes] = nf0;
    a->n_meshes++;
    a->vertex_start[a->n_meshes] = joined->nv;
    a->face_start[a->n_meshes] = joined->nf;
    memset(&a->outputs[a->n_meshes - 1], 0, sizeof *a->outputs);
    return NEUV_OK;
}

neuv_status neuv_atlas_add_mesh(neuv_atlas *a, const neuv_mesh_decl *d)
{
    if (!a) return error_set(NEUV_ERR_INPUT, "neuv_atlas_add_mesh: no atlas");
    neuv_mesh *m = NULL;
    neuv_status s = neuv_mesh_create(d, &m);
    if (s != NEUV_OK) return s;
    s = neuv_atlas_add_loaded_mesh(a, m);
    mesh_free(m);
    return s;
}

int neuv_atlas_mesh_count(const neuv_atlas *a) { return a ? a->n_meshes : 0; }
int neuv_atlas_stage(const neuv_atlas *a) { return a ? a->stage : 0; }

/* The result of the last stage run (NULL before stage 1). */
static const struct neuv_unwrap_result *latest(const neuv_atlas *a)
{
    return a->stage == 3 ? a->result : a->stage == 2 ? a->after_param : a->stage == 1 ? a->after_charts : NULL;
}

int neuv_atlas_chart_count(const neuv_atlas *a)
{
    const struct neuv_unwrap_result *r = a ? latest(a) : NULL;
    return r ? r->n_charts : 0;
}

static neuv_status need_mesh(const neuv_atlas *a)
{
    if (!a) return error_set(NEUV_ERR_INPUT, "no atlas");
    if (a->n_meshes == 0) return error_set(NEUV_ERR_INPUT, "no mesh added to the atlas");
    return NEUV_OK;
}

neuv_status neuv_atlas_compute_charts(neuv_atlas *a, const neuv_chart_options *o)
{
    neuv_status s = need_mesh(a);
    if (s != NEUV_OK) return s;
    neuv_chart_options def;
    if (!o) { neuv_chart_options_init(&def); o = &def; }
    discard_from(a, 1);
    neuv_unwrap_options u = a->opts;
    api_options_set_charts(&u, o);
    log_scope scope;
    log_scope_open(&scope, &a->callbacks);
    struct neuv_unwrap_result *r = NULL;
    s = unwrap_result_new(&u, &r);
    unwrap_plan plan = {NULL, 0, 0, NULL};
    if (s == NEUV_OK) s = unwrap_stage_charts(r, a->input, &plan, &a->features, &a->feature_dim);
    log_scope_close(&scope);
    if (s != NEUV_OK) { neuv_unwrap_result_free(r); return s; }
    a->opts = u;
    a->after_charts = r;
    a->stage = 1;
    return NEUV_OK;
}

neuv_status neuv_atlas_parameterize(neuv_atlas *a, const neuv_param_options *o)
{
    neuv_status s = need_mesh(a);
    if (s != NEUV_OK) return s;
    if (!a->after_charts) return error_set(NEUV_ERR_INPUT, "compute the charts first (neuv_atlas_compute_charts)");
    neuv_param_options def;
    if (!o) { neuv_param_options_init(&def); o = &def; }
    discard_from(a, 2);
    neuv_unwrap_options u = a->opts;
    api_options_set_param(&u, o);
    log_scope scope;
    log_scope_open(&scope, &a->callbacks);
    struct neuv_unwrap_result *r = NULL;
    s = unwrap_result_clone(a->after_charts, &r);
    if (s == NEUV_OK) {
        r->opts = u;
        nn_set_threads(u.threads);
        unwrap_plan plan = {NULL, 0, 0, NULL};
        s = unwrap_stage_param(r, &plan, a->features, a->feature_dim);
    }
    log_scope_close(&scope);
    if (s != NEUV_OK) { neuv_unwrap_result_free(r); return s; }
    a->opts = u;
    a->after_param = r;
    a->stage = 2;
    return NEUV_OK;
}

neuv_status neuv_atlas_pack(neuv_atlas *a, const neuv_pack_options *o)
{
    neuv_status s = need_mesh(a);
    if (s != NEUV_OK) return s;
    if (!a->after_param) return error_set(NEUV_ERR_INPUT, "parameterize the charts first (neuv_atlas_parameterize)");
    neuv_pack_options def;
    if (!o) { neuv_pack_options_init(&def); o = &def; }
    neuv_unwrap_options u = a->opts;
    api_options_set_pack(&u, o);
    struct neuv_unwrap_result *check = NULL;
    if ((s = unwrap_result_new(&u, &check)) != NEUV_OK) return s; /* resolution and padding checked */
    neuv_unwrap_result_free(check);
    discard_from(a, 3);
    log_scope scope;
    log_scope_open(&scope, &a->callbacks);
    struct neuv_unwrap_result *r = NULL;
    s = unwrap_result_clone(a->after_param, &r);
    if (s == NEUV_OK) {
        r->opts = u;
        nn_set_threads(u.threads);
        unwrap_plan plan = {NULL, 0, 0, NULL};
        s = unwrap_stage_pack(r, &plan);
    }
    log_scope_close(&scope);
    if (s != NEUV_OK) { neuv_unwrap_result_free(r); return s; }
    a->opts = u;
    a->result = r;
    a->stage = 3;
    return NEUV_OK;
}

/* The whole pipeline on one result (the same computation as the stages one
 * by one), keeping copies after stages 1 and 2 so that they can run again. */
static neuv_status generate_staged(neuv_atlas *a, const neuv_unwrap_options *o)
{
    struct neuv_unwrap_result *r = NULL;
    neuv_status s = unwrap_result_new(o, &r);
    unwrap_plan plan = {NULL, o->keep_model, 0, NULL};
    if (s == NEUV_OK) s = unwrap_stage_charts(r, a->input, &plan, &a->features, &a->feature_dim);
    if (s == NEUV_OK) s = unwrap_result_clone(r, &a->after_charts);
    if (s == NEUV_OK) s = unwrap_stage_param(r, &plan, a->features, a->feature_dim);
    if (s == NEUV_OK) s = unwrap_result_clone(r, &a->after_param);
    if (s == NEUV_OK) s = unwrap_stage_pack(r, &plan);
    if (s == NEUV_OK && o->keep_model) s = unwrap_model_from_result(r, &a->model);
    if (s != NEUV_OK) { neuv_unwrap_result_free(r); return s; }
    a->result = r;
    return NEUV_OK;
}

neuv_status neuv_atlas_generate(neuv_atlas *a, const neuv_unwrap_options *o)
{
    neuv_status s = need_mesh(a);
    if (s != NEUV_OK) return s;
    neuv_unwrap_options def;
    if (!o) { neuv_unwrap_options_init(&def); o = &def; }
    if (o->train_faces < 0) return error_set(NEUV_ERR_INPUT, "train_faces must be 0 or a face count");
    discard_from(a, 1);
    log_scope scope;
    log_scope_open(&scope, &a->callbacks);
    if (o->train_faces > 0 && a->input->nf > o->train_faces)
        s = unwrap_budgeted(a->input, o, o->train_faces, o->keep_model ? &a->model : NULL, &a->result);
    else
        s = generate_staged(a, o);
    log_scope_close(&scope);
    if (s != NEUV_OK) { discard_from(a, 1); return s; }
    a->opts = *o;
    a->stage = 3;
    return NEUV_OK;
}

neuv_status api_atlas_adopt(neuv_atlas *a, struct neuv_unwrap_result *r, struct unwrap_model *model)
{
    discard_from(a, 1);
    a->result = r;
    a->model = model;
    a->opts = r->opts;
    a->stage = 3;
    return NEUV_OK;
}

const neuv_mesh *api_atlas_input(const neuv_atlas *a) { return a ? a->input : NULL; }
const neuv_callbacks *api_atlas_callbacks(const neuv_atlas *a) { return &a->callbacks; }

static neuv_status need_result(const neuv_atlas *a)
{
    if (!a) return error_set(NEUV_ERR_INPUT, "no atlas");
    if (a->stage < 3 || !a->result) return error_set(NEUV_ERR_INPUT, "the atlas is not packed yet");
    return NEUV_OK;
}

const neuv_mesh *neuv_atlas_mesh(const neuv_atlas *a) { return need_result(a) == NEUV_OK ? a->result->mesh : NULL; }

neuv_status neuv_atlas_get_metrics(const neuv_atlas *a, neuv_metrics *out)
{
    neuv_status s = need_result(a);
    if (s != NEUV_OK) return s;
    memcpy(out, &a->result->metrics, sizeof *out);
    return NEUV_OK;
}

/* Position equality of two corners, as cleaning moves no vertex. */
static int same_point(const double *p, const double *q) { return p[0] == q[0] && p[1] == q[1] && p[2] == q[2]; }

/* Input face and input vertex of every face and corner of the cleaned mesh:
 * cleaning keeps the faces it does not drop in their order and moves no
 * vertex (it welds, splits and reorients), so each cleaned face is the next
 * input face with the same three points. */
static neuv_status find_origins(neuv_atlas *a)
{
    if (a->face_origin) return NEUV_OK;
    const neuv_mesh *in = a->input, *m = a->result->mesh;
    a->face_origin = mem_alloc(sizeof(int) * (size_t)m->nf);
    a->corner_origin = mem_alloc(sizeof(int) * 3 * (size_t)m->nf);
    if (!a->face_origin || !a->corner_origin) { clear_outputs(a); return error_nomem("the output"); }
    int i = 0;
    for (int f = 0; f < m->nf; f++) {
        int found = 0;
        for (; i < in->nf && !found; i++) {
            int match[3] = {-1, -1, -1}, all = 1;
            for (int k = 0; k < 3 && all; k++) {
                const double *p = m->pos + 3 * (size_t)m->tri[3 * f + k];
                for (int j = 0; j < 3; j++)
                    if (same_point(p, in->pos + 3 * (size_t)in->tri[3 * i + j])) { match[k] = in->tri[3 * i + j]; break; }
                all = match[k] >= 0;
            }
            if (!all) continue;
            a->face_origin[f] = i;
            for (int k = 0; k < 3; k++) a->corner_origin[3 * f + k] = match[k];
            found = 1;
        }
        if (!found) {
            clear_outputs(a);
            return error_set(NEUV_ERR_INTERNAL, "output face %d matches no input face", f);
        }
    }
    return NEUV_OK;
}

neuv_status api_atlas_origins(neuv_atlas *a, int index, api_atlas_origin *out)
{
    neuv_status s = need_result(a);
    if (s != NEUV_OK) return s;
    if (index < 0 || index >= a->n_meshes)
        return error_set(NEUV_ERR_INPUT, "mesh %d: the atlas has %d mesh%s", index, a->n_meshes,
                         a->n_meshes == 1 ? "" : "es");
    if ((s = find_origins(a)) != NEUV_OK) return s;
    out->packed = a->result->mesh;
    out->face_chart = a->result->face_chart;
    out->face_origin = a->face_origin;
    out->corner_origin = a->corner_origin;
    out->input = a->input;
    out->v0 = a->vertex_start[index];
    out->v1 = a->vertex_start[index + 1];
    out->f0 = a->face_start[index];
    out->f1 = a->face_start[index + 1];
    return NEUV_OK;
}

static int compare_u64(const void *x, const void *y)
{
    uint64_t a = *(const uint64_t *)x, b = *(const uint64_t *)y;
    return a < b ? -1 : a > b;
}

static neuv_status build_output(neuv_atlas *a, int index)
{
    atlas_output *o = &a->outputs[index];
    if (o->built) return NEUV_OK;
    neuv_status s = find_origins(a);
    if (s != NEUV_OK) return s;
    const neuv_mesh *m = a->result->mesh;
    int f0 = a->face_start[index], f1 = a->face_start[index + 1];
    int nf = 0;
    for (int f = 0; f < m->nf; f++) nf += a->face_origin[f] >= f0 && a->face_origin[f] < f1;
    /* Output vertices: the distinct (UV index, cleaned vertex) pairs of the
     * mesh's corners, in the order of their keys. */
    uint64_t *keys = mem_alloc(sizeof *keys * (size_t)(3 * nf > 0 ? 3 * nf : 1));
    o->indices = mem_alloc(sizeof *o->indices * (size_t)(3 * nf > 0 ? 3 * nf : 1));
    o->face_chart = mem_alloc(sizeof(int) * (size_t)(nf > 0 ? nf : 1));
    if (!keys || !o->indices || !o->face_chart) { mem_free(keys); s = error_nomem("the output"); goto fail; }
    int n = 0;
    for (int f = 0; f < m->nf; f++) {
        if (a->face_origin[f] < f0 || a->face_origin[f] >= f1) continue;
        for (int k = 0; k < 3; k++)
            keys[n++] = (uint64_t)m->tri_uv[3 * f + k] << 32 | (uint32_t)(3 * f + k);
    }
    /* Sorted by UV index; corners of one UV index on different vertices
     * (never made by the pipeline, but possible) stay apart below. */
    qsort(keys, (size_t)n, sizeof *keys, compare_u64);
    int *corner_vertex = mem_alloc(sizeof(int) * (size_t)(n > 0 ? n : 1));
    int *vx = mem_alloc(sizeof(int) * (size_t)(n > 0 ? n : 1));
    double *vuv = mem_alloc(sizeof(double) * 2 * (size_t)(n > 0 ? n : 1));
    int *corner_out = mem_alloc(sizeof(int) * 3 * (size_t)(m->nf > 0 ? m->nf : 1));
    if (!corner_vertex || !vx || !vuv || !corner_out) {
        mem_free(keys); mem_free(corner_vertex); mem_free(vx); mem_free(vuv); mem_free(corner_out);
        s = error_nomem("the output");
        goto fail;
    }
    int nv = 0;
    for (int i = 0; i < n; i++) {
        int corner = (int)(keys[i] & 0xffffffffu), t = (int)(keys[i] >> 32);
        int v = m->tri[corner];
        int same = -1;
        for (int j = nv - 1; j >= 0 && (int)(keys[corner_vertex[j]] >> 32) == t; j--)
            if (m->tri[(int)(keys[corner_vertex[j]] & 0xffffffffu)] == v) { same = j; break; }
        if (same < 0) {
            same = nv++;
            corner_vertex[same] = i;
            vx[same] = a->corner_origin[corner] - a->vertex_start[index];
            vuv[2 * same] = m->uv[2 * t];
            vuv[2 * same + 1] = m->uv[2 * t + 1];
        }
        corner_out[corner] = same;
    }
    int k = 0;
    for (int f = 0; f < m->nf; f++) {
        if (a->face_origin[f] < f0 || a->face_origin[f] >= f1) continue;
        o->face_chart[k / 3] = a->result->face_chart[f];
        for (int c = 0; c < 3; c++) o->indices[k++] = (unsigned int)corner_out[3 * f + c];
    }
    mem_free(keys);
    mem_free(corner_vertex);
    mem_free(corner_out);
    o->xref = vx;
    o->uvs = vuv;
    o->vertex_count = nv;
    o->index_count = 3 * nf;
    o->built = 1;
    return NEUV_OK;
fail:
    mem_free(o->indices);
    mem_free(o->face_chart);
    memset(o, 0, sizeof *o);
    return s;
}

neuv_status neuv_atlas_get_output(neuv_atlas *a, int index, neuv_atlas_output *out)
{
    neuv_status s = need_result(a);
    if (s != NEUV_OK) return s;
    if (!out) return error_set(NEUV_ERR_INPUT, "neuv_atlas_get_output: no output struct");
    if (index < 0 || index >= a->n_meshes)
        return error_set(NEUV_ERR_INPUT, "mesh %d: the atlas has %d mesh%s", index, a->n_meshes,
                         a->n_meshes == 1 ? "" : "es");
    if ((s = build_output(a, index)) != NEUV_OK) return s;
    const atlas_output *o = &a->outputs[index];
    out->vertex_count = o->vertex_count;
    out->xref = o->xref;
    out->uvs = o->uvs;
    out->index_count = o->index_count;
    out->indices = o->indices;
    out->face_chart = o->face_chart;
    return NEUV_OK;
}

const char *neuv_chart_source_name(neuv_chart_source s)
{
    return s >= 0 && s < NEUV_SOURCE_COUNT ? chart_source_name((chart_source)s) : "unknown";
}

neuv_status neuv_atlas_get_chart(const neuv_atlas *a, int chart, neuv_chart_info *out)
{
    if (!a || !out) return error_set(NEUV_ERR_INPUT, "neuv_atlas_get_chart: no atlas or no output");
    const struct neuv_unwrap_result *r = a->stage >= 2 ? latest(a) : NULL;
    if (!r || !r->chart_source) return error_set(NEUV_ERR_INPUT, "the atlas has no parameterized charts yet");
    if (chart < 0 || chart >= r->n_charts)
        return error_set(NEUV_ERR_INPUT, "chart %d: the atlas has %d charts", chart, r->n_charts);
    unwrap_chart_figures *cf = unwrap_chart_figures_compute(r);
    if (!cf) return error_nomem("chart figures");
    out->faces = cf[chart].faces;
    out->area = cf[chart].area;
    out->source = (neuv_chart_source)r->chart_source[chart];
    out->network_qce = r->chart_net_qce[chart];
    out->qce = cf[chart].qce_den > 0 ? cf[chart].qce_num / cf[chart].qce_den : NAN;
    mem_free(cf);
    return NEUV_OK;
}

neuv_status neuv_atlas_get_report(const neuv_atlas *a, neuv_report *out)
{
    if (!a || !out) return error_set(NEUV_ERR_INPUT, "neuv_atlas_get_report: no atlas or no output");
    memset(out, 0, sizeof *out);
    out->network_qce_mean = NAN;
    const struct neuv_unwrap_result *r = latest(a);
    if (!r) return error_set(NEUV_ERR_INPUT, "no stage has run on the atlas");
    out->input_vertices = r->input_vertices;
    out->input_faces = r->input_faces;
    out->vertices = r->mesh->nv;
    out->faces = r->mesh->nf;
    out->charts = r->n_charts;
    out->repairs = r->n_repairs;
    out->seconds_clean = r->seconds[STAGE_CLEAN];
    out->seconds_operators = r->seconds[STAGE_OPERATORS];
    out->seconds_patches = r->seconds[STAGE_PATCHES];
    out->seconds_param = r->seconds[STAGE_PARAM];
    out->seconds_repair = r->seconds[STAGE_REPAIR];
    out->seconds_pack = r->seconds[STAGE_PACK];
    out->seconds_metrics = r->seconds[STAGE_METRICS];
    out->seconds_total = r->total_seconds;
    out->from_model = r->model.used;
    out->moved_charts = r->model.moved_charts;
    out->trained_on_copy = r->model.trained_on_copy;
    out->train_faces = r->model.train_faces;
    out->seam_edges = r->seam_edges;
    out->seams_crossed = r->seam_crossed;
    out->hard_edges_not_kept = r->hard_edges_not_kept;
    out->polygons = r->polygons;
    out->polygons_split = r->polygons_split;
    if (a->stage == 3) memcpy(&out->metrics, &r->metrics, sizeof out->metrics);
    if (a->stage >= 2 && r->chart_source) {
        unwrap_chart_figures *cf = unwrap_chart_figures_compute(r);
        if (!cf) return error_nomem("chart figures");
        unwrap_provenance pv;
        unwrap_provenance_compute(r, cf, &pv);
        mem_free(cf);
        for (int k = 0; k < NEUV_SOURCE_COUNT; k++) out->charts_by_source[k] = pv.count[k];
        out->network_area_fraction = pv.network_area_fraction;
        out->network_qce_mean = pv.network_qce_mean;
    }
    return NEUV_OK;
}

char *neuv_atlas_report_json(const neuv_atlas *a, const char *input_name, double load_seconds,
                             double export_seconds)
{
    if (need_result(a) != NEUV_OK) return NULL;
    char *json = neuv_unwrap_report_json(a->result, input_name, load_seconds, export_seconds);
    if (!json) error_nomem("the report");
    return json;
}

neuv_status api_atlas_take_model(neuv_atlas *a, unwrap_model **out)
{
    *out = NULL;
    if (!a) return error_set(NEUV_ERR_INPUT, "no atlas");
    if (!a->model)
        return error_set(NEUV_ERR_INPUT, "the atlas kept no model: generate with keep_model = 1, or apply a category "
                                         "model with finetune and keep_model = 1 (once per model)");
    *out = a->model;
    a->model = NULL;
    return NEUV_OK;
}

/* The older one-call interface, on an atlas. */
neuv_status neuv_unwrap(const neuv_mesh *mesh, const neuv_unwrap_options *opts, neuv_unwrap_result **out)
{
    if (!out) return error_set(NEUV_ERR_INPUT, "neuv_unwrap: no output pointer");
    *out = NULL;
    if (!mesh) return error_set(NEUV_ERR_INPUT, "neuv_unwrap: no mesh");
    return unwrap_train(mesh, opts, 0, out);
}
