/* Linear layers and multilayer perceptrons. */
#include "nn/mlp.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/mem.h"
#include "core/rng.h"

neuv_status nn_linear_create(nn_linear *l, int in, int out, nn_activation act,
                             struct rng *r, nn_params *params, const char *prefix)
{
    memset(l, 0, sizeof *l);
    if (in <= 0 || out <= 0) return error_set(NEUV_ERR_INPUT, "linear layer '%s': sizes %d -> %d", prefix, in, out);
    char name[256];
    snprintf(name, sizeof name, "%s.w", prefix);
    l->w = nn_params_add(params, in, out, name);
    if (!l->w) return error_last();
    snprintf(name, sizeof name, "%s.b", prefix);
    l->b = nn_params_add(params, 1, out, name);
    if (!l->b) return error_last();
    l->in = in;
    l->out = out;
    /* Kaiming-uniform keeps activations' variance through ReLU-family layers
     * (He et al. 2015); Xavier-uniform suits tanh and linear outputs (Glorot & Bengio 2010). */
    int relu_family = act == NN_ACT_RELU || act == NN_ACT_LEAKY_RELU;
    double bound = relu_family ? sqrt(6.0 / in) : sqrt(6.0 / (in + out));
    for (long i = 0; i < (long)in * out; i++) l->w->data[i] = (float)((2.0 * rng_uniform(r) - 1.0) * bound);
    return NEUV_OK;
}

nn_tensor *nn_linear_forward(nn_ctx *ctx, const nn_linear *l, nn_tensor *x)
{
    return nn_linear_act(ctx, x, l->w, l->b, NN_ACT_NONE, 0);
}

nn_tensor *nn_activate(nn_ctx *ctx, nn_tensor *x, nn_activation act, float leaky_slope)
{
    switch (act) {
    case NN_ACT_RELU: return nn_relu(ctx, x);
    case NN_ACT_LEAKY_RELU: return nn_leaky_relu(ctx, x, leaky_slope);
    case NN_ACT_TANH: return nn_tanh(ctx, x);
    default: return x;
    }
}

neuv_status nn_mlp_create(nn_mlp *m, const nn_mlp_config *cfg, nn_params *params, const char *prefix)
{
    memset(m, 0, sizeof *m);
    if (cfg->depth < 1 || cfg->in <= 0 || cfg->out <= 0 || (cfg->depth > 1 && cfg->width <= 0))
        return error_set(NEUV_ERR_INPUT, "MLP '%s': depth %d, sizes %d -> %d -> %d are not usable", prefix,
                         cfg->depth, cfg->in, cfg->width, cfg->out);
    if (cfg->hidden == NN_ACT_NONE && cfg->depth > 1)
        return error_set(NEUV_ERR_INPUT, "MLP '%s': hidden activation must be relu, leaky_relu or tanh", prefix);
    if (cfg->output != NN_ACT_NONE && cfg->output != NN_ACT_TANH)
        return error_set(NEUV_ERR_INPUT, "MLP '%s': output activation must be none or tanh", prefix);
    if (cfg->dropout != 0)
        return error_set(NEUV_ERR_INPUT, "MLP '%s': dropout is not supported (set it to 0)", prefix);
    m->cfg = *cfg;
    if (m->cfg.leaky_slope == 0) m->cfg.leaky_slope = 0.01f;
    if (!(m->cfg.leaky_slope > 0 && m->cfg.leaky_slope < 1))
        return error_set(NEUV_ERR_INPUT, "MLP '%s': LeakyReLU slope %g outside (0, 1)", prefix, m->cfg.leaky_slope);
    m->layers = mem_calloc((size_t)cfg->depth, sizeof *m->layers);
    if (!m->layers) return error_nomem("MLP layers");
    m->n = cfg->depth;
    rng r;
    rng_seed(&r, cfg->seed);
    for (int i = 0; i < cfg->depth; i++) {
        int in = i == 0 ? cfg->in : cfg->width;
        int out = i == cfg->depth - 1 ? cfg->out : cfg->width;
        nn_activation act = i == cfg->depth - 1 ? cfg->output : cfg->hidden;
        char name[200];
        snprintf(name, sizeof name, "%s.%d", prefix, i);
        neuv_status st = nn_linear_create(&m->layers[i], in, out, act, &r, params, name);
        if (st != NEUV_OK) { nn_mlp_free(m); return st; }
    }
    return NEUV_OK;
}

nn_tensor *nn_mlp_forward(nn_ctx *ctx, const nn_mlp *m, nn_tensor *x)
{
    for (int i = 0; i < m->n; i++) {
        nn_activation act = i == m->n - 1 ? m->cfg.output : m->cfg.hidden;
        x = nn_linear_act(ctx, x, m->layers[i].w, m->layers[i].b, act, m->cfg.leaky_slope);
    }
    return x;
}

void nn_mlp_free(nn_mlp *m)
{
    if (!m) return;
    mem_free(m->layers);
    m->layers = NULL;
    m->n = 0;
}
