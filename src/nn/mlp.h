/* Linear layers and multilayer perceptrons built on nn/nn.h. */
#ifndef NEUV_NN_MLP_H
#define NEUV_NN_MLP_H

#include <stdint.h>
#include "nn/nn.h"

/* y = x W + b with W #in by #out and b 1 by #out, both registered in a parameter set. */
typedef struct nn_linear {
    int in, out;
    nn_tensor *w, *b;
} nn_linear;

/* Creates W and b named "<prefix>.w" and "<prefix>.b" in `params`. Initialization
 * (seeded by r): Kaiming-uniform U(-sqrt(6/in), sqrt(6/in)) for ReLU-family layers
 * (He et al. 2015, gain sqrt(2)), Xavier-uniform U(-sqrt(6/(in+out)), ...) for tanh
 * and linear outputs (Glorot & Bengio 2010); biases zero. */
struct rng;
neuv_status nn_linear_create(nn_linear *l, int in, int out, nn_activation act,
                             struct rng *r, nn_params *params, const char *prefix);
/* x: #N by in -> #N by out (no activation). */
nn_tensor *nn_linear_forward(nn_ctx *ctx, const nn_linear *l, nn_tensor *x);
/* Applies an activation (NN_ACT_NONE returns x). */
nn_tensor *nn_activate(nn_ctx *ctx, nn_tensor *x, nn_activation act, float leaky_slope);

typedef struct nn_mlp_config {
    int in, width, out;   /* input, hidden and output widths */
    int depth;            /* number of linear layers (>= 1); depth 8 = paper's MLPs */
    nn_activation hidden; /* relu | leaky_relu | tanh */
    nn_activation output; /* none | tanh */
    float leaky_slope;    /* LeakyReLU slope (0 -> 0.01) */
    float dropout;        /* must be 0: dropout is not implemented (off by default) */
    uint64_t seed;        /* initialization seed */
} nn_mlp_config;

typedef struct nn_mlp {
    nn_mlp_config cfg;
    int n;                /* = depth */
    nn_linear *layers;
} nn_mlp;

/* Builds depth linear layers named "<prefix>.<i>.w/b" in `params`. */
neuv_status nn_mlp_create(nn_mlp *m, const nn_mlp_config *cfg, nn_params *params,
                          const char *prefix);
/* x: #N by in -> #N by out. */
nn_tensor *nn_mlp_forward(nn_ctx *ctx, const nn_mlp *m, nn_tensor *x);
/* Frees the layer list (the parameters belong to the nn_params set). */
void nn_mlp_free(nn_mlp *m);

#endif
