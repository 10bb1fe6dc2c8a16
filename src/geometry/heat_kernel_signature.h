/* Heat kernel signature (Sun, Ovsjanikov, Guibas 2009, eq. 3):
 *     HKS(x, t) = Σ_i exp(−λ_i t) φ_i(x)²
 * over the k eigenpairs, multiplied here by the total area A so the values
 * are dimensionless: with t scaling like 1/λ, A · HKS is invariant under a
 * uniform scaling of the mesh.
 *
 * Times (heat_kernel_times): n values log-spaced from t_min = 4 ln10 / λ_max
 * to t_max = 4 ln10 / λ_min, λ_min the smallest eigenvalue above
 * 1e-8 λ_max (Sun et al. 2009, section 5), so the range follows the
 * spectrum and is scale invariant. With no nonzero eigenvalue, t = 1. */
#ifndef NEUV_GEOMETRY_HEAT_KERNEL_SIGNATURE_H
#define NEUV_GEOMETRY_HEAT_KERNEL_SIGNATURE_H

#include "neuv/neuv.h"

/* Inputs:  k evals (ascending), n number of times
 * Outputs: times n, ascending */
void heat_kernel_times(int k, const double *evals, int n, double *times);

/* Inputs:  nv, k, evals k, evecs #V by k row-major, area total area,
 *          n times n
 * Outputs: hks #V by n row-major (caller allocates) */
neuv_status heat_kernel_signature(int nv, int k, const double *evals, const double *evecs, double area,
                                  int n, const double *times, double *hks);

#endif
