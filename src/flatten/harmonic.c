/* Harmonic flattening with cotangent weights and a circular boundary. */
#include "flatten/harmonic.h"

#include <math.h>
#include <stdlib.h>

#include "core/error.h"
#include "core/mem.h"
#include "flatten/disk_topology.h"
#include "flatten/uv_orient.h"
#include "geometry/cholesky.h"
#include "geometry/cotan_laplacian.h"
#include "geometry/sparse_matrix.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

neuv_status harmonic(const neuv_mesh *m, double *uv)
{
    int *boundary = NULL, nb = 0;
    neuv_status s = flatten_require_disk(m, &boundary, &nb);
    if (s) return s;
    const int nv = m->nv;
    int *index = mem_alloc(sizeof(int) * (size_t)nv); /* interior unknown, or -1 */
    unsigned char *fixed = mem_calloc((size_t)nv, 1);
    double *seg = mem_alloc(sizeof(double) * (size_t)nb);
    double *rhs = NULL, *x = NULL;
    sparse_matrix lap = {0}, lii = {0};
    triplet_list t = {0};
    cholesky *chol = NULL;
    if (!index || !fixed || !seg) { s = error_nomem("harmonic map"); goto done; }

    for (int v = 0; v < nv; v++) uv[2 * v] = uv[2 * v + 1] = 0.0;
    /* Boundary onto the unit circle, angle proportional to arc length. */
    double total = 0;
    for (int k = 0; k < nb; k++) {
        const double *a = m->pos + 3 * boundary[k], *b = m->pos + 3 * boundary[(k + 1) % nb];
        seg[k] = sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
        total += seg[k];
    }
    if (!(total > 0)) { s = error_set(NEUV_ERR_INPUT, "harmonic map: the boundary loop has zero length"); goto done; }
    double run = 0;
    for (int k = 0; k < nb; k++) {
        double angle = 2.0 * M_PI * run / total;
        uv[2 * boundary[k]] = cos(angle);
        uv[2 * boundary[k] + 1] = sin(angle);
        fixed[boundary[k]] = 1;
        run += seg[k];
    }
    /* Vertices no face uses stay at the origin, outside the system. */
    for (int v = 0; v < nv; v++) index[v] = -1;
    int n = 0;
    {
        unsigned char *referenced = mem_calloc((size_t)nv, 1);
        if (!referenced) { s = error_nomem("harmonic map"); goto done; }
        for (int i = 0; i < 3 * m->nf; i++) referenced[m->tri[i]] = 1;
        for (int v = 0; v < nv; v++)
            if (referenced[v] && !fixed[v]) index[v] = n++;
        mem_free(referenced);
    }
    if ((s = cotan_laplacian(m, &lap))) goto done;
    if (n > 0) {
        rhs = mem_calloc(2 * (size_t)n, sizeof(double));
        x = mem_alloc(sizeof(double) * 2 * (size_t)n);
        if (!rhs || !x) { s = error_nomem("harmonic map"); goto done; }
        if ((s = triplets_init(&t, n, n, sparse_nnz(&lap)))) goto done;
        for (int r = 0; r < nv && !s; r++) {
            int i = index[r];
            if (i < 0) continue;
            for (int p = lap.row_start[r]; p < lap.row_start[r + 1] && !s; p++) {
                int c = lap.col[p];
                if (index[c] >= 0) s = triplets_add(&t, i, index[c], lap.val[p]);
                else if (fixed[c]) {
                    /* L_II u_I = -L_IB u_B */
                    rhs[i] -= lap.val[p] * uv[2 * c];
                    rhs[n + i] -= lap.val[p] * uv[2 * c + 1];
                }
            }
        }
        if (s) goto done;
        if ((s = sparse_from_triplets(&t, &lii))) goto done;
        s = cholesky_factor(&lii, &chol);
        if (s == NEUV_ERR_INPUT) { s = error_set(NEUV_ERR_INTERNAL, "harmonic map: the interior Laplacian is not positive definite"); goto done; }
        if (s) goto done;
        if ((s = cholesky_solve(chol, rhs, x, 2))) goto done;
        for (int v = 0; v < nv; v++)
            if (index[v] >= 0) {
                uv[2 * v] = x[index[v]];
                uv[2 * v + 1] = x[n + index[v]];
            }
    }
    flatten_orient_ccw(m, uv);
done:
    cholesky_free(chol);
    sparse_free(&lii);
    sparse_free(&lap);
    triplets_free(&t);
    mem_free(boundary); mem_free(index); mem_free(fixed); mem_free(seg); mem_free(rhs); mem_free(x);
    return s;
}
