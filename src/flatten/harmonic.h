/* Harmonic (Tutte–Floater style, cotangent weights) flattening of a disk:
 * the boundary loop goes onto the unit circle by arc length, the interior
 * solves the cotangent Laplace equation L_II u_I = -L_IB u_B (Eck et al. 1995,
 * "Multiresolution analysis of arbitrary meshes", with Pinkall–Polthier
 * weights). Cotangent weights can be negative on obtuse triangles, but L_II is
 * still positive definite (a principal block of a connected Laplacian with at
 * least one boundary row removed), so one Cholesky factorization solves it;
 * the map is then not guaranteed free of flips, unlike with positive weights.
 *
 * Inputs:  m   one disk (see flatten_require_disk), #V by 3, #F by 3
 * Outputs: uv  #V by 2 in the unit disk (caller allocates), counter-clockwise;
 *              vertices used by no face get (0,0)
 * Errors:  NEUV_ERR_INPUT when m is not one disk (the message names its
 *          topology), NEUV_ERR_NOMEM, NEUV_ERR_INTERNAL if the solve fails. */
#ifndef NEUV_FLATTEN_HARMONIC_H
#define NEUV_FLATTEN_HARMONIC_H

#include "mesh/mesh.h"

neuv_status harmonic(const neuv_mesh *m, double *uv);

#endif
