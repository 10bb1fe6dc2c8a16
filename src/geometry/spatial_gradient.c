/* Least-squares tangent-plane gradients over one-ring edges. See spatial_gradient.h. */
#include <string.h>

#include "core/error.h"
#include "geometry/spatial_gradient.h"

/* One-ring adjacency as a pattern-only sparse matrix (sorted, unique). */
static neuv_status vertex_adjacency(const neuv_mesh *m, sparse_matrix *adj)
{
    triplet_list t;
    neuv_status s = triplets_init(&t, m->nv, m->nv, (size_t)m->nf * 6);
    for (int f = 0; f < m->nf && !s; f++)
        for (int c = 0; c < 3 && !s; c++) {
            int a = m->tri[3 * f + c], b = m->tri[3 * f + (c + 1) % 3];
            if (a == b) continue;
            if (!(s = triplets_add(&t, a, b, 1.0))) s = triplets_add(&t, b, a, 1.0);
        }
    if (!s) s = sparse_from_triplets(&t, adj);
    triplets_free(&t);
    return s;
}

neuv_status spatial_gradient(const neuv_mesh *m, const double *frames, sparse_matrix *gx, sparse_matrix *gy)
{
    memset(gx, 0, sizeof *gx);
    memset(gy, 0, sizeof *gy);
    sparse_matrix adj;
    neuv_status s = vertex_adjacency(m, &adj);
    if (s) return s;
    size_t nnz = sparse_nnz(&adj) + (size_t)m->nv;
    triplet_list tx, ty;
    memset(&ty, 0, sizeof ty);
    if ((s = triplets_init(&tx, m->nv, m->nv, nnz)) || (s = triplets_init(&ty, m->nv, m->nv, nnz))) goto done;

    for (int i = 0; i < m->nv && !s; i++) {
        const double *e1 = frames + 9 * (size_t)i, *e2 = e1 + 3;
        const double *xi = m->pos + 3 * (size_t)i;
        /* Normal matrix AᵀA of the projected edge vectors. */
        double a11 = 0, a12 = 0, a22 = 0;
        for (int p = adj.row_start[i]; p < adj.row_start[i + 1]; p++) {
            const double *xj = m->pos + 3 * (size_t)adj.col[p];
            double e[3] = {xj[0] - xi[0], xj[1] - xi[1], xj[2] - xi[2]};
            double u = e[0] * e1[0] + e[1] * e1[1] + e[2] * e1[2];
            double v = e[0] * e2[0] + e[1] * e2[1] + e[2] * e2[2];
            a11 += u * u;
            a12 += u * v;
            a22 += v * v;
        }
        double reg = 1e-12 * (a11 + a22);
        a11 += reg;
        a22 += reg;
        double det = a11 * a22 - a12 * a12;
        if (!(det > 0)) continue; /* isolated vertex: zero gradient row */
        double i11 = a22 / det, i12 = -a12 / det, i22 = a11 / det;
        /* g = (AᵀA)⁻¹ Aᵀ (u_j − u_i): coefficient of u_j is (AᵀA)⁻¹ a_j,
         * and u_i gets minus their sum. */
        double sx = 0, sy = 0;
        for (int p = adj.row_start[i]; p < adj.row_start[i + 1] && !s; p++) {
            int j = adj.col[p];
            const double *xj = m->pos + 3 * (size_t)j;
            double e[3] = {xj[0] - xi[0], xj[1] - xi[1], xj[2] - xi[2]};
            double u = e[0] * e1[0] + e[1] * e1[1] + e[2] * e1[2];
            double v = e[0] * e2[0] + e[1] * e2[1] + e[2] * e2[2];
            double cx = i11 * u + i12 * v, cy = i12 * u + i22 * v;
            sx += cx;
            sy += cy;
            if (!(s = triplets_add(&tx, i, j, cx))) s = triplets_add(&ty, i, j, cy);
        }
        if (!s && !(s = triplets_add(&tx, i, i, -sx))) s = triplets_add(&ty, i, i, -sy);
    }
    if (!s && !(s = sparse_from_triplets(&tx, gx))) {
        s = sparse_from_triplets(&ty, gy);
        if (s) sparse_free(gx);
    }
done:
    triplets_free(&tx);
    triplets_free(&ty);
    sparse_free(&adj);
    return s;
}
