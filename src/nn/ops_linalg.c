/* Dense products (OpenBLAS sgemm) and products with fixed sparse matrices. */
#include "nn/nn_internal.h"

#include <cblas.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"

/* ---- matmul: C = op(A) op(B) ------------------------------------------ */

nn_tensor *nn_matmul_t(nn_ctx *ctx, nn_tensor *a, int transpose_a, nn_tensor *b, int transpose_b)
{
    if (NN_ANY_NULL(a, b)) return NULL;
    int m = transpose_a ? a->cols : a->rows, k = transpose_a ? a->rows : a->cols;
    int kb = transpose_b ? b->cols : b->rows, n = transpose_b ? b->rows : b->cols;
    if (k != kb)
        return nn_ctx_fail(ctx, NEUV_ERR_INPUT, "matmul: inner sizes differ (%d by %d%s times %d by %d%s)",
                           a->rows, a->cols, transpose_a ? " transposed" : "", b->rows, b->cols,
                           transpose_b ? " transposed" : "");
    nn_tensor *t = nn_node(ctx, NN_OP_MATMUL, m, n, a, b);
    if (!t) return NULL;
    t->iparam[0] = transpose_a != 0;
    t->iparam[1] = transpose_b != 0;
    cblas_sgemm(CblasRowMajor, transpose_a ? CblasTrans : CblasNoTrans,
                transpose_b ? CblasTrans : CblasNoTrans, m, n, k, 1.0f, a->data, a->cols,
                b->data, b->cols, 0.0f, t->data, n);
    return t;
}

nn_tensor *nn_matmul(nn_ctx *ctx, nn_tensor *a, nn_tensor *b) { return nn_matmul_t(ctx, a, 0, b, 0); }

/* With A' = op(A) (M by K), B' = op(B) (K by N) and G = dL/dC (M by N):
 * dA' = G B'^T and dB' = A'^T G; a transposed operand receives the transpose. */
void nn_backward_matmul(nn_ctx *ctx, nn_tensor *t)
{
    nn_tensor *a = t->src[0], *b = t->src[1];
    int ta = t->iparam[0], tb = t->iparam[1];
    int m = t->rows, n = t->cols, k = ta ? a->rows : a->cols;
    int acc = 0;
    float *ga = nn_grad_for(ctx, a, &acc);
    if (ga) {
        if (!ta) /* dA (M by K) = G B'^T */
            cblas_sgemm(CblasRowMajor, CblasNoTrans, tb ? CblasNoTrans : CblasTrans, m, k, n, 1.0f,
                        t->grad, n, b->data, b->cols, acc ? 1.0f : 0.0f, ga, a->cols);
        else     /* dA (K by M) = B' G^T */
            cblas_sgemm(CblasRowMajor, tb ? CblasTrans : CblasNoTrans, CblasTrans, k, m, n, 1.0f,
                        b->data, b->cols, t->grad, n, acc ? 1.0f : 0.0f, ga, a->cols);
    }
    float *gb = nn_grad_for(ctx, b, &acc);
    if (gb) {
        if (!tb) /* dB (K by N) = A'^T G */
            cblas_sgemm(CblasRowMajor, ta ? CblasNoTrans : CblasTrans, CblasNoTrans, k, n, m, 1.0f,
                        a->data, a->cols, t->grad, n, acc ? 1.0f : 0.0f, gb, b->cols);
        else     /* dB (N by K) = G^T A' */
            cblas_sgemm(CblasRowMajor, CblasTrans, ta ? CblasTrans : CblasNoTrans, n, k, m, 1.0f,
                        t->grad, n, a->data, a->cols, acc ? 1.0f : 0.0f, gb, b->cols);
    }
}

/* ---- fixed sparse matrices ------------------------------------------- */

void nn_sparse_free(nn_sparse *s)
{
    if (!s) return;
    free(s->row_start); free(s->col); free(s->val);
    free(s->t_row_start); free(s->t_col); free(s->t_val);
    memset(s, 0, sizeof *s);
}

