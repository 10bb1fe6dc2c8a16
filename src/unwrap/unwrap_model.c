/* Saving and loading a whole unwrap as one checkpoint (unwrap_model.h). */
#include "unwrap/unwrap_model.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/json_writer.h"
#include "core/mem.h"
#include "core/rng.h"
#include "models/param_output_solve.h"
#include "nn/checkpoint.h"
#include "unwrap/unwrap_internal.h"

#define FORMAT_NAME "neuv-unwrap-model"
/* Float32 holds integers exactly up to 2^24: the largest index a file may carry. */
#define MAX_EXACT_INT 16777216

void unwrap_model_free(unwrap_model *model)
{
    if (!model) return;
    mesh_free(model->source);
    mem_free(model->face_chart);
    mem_free(model->face_label);
    mem_free(model->xf);
    mem_free(model->chart_net);
    mem_free(model->chart_mirrored);
    mem_free(model->chart_tried);
    param_net_model_free(model->param);
    if (model->patchnet) patchnet_model_free(model->patchnet);
    mem_free(model->patchnet);
    mem_free(model);
}

neuv_status unwrap_model_from_result(struct neuv_unwrap_result *r, unwrap_model **out)
{
    *out = NULL;
    if (!r->chart_net || !r->transforms)
        return error_set(NEUV_ERR_INPUT, "this unwrap kept no model to save");
    if (r->mesh->nv >= MAX_EXACT_INT || r->mesh->nuv >= MAX_EXACT_INT)
        return error_set(NEUV_ERR_INPUT, "the mesh is too large to save as a model (%d vertices)", r->mesh->nv);
    unwrap_model *m = mem_calloc(1, sizeof *m);
    if (!m) return error_nomem("the model");
    m->method = r->opts.method;
    m->preset = r->opts.preset;
    m->seed = r->opts.seed;
    m->refine = r->opts.method == NEUV_METHOD_NEURAL ? r->opts.refine : 0;
    m->resolution = r->opts.resolution;
    m->padding = r->opts.padding;
    m->n_charts = r->n_charts;
    int nf = r->mesh->nf, nc = r->n_charts;
    m->source = mesh_clone(r->mesh);
    m->face_chart = mem_alloc(sizeof(int) * (size_t)nf);
    m->xf = mem_alloc(sizeof *m->xf * (size_t)nc);
    m->chart_net = mem_alloc(sizeof(int) * (size_t)nc);
    m->chart_mirrored = mem_alloc(sizeof(int) * (size_t)nc);
    if (!m->source || !m->face_chart || !m->xf || !m->chart_net || !m->chart_mirrored) {
        unwrap_model_free(m);
        return error_nomem("the model");
    }
    memcpy(m->face_chart, r->face_chart, sizeof(int) * (size_t)nf);
    memcpy(m->xf, r->transforms, sizeof *m->xf * (size_t)nc);
    memcpy(m->chart_net, r->chart_net, sizeof(int) * (size_t)nc);
    memcpy(m->chart_mirrored, r->chart_mirrored, sizeof(int) * (size_t)nc);
    if (r->chart_tried) {
        m->chart_tried = mem_alloc(sizeof(int) * (size_t)nc);
        if (!m->chart_tried) { unwrap_model_free(m); return error_nomem("the model"); }
        memcpy(m->chart_tried, r->chart_tried, sizeof(int) * (size_t)nc);
    }
    double lo[3], hi[3];
    mesh_bounding_box(m->source, lo, hi);
    for (int q = 0; q < 3; q++) m->norm[q] = 0.5 * (lo[q] + hi[q]);
    m->norm[3] = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                      (hi[2] - lo[2]) * (hi[2] - lo[2]));
    m->norm[4] = mesh_total_area(m->source);
    /* The networks move over; the result keeps only its atlas. */
    m->face_label = r->face_label;
    r->face_label = NULL;
    m->param = r->param;
    r->param = NULL;
    m->patchnet = r->patchnet;
    r->patchnet = NULL;
    *out = m;
    return NEUV_OK;
}

/* ---- writing ----------------------------------------------------------- */

typedef struct tensor_list {
    int n, cap;
    nn_tensor *t;           /* views (rows, cols, data) */
    const char **name;
    float **owned;          /* buffers to free after writing */
    int n_owned;
} tensor_list;

