/* Dense products (OpenBLAS sgemm) and products with fixed sparse matrices. */
#include "nn/nn_internal.h"

#include <cblas.h>
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/mem.h"

/* ---- matmul: C = op(A) op(B) ------------------------------------------ */

/* Products below this many multiply-adds run as one OpenBLAS call. */
#define SPLIT_MIN_WORK 4e6
#define BLOCKS_PER_THREAD 4

/* C = op(A) op(B) + beta C (row-major, M by N, inner size K) on the OpenMP threads:
 * C is cut into one block of rows per thread (of columns when C is wide), each
 * block one single-threaded OpenBLAS call. Why not OpenBLAS's own threads: its
 * pthread workers and libgomp's workers both spin-wait after their parallel
 * sections, so alternating sgemm calls with OpenMP element-wise loops made each
 * pool steal the cores of the other (a step ran at 45% of the sgemm rate on 2
 * cores). One pool avoids that. The blocks depend only on the sizes and the
 * thread count and each is one call, whichever thread runs it, so results are
 * identical for a given thread count. Inside a parallel region (charts solved
 * side by side) the same blocks run one after another on the calling thread:
 * the same bits as the call at top level on that many threads. */
static void gemm(int ta, int tb, int m, int n, int k, const float *a, int lda, const float *b, int ldb,
                 float beta, float *c, int ldc)
{
    int threads = omp_get_max_threads();
    if (threads <= 1 || (double)m * n * k < SPLIT_MIN_WORK) {
        cblas_sgemm(CblasRowMajor, ta ? CblasTrans : CblasNoTrans, tb ? CblasTrans : CblasNoTrans, m, n, k,
                    1.0f, a, lda, b, ldb, beta, c, ldc);
        return;
    }
    int by_rows = m >= n, len = by_rows ? m : n;
    /* Several blocks per thread, handed out as threads free up: a thread that
     * the OS preempts delays one small block, not half the product. */
    int blocks = BLOCKS_PER_THREAD * threads;
    if (blocks > len / 16) blocks = len / 16 > 0 ? len / 16 : 1;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (!omp_in_parallel())
    for (int t = 0; t < blocks; t++) {
        /* Block boundaries on multiples of 16 keep the kernels' panels whole. */
        int lo = (int)((long)len * t / blocks) & ~15, hi = t == blocks - 1 ? len : (int)((long)len * (t + 1) / blocks) & ~15;
        if (hi <= lo) continue;
        if (by_rows) {
            const float *ab = ta ? a + lo : a + (long)lo * lda;
            cblas_sgemm(CblasRowMajor, ta ? CblasTrans : CblasNoTrans, tb ? CblasTrans : CblasNoTrans, hi - lo, n,
                        k, 1.0f, ab, lda, b, ldb, beta, c + (long)lo * ldc, ldc);
        } else {
            const float *bb = tb ? b + (long)lo * ldb : b + lo;
            cblas_sgemm(CblasRowMajor, ta ? CblasTrans : CblasNoTrans, tb ? CblasTrans : CblasNoTrans, m, hi - lo,
                        k, 1.0f, a, lda, bb, ldb, beta, c + lo, ldc);
        }
    }
}

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
    gemm(t->iparam[0], t->iparam[1], m, n, k, a->data, a->cols, b->data, b->cols, 0.0f, t->data, n);
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
            gemm(0, !tb, m, k, n, t->grad, n, b->data, b->cols, acc ? 1.0f : 0.0f, ga, a->cols);
        else     /* dA (K by M) = B' G^T */
            gemm(tb, 1, k, m, n, b->data, b->cols, t->grad, n, acc ? 1.0f : 0.0f, ga, a->cols);
    }
    float *gb = nn_grad_for(ctx, b, &acc);
    if (gb) {
        if (!tb) /* dB (K by N) = A'^T G */
            gemm(!ta, 0, k, n, m, a->data, a->cols, t->grad, n, acc ? 1.0f : 0.0f, gb, b->cols);
        else     /* dB (N by K) = G^T A' */
            gemm(1, ta, n, k, m, t->grad, n, a->data, a->cols, acc ? 1.0f : 0.0f, gb, b->cols);
    }
}

