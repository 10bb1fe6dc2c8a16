/* Two shortest cuts across an annulus. A chart is a set of faces, so one
 * seam cannot make an annulus a disk; two disjoint paths between its two
 * loops split it into two disks, and taking each path shortest keeps the
 * new boundary short (a long tube is cut lengthwise into two half-tubes,
 * not into rings). */
#include "charts/chart_local.h"

#include <math.h>
#include <stdlib.h>

#include "charts/min_heap.h"
#include "core/mem.h"

typedef struct vertex_graph {
    int *start, *face; /* vertex -> incident local faces (CSR) */
} vertex_graph;

static int vertex_graph_build(const chart_local *L, vertex_graph *vg)
{
    vg->start = mem_calloc((size_t)L->nv + 1, sizeof(int));
    vg->face = mem_alloc(sizeof(int) * (size_t)(L->nf > 0 ? L->nf : 1) * 3);
    if (!vg->start || !vg->face) return -1;
    for (int i = 0; i < 3 * L->nf; i++) vg->start[L->tri[i] + 1]++;
    for (int v = 0; v < L->nv; v++) vg->start[v + 1] += vg->start[v];
    int *fill = mem_alloc(sizeof(int) * (size_t)(L->nv > 0 ? L->nv : 1));
    if (!fill) return -1;
    for (int v = 0; v < L->nv; v++) fill[v] = vg->start[v];
    for (int i = 0; i < 3 * L->nf; i++) vg->face[fill[L->tri[i]]++] = i / 3;
    mem_free(fill);
    return 0;
}

static double vertex_distance(const chart_local *L, int a, int b)
{
    const double *p = L->vpos + 3 * a, *q = L->vpos + 3 * b;
    double dx = q[0] - p[0], dy = q[1] - p[1], dz = q[2] - p[2];
    return sqrt(dx * dx + dy * dy + dz * dz);
}

/* Dijkstra along chart edges from the vertices with role SOURCE. Vertices
 * with role BLOCKED are never entered; TARGET vertices are entered but not
 * left. Stops at the first TARGET popped and returns it (-1 when none is
 * reachable, or when stop_at_target is 0), filling dist and parent. */
enum { FREE = 0, SOURCE = 1, BLOCKED = 2, TARGET = 3 };

static int vertex_dijkstra(const chart_local *L, const vertex_graph *vg, const unsigned char *role,
                           int stop_at_target, double *dist, int *parent, int *oom)
{
    min_heap h;
    *oom = 0;
    if (min_heap_init(&h, L->nv) != 0) { *oom = 1; return -1; }
    for (int v = 0; v < L->nv; v++) {
        dist[v] = INFINITY;
        parent[v] = -1;
        if (role[v] == SOURCE) {
            dist[v] = 0.0;
            if (min_heap_push(&h, 0.0, v) != 0) { *oom = 1; min_heap_free(&h); return -1; }
        }
    }
    int found = -1;
    double d;
    int v;
    while (min_heap_pop(&h, &d, &v) == 0) {
        if (d > dist[v]) continue;
        if (role[v] == TARGET) {
            if (stop_at_target) { found = v; break; }
            continue;
        }
        for (int j = vg->start[v]; j < vg->start[v + 1]; j++) {
            const int *t = L->tri + 3 * vg->face[j];
            for (int k = 0; k < 3; k++) {
                int w = t[k];
                if (w == v || role[w] == BLOCKED || role[w] == SOURCE) continue;
                double nd = d + vertex_distance(L, v, w);
                if (nd < dist[w]) {
                    dist[w] = nd;
                    parent[w] = v;
                    if (min_heap_push(&h, nd, w) != 0) { *oom = 1; min_heap_free(&h); return -1; }
                }
            }
        }
    }
    min_heap_free(&h);
    return found;
}

/* Marks both half-edges of edge {a, b} in the faces around a. */
static void mark_edge(const chart_local *L, const vertex_graph *vg, int a, int b, unsigned char *cut)
{
    for (int j = vg->start[a]; j < vg->start[a + 1]; j++) {
        int f = vg->face[j];
        for (int k = 0; k < 3; k++) {
            int p = L->tri[3 * f + k], q = L->tri[3 * f + (k + 1) % 3];
            if ((p == a && q == b) || (p == b && q == a)) cut[3 * f + k] = 1;
        }
    }
}

static void mark_path(const chart_local *L, const vertex_graph *vg, const int *parent, int end,
                      unsigned char *cut)
{
    for (int v = end; parent[v] >= 0; v = parent[v]) mark_edge(L, vg, v, parent[v], cut);
}

typedef struct cut_work {
    vertex_graph vg;
    unsigned char *role, *on_path;
    double *dist;
    int *parent1, *parent;
} cut_work;

static void cut_work_free(cut_work *w)
{
    mem_free(w->vg.start); mem_free(w->vg.face);
    mem_free(w->role); mem_free(w->on_path); mem_free(w->dist); mem_free(w->parent1); mem_free(w->parent);
}