static int list_push(tensor_list *l, const char *name, int rows, int cols, float *data, int owned)
{
    if (l->n == l->cap) {
        int cap = l->cap ? 2 * l->cap : 64;
        nn_tensor *t = mem_realloc(l->t, sizeof *t * (size_t)cap);
        if (t) l->t = t;
        const char **nm = mem_realloc(l->name, sizeof *nm * (size_t)cap);
        if (nm) l->name = nm;
        float **ow = mem_realloc(l->owned, sizeof *ow * (size_t)cap);
        if (ow) l->owned = ow;
        if (!t || !nm || !ow) { if (owned) mem_free(data); return -1; }
        l->cap = cap;
    }
    memset(&l->t[l->n], 0, sizeof l->t[l->n]);
    l->t[l->n].rows = rows;
    l->t[l->n].cols = cols;
    l->t[l->n].data = data;
    l->name[l->n++] = name;
    if (owned) l->owned[l->n_owned++] = data;
    return 0;
}

/* A rows by cols block of doubles as rows by 2*cols float32 slots, bit for bit. */
static int push_doubles(tensor_list *l, const char *name, int rows, int cols, const double *x)
{
    float *buf = mem_alloc(sizeof(double) * (size_t)rows * (size_t)cols);
    if (!buf) return -1;
    memcpy(buf, x, sizeof(double) * (size_t)rows * (size_t)cols);
    return list_push(l, name, rows, 2 * cols, buf, 1);
}

static int push_ints(tensor_list *l, const char *name, int rows, int cols, const int *x)
{
    size_t n = (size_t)rows * (size_t)cols;
    float *buf = mem_alloc(sizeof(float) * n);
    if (!buf) return -1;
    for (size_t i = 0; i < n; i++) buf[i] = (float)x[i];
    return list_push(l, name, rows, cols, buf, 1);
}

static int push_params(tensor_list *l, const nn_params *ps)
{
    for (int i = 0; i < ps->n; i++)
        if (list_push(l, ps->t[i]->name, ps->t[i]->rows, ps->t[i]->cols, ps->t[i]->data, 0)) return -1;
    return 0;
}

static const char *method_key(neuv_method m)
{
    return m == NEUV_METHOD_LSCM ? "lscm" : m == NEUV_METHOD_HARMONIC ? "harmonic" : "neural";
}

static char *header_json(const unwrap_model *m)
{
    json_writer w;
    json_init(&w);
    json_begin_object(&w);
    json_key(&w, "format"); json_string(&w, FORMAT_NAME);
    json_key(&w, "model_version"); json_int(&w, UNWRAP_MODEL_VERSION);
    json_key(&w, "neuv_version"); json_string(&w, neuv_version());
    json_key(&w, "kind"); json_string(&w, m->category ? "category" : "surface");
    json_key(&w, "method"); json_string(&w, method_key(m->method));
    json_key(&w, "preset"); json_string(&w, m->preset == NEUV_PRESET_PAPER ? "paper" : "fast");
    json_key(&w, "seed"); json_int(&w, (long long)m->seed);
    json_key(&w, "refine"); json_int(&w, m->refine);
    json_key(&w, "resolution"); json_int(&w, m->resolution);
    json_key(&w, "padding"); json_int(&w, m->padding);
    if (m->category) {
        json_key(&w, "category_shapes"); json_int(&w, m->category_shapes);
        json_key(&w, "charts_auto"); json_int(&w, m->charts_auto);
        json_key(&w, "max_distortion"); json_number(&w, m->max_distortion);
    } else {
        json_key(&w, "charts"); json_int(&w, m->n_charts);
        json_key(&w, "source_vertices"); json_int(&w, m->source->nv);
        json_key(&w, "source_faces"); json_int(&w, m->source->nf);
        json_key(&w, "source_uvs"); json_int(&w, m->source->nuv);
        json_key(&w, "source_labels"); json_int(&w, m->face_label != NULL);
    }
    json_key(&w, "param"); json_int(&w, m->param != NULL);
    if (m->param) {
        const param_net_model *p = m->param;
        json_key(&w, "param_charts"); json_int(&w, m->category ? 0 : p->n_charts);
        json_key(&w, "param_psi_norm"); json_int(&w, p->psi_shift != NULL);
        json_key(&w, "param_psi_dim"); json_int(&w, p->psi_dim);
        json_key(&w, "param_width"); json_int(&w, p->f.width);
        json_key(&w, "param_depth"); json_int(&w, p->f.depth);
        json_key(&w, "param_heads"); json_int(&w, p->heads && p->n_charts > 0 ? 1 : 0);
        json_key(&w, "param_head_fourier"); json_int(&w, p->f.fourier);
        json_key(&w, "param_uv_gain"); json_int(&w, p->uv_gain && p->n_charts > 0 ? 1 : 0);
        json_key(&w, "param_slope"); json_number(&w, p->f.slope);
    }
    json_key(&w, "patchnet"); json_int(&w, m->patchnet != NULL);
    if (m->patchnet) {
        const patchnet_model *p = m->patchnet;
        json_key(&w, "patchnet_k"); json_int(&w, p->k);
        json_key(&w, "patchnet_k_eig"); json_int(&w, p->k_eig);
        json_key(&w, "patchnet_in_dim"); json_int(&w, p->in_dim);
        json_key(&w, "patchnet_features"); json_string(&w, diffusion_net_features_name(p->features));
        json_key(&w, "patchnet_blocks"); json_int(&w, p->net.cfg.blocks);
        json_key(&w, "patchnet_width"); json_int(&w, p->net.cfg.width);
        json_key(&w, "patchnet_seed"); json_int(&w, (long long)p->net.cfg.seed);
    }
    json_end_object(&w);
    if (w.failed) { json_free(&w); return NULL; }
    return w.buf;
}

