#include "mesh/topology.h"

#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/mem.h"
#include "core/union_find.h"
#include "mesh/edge_map.h"

int mesh_face_components(const neuv_mesh *m, int *face_component)
{
    union_find u;
    if (uf_init(&u, m->nf) != 0) return -1;
    edge_map first;
    if (edge_map_init(&first, (size_t)m->nf * 3 / 2) != 0) { uf_free(&u); return -1; }
    for (int f = 0; f < m->nf; f++)
        for (int k = 0; k < 3; k++) {
            int a = m->tri[3 * f + k], b = m->tri[3 * f + (k + 1) % 3];
            if (a == b) continue;
            int inserted;
            int *slot = edge_map_slot(&first, a < b ? a : b, a < b ? b : a, f, &inserted);
            if (!slot) { edge_map_free(&first); uf_free(&u); return -1; }
            if (!inserted) uf_union(&u, *slot, f);
        }
    edge_map_free(&first);
    int n = uf_labels(&u, face_component);
    uf_free(&u);
    return n;
}

/* The edges of a face subset: for each undirected edge, how many subset
 * faces use it and the first two of them. Built in O(subset size). */
typedef struct subset_edges {
    edge_map map;  /* (min, max) -> edge index */
    int n;
    int *count, *face0, *face1;
} subset_edges;

static void subset_edges_free(subset_edges *s)
{
    edge_map_free(&s->map);
    mem_free(s->count); mem_free(s->face0); mem_free(s->face1);
}

static int subset_edges_build(subset_edges *s, const neuv_mesh *m, const int *faces, int nfaces)
{
    memset(s, 0, sizeof *s);
    size_t cap = (size_t)nfaces * 3 + 1;
    s->count = mem_alloc(sizeof(int) * cap);
    s->face0 = mem_alloc(sizeof(int) * cap);
    s->face1 = mem_alloc(sizeof(int) * cap);
    if (!s->count || !s->face0 || !s->face1 || edge_map_init(&s->map, cap) != 0) {
        subset_edges_free(s);
        return -1;
    }
    for (int i = 0; i < nfaces; i++) {
        int f = faces[i];
        for (int k = 0; k < 3; k++) {
            int a = m->tri[3 * f + k], b = m->tri[3 * f + (k + 1) % 3];
            if (a == b) continue;
            int inserted;
            int *slot = edge_map_slot(&s->map, a < b ? a : b, a < b ? b : a, s->n, &inserted);
            if (!slot) { subset_edges_free(s); return -1; }
            int e = *slot;
            if (inserted) { s->count[e] = 0; s->face0[e] = f; s->face1[e] = -1; s->n++; }
            else if (s->count[e] == 1) s->face1[e] = f;
            s->count[e]++;
        }
    }
    return 0;
}

static int edge_index(const subset_edges *s, int a, int b)
{
    return edge_map_get(&s->map, a < b ? a : b, a < b ? b : a);
}

/* The third vertex of face f, other than a and b. */
static int third_vertex(const neuv_mesh *m, int f, int a, int b)
{
    for (int k = 0; k < 3; k++) {
        int v = m->tri[3 * f + k];
        if (v != a && v != b) return v;
    }
    return -1;
}

/* The boundary edge that follows boundary edge (a -> b) of face f around
 * the loop: turn around b through the subset's faces (its fan) until an
 * edge with a single face is reached. This stays correct where two
 * boundary loops touch at a vertex, and does not depend on the faces'
 * orientation. Writes the next edge (b -> *c) and its face; returns its
 * edge index, or -1 when the walk fails (non-manifold fan). */
static int next_boundary_edge(const neuv_mesh *m, const subset_edges *s, int f, int a, int b,
                              int nfaces, int *c_out, int *f_out)
{
    int prev = a;
    for (int steps = 0; steps <= nfaces; steps++) {
        int c = third_vertex(m, f, prev, b);
        if (c < 0) return -1;
        int e = edge_index(s, b, c);
        if (e < 0) return -1;
        if (s->count[e] == 1) { *c_out = c; *f_out = f; return e; }
        if (s->count[e] != 2) return -1;
        f = s->face0[e] == f ? s->face1[e] : s->face0[e];
        prev = c;
    }
    return -1;
}

/* Traces every boundary loop of the subset. When loop_vertices is non-NULL
 * writes the loops (total length = number of boundary edges) and
 * loop_start (#loops+1). Returns the number of loops, -1 on OOM. */
