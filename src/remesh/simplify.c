#include "remesh/simplify.h"

#include <meshoptimizer.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/log.h"
#include "core/mem.h"
#include "mesh/edge_map.h"
#include "mesh/topology.h"
#include "remesh/edge_collapse.h"

/* What a simplification must keep of a manifold surface. */
typedef struct surface_signature {
    int components, boundary_loops, euler;
    int bad_edges; /* directed edges used by more than one face: edges with
                      over two faces, or faces of opposite orientation */
} surface_signature;

static neuv_status signature_of(const neuv_mesh *m, surface_signature *s)
{
    memset(s, 0, sizeof *s);
    int *comp = mem_alloc(sizeof(int) * (size_t)(m->nf > 0 ? m->nf : 1));
    edge_map e;
    if (!comp) return error_nomem("the simplified mesh's topology");
    if (edge_map_init(&e, 3 * (size_t)m->nf)) { mem_free(comp); return error_nomem("the simplified mesh's topology"); }
    neuv_status st = NEUV_OK;
    s->components = mesh_face_components(m, comp);
    for (size_t c = 0; c < 3 * (size_t)m->nf && s->components >= 0; c++) {
        int a = m->tri[c], b = m->tri[c % 3 == 2 ? c - 2 : c + 1], inserted;
        if (!edge_map_slot(&e, a, b, 0, &inserted)) { s->components = -1; break; }
        s->bad_edges += !inserted;
    }
    component_topology t;
    if (s->components < 0) st = error_nomem("the simplified mesh's topology");
    else if ((st = mesh_subset_topology(m, NULL, 0, &t)) == NEUV_OK) {
        s->boundary_loops = t.boundary_loops;
        s->euler = t.euler;
    }
    edge_map_free(&e);
    mem_free(comp);
    return st;
}

static int same_signature(const surface_signature *a, const surface_signature *b)
{
    return a->components == b->components && a->boundary_loops == b->boundary_loops && a->euler == b->euler &&
           a->bad_edges == b->bad_edges;
}

static neuv_status simplify_quadric(const neuv_mesh *m, double ratio, neuv_mesh **out);

/* meshoptimizer first (fast, keeps positions and UVs); it checks no link
 * condition, so on some inputs (a regular bumpy grid: 200k faces -> 9
 * components, a closed tetrahedron, 9 holes) its collapses tear the
 * surface. The copy's topology is compared with the input's, and a
 * manifold input without UVs whose copy differs is simplified again by
 * CGAL's edge collapse, which checks the link condition at every step. */
neuv_status mesh_simplify(const neuv_mesh *m, double ratio, neuv_mesh **out)
{
    neuv_status st = simplify_quadric(m, ratio, out);
    if (st || ratio == 1) return st;
    surface_signature in, got;
    if ((st = signature_of(m, &in)) || (st = signature_of(*out, &got))) {
        mesh_free(*out);
        *out = NULL;
        return st;
    }
    if (same_signature(&in, &got) || in.bad_edges) return NEUV_OK;
    log_message(NEUV_LOG_INFO, "simplify: meshoptimizer changed the topology (components %d -> %d, boundary loops "
                "%d -> %d, Euler characteristic %d -> %d, non-manifold or misoriented edges %d -> %d)",
                in.components, got.components, in.boundary_loops, got.boundary_loops, in.euler, got.euler,
                in.bad_edges, got.bad_edges);
    if (m->nuv > 0 && m->tri_uv) {
        log_message(NEUV_LOG_WARN, "simplify: the copy's topology differs from the input's (kept: the "
                    "topology-preserving edge collapse does not carry UVs)");
        return NEUV_OK;
    }
    neuv_mesh *c = NULL;
    int target = (int)(ratio * m->nf + 0.5);
    st = mesh_edge_collapse(m, target > 0 ? target : 1, &c);
    if (st == NEUV_ERR_INPUT) {
        log_message(NEUV_LOG_WARN, "simplify: the copy's topology differs from the input's (kept: %s)",
                    neuv_last_error());
        return NEUV_OK;
    }
    mesh_free(*out);
    *out = c;
    if (st) return st;
    log_message(NEUV_LOG_INFO, "simplify: edge collapse with the link condition instead: %d -> %d faces (target %d)",
                m->nf, c->nf, target);
    return NEUV_OK;
}

