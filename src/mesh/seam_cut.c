#include "mesh/seam_cut.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/mem.h"
#include "core/union_find.h"
#include "mesh/edge_map.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

int seam_mark_angle(const neuv_mesh *m, const edge_faces *ef, double degrees, unsigned char *seam)
{
    double cos_limit = cos(degrees * M_PI / 180.0);
    int marked = 0;
    for (int e = 0; e < ef->ne; e++) {
        if (seam[e] || edge_faces_count(ef, e) != 2) continue;
        double n0[3], n1[3];
        mesh_face_normal(m, ef->side[ef->start[e]] / 3, n0);
        mesh_face_normal(m, ef->side[ef->start[e] + 1] / 3, n1);
        double l0 = n0[0] * n0[0] + n0[1] * n0[1] + n0[2] * n0[2];
        double l1 = n1[0] * n1[0] + n1[1] * n1[1] + n1[2] * n1[2];
        if (l0 == 0 || l1 == 0) continue;
        if (n0[0] * n1[0] + n0[1] * n1[1] + n0[2] * n1[2] < cos_limit) { seam[e] = 1; marked++; }
    }
    return marked;
}

/* A vertex and its position, sorted lexicographically by position. */
typedef struct placed_vertex { double p[3]; int v; } placed_vertex;

static int compare_points(const double *a, const double *b)
{
    for (int i = 0; i < 3; i++)
        if (a[i] != b[i]) return a[i] < b[i] ? -1 : 1;
    return 0;
}

static int compare_placed(const void *x, const void *y)
{
    const placed_vertex *a = x, *b = y;
    int c = compare_points(a->p, b->p);
    return c ? c : (a->v > b->v) - (a->v < b->v);
}

/* The range [*lo, *hi) of the n sorted vertices that sit exactly at p. */
static void find_point(const placed_vertex *sorted, int n, const double *p, int *lo, int *hi)
{
    int a = 0, b = n;
    while (a < b) {
        int mid = a + (b - a) / 2;
        if (compare_points(sorted[mid].p, p) < 0) a = mid + 1; else b = mid;
    }
    *lo = a;
    b = n;
    while (a < b) {
        int mid = a + (b - a) / 2;
        if (compare_points(sorted[mid].p, p) <= 0) a = mid + 1; else b = mid;
    }
    *hi = a;
}

int seam_mark_positions(const neuv_mesh *m, const edge_faces *ef, const double *ends, int n,
                        unsigned char *seam, int *unmatched)
{
    *unmatched = 0;
    if (n <= 0) return 0;
    placed_vertex *sorted = mem_alloc(sizeof *sorted * (size_t)m->nv);
    edge_map map;
    if (!sorted || edge_faces_index(ef, &map) != 0) { mem_free(sorted); return -1; }
    for (int v = 0; v < m->nv; v++) {
        memcpy(sorted[v].p, m->pos + 3 * (size_t)v, sizeof sorted[v].p);
        sorted[v].v = v;
    }
    qsort(sorted, (size_t)m->nv, sizeof *sorted, compare_placed);
    int marked = 0;
    for (int i = 0; i < n; i++) {
        int a0, a1, b0, b1, found = 0;
        find_point(sorted, m->nv, ends + 6 * (size_t)i, &a0, &a1);
        find_point(sorted, m->nv, ends + 6 * (size_t)i + 3, &b0, &b1);
        for (int x = a0; x < a1; x++)
            for (int y = b0; y < b1; y++) {
                int u = sorted[x].v, v = sorted[y].v;
                int e = edge_map_get(&map, u < v ? u : v, u < v ? v : u);
                if (e < 0) continue;
                found = 1;
                if (!seam[e]) { seam[e] = 1; marked++; }
            }
        if (!found) (*unmatched)++;
    }
    edge_map_free(&map);
    mem_free(sorted);
    return marked;
}

/* The corner of face f that holds vertex v (-1 if none). */
static int corner_of(const neuv_mesh *m, int f, int v)
{
    for (int k = 0; k < 3; k++)
        if (m->tri[3 * (size_t)f + k] == v) return 3 * f + k;
    return -1;
}

neuv_status mesh_cut_seams(const neuv_mesh *m, const edge_faces *ef, const unsigned char *seam,
                           neuv_mesh **out, int **origin)
{
    *out = NULL;
    *origin = NULL;
    int nc = 3 * m->nf;
    union_find uf;
    if (uf_init(&uf, nc) != 0) return error_nomem("the seam cut");
    /* Corners at the same vertex are one fan when joined across an unmarked
     * edge with two faces. */
    for (int e = 0; e < ef->ne; e++) {
        if (seam[e] || edge_faces_count(ef, e) != 2) continue;
        int f0 = ef->side[ef->start[e]] / 3, f1 = ef->side[ef->start[e] + 1] / 3;
        for (int i = 0; i < 2; i++) {
            int v = ef->edge_v[2 * e + i], c0 = corner_of(m, f0, v), c1 = corner_of(m, f1, v);
            if (c0 >= 0 && c1 >= 0) uf_union(&uf, c0, c1);
        }
    }
    /* The first fan of a vertex (in corner order) keeps its index. */
    int *owner = mem_alloc(sizeof(int) * (size_t)m->nv);   /* root of the fan holding v's index */
    int *copy = mem_alloc(sizeof(int) * (size_t)nc);       /* per root: the vertex it became */
    int *org = mem_alloc(sizeof(int) * ((size_t)m->nv + (size_t)nc));
    if (!owner || !copy || !org) {
        mem_free(owner); mem_free(copy); mem_free(org); uf_free(&uf);
        return error_nomem("the seam cut");
    }
    for (int v = 0; v < m->nv; v++) { owner[v] = -1; org[v] = v; }
    for (int c = 0; c < nc; c++) copy[c] = -1;
    int nv = m->nv;
    for (int c = 0; c < nc; c++) {
        int v = m->tri[c], root = uf_find(&uf, c);
        if (copy[root] >= 0) continue;
        if (owner[v] < 0) { owner[v] = root; copy[root] = v; }
        else { copy[root] = nv; org[nv++] = v; }
    }
    neuv_mesh *cut = mesh_create(nv, m->nf, m->nuv);
    if (!cut) {
        mem_free(owner); mem_free(copy); mem_free(org); uf_free(&uf);
        return error_nomem("the seam cut");
    }
    for (int v = 0; v < nv; v++) memcpy(cut->pos + 3 * (size_t)v, m->pos + 3 * (size_t)org[v], sizeof(double) * 3);
    for (int c = 0; c < nc; c++) cut->tri[c] = copy[uf_find(&uf, c)];
    if (m->nuv > 0) {
        memcpy(cut->uv, m->uv, sizeof(double) * 2 * (size_t)m->nuv);
        memcpy(cut->tri_uv, m->tri_uv, sizeof(int) * (size_t)nc);
    }
    mem_free(owner);
    mem_free(copy);
    uf_free(&uf);
    *out = cut;
    *origin = org;
    return NEUV_OK;
}

void mesh_join_seams(neuv_mesh *m, const int *origin, int nv_before)
{
    for (size_t c = 0; c < 3 * (size_t)m->nf; c++) m->tri[c] = origin[m->tri[c]];
    m->nv = nv_before;
}