/* The source surface, its charts and the per-chart frames of a surface model. */
static int push_surface(tensor_list *l, const unwrap_model *m)
{
    const neuv_mesh *s = m->source;
    int nc = m->n_charts, bad = 0;
    bad |= push_doubles(l, "source.pos", s->nv, 3, s->pos);
    bad |= push_ints(l, "source.tri", s->nf, 3, s->tri);
    bad |= push_doubles(l, "source.uv", s->nuv, 2, s->uv);
    bad |= push_ints(l, "source.tri_uv", s->nf, 3, s->tri_uv);
    bad |= push_ints(l, "source.chart", s->nf, 1, m->face_chart);
    if (m->face_label) bad |= push_ints(l, "source.label", s->nf, 1, m->face_label);
    bad |= push_doubles(l, "source.norm", 1, 5, m->norm);
    double *xf = mem_alloc(sizeof(double) * 4 * (size_t)nc);
    int *map = mem_alloc(sizeof(int) * 2 * (size_t)nc);
    if (xf && map) {
        for (int c = 0; c < nc; c++) {
            xf[4 * c] = m->xf[c].scale; xf[4 * c + 1] = m->xf[c].angle;
            xf[4 * c + 2] = m->xf[c].tx; xf[4 * c + 3] = m->xf[c].ty;
            map[2 * c] = m->chart_net[c];
            map[2 * c + 1] = m->chart_mirrored[c];
        }
        bad |= push_doubles(l, "charts.xf", nc, 4, xf);
        bad |= push_ints(l, "charts.map", nc, 2, map);
    } else bad = 1;
    mem_free(xf);
    mem_free(map);
    if (m->param) {
        const param_net_model *p = m->param;
        double *frame = mem_alloc(sizeof(double) * 13 * (size_t)p->n_charts);
        if (frame) {
            for (int c = 0; c < p->n_charts; c++) {
                memcpy(frame + 13 * c, p->center + 3 * c, 3 * sizeof(double));
                frame[13 * c + 3] = p->scale[c];
                memcpy(frame + 13 * c + 4, p->rot + 9 * c, 9 * sizeof(double));
            }
            bad |= push_doubles(l, "param.frame", p->n_charts, 13, frame);
            mem_free(frame);
        } else bad = 1;
        bad |= push_ints(l, "param.mirror", p->n_charts, 1, p->mirror);
        if (!bad) bad |= list_push(l, "param.psi", p->n_charts, p->psi_dim, p->psi, 0);
        if (!bad && p->heads)
            bad |= list_push(l, "param.heads", p->n_charts, param_head_size(&p->f), p->heads, 0);
        if (!bad && p->uv_gain) bad |= push_doubles(l, "param.uv_gain", p->n_charts, 1, p->uv_gain);
    }
    return bad;
}

neuv_status unwrap_model_save(const unwrap_model *m, const char *path)
{
    tensor_list l;
    memset(&l, 0, sizeof l);
    int bad = m->category ? 0 : push_surface(&l, m);
    if (m->param && !bad) {
        const param_net_model *p = m->param;
        if (p->psi_shift) {
            double *norm = mem_alloc(sizeof(double) * 2 * (size_t)p->psi_dim);
            if (!norm) bad = 1;
            else {
                memcpy(norm, p->psi_shift, sizeof(double) * (size_t)p->psi_dim);
                memcpy(norm + p->psi_dim, p->psi_mul, sizeof(double) * (size_t)p->psi_dim);
                bad |= push_doubles(&l, "param.psi_norm", 2, p->psi_dim, norm);
                mem_free(norm);
            }
        }
        if (!bad) bad |= push_params(&l, &p->params);
    }
    if (m->patchnet && !bad) bad |= push_params(&l, &m->patchnet->params);
    char *header = bad ? NULL : header_json(m);
    neuv_status st;
    if (bad || !header) st = error_nomem("the model");
    else {
        nn_tensor **tp = mem_alloc(sizeof *tp * (size_t)l.n);
        if (!tp) st = error_nomem("the model");
        else {
            for (int i = 0; i < l.n; i++) tp[i] = &l.t[i];
            st = nn_checkpoint_save(path, header, tp, l.name, l.n);
            mem_free(tp);
        }
    }
    mem_free(header);
    for (int i = 0; i < l.n_owned; i++) mem_free(l.owned[i]);
    mem_free(l.owned);
    mem_free(l.t);
    mem_free(l.name);
    return st;
}

