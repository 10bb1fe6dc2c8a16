#include "remesh/subdivide.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/mem.h"
#include "mesh/edge_faces.h"
#include "mesh/edge_map.h"

/* New UV per undirected pair of corner UV indices, so the two faces of an
 * interior edge share the midpoint UV and a seam gets one per side. */
static neuv_status subdivide_uv(const neuv_mesh *m, int *tri_uv_out, double **uv_out, int *nuv_out)
{
    size_t nc = (size_t)m->nf * 3;
    edge_map map;
    if (edge_map_init(&map, nc / 2 + 1)) return error_set(NEUV_ERR_NOMEM, "out of memory subdividing UVs");
    int *mid = mem_alloc(sizeof(int) * (nc + 1));
    if (!mid) { edge_map_free(&map); return error_set(NEUV_ERR_NOMEM, "out of memory subdividing UVs"); }
    int count = m->nuv;
    for (size_t c = 0; c < nc; c++) {
        size_t f = c / 3;
        int a = m->tri_uv[c], b = m->tri_uv[3 * f + (c % 3 + 1) % 3];
        int lo = a < b ? a : b, hi = a < b ? b : a, inserted;
        int *slot = edge_map_slot(&map, lo, hi, count, &inserted);
        if (!slot) { mem_free(mid); edge_map_free(&map); return error_set(NEUV_ERR_NOMEM, "out of memory subdividing UVs"); }
        if (inserted) count++;
        mid[c] = *slot;
    }
    edge_map_free(&map);
    double *uv = mem_alloc(sizeof(double) * 2 * (size_t)count);
    if (!uv) { mem_free(mid); return error_set(NEUV_ERR_NOMEM, "out of memory subdividing UVs"); }
    memcpy(uv, m->uv, sizeof(double) * 2 * (size_t)m->nuv);
    for (size_t c = 0; c < nc; c++) {
        size_t f = c / 3;
        int a = m->tri_uv[c], b = m->tri_uv[3 * f + (c % 3 + 1) % 3];
        for (int i = 0; i < 2; i++) uv[2 * (size_t)mid[c] + i] = 0.5 * (m->uv[2 * (size_t)a + i] + m->uv[2 * (size_t)b + i]);
    }
    for (int f = 0; f < m->nf; f++) {
        const int *t = m->tri_uv + 3 * (size_t)f;
        const int *e = mid + 3 * (size_t)f; /* e[k]: midpoint of side k -> k+1 */
        int *o = tri_uv_out + 12 * (size_t)f;
        o[0] = t[0]; o[1] = e[0]; o[2] = e[2];
        o[3] = t[1]; o[4] = e[1]; o[5] = e[0];
        o[6] = t[2]; o[7] = e[2]; o[8] = e[1];
        o[9] = e[0]; o[10] = e[1]; o[11] = e[2];
    }
    mem_free(mid);
    *uv_out = uv;
    *nuv_out = count;
    return NEUV_OK;
}

/* Loop's weights for the old vertices: new positions into pos_out (#V by 3). */
static neuv_status loop_vertex_points(const neuv_mesh *m, const edge_faces *ef, double *pos_out)
{
    int nv = m->nv;
    double *sum = mem_calloc((size_t)nv * 3, sizeof(double)), *bsum = mem_calloc((size_t)nv * 3, sizeof(double));
    int *n = mem_calloc((size_t)nv, sizeof(int)), *nb = mem_calloc((size_t)nv, sizeof(int));
    char *fixed = mem_calloc((size_t)nv, 1);
    if (!sum || !bsum || !n || !nb || !fixed) {
        mem_free(sum); mem_free(bsum); mem_free(n); mem_free(nb); mem_free(fixed);
        return error_set(NEUV_ERR_NOMEM, "out of memory in Loop subdivision");
    }
    for (int e = 0; e < ef->ne; e++) {
        int a = ef->edge_v[2 * e], b = ef->edge_v[2 * e + 1], k = edge_faces_count(ef, e);
        if (k > 2) { fixed[a] = fixed[b] = 1; continue; }
        for (int i = 0; i < 3; i++) {
            sum[3 * (size_t)a + i] += m->pos[3 * (size_t)b + i];
            sum[3 * (size_t)b + i] += m->pos[3 * (size_t)a + i];
        }
        n[a]++; n[b]++;
        if (k == 1) {
            for (int i = 0; i < 3; i++) {
                bsum[3 * (size_t)a + i] += m->pos[3 * (size_t)b + i];
                bsum[3 * (size_t)b + i] += m->pos[3 * (size_t)a + i];
            }
            nb[a]++; nb[b]++;
        }
    }
    for (int v = 0; v < nv; v++) {
        const double *p = m->pos + 3 * (size_t)v;
        double *q = pos_out + 3 * (size_t)v;
        if (fixed[v] || n[v] == 0 || (nb[v] != 0 && nb[v] != 2)) { memcpy(q, p, sizeof(double) * 3); continue; }
        if (nb[v] == 2) {
            for (int i = 0; i < 3; i++) q[i] = 0.75 * p[i] + 0.125 * bsum[3 * (size_t)v + i];
            continue;
        }
        double c = 0.375 + 0.25 * cos(2 * 3.14159265358979323846 / n[v]);
        double beta = (0.625 - c * c) / n[v];
        for (int i = 0; i < 3; i++) q[i] = (1 - n[v] * beta) * p[i] + beta * sum[3 * (size_t)v + i];
    }
    mem_free(sum); mem_free(bsum); mem_free(n); mem_free(nb); mem_free(fixed);
    return NEUV_OK;
}

