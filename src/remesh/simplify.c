#include "remesh/simplify.h"

#include <meshoptimizer.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/log.h"
#include "core/mem.h"
#include "mesh/edge_map.h"

neuv_status mesh_simplify(const neuv_mesh *m, double ratio, neuv_mesh **out)
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
