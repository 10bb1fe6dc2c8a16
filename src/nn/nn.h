/* neuv's neural engine: float32 2-D tensors, reverse-mode differentiation,
 * parameters. Layers are in nn/mlp.h, the optimizer in nn/adam.h, the file
 * format in nn/checkpoint.h.
 *
 * Usage (one training step of a 2-layer MLP on a batch; see tests/test_nn_train.c):
 *
 *     nn_params params;  nn_params_init(&params);
 *     nn_mlp mlp;        // 3 -> 64 -> 2, LeakyReLU hidden, tanh out
 *     nn_mlp_config cfg = { .in = 3, .width = 64, .out = 2, .depth = 2,
 *                           .hidden = NN_ACT_LEAKY_RELU, .output = NN_ACT_TANH,
 *                           .leaky_slope = 0.01f, .seed = 1 };
 *     nn_mlp_create(&mlp, &cfg, &params, "mlp");   // registers mlp.0.w, mlp.0.b, ...
 *     nn_adam adam;      nn_adam_init(&adam, &params, NULL);   // NULL: lr 1e-3, betas 0.9/0.999
 *     nn_ctx *ctx = nn_ctx_create(0);                 // arena grows during step 1 only
 *     for (int step = 0; step < steps; step++) {
 *         nn_ctx_reset(ctx);                          // frees every intermediate at once
 *         nn_tensor *x = nn_from(ctx, batch, 3, xs);  // copies into the arena
 *         nn_tensor *t = nn_from(ctx, batch, 2, targets);
 *         nn_tensor *y = nn_mlp_forward(ctx, &mlp, x);
 *         nn_tensor *loss = nn_mean(ctx, nn_square(ctx, nn_sub(ctx, y, t)), NN_ALL);
 *         nn_params_zero_grad(&params);
 *         if (nn_backward(ctx, loss) != NEUV_OK) ...  // also reports any op error since reset
 *         nn_adam_step(&adam);
 *     }
 *     nn_checkpoint_save_params("m.neuv", "{\"width\":64}", &params);
 *     nn_ctx_free(ctx); nn_adam_free(&adam); nn_mlp_free(&mlp); nn_params_free(&params);
 *
 * Lifetimes: every tensor made by an op lives in its nn_ctx arena until the
 * next nn_ctx_reset. Parameters (nn_param_create) are heap objects owned by an
 * nn_params set; they outlive resets and carry a persistent grad buffer that
 * nn_backward ADDS into (zero it each step). Index arrays and sparse matrices
 * passed to ops are borrowed: they must stay alive until nn_backward returns.
 *
 * Errors: an op given a NULL input or mismatched shapes returns NULL and records
 * the first failure (one-line message) in the ctx; later ops on NULL return NULL,
 * so a whole forward pass can be written without checks and tested once with
 * nn_ctx_status() or nn_backward(). No op prints, asserts on input or exits.
 *
 * Gradients of inputs: set `x->requires_grad = 1` on a leaf before using it and
 * nn_backward leaves dL/dx in x->grad (arena memory). After backward, the grad of
 * an intermediate may share storage with another's (add passes its buffer on),
 * so read only leaf and parameter grads.
 *
 * Ops evaluate eagerly (the forward value is ready when the op returns) and
 * record themselves on the ctx tape; nn_backward walks the tape backwards.
 * Broadcasting: the second operand of add/sub/mul/div may be the same shape,
 * a row vector 1 by C, a column vector R by 1 or a scalar 1 by 1.
 * Determinism: no atomics; reductions use fixed blocks combined in a fixed
 * order, so results are identical for a seed and a thread count. */
#ifndef NEUV_NN_NN_H
#define NEUV_NN_NN_H

#include <stddef.h>
#include "neuv/neuv.h"