/* ---- fused linear layer: y = act(x W + b) ------------------------------ */

#define STORE(acc, dst, v) ((dst) = (acc) ? (dst) + (v) : (v))
/* Row blocks of the layer: the unit of work of a thread, and of the bias
 * gradient's partial sums (fixed size, so those sums do not depend on the
 * number of threads). */
#define LINEAR_ROW_BLOCK 64

/* The threads a layer of `work` multiply-adds over `nblocks` row blocks is
 * split for (its chunks depend on it); inside a parallel region the chunks
 * run one after another on the calling thread (linear_run_threads), with the
 * same bits as at top level. */
static int linear_threads(double work, long nblocks)
{
    int threads = omp_get_max_threads();
    if (work < SPLIT_MIN_WORK) threads = 1;
    if (threads > nblocks) threads = (int)nblocks;
    return threads < 1 ? 1 : threads;
}

static int linear_run_threads(int threads) { return omp_in_parallel() ? 1 : threads; }

/* y[rows lo..hi) = act(y + b) in place. */
NN_VECTORIZE static void bias_activation(float *y, const float *bias, long lo, long hi, long cols, nn_activation act, float s)
{
    for (long i = lo; i < hi; i++) {
        float *yi = y + i * cols;
        switch (act) {
        case NN_ACT_NONE:
#pragma omp simd
            for (long j = 0; j < cols; j++) yi[j] += bias[j];
            break;
        case NN_ACT_RELU:
#pragma omp simd
            for (long j = 0; j < cols; j++) { float z = yi[j] + bias[j]; yi[j] = z > 0 ? z : 0.0f; }
            break;
        case NN_ACT_LEAKY_RELU:
#pragma omp simd
            for (long j = 0; j < cols; j++) { float z = yi[j] + bias[j]; yi[j] = z > 0 ? z : s * z; }
            break;
        default:
            for (long j = 0; j < cols; j++) yi[j] = tanhf(yi[j] + bias[j]);
        }
    }
}

nn_tensor *nn_linear_act(nn_ctx *ctx, nn_tensor *x, nn_tensor *w, nn_tensor *b, nn_activation act,
                         float leaky_slope)
{
    if (!x || !w || !b) return NULL;
    if (x->cols != w->rows || b->rows != 1 || b->cols != w->cols)
        return nn_ctx_fail(ctx, NEUV_ERR_INPUT, "linear: x %d by %d, W %d by %d and b %d by %d do not fit",
                           x->rows, x->cols, w->rows, w->cols, b->rows, b->cols);
    if (act < NN_ACT_NONE || act > NN_ACT_TANH || (act == NN_ACT_LEAKY_RELU && !(leaky_slope > 0)))
        return nn_ctx_fail(ctx, NEUV_ERR_INPUT, "linear: activation %d with slope %g", (int)act, leaky_slope);
    nn_tensor *t = nn_node(ctx, NN_OP_LINEAR, x->rows, w->cols, x, w);
    if (!t) return NULL;
    t->src[2] = b;
    t->requires_grad |= b->requires_grad;
    t->iparam[0] = act;
    t->fparam[0] = leaky_slope;
    long rows = x->rows, cols = w->cols, in = x->cols;
    long nblocks = (rows + LINEAR_ROW_BLOCK - 1) / LINEAR_ROW_BLOCK;
    int threads = linear_threads((double)rows * cols * in, nblocks);
    const float *xd = x->data, *wd = w->data, *bias = b->data;
    float *y = t->data;
    /* Each chunk of rows is multiplied, then biased and activated while fresh:
     * one parallel section per layer; chunks go to threads as they free up. */
    long chunks = threads > 1 ? BLOCKS_PER_THREAD * threads : 1;
    if (chunks > nblocks) chunks = nblocks;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (linear_run_threads(threads) > 1)
    for (long ch = 0; ch < chunks; ch++) {
        long lo = nblocks * ch / chunks * LINEAR_ROW_BLOCK, hi = nblocks * (ch + 1) / chunks * LINEAR_ROW_BLOCK;
        if (hi > rows) hi = rows;
        if (hi <= lo) continue;
        cblas_sgemm(CblasRowMajor, CblasNoTrans, CblasNoTrans, (int)(hi - lo), (int)cols, (int)in, 1.0f,
                    xd + lo * in, (int)in, wd, (int)cols, 0.0f, y + lo * cols, (int)cols);
        bias_activation(y, bias, lo, hi, cols, act, leaky_slope);
    }
    return t;
}

