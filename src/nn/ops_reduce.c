/* Reductions (sum, mean), row-wise ops (softmax, norm, dot, cosine) and the
 * deterministic reduction kernels the backward rules share. */
#include "nn/nn_internal.h"

#include <math.h>
#include <string.h>

#define STORE(acc, dst, v) ((dst) = (acc) ? (dst) + (v) : (v))

/* Blocks are fixed by the data size, never by the thread count, and partial
 * sums are combined in block order: the same bits for any number of threads. */
#define ROW_BLOCK 256
#define FLAT_BLOCK 4096

void nn_reduce_rows(nn_ctx *ctx, const float *x, int rows, int cols, float *out, int accumulate)
{
    long nblocks = (rows + ROW_BLOCK - 1) / ROW_BLOCK;
    double *part = nn_ctx_alloc(ctx, (size_t)nblocks * (size_t)cols * sizeof(double));
    if (!part) return;
#pragma omp parallel for if ((long)rows * cols > NN_PAR_MIN) schedule(static)
    for (long blk = 0; blk < nblocks; blk++) {
        double *p = part + blk * cols;
        for (long j = 0; j < cols; j++) p[j] = 0;
        long end = (blk + 1) * ROW_BLOCK < rows ? (blk + 1) * ROW_BLOCK : rows;
        for (long i = blk * ROW_BLOCK; i < end; i++) {
            const float *r = x + i * cols;
            for (long j = 0; j < cols; j++) p[j] += r[j];
        }
    }
    for (long j = 0; j < cols; j++) {
        double s = 0;
        for (long blk = 0; blk < nblocks; blk++) s += part[blk * cols + j];
        STORE(accumulate, out[j], (float)s);
    }
}

void nn_reduce_cols(const float *x, int rows, int cols, float *out, int accumulate)
{
#pragma omp parallel for if ((long)rows * cols > NN_PAR_MIN) schedule(static)
    for (long i = 0; i < rows; i++) {
        double s = 0;
        const float *r = x + i * (long)cols;
        for (long j = 0; j < cols; j++) s += r[j];
        STORE(accumulate, out[i], (float)s);
    }
}

double nn_reduce_all(nn_ctx *ctx, const float *x, size_t n)
{
    long nblocks = (long)((n + FLAT_BLOCK - 1) / FLAT_BLOCK);
    double *part = nn_ctx_alloc(ctx, (size_t)nblocks * sizeof(double));
    if (!part) return NAN;
#pragma omp parallel for if ((long)n > NN_PAR_MIN) schedule(static)
    for (long blk = 0; blk < nblocks; blk++) {
        size_t end = (size_t)(blk + 1) * FLAT_BLOCK < n ? (size_t)(blk + 1) * FLAT_BLOCK : n;
        double s = 0;
        for (size_t i = (size_t)blk * FLAT_BLOCK; i < end; i++) s += x[i];
        part[blk] = s;
    }
    double s = 0;
    for (long blk = 0; blk < nblocks; blk++) s += part[blk];
    return s;
}

/* ---- sum and mean ---------------------------------------------------- */

static nn_tensor *reduce(nn_ctx *ctx, nn_op op, nn_tensor *a, int axis)
{
    if (!a) return NULL;
    if (axis != NN_ALL && axis != NN_ROWS && axis != NN_COLS)
        return nn_ctx_fail(ctx, NEUV_ERR_INPUT, "%s: unknown axis %d", nn_op_name(op), axis);
    int rows = axis == NN_COLS ? a->rows : 1;
    int cols = axis == NN_ROWS ? a->cols : 1;
    nn_tensor *t = nn_node(ctx, op, rows, cols, a, NULL);
    if (!t) return NULL;
    t->iparam[0] = axis;
    double count = axis == NN_ALL ? (double)a->rows * a->cols : axis == NN_ROWS ? a->rows : a->cols;
    if (axis == NN_ALL) t->data[0] = (float)nn_reduce_all(ctx, a->data, (size_t)a->rows * a->cols);
    else if (axis == NN_ROWS) nn_reduce_rows(ctx, a->data, a->rows, a->cols, t->data, 0);
    else nn_reduce_cols(a->data, a->rows, a->cols, t->data, 0);
    if (op == NN_OP_MEAN)
        for (int i = 0; i < rows * cols; i++) t->data[i] = (float)(t->data[i] / count);
    return t;
}