static int trace_loops(const neuv_mesh *m, const subset_edges *s, const int *faces, int nfaces,
                       int *loop_start, int *loop_vertices)
{
    unsigned char *seen = mem_calloc((size_t)s->n + 1, 1);
    if (!seen) return -1;
    int loops = 0, written = 0;
    for (int i = 0; i < nfaces; i++) {
        int f = faces[i];
        for (int k = 0; k < 3; k++) {
            int a = m->tri[3 * f + k], b = m->tri[3 * f + (k + 1) % 3];
            if (a == b) continue;
            int e = edge_index(s, a, b);
            if (s->count[e] != 1 || seen[e]) continue;
            if (loop_start) loop_start[loops] = written;
            loops++;
            /* Follow the loop in the direction of f's orientation. */
            int cf = f, ca = a, cb = b, ce = e;
            while (!seen[ce]) {
                seen[ce] = 1;
                if (loop_vertices) loop_vertices[written] = ca;
                written++;
                int c, nf;
                int ne = next_boundary_edge(m, s, cf, ca, cb, nfaces, &c, &nf);
                if (ne < 0) break;
                ca = cb; cb = c; cf = nf; ce = ne;
            }
        }
    }
    if (loop_start) loop_start[loops] = written;
    mem_free(seen);
    return loops;
}

neuv_status mesh_faces_topology(const neuv_mesh *m, const int *faces, int nfaces,
                                component_topology *out)
{
    memset(out, 0, sizeof *out);
    subset_edges s;
    if (subset_edges_build(&s, m, faces, nfaces) != 0) return error_nomem("edge table");
    edge_map verts;
    if (edge_map_init(&verts, (size_t)nfaces + 3) != 0) {
        subset_edges_free(&s);
        return error_nomem("vertex table");
    }
    int nv = 0;
    for (int i = 0; i < nfaces && nv >= 0; i++)
        for (int k = 0; k < 3; k++) {
            int inserted;
            if (!edge_map_slot(&verts, m->tri[3 * faces[i] + k], 0, 0, &inserted)) { nv = -1; break; }
            nv += inserted;
        }
    edge_map_free(&verts);
    int loops = nv < 0 ? -1 : trace_loops(m, &s, faces, nfaces, NULL, NULL);
    int boundary_edges = 0;
    for (int e = 0; e < s.n; e++) boundary_edges += s.count[e] == 1;
    out->edges = s.n;
    subset_edges_free(&s);
    if (loops < 0) return error_nomem("boundary loops");
    out->faces = nfaces;
    out->vertices = nv;
    out->boundary_loops = loops;
    out->euler = nv - out->edges + nfaces;
    out->genus = (2 - out->euler - loops) / 2;
    out->closed = boundary_edges == 0;
    return NEUV_OK;
}

/* The faces with face_label == label, or all faces when face_label is NULL. */
static int *select_faces(const neuv_mesh *m, const int *face_label, int label, int *n)
{
    int *faces = mem_alloc(sizeof(int) * (size_t)(m->nf > 0 ? m->nf : 1));
    if (!faces) return NULL;
    *n = 0;
    for (int f = 0; f < m->nf; f++)
        if (!face_label || face_label[f] == label) faces[(*n)++] = f;
    return faces;
}

neuv_status mesh_subset_topology(const neuv_mesh *m, const int *face_label, int label,
                                 component_topology *out)
{
    int n;
    int *faces = select_faces(m, face_label, label, &n);
    if (!faces) return error_nomem("face subset");
    neuv_status st = mesh_faces_topology(m, faces, n, out);
    mem_free(faces);
    return st;
}

int mesh_faces_boundary_loops(const neuv_mesh *m, const int *faces, int nfaces,
                              int **loop_start, int **loop_vertices)
{
    *loop_start = NULL;
    *loop_vertices = NULL;
    subset_edges s;
    if (subset_edges_build(&s, m, faces, nfaces) != 0) return -1;
    int boundary_edges = 0;
    for (int e = 0; e < s.n; e++) boundary_edges += s.count[e] == 1;
    int *verts = mem_alloc(sizeof(int) * (size_t)(boundary_edges + 1));
    int *start = mem_alloc(sizeof(int) * (size_t)(boundary_edges + 2));
    if (!verts || !start) { mem_free(verts); mem_free(start); subset_edges_free(&s); return -1; }
    int loops = trace_loops(m, &s, faces, nfaces, start, verts);
    subset_edges_free(&s);
    if (loops < 0) { mem_free(verts); mem_free(start); return -1; }
    *loop_start = start;
    *loop_vertices = verts;
    return loops;
}

int mesh_boundary_loops(const neuv_mesh *m, const int *face_label, int label,
                        int **loop_start, int **loop_vertices)
{
    int n;
    int *faces = select_faces(m, face_label, label, &n);
    if (!faces) { *loop_start = NULL; *loop_vertices = NULL; return -1; }
    int loops = mesh_faces_boundary_loops(m, faces, n, loop_start, loop_vertices);
    mem_free(faces);
    return loops;
}
