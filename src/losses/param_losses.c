/* Parameterization losses (Pokhariya et al. 2022, section 3.2) on the nn tape. */
#include "losses/param_losses.h"

#include <math.h>
#include <stdlib.h>

#include "core/error.h"
#include "core/mem.h"

neuv_status param_corners_build(const int *tri, int nf, param_corners *c)
{
    c->nf = nf;
    size_t n = (size_t)3 * (size_t)(nf > 0 ? nf : 1);
    c->p0 = mem_alloc(n * sizeof(int));
    c->p1 = mem_alloc(n * sizeof(int));
    c->p2 = mem_alloc(n * sizeof(int));
    if (!c->p0 || !c->p1 || !c->p2) {
        param_corners_free(c);
        return error_set(NEUV_ERR_NOMEM, "out of memory for %d triangle corners", nf);
    }
    for (int k = 0; k < 3; k++)
        for (int f = 0; f < nf; f++) {
            int r = k * nf + f;
            c->p0[r] = tri[3 * f + k];
            c->p1[r] = tri[3 * f + (k + 1) % 3];
            c->p2[r] = tri[3 * f + (k + 2) % 3];
        }
    return NEUV_OK;
}

void param_corners_free(param_corners *c)
{
    mem_free(c->p0); mem_free(c->p1); mem_free(c->p2);
    c->p0 = c->p1 = c->p2 = NULL;
    c->nf = 0;
}

void param_corner_targets(const double *pos, const param_corners *c, float *cos3d, float *area3d)
{
    int nf = c->nf;
    for (int r = 0; r < 3 * nf; r++) {
        const double *a = pos + 3 * c->p0[r], *b = pos + 3 * c->p1[r], *d = pos + 3 * c->p2[r];
        double e1[3], e2[3];
        for (int k = 0; k < 3; k++) { e1[k] = b[k] - a[k]; e2[k] = d[k] - a[k]; }
        double dot = e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2];
        double n1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
        double n2 = sqrt(e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]);
        cos3d[r] = n1 > 0 && n2 > 0 ? (float)(dot / (n1 * n2)) : 1.0f;
        if (r < nf) {
            double x = e1[1] * e2[2] - e1[2] * e2[1];
            double y = e1[2] * e2[0] - e1[0] * e2[2];
            double z = e1[0] * e2[1] - e1[1] * e2[0];
            area3d[r] = (float)(0.5 * sqrt(x * x + y * y + z * z));
        }
    }
}

nn_tensor *param_loss_cycle(nn_ctx *ctx, nn_tensor *x, nn_tensor *x_rec)
{
    nn_tensor *d2 = nn_sum(ctx, nn_square(ctx, nn_sub(ctx, x_rec, x)), NN_COLS);
    return nn_mean(ctx, d2, NN_ALL);
}

nn_tensor *param_loss_iso(nn_ctx *ctx, nn_tensor *uv, const int *pi, const int *pj, nn_tensor *g, int np)
{
    nn_tensor *d = nn_sub(ctx, nn_gather_rows(ctx, uv, pi, np), nn_gather_rows(ctx, uv, pj, np));
    /* eps keeps the norm differentiable when two UVs coincide (1e-12 in squared units). */
    nn_tensor *len = nn_row_norm(ctx, d, 1e-12f);
    return nn_mean(ctx, nn_square(ctx, nn_sub(ctx, len, g)), NN_ALL);
}

nn_tensor *param_loss_angle(nn_ctx *ctx, nn_tensor *uv, const param_corners *c, nn_tensor *cos3d)
{
    int n = 3 * c->nf;
    nn_tensor *a = nn_gather_rows(ctx, uv, c->p0, n);
    nn_tensor *e1 = nn_sub(ctx, nn_gather_rows(ctx, uv, c->p1, n), a);
    nn_tensor *e2 = nn_sub(ctx, nn_gather_rows(ctx, uv, c->p2, n), a);
    nn_tensor *cosuv = nn_row_cosine(ctx, e1, e2, 1e-12f);
    /* mean over the 3|F| corners = 1/|F| Σ_f 1/3 Σ_i */
    return nn_mean(ctx, nn_square(ctx, nn_sub(ctx, cosuv, cos3d)), NN_ALL);
}

nn_tensor *param_face_area_uv(nn_ctx *ctx, nn_tensor *uv, const param_corners *c)
{
    int nf = c->nf;
    nn_tensor *a = nn_gather_rows(ctx, uv, c->p0, nf);
    nn_tensor *e1 = nn_sub(ctx, nn_gather_rows(ctx, uv, c->p1, nf), a);
    nn_tensor *e2 = nn_sub(ctx, nn_gather_rows(ctx, uv, c->p2, nf), a);
    nn_tensor *cross = nn_sub(ctx, nn_mul(ctx, nn_slice_cols(ctx, e1, 0, 1), nn_slice_cols(ctx, e2, 1, 1)),
                              nn_mul(ctx, nn_slice_cols(ctx, e1, 1, 1), nn_slice_cols(ctx, e2, 0, 1)));
    return nn_scale(ctx, cross, 0.5f);
}

