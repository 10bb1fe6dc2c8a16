#include "mesh/edge_faces.h"

#include <stdlib.h>
#include <string.h>

#include "core/mem.h"
#include "mesh/edge_map.h"

void edge_faces_free(edge_faces *t)
{
    mem_free(t->face_edge); mem_free(t->start); mem_free(t->side); mem_free(t->edge_v);
    memset(t, 0, sizeof *t);
}

int edge_faces_build(edge_faces *t, const neuv_mesh *m)
{
    memset(t, 0, sizeof *t);
    size_t nc = (size_t)m->nf * 3;
    edge_map map;
    t->face_edge = mem_alloc(sizeof(int) * (nc + 1));
    t->edge_v = mem_alloc(sizeof(int) * 2 * (nc + 1));
    t->side = mem_alloc(sizeof(int) * (nc + 1));
    if (!t->face_edge || !t->edge_v || !t->side || edge_map_init(&map, nc / 2 + 1) != 0) {
        edge_faces_free(t);
        return -1;
    }
    for (size_t c = 0; c < nc; c++) {
        size_t f = c / 3;
        int a = m->tri[c], b = m->tri[3 * f + (c % 3 + 1) % 3];
        if (a == b) { t->face_edge[c] = -1; continue; }
        int lo = a < b ? a : b, hi = a < b ? b : a, inserted;
        int *slot = edge_map_slot(&map, lo, hi, t->ne, &inserted);
        if (!slot) { edge_map_free(&map); edge_faces_free(t); return -1; }
        if (inserted) { t->edge_v[2 * t->ne] = lo; t->edge_v[2 * t->ne + 1] = hi; t->ne++; }
        t->face_edge[c] = *slot;
    }
    edge_map_free(&map);
    t->start = mem_calloc((size_t)t->ne + 2, sizeof(int));
    if (!t->start) { edge_faces_free(t); return -1; }
    for (size_t c = 0; c < nc; c++)
        if (t->face_edge[c] >= 0) t->start[t->face_edge[c] + 2]++;
    for (int e = 0; e < t->ne; e++) t->start[e + 2] += t->start[e + 1];
    /* start[e+1] is now the write cursor of edge e; after the fill it is its end. */
    for (size_t c = 0; c < nc; c++)
        if (t->face_edge[c] >= 0) t->side[t->start[t->face_edge[c] + 1]++] = (int)c;
    return 0;
}

int edge_faces_index(const edge_faces *t, edge_map *map)
{
    if (edge_map_init(map, (size_t)t->ne) != 0) return -1;
    for (int e = 0; e < t->ne; e++)
        if (!edge_map_slot(map, t->edge_v[2 * e], t->edge_v[2 * e + 1], e, NULL)) {
            edge_map_free(map);
            return -1;
        }
    return 0;
}