/* gz = g act'(z) on rows lo..hi, act' read from the output y. */
NN_VECTORIZE static void activation_gradient(const float *g, const float *y, float *gz, long lo, long hi,
                                             long cols, nn_activation act, float s)
{
    for (long i = lo; i < hi; i++) {
        const float *gi = g + i * cols, *yi = y + i * cols;
        float *zi = gz + i * cols;
        if (act == NN_ACT_TANH) {
#pragma omp simd
            for (long j = 0; j < cols; j++) zi[j] = gi[j] * (1 - yi[j] * yi[j]);
        } else {
#pragma omp simd
            for (long j = 0; j < cols; j++) zi[j] = yi[j] > 0 ? gi[j] : s * gi[j];
        }
    }
}

/* With z = x W + b and gz = dL/dz = g act'(z) (act' read from the output: the
 * sign for (leaky) ReLU, 1 - y^2 for tanh): dx = gz W^T, dW = x^T gz, db = column
 * sums of gz. One parallel section computes gz, the bias partial sums and dx
 * row block by row block; dW, a sum over all rows, follows as a split product. */
void nn_backward_linear(nn_ctx *ctx, nn_tensor *t)
{
    nn_tensor *x = t->src[0], *w = t->src[1], *b = t->src[2];
    long rows = t->rows, cols = t->cols, in = x->cols;
    nn_activation act = (nn_activation)t->iparam[0];
    float s = act == NN_ACT_RELU ? 0.0f : t->fparam[0];
    const float *g = t->grad, *y = t->data;
    long nblocks = (rows + LINEAR_ROW_BLOCK - 1) / LINEAR_ROW_BLOCK;
    float *gz = (float *)g;
    if (act != NN_ACT_NONE) gz = nn_ctx_alloc(ctx, (size_t)rows * (size_t)cols * sizeof(float));
    int bacc = 0, xacc = 0, wacc = 0;
    float *gb = nn_grad_for(ctx, b, &bacc);
    double *part = gb ? nn_ctx_alloc(ctx, (size_t)nblocks * (size_t)cols * sizeof(double)) : NULL;
    float *gx = nn_grad_for(ctx, x, &xacc);
    if (!gz || (gb && !part) || nn_ctx_status(ctx) != NEUV_OK) return;
    const float *wd = w->data;
    int threads = linear_threads((double)rows * cols * in, nblocks);
    long chunks = threads > 1 ? BLOCKS_PER_THREAD * threads : 1;
    if (chunks > nblocks) chunks = nblocks;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (linear_run_threads(threads) > 1)
    for (long ch = 0; ch < chunks; ch++) {
        long b0 = nblocks * ch / chunks, b1 = nblocks * (ch + 1) / chunks;
        for (long blk = b0; blk < b1; blk++) {
            long lo = blk * LINEAR_ROW_BLOCK, hi = lo + LINEAR_ROW_BLOCK < rows ? lo + LINEAR_ROW_BLOCK : rows;
            if (act != NN_ACT_NONE) activation_gradient(g, y, gz, lo, hi, cols, act, s);
            if (part) {
                double *p = part + blk * cols;
                for (long j = 0; j < cols; j++) p[j] = 0;
                for (long i = lo; i < hi; i++) {
                    const float *zi = gz + i * cols;
#pragma omp simd
                    for (long j = 0; j < cols; j++) p[j] += zi[j];
                }
            }
        }
        long lo = b0 * LINEAR_ROW_BLOCK, hi = b1 * LINEAR_ROW_BLOCK < rows ? b1 * LINEAR_ROW_BLOCK : rows;
        if (gx && hi > lo)
            cblas_sgemm(CblasRowMajor, CblasNoTrans, CblasTrans, (int)(hi - lo), (int)in, (int)cols, 1.0f,
                        gz + lo * cols, (int)cols, wd, (int)cols, xacc ? 1.0f : 0.0f, gx + lo * in, (int)in);
    }
    if (gb)
        for (long j = 0; j < cols; j++) {
            double sum = 0;
            for (long blk = 0; blk < nblocks; blk++) sum += part[blk * cols + j];
            STORE(bacc, gb[j], (float)sum);
        }
    float *gw = nn_grad_for(ctx, w, &wacc);
    if (gw) gemm(1, 0, (int)in, (int)cols, (int)rows, x->data, (int)in, gz, (int)cols, wacc ? 1.0f : 0.0f, gw, (int)cols);
}

