/* Internals shared by the op files: tensor creation on the tape, error
 * recording, gradient buffers and the per-op backward table. Not for models. */
#ifndef NEUV_NN_INTERNAL_H
#define NEUV_NN_INTERNAL_H

#include "nn/nn.h"

/* Element counts above which element-wise loops use OpenMP (below it, thread
 * start-up costs more than the work). */
#define NN_PAR_MIN 32768

/* On a function whose loops select between floats (LeakyReLU): without it gcc
 * keeps them scalar, because a select after a comparison that may raise an FP
 * flag is not if-converted under -ftrapping-math. neuv never reads FP flags.
 * noinline: inlined into a caller without the attribute, the loops lose it. */
#define NN_VECTORIZE __attribute__((optimize("no-trapping-math"), noinline))

/* Records the first failure of this ctx (message kept) and returns NULL. */
nn_tensor *nn_ctx_fail(nn_ctx *ctx, neuv_status code, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
/* A new op result on the tape, rows by cols, data allocated (uninitialized);
 * requires_grad inherited from the sources. NULL (ctx failed) on no memory. */
nn_tensor *nn_node(nn_ctx *ctx, nn_op op, int rows, int cols, nn_tensor *a, nn_tensor *b);
/* True when any input is NULL (the ctx already holds the error). */
#define NN_ANY_NULL(a, b) ((a) == NULL || (b) == NULL)

/* Gradient buffer of t for the backward pass. Returns NULL when t needs no
 * gradient. *accumulate is 1 when the buffer already holds values (add into it)
 * and 0 when it is fresh and uninitialized (the caller must write every entry). */
float *nn_grad_for(nn_ctx *ctx, nn_tensor *t, int *accumulate);
/* Same, but a fresh buffer is zeroed (for scatter-style backward rules). */
float *nn_grad_zeroed(nn_ctx *ctx, nn_tensor *t);

/* Deterministic reductions (fixed blocks, fixed combination order).
 * out[j] (+)= sum_i x[i*cols + j] ; out[i] (+)= sum_j x[i*cols + j]; total. */
void nn_reduce_rows(nn_ctx *ctx, const float *x, int rows, int cols, float *out, int accumulate);
void nn_reduce_cols(const float *x, int rows, int cols, float *out, int accumulate);
double nn_reduce_all(nn_ctx *ctx, const float *x, size_t n);

/* Backward rules: one per op, defined beside the op's forward. */
typedef void (*nn_backward_fn)(nn_ctx *ctx, nn_tensor *t);
void nn_backward_matmul(nn_ctx *, nn_tensor *);
void nn_backward_linear(nn_ctx *, nn_tensor *);
void nn_backward_spmm(nn_ctx *, nn_tensor *);
void nn_backward_binary(nn_ctx *, nn_tensor *);      /* add, sub, mul, div */
void nn_backward_unary(nn_ctx *, nn_tensor *);       /* element-wise one-input ops */
void nn_backward_reduce(nn_ctx *, nn_tensor *);      /* sum, mean */
void nn_backward_softmax_rows(nn_ctx *, nn_tensor *);
void nn_backward_row_norm(nn_ctx *, nn_tensor *);
void nn_backward_row_dot(nn_ctx *, nn_tensor *);
void nn_backward_row_cosine(nn_ctx *, nn_tensor *);
void nn_backward_concat_cols(nn_ctx *, nn_tensor *);
void nn_backward_slice_cols(nn_ctx *, nn_tensor *);
void nn_backward_gather_rows(nn_ctx *, nn_tensor *);
void nn_backward_scatter_add_rows(nn_ctx *, nn_tensor *);

#endif
