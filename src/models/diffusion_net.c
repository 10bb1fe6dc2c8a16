/* DiffusionNet: see diffusion_net.h. */
#include "models/diffusion_net.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/mem.h"
#include "core/rng.h"

/* nn's view of a geometry operator. */
static nn_csr csr_view(const sparse_matrix *a)
{
    return (nn_csr){a->rows, a->cols, a->row_start, a->col, a->val};
}

neuv_status diffusion_net_create(diffusion_net *net, const diffusion_net_config *cfg, nn_params *params,
                                 const char *prefix)
{
    memset(net, 0, sizeof *net);
    if (!cfg || cfg->in < 1 || cfg->width < 1 || cfg->out < 1 || cfg->blocks < 1)
        return error_set(NEUV_ERR_INPUT, "DiffusionNet: sizes must be >= 1 (in %d, width %d, out %d, blocks %d)",
                         cfg ? cfg->in : 0, cfg ? cfg->width : 0, cfg ? cfg->out : 0, cfg ? cfg->blocks : 0);
    net->cfg = *cfg;
    int C = cfg->width;
    net->block = mem_calloc((size_t)cfg->blocks, sizeof *net->block);
    if (!net->block) return error_nomem("DiffusionNet blocks");
    rng r;
    rng_seed(&r, cfg->seed);
    char name[256];
    neuv_status st;
    snprintf(name, sizeof name, "%s.first", prefix);
    if ((st = nn_linear_create(&net->first, cfg->in, C, NN_ACT_NONE, &r, params, name))) goto fail;
    for (int b = 0; b < cfg->blocks; b++) {
        diffusion_net_block *B = &net->block[b];
        snprintf(name, sizeof name, "%s.block%d.time", prefix, b);
        if (!(B->time = nn_params_add(params, 1, C, name))) { st = error_last(); goto fail; }
        for (int c = 0; c < C; c++)
            B->time->data[c] = (float)(1e-4 * pow(1e3, C > 1 ? (double)c / (C - 1) : 0.5));
        /* Rotations start near the identity (real part I plus noise), so the
         * first features are the gradient magnitudes |∇h|², the rotation-free
         * invariant, and learning moves away from it. */
        snprintf(name, sizeof name, "%s.block%d.rot_re", prefix, b);
        if (!(B->rot_re = nn_params_add(params, C, C, name))) { st = error_last(); goto fail; }
        snprintf(name, sizeof name, "%s.block%d.rot_im", prefix, b);
        if (!(B->rot_im = nn_params_add(params, C, C, name))) { st = error_last(); goto fail; }
        double bound = 1.0 / sqrt((double)C);
        for (int i = 0; i < C * C; i++) {
            B->rot_re->data[i] = (float)((2 * rng_uniform(&r) - 1) * bound);
            B->rot_im->data[i] = (float)((2 * rng_uniform(&r) - 1) * bound);
        }
        snprintf(name, sizeof name, "%s.block%d.mlp0", prefix, b);
        if ((st = nn_linear_create(&B->mlp0, 3 * C, C, NN_ACT_RELU, &r, params, name))) goto fail;
        snprintf(name, sizeof name, "%s.block%d.mlp1", prefix, b);
        if ((st = nn_linear_create(&B->mlp1, C, C, NN_ACT_NONE, &r, params, name))) goto fail;
    }
    snprintf(name, sizeof name, "%s.last", prefix);
    if ((st = nn_linear_create(&net->last, C, cfg->out, NN_ACT_NONE, &r, params, name))) goto fail;
    return NEUV_OK;
fail:
    diffusion_net_free(net);
    return st;
}

void diffusion_net_free(diffusion_net *net)
{
    if (!net) return;
    mem_free(net->block);
    net->block = NULL;
}

void diffusion_net_geometry_free(diffusion_net_geometry *g)
{
    if (!g) return;
    mem_free(g->evecs);
    mem_free(g->neg_evals);
    mem_free(g->mass);
    mem_free(g->face_vertex);
    nn_sparse_free(&g->grad_x);
    nn_sparse_free(&g->grad_y);
    memset(g, 0, sizeof *g);
}

