/* Inference with a trained parameterization model (param_net.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/mem.h"
#include "losses/param_losses.h"
#include "models/param_net.h"
#include "models/param_output_solve.h"

void param_net_model_free(param_net_model *model)
{
    if (!model) return;
    if (!model->borrowed) {
        param_mlp_free(&model->f);
        param_mlp_free(&model->g);
        nn_params_free(&model->params);
        mem_free(model->psi_shift); mem_free(model->psi_mul);
    }
    mem_free(model->psi); mem_free(model->center); mem_free(model->scale); mem_free(model->rot); mem_free(model->mirror);
    mem_free(model->heads); mem_free(model->uv_gain);
    mem_free(model);
}

/* Runs one of the networks on n rows of the chart's normalized inputs. */
static neuv_status run_net_heads(const param_net_model *model, const param_mlp *net, int chart_id, const float *in,
                                 int n, int in_dim, const float *heads, int head_id, float *out, int out_dim);

static neuv_status run_net(const param_net_model *model, const param_mlp *net, int chart_id, const float *in,
                           int n, int in_dim, float *out, int out_dim)
{
    return run_net_heads(model, net, chart_id, in, n, in_dim, net == &model->f ? model->heads : NULL, chart_id, out,
                         out_dim);
}

/* As run_net, with MLP_f's output layer the head `head_id` of `heads` (NULL: the shared layer). */
static neuv_status run_net_heads(const param_net_model *model, const param_mlp *net, int chart_id, const float *in,
                                 int n, int in_dim, const float *heads, int head_id, float *out, int out_dim)
{
    if (!model || chart_id < 0 || chart_id >= model->n_charts)
        return error_set(NEUV_ERR_INPUT, "chart %d is not in the model (%d charts)", chart_id,
                         model ? model->n_charts : 0);
    if (model->psi_mode != PARAM_PSI_POOLED || !model->psi)
        return error_set(NEUV_ERR_INPUT, "a per-vertex-feature model cannot be applied without features");
    nn_ctx *ctx = nn_ctx_create(0);
    int *row = mem_calloc((size_t)(n > 0 ? n : 1), sizeof(int));
    if (!ctx || !row) { nn_ctx_free(ctx); mem_free(row); return error_nomem("parameterization inference"); }
    nn_tensor *x = nn_from(ctx, n, in_dim, in);
    nn_tensor *psi = nn_view(ctx, 1, model->psi_dim, model->psi + (size_t)chart_id * model->psi_dim);
    neuv_status s = NEUV_OK;
    if (net == &model->f && heads) {
        /* The chart's own output layer (param_output_solve.h); row is all chart_id's row 0. */
        nn_tensor *h = param_mlp_head_features(ctx, net, x, psi, row);
        int *head_of = h ? mem_alloc(sizeof(int) * (size_t)(n > 0 ? n : 1)) : NULL;
        if (!h) s = nn_ctx_status(ctx);
        else if (!head_of) s = error_nomem("parameterization inference");
        else {
            for (int i = 0; i < n; i++) head_of[i] = head_id;
            param_heads_apply(net, h->data, n, head_of, heads, out);
        }
        mem_free(head_of);
    } else {
        nn_tensor *y = param_mlp_forward(ctx, net, x, psi, row);
        s = y ? NEUV_OK : nn_ctx_status(ctx);
        if (y) for (long i = 0; i < (long)n * out_dim; i++) out[i] = y->data[i];
    }
    nn_ctx_free(ctx);
    mem_free(row);
    return s;
}

/* Points in chart `chart_id`'s normalized frame, as training saw them. */
static void normalize_points(const param_net_model *model, int chart_id, const double *points, int n, float *in)
{
    const double *c = model->center + 3 * chart_id;
    double sc = model->scale[chart_id];
    const double *R = model->rot + 9 * chart_id;
    for (int i = 0; i < n; i++) {
        const double *p = points + 3 * i;
        for (int q = 0; q < 3; q++)
            in[3 * i + q] = (float)(sc * (R[3 * q] * (p[0] - c[0]) + R[3 * q + 1] * (p[1] - c[1]) +
                                          R[3 * q + 2] * (p[2] - c[2])));
    }
}

/* MLP_f's outputs to the chart's frame in mesh units (mirror, gain, 1/scale). */
static void uv_from_net(const param_net_model *model, int chart_id, const float *out, int n, double gain, double *uv)
{
    double sc = model->scale[chart_id];
    double sign = model->mirror[chart_id] ? -1 : 1;
    for (int i = 0; i < n; i++) {
        uv[2 * i] = sign * gain * out[2 * i] / sc;
        uv[2 * i + 1] = gain * out[2 * i + 1] / sc;
    }
}