typedef enum nn_op {
    NN_OP_LEAF = 0,       /* input, constant or parameter */
    NN_OP_MATMUL,         /* op(A) op(B), iparam[0..1] = transpose flags */
    NN_OP_ADD,            /* a + b (b broadcast) */
    NN_OP_SUB,            /* a - b */
    NN_OP_MUL,            /* a * b element-wise */
    NN_OP_DIV,            /* a / b element-wise */
    NN_OP_ADD_CONST,      /* a + fparam[0] */
    NN_OP_SCALE,          /* a * fparam[0] */
    NN_OP_SUM,            /* iparam[0] = axis: NN_ALL (1x1), NN_ROWS (1xC), NN_COLS (Rx1) */
    NN_OP_MEAN,           /* like SUM, divided by the count */
    NN_OP_CONCAT_COLS,    /* [a b] */
    NN_OP_SLICE_COLS,     /* a[:, iparam[0] : iparam[0]+cols] */
    NN_OP_GATHER_ROWS,    /* out[i] = a[index[i]] */
    NN_OP_SCATTER_ADD_ROWS, /* out (iparam[0] rows) = 0; out[index[i]] += a[i] */
    NN_OP_SPMM,           /* S a, S a fixed sparse matrix (nn_sparse) */
    NN_OP_RELU,
    NN_OP_LEAKY_RELU,     /* slope fparam[0] for x < 0 */
    NN_OP_TANH,
    NN_OP_SIGMOID,
    NN_OP_SOFTMAX_ROWS,   /* softmax along each row */
    NN_OP_EXP,
    NN_OP_LOG,
    NN_OP_SQRT,
    NN_OP_SQUARE,
    NN_OP_ROW_NORM,       /* sqrt(sum_j a_ij^2 + eps), R by 1, eps = fparam[0] */
    NN_OP_ROW_DOT,        /* sum_j a_ij b_ij, R by 1 */
    NN_OP_ROW_COSINE,     /* dot / (norm_eps(a) norm_eps(b)), R by 1 */
    NN_OP_CLAMP_MIN,      /* max(a, fparam[0]); grad passes where a >= min, else 0 */
    NN_OP_LINEAR,         /* act(x W + b): src x, W, b; iparam[0] = activation, fparam[0] = slope */
    NN_OP_COUNT
} nn_op;

enum { NN_ALL = -1, NN_ROWS = 0, NN_COLS = 1 }; /* reduction axes */

/* Activations of the fused linear op and of the layers in nn/mlp.h. */
typedef enum nn_activation {
    NN_ACT_NONE = 0,
    NN_ACT_RELU,
    NN_ACT_LEAKY_RELU,
    NN_ACT_TANH
} nn_activation;

typedef struct nn_tensor {
    int rows, cols;          /* row-major, element (i, j) at data[i*cols + j] */
    float *data;
    float *grad;             /* same shape; NULL until backward reaches it (params: always) */
    nn_op op;
    struct nn_tensor *src[3];
    int iparam[2];
    float fparam[1];
    const void *aux;         /* borrowed: const int *index (gather/scatter), const nn_sparse * */
    int requires_grad;       /* a parameter is upstream */
    int is_param;
    int grad_fresh;          /* backward: grad not yet written this pass (overwrite, don't add) */
    struct nn_tensor *prev;  /* tape link (arena tensors) */
    const char *name;        /* parameters: the checkpoint name */
} nn_tensor;

/* ---- per-step arena and tape ---------------------------------------- */

typedef struct nn_ctx nn_ctx;

/* Creates a context whose arena starts with `initial_bytes` (0: grows on demand;
 * a reset after growth merges the blocks so later identical steps never allocate). */
nn_ctx *nn_ctx_create(size_t initial_bytes);
void nn_ctx_free(nn_ctx *ctx);
/* Forgets every tensor made since the last reset (no free, no malloc). */
void nn_ctx_reset(nn_ctx *ctx);
/* First error since the last reset (NEUV_OK if none); message via neuv_last_error(). */
neuv_status nn_ctx_status(const nn_ctx *ctx);
/* Number of heap allocations the arena has made since creation (tests assert it stops rising). */
size_t nn_ctx_grow_count(const nn_ctx *ctx);
/* Bytes in use since the last reset, and bytes reserved. */
size_t nn_ctx_bytes_used(const nn_ctx *ctx);
size_t nn_ctx_bytes_reserved(const nn_ctx *ctx);
/* Scratch memory from the arena (16-byte aligned), valid until reset; NULL on failure. */
void *nn_ctx_alloc(nn_ctx *ctx, size_t bytes);