/* ---- reading ----------------------------------------------------------- */

/* The text right after "key": in a flat JSON object, or NULL. */
static const char *header_value(const char *json, const char *key)
{
    char pat[80];
    snprintf(pat, sizeof pat, "\"%s\":", key);
    const char *p = strstr(json, pat);
    if (!p) return NULL;
    p += strlen(pat);
    while (*p == ' ') p++;
    return p;
}

static neuv_status header_int(const char *json, const char *key, long long lo, long long hi, long long *out)
{
    const char *p = header_value(json, key);
    if (!p) return error_set(NEUV_ERR_INPUT, "model header has no \"%s\"", key);
    char *end;
    long long v = strtoll(p, &end, 10);
    if (end == p || (*end != ',' && *end != '}') || v < lo || v > hi)
        return error_set(NEUV_ERR_INPUT, "model header: \"%s\" must be an integer in %lld..%lld", key, lo, hi);
    *out = v;
    return NEUV_OK;
}

/* Compares a string value with `want`. */
static int header_string_is(const char *json, const char *key, const char *want)
{
    const char *p = header_value(json, key);
    if (!p || *p != '"') return 0;
    size_t n = strlen(want);
    return strncmp(p + 1, want, n) == 0 && p[1 + n] == '"';
}

/* Finds a tensor of the given shape. */
static neuv_status want_tensor(const nn_checkpoint *c, const char *name, int rows, int cols,
                               const nn_checkpoint_tensor **out)
{
    const nn_checkpoint_tensor *t = nn_checkpoint_find(c, name);
    if (!t) return error_set(NEUV_ERR_INPUT, "model has no tensor '%s'", name);
    if (t->rows != rows || t->cols != cols)
        return error_set(NEUV_ERR_INPUT, "model tensor '%s' is %d by %d, expected %d by %d", name, t->rows, t->cols,
                         rows, cols);
    *out = t;
    return NEUV_OK;
}

static neuv_status read_doubles(const nn_checkpoint *c, const char *name, int rows, int cols, double *out)
{
    const nn_checkpoint_tensor *t;
    neuv_status s = want_tensor(c, name, rows, 2 * cols, &t);
    if (s) return s;
    memcpy(out, t->data, sizeof(double) * (size_t)rows * (size_t)cols);
    for (size_t i = 0; i < (size_t)rows * (size_t)cols; i++)
        if (!isfinite(out[i])) return error_set(NEUV_ERR_INPUT, "model tensor '%s' holds a non-finite value", name);
    return NEUV_OK;
}

/* Integers stored as float32; each must be whole and in lo..hi. */
static neuv_status read_ints(const nn_checkpoint *c, const char *name, int rows, int cols, int lo, int hi, int *out)
{
    const nn_checkpoint_tensor *t;
    neuv_status s = want_tensor(c, name, rows, cols, &t);
    if (s) return s;
    for (size_t i = 0; i < (size_t)rows * (size_t)cols; i++) {
        float v = t->data[i];
        if (!(v >= (float)lo && v <= (float)hi) || v != floorf(v))
            return error_set(NEUV_ERR_INPUT, "model tensor '%s' entry %zu is %g, expected an integer in %d..%d", name,
                             i, (double)v, lo, hi);
        out[i] = (int)v;
    }
    return NEUV_OK;
}

static neuv_status check_params(const nn_checkpoint *c, nn_params *ps)
{
    neuv_status s = nn_checkpoint_restore_params(c, ps);
    if (s) return s;
    for (int i = 0; i < ps->n; i++)
        for (long k = 0; k < (long)ps->t[i]->rows * ps->t[i]->cols; k++)
            if (!isfinite(ps->t[i]->data[k]))
                return error_set(NEUV_ERR_INPUT, "model weight '%s' holds a non-finite value", ps->t[i]->name);
    return NEUV_OK;
}

/* The ψ standardization: required in a category model, optional (newer
 * files) in a surface model. */
