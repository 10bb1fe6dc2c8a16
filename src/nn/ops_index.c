/* Column concatenation and slicing, row gathering and scatter-adding by index
 * (faces -> vertices, vertex pairs). Forward and backward side by side. */
#include "nn/nn_internal.h"

#include <string.h>

#define STORE(acc, dst, v) ((dst) = (acc) ? (dst) + (v) : (v))

/* ---- concat / slice of columns -------------------------------------- */

nn_tensor *nn_concat_cols(nn_ctx *ctx, nn_tensor *a, nn_tensor *b)
{
    if (NN_ANY_NULL(a, b)) return NULL;
    if (a->rows != b->rows)
        return nn_ctx_fail(ctx, NEUV_ERR_INPUT, "concat_cols: %d rows and %d rows differ", a->rows, b->rows);
    nn_tensor *t = nn_node(ctx, NN_OP_CONCAT_COLS, a->rows, a->cols + b->cols, a, b);
    if (!t) return NULL;
    long rows = a->rows, ca = a->cols, cb = b->cols, c = t->cols;
#pragma omp parallel for if (rows * c > NN_PAR_MIN) schedule(static)
    for (long i = 0; i < rows; i++) {
        memcpy(t->data + i * c, a->data + i * ca, (size_t)ca * sizeof(float));
        memcpy(t->data + i * c + ca, b->data + i * cb, (size_t)cb * sizeof(float));
    }
    return t;
}

void nn_backward_concat_cols(nn_ctx *ctx, nn_tensor *t)
{
    long rows = t->rows, c = t->cols, off = 0;
    for (int s = 0; s < 2; s++) {
        nn_tensor *src = t->src[s];
        long cs = src->cols;
        int acc = 0;
        float *gs = nn_grad_for(ctx, src, &acc);
        if (gs) {
#pragma omp parallel for if (rows * cs > NN_PAR_MIN) schedule(static)
            for (long i = 0; i < rows; i++)
                for (long j = 0; j < cs; j++) STORE(acc, gs[i * cs + j], t->grad[i * c + off + j]);
        }
        off += cs;
    }
}

nn_tensor *nn_slice_cols(nn_ctx *ctx, nn_tensor *a, int first, int count)
{
    if (!a) return NULL;
    if (first < 0 || count <= 0 || first > a->cols - count)
        return nn_ctx_fail(ctx, NEUV_ERR_INPUT, "slice_cols: columns %d..%d outside 0..%d", first,
                           first + count - 1, a->cols - 1);
    nn_tensor *t = nn_node(ctx, NN_OP_SLICE_COLS, a->rows, count, a, NULL);
    if (!t) return NULL;
    t->iparam[0] = first;
    long rows = a->rows, ca = a->cols;
#pragma omp parallel for if (rows * count > NN_PAR_MIN) schedule(static)
    for (long i = 0; i < rows; i++)
        memcpy(t->data + i * count, a->data + i * ca + first, (size_t)count * sizeof(float));
    return t;
}

/* The slice's gradient lands in its columns; the others receive zero. */
void nn_backward_slice_cols(nn_ctx *ctx, nn_tensor *t)
{
    nn_tensor *a = t->src[0];
    int acc = 0;
    float *ga = nn_grad_for(ctx, a, &acc);
    if (!ga) return;
    long rows = a->rows, ca = a->cols, first = t->iparam[0], count = t->cols;
#pragma omp parallel for if (rows * ca > NN_PAR_MIN) schedule(static)
    for (long i = 0; i < rows; i++)
        for (long j = 0; j < ca; j++) {
            float v = j >= first && j < first + count ? t->grad[i * count + j - first] : 0.0f;
            STORE(acc, ga[i * ca + j], v);
        }
}

/* ---- gather / scatter-add of rows ----------------------------------- */

static int check_index(nn_ctx *ctx, nn_op op, const int *index, int n, int limit)
{
    if (!index) { nn_ctx_fail(ctx, NEUV_ERR_INPUT, "%s: no index array", nn_op_name(op)); return 0; }
    for (int i = 0; i < n; i++)
        if (index[i] < 0 || index[i] >= limit) {
            nn_ctx_fail(ctx, NEUV_ERR_INPUT, "%s: index[%d] = %d outside 0..%d", nn_op_name(op), i,
                        index[i], limit - 1);
            return 0;
        }
    return 1;
}

/* out[i] += a[i] rows by index: serial in i so repeated indices add in a fixed order. */
static void scatter_add(const float *x, const int *index, long n, long cols, float *out)
{
    for (long i = 0; i < n; i++) {
        float *o = out + (long)index[i] * cols;
        const float *r = x + i * cols;
        for (long j = 0; j < cols; j++) o[j] += r[j];
    }
}

nn_tensor *nn_gather_rows(nn_ctx *ctx, nn_tensor *a, const int *index, int n)
{
    if (!a) return NULL;
    if (!check_index(ctx, NN_OP_GATHER_ROWS, index, n, a->rows)) return NULL;
    nn_tensor *t = nn_node(ctx, NN_OP_GATHER_ROWS, n, a->cols, a, NULL);
    if (!t) return NULL;
    t->aux = index;
    long cols = a->cols;
#pragma omp parallel for if ((long)n * cols > NN_PAR_MIN) schedule(static)
    for (long i = 0; i < n; i++)
        memcpy(t->data + i * cols, a->data + (long)index[i] * cols, (size_t)cols * sizeof(float));
    return t;
}

/* Adjoint of gather: scatter-add the gradient rows back to their sources. */
void nn_backward_gather_rows(nn_ctx *ctx, nn_tensor *t)
{
    float *ga = nn_grad_zeroed(ctx, t->src[0]);
    if (ga) scatter_add(t->grad, t->aux, t->rows, t->cols, ga);
}

nn_tensor *nn_scatter_add_rows(nn_ctx *ctx, nn_tensor *a, const int *index, int out_rows)
{
    if (!a) return NULL;
    if (out_rows <= 0)
        return nn_ctx_fail(ctx, NEUV_ERR_INPUT, "scatter_add_rows: %d output rows", out_rows);
    if (!check_index(ctx, NN_OP_SCATTER_ADD_ROWS, index, a->rows, out_rows)) return NULL;
    nn_tensor *t = nn_node(ctx, NN_OP_SCATTER_ADD_ROWS, out_rows, a->cols, a, NULL);
    if (!t) return NULL;
    t->aux = index;
    t->iparam[0] = out_rows;
    memset(t->data, 0, (size_t)out_rows * (size_t)a->cols * sizeof(float));
    scatter_add(a->data, index, a->rows, a->cols, t->data);
    return t;
}

/* Adjoint of scatter-add: gather the gradient rows. */
void nn_backward_scatter_add_rows(nn_ctx *ctx, nn_tensor *t)
{
    nn_tensor *a = t->src[0];
    int acc = 0;
    float *ga = nn_grad_for(ctx, a, &acc);
    if (!ga) return;
    const int *index = t->aux;
    long rows = a->rows, cols = a->cols;
#pragma omp parallel for if (rows * cols > NN_PAR_MIN) schedule(static)
    for (long i = 0; i < rows; i++)
        for (long j = 0; j < cols; j++) STORE(acc, ga[i * cols + j], t->grad[(long)index[i] * cols + j]);
}
