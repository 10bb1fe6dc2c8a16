/* Sparse Cholesky factorization (CHOLMOD) of a symmetric positive definite
 * matrix, factored once and solved many times. Each factor owns its own
 * cholmod_common, so factors are independent. */
#ifndef NEUV_GEOMETRY_CHOLESKY_H
#define NEUV_GEOMETRY_CHOLESKY_H

#include "geometry/sparse_matrix.h"

typedef struct cholesky cholesky;

/* Inputs: a #N by #N symmetric positive definite, both triangles stored.
 * Fails with NEUV_ERR_INPUT when a is not positive definite. */
neuv_status cholesky_factor(const sparse_matrix *a, cholesky **out);
/* Solves A X = B for nrhs right-hand sides, column-major (#N by nrhs). */
neuv_status cholesky_solve(cholesky *c, const double *b, double *x, int nrhs);
void cholesky_free(cholesky *c);

#endif
