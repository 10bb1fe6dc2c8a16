/* PatchNet's self-supervised losses (SPEC.md section 1.1), as nn ops so they
 * differentiate with respect to the soft assignment P (#F by K, rows summing
 * to one, e.g. a softmax).
 *
 *   L_cos = Σ_f a_f Σ_k P_fk (1 − n_f·m_k) / Σ_f a_f,
 *           m_k = normalize(Σ_f a_f P_fk n_f)
 *   L_geo = Σ_k Σ_{f,g} a_f a_g P_fk P_gk D_fg / Σ_k (Σ_f a_f P_fk)²
 *
 * L_geo never forms the #F by #F matrix D: the numerator's sum over f is
 * estimated from S source faces drawn uniformly without replacement,
 *     Σ_f X_f ≈ (F / S) Σ_{s in sample} X_s,
 * an unbiased estimator of the full sum (every face is a source with
 * probability S/F); the sum over g and the denominator are exact. With
 * S = F (every face a source, any order) the value is exact. Memory: S by F. */
#ifndef NEUV_LOSSES_PATCH_LOSSES_H
#define NEUV_LOSSES_PATCH_LOSSES_H

#include "nn/nn.h"

/* Inputs:  P        #F by K soft assignment
 *          area     #F by 1 face areas (constant)
 *          normal   #F by 3 unit face normals (constant)
 * Output:  1 by 1 L_cos. */
nn_tensor *patch_loss_cos(nn_ctx *ctx, nn_tensor *P, nn_tensor *area, nn_tensor *normal);

/* Inputs:  P        #F by K soft assignment
 *          area     #F by 1 face areas (constant)
 *          source   #S source face indices (borrowed until backward)
 *          dist     #S by #F constant: row s holds D between face source[s]
 *                   and every face (geodesic distance / geodesic diameter)
 * Output:  1 by 1 L_geo estimate (exact when the sources are all faces). */
nn_tensor *patch_loss_geo(nn_ctx *ctx, nn_tensor *P, nn_tensor *area, const int *source, int nsource,
                          nn_tensor *dist);

#endif
