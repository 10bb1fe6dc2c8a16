/* Inference with a trained parameterization model (param_net.h). */
#include <stdlib.h>

#include "core/error.h"
#include "core/mem.h"
#include "models/param_net.h"
#include "models/param_output_solve.h"

void param_net_model_free(param_net_model *model)
{
    if (!model) return;
    param_mlp_free(&model->f);
    param_mlp_free(&model->g);
    nn_params_free(&model->params);
    mem_free(model->psi); mem_free(model->center); mem_free(model->scale); mem_free(model->rot); mem_free(model->mirror);
    mem_free(model->psi_shift); mem_free(model->psi_mul); mem_free(model->heads); mem_free(model->uv_gain);
    mem_free(model);
}

/* Runs one of the networks on n rows of the chart's normalized inputs. */
static neuv_status run_net(const param_net_model *model, const param_mlp *net, int chart_id, const float *in,
                           int n, int in_dim, float *out, int out_dim)
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
    if (net == &model->f && model->heads) {
        /* The chart's own output layer (param_output_solve.h); row is all chart_id's row 0. */
        nn_tensor *h = param_mlp_head_features(ctx, net, x, psi, row);
        int *head_of = h ? mem_alloc(sizeof(int) * (size_t)(n > 0 ? n : 1)) : NULL;
        if (!h) s = nn_ctx_status(ctx);
        else if (!head_of) s = error_nomem("parameterization inference");
        else {
            for (int i = 0; i < n; i++) head_of[i] = chart_id;
            param_heads_apply(net, h->data, n, head_of, model->heads, out);
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

neuv_status param_net_apply(const param_net_model *model, int chart_id, const double *points, int n, double *uv)
{
    if (n <= 0) return NEUV_OK;
    if (!model || chart_id < 0 || chart_id >= model->n_charts)
        return error_set(NEUV_ERR_INPUT, "chart %d is not in the model", chart_id);
    float *in = mem_alloc((size_t)n * 3 * sizeof(float)), *out = mem_alloc((size_t)n * 2 * sizeof(float));
    if (!in || !out) { mem_free(in); mem_free(out); return error_nomem("parameterization inference"); }
    const double *c = model->center + 3 * chart_id;
    double sc = model->scale[chart_id];
    const double *R = model->rot + 9 * chart_id;
    for (int i = 0; i < n; i++) {
        const double *p = points + 3 * i;
        for (int q = 0; q < 3; q++)
            in[3 * i + q] = (float)(sc * (R[3 * q] * (p[0] - c[0]) + R[3 * q + 1] * (p[1] - c[1]) +
                                          R[3 * q + 2] * (p[2] - c[2])));
    }
    neuv_status s = run_net(model, &model->f, chart_id, in, n, 3, out, 2);
    double sign = model->mirror[chart_id] ? -1 : 1, gain = model->uv_gain ? model->uv_gain[chart_id] : 1;
    if (s == NEUV_OK)
        for (int i = 0; i < n; i++) {
            uv[2 * i] = sign * gain * out[2 * i] / sc;
            uv[2 * i + 1] = gain * out[2 * i + 1] / sc;
        }
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
