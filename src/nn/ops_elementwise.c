/* Element-wise ops: broadcasting binary arithmetic and one-input functions.
 * Each op's forward and backward rule sit together. */
#include "nn/nn_internal.h"

#include <math.h>
#include <string.h>

/* dst = v on a fresh gradient buffer, dst += v on one that already holds values. */
#define STORE(acc, dst, v) ((dst) = (acc) ? (dst) + (v) : (v))

/* ---- broadcasting binary ops: a (R by C) op b (R by C | 1 by C | R by 1 | 1 by 1) ---- */

typedef enum { BC_SAME, BC_ROW, BC_COL, BC_SCALAR } broadcast;

static broadcast broadcast_of(const nn_tensor *a, const nn_tensor *b)
{
    if (b->rows == a->rows && b->cols == a->cols) return BC_SAME;
    if (b->rows == 1 && b->cols == 1) return BC_SCALAR;
    if (b->rows == 1 && b->cols == a->cols) return BC_ROW;
    return BC_COL; /* b->cols == 1 && b->rows == a->rows, checked by the caller */
}

static inline long b_index(broadcast m, long i, long j, long cols)
{
    switch (m) {
    case BC_SAME: return i * cols + j;
    case BC_ROW: return j;
    case BC_COL: return i;
    default: return 0;
    }
}

/* z = x OP y over a rows by cols block for one broadcast mode. The loops are
 * written out per mode so the inner loop is a plain vectorizable stream
 * (gcc -O2 does not unswitch loops or version them for aliasing; omp simd
 * states that the arrays do not overlap). */
#define BROADCAST_LOOPS(EXPR)                                                              \
    switch (m) {                                                                           \
    case BC_SAME:                                                                          \
        _Pragma("omp parallel for simd if (rows * cols > NN_PAR_MIN) schedule(static)")     \
        for (long k = 0; k < rows * cols; k++) { float xv = x[k], yv = y[k]; z[k] = EXPR; } \
        break;                                                                             \
    case BC_ROW:                                                                           \
        _Pragma("omp parallel for if (rows * cols > NN_PAR_MIN) schedule(static)")          \
        for (long i = 0; i < rows; i++) {                                                  \
            _Pragma("omp simd")                                                            \
            for (long j = 0; j < cols; j++) {                                              \
                float xv = x[i * cols + j], yv = y[j]; z[i * cols + j] = EXPR; }            \
        }                                                                                  \
        break;                                                                             \
    case BC_COL:                                                                           \
        _Pragma("omp parallel for if (rows * cols > NN_PAR_MIN) schedule(static)")          \
        for (long i = 0; i < rows; i++) {                                                  \
            float yv = y[i];                                                               \
            _Pragma("omp simd")                                                            \
            for (long j = 0; j < cols; j++) { float xv = x[i * cols + j]; z[i * cols + j] = EXPR; } \
        }                                                                                  \
        break;                                                                             \
    default: {                                                                             \
        float yv = y[0];                                                                   \
        _Pragma("omp parallel for simd if (rows * cols > NN_PAR_MIN) schedule(static)")     \
        for (long k = 0; k < rows * cols; k++) { float xv = x[k]; z[k] = EXPR; }            \
    } }

static nn_tensor *binary(nn_ctx *ctx, nn_op op, nn_tensor *a, nn_tensor *b)
{
    if (NN_ANY_NULL(a, b)) return NULL;
    int ok = (b->rows == a->rows && b->cols == a->cols) || (b->rows == 1 && b->cols == 1) ||
             (b->rows == 1 && b->cols == a->cols) || (b->cols == 1 && b->rows == a->rows);
    if (!ok)
        return nn_ctx_fail(ctx, NEUV_ERR_INPUT, "%s: shapes %d by %d and %d by %d do not broadcast",
                           nn_op_name(op), a->rows, a->cols, b->rows, b->cols);
    nn_tensor *t = nn_node(ctx, op, a->rows, a->cols, a, b);
    if (!t) return NULL;
    broadcast m = broadcast_of(a, b);
    long rows = a->rows, cols = a->cols;
    const float *x = a->data, *y = b->data;
    float *z = t->data;
    switch (op) {
    case NN_OP_ADD: BROADCAST_LOOPS(xv + yv) break;
    case NN_OP_SUB: BROADCAST_LOOPS(xv - yv) break;
    case NN_OP_MUL: BROADCAST_LOOPS(xv * yv) break;
    default: BROADCAST_LOOPS(xv / yv) break;
    }
    return t;
}

nn_tensor *nn_add(nn_ctx *ctx, nn_tensor *a, nn_tensor *b) { return binary(ctx, NN_OP_ADD, a, b); }
nn_tensor *nn_sub(nn_ctx *ctx, nn_tensor *a, nn_tensor *b) { return binary(ctx, NN_OP_SUB, a, b); }
nn_tensor *nn_mul(nn_ctx *ctx, nn_tensor *a, nn_tensor *b) { return binary(ctx, NN_OP_MUL, a, b); }
nn_tensor *nn_div(nn_ctx *ctx, nn_tensor *a, nn_tensor *b) { return binary(ctx, NN_OP_DIV, a, b); }