/* ---- leaves ---------------------------------------------------------- */

/* Uninitialized rows by cols constant in the arena. */
nn_tensor *nn_new(nn_ctx *ctx, int rows, int cols);
/* Arena copy of `data` (rows*cols floats); a constant (no gradient). */
nn_tensor *nn_from(nn_ctx *ctx, int rows, int cols, const float *data);
/* Constant that borrows `data` without copying (fixed matrices: eigenvectors). */
nn_tensor *nn_view(nn_ctx *ctx, int rows, int cols, float *data);
/* Constant filled with `value`. */
nn_tensor *nn_fill(nn_ctx *ctx, int rows, int cols, float value);

/* ---- parameters ------------------------------------------------------ */

/* A heap parameter (data and grad zeroed), owned by the caller or an nn_params set. */
nn_tensor *nn_param_create(int rows, int cols, const char *name);
void nn_param_free(nn_tensor *p);

/* An ordered set of named parameters (the unit of Adam and checkpoints). */
typedef struct nn_params {
    int n, cap;
    nn_tensor **t;
} nn_params;
void nn_params_init(nn_params *ps);
/* Creates a parameter named `name` (copied), zero-filled, owned by the set; NULL on failure
 * (duplicate name, bad shape, no memory) with neuv_last_error set. */
nn_tensor *nn_params_add(nn_params *ps, int rows, int cols, const char *name);
nn_tensor *nn_params_find(const nn_params *ps, const char *name);
size_t nn_params_count(const nn_params *ps); /* scalars in all parameters */
void nn_params_zero_grad(nn_params *ps);
void nn_params_free(nn_params *ps);

/* ---- ops (forward now, backward recorded) --------------------------- */

nn_tensor *nn_matmul(nn_ctx *ctx, nn_tensor *a, nn_tensor *b);             /* a b */
nn_tensor *nn_matmul_t(nn_ctx *ctx, nn_tensor *a, int transpose_a,
                       nn_tensor *b, int transpose_b);                       /* op(a) op(b) */
nn_tensor *nn_add(nn_ctx *ctx, nn_tensor *a, nn_tensor *b);
nn_tensor *nn_sub(nn_ctx *ctx, nn_tensor *a, nn_tensor *b);
nn_tensor *nn_mul(nn_ctx *ctx, nn_tensor *a, nn_tensor *b);
nn_tensor *nn_div(nn_ctx *ctx, nn_tensor *a, nn_tensor *b);
nn_tensor *nn_add_const(nn_ctx *ctx, nn_tensor *a, float c);
nn_tensor *nn_scale(nn_ctx *ctx, nn_tensor *a, float c);
nn_tensor *nn_sum(nn_ctx *ctx, nn_tensor *a, int axis);   /* NN_ALL, NN_ROWS, NN_COLS */
nn_tensor *nn_mean(nn_ctx *ctx, nn_tensor *a, int axis);
nn_tensor *nn_concat_cols(nn_ctx *ctx, nn_tensor *a, nn_tensor *b);
nn_tensor *nn_slice_cols(nn_ctx *ctx, nn_tensor *a, int first, int count);
/* n rows: out[i] = a[index[i]], 0 <= index[i] < a->rows (checked). */
nn_tensor *nn_gather_rows(nn_ctx *ctx, nn_tensor *a, const int *index, int n);
/* out_rows by a->cols: zero, then out[index[i]] += a[i] for i < a->rows (checked). */
nn_tensor *nn_scatter_add_rows(nn_ctx *ctx, nn_tensor *a, const int *index, int out_rows);
nn_tensor *nn_relu(nn_ctx *ctx, nn_tensor *a);
nn_tensor *nn_leaky_relu(nn_ctx *ctx, nn_tensor *a, float slope);
nn_tensor *nn_tanh(nn_ctx *ctx, nn_tensor *a);
nn_tensor *nn_sigmoid(nn_ctx *ctx, nn_tensor *a);
nn_tensor *nn_softmax_rows(nn_ctx *ctx, nn_tensor *a);
nn_tensor *nn_exp(nn_ctx *ctx, nn_tensor *a);
nn_tensor *nn_log(nn_ctx *ctx, nn_tensor *a);
nn_tensor *nn_sqrt(nn_ctx *ctx, nn_tensor *a);
nn_tensor *nn_square(nn_ctx *ctx, nn_tensor *a);
nn_tensor *nn_row_norm(nn_ctx *ctx, nn_tensor *a, float eps);
nn_tensor *nn_row_dot(nn_ctx *ctx, nn_tensor *a, nn_tensor *b);
/* Cosine of the angle between row i of a and row i of b (angle losses without acos). */
nn_tensor *nn_row_cosine(nn_ctx *ctx, nn_tensor *a, nn_tensor *b, float eps);
/* max(a, min). Gradient convention: passes through where a >= min, zero where clamped
 * (as torch.clamp); keep learned quantities positive by clamping in the forward pass. */