/* ---- fixed sparse matrices ------------------------------------------- */

void nn_sparse_free(nn_sparse *s)
{
    if (!s) return;
    mem_free(s->row_start); mem_free(s->col); mem_free(s->val);
    mem_free(s->t_row_start); mem_free(s->t_col); mem_free(s->t_val);
    memset(s, 0, sizeof *s);
}

neuv_status nn_sparse_from_csr(const nn_csr *a, nn_sparse *out)
{
    memset(out, 0, sizeof *out);
    if (!a || a->rows <= 0 || a->cols <= 0 || !a->row_start)
        return error_set(NEUV_ERR_INPUT, "sparse operator is empty");
    size_t nnz = (size_t)a->row_start[a->rows];
    for (int i = 0; i < a->rows; i++)
        if (a->row_start[i] > a->row_start[i + 1])
            return error_set(NEUV_ERR_INPUT, "sparse operator row %d has a negative length", i);
    for (size_t e = 0; e < nnz; e++)
        if (a->col[e] < 0 || a->col[e] >= a->cols)
            return error_set(NEUV_ERR_INPUT, "sparse operator entry %zu has column %d outside 0..%d", e,
                             a->col[e], a->cols - 1);
    out->rows = a->rows;
    out->cols = a->cols;
    size_t alloc = nnz ? nnz : 1;
    out->row_start = mem_alloc((size_t)(a->rows + 1) * sizeof(int));
    out->col = mem_alloc(alloc * sizeof(int));
    out->val = mem_alloc(alloc * sizeof(float));
    out->t_row_start = mem_calloc((size_t)a->cols + 1, sizeof(int));
    out->t_col = mem_alloc(alloc * sizeof(int));
    out->t_val = mem_alloc(alloc * sizeof(float));
    if (!out->row_start || !out->col || !out->val || !out->t_row_start || !out->t_col || !out->t_val) {
        nn_sparse_free(out);
        return error_nomem("float32 sparse operator");
    }
    memcpy(out->row_start, a->row_start, (size_t)(a->rows + 1) * sizeof(int));
    memcpy(out->col, a->col, nnz * sizeof(int));
    for (size_t e = 0; e < nnz; e++) out->val[e] = (float)a->val[e];
    /* Transpose by counting; rows are visited in order, so each transposed row
     * lists its entries by increasing column, a fixed summation order. */
    for (size_t e = 0; e < nnz; e++) out->t_row_start[a->col[e] + 1]++;
    for (int j = 0; j < a->cols; j++) out->t_row_start[j + 1] += out->t_row_start[j];
    int *fill = mem_alloc((size_t)a->cols * sizeof(int));
    if (!fill) { nn_sparse_free(out); return error_nomem("sparse transpose"); }
    memcpy(fill, out->t_row_start, (size_t)a->cols * sizeof(int));
    for (int i = 0; i < a->rows; i++)
        for (int e = a->row_start[i]; e < a->row_start[i + 1]; e++) {
            int p = fill[a->col[e]]++;
            out->t_col[p] = i;
            out->t_val[p] = (float)a->val[e];
        }
    mem_free(fill);
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