static neuv_status load_psi_norm(const nn_checkpoint *c, const char *h, int required, param_net_model *p)
{
    long long has = 0;
    neuv_status s;
    if (header_value(h, "param_psi_norm") && (s = header_int(h, "param_psi_norm", 0, 1, &has))) return s;
    if (!has) return required ? error_set(NEUV_ERR_INPUT, "category model has no psi standardization") : NEUV_OK;
    p->psi_shift = mem_alloc(sizeof(double) * (size_t)p->psi_dim);
    p->psi_mul = mem_alloc(sizeof(double) * (size_t)p->psi_dim);
    double *norm = mem_alloc(sizeof(double) * 2 * (size_t)p->psi_dim);
    if (!p->psi_shift || !p->psi_mul || !norm) { mem_free(norm); return error_nomem("the model"); }
    s = read_doubles(c, "param.psi_norm", 2, p->psi_dim, norm);
    if (s == NEUV_OK) {
        memcpy(p->psi_shift, norm, sizeof(double) * (size_t)p->psi_dim);
        memcpy(p->psi_mul, norm + p->psi_dim, sizeof(double) * (size_t)p->psi_dim);
    }
    mem_free(norm);
    return s;
}

static neuv_status load_param(const nn_checkpoint *c, const char *h, unwrap_model *m)
{
    long long nch, psi, width, depth;
    neuv_status s;
    /* A surface model's networks may have more charts than its atlas: the
     * pieces of a chart split on the full mesh of a source trained on a
     * simplified copy keep heads of their own. Their count is bounded by the
     * file's own ψ tensor (read before anything is sized by it). */
    const nn_checkpoint_tensor *psi_t;
    if ((s = header_int(h, "param_charts", m->category ? 0 : 1, m->category ? 0 : 1 << 20, &nch)) ||
        (s = header_int(h, "param_psi_dim", 1, 1 << 16, &psi)) ||
        (s = header_int(h, "param_width", 1, 1 << 14, &width)) ||
        (s = header_int(h, "param_depth", 1, 64, &depth)) ||
        (nch > 0 && (s = want_tensor(c, "param.psi", (int)nch, (int)psi, &psi_t))))
        return s;
    long long heads = 0, gain = 0; /* per-chart output layers and UV scales (absent in older models) */
    if (header_value(h, "param_heads") && (s = header_int(h, "param_heads", 0, 1, &heads))) return s;
    if (header_value(h, "param_uv_gain") && (s = header_int(h, "param_uv_gain", 0, 1, &gain))) return s;
    long long fourier = 0; /* absent in models from before the heads read Fourier features */
    if (header_value(h, "param_head_fourier") && (s = header_int(h, "param_head_fourier", 0, 4096, &fourier))) return s;
    const char *sv = header_value(h, "param_slope");
    char *end;
    double slope = sv ? strtod(sv, &end) : NAN;
    if (!sv || end == sv || !(slope >= 0 && slope < 1))
        return error_set(NEUV_ERR_INPUT, "model header: \"param_slope\" must be a number in [0, 1)");
    param_net_model *p = mem_calloc(1, sizeof *p);
    if (!p) return error_nomem("the model");
    m->param = p;
    nn_params_init(&p->params);
    int n = (int)nch;
    p->psi_mode = PARAM_PSI_POOLED;
    p->psi_dim = (int)psi;
    p->n_charts = n;
    if (n > 0) { /* a category model has no chart of its own */
        p->psi = mem_alloc(sizeof(float) * (size_t)n * (size_t)psi);
        p->center = mem_alloc(sizeof(double) * 3 * (size_t)n);
        p->scale = mem_alloc(sizeof(double) * (size_t)n);
        p->rot = mem_alloc(sizeof(double) * 9 * (size_t)n);
        p->mirror = mem_alloc(sizeof(int) * (size_t)n);
    }
    double *frame = mem_alloc(sizeof(double) * 13 * (size_t)n + 1);
    if ((n > 0 && (!p->psi || !p->center || !p->scale || !p->rot || !p->mirror)) || !frame) {
        mem_free(frame);
        return error_nomem("the model");
    }
    rng r;
    rng_seed(&r, 1); /* the initial values are overwritten by the file's */
    s = param_mlp_create(&p->f, 3, (int)psi, (int)width, 2, (int)depth, (float)slope, &r, &p->params, "f");
    if (!s) s = param_mlp_create(&p->g, 2, (int)psi, (int)width, 3, (int)depth, (float)slope, &r, &p->params, "g");
    p->f.fourier = (int)fourier;
    if (!s) s = check_params(c, &p->params);
    if (!s) s = load_psi_norm(c, h, m->category, p);
    if (n == 0) { mem_free(frame); return s; }
    if (!s) s = read_doubles(c, "param.frame", n, 13, frame);
    if (!s) s = read_ints(c, "param.mirror", n, 1, 0, 1, p->mirror);
    const nn_checkpoint_tensor *t;
    if (!s && gain) {
        p->uv_gain = mem_alloc(sizeof(double) * (size_t)n);
        if (!p->uv_gain) s = error_nomem("the model");
        else s = read_doubles(c, "param.uv_gain", n, 1, p->uv_gain);
        for (int i = 0; !s && i < n; i++)
            if (!(p->uv_gain[i] > 0) || !isfinite(p->uv_gain[i]))
                s = error_set(NEUV_ERR_INPUT, "model chart %d has a UV scale that is not a positive number", i);
    }
    if (!s && heads) {
        int hs = param_head_size(&p->f);
        s = want_tensor(c, "param.heads", n, hs, &t);
        if (!s) p->heads = mem_alloc(sizeof(float) * (size_t)n * hs);
        if (!s && !p->heads) s = error_nomem("the model");
        if (!s) memcpy(p->heads, t->data, sizeof(float) * (size_t)n * hs);
        for (long i = 0; !s && i < (long)n * hs; i++)
            if (!isfinite(p->heads[i])) s = error_set(NEUV_ERR_INPUT, "model tensor \"param.heads\" holds a non-finite value");
    }
    if (!s) s = want_tensor(c, "param.psi", n, (int)psi, &t);
    if (!s) {
        memcpy(p->psi, t->data, sizeof(float) * (size_t)n * (size_t)psi);
        for (int c2 = 0; c2 < n; c2++) {
            memcpy(p->center + 3 * c2, frame + 13 * c2, 3 * sizeof(double));
            p->scale[c2] = frame[13 * c2 + 3];
            memcpy(p->rot + 9 * c2, frame + 13 * c2 + 4, 9 * sizeof(double));
            if (!(p->scale[c2] > 0)) s = error_set(NEUV_ERR_INPUT, "model chart frame %d has a non-positive scale", c2);
        }
    }
    mem_free(frame);
    return s;
}

