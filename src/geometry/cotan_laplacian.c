/* Cotangent Laplacian (Pinkall and Polthier 1993; Meyer et al. 2003, eq. 5)
 * in weak form: L_ij = -(cot α_ij + cot β_ij)/2, L_ii = -Σ_j L_ij. */
#include <math.h>

#include "core/error.h"
#include "geometry/cotan_laplacian.h"

/* Squared length of the edge between vertices a and b. */
static double edge_len2(const double *p, int a, int b)
{
    double dx = p[3 * a] - p[3 * b], dy = p[3 * a + 1] - p[3 * b + 1], dz = p[3 * a + 2] - p[3 * b + 2];
    return dx * dx + dy * dy + dz * dz;
}

neuv_status cotan_laplacian(const neuv_mesh *m, sparse_matrix *out)
{
    triplet_list t;
    neuv_status s = triplets_init(&t, m->nv, m->nv, (size_t)m->nf * 12);
    if (s) return s;

    /* Floor for the doubled face area, relative to the mean squared edge
     * length, so a sliver triangle gives a large but finite cotangent. */
    double mean_l2 = 0.0;
    for (int f = 0; f < m->nf; f++) {
        const int *v = m->tri + 3 * f;
        mean_l2 += edge_len2(m->pos, v[0], v[1]) + edge_len2(m->pos, v[1], v[2]) + edge_len2(m->pos, v[2], v[0]);
    }
    mean_l2 = m->nf ? mean_l2 / (3.0 * m->nf) : 1.0;
    double area_floor = 1e-12 * (mean_l2 > 0 ? mean_l2 : 1.0);

    for (int f = 0; f < m->nf && !s; f++) {
        const int *v = m->tri + 3 * f;
        /* l2[c] is the squared length of the edge opposite corner c. */
        double l2[3] = {edge_len2(m->pos, v[1], v[2]), edge_len2(m->pos, v[2], v[0]), edge_len2(m->pos, v[0], v[1])};
        /* Heron-type area from squared lengths: 16 A² = 4 l1² l2² - (l1² + l2² - l0²)²;
         * robust for obtuse triangles, clamped for degenerate ones. */
        double q = l2[1] + l2[2] - l2[0];
        double a16 = 4.0 * l2[1] * l2[2] - q * q;
        double twice_area = a16 > 0 ? 0.5 * sqrt(a16) : 0.0;
        if (twice_area < area_floor) twice_area = area_floor;
        for (int c = 0; c < 3 && !s; c++) {
            /* cot of the angle at corner c = (l_a² + l_b² - l_c²) / (4 A), with l_c opposite c. */
            double cot = (l2[(c + 1) % 3] + l2[(c + 2) % 3] - l2[c]) / (2.0 * twice_area);
            double w = 0.5 * cot;
            int i = v[(c + 1) % 3], j = v[(c + 2) % 3];
            if ((s = triplets_add(&t, i, j, -w))) break;
            if ((s = triplets_add(&t, j, i, -w))) break;
            if ((s = triplets_add(&t, i, i, w))) break;
            s = triplets_add(&t, j, j, w);
        }
    }
    if (!s) s = sparse_from_triplets(&t, out);
    triplets_free(&t);
    return s;
}