nn_tensor *nn_clamp_min(nn_ctx *ctx, nn_tensor *a, float min);

/* Fused layer y = act(x W + b): x #N by in, W in by out, b 1 by out. Same values
 * and gradients as nn_activate(nn_add(nn_matmul(x, W), b)) but the bias, the
 * activation and their gradients (and the bias's column sums) each take one
 * pass over the #N by out result instead of two or three. leaky_slope must be
 * > 0 for NN_ACT_LEAKY_RELU (the backward reads the sign from the output). */
nn_tensor *nn_linear_act(nn_ctx *ctx, nn_tensor *x, nn_tensor *w, nn_tensor *b, nn_activation act,
                         float leaky_slope);

/* ---- fixed sparse matrices (gradient operators, mass) --------------- */

/* Float32 CSR copy of a geometry operator plus its transpose (for the backward
 * product, computed row-parallel without atomics). */
typedef struct nn_sparse {
    int rows, cols;
    int *row_start, *col; float *val;       /* A   */
    int *t_row_start, *t_col; float *t_val; /* A^T */
} nn_sparse;
/* A borrowed float64 CSR matrix to copy from: row_start #rows+1, col and val
 * #nnz with columns sorted within each row (the fields of geometry's
 * sparse_matrix, so a caller fills it from one; nn itself knows no geometry). */
typedef struct nn_csr {
    int rows, cols;
    const int *row_start, *col;
    const double *val;
} nn_csr;
neuv_status nn_sparse_from_csr(const nn_csr *a, nn_sparse *out);
void nn_sparse_free(nn_sparse *s);
/* out = S a: S is #R by #C, a is #C by k, out #R by k. */
nn_tensor *nn_spmm(nn_ctx *ctx, const nn_sparse *s, nn_tensor *a);

/* ---- differentiation ------------------------------------------------- */

/* Reverse-mode pass from a 1 by 1 `loss`: fills the grad of every tensor that
 * depends on a parameter and ADDS into parameter grads. Returns the first op
 * error since the last reset, or NEUV_ERR_INPUT when loss is not a scalar. */
neuv_status nn_backward(nn_ctx *ctx, nn_tensor *loss);

/* Op name ("matmul", ...), for messages and tests. */
const char *nn_op_name(nn_op op);

/* ---- threads --------------------------------------------------------- */

/* Sets the OpenMP threads to n (n <= 0: leaves them as they are) and OpenBLAS
 * to one thread. Element-wise loops above a size threshold and large products both run
 * on the OpenMP threads (a product is cut into row or column blocks, each one
 * single-threaded OpenBLAS call), because OpenBLAS's own pthread pool and
 * libgomp's pool spin-wait and steal each other's cores when they alternate.
 * OpenBLAS's own split of a product also depends on its thread count, which
 * changed results at the last bits between thread counts; so every BLAS call,
 * in nn or not, runs on one thread. */
void nn_set_threads(int n);

#endif
