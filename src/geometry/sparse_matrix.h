/* Sparse matrices in compressed sparse row form (float64), built from triplets.
 * The geometry operators (Laplacian, mass, gradients) are sparse_matrix values. */
#ifndef NEUV_GEOMETRY_SPARSE_MATRIX_H
#define NEUV_GEOMETRY_SPARSE_MATRIX_H

#include <stddef.h>
#include "neuv/neuv.h"

typedef struct sparse_matrix {
    int rows, cols;
    int *row_start; /* rows+1 */
    int *col;       /* nnz, sorted within each row */
    double *val;    /* nnz */
} sparse_matrix;

typedef struct triplet_list {
    int rows, cols;
    size_t n, cap;
    int *i, *j;
    double *v;
} triplet_list;

neuv_status triplets_init(triplet_list *t, int rows, int cols, size_t reserve);
neuv_status triplets_add(triplet_list *t, int i, int j, double v);
void triplets_free(triplet_list *t);
/* Sums duplicates; entries are sorted by (row, col). */
neuv_status sparse_from_triplets(const triplet_list *t, sparse_matrix *out);
void sparse_free(sparse_matrix *a);
size_t sparse_nnz(const sparse_matrix *a);
/* y = A x */
void sparse_matvec(const sparse_matrix *a, const double *x, double *y);
/* out = A + s diag(d): a copy of the square matrix A with s d_i added to
 * entry (i, i) (created when absent).
 * Inputs:  a #N by #N, d #N, s scalar
 * Outputs: out #N by #N (caller frees with sparse_free) */
neuv_status sparse_add_diagonal(const sparse_matrix *a, const double *d, double s, sparse_matrix *out);
/* Deep copy of a. */
neuv_status sparse_copy(const sparse_matrix *a, sparse_matrix *out);

#endif
