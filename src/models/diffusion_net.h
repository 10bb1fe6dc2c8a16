/* DiffusionNet (Sharp, Attaiki, Crane, Ovsjanikov 2022, "DiffusionNet:
 * Discretization Agnostic Learning on Surfaces", section 3 and figure 2) on
 * the neural engine (nn/nn.h):
 *
 *     x -> linear(in, C) -> N x block -> linear(C, out)
 *     block(x) = x + MLP([x, h, g])            (section 3.4)
 *         h = learned-time spectral diffusion of x    (section 3.2, eq. 5)
 *         g = spatial gradient features of h          (section 3.3, eq. 6)
 *         MLP = linear(3C, C), ReLU, linear(C, C)      (per vertex)
 *
 * Scale: the fixed operators are expressed for the mesh scaled to unit total
 * area (eigenvalues multiplied by A, gradients by sqrt(A)), so diffusion
 * times and gradient features do not depend on the units of the input — the
 * paper normalizes its meshes for the same reason.
 *
 * Lifetime: diffusion_net_create registers its parameters in a caller-owned
 * nn_params set and allocates only the block list (diffusion_net_free).
 * diffusion_net_geometry_create makes float32 copies of one mesh's operators
 * that the forward pass borrows (nn_view); free with diffusion_net_geometry_free. */
#ifndef NEUV_MODELS_DIFFUSION_NET_H
#define NEUV_MODELS_DIFFUSION_NET_H

#include <stdint.h>

#include "geometry/operators.h"
#include "mesh/mesh.h"
#include "nn/mlp.h"
#include "nn/nn.h"

/* Diffusion times are kept at or above this (the reference clamps at 1e-8). */
#define DIFFUSION_NET_MIN_TIME 1e-8f

typedef struct diffusion_net_config {
    int in;        /* input channels per vertex */
    int width;     /* C, hidden channels (paper: 128) */
    int out;       /* output channels per vertex */
    int blocks;    /* N (paper: 4) */
    uint64_t seed; /* initialization seed */
} diffusion_net_config;

/* One block's parameters: per-channel diffusion times (1 by C), the real and
 * imaginary parts of the learned gradient rotation (C by C each, no bias),
 * and the two-layer per-vertex MLP. */
typedef struct diffusion_net_block {
    nn_tensor *time;
    nn_tensor *rot_re, *rot_im;
    nn_linear mlp0, mlp1;
} diffusion_net_block;

typedef struct diffusion_net {
    diffusion_net_config cfg;
    nn_linear first, last;
    diffusion_net_block *block; /* cfg.blocks */
} diffusion_net;

/* The fixed per-mesh operators in float32, shaped for the forward pass. */
typedef struct diffusion_net_geometry {
    int nv, nf, k;
    float *evecs;      /* #V by k, M-orthonormal columns */
    float *neg_evals;  /* k by 1: -λ_i · A (unit-area eigenvalues, negated) */
    float *mass;       /* #V by 1: lumped mass / A */
    nn_sparse grad_x, grad_y; /* #V by #V, times sqrt(A) */
    int *face_vertex;  /* 3 by #F: corner c of face f at [c * #F + f] (gathers) */
} diffusion_net_geometry;

/* Builds the network and registers its parameters as "<prefix>.first.w",
 * "<prefix>.block<i>.time", ".rot_re", ".rot_im", ".mlp0.w", ... in params.
 * Times start log-spaced over [1e-4, 1e-1] (unit-area units) across channels,
 * so the blocks see short and long range diffusion from the first step.
 * Inputs: cfg (all sizes >= 1), prefix (parameter names)
 * Outputs: net (free with diffusion_net_free), params gains the parameters */
neuv_status diffusion_net_create(diffusion_net *net, const diffusion_net_config *cfg, nn_params *params,
                                 const char *prefix);
void diffusion_net_free(diffusion_net *net);

