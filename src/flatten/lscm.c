/* Least squares conformal maps (Lévy, Petitjean, Ray, Maillot 2002, section
 * 3.2): per triangle, the Cauchy–Riemann residuals u_x - v_y and u_y + v_x in
 * the triangle's own orthonormal frame, weighted by its area, summed in the
 * least-squares sense; two pinned vertices remove the similarity freedom and
 * the normal equations (symmetric positive definite) go through CHOLMOD. */
#include "flatten/lscm.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/mem.h"
#include "flatten/disk_topology.h"
#include "flatten/uv_orient.h"
#include "geometry/cholesky.h"
#include "geometry/sparse_matrix.h"

static double dist2(const double *a, const double *b)
{
    return (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]);
}

/* The boundary pair farthest apart in 3D; ties go to the first pair found,
 * so the choice is deterministic. */
static void farthest_pair(const neuv_mesh *m, const int *b, int nb, int *pa, int *pb)
{
    int best_a = b[0], best_b = b[nb / 2];
    double best = -1;
    if (nb <= 4096) {
        for (int i = 0; i < nb; i++)
            for (int j = i + 1; j < nb; j++) {
                double d = dist2(m->pos + 3 * b[i], m->pos + 3 * b[j]);
                if (d > best) { best = d; best_a = b[i]; best_b = b[j]; }
            }
    } else {
        /* Double sweep: farthest from the first vertex, then farthest from that. */
        int a = b[0];
        for (int sweep = 0; sweep < 2; sweep++) {
            int far = a;
            best = -1;
            for (int i = 0; i < nb; i++) {
                double d = dist2(m->pos + 3 * a, m->pos + 3 * b[i]);
                if (d > best) { best = d; far = b[i]; }
            }
            if (sweep == 0) a = far;
            else { best_a = a; best_b = far; }
        }
    }
    *pa = best_a;
    *pb = best_b;
}

/* The least-squares system and its solve. Either two pins (pin, pin_uv) or,
 * with anchor != NULL and pin == NULL, no pin and the anchor term
 * w sum_v a_v |uv_v - anchor_v|^2 (a_v: a third of the vertex's face areas). */
