/* The losses of the surface parameterization module (Pokhariya et al. 2022,
 * "Discretization-Agnostic Deep Self-Supervised 3D Surface Parameterization",
 * section 3.2; SPEC.md section 1.3), written with the ops of nn/nn.h so that
 * their gradients come from the tape:
 *
 *   L = λ1 L_cycle + λ2 L_iso + λ3 L_angle + λ4 L_area,  λ = [1, 1, 0.001, 0.001]
 *
 * Every length and area is in the chart's normalized units (the caller scales
 * the chart before it reaches the networks). Index arrays are borrowed by the
 * tape: keep them alive until nn_backward returns. */
#ifndef NEUV_LOSSES_PARAM_LOSSES_H
#define NEUV_LOSSES_PARAM_LOSSES_H

#include "nn/nn.h"

/* Corners of a set of triangles arranged for the angle and area losses: row
 * r = k*nf + f is corner k of face f, at vertex p0[r], with the next corner
 * p1[r] and the one after p2[r] (counter-clockwise), so the first nf rows of
 * (p0, p1, p2) are the faces themselves. */
typedef struct param_corners {
    int nf;
    int *p0, *p1, *p2;   /* 3 #F each, vertex indices into the uv tensor */
} param_corners;

/* Builds the corner arrays of nf faces (tri: #F by 3 vertex indices).
 * Returns NEUV_OK or NEUV_ERR_NOMEM (free with param_corners_free). */
neuv_status param_corners_build(const int *tri, int nf, param_corners *c);
void param_corners_free(param_corners *c);

/* Cosine of each corner angle and area of each triangle of a 3D mesh, the
 * targets of L_angle and L_area.
 * Inputs:  pos  #V by 3 (float64), c corners
 * Outputs: cos3d  3 #F (row order of param_corners), area3d  #F */
void param_corner_targets(const double *pos, const param_corners *c, float *cos3d, float *area3d);

/* L_cycle = 1/N Σ_n ‖x_rec_n − x_n‖²: the inverse network must undo the forward one.
 * Inputs: x, x_rec  #N by 3. Output: 1 by 1. */
nn_tensor *param_loss_cycle(nn_ctx *ctx, nn_tensor *x, nn_tensor *x_rec);

/* L_iso = 1/P Σ_p (G_p − ‖uv_{i_p} − uv_{j_p}‖)² over vertex pairs closer than σ
 * on the surface: the map keeps short geodesic distances.
 * Inputs: uv #V by 2; pi, pj, g  #P (g: geodesic distances, a 1-column constant
 * built by the caller with nn_from). Output: 1 by 1. */
nn_tensor *param_loss_iso(nn_ctx *ctx, nn_tensor *uv, const int *pi, const int *pj, nn_tensor *g, int np);

/* L_angle = 1/|F| Σ_f 1/3 Σ_i (cos θ_i^uv − cos θ_i^3D)².
 * Inputs: uv #V by 2, c corners, cos3d  3 #F by 1 constant. Output: 1 by 1. */
nn_tensor *param_loss_angle(nn_ctx *ctx, nn_tensor *uv, const param_corners *c, nn_tensor *cos3d);

/* L_area = 1/|F| Σ_f (a_f^uv − a_f^3D)² with a_f^uv the SIGNED UV area times
 * orient_f (±1, the chart's orientation: a network may learn either a map or
 * its mirror image, and a face folded against its chart then costs more than
 * a correct one, which the unsigned area would not see).
 * Inputs: uv #V by 2, c corners, area3d #F by 1, orient #F by 1 constants.
 * Output: 1 by 1. */
nn_tensor *param_loss_area(nn_ctx *ctx, nn_tensor *uv, const param_corners *c, nn_tensor *area3d,
                           nn_tensor *orient);

/* Fold barrier (a neuv extension, not in the paper): 
 *   L_fold = 1/|F| Σ_f max(0, ε − orient_f a_f^uv / a_f^3D)²
 * zero while every face keeps at least ε of its 3D area with the chart's
 * orientation, growing quadratically as a face shrinks, degenerates or flips.
 * L_area cannot prevent folds at the paper's weight 0.001 (its gradient on a
 * small face is O(a_f^3D), ~1e-3 in normalized units); this term is
 * scale-free, so a folded face costs the same whatever its size.
 * Inputs: uv #V by 2, c corners, area3d #F by 1 (> 0), orient #F by 1
 * constants, eps the area ratio below which the barrier acts. Output: 1 by 1. */
nn_tensor *param_loss_fold_barrier(nn_ctx *ctx, nn_tensor *uv, const param_corners *c, nn_tensor *area3d,
                                   nn_tensor *orient, float eps);

/* Conformal energy (a neuv extension, used by the vertex refinement,
 * flatten/uv_refine.h): per face the Jacobian J of the affine map from the 3D
 * triangle (isometrically laid in its plane) to its UV triangle, and
 *   L_conf = Σ_f w_f (‖J‖_F² / max(orient_f det J, δ_f) − 2)
 * with w_f the face's share of the 3D area. ‖J‖²/det J = s1/s2 + s2/s1 for
 * singular values s1 ≥ s2, so this is the symmetric form of the quasi-
 * conformal error qce = s1/s2 of SPEC.md section 5 (0 for a conformal map).
 * δ_f = 1e-6 (in the units of det J, i.e. UV area / 3D area) only keeps a
 * folded face finite: the fold barrier keeps faces away from it.
 * Inputs: uv #V by 2, c corners, frame_inv #F by 4 (param_conformal_targets),
 * weight #F by 1, orient #F by 1 constants. Output: 1 by 1. */
nn_tensor *param_loss_conformal(nn_ctx *ctx, nn_tensor *uv, const param_corners *c, nn_tensor *frame_inv,
                                nn_tensor *weight, nn_tensor *orient);

/* Targets of L_conf: per face the inverse of the 2x2 matrix whose columns are
 * the edges p1 − p0 and p2 − p0 laid isometrically in the plane (row-major
 * B00 B01 B10 B11, so J = [u1 − u0, u2 − u0] B), and the face's share of the
 * total 3D area. A face of zero 3D area gets B = 0 and weight 0.
 * Inputs: pos #V by 3, c corners. Outputs: frame_inv #F by 4, weight #F. */
void param_conformal_targets(const double *pos, const param_corners *c, float *frame_inv, float *weight);

/* Signed UV area of each face (#F by 1), the quantity L_area compares. */
nn_tensor *param_face_area_uv(nn_ctx *ctx, nn_tensor *uv, const param_corners *c);

#endif