/* Float32 copies of the operators a forward pass needs.
 * Inputs:  m    mesh the operators were computed on (#V, #F by 3)
 *          ops  its operators (L, mass, evals, evecs, grad_x, grad_y)
 *          k    eigenpairs to use (<= ops->k; <= 0 means all of ops->k)
 * Outputs: g    (free with diffusion_net_geometry_free) */
neuv_status diffusion_net_geometry_create(const neuv_mesh *m, const operators *ops, int k,
                                          diffusion_net_geometry *g);
void diffusion_net_geometry_free(diffusion_net_geometry *g);

/* Clamps every diffusion time to DIFFUSION_NET_MIN_TIME in place, outside
 * the tape (as the reference does before each forward pass), so a time that
 * Adam pushed negative restarts from a tiny positive value with a gradient. */
void diffusion_net_clamp_times(diffusion_net *net);

/* Learned-time spectral diffusion (paper eq. 5): with c = Φᵀ(M x) (k by C),
 * h = Φ (exp(−λ tᵀ) ⊙ c).
 * Inputs: x #V by C, time 1 by C (positive). Output: #V by C. */
nn_tensor *learned_time_diffusion(nn_ctx *ctx, const diffusion_net_geometry *g, nn_tensor *x, nn_tensor *time);

/* Spatial gradient features (paper eq. 6) with learned rotations: gradients
 * w = G_x h + i G_y h per channel, rotated w' = (A_re + i A_im) w across
 * channels, feature tanh(Re(conj(w) ⊙ w'))
 *     = tanh(g_x ⊙ (g_x A_re − g_y A_im) + g_y ⊙ (g_y A_re + g_x A_im)).
 * Inputs: h #V by C, rot_re and rot_im C by C. Output: #V by C. */
nn_tensor *spatial_gradient_features(nn_ctx *ctx, const diffusion_net_geometry *g, nn_tensor *h,
                                     nn_tensor *rot_re, nn_tensor *rot_im);

/* One block: x + MLP([x, h, grad features]). x #V by C -> #V by C. */
nn_tensor *diffusion_net_block_forward(nn_ctx *ctx, const diffusion_net_block *b,
                                       const diffusion_net_geometry *g, nn_tensor *x);

/* The whole network.
 * Inputs:  x       #V by cfg.in vertex features
 * Outputs: returns #V by cfg.out; *hidden (may be NULL) the last block's
 *          output, #V by C (the per-vertex features later stages pool) */
nn_tensor *diffusion_net_forward(nn_ctx *ctx, const diffusion_net *net, const diffusion_net_geometry *g,
                                 nn_tensor *x, nn_tensor **hidden);

/* Face values as the mean of their three vertices' values.
 * Inputs: x #V by C. Output: #F by C. */
nn_tensor *diffusion_net_vertices_to_faces(nn_ctx *ctx, const diffusion_net_geometry *g, nn_tensor *x);

/* Input features for the network, float32 #V by *dim (caller frees *out).
 * "hks": the operators' heat kernel signatures (invariant to rigid motions
 * and scale); "xyz": positions minus their area-weighted centroid, scaled so
 * the farthest vertex is at distance 1; "hks+normals": the signatures and
 * the unit vertex normals (area-weighted face normals; invariant to
 * translation and scale, not rotation), so that parts the signatures cannot
 * tell apart (a cube's sides) can still be told apart by their direction. */
typedef enum diffusion_net_features {
    DIFFUSION_NET_HKS = 0,
    DIFFUSION_NET_XYZ = 1,
    DIFFUSION_NET_HKS_NORMALS = 2
} diffusion_net_features;
neuv_status diffusion_net_input_features(const neuv_mesh *m, const operators *ops, diffusion_net_features f,
                                         float **out, int *dim);
/* "hks", "xyz", "hks+normals" (the values 0, 1, 2, as model files name
 * them); NULL for another value. */
const char *diffusion_net_features_name(diffusion_net_features f);

#endif