static neuv_status subdivide_once(const neuv_mesh *m, subdivide_scheme scheme, neuv_mesh **out)
{
    *out = NULL;
    edge_faces ef;
    if (edge_faces_build(&ef, m)) return error_set(NEUV_ERR_NOMEM, "out of memory building the edge table");
    for (size_t c = 0; c < (size_t)m->nf * 3; c++)
        if (ef.face_edge[c] < 0) {
            edge_faces_free(&ef);
            return error_set(NEUV_ERR_INPUT, "face %zu has a repeated vertex; clean the mesh before subdividing", c / 3);
        }
    if ((double)m->nv + ef.ne > 2e9 || (double)m->nf * 4 > 2e9) {
        edge_faces_free(&ef);
        return error_set(NEUV_ERR_INPUT, "subdividing %d faces would exceed 2^31 elements", m->nf);
    }
    neuv_mesh *o = mesh_create(m->nv + ef.ne, m->nf * 4, 0);
    if (!o) { edge_faces_free(&ef); return error_set(NEUV_ERR_NOMEM, "out of memory subdividing %d faces", m->nf); }
    neuv_status st = NEUV_OK;
    if (scheme == SUBDIVIDE_LOOP) st = loop_vertex_points(m, &ef, o->pos);
    else memcpy(o->pos, m->pos, sizeof(double) * 3 * (size_t)m->nv);
    if (st) { edge_faces_free(&ef); mesh_free(o); return st; }
    for (int e = 0; e < ef.ne; e++) {
        int a = ef.edge_v[2 * e], b = ef.edge_v[2 * e + 1];
        double *q = o->pos + 3 * ((size_t)m->nv + e);
        const double *pa = m->pos + 3 * (size_t)a, *pb = m->pos + 3 * (size_t)b;
        if (scheme == SUBDIVIDE_LOOP && edge_faces_count(&ef, e) == 2) {
            int s0 = ef.side[ef.start[e]], s1 = ef.side[ef.start[e] + 1];
            /* The corner after the side's end is the vertex opposite the edge. */
            const double *pc = m->pos + 3 * (size_t)m->tri[3 * (s0 / 3) + (s0 % 3 + 2) % 3];
            const double *pd = m->pos + 3 * (size_t)m->tri[3 * (s1 / 3) + (s1 % 3 + 2) % 3];
            for (int i = 0; i < 3; i++) q[i] = 0.375 * (pa[i] + pb[i]) + 0.125 * (pc[i] + pd[i]);
        } else {
            for (int i = 0; i < 3; i++) q[i] = 0.5 * (pa[i] + pb[i]);
        }
    }
    for (int f = 0; f < m->nf; f++) {
        const int *t = m->tri + 3 * (size_t)f;
        int e0 = m->nv + ef.face_edge[3 * f], e1 = m->nv + ef.face_edge[3 * f + 1], e2 = m->nv + ef.face_edge[3 * f + 2];
        int *r = o->tri + 12 * (size_t)f;
        r[0] = t[0]; r[1] = e0; r[2] = e2;
        r[3] = t[1]; r[4] = e1; r[5] = e0;
        r[6] = t[2]; r[7] = e2; r[8] = e1;
        r[9] = e0; r[10] = e1; r[11] = e2;
    }
    edge_faces_free(&ef);
    if (m->nuv > 0 && m->tri_uv) {
        o->tri_uv = mem_alloc(sizeof(int) * 12 * (size_t)m->nf);
        if (!o->tri_uv) { mesh_free(o); return error_set(NEUV_ERR_NOMEM, "out of memory subdividing UVs"); }
        if ((st = subdivide_uv(m, o->tri_uv, &o->uv, &o->nuv))) { mesh_free(o); return st; }
    }
    *out = o;
    return NEUV_OK;
}

neuv_status mesh_subdivide(const neuv_mesh *m, int rounds, subdivide_scheme scheme, neuv_mesh **out)
{
    *out = NULL;
    if (rounds < 0) return error_set(NEUV_ERR_INPUT, "subdivision rounds must be >= 0, got %d", rounds);
    neuv_mesh *cur = mesh_clone(m);
    if (!cur) return error_set(NEUV_ERR_NOMEM, "out of memory copying the mesh");
    for (int r = 0; r < rounds; r++) {
        neuv_mesh *next;
        neuv_status st = subdivide_once(cur, scheme, &next);
        mesh_free(cur);
        if (st) return st;
        cur = next;
    }
    *out = cur;
    return NEUV_OK;
}
