/* Compressed sparse row matrices built from (i, j, v) triplets. */
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/mem.h"
#include "geometry/sparse_matrix.h"

neuv_status triplets_init(triplet_list *t, int rows, int cols, size_t reserve)
{
    memset(t, 0, sizeof *t);
    if (rows < 0 || cols < 0) return error_set(NEUV_ERR_INTERNAL, "triplets_init: negative size %d by %d", rows, cols);
    t->rows = rows;
    t->cols = cols;
    if (reserve < 16) reserve = 16;
    t->i = mem_alloc(reserve * sizeof *t->i);
    t->j = mem_alloc(reserve * sizeof *t->j);
    t->v = mem_alloc(reserve * sizeof *t->v);
    if (!t->i || !t->j || !t->v) {
        triplets_free(t);
        return error_nomem("sparse matrix triplets");
    }
    t->cap = reserve;
    return NEUV_OK;
}

neuv_status triplets_add(triplet_list *t, int i, int j, double v)
{
    if (i < 0 || i >= t->rows || j < 0 || j >= t->cols)
        return error_set(NEUV_ERR_INTERNAL, "triplet (%d, %d) outside a %d by %d matrix", i, j, t->rows, t->cols);
    if (t->n == t->cap) {
        /* Grow all three arrays together; keep the old ones on failure so
         * triplets_free still releases everything. */
        size_t cap = t->cap ? 2 * t->cap : 16;
        int *ni = mem_realloc(t->i, cap * sizeof *ni);
        if (!ni) return error_nomem("sparse matrix triplets");
        t->i = ni;
        int *nj = mem_realloc(t->j, cap * sizeof *nj);
        if (!nj) return error_nomem("sparse matrix triplets");
        t->j = nj;
        double *nv = mem_realloc(t->v, cap * sizeof *nv);
        if (!nv) return error_nomem("sparse matrix triplets");
        t->v = nv;
        t->cap = cap;
    }
    t->i[t->n] = i;
    t->j[t->n] = j;
    t->v[t->n] = v;
    t->n++;
    return NEUV_OK;
}

void triplets_free(triplet_list *t)
{
    if (!t) return;
    mem_free(t->i);
    mem_free(t->j);
    mem_free(t->v);
    memset(t, 0, sizeof *t);
}

/* Two counting-sort passes (by column, then stably by row) give entries
 * sorted by (row, col) in O(nnz + rows + cols), then duplicates are summed. */
