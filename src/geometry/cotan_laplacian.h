/* Cotangent Laplacian (weak form), symmetric positive semi-definite.
 * L_ij = -(cot α_ij + cot β_ij)/2 for an edge ij, L_ii = -Σ_j L_ij.
 *
 * Inputs:  m   mesh, #V by 3 positions, #F by 3 faces
 * Outputs: out #V by #V sparse matrix
 * Robustness: cotangents are computed from edge lengths with the area
 * clamped away from zero, so obtuse and near-degenerate triangles give
 * finite weights. */
#ifndef NEUV_GEOMETRY_COTAN_LAPLACIAN_H
#define NEUV_GEOMETRY_COTAN_LAPLACIAN_H

#include "geometry/sparse_matrix.h"
#include "mesh/mesh.h"

neuv_status cotan_laplacian(const neuv_mesh *m, sparse_matrix *out);

#endif