static neuv_status load_patchnet(const nn_checkpoint *c, const char *h, unwrap_model *m)
{
    long long k, k_eig, in_dim, blocks, width, seed;
    neuv_status s;
    if ((s = header_int(h, "patchnet_k", 1, 4096, &k)) || (s = header_int(h, "patchnet_k_eig", 1, 4096, &k_eig)) ||
        (s = header_int(h, "patchnet_in_dim", 1, 4096, &in_dim)) ||
        (s = header_int(h, "patchnet_blocks", 1, 64, &blocks)) ||
        (s = header_int(h, "patchnet_width", 1, 4096, &width)) ||
        (s = header_int(h, "patchnet_seed", 0, INT64_MAX, &seed)))
        return s;
    patchnet_options o;
    patchnet_default_options(&o);
    int known = 0;
    for (int f = 0; !known && diffusion_net_features_name((diffusion_net_features)f); f++)
        if (header_string_is(h, "patchnet_features", diffusion_net_features_name((diffusion_net_features)f))) {
            o.features = (diffusion_net_features)f;
            known = 1;
        }
    if (!known) return error_set(NEUV_ERR_INPUT, "model header: \"patchnet_features\" must be \"hks\", \"xyz\" or \"hks+normals\"");
    o.k_eig = (int)k_eig;
    o.blocks = (int)blocks;
    o.width = (int)width;
    o.seed = (uint64_t)seed;
    m->patchnet = mem_calloc(1, sizeof *m->patchnet);
    if (!m->patchnet) return error_nomem("the model");
    if ((s = patchnet_model_create(m->patchnet, &o, (int)in_dim, (int)k))) return s;
    return check_params(c, &m->patchnet->params);
}