nn_tensor *param_loss_area(nn_ctx *ctx, nn_tensor *uv, const param_corners *c, nn_tensor *area3d,
                           nn_tensor *orient)
{
    nn_tensor *auv = nn_mul(ctx, param_face_area_uv(ctx, uv, c), orient);
    return nn_mean(ctx, nn_square(ctx, nn_sub(ctx, auv, area3d)), NN_ALL);
}

nn_tensor *param_loss_fold_barrier(nn_ctx *ctx, nn_tensor *uv, const param_corners *c, nn_tensor *area3d,
                                   nn_tensor *orient, float eps)
{
    /* The clamp only guards a face of zero 3D area (none after cleaning). */
    nn_tensor *ratio = nn_div(ctx, nn_mul(ctx, param_face_area_uv(ctx, uv, c), orient), nn_clamp_min(ctx, area3d, 1e-12f));
    nn_tensor *short_by = nn_relu(ctx, nn_add_const(ctx, nn_scale(ctx, ratio, -1.0f), eps));
    return nn_mean(ctx, nn_square(ctx, short_by), NN_ALL);
}

void param_conformal_targets(const double *pos, const param_corners *c, float *frame_inv, float *weight)
{
    int nf = c->nf;
    double total = 0;
    for (int f = 0; f < nf; f++) {
        const double *a = pos + 3 * c->p0[f], *b = pos + 3 * c->p1[f], *d = pos + 3 * c->p2[f];
        double e1[3], e2[3];
        for (int k = 0; k < 3; k++) { e1[k] = b[k] - a[k]; e2[k] = d[k] - a[k]; }
        double l1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
        double x2 = l1 > 0 ? (e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2]) / l1 : 0;
        double cx = e1[1] * e2[2] - e1[2] * e2[1], cy = e1[2] * e2[0] - e1[0] * e2[2], cz = e1[0] * e2[1] - e1[1] * e2[0];
        double y2 = l1 > 0 ? sqrt(cx * cx + cy * cy + cz * cz) / l1 : 0;
        /* P = [[l1, x2], [0, y2]]; P^-1 = [[1/l1, -x2/(l1 y2)], [0, 1/y2]] */
        float *B = frame_inv + 4 * (size_t)f;
        double det = l1 * y2;
        if (det > 0) {
            B[0] = (float)(1 / l1); B[1] = (float)(-x2 / det); B[2] = 0; B[3] = (float)(1 / y2);
        } else {
            B[0] = B[1] = B[2] = B[3] = 0;
        }
        weight[f] = (float)(0.5 * det);
        total += 0.5 * det;
    }
    for (int f = 0; f < nf; f++) weight[f] = total > 0 ? (float)(weight[f] / total) : 0;
}

nn_tensor *param_loss_conformal(nn_ctx *ctx, nn_tensor *uv, const param_corners *c, nn_tensor *frame_inv,
                                nn_tensor *weight, nn_tensor *orient)
{
    int nf = c->nf;
    nn_tensor *a = nn_gather_rows(ctx, uv, c->p0, nf);
    nn_tensor *e1 = nn_sub(ctx, nn_gather_rows(ctx, uv, c->p1, nf), a);
    nn_tensor *e2 = nn_sub(ctx, nn_gather_rows(ctx, uv, c->p2, nf), a);
    /* columns of J: J e_x = e1 B00 + e2 B10, J e_y = e1 B01 + e2 B11 (each #F by 2) */
    nn_tensor *jx = nn_add(ctx, nn_mul(ctx, e1, nn_slice_cols(ctx, frame_inv, 0, 1)),
                           nn_mul(ctx, e2, nn_slice_cols(ctx, frame_inv, 2, 1)));
    nn_tensor *jy = nn_add(ctx, nn_mul(ctx, e1, nn_slice_cols(ctx, frame_inv, 1, 1)),
                           nn_mul(ctx, e2, nn_slice_cols(ctx, frame_inv, 3, 1)));
    nn_tensor *frob = nn_add(ctx, nn_sum(ctx, nn_square(ctx, jx), NN_COLS), nn_sum(ctx, nn_square(ctx, jy), NN_COLS));
    nn_tensor *det = nn_sub(ctx, nn_mul(ctx, nn_slice_cols(ctx, jx, 0, 1), nn_slice_cols(ctx, jy, 1, 1)),
                            nn_mul(ctx, nn_slice_cols(ctx, jx, 1, 1), nn_slice_cols(ctx, jy, 0, 1)));
    det = nn_clamp_min(ctx, nn_mul(ctx, det, orient), 1e-6f);
    nn_tensor *energy = nn_mul(ctx, nn_add_const(ctx, nn_div(ctx, frob, det), -2.0f), weight);
    return nn_sum(ctx, energy, NN_ALL);
}
