#include "charts/face_graph.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/mem.h"

typedef struct half_edge_key { int lo, hi, he; } half_edge_key;

static int half_edge_cmp_hi(const void *pa, const void *pb)
{
    const half_edge_key *a = pa, *b = pb;
    if (a->hi != b->hi) return a->hi < b->hi ? -1 : 1;
    return (a->he > b->he) - (a->he < b->he);
}

/* keys (n, in half-edge order) into out ordered by (lo, hi, he): a
 * counting sort on lo, which keeps the half-edge order, then a sort on hi
 * within each lo (insertion: a vertex has a handful of edges; qsort for a
 * vertex of many, a fan of thousands of faces). Returns 0, or -1 when out
 * of memory. */
static int half_edges_sort(const half_edge_key *keys, size_t n, int nv, half_edge_key *out)
{
    size_t *start = mem_calloc((size_t)nv + 2, sizeof *start);
    if (!start) return -1;
    for (size_t i = 0; i < n; i++) start[keys[i].lo + 1]++;
    for (int v = 0; v < nv; v++) start[v + 1] += start[v];
    for (size_t i = 0; i < n; i++) out[start[keys[i].lo]++] = keys[i];
    /* start[v] is now the end of v's bucket. */
    size_t b = 0;
    for (int v = 0; v < nv; v++) {
        size_t e = start[v];
        if (e - b > 32) {
            qsort(out + b, e - b, sizeof *out, half_edge_cmp_hi);
            b = e;
            continue;
        }
        for (size_t i = b + 1; i < e; i++) {
            half_edge_key k = out[i];
            size_t j = i;
            for (; j > b && out[j - 1].hi > k.hi; j--) out[j] = out[j - 1];
            out[j] = k;
        }
        b = e;
    }
    mem_free(start);
    return 0;
}

void face_graph_free(face_graph *g)
{
    mem_free(g->adj); mem_free(g->elen); mem_free(g->centroid); mem_free(g->area);
    memset(g, 0, sizeof *g);
}

neuv_status face_graph_build(const neuv_mesh *m, face_graph *g)
{
    memset(g, 0, sizeof *g);
    int nf = m->nf;
    size_t n3 = (size_t)(nf > 0 ? nf : 1) * 3;
    g->nf = nf;
    g->nv = m->nv;
    g->adj = mem_alloc(sizeof(int) * n3);
    g->elen = mem_alloc(sizeof(double) * n3);
    g->centroid = mem_alloc(sizeof(double) * n3);
    g->area = mem_alloc(sizeof(double) * (n3 / 3));
    half_edge_key *keys = mem_alloc(sizeof *keys * n3), *sorted = mem_alloc(sizeof *sorted * n3);
    if (!g->adj || !g->elen || !g->centroid || !g->area || !keys || !sorted) {
        mem_free(keys);
        mem_free(sorted);
        face_graph_free(g);
        return error_nomem("face graph");
    }
    for (int f = 0; f < nf; f++) {
        const int *t = m->tri + 3 * f;
        for (int k = 0; k < 3; k++) {
            const double *p = m->pos + 3 * t[k], *q = m->pos + 3 * t[(k + 1) % 3];
            double dx = q[0] - p[0], dy = q[1] - p[1], dz = q[2] - p[2];
            g->elen[3 * f + k] = sqrt(dx * dx + dy * dy + dz * dz);
            g->adj[3 * f + k] = -1;
            int a = t[k], b = t[(k + 1) % 3];
            keys[3 * f + k] = (half_edge_key){a < b ? a : b, a < b ? b : a, 3 * f + k};
        }
        for (int c = 0; c < 3; c++)
            g->centroid[3 * f + c] = (m->pos[3 * t[0] + c] + m->pos[3 * t[1] + c] + m->pos[3 * t[2] + c]) / 3.0;
        g->area[f] = mesh_face_area(m, f);
    }
    /* Sorting the undirected edge keys groups the half-edges of each edge;
     * only an edge with exactly two half-edges of two different faces joins
     * faces, so charts never grow across a non-manifold edge. */
    if (half_edges_sort(keys, (size_t)nf * 3, m->nv, sorted) != 0) {
        mem_free(keys);
        mem_free(sorted);
        face_graph_free(g);
        return error_nomem("face graph");
    }
    mem_free(keys);
    keys = sorted;
    size_t i = 0, n = (size_t)nf * 3;
    while (i < n) {
        size_t j = i + 1;
        while (j < n && keys[j].lo == keys[i].lo && keys[j].hi == keys[i].hi) j++;
        if (j - i == 2 && keys[i].lo != keys[i].hi) {
            int h0 = keys[i].he, h1 = keys[i + 1].he;
            if (h0 / 3 != h1 / 3) {
                g->adj[h0] = h1 / 3;
                g->adj[h1] = h0 / 3;
            }
        }
        i = j;
    }
    mem_free(keys);
    return NEUV_OK;
}