neuv_status sparse_from_triplets(const triplet_list *t, sparse_matrix *out)
{
    memset(out, 0, sizeof *out);
    size_t n = t->n;
    int rows = t->rows, cols = t->cols;
    size_t *cstart = mem_calloc((size_t)cols + 1, sizeof *cstart);
    size_t *by_col = mem_alloc((n ? n : 1) * sizeof *by_col);
    int *rcount = mem_calloc((size_t)rows + 1, sizeof *rcount);
    size_t *rpos = mem_alloc(((size_t)rows + 1) * sizeof *rpos);
    size_t *order = mem_alloc((n ? n : 1) * sizeof *order);
    int *row_start = mem_calloc((size_t)rows + 1, sizeof *row_start);
    if (!cstart || !by_col || !rcount || !rpos || !order || !row_start) goto nomem;

    for (size_t k = 0; k < n; k++) cstart[t->j[k] + 1]++;
    for (int c = 0; c < cols; c++) cstart[c + 1] += cstart[c];
    for (size_t k = 0; k < n; k++) by_col[cstart[t->j[k]]++] = k;

    for (size_t k = 0; k < n; k++) rcount[t->i[k]]++;
    rpos[0] = 0;
    for (int r = 0; r < rows; r++) rpos[r + 1] = rpos[r] + (size_t)rcount[r];
    for (size_t q = 0; q < n; q++) {
        size_t k = by_col[q];
        order[rpos[t->i[k]]++] = k;
    }

    /* Count distinct (row, col) pairs. */
    size_t nnz = 0;
    for (size_t q = 0; q < n; q++) {
        size_t k = order[q];
        if (q == 0 || t->i[k] != t->i[order[q - 1]] || t->j[k] != t->j[order[q - 1]]) nnz++;
    }
    if (nnz > (size_t)0x7fffffff) {
        mem_free(cstart); mem_free(by_col); mem_free(rcount); mem_free(rpos); mem_free(order); mem_free(row_start);
        return error_set(NEUV_ERR_NOMEM, "sparse matrix with %zu nonzeros is too large", nnz);
    }
    int *col = mem_alloc((nnz ? nnz : 1) * sizeof *col);
    double *val = mem_alloc((nnz ? nnz : 1) * sizeof *val);
    if (!col || !val) { mem_free(col); mem_free(val); goto nomem; }

    size_t e = 0;
    for (size_t q = 0; q < n; q++) {
        size_t k = order[q];
        if (q == 0 || t->i[k] != t->i[order[q - 1]] || t->j[k] != t->j[order[q - 1]]) {
            col[e] = t->j[k];
            val[e] = t->v[k];
            row_start[t->i[k] + 1]++;
            e++;
        } else {
            val[e - 1] += t->v[k];
        }
    }
    for (int r = 0; r < rows; r++) row_start[r + 1] += row_start[r];

    mem_free(cstart); mem_free(by_col); mem_free(rcount); mem_free(rpos); mem_free(order);
    out->rows = rows;
    out->cols = cols;
    out->row_start = row_start;
    out->col = col;
    out->val = val;
    return NEUV_OK;

nomem:
    mem_free(cstart); mem_free(by_col); mem_free(rcount); mem_free(rpos); mem_free(order); mem_free(row_start);
    return error_nomem("sparse matrix");
}

void sparse_free(sparse_matrix *a)
{
    if (!a) return;
    mem_free(a->row_start);
    mem_free(a->col);
    mem_free(a->val);
    memset(a, 0, sizeof *a);
}

size_t sparse_nnz(const sparse_matrix *a)
{
    return a->row_start ? (size_t)a->row_start[a->rows] : 0;
}

void sparse_matvec(const sparse_matrix *a, const double *x, double *y)
{
    for (int r = 0; r < a->rows; r++) {
        double s = 0.0;
        for (int p = a->row_start[r]; p < a->row_start[r + 1]; p++) s += a->val[p] * x[a->col[p]];
        y[r] = s;
    }
}

neuv_status sparse_add_diagonal(const sparse_matrix *a, const double *d, double s, sparse_matrix *out)
{
    triplet_list t;
    neuv_status st = triplets_init(&t, a->rows, a->cols, sparse_nnz(a) + (size_t)a->rows);
    if (st) return st;
    for (int r = 0; r < a->rows && !st; r++)
        for (int p = a->row_start[r]; p < a->row_start[r + 1] && !st; p++)
            st = triplets_add(&t, r, a->col[p], a->val[p]);
    for (int r = 0; r < a->rows && !st; r++) st = triplets_add(&t, r, r, s * d[r]);
    if (!st) st = sparse_from_triplets(&t, out);
    triplets_free(&t);
    return st;
}

neuv_status sparse_copy(const sparse_matrix *a, sparse_matrix *out)
{
    memset(out, 0, sizeof *out);
    size_t nnz = sparse_nnz(a);
    out->row_start = mem_alloc(((size_t)a->rows + 1) * sizeof *out->row_start);
    out->col = mem_alloc((nnz ? nnz : 1) * sizeof *out->col);
    out->val = mem_alloc((nnz ? nnz : 1) * sizeof *out->val);
    if (!out->row_start || !out->col || !out->val) {
        sparse_free(out);
        return error_nomem("sparse matrix copy");
    }
    out->rows = a->rows;
    out->cols = a->cols;
    memcpy(out->row_start, a->row_start, ((size_t)a->rows + 1) * sizeof *out->row_start);
    memcpy(out->col, a->col, nnz * sizeof *out->col);
    memcpy(out->val, a->val, nnz * sizeof *out->val);
    return NEUV_OK;
}
