/* Conditioned MLP of the parameterization networks (see param_mlp.h). */
#include "models/param_mlp.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "core/error.h"
#include "core/mem.h"
#include "core/rng.h"

neuv_status param_mlp_create(param_mlp *m, int in, int psi, int width, int out, int depth, float slope,
                             struct rng *r, nn_params *params, const char *prefix)
{
    *m = (param_mlp){0};
    if (in < 1 || psi < 0 || width < 1 || out < 1 || depth < 1)
        return error_set(NEUV_ERR_INPUT, "bad MLP shape (in %d, psi %d, width %d, out %d, depth %d)", in,
                         psi, width, out, depth);
    m->in = in; m->psi = psi; m->width = width; m->out = out; m->depth = depth;
    m->slope = slope > 0 ? slope : 0.01f;
    int w0 = depth > 1 ? width : out;
    char name[128];
    snprintf(name, sizeof name, "%s.0.wx", prefix);
    m->w_x = nn_params_add(params, in, w0, name);
    if (psi > 0) {
        snprintf(name, sizeof name, "%s.0.wpsi", prefix);
        m->w_psi = nn_params_add(params, psi, w0, name);
    }
    snprintf(name, sizeof name, "%s.0.b", prefix);
    m->b0 = nn_params_add(params, 1, w0, name);
    if (!m->w_x || !m->b0 || (psi > 0 && !m->w_psi)) return error_last();
    /* One bound for both blocks: they are one layer of fan-in in + psi. */
    int fan_in = in + psi;
    double bound = depth > 1 ? sqrt(6.0 / fan_in) : sqrt(6.0 / (fan_in + out));
    for (long i = 0; i < (long)in * w0; i++) m->w_x->data[i] = (float)((2 * rng_uniform(r) - 1) * bound);
    for (long i = 0; psi > 0 && i < (long)psi * w0; i++)
        m->w_psi->data[i] = (float)((2 * rng_uniform(r) - 1) * bound);
    if (depth > 1) {
        m->rest = mem_calloc((size_t)(depth - 1), sizeof *m->rest);
        if (!m->rest) return error_nomem("MLP layers");
        for (int l = 1; l < depth; l++) {
            int last = l == depth - 1;
            snprintf(name, sizeof name, "%s.%d", prefix, l);
            neuv_status s = nn_linear_create(&m->rest[l - 1], width, last ? out : width,
                                             last ? NN_ACT_TANH : NN_ACT_LEAKY_RELU, r, params, name);
            if (s != NEUV_OK) return s;
        }
    }
    return NEUV_OK;
}

void param_mlp_free(param_mlp *m)
{
    mem_free(m->rest);
    m->rest = NULL;
}

/* The first `layers` linear layers with their activations (all: the
 * pre-tanh output). */
static nn_tensor *forward_layers(nn_ctx *ctx, const param_mlp *m, nn_tensor *x, nn_tensor *psi, const int *psi_row,
                                 int layers)
{
    nn_tensor *h = nn_add(ctx, nn_matmul(ctx, x, m->w_x), m->b0);
    if (m->psi > 0) {
        nn_tensor *p = nn_matmul(ctx, psi, m->w_psi);
        if (psi_row && x) p = nn_gather_rows(ctx, p, psi_row, x->rows);
        h = nn_add(ctx, h, p);
    }
    for (int l = 1; l < layers; l++) {
        h = nn_leaky_relu(ctx, h, m->slope);
        h = nn_linear_forward(ctx, &m->rest[l - 1], h);
    }
    return h;
}

nn_tensor *param_mlp_forward(nn_ctx *ctx, const param_mlp *m, nn_tensor *x, nn_tensor *psi,
                             const int *psi_row)
{
    return nn_tanh(ctx, forward_layers(ctx, m, x, psi, psi_row, m->depth));
}

int param_mlp_head_width(const param_mlp *m)
{
    return m->depth > 1 ? m->width * (m->depth - 1) + param_mlp_fourier_width(m) : 0;
}

int param_mlp_fourier_width(const param_mlp *m)
{
    return m->fourier > 0 ? 3 + 2 * m->fourier : 0;
}

void param_mlp_fourier_features(const param_mlp *m, const float *x, int n, int stride, float *out)
{
    int k = m->fourier, F = param_mlp_fourier_width(m);
    const double pi = 3.14159265358979323846, golden = pi * (3 - sqrt(5.0));
    for (int i = 0; i < n; i++) {
        const float *p = x + (size_t)i * stride;
        float *o = out + (size_t)i * F;
        o[0] = p[0]; o[1] = p[1]; o[2] = p[2];
        for (int j = 0; j < k; j++) {
            double z = 1 - (j + 0.5) * 2.0 / k, r = sqrt(fmax(0, 1 - z * z)), th = golden * j;
            double w = (pi / 1.2) * (double)(1 << (j % 3));
            double t = w * (r * cos(th) * p[0] + r * sin(th) * p[1] + z * p[2]);
            o[3 + 2 * j] = (float)sin(t);
            o[4 + 2 * j] = (float)cos(t);
        }
    }
}

static nn_tensor *fourier_tensor(nn_ctx *ctx, const param_mlp *m, nn_tensor *x)
{
    nn_tensor *t = x ? nn_fill(ctx, x->rows, param_mlp_fourier_width(m), 0) : NULL;
    if (t) param_mlp_fourier_features(m, x->data, x->rows, x->cols, t->data);
    return t;
}

nn_tensor *param_mlp_head_features(nn_ctx *ctx, const param_mlp *m, nn_tensor *x, nn_tensor *psi, const int *psi_row)
{
    if (m->depth < 2) return NULL;
    nn_tensor *h = nn_leaky_relu(ctx, forward_layers(ctx, m, x, psi, psi_row, 1), m->slope), *all = h;
    if (m->fourier > 0) all = nn_concat_cols(ctx, fourier_tensor(ctx, m, x), h);
    for (int l = 1; l < m->depth - 1; l++) {
        h = nn_leaky_relu(ctx, nn_linear_forward(ctx, &m->rest[l - 1], h), m->slope);
        all = nn_concat_cols(ctx, all, h);
    }
    return all;
}

nn_tensor *param_mlp_hidden(nn_ctx *ctx, const param_mlp *m, nn_tensor *x, nn_tensor *psi, const int *psi_row)
{
    if (m->depth < 2) return NULL;
    return nn_leaky_relu(ctx, forward_layers(ctx, m, x, psi, psi_row, m->depth - 1), m->slope);
}
