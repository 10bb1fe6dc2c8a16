#include "io/seam_split.h"

#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/mem.h"
#include "mesh/mesh_attributes.h"

void seam_split_free(seam_split *s)
{
    mem_free(s->src); mem_free(s->uv); mem_free(s->normal); mem_free(s->uv0); mem_free(s->tri);
    memset(s, 0, sizeof *s);
}

/* The values a corner carries, one key of up to 7 numbers (atlas UV, normal,
 * first-set UV, those the mesh has). */
typedef struct corner_source {
    const double *uv, *normal, *uv0;
    const int *tri_uv, *tri_normal, *tri_uv0;
} corner_source;

static int corner_key(const corner_source *cs, size_t c, double *key)
{
    int n = 0;
    if (cs->uv) { const double *t = cs->uv + 2 * (size_t)cs->tri_uv[c]; key[n++] = t[0]; key[n++] = t[1]; }
    if (cs->normal) {
        const double *t = cs->normal + 3 * (size_t)cs->tri_normal[c];
        key[n++] = t[0]; key[n++] = t[1]; key[n++] = t[2];
    }
    if (cs->uv0) { const double *t = cs->uv0 + 2 * (size_t)cs->tri_uv0[c]; key[n++] = t[0]; key[n++] = t[1]; }
    return n;
}

static void store_key(seam_split *out, const corner_source *cs, int j, const double *key)
{
    int n = 0;
    if (cs->uv) { out->uv[2 * (size_t)j] = key[n++]; out->uv[2 * (size_t)j + 1] = key[n++]; }
    if (cs->normal) for (int k = 0; k < 3; k++) out->normal[3 * (size_t)j + k] = key[n++];
    if (cs->uv0) { out->uv0[2 * (size_t)j] = key[n++]; out->uv0[2 * (size_t)j + 1] = key[n++]; }
}

neuv_status seam_split_vertices(const neuv_mesh *m, seam_split *out)
{
    memset(out, 0, sizeof *out);
    size_t nc = 3 * (size_t)m->nf;
    corner_source cs = {0};
    if (m->nuv > 0 && m->tri_uv) { cs.uv = m->uv; cs.tri_uv = m->tri_uv; }
    if (m->nn > 0 && m->tri_normal) { cs.normal = m->normal; cs.tri_normal = m->tri_normal; }
    if (m->attr && m->attr->nuv0 > 0 && m->attr->uv0 && m->attr->tri_uv0) { cs.uv0 = m->attr->uv0; cs.tri_uv0 = m->attr->tri_uv0; }
    /* A mesh made by neuv is consistent; the check turns a bug elsewhere
     * into a message instead of a wild read. */
    for (size_t c = 0; c < nc; c++)
        if ((cs.uv && (m->tri_uv[c] < 0 || m->tri_uv[c] >= m->nuv)) ||
            (cs.normal && (m->tri_normal[c] < 0 || m->tri_normal[c] >= m->nn)) ||
            (cs.uv0 && (m->attr->tri_uv0[c] < 0 || m->attr->tri_uv0[c] >= m->attr->nuv0)))
            return error_set(NEUV_ERR_INTERNAL, "cannot save: face %zu has a UV or normal index out of range", c / 3);
    out->tri = mem_alloc(sizeof(int) * (nc > 0 ? nc : 1));
    if (!out->tri) return error_nomem("split faces");
    if (!cs.uv && !cs.normal && !cs.uv0) {
        out->nv = m->nv;
        out->src = mem_alloc(sizeof(int) * (size_t)(m->nv > 0 ? m->nv : 1));
        if (!out->src) { seam_split_free(out); return error_nomem("split vertices"); }
        for (int v = 0; v < m->nv; v++) out->src[v] = v;
        memcpy(out->tri, m->tri, sizeof(int) * nc);
        return NEUV_OK;
    }
    /* Corners grouped by vertex (counting sort keeps face order within a
     * vertex, which makes the output deterministic). */
    int *start = mem_calloc((size_t)m->nv + 1, sizeof(int));
    int *corner = mem_alloc(sizeof(int) * (nc > 0 ? nc : 1));
    /* At most one output vertex per corner, plus one per unused vertex. */
    size_t cap = nc + (size_t)m->nv;
    if (cap == 0) cap = 1;
    out->src = mem_alloc(sizeof(int) * cap);
    if (cs.uv) out->uv = mem_alloc(sizeof(double) * 2 * cap);
    if (cs.normal) out->normal = mem_alloc(sizeof(double) * 3 * cap);
    if (cs.uv0) out->uv0 = mem_alloc(sizeof(double) * 2 * cap);
    if (!start || !corner || !out->src || (cs.uv && !out->uv) || (cs.normal && !out->normal) || (cs.uv0 && !out->uv0)) {
        mem_free(start); mem_free(corner); seam_split_free(out);
        return error_nomem("split vertices");
    }
    for (size_t c = 0; c < nc; c++) start[m->tri[c] + 1]++;
    for (int v = 0; v < m->nv; v++) start[v + 1] += start[v];
    {
        int *fill = mem_alloc(sizeof(int) * ((size_t)m->nv + 1));
        if (!fill) { mem_free(start); mem_free(corner); seam_split_free(out); return error_nomem("split vertices"); }
        memcpy(fill, start, sizeof(int) * ((size_t)m->nv + 1));
        for (size_t c = 0; c < nc; c++) corner[fill[m->tri[c]]++] = (int)c;
        mem_free(fill);
    }
    int n = 0;
    double key[7], other[7];
    for (int v = 0; v < m->nv; v++) {
        int first = n;
        if (start[v] == start[v + 1]) {
            static const double zero[7] = {0};
            out->src[n] = v;
            store_key(out, &cs, n, zero);
            n++;
            continue;
        }
        for (int k = start[v]; k < start[v + 1]; k++) {
            int c = corner[k];
            int nk = corner_key(&cs, (size_t)c, key);
            int found = -1;
            /* Few distinct keys per vertex (one, or a handful on a seam): a
             * linear scan beats hashing here. Equality value for value, so a
             * NaN gets a copy of its own. */
            for (int j = first; j < n && found < 0; j++) {
                int same = 1, q = 0;
                if (cs.uv) { other[q++] = out->uv[2 * (size_t)j]; other[q++] = out->uv[2 * (size_t)j + 1]; }
                if (cs.normal) for (int e = 0; e < 3; e++) other[q++] = out->normal[3 * (size_t)j + e];
                if (cs.uv0) { other[q++] = out->uv0[2 * (size_t)j]; other[q++] = out->uv0[2 * (size_t)j + 1]; }
                for (int e = 0; e < nk && same; e++) same = other[e] == key[e];
                if (same) found = j;
            }
            if (found < 0) {
                found = n++;
                out->src[found] = v;
                store_key(out, &cs, found, key);
            }
            out->tri[c] = found;
        }
    }
    mem_free(start);
    mem_free(corner);
    out->nv = n;
    return NEUV_OK;
}
