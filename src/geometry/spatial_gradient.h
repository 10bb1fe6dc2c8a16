/* DiffusionNet's spatial gradient operators (Sharp et al. 2022, "DiffusionNet:
 * Discretization Agnostic Learning on Surfaces", section 3.3 / appendix):
 * at each vertex i the tangent-plane gradient (g_x, g_y), in i's frame
 * (e1, e2), of a per-vertex scalar u is the least-squares fit
 *     min_g Σ_j (⟨g, P_i(x_j − x_i)⟩ − (u_j − u_i))²
 * over i's one-ring edges ij, P_i the projection onto (e1, e2). Every edge
 * has weight 1, as in the reference implementation; a Tikhonov term of
 * 1e-12 × trace of the 2×2 normal matrix keeps a vertex with collinear
 * projected edges finite while leaving linear functions exact to round-off.
 *
 * Inputs:  m      mesh
 *          frames #V by 3 by 3 tangent frames (tangent_frames.h)
 * Outputs: gx, gy #V by #V sparse: (G_x u)_i, (G_y u)_i are the e1, e2
 *          components of the gradient at vertex i (caller frees) */
#ifndef NEUV_GEOMETRY_SPATIAL_GRADIENT_H
#define NEUV_GEOMETRY_SPATIAL_GRADIENT_H

#include "geometry/sparse_matrix.h"
#include "mesh/mesh.h"

neuv_status spatial_gradient(const neuv_mesh *m, const double *frames, sparse_matrix *gx, sparse_matrix *gy);

#endif