/* A category model: settings, both networks and PatchNet; no surface. */
static neuv_status load_category(const nn_checkpoint *c, const char *h, unwrap_model *m)
{
    long long seed, res, pad, shapes, autok, refine = 0, has_param, has_patchnet;
    neuv_status s;
    m->category = 1;
    if ((s = header_int(h, "seed", 0, INT64_MAX, &seed)) || (s = header_int(h, "resolution", 64, 16384, &res)) ||
        (s = header_int(h, "padding", 0, 2048, &pad)) || (s = header_int(h, "category_shapes", 1, 1 << 20, &shapes)) ||
        (s = header_int(h, "charts_auto", 0, 1, &autok)) || (s = header_int(h, "refine", 0, 1000000, &refine)) ||
        (s = header_int(h, "param", 0, 1, &has_param)) || (s = header_int(h, "patchnet", 0, 1, &has_patchnet)))
        return s;
    if (m->method != NEUV_METHOD_NEURAL || !has_param || !has_patchnet)
        return error_set(NEUV_ERR_INPUT, "a category model must be neural and hold both PatchNet and the "
                                         "parameterization networks");
    const char *dv = header_value(h, "max_distortion");
    char *end;
    double maxd = dv ? strtod(dv, &end) : NAN;
    if (!dv || end == dv || !(maxd >= 1 && maxd < 1e6))
        return error_set(NEUV_ERR_INPUT, "model header: \"max_distortion\" must be a number >= 1");
    m->seed = (uint64_t)seed;
    m->resolution = (int)res;
    m->padding = (int)pad;
    m->category_shapes = (int)shapes;
    m->charts_auto = (int)autok;
    m->refine = (int)refine;
    m->max_distortion = maxd;
    if ((s = load_param(c, h, m))) return s;
    return load_patchnet(c, h, m);
}

static neuv_status load_from(const nn_checkpoint *c, unwrap_model *m)
{
    const char *h = c->config;
    neuv_status s;
    if (!header_string_is(h, "format", FORMAT_NAME))
        return error_set(NEUV_ERR_INPUT, "not a neuv unwrap model (header format is not \"%s\")", FORMAT_NAME);
    long long ver, seed, res, pad, nc, nv, nf, nuv, has_labels, has_param, has_patchnet;
    if ((s = header_int(h, "model_version", 0, 1 << 30, &ver))) return s;
    if (ver != UNWRAP_MODEL_VERSION)
        return error_set(NEUV_ERR_INPUT, "model version %lld is not supported (this neuv reads version %d)", ver,
                         UNWRAP_MODEL_VERSION);
    if (header_string_is(h, "method", "neural")) m->method = NEUV_METHOD_NEURAL;
    else if (header_string_is(h, "method", "lscm")) m->method = NEUV_METHOD_LSCM;
    else if (header_string_is(h, "method", "harmonic")) m->method = NEUV_METHOD_HARMONIC;
    else return error_set(NEUV_ERR_INPUT, "model header: \"method\" must be neural, lscm or harmonic");
    if (header_string_is(h, "preset", "paper")) m->preset = NEUV_PRESET_PAPER;
    else if (header_string_is(h, "preset", "fast")) m->preset = NEUV_PRESET_FAST;
    else return error_set(NEUV_ERR_INPUT, "model header: \"preset\" must be fast or paper");
    if (header_string_is(h, "kind", "category")) return load_category(c, h, m);
    if (header_value(h, "kind") && !header_string_is(h, "kind", "surface"))
        return error_set(NEUV_ERR_INPUT, "model header: \"kind\" must be \"surface\" or \"category\"");
    if ((s = header_int(h, "seed", 0, INT64_MAX, &seed)) || (s = header_int(h, "resolution", 64, 16384, &res)) ||
        (s = header_int(h, "padding", 0, 2048, &pad)) || (s = header_int(h, "charts", 1, 1 << 20, &nc)) ||
        (s = header_int(h, "source_vertices", 3, MAX_EXACT_INT - 1, &nv)) ||
        (s = header_int(h, "source_faces", 1, 1 << 28, &nf)) ||
        (s = header_int(h, "source_uvs", 3, MAX_EXACT_INT - 1, &nuv)) ||
        (s = header_int(h, "source_labels", 0, 1, &has_labels)) || (s = header_int(h, "param", 0, 1, &has_param)) ||
        (s = header_int(h, "patchnet", 0, 1, &has_patchnet)))
        return s;
    if (m->method == NEUV_METHOD_NEURAL && !has_param)
        return error_set(NEUV_ERR_INPUT, "model says method neural but holds no parameterization network");
    /* Shapes first, so a header that lies about sizes allocates nothing. */
    const nn_checkpoint_tensor *t;
    if ((s = want_tensor(c, "source.pos", (int)nv, 6, &t)) || (s = want_tensor(c, "source.tri", (int)nf, 3, &t)) ||
        (s = want_tensor(c, "source.uv", (int)nuv, 4, &t)) || (s = want_tensor(c, "charts.map", (int)nc, 2, &t)))
        return s;
    m->seed = (uint64_t)seed;
    long long refine = 0; /* written since the vertex refinement exists; older models have none */
    if (header_value(h, "refine") && (s = header_int(h, "refine", 0, 1000000, &refine))) return s;
    m->refine = (int)refine;
    m->resolution = (int)res;
    m->padding = (int)pad;
    m->n_charts = (int)nc;
    m->source = mesh_create((int)nv, (int)nf, (int)nuv);
    m->face_chart = mem_alloc(sizeof(int) * (size_t)nf);
    m->xf = mem_alloc(sizeof *m->xf * (size_t)nc);
    m->chart_net = mem_alloc(sizeof(int) * (size_t)nc);
    m->chart_mirrored = mem_alloc(sizeof(int) * (size_t)nc);
    double *xf = mem_alloc(sizeof(double) * 4 * (size_t)nc);
    int *map = mem_alloc(sizeof(int) * 2 * (size_t)nc);
    if (has_labels) m->face_label = mem_alloc(sizeof(int) * (size_t)nf);
    if (!m->source || !m->source->tri_uv || !m->face_chart || !m->xf || !m->chart_net || !m->chart_mirrored || !xf ||
        !map || (has_labels && !m->face_label)) {
        mem_free(xf); mem_free(map);
        return error_nomem("the model");
    }
    neuv_mesh *src = m->source;
    s = read_doubles(c, "source.pos", src->nv, 3, src->pos);
    if (!s) s = read_ints(c, "source.tri", src->nf, 3, 0, src->nv - 1, src->tri);
    if (!s) s = read_doubles(c, "source.uv", src->nuv, 2, src->uv);
    if (!s) s = read_ints(c, "source.tri_uv", src->nf, 3, 0, src->nuv - 1, src->tri_uv);
    if (!s) s = read_ints(c, "source.chart", src->nf, 1, 0, m->n_charts - 1, m->face_chart);
    if (!s && has_labels) s = read_ints(c, "source.label", src->nf, 1, 0, 1 << 20, m->face_label);
    if (!s) s = read_doubles(c, "source.norm", 1, 5, m->norm);
    if (!s) s = read_doubles(c, "charts.xf", m->n_charts, 4, xf);
    if (!s) s = read_ints(c, "charts.map", m->n_charts, 2, -1, 1 << 20, map);
    for (int k = 0; !s && k < m->n_charts; k++) {
        m->xf[k] = (atlas_chart_transform){xf[4 * k], xf[4 * k + 1], xf[4 * k + 2], xf[4 * k + 3]};
        m->chart_net[k] = map[2 * k];
        m->chart_mirrored[k] = map[2 * k + 1];
        if (!(m->xf[k].scale > 0)) s = error_set(NEUV_ERR_INPUT, "model chart %d has a non-positive packing scale", k);
        else if (m->chart_mirrored[k] != 0 && m->chart_mirrored[k] != 1)
            s = error_set(NEUV_ERR_INPUT, "model chart %d has a bad mirror flag", k);
    }
    mem_free(xf);
    mem_free(map);
    if (s) return s;
    if (has_param && (s = load_param(c, h, m))) return s;
    for (int k = 0; k < m->n_charts; k++)
        if (m->chart_net[k] >= (m->param ? m->param->n_charts : 0))
            return error_set(NEUV_ERR_INPUT, "model chart %d names network chart %d, which the model lacks", k,
                             m->chart_net[k]);
    if (has_patchnet && (s = load_patchnet(c, h, m))) return s;
    return NEUV_OK;
}