static neuv_status simplify_quadric(const neuv_mesh *m, double ratio, neuv_mesh **out)
{
    *out = NULL;
    if (!(ratio > 0 && ratio <= 1)) return error_set(NEUV_ERR_INPUT, "simplify ratio must be in (0, 1], got %g", ratio);
    if (m->nf <= 0) return error_set(NEUV_ERR_INPUT, "cannot simplify a mesh without faces");
    if (ratio == 1) {
        *out = mesh_clone(m);
        return *out ? NEUV_OK : error_set(NEUV_ERR_NOMEM, "out of memory copying the mesh");
    }
    int has_uv = m->nuv > 0 && m->tri_uv;
    size_t nc = (size_t)m->nf * 3;
    /* Wedges: one simplifier vertex per distinct (vertex, UV) pair. */
    unsigned *idx = mem_alloc(sizeof(unsigned) * nc), *dst = mem_alloc(sizeof(unsigned) * nc);
    int *wedge_v = mem_alloc(sizeof(int) * nc), *wedge_uv = mem_alloc(sizeof(int) * nc);
    float *fpos = mem_alloc(sizeof(float) * 3 * nc);
    edge_map map;
    int map_ok = has_uv ? edge_map_init(&map, nc) == 0 : 1;
    neuv_status st = NEUV_OK;
    int *vmap = NULL, *uvmap = NULL;
    neuv_mesh *o = NULL;
    if (!idx || !dst || !wedge_v || !wedge_uv || !fpos || !map_ok) goto nomem;
    int nw = 0;
    if (has_uv) {
        for (size_t c = 0; c < nc; c++) {
            int inserted;
            int *slot = edge_map_slot(&map, m->tri[c], m->tri_uv[c], nw, &inserted);
            if (!slot) goto nomem;
            if (inserted) { wedge_v[nw] = m->tri[c]; wedge_uv[nw] = m->tri_uv[c]; nw++; }
            idx[c] = (unsigned)*slot;
        }
    } else {
        for (int v = 0; v < m->nv; v++) wedge_v[v] = v;
        nw = m->nv;
        for (size_t c = 0; c < nc; c++) idx[c] = (unsigned)m->tri[c];
    }
    for (int w = 0; w < nw; w++)
        for (int i = 0; i < 3; i++) fpos[3 * (size_t)w + i] = (float)m->pos[3 * (size_t)wedge_v[w] + i];
    size_t target = (size_t)(ratio * m->nf + 0.5);
    if (target < 1) target = 1;
    float err = 0;
    /* target_error 1 (the whole extent): the face count is the only stop. */
    size_t nidx = meshopt_simplify(dst, idx, nc, fpos, (size_t)nw, sizeof(float) * 3, target * 3, 1.0f, 0, &err);
    vmap = mem_alloc(sizeof(int) * (size_t)(m->nv > 0 ? m->nv : 1));
    uvmap = mem_alloc(sizeof(int) * (size_t)(m->nuv > 0 ? m->nuv : 1));
    if (!vmap || !uvmap) goto nomem;
    for (int v = 0; v < m->nv; v++) vmap[v] = -1;
    for (int u = 0; u < m->nuv; u++) uvmap[u] = -1;
    int nf = 0, dropped = 0;
    for (size_t t = 0; t < nidx; t += 3) {
        int a = wedge_v[dst[t]], b = wedge_v[dst[t + 1]], c = wedge_v[dst[t + 2]];
        if (a == b || b == c || c == a) { dropped++; continue; }
        for (int k = 0; k < 3; k++) {
            vmap[wedge_v[dst[t + k]]] = 0;
            if (has_uv) uvmap[wedge_uv[dst[t + k]]] = 0;
        }
        dst[3 * (size_t)nf] = dst[t]; dst[3 * (size_t)nf + 1] = dst[t + 1]; dst[3 * (size_t)nf + 2] = dst[t + 2];
        nf++;
    }
    int nv = 0, nuv = 0;
    for (int v = 0; v < m->nv; v++) if (vmap[v] == 0) vmap[v] = nv++;
    if (has_uv) for (int u = 0; u < m->nuv; u++) if (uvmap[u] == 0) uvmap[u] = nuv++;
    o = mesh_create(nv, nf, nuv);
    if (!o) goto nomem;
    for (int v = 0; v < m->nv; v++)
        if (vmap[v] >= 0) memcpy(o->pos + 3 * (size_t)vmap[v], m->pos + 3 * (size_t)v, sizeof(double) * 3);
    for (int u = 0; has_uv && u < m->nuv; u++)
        if (uvmap[u] >= 0) memcpy(o->uv + 2 * (size_t)uvmap[u], m->uv + 2 * (size_t)u, sizeof(double) * 2);
    for (size_t c = 0; c < (size_t)nf * 3; c++) {
        o->tri[c] = vmap[wedge_v[dst[c]]];
        if (has_uv) o->tri_uv[c] = uvmap[wedge_uv[dst[c]]];
    }
    if (dropped) log_message(NEUV_LOG_WARN, "simplify: dropped %d collapsed faces that joined two UV copies of one vertex", dropped);
    log_message(NEUV_LOG_INFO, "simplify: %d -> %d faces (target %zu), relative error %.3g", m->nf, nf, target, (double)err);
    *out = o;
    goto done;
nomem:
    st = error_set(NEUV_ERR_NOMEM, "out of memory simplifying %d faces", m->nf);
done:
    mem_free(idx); mem_free(dst); mem_free(wedge_v); mem_free(wedge_uv); mem_free(fpos); mem_free(vmap); mem_free(uvmap);
    if (has_uv && map_ok) edge_map_free(&map);
    return st;
}
