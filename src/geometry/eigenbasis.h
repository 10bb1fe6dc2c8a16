/* The k smallest generalized eigenpairs of the Laplacian, L φ = λ M φ
 * (the "eigenbasis" DiffusionNet's spectral diffusion uses).
 *
 * Large problems: ARPACK (implicitly restarted Lanczos, dsaupd/dseupd) in
 * shift-invert mode 3 with OP = (L − σM)⁻¹ M and B = M, on a CHOLMOD factor
 * of L − σM. σ is a small negative shift (−1e-6 × the mean of L_ii / M_i), so
 * L − σM is positive definite and the zero eigenvalue(s) are found.
 * Small problems (#V ≤ 400, or k ≥ #V − 1) use dense LAPACK dsyev on
 * M^-1/2 L M^-1/2 instead, which gives every eigenpair exactly.
 *
 * A Laplacian with several connected components is block diagonal: each
 * component is solved on its own (a single Lanczos run would have to find a
 * zero eigenvalue of multiplicity #components from one start vector) and
 * the k smallest over all components are kept, each eigenvector zero
 * outside its component.
 *
 * Results are sorted ascending, M-orthonormal (checked, re-orthonormalized
 * when the error exceeds 1e-10), each eigenvector signed so that its entry
 * of largest magnitude is positive, and deterministic: the Lanczos start
 * vector is drawn from a seeded generator, not ARPACK's own. */
#ifndef NEUV_GEOMETRY_EIGENBASIS_H
#define NEUV_GEOMETRY_EIGENBASIS_H

#include "geometry/sparse_matrix.h"

typedef struct eigenbasis_info {
    double sigma;           /* shift used (0 for the dense path) */
    int dense;              /* 1 when the dense LAPACK path was used (for every component) */
    int components;         /* connected components of L, each solved on its own */
    int restarts;           /* ARPACK restart iterations */
    int op_applies;         /* solves with the factor */
    double orth_error;      /* max |Φᵀ M Φ − I| after the final check */
    double factor_seconds;  /* time to factor L − σM */
    double solve_seconds;   /* time in the eigen iteration (ARPACK + solves) */
    double op_seconds;      /* of which: applying (L − σM)⁻¹ M */
} eigenbasis_info;

/* Inputs:  L     #V by #V symmetric positive semi-definite (cotangent Laplacian)
 *          mass  #V positive lumped masses (diagonal of M)
 *          k     number of eigenpairs, 1 ≤ k ≤ #V
 * Outputs: evals k eigenvalues, ascending
 *          evecs #V by k, row-major (row i: vertex i's spectral coordinates)
 *          info  may be NULL
 * Fails with NEUV_ERR_INPUT on a non-positive mass or when the solver does
 * not converge. */
neuv_status eigenbasis(const sparse_matrix *L, const double *mass, int k,
                       double *evals, double *evecs, eigenbasis_info *info);

#endif