nn_tensor *nn_sum(nn_ctx *ctx, nn_tensor *a, int axis) { return reduce(ctx, NN_OP_SUM, a, axis); }
nn_tensor *nn_mean(nn_ctx *ctx, nn_tensor *a, int axis) { return reduce(ctx, NN_OP_MEAN, a, axis); }

/* Each input element receives the gradient of the sum it fed (divided by the count for mean). */
void nn_backward_reduce(nn_ctx *ctx, nn_tensor *t)
{
    nn_tensor *a = t->src[0];
    int acc = 0;
    float *ga = nn_grad_for(ctx, a, &acc);
    if (!ga) return;
    int axis = t->iparam[0];
    long rows = a->rows, cols = a->cols;
    float scale = 1.0f;
    if (t->op == NN_OP_MEAN)
        scale = (float)(1.0 / (axis == NN_ALL ? (double)rows * cols : axis == NN_ROWS ? rows : cols));
    const float *g = t->grad;
#pragma omp parallel for if (rows * cols > NN_PAR_MIN) schedule(static)
    for (long i = 0; i < rows; i++)
        for (long j = 0; j < cols; j++) {
            float gi = axis == NN_ALL ? g[0] : axis == NN_ROWS ? g[j] : g[i];
            STORE(acc, ga[i * cols + j], gi * scale);
        }
}

/* ---- softmax along rows --------------------------------------------- */

nn_tensor *nn_softmax_rows(nn_ctx *ctx, nn_tensor *a)
{
    if (!a) return NULL;
    nn_tensor *t = nn_node(ctx, NN_OP_SOFTMAX_ROWS, a->rows, a->cols, a, NULL);
    if (!t) return NULL;
    long rows = a->rows, cols = a->cols;
#pragma omp parallel for if (rows * cols > NN_PAR_MIN) schedule(static)
    for (long i = 0; i < rows; i++) {
        const float *x = a->data + i * cols;
        float *y = t->data + i * cols;
        float mx = x[0];
        for (long j = 1; j < cols; j++) mx = x[j] > mx ? x[j] : mx;
        double s = 0;
        for (long j = 0; j < cols; j++) { y[j] = expf(x[j] - mx); s += y[j]; }
        float inv = (float)(1.0 / s);
        for (long j = 0; j < cols; j++) y[j] *= inv;
    }
    return t;
}

/* dx = y * (g - sum_j g_j y_j), row by row. */
void nn_backward_softmax_rows(nn_ctx *ctx, nn_tensor *t)
{
    int acc = 0;
    float *ga = nn_grad_for(ctx, t->src[0], &acc);
    if (!ga) return;
    long rows = t->rows, cols = t->cols;
#pragma omp parallel for if (rows * cols > NN_PAR_MIN) schedule(static)
    for (long i = 0; i < rows; i++) {
        const float *y = t->data + i * cols, *g = t->grad + i * cols;
        double d = 0;
        for (long j = 0; j < cols; j++) d += (double)g[j] * y[j];
        for (long j = 0; j < cols; j++) STORE(acc, ga[i * cols + j], y[j] * (g[j] - (float)d));
    }
}

/* ---- row norm, dot and cosine --------------------------------------- */

static double row_sq(const float *x, long cols)
{
    double s = 0;
    for (long j = 0; j < cols; j++) s += (double)x[j] * x[j];
    return s;
}

static double row_dot(const float *x, const float *y, long cols)
{
    double s = 0;
    for (long j = 0; j < cols; j++) s += (double)x[j] * y[j];
    return s;
}

nn_tensor *nn_row_norm(nn_ctx *ctx, nn_tensor *a, float eps)
{
    if (!a) return NULL;
    if (!(eps >= 0)) return nn_ctx_fail(ctx, NEUV_ERR_INPUT, "row_norm: eps %g is negative", eps);
    nn_tensor *t = nn_node(ctx, NN_OP_ROW_NORM, a->rows, 1, a, NULL);
    if (!t) return NULL;
    t->fparam[0] = eps;
    long rows = a->rows, cols = a->cols;
#pragma omp parallel for if (rows * cols > NN_PAR_MIN) schedule(static)
    for (long i = 0; i < rows; i++) t->data[i] = (float)sqrt(row_sq(a->data + i * cols, cols) + eps);
    return t;
}

/* d n / d x = x / n. */
void nn_backward_row_norm(nn_ctx *ctx, nn_tensor *t)
{
    nn_tensor *a = t->src[0];
    int acc = 0;
    float *ga = nn_grad_for(ctx, a, &acc);
    if (!ga) return;
    long rows = a->rows, cols = a->cols;
#pragma omp parallel for if (rows * cols > NN_PAR_MIN) schedule(static)
    for (long i = 0; i < rows; i++) {
        float f = t->data[i] > 0 ? t->grad[i] / t->data[i] : 0.0f;
        for (long j = 0; j < cols; j++) STORE(acc, ga[i * cols + j], f * a->data[i * cols + j]);
    }
}

