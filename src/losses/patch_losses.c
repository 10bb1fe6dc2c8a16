/* PatchNet losses: see patch_losses.h. */
#include "losses/patch_losses.h"

nn_tensor *patch_loss_cos(nn_ctx *ctx, nn_tensor *P, nn_tensor *area, nn_tensor *normal)
{
    /* m_k: rows of Pᵀ (a ⊙ n), normalized; the epsilon only guards an empty patch. */
    nn_tensor *an = nn_mul(ctx, normal, area);                          /* #F by 3 */
    nn_tensor *s = nn_matmul_t(ctx, P, 1, an, 0);                        /* K by 3 */
    nn_tensor *mk = nn_div(ctx, s, nn_row_norm(ctx, s, 1e-12f));         /* K by 3 */
    nn_tensor *cos = nn_matmul_t(ctx, normal, 0, mk, 1);                 /* #F by K: n_f · m_k */
    nn_tensor *w = nn_mul(ctx, P, area);                                 /* a_f P_fk */
    nn_tensor *num = nn_sum(ctx, nn_mul(ctx, w, nn_add_const(ctx, nn_scale(ctx, cos, -1.0f), 1.0f)), NN_ALL);
    return nn_div(ctx, num, nn_sum(ctx, area, NN_ALL));
}

nn_tensor *patch_loss_geo(nn_ctx *ctx, nn_tensor *P, nn_tensor *area, const int *source, int nsource,
                          nn_tensor *dist)
{
    if (!P) return NULL;
    int nf = P->rows;
    nn_tensor *q = nn_mul(ctx, P, area);                                 /* #F by K: a_g P_gk */
    nn_tensor *t = nn_matmul(ctx, dist, q);                              /* #S by K: Σ_g D_sg a_g P_gk */
    nn_tensor *qs = nn_gather_rows(ctx, q, source, nsource);             /* #S by K: a_s P_sk */
    nn_tensor *num = nn_scale(ctx, nn_sum(ctx, nn_mul(ctx, qs, t), NN_ALL), (float)nf / (float)nsource);
    nn_tensor *den = nn_sum(ctx, nn_square(ctx, nn_sum(ctx, q, NN_ROWS)), NN_ALL);
    return nn_div(ctx, num, den);
}
