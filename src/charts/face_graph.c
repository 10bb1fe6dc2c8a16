#include "charts/face_graph.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/mem.h"

typedef struct half_edge_key { int lo, hi, he; } half_edge_key;

static int half_edge_cmp(const void *pa, const void *pb)
{
    const half_edge_key *a = pa, *b = pb;
    if (a->lo != b->lo) return a->lo < b->lo ? -1 : 1;
    if (a->hi != b->hi) return a->hi < b->hi ? -1 : 1;
    return (a->he > b->he) - (a->he < b->he);
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
    half_edge_key *keys = mem_alloc(sizeof *keys * n3);
    if (!g->adj || !g->elen || !g->centroid || !g->area || !keys) {
        mem_free(keys);
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
    qsort(keys, (size_t)nf * 3, sizeof *keys, half_edge_cmp);
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
