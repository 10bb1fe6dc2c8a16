#include "atlas/uv_charts.h"

#include <stdlib.h>

#include "core/mem.h"
#include "core/union_find.h"

typedef struct half_edge { int lo, hi, face, corner; } half_edge;

static int cmp_half_edge(const void *a, const void *b)
{
    const half_edge *x = a, *y = b;
    if (x->lo != y->lo) return x->lo < y->lo ? -1 : 1;
    if (x->hi != y->hi) return x->hi < y->hi ? -1 : 1;
    if (x->face != y->face) return x->face < y->face ? -1 : 1;
    return x->corner - y->corner;
}

/* UV of vertex v as seen from face f (v must be a corner of f). */
static const double *corner_uv(const neuv_mesh *m, int f, int v)
{
    for (int k = 0; k < 3; k++)
        if (m->tri[3 * f + k] == v) return m->uv + 2 * m->tri_uv[3 * f + k];
    return NULL;
}

static int same_uv(const double *a, const double *b)
{
    return a && b && a[0] == b[0] && a[1] == b[1];
}

int uv_charts(const neuv_mesh *m, int *face_chart)
{
    size_t nh = (size_t)m->nf * 3;
    half_edge *he = mem_alloc(sizeof *he * (nh > 0 ? nh : 1));
    union_find uf;
    if (!he || uf_init(&uf, m->nf) != 0) { mem_free(he); return -1; }
    for (int f = 0; f < m->nf; f++)
        for (int k = 0; k < 3; k++) {
            int a = m->tri[3 * f + k], b = m->tri[3 * f + (k + 1) % 3];
            half_edge *h = &he[3 * (size_t)f + k];
            h->lo = a < b ? a : b;
            h->hi = a < b ? b : a;
            h->face = f;
            h->corner = k;
        }
    qsort(he, nh, sizeof *he, cmp_half_edge);
    for (size_t i = 0; i < nh;) {
        size_t j = i + 1;
        while (j < nh && he[j].lo == he[i].lo && he[j].hi == he[i].hi) j++;
        /* Every pair of faces around this edge (more than two only at non-manifold edges). */
        for (size_t p = i; p < j; p++)
            for (size_t q = p + 1; q < j; q++) {
                int f = he[p].face, g = he[q].face;
                if (f == g) continue;
                if (same_uv(corner_uv(m, f, he[p].lo), corner_uv(m, g, he[p].lo)) &&
                    same_uv(corner_uv(m, f, he[p].hi), corner_uv(m, g, he[p].hi)))
                    uf_union(&uf, f, g);
            }
        i = j;
    }
    mem_free(he);
    int n = uf_labels(&uf, face_chart);
    uf_free(&uf);
    return n;
}