neuv_status param_net_apply(const param_net_model *model, int chart_id, const double *points, int n, double *uv)
{
    if (n <= 0) return NEUV_OK;
    if (!model || chart_id < 0 || chart_id >= model->n_charts)
        return error_set(NEUV_ERR_INPUT, "chart %d is not in the model", chart_id);
    float *in = mem_alloc((size_t)n * 3 * sizeof(float)), *out = mem_alloc((size_t)n * 2 * sizeof(float));
    if (!in || !out) { mem_free(in); mem_free(out); return error_nomem("parameterization inference"); }
    normalize_points(model, chart_id, points, n, in);
    neuv_status s = run_net(model, &model->f, chart_id, in, n, 3, out, 2);
    if (s == NEUV_OK) uv_from_net(model, chart_id, out, n, model->uv_gain ? model->uv_gain[chart_id] : 1, uv);
    mem_free(in); mem_free(out);
    return s;
}

neuv_status param_net_apply_inverse(const param_net_model *model, int chart_id, const double *uv, int n,
                                    double *points)
{
    if (n <= 0) return NEUV_OK;
    if (!model || chart_id < 0 || chart_id >= model->n_charts)
        return error_set(NEUV_ERR_INPUT, "chart %d is not in the model", chart_id);
    float *in = mem_alloc((size_t)n * 2 * sizeof(float)), *out = mem_alloc((size_t)n * 3 * sizeof(float));
    if (!in || !out) { mem_free(in); mem_free(out); return error_nomem("parameterization inference"); }
    double sign = model->mirror[chart_id] ? -1 : 1;
    double sc = model->scale[chart_id] / (model->uv_gain ? model->uv_gain[chart_id] : 1);
    for (int i = 0; i < n; i++) {
        in[2 * i] = (float)(sign * uv[2 * i] * sc);
        in[2 * i + 1] = (float)(uv[2 * i + 1] * sc);
    }
    neuv_status s = run_net(model, &model->g, chart_id, in, n, 2, out, 3);
    const double *c = model->center + 3 * chart_id, *R = model->rot + 9 * chart_id;
    if (s == NEUV_OK)
        for (int i = 0; i < n; i++)
            for (int q = 0; q < 3; q++) /* x = R^T y / s + c */
                points[3 * i + q] = (R[q] * out[3 * i] + R[3 + q] * out[3 * i + 1] + R[6 + q] * out[3 * i + 2]) / sc + c[q];
    mem_free(in); mem_free(out);
    return s;
}

/* The core of param_net_apply_solved and param_net_solve_head: the solved
 * output layer into head_out (param_head_size floats), its gain into
 * *gain_out (either NULL: not wanted). between: whether the sub-faces carry
 * their share of the conformal energy (solve_subdivide_energy) besides the
 * fold barrier: for a head kept in the model, whose map other
 * triangulations will see; a map for this mesh alone needs only its own
 * vertices judged (and costs a fifth of the rows). */