neuv_status nn_sparse_from_csr(const sparse_matrix *a, nn_sparse *out)
{
    memset(out, 0, sizeof *out);
    if (!a || a->rows <= 0 || a->cols <= 0 || !a->row_start)
        return neuv_fail(NEUV_ERR_INPUT, "sparse operator is empty");
    size_t nnz = (size_t)a->row_start[a->rows];
    for (int i = 0; i < a->rows; i++)
        if (a->row_start[i] > a->row_start[i + 1])
            return neuv_fail(NEUV_ERR_INPUT, "sparse operator row %d has a negative length", i);
    for (size_t e = 0; e < nnz; e++)
        if (a->col[e] < 0 || a->col[e] >= a->cols)
            return neuv_fail(NEUV_ERR_INPUT, "sparse operator entry %zu has column %d outside 0..%d", e,
                             a->col[e], a->cols - 1);
    out->rows = a->rows;
    out->cols = a->cols;
    size_t alloc = nnz ? nnz : 1;
    out->row_start = malloc((size_t)(a->rows + 1) * sizeof(int));
    out->col = malloc(alloc * sizeof(int));
    out->val = malloc(alloc * sizeof(float));
    out->t_row_start = calloc((size_t)a->cols + 1, sizeof(int));
    out->t_col = malloc(alloc * sizeof(int));
    out->t_val = malloc(alloc * sizeof(float));
    if (!out->row_start || !out->col || !out->val || !out->t_row_start || !out->t_col || !out->t_val) {
        nn_sparse_free(out);
        return neuv_fail_nomem("float32 sparse operator");
    }
    memcpy(out->row_start, a->row_start, (size_t)(a->rows + 1) * sizeof(int));
    memcpy(out->col, a->col, nnz * sizeof(int));
    for (size_t e = 0; e < nnz; e++) out->val[e] = (float)a->val[e];
    /* Transpose by counting; rows are visited in order, so each transposed row
     * lists its entries by increasing column, a fixed summation order. */
    for (size_t e = 0; e < nnz; e++) out->t_row_start[a->col[e] + 1]++;
    for (int j = 0; j < a->cols; j++) out->t_row_start[j + 1] += out->t_row_start[j];
    int *fill = malloc((size_t)a->cols * sizeof(int));
    if (!fill) { nn_sparse_free(out); return neuv_fail_nomem("sparse transpose"); }
    memcpy(fill, out->t_row_start, (size_t)a->cols * sizeof(int));
    for (int i = 0; i < a->rows; i++)
        for (int e = a->row_start[i]; e < a->row_start[i + 1]; e++) {
            int p = fill[a->col[e]]++;
            out->t_col[p] = i;
            out->t_val[p] = (float)a->val[e];
        }
    free(fill);
    return NEUV_OK;
}

/* y (rows by k) (+)= S x with S in CSR; row-parallel, each row summed in order. */
static void csr_times(int rows, const int *row_start, const int *col, const float *val,
                      const float *x, long k, float *y, int accumulate)
{
#pragma omp parallel for if ((long)row_start[rows] * k > NN_PAR_MIN) schedule(static)
    for (long i = 0; i < rows; i++) {
        float *yi = y + i * k;
        if (!accumulate) memset(yi, 0, (size_t)k * sizeof(float));
        for (int e = row_start[i]; e < row_start[i + 1]; e++) {
            const float *xr = x + (long)col[e] * k;
            float v = val[e];
            for (long j = 0; j < k; j++) yi[j] += v * xr[j];
        }
    }
}

nn_tensor *nn_spmm(nn_ctx *ctx, const nn_sparse *s, nn_tensor *a)
{
    if (!a) return NULL;
    if (!s || !s->row_start) return nn_ctx_fail(ctx, NEUV_ERR_INPUT, "spmm: no sparse matrix");
    if (s->cols != a->rows)
        return nn_ctx_fail(ctx, NEUV_ERR_INPUT, "spmm: %d by %d sparse matrix times %d by %d tensor",
                           s->rows, s->cols, a->rows, a->cols);
    nn_tensor *t = nn_node(ctx, NN_OP_SPMM, s->rows, a->cols, a, NULL);
    if (!t) return NULL;
    t->aux = s;
    csr_times(s->rows, s->row_start, s->col, s->val, a->data, a->cols, t->data, 0);
    return t;
}

/* d/da = S^T g, using the stored transpose. */
void nn_backward_spmm(nn_ctx *ctx, nn_tensor *t)
{
    const nn_sparse *s = t->aux;
    int acc = 0;
    float *ga = nn_grad_for(ctx, t->src[0], &acc);
    if (ga) csr_times(s->cols, s->t_row_start, s->t_col, s->t_val, t->grad, t->cols, ga, acc);
}