/* The checkpoint's version, then the model from its configuration and
 * tensors; the checkpoint is freed either way. */
static neuv_status model_from_checkpoint(nn_checkpoint *c, unwrap_model **out)
{
    if (c->version != NN_CHECKPOINT_VERSION) {
        unsigned v = c->version;
        nn_checkpoint_free(c);
        return error_set(NEUV_ERR_INPUT, "checkpoint version %u is not supported", v);
    }
    unwrap_model *m = mem_calloc(1, sizeof *m);
    if (!m) { nn_checkpoint_free(c); return error_nomem("the model"); }
    neuv_status s = load_from(c, m);
    nn_checkpoint_free(c);
    if (s) { unwrap_model_free(m); return s; }
    *out = m;
    return NEUV_OK;
}

neuv_status unwrap_model_load(const char *path, unwrap_model **out)
{
    *out = NULL;
    nn_checkpoint c;
    neuv_status s = nn_checkpoint_load(path, &c);
    return s ? s : model_from_checkpoint(&c, out);
}

neuv_status unwrap_model_parse(const void *bytes, size_t len, unwrap_model **out)
{
    *out = NULL;
    nn_checkpoint c;
    neuv_status s = nn_checkpoint_parse(bytes, len, &c);
    return s ? s : model_from_checkpoint(&c, out);
}