static int same_shape(nn_ctx *ctx, nn_op op, const nn_tensor *a, const nn_tensor *b)
{
    if (a->rows == b->rows && a->cols == b->cols) return 1;
    nn_ctx_fail(ctx, NEUV_ERR_INPUT, "%s: shapes %d by %d and %d by %d differ", nn_op_name(op),
                a->rows, a->cols, b->rows, b->cols);
    return 0;
}

nn_tensor *nn_row_dot(nn_ctx *ctx, nn_tensor *a, nn_tensor *b)
{
    if (NN_ANY_NULL(a, b) || !same_shape(ctx, NN_OP_ROW_DOT, a, b)) return NULL;
    nn_tensor *t = nn_node(ctx, NN_OP_ROW_DOT, a->rows, 1, a, b);
    if (!t) return NULL;
    long rows = a->rows, cols = a->cols;
#pragma omp parallel for if (rows * cols > NN_PAR_MIN) schedule(static)
    for (long i = 0; i < rows; i++) t->data[i] = (float)row_dot(a->data + i * cols, b->data + i * cols, cols);
    return t;
}

/* d/da = g b, d/db = g a (a and b may be the same tensor: both rules add). */
void nn_backward_row_dot(nn_ctx *ctx, nn_tensor *t)
{
    long rows = t->src[0]->rows, cols = t->src[0]->cols;
    for (int s = 0; s < 2; s++) {
        nn_tensor *self = t->src[s], *other = t->src[1 - s];
        int acc = 0;
        float *gs = nn_grad_for(ctx, self, &acc);
        if (!gs) continue;
#pragma omp parallel for if (rows * cols > NN_PAR_MIN) schedule(static)
        for (long i = 0; i < rows; i++)
            for (long j = 0; j < cols; j++) STORE(acc, gs[i * cols + j], t->grad[i] * other->data[i * cols + j]);
    }
}

nn_tensor *nn_row_cosine(nn_ctx *ctx, nn_tensor *a, nn_tensor *b, float eps)
{
    if (NN_ANY_NULL(a, b) || !same_shape(ctx, NN_OP_ROW_COSINE, a, b)) return NULL;
    if (!(eps >= 0)) return nn_ctx_fail(ctx, NEUV_ERR_INPUT, "row_cosine: eps %g is negative", eps);
    nn_tensor *t = nn_node(ctx, NN_OP_ROW_COSINE, a->rows, 1, a, b);
    if (!t) return NULL;
    t->fparam[0] = eps;
    long rows = a->rows, cols = a->cols;
#pragma omp parallel for if (rows * cols > NN_PAR_MIN) schedule(static)
    for (long i = 0; i < rows; i++) {
        const float *x = a->data + i * cols, *y = b->data + i * cols;
        double na = sqrt(row_sq(x, cols) + eps), nb = sqrt(row_sq(y, cols) + eps);
        t->data[i] = (float)(row_dot(x, y, cols) / (na * nb));
    }
    return t;
}

/* c = d / (na nb), na = sqrt(|a|^2 + eps):  dc/da = b / (na nb) - c a / na^2 (and symmetric). */
void nn_backward_row_cosine(nn_ctx *ctx, nn_tensor *t)
{
    long rows = t->src[0]->rows, cols = t->src[0]->cols;
    float eps = t->fparam[0];
    for (int s = 0; s < 2; s++) {
        nn_tensor *self = t->src[s], *other = t->src[1 - s];
        int acc = 0;
        float *gs = nn_grad_for(ctx, self, &acc);
        if (!gs) continue;
#pragma omp parallel for if (rows * cols > NN_PAR_MIN) schedule(static)
        for (long i = 0; i < rows; i++) {
            const float *x = self->data + i * cols, *y = other->data + i * cols;
            double nx2 = row_sq(x, cols) + eps;
            double nx = sqrt(nx2), ny = sqrt(row_sq(y, cols) + eps);
            double c = t->data[i], g = t->grad[i];
            double f1 = g / (nx * ny), f2 = g * c / nx2;
            for (long j = 0; j < cols; j++) STORE(acc, gs[i * cols + j], (float)(f1 * y[j] - f2 * x[j]));
        }
    }
}