/* d/da: 1, 1, b, 1/b.  d/db: 1, -1, a, -a/b^2.  A broadcast b sums its
 * contributions over the broadcast axis (deterministic blocked reduction). */
void nn_backward_binary(nn_ctx *ctx, nn_tensor *t)
{
    nn_tensor *a = t->src[0], *b = t->src[1];
    broadcast m = broadcast_of(a, b);
    long rows = t->rows, cols = t->cols, n = rows * cols;
    const float *g = t->grad, *x = a->data, *y = b->data;
    nn_op op = t->op;
    int acc = 0;
    float *ga = NULL;
    if (op == NN_OP_ADD && a->requires_grad && !a->grad && !a->is_param && a != b) {
        /* d(a + b)/da is the identity: a takes t's gradient buffer instead of a copy.
         * t's gradient is final here (every consumer of t came later on the tape and
         * has run), so later additions into a's gradient may reuse the storage. */
        a->grad = t->grad;
    } else {
        ga = nn_grad_for(ctx, a, &acc);
    }
    if (ga) {
#pragma omp parallel for if (n > NN_PAR_MIN) schedule(static)
        for (long i = 0; i < rows; i++)
            for (long j = 0; j < cols; j++) {
                long k = i * cols + j;
                float yb = y[b_index(m, i, j, cols)];
                float v = op == NN_OP_MUL ? g[k] * yb : op == NN_OP_DIV ? g[k] / yb : g[k];
                STORE(acc, ga[k], v);
            }
    }
    if (!b->requires_grad) return;
    /* Per-element contribution to b before any broadcast reduction. */
    float *contrib = NULL;
    if (op == NN_OP_ADD && m != BC_SAME) {
        contrib = (float *)g;
    } else {
        float *dst;
        int bacc = 0;
        if (m == BC_SAME) {
            dst = nn_grad_for(ctx, b, &bacc);
        } else {
            dst = nn_ctx_alloc(ctx, (size_t)n * sizeof(float));
        }
        if (!dst) return;
#pragma omp parallel for if (n > NN_PAR_MIN) schedule(static)
        for (long i = 0; i < rows; i++)
            for (long j = 0; j < cols; j++) {
                long k = i * cols + j;
                float yb = y[b_index(m, i, j, cols)];
                float v = op == NN_OP_ADD ? g[k] : op == NN_OP_SUB ? -g[k]
                        : op == NN_OP_MUL ? g[k] * x[k] : -g[k] * x[k] / (yb * yb);
                STORE(bacc, dst[k], v);
            }
        if (m == BC_SAME) return;
        contrib = dst;
    }
    int bacc = 0;
    float *gb = nn_grad_for(ctx, b, &bacc);
    if (!gb) return;
    if (m == BC_ROW) nn_reduce_rows(ctx, contrib, (int)rows, (int)cols, gb, bacc);
    else if (m == BC_COL) nn_reduce_cols(contrib, (int)rows, (int)cols, gb, bacc);
    else {
        float s = (float)nn_reduce_all(ctx, contrib, (size_t)n);
        STORE(bacc, gb[0], s);
    }
}

/* ---- one-input element-wise ops ------------------------------------- */

static inline float forward_unary(nn_op op, float x, float p)
{
    switch (op) {
    case NN_OP_ADD_CONST: return x + p;
    case NN_OP_SCALE: return x * p;
    case NN_OP_RELU: return x > 0 ? x : 0;
    case NN_OP_LEAKY_RELU: return x > 0 ? x : p * x;
    case NN_OP_TANH: return tanhf(x);
    case NN_OP_SIGMOID: return 1.0f / (1.0f + expf(-x));
    case NN_OP_EXP: return expf(x);
    case NN_OP_LOG: return logf(x);
    case NN_OP_SQRT: return sqrtf(x);
    case NN_OP_SQUARE: return x * x;
    default: /* NN_OP_CLAMP_MIN */ return x >= p ? x : p;
    }
}

/* Derivative dy/dx from the input x, the output y and the parameter p. */
static inline float derivative_unary(nn_op op, float x, float y, float p)
{
    switch (op) {
    case NN_OP_ADD_CONST: return 1;
    case NN_OP_SCALE: return p;
    case NN_OP_RELU: return x > 0 ? 1 : 0;
    case NN_OP_LEAKY_RELU: return x > 0 ? 1 : p;
    case NN_OP_TANH: return 1 - y * y;
    case NN_OP_SIGMOID: return y * (1 - y);
    case NN_OP_EXP: return y;
    case NN_OP_LOG: return 1 / x;
    case NN_OP_SQRT: return 0.5f / y;
    case NN_OP_SQUARE: return 2 * x;
    default: /* NN_OP_CLAMP_MIN: pass-through where not clamped (x >= min) */ return x >= p ? 1 : 0;
    }
}