neuv_status diffusion_net_geometry_create(const neuv_mesh *m, const operators *ops, int k,
                                          diffusion_net_geometry *g)
{
    memset(g, 0, sizeof *g);
    if (!m || !ops || m->nv != ops->nv || m->nf < 1 || ops->k < 1)
        return error_set(NEUV_ERR_INPUT, "DiffusionNet: operators do not match the mesh (%d vs %d vertices)",
                         m ? m->nv : 0, ops ? ops->nv : 0);
    if (k <= 0 || k > ops->k) k = ops->k;
    int nv = m->nv, K = ops->k;
    g->nv = nv;
    g->nf = m->nf;
    g->k = k;
    double area = 0;
    for (int v = 0; v < nv; v++) area += ops->mass[v];
    if (!(area > 0)) return error_set(NEUV_ERR_INPUT, "DiffusionNet: mesh has zero total area");
    g->evecs = mem_alloc(sizeof(float) * (size_t)nv * k);
    g->neg_evals = mem_alloc(sizeof(float) * (size_t)k);
    g->mass = mem_alloc(sizeof(float) * (size_t)nv);
    g->face_vertex = mem_alloc(sizeof(int) * 3 * (size_t)m->nf);
    if (!g->evecs || !g->neg_evals || !g->mass || !g->face_vertex) {
        diffusion_net_geometry_free(g);
        return error_nomem("DiffusionNet operators");
    }
    /* Unit-area rescaling: Φ' = Φ sqrt(A) keeps Φ'ᵀ (M/A) Φ' = I, so the
     * projection Φᵀ M x is unchanged when written as Φ'ᵀ (M/A) x. */
    double sa = sqrt(area);
    for (int v = 0; v < nv; v++) {
        for (int i = 0; i < k; i++) g->evecs[(size_t)v * k + i] = (float)(ops->evecs[(size_t)v * K + i] * sa);
        g->mass[v] = (float)(ops->mass[v] / area);
    }
    for (int i = 0; i < k; i++) g->neg_evals[i] = (float)(-ops->evals[i] * area);
    for (int f = 0; f < m->nf; f++)
        for (int c = 0; c < 3; c++) g->face_vertex[(size_t)c * m->nf + f] = m->tri[3 * f + c];
    nn_csr gx = csr_view(&ops->grad_x), gy = csr_view(&ops->grad_y);
    neuv_status st = nn_sparse_from_csr(&gx, &g->grad_x);
    if (!st) st = nn_sparse_from_csr(&gy, &g->grad_y);
    if (st) { diffusion_net_geometry_free(g); return st; }
    size_t nnx = (size_t)g->grad_x.row_start[g->grad_x.rows], nny = (size_t)g->grad_y.row_start[g->grad_y.rows];
    for (size_t e = 0; e < nnx; e++) { g->grad_x.val[e] *= (float)sa; g->grad_x.t_val[e] *= (float)sa; }
    for (size_t e = 0; e < nny; e++) { g->grad_y.val[e] *= (float)sa; g->grad_y.t_val[e] *= (float)sa; }
    return NEUV_OK;
}

void diffusion_net_clamp_times(diffusion_net *net)
{
    for (int b = 0; b < net->cfg.blocks; b++) {
        nn_tensor *t = net->block[b].time;
        for (int c = 0; c < t->cols; c++)
            if (!(t->data[c] >= DIFFUSION_NET_MIN_TIME)) t->data[c] = DIFFUSION_NET_MIN_TIME;
    }
}

nn_tensor *learned_time_diffusion(nn_ctx *ctx, const diffusion_net_geometry *g, nn_tensor *x, nn_tensor *time)
{
    nn_tensor *evecs = nn_view(ctx, g->nv, g->k, g->evecs);
    nn_tensor *neg_evals = nn_view(ctx, g->k, 1, g->neg_evals);
    nn_tensor *mass = nn_view(ctx, g->nv, 1, g->mass);
    nn_tensor *coef = nn_matmul_t(ctx, evecs, 1, nn_mul(ctx, x, mass), 0);      /* k by C */
    nn_tensor *decay = nn_exp(ctx, nn_matmul(ctx, neg_evals, time));            /* k by C: exp(-λ_i t_c) */
    return nn_matmul(ctx, evecs, nn_mul(ctx, coef, decay));                      /* #V by C */
}

nn_tensor *spatial_gradient_features(nn_ctx *ctx, const diffusion_net_geometry *g, nn_tensor *h,
                                     nn_tensor *rot_re, nn_tensor *rot_im)
{
    nn_tensor *gx = nn_spmm(ctx, &g->grad_x, h);
    nn_tensor *gy = nn_spmm(ctx, &g->grad_y, h);
    nn_tensor *re = nn_sub(ctx, nn_matmul(ctx, gx, rot_re), nn_matmul(ctx, gy, rot_im));
    nn_tensor *im = nn_add(ctx, nn_matmul(ctx, gy, rot_re), nn_matmul(ctx, gx, rot_im));
    return nn_tanh(ctx, nn_add(ctx, nn_mul(ctx, gx, re), nn_mul(ctx, gy, im)));
}

