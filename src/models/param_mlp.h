/* The MLP of the surface parameterization module, conditioned on a chart code
 * ψ (Pokhariya et al. 2022, section 3.2: MLP_f(x, ψ) -> uv and
 * MLP_f⁻¹(uv, ψ) -> x): LeakyReLU between layers, tanh on the output.
 *
 * The first layer is the linear layer of the concatenation [x ψ], stored as
 * two blocks, h = x W_x + ψ W_ψ + b. When ψ is one row per chart (pooled),
 * ψ W_ψ is computed once per chart and gathered per point, so the ψ half of
 * the first layer costs #charts rows instead of #points rows; the result is
 * the same as feeding [x ψ] to one linear layer.
 */
#ifndef NEUV_MODELS_PARAM_MLP_H
#define NEUV_MODELS_PARAM_MLP_H

#include "nn/mlp.h"
#include "nn/nn.h"

struct rng;

typedef struct param_mlp {
    int in, psi, width, out, depth;
    float slope;                 /* LeakyReLU slope */
    nn_tensor *w_x, *w_psi, *b0; /* first layer: in by W, psi by W, 1 by W (W = width, or out if depth 1) */
    nn_linear *rest;             /* depth - 1 layers */
    int fourier;                 /* Fourier directions the per-chart heads also read (0: none);
                                    set after param_mlp_create, which leaves it 0 */
} param_mlp;

/* Registers the layers as "<prefix>.0.wx", "<prefix>.0.wpsi", "<prefix>.0.b",
 * "<prefix>.<l>.w/b" in `params`, initialized from r (Kaiming-uniform for the
 * LeakyReLU layers over the first layer's whole fan-in in + psi, Xavier for the
 * tanh output layer). psi may be 0 (unconditioned).
 * Returns NEUV_OK, NEUV_ERR_INPUT (bad sizes) or NEUV_ERR_NOMEM. */
neuv_status param_mlp_create(param_mlp *m, int in, int psi, int width, int out, int depth, float slope,
                             struct rng *r, nn_params *params, const char *prefix);
void param_mlp_free(param_mlp *m);

/* Inputs:  x        #N by in
 *          psi      #C by psi (NULL when m->psi == 0)
 *          psi_row  #N row of psi for each point, or NULL when psi has #N rows
 * Output:  #N by out, in (-1, 1). */
nn_tensor *param_mlp_forward(nn_ctx *ctx, const param_mlp *m, nn_tensor *x, nn_tensor *psi,
                             const int *psi_row);

/* The last hidden layer's activations (#N by width), the input of the
 * output layer m->rest[depth - 2]: forward = tanh(hidden W + b).
 * NULL when depth < 2 (no hidden layer) or on failure. */
nn_tensor *param_mlp_hidden(nn_ctx *ctx, const param_mlp *m, nn_tensor *x, nn_tensor *psi, const int *psi_row);

/* What a per-chart output layer reads (param_output_solve.h): the Fourier
 * features of x (below; none when m->fourier is 0), then every hidden
 * layer's activations, the first hidden layer first and the last hidden
 * layer last (#N by param_mlp_head_width(m) = fourier width + width x
 * (depth - 1)). NULL when depth < 2 or on failure. */
int param_mlp_head_width(const param_mlp *m);

/* With m->fourier = k > 0, a head also reads, before the hidden layers,
 * param_mlp_fourier_width(m) = 3 + 2k fixed features of the input point x
 * (the chart's normalized frame): x itself, then sin and cos of ω_j d_j·x for
 * j < k, d_j the j-th point of a Fibonacci lattice on the unit sphere and
 * ω_j = (π / 1.2) 2^(j mod 3): a chart spans about 1.2 normalized units, so
 * half a period, one and two periods across it. No weights: they are a
 * function of the surface point only, whatever the triangulation.
 * param_mlp_fourier_features writes them for n points (x rows `stride`
 * floats apart) into out (#n by the width). 0 when k = 0. */
int param_mlp_fourier_width(const param_mlp *m);
void param_mlp_fourier_features(const param_mlp *m, const float *x, int n, int stride, float *out);
nn_tensor *param_mlp_head_features(nn_ctx *ctx, const param_mlp *m, nn_tensor *x, nn_tensor *psi, const int *psi_row);

#endif