#define UNARY_LOOP(EXPR)                                                           \
    _Pragma("omp parallel for simd if (n > NN_PAR_MIN) schedule(static)")           \
    for (long i = 0; i < n; i++) { float xv = x[i]; y[i] = EXPR; }

NN_VECTORIZE static nn_tensor *unary(nn_ctx *ctx, nn_op op, nn_tensor *a, float p)
{
    if (!a) return NULL;
    nn_tensor *t = nn_node(ctx, op, a->rows, a->cols, a, NULL);
    if (!t) return NULL;
    t->fparam[0] = p;
    long n = (long)a->rows * a->cols;
    const float *x = a->data;
    float *y = t->data;
    /* The cheap, hot ops get their own loops (vectorized); the rest share one. */
    switch (op) {
    case NN_OP_ADD_CONST: UNARY_LOOP(xv + p) break;
    case NN_OP_SCALE: UNARY_LOOP(xv * p) break;
    case NN_OP_RELU: UNARY_LOOP(xv > 0 ? xv : 0.0f) break;
    /* A factor chosen, then one product: the same bits as x > 0 ? x : p·x, but
     * nothing is computed under a condition, so the loop vectorizes (an
     * omp-outlined loop does not inherit NN_VECTORIZE's no-trapping-math). */
    case NN_OP_LEAKY_RELU: UNARY_LOOP((xv > 0 ? 1.0f : p) * xv) break;
    case NN_OP_SQUARE: UNARY_LOOP(xv * xv) break;
    case NN_OP_CLAMP_MIN: UNARY_LOOP(xv >= p ? xv : p) break;
    default: {
#pragma omp parallel for if (n > NN_PAR_MIN) schedule(static)
        for (long i = 0; i < n; i++) y[i] = forward_unary(op, x[i], p);
    }
    }
    return t;
}

NN_VECTORIZE void nn_backward_unary(nn_ctx *ctx, nn_tensor *t)
{
    nn_tensor *a = t->src[0];
    int acc = 0;
    float *ga = nn_grad_for(ctx, a, &acc);
    if (!ga) return;
    long n = (long)t->rows * t->cols;
    const float *g = t->grad, *x = a->data, *y = t->data;
    float p = t->fparam[0];
    nn_op op = t->op;
    /* The hot activations get their own loops so the compiler vectorizes them. */
    if (op == NN_OP_LEAKY_RELU || op == NN_OP_RELU) {
        float s = op == NN_OP_RELU ? 0.0f : p;
        if (acc) {
#pragma omp parallel for simd if (n > NN_PAR_MIN) schedule(static)
            for (long i = 0; i < n; i++) ga[i] += (x[i] > 0 ? 1.0f : s) * g[i];
        } else {
#pragma omp parallel for simd if (n > NN_PAR_MIN) schedule(static)
            for (long i = 0; i < n; i++) ga[i] = (x[i] > 0 ? 1.0f : s) * g[i];
        }
        return;
    }
#pragma omp parallel for if (n > NN_PAR_MIN) schedule(static)
    for (long i = 0; i < n; i++) {
        float v = g[i] * derivative_unary(op, x[i], y[i], p);
        STORE(acc, ga[i], v);
    }
}

nn_tensor *nn_add_const(nn_ctx *ctx, nn_tensor *a, float c) { return unary(ctx, NN_OP_ADD_CONST, a, c); }
nn_tensor *nn_scale(nn_ctx *ctx, nn_tensor *a, float c) { return unary(ctx, NN_OP_SCALE, a, c); }
nn_tensor *nn_relu(nn_ctx *ctx, nn_tensor *a) { return unary(ctx, NN_OP_RELU, a, 0); }
nn_tensor *nn_leaky_relu(nn_ctx *ctx, nn_tensor *a, float slope) { return unary(ctx, NN_OP_LEAKY_RELU, a, slope); }
nn_tensor *nn_tanh(nn_ctx *ctx, nn_tensor *a) { return unary(ctx, NN_OP_TANH, a, 0); }
nn_tensor *nn_sigmoid(nn_ctx *ctx, nn_tensor *a) { return unary(ctx, NN_OP_SIGMOID, a, 0); }
nn_tensor *nn_exp(nn_ctx *ctx, nn_tensor *a) { return unary(ctx, NN_OP_EXP, a, 0); }
nn_tensor *nn_log(nn_ctx *ctx, nn_tensor *a) { return unary(ctx, NN_OP_LOG, a, 0); }
nn_tensor *nn_sqrt(nn_ctx *ctx, nn_tensor *a) { return unary(ctx, NN_OP_SQRT, a, 0); }
nn_tensor *nn_square(nn_ctx *ctx, nn_tensor *a) { return unary(ctx, NN_OP_SQUARE, a, 0); }
nn_tensor *nn_clamp_min(nn_ctx *ctx, nn_tensor *a, float min) { return unary(ctx, NN_OP_CLAMP_MIN, a, min); }