static int cut_work_init(const chart_local *L, cut_work *w)
{
    size_t n1 = (size_t)(L->nv > 0 ? L->nv : 1);
    w->role = mem_alloc(n1);
    w->on_path = mem_calloc(n1, 1);
    w->dist = mem_alloc(sizeof(double) * n1);
    w->parent1 = mem_alloc(sizeof(int) * n1);
    w->parent = mem_alloc(sizeof(int) * n1);
    if (!w->role || !w->on_path || !w->dist || !w->parent1 || !w->parent) return -1;
    return vertex_graph_build(L, &w->vg);
}

/* The first cut: shortest path from loop 0 to any other loop, into
 * w->parent1 and w->on_path. Returns its end vertex, -1 when there is
 * none, -2 on allocation failure. */
static int first_cut(const chart_local *L, const int *vloop, cut_work *w)
{
    int oom;
    for (int v = 0; v < L->nv; v++) w->role[v] = vloop[v] == 0 ? SOURCE : vloop[v] > 0 ? TARGET : FREE;
    int end = vertex_dijkstra(L, &w->vg, w->role, 1, w->dist, w->parent1, &oom);
    if (oom) return -2;
    if (end >= 0)
        for (int v = end; v >= 0; v = w->parent1[v]) w->on_path[v] = 1;
    return end;
}

int chart_local_annulus_cut(const chart_local *L, const int *vloop, unsigned char *cut)
{
    int nv = L->nv, oom = 0;
    for (int i = 0; i < 3 * L->nf; i++) cut[i] = 0;
    cut_work w = {0};
    int result = -1;
    if (cut_work_init(L, &w) != 0) goto done;
    int end1 = first_cut(L, vloop, &w);
    if (end1 == -2) goto done;
    result = 0;
    if (end1 < 0) goto done;
    int target = vloop[end1];

    /* Start the second cut at the loop-0 vertex farthest from the first. */
    for (int v = 0; v < nv; v++) w.role[v] = w.on_path[v] ? SOURCE : FREE;
    vertex_dijkstra(L, &w.vg, w.role, 0, w.dist, w.parent, &oom);
    if (oom) { result = -1; goto done; }
    int start2 = -1;
    for (int v = 0; v < nv; v++)
        if (vloop[v] == 0 && !w.on_path[v] && isfinite(w.dist[v]) && (start2 < 0 || w.dist[v] > w.dist[start2]))
            start2 = v;
    if (start2 < 0) goto done;

    /* Second cut: from start2 to the same loop, avoiding the first cut and
     * every other boundary vertex, so the two paths are disjoint and each
     * touches the loops only at its ends. */
    for (int v = 0; v < nv; v++) {
        if (w.on_path[v]) w.role[v] = BLOCKED;
        else if (v == start2) w.role[v] = SOURCE;
        else if (vloop[v] == target) w.role[v] = TARGET;
        else if (vloop[v] >= 0) w.role[v] = BLOCKED;
        else w.role[v] = FREE;
    }
    int end2 = vertex_dijkstra(L, &w.vg, w.role, 1, w.dist, w.parent, &oom);
    if (oom) { result = -1; goto done; }
    if (end2 < 0) goto done;
    mark_path(L, &w.vg, w.parent1, end1, cut);
    mark_path(L, &w.vg, w.parent, end2, cut);
    result = 1;
done:
    cut_work_free(&w);
    return result;
}

int chart_local_cut_and_grow(const chart_local *L, const int *vloop, int *part)
{
    cut_work w = {0};
    unsigned char *cut = mem_calloc((size_t)L->nf * 3 + 1, 1);
    int *seeds = mem_alloc(sizeof(int) * ((size_t)L->nf * 3 + 1));
    int *lab = mem_alloc(sizeof(int) * ((size_t)L->nf * 3 + 1));
    double *fdist = mem_alloc(sizeof(double) * ((size_t)L->nf + 1));
    int result = -1;
    if (!cut || !seeds || !lab || !fdist || cut_work_init(L, &w) != 0) goto done;
    int end = first_cut(L, vloop, &w);
    if (end == -2) goto done;
    result = 0;
    if (end < 0) goto done;
    mark_path(L, &w.vg, w.parent1, end, cut);
    /* Seeds: the face left of each path edge grows region 0, the face on
     * its right region 1 (left/right by the faces' orientation). */
    int ns = 0;
    for (int v = end; w.parent1[v] >= 0; v = w.parent1[v]) {
        int a = v, b = w.parent1[v];
        for (int j = w.vg.start[a]; j < w.vg.start[a + 1]; j++) {
            int f = w.vg.face[j];
            for (int k = 0; k < 3; k++) {
                int p = L->tri[3 * f + k], q = L->tri[3 * f + (k + 1) % 3];
                if (p == a && q == b) { seeds[ns] = f; lab[ns++] = 0; }
                else if (p == b && q == a) { seeds[ns] = f; lab[ns++] = 1; }
            }
        }
    }
    int has[2] = {0, 0};
    for (int i = 0; i < ns; i++) has[lab[i]] = 1;
    if (!has[0] || !has[1]) goto done;
    if (chart_local_face_dijkstra(L, seeds, lab, ns, cut, fdist, part) != NEUV_OK) { result = -1; goto done; }
    for (int i = 0; i < L->nf; i++)
        if (part[i] < 0) part[i] = 0;
    result = 1;
done:
    cut_work_free(&w);
    mem_free(cut); mem_free(seeds); mem_free(lab); mem_free(fdist);
    return result;
}