static neuv_status solve_head(const param_net_model *model, int chart_id, const neuv_mesh *chart, double *uv,
                              float *head_out, double *gain_out, int between, param_solve_report *rep)
{
    param_solve_report local;
    if (!rep) rep = &local;
    memset(rep, 0, sizeof *rep);
    if (!model || chart_id < 0 || chart_id >= model->n_charts)
        return error_set(NEUV_ERR_INPUT, "chart %d is not in the model", chart_id);
    if (!model->heads || model->f.depth < 2)
        return error_set(NEUV_ERR_INPUT, "this model has no per-chart output layers to solve");
    int nv = chart->nv, nf = chart->nf, hs = param_head_size(&model->f);
    if (nv <= 0 || nf <= 0) return NEUV_OK;
    param_net_options o;
    param_net_default_options(&o, PARAM_PRESET_FAST);
    float *x = mem_alloc(sizeof(float) * 3 * (size_t)nv), *frame_inv = mem_alloc(sizeof(float) * 4 * (size_t)nf);
    float *face_w = mem_alloc(sizeof(float) * (size_t)nf), *head = mem_alloc(sizeof(float) * (size_t)hs);
    float *out = mem_alloc(sizeof(float) * 2 * (size_t)nv);
    double *xn = mem_alloc(sizeof(double) * 3 * (size_t)nv);
    int *vchart = mem_calloc((size_t)nv, sizeof(int)), *fchart = mem_calloc((size_t)nf, sizeof(int));
    param_corners corners = {0};
    param_solve_subdivided sub;
    memset(&sub, 0, sizeof sub);
    neuv_status s = NEUV_OK;
    if (!x || !frame_inv || !face_w || !head || !out || !xn || !vchart || !fchart) s = error_nomem("chart head");
    if (s == NEUV_OK) s = param_corners_build(chart->tri, nf, &corners);
    if (s == NEUV_OK) {
        /* The conformal targets from the normalized float positions, as training builds them. */
        normalize_points(model, chart_id, chart->pos, nv, x);
        for (long i = 0; i < 3 * (long)nv; i++) xn[i] = x[i];
        param_conformal_targets(xn, &corners, frame_inv, face_w);
        param_solve_data d = {nv, nf, 1, x, x, 3, vchart, model->psi + (size_t)chart_id * model->psi_dim,
                              model->psi_dim, 0, chart->tri, fchart, frame_inv, face_w, o.solve_fold,
                              o.solve_fold_eps, NULL, o.solve_mips, NULL, 0, 0};
        if (o.solve_subdivide && o.solve_fold > 0 &&
            (s = param_solve_subdivide(&d, between ? o.solve_subdivide_energy : 0, param_net_dense_vertices(&model->f, &o),
                                       &sub)) == NEUV_OK)
            d = sub.d;
        if (s == NEUV_OK)
            s = param_output_solve_head_from(&model->f, &d, o.solve_anchor, o.solve_steps,
                                             model->heads + (size_t)chart_id * hs, head, rep);
    }
    if (s == NEUV_OK) s = run_net_heads(model, &model->f, chart_id, x, nv, 3, head, 0, out, 2);
    if (s == NEUV_OK) {
        /* The solved map brought to the chart's 3D area, as training brings
         * the learnt one (its gain is the learnt head's on the learnt
         * triangulation). */
        double a3 = 0, auv = 0;
        for (int f = 0; f < nf; f++) {
            const int *t = chart->tri + 3 * f;
            const double *a = xn + 3 * t[0], *b = xn + 3 * t[1], *c = xn + 3 * t[2];
            double e0[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e1[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
            double cx = e0[1] * e1[2] - e0[2] * e1[1], cy = e0[2] * e1[0] - e0[0] * e1[2], cz = e0[0] * e1[1] - e0[1] * e1[0];
            a3 += 0.5 * sqrt(cx * cx + cy * cy + cz * cz);
            const float *p = out + 2 * t[0], *q = out + 2 * t[1], *r = out + 2 * t[2];
            auv += 0.5 * ((double)(q[0] - p[0]) * (r[1] - p[1]) - (double)(q[1] - p[1]) * (r[0] - p[0]));
        }
        double gain = fabs(auv) > 0 && a3 > 0 ? sqrt(a3 / fabs(auv)) : model->uv_gain ? model->uv_gain[chart_id] : 1;
        uv_from_net(model, chart_id, out, nv, gain, uv);
        if (gain_out) *gain_out = gain;
        if (head_out) memcpy(head_out, head, sizeof(float) * (size_t)hs);
    }
    param_solve_subdivided_free(&sub);
    param_corners_free(&corners);
    mem_free(x); mem_free(frame_inv); mem_free(face_w); mem_free(head); mem_free(out); mem_free(xn);
    mem_free(vchart); mem_free(fchart);
    return s;
}

neuv_status param_net_apply_solved(const param_net_model *model, int chart_id, const neuv_mesh *chart, double *uv,
                                   float *head, double *gain, param_solve_report *rep)
{
    return solve_head(model, chart_id, chart, uv, head, gain, 0, rep);
}

neuv_status param_net_solve_head(const param_net_model *model, int chart_id, const neuv_mesh *chart, double *uv,
                                 float *head, double *gain)
{
    return solve_head(model, chart_id, chart, uv, head, gain, 1, NULL);
}

int param_net_can_add_chart(const param_net_model *model)
{
    return model && model->heads && model->uv_gain && model->psi_mode == PARAM_PSI_POOLED;
}

neuv_status param_net_add_chart(param_net_model *model, int parent, const float *head, double gain, int *id)
{
    if (!param_net_can_add_chart(model) || parent < 0 || parent >= model->n_charts)
        return error_set(NEUV_ERR_INPUT, "chart %d cannot be derived: not in the model, or a model without per-chart "
                                         "output layers, gains and codes", parent);
    int n = model->n_charts + 1, hs = param_head_size(&model->f), pd = model->psi_dim;
    float *psi = mem_realloc(model->psi, sizeof(float) * (size_t)n * (size_t)pd);
    if (psi) model->psi = psi;
    double *center = mem_realloc(model->center, sizeof(double) * 3 * (size_t)n);
    if (center) model->center = center;
    double *scale = mem_realloc(model->scale, sizeof(double) * (size_t)n);
    if (scale) model->scale = scale;
    double *rot = mem_realloc(model->rot, sizeof(double) * 9 * (size_t)n);
    if (rot) model->rot = rot;
    int *mirror = mem_realloc(model->mirror, sizeof(int) * (size_t)n);
    if (mirror) model->mirror = mirror;
    float *heads = mem_realloc(model->heads, sizeof(float) * (size_t)n * (size_t)hs);
    if (heads) model->heads = heads;
    double *uv_gain = mem_realloc(model->uv_gain, sizeof(double) * (size_t)n);
    if (uv_gain) model->uv_gain = uv_gain;
    if (!psi || !center || !scale || !rot || !mirror || !heads || !uv_gain) return error_nomem("chart head");
    int c = model->n_charts;
    memcpy(model->psi + (size_t)c * pd, model->psi + (size_t)parent * pd, sizeof(float) * (size_t)pd);
    memcpy(model->center + 3 * c, model->center + 3 * parent, sizeof(double) * 3);
    model->scale[c] = model->scale[parent];
    memcpy(model->rot + 9 * c, model->rot + 9 * parent, sizeof(double) * 9);
    model->mirror[c] = model->mirror[parent];
    memcpy(model->heads + (size_t)c * hs, head, sizeof(float) * (size_t)hs);
    model->uv_gain[c] = gain;
    model->n_charts = n;
    *id = c;
    return NEUV_OK;
}
