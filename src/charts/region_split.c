/* Splitting a chart in two by growing regions from two far-apart faces.
 * The farthest pair comes from a double sweep (farthest face from the first
 * face, then farthest face from that one), the usual cheap approximation of
 * the graph diameter; the two regions are the geodesic Voronoi cells of the
 * pair, so the cut runs across the chart's long axis. Each cell is connected
 * because every face's shortest-path parent carries the same label. */
#include "charts/chart_local.h"

#include <math.h>
#include <stdlib.h>

#include "charts/min_heap.h"
#include "core/error.h"
#include "core/mem.h"

static double centroid_distance(const chart_local *L, int a, int b)
{
    const double *p = L->cen + 3 * a, *q = L->cen + 3 * b;
    double dx = q[0] - p[0], dy = q[1] - p[1], dz = q[2] - p[2];
    return sqrt(dx * dx + dy * dy + dz * dz);
}

neuv_status chart_local_face_dijkstra(const chart_local *L, const int *seeds, const int *seed_label,
                                      int n_seeds, const unsigned char *cut, double *dist, int *label)
{
    min_heap h;
    if (min_heap_init(&h, L->nf + n_seeds) != 0) return error_nomem("face Dijkstra");
    for (int i = 0; i < L->nf; i++) {
        dist[i] = INFINITY;
        if (label) label[i] = -1;
    }
    for (int s = 0; s < n_seeds; s++) {
        int f = seeds[s];
        if (dist[f] == 0.0) continue; /* a repeated seed keeps its first label */
        dist[f] = 0.0;
        if (label) label[f] = seed_label ? seed_label[s] : s;
        if (min_heap_push(&h, 0.0, f) != 0) { min_heap_free(&h); return error_nomem("face Dijkstra"); }
    }
    double d;
    int f;
    while (min_heap_pop(&h, &d, &f) == 0) {
        if (d > dist[f]) continue;
        for (int k = 0; k < 3; k++) {
            int o = L->adj[3 * f + k];
            if (o < 0 || (cut && cut[3 * f + k])) continue;
            double nd = d + centroid_distance(L, f, o);
            if (nd < dist[o]) {
                dist[o] = nd;
                if (label) label[o] = label[f];
                if (min_heap_push(&h, nd, o) != 0) { min_heap_free(&h); return error_nomem("face Dijkstra"); }
            }
        }
    }
    min_heap_free(&h);
    return NEUV_OK;
}

/* The reached face with the largest distance (first in local order on ties). */
static int farthest_face(const chart_local *L, const double *dist)
{
    int best = 0;
    for (int i = 1; i < L->nf; i++)
        if (isfinite(dist[i]) && (!isfinite(dist[best]) || dist[i] > dist[best])) best = i;
    return best;
}

neuv_status chart_local_grow2(const chart_local *L, int *part)
{
    double *dist = mem_alloc(sizeof(double) * (size_t)(L->nf > 0 ? L->nf : 1));
    if (!dist) return error_nomem("region split");
    int seed[2] = {0, 0};
    neuv_status st = chart_local_face_dijkstra(L, seed, NULL, 1, NULL, dist, NULL);
    if (st == NEUV_OK) {
        seed[0] = farthest_face(L, dist);
        st = chart_local_face_dijkstra(L, seed, NULL, 1, NULL, dist, NULL);
    }
    if (st == NEUV_OK) {
        seed[1] = farthest_face(L, dist);
        /* Zero-length steps (coincident centroids) could leave seed[1] equal
         * to seed[0]; any other face then serves, so both parts are non-empty. */
        if (seed[1] == seed[0]) seed[1] = seed[0] == 0 ? 1 : 0;
        int lab[2] = {0, 1};
        st = chart_local_face_dijkstra(L, seed, lab, 2, NULL, dist, part);
    }
    /* Faces the sweep cannot reach (a chart in several parts) go with part 0. */
    if (st == NEUV_OK)
        for (int i = 0; i < L->nf; i++)
            if (part[i] < 0) part[i] = 0;
    mem_free(dist);
    return st;
}