static neuv_status lscm_solve(const neuv_mesh *m, const int *pin, double pin_uv[2][2], const double *anchor,
                              double w, double *uv)
{
    neuv_status s = NEUV_OK;
    const int nv = m->nv;
    int no_pin[2] = {-1, -1};
    if (!pin) pin = no_pin;

    /* Unknown index of (vertex v, coordinate c) at dof[2v + c]: -1 for the
     * pins and for vertices no face uses. */
    int *dof = mem_alloc(sizeof(int) * 2 * (size_t)nv);
    unsigned char *used = mem_calloc((size_t)nv, 1);
    double *rhs = NULL, *x = NULL;
    triplet_list t = {0};
    sparse_matrix k = {0};
    cholesky *chol = NULL;
    if (!dof || !used) { s = error_nomem("LSCM unknowns"); goto done; }
    for (int i = 0; i < 3 * m->nf; i++) used[m->tri[i]] = 1;
    if (pin[0] >= 0) used[pin[0]] = used[pin[1]] = 0;
    int n = 0;
    for (int v = 0; v < nv; v++) {
        dof[2 * v] = used[v] ? n++ : -1;
        dof[2 * v + 1] = used[v] ? n++ : -1;
    }
    rhs = mem_calloc((size_t)(n > 0 ? n : 1), sizeof(double));
    x = mem_alloc(sizeof(double) * (size_t)(n > 0 ? n : 1));
    if (!rhs || !x) { s = error_nomem("LSCM system"); goto done; }
    if ((s = triplets_init(&t, n, n, (size_t)m->nf * 72 + (size_t)n))) goto done;

    double mean_area = 0;
    for (int f = 0; f < m->nf; f++) mean_area += mesh_face_area(m, f);
    mean_area /= m->nf;
    for (int f = 0; f < m->nf && !s; f++) {
        const int *v = m->tri + 3 * f;
        const double *p0 = m->pos + 3 * v[0], *p1 = m->pos + 3 * v[1], *p2 = m->pos + 3 * v[2];
        double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
        double e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
        double nrm[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        double twice_area = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
        double l1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
        /* A degenerate face constrains nothing conformally; skip it. */
        if (!(twice_area > 1e-14 * mean_area) || !(l1 > 0)) continue;
        /* The triangle in its own frame: q0 = 0, q1 = (|e1|, 0), q2 = (e2·x, e2·y). */
        double q[3][2] = {{0, 0}, {l1, 0}, {(e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2]) / l1, twice_area / l1}};
        /* ∇φ_j = rot90(q_{j+2} - q_{j+1}) / (2A); the residuals
         * u_x - v_y and u_y + v_x times sqrt(A) make the two rows. */
        double sc = 1.0 / (2.0 * sqrt(0.5 * twice_area)); /* 1 / (2 sqrt(A)) */
        double row[2][6];
        for (int j = 0; j < 3; j++) {
            double ex = q[(j + 2) % 3][0] - q[(j + 1) % 3][0], ey = q[(j + 2) % 3][1] - q[(j + 1) % 3][1];
            row[0][j] = -ey * sc; row[0][3 + j] = -ex * sc; /* u_x - v_y */
            row[1][j] = ex * sc;  row[1][3 + j] = -ey * sc; /* u_y + v_x */
        }
        int idx[6];
        double known[6];
        for (int j = 0; j < 3; j++)
            for (int c = 0; c < 2; c++) {
                idx[3 * c + j] = dof[2 * v[j] + c];
                known[3 * c + j] = v[j] == pin[0] ? pin_uv[0][c] : v[j] == pin[1] ? pin_uv[1][c] : 0.0;
            }
        for (int r = 0; r < 2 && !s; r++) {
            double cst = 0;
            for (int a = 0; a < 6; a++) if (idx[a] < 0) cst += row[r][a] * known[a];
            for (int a = 0; a < 6 && !s; a++) {
                if (idx[a] < 0) continue;
                rhs[idx[a]] -= row[r][a] * cst;
                for (int b = 0; b < 6 && !s; b++)
                    if (idx[b] >= 0) s = triplets_add(&t, idx[a], idx[b], row[r][a] * row[r][b]);
            }
        }
    }
    if (anchor)
        for (int f = 0; f < m->nf && !s; f++) {
            double a = w * mesh_face_area(m, f) / 3;
            for (int j = 0; j < 3 && !s; j++) {
                int v = m->tri[3 * f + j];
                for (int c = 0; c < 2 && !s; c++) {
                    rhs[dof[2 * v + c]] += a * anchor[2 * v + c];
                    s = triplets_add(&t, dof[2 * v + c], dof[2 * v + c], a);
                }
            }
        }
    if (s) goto done;
    if ((s = sparse_from_triplets(&t, &k))) goto done;
    /* A whisker of Tikhonov regularization (1e-15 of the mean diagonal) keeps
     * the system definite if a vertex only touches skipped degenerate faces. */
    {
        double diag_mean = 0;
        for (int r = 0; r < n; r++)
            for (int p = k.row_start[r]; p < k.row_start[r + 1]; p++)
                if (k.col[p] == r) diag_mean += k.val[p];
        diag_mean = n ? diag_mean / n : 1.0;
        for (int r = 0; r < n; r++)
            for (int p = k.row_start[r]; p < k.row_start[r + 1]; p++)
                if (k.col[p] == r) k.val[p] += 1e-15 * diag_mean;
    }
    if (n > 0) {
        s = cholesky_factor(&k, &chol);
        if (s == NEUV_ERR_INPUT) { s = error_set(NEUV_ERR_INTERNAL, "LSCM: the normal equations are not positive definite"); goto done; }
        if (s) goto done;
        if ((s = cholesky_solve(chol, rhs, x, 1))) goto done;
    }
    for (int v = 0; v < nv; v++)
        for (int c = 0; c < 2; c++)
            uv[2 * v + c] = dof[2 * v + c] >= 0 ? x[dof[2 * v + c]]
                          : v == pin[0] ? pin_uv[0][c] : v == pin[1] ? pin_uv[1][c] : 0.0;
    if (!anchor) flatten_orient_ccw(m, uv);
done:
    cholesky_free(chol);
    sparse_free(&k);
    triplets_free(&t);
    mem_free(dof); mem_free(used); mem_free(rhs); mem_free(x);
    return s;
}

neuv_status lscm(const neuv_mesh *m, double *uv)
{
    int *boundary = NULL, nb = 0;
    neuv_status s = flatten_require_disk(m, &boundary, &nb);
    if (s) return s;
    int pin[2];
    farthest_pair(m, boundary, nb, &pin[0], &pin[1]);
    mem_free(boundary);
    double pin_uv[2][2] = {{0, 0}, {sqrt(dist2(m->pos + 3 * pin[0], m->pos + 3 * pin[1])), 0}};
    return lscm_solve(m, pin, pin_uv, NULL, 0, uv);
}

neuv_status lscm_anchored(const neuv_mesh *m, const double *anchor, double lambda, double *uv)
{
    neuv_status s = flatten_require_disk(m, NULL, NULL);
    if (s) return s;
    if (!(lambda > 0)) return error_set(NEUV_ERR_INPUT, "anchored LSCM needs a positive weight, not %g", lambda);
    double area = mesh_total_area(m);
    if (!(area > 0)) return error_set(NEUV_ERR_INPUT, "anchored LSCM: the chart has no area");
    return lscm_solve(m, NULL, NULL, anchor, lambda / area, uv);
}