nn_tensor *diffusion_net_block_forward(nn_ctx *ctx, const diffusion_net_block *b,
                                       const diffusion_net_geometry *g, nn_tensor *x)
{
    nn_tensor *h = learned_time_diffusion(ctx, g, x, b->time);
    nn_tensor *gf = spatial_gradient_features(ctx, g, h, b->rot_re, b->rot_im);
    nn_tensor *cat = nn_concat_cols(ctx, nn_concat_cols(ctx, x, h), gf);
    nn_tensor *y = nn_linear_forward(ctx, &b->mlp1, nn_relu(ctx, nn_linear_forward(ctx, &b->mlp0, cat)));
    return nn_add(ctx, x, y);
}

nn_tensor *diffusion_net_forward(nn_ctx *ctx, const diffusion_net *net, const diffusion_net_geometry *g,
                                 nn_tensor *x, nn_tensor **hidden)
{
    x = nn_linear_forward(ctx, &net->first, x);
    for (int b = 0; b < net->cfg.blocks; b++) x = diffusion_net_block_forward(ctx, &net->block[b], g, x);
    if (hidden) *hidden = x;
    return nn_linear_forward(ctx, &net->last, x);
}

nn_tensor *diffusion_net_vertices_to_faces(nn_ctx *ctx, const diffusion_net_geometry *g, nn_tensor *x)
{
    int nf = g->nf;
    nn_tensor *s = nn_add(ctx, nn_gather_rows(ctx, x, g->face_vertex, nf),
                          nn_gather_rows(ctx, x, g->face_vertex + nf, nf));
    s = nn_add(ctx, s, nn_gather_rows(ctx, x, g->face_vertex + 2 * (size_t)nf, nf));
    return nn_scale(ctx, s, 1.0f / 3.0f);
}

neuv_status diffusion_net_input_features(const neuv_mesh *m, const operators *ops, diffusion_net_features f,
                                         float **out, int *dim)
{
    *out = NULL;
    *dim = 0;
    int nv = m->nv;
    if (f == DIFFUSION_NET_HKS || f == DIFFUSION_NET_HKS_NORMALS) {
        if (!ops || !ops->hks || ops->n_hks < 1 || ops->nv != nv)
            return error_set(NEUV_ERR_INPUT, "DiffusionNet: no heat kernel signatures in the operators");
        int nh = ops->n_hks, d = nh + (f == DIFFUSION_NET_HKS_NORMALS ? 3 : 0);
        float *x = mem_alloc(sizeof(float) * (size_t)nv * d);
        if (!x) return error_nomem("HKS features");
        for (int v = 0; v < nv; v++)
            for (int i = 0; i < nh; i++) x[(size_t)v * d + i] = (float)ops->hks[(size_t)v * nh + i];
        if (f == DIFFUSION_NET_HKS_NORMALS) {
            double *n = mem_calloc(3 * (size_t)nv, sizeof(double));
            if (!n) { mem_free(x); return error_nomem("normal features"); }
            mesh_vertex_normals(m, n);
            for (int v = 0; v < nv; v++)
                for (int c = 0; c < 3; c++) x[(size_t)v * d + nh + c] = (float)n[3 * v + c];
            mem_free(n);
        }
        *out = x;
        *dim = d;
        return NEUV_OK;
    }
    if (f != DIFFUSION_NET_XYZ) return error_set(NEUV_ERR_INPUT, "DiffusionNet: unknown input features %d", (int)f);
    double c[3] = {0, 0, 0}, wsum = 0;
    for (int v = 0; v < nv; v++) {
        double w = ops && ops->mass ? ops->mass[v] : 1.0;
        for (int d = 0; d < 3; d++) c[d] += w * m->pos[3 * v + d];
        wsum += w;
    }
    if (!(wsum > 0)) return error_set(NEUV_ERR_INPUT, "DiffusionNet: mesh has zero area");
    for (int d = 0; d < 3; d++) c[d] /= wsum;
    double r = 0;
    for (int v = 0; v < nv; v++) {
        double q = 0;
        for (int d = 0; d < 3; d++) q += (m->pos[3 * v + d] - c[d]) * (m->pos[3 * v + d] - c[d]);
        if (q > r) r = q;
    }
    r = r > 0 ? 1.0 / sqrt(r) : 1.0;
    float *x = mem_alloc(sizeof(float) * (size_t)nv * 3);
    if (!x) return error_nomem("xyz features");
    for (int v = 0; v < nv; v++)
        for (int d = 0; d < 3; d++) x[3 * v + d] = (float)((m->pos[3 * v + d] - c[d]) * r);
    *out = x;
    *dim = 3;
    return NEUV_OK;
}

const char *diffusion_net_features_name(diffusion_net_features f)
{
    switch (f) {
    case DIFFUSION_NET_HKS: return "hks";
    case DIFFUSION_NET_XYZ: return "xyz";
    case DIFFUSION_NET_HKS_NORMALS: return "hks+normals";
    }
    return NULL;
}
