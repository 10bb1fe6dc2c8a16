#include "io/seam_split.h"

#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/mem.h"

void seam_split_free(seam_split *s)
{
    mem_free(s->src); mem_free(s->uv); mem_free(s->tri);
    memset(s, 0, sizeof *s);
}

neuv_status seam_split_vertices(const neuv_mesh *m, seam_split *out)
{
    memset(out, 0, sizeof *out);
    size_t nc = 3 * (size_t)m->nf;
    out->tri = mem_alloc(sizeof(int) * (nc > 0 ? nc : 1));
    if (!out->tri) return error_nomem("split faces");
    if (m->nuv == 0 || !m->tri_uv) {
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
    out->src = mem_alloc(sizeof(int) * (cap > 0 ? cap : 1));
    out->uv = mem_alloc(sizeof(double) * 2 * (cap > 0 ? cap : 1));
    if (!start || !corner || !out->src || !out->uv) {
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
    for (int v = 0; v < m->nv; v++) {
        int first = n;
        if (start[v] == start[v + 1]) {
            out->src[n] = v;
            out->uv[2 * n] = out->uv[2 * n + 1] = 0;
            n++;
            continue;
        }
        for (int k = start[v]; k < start[v + 1]; k++) {
            int c = corner[k];
            const double *t = m->uv + 2 * (size_t)m->tri_uv[c];
            int found = -1;
            /* Few distinct UVs per vertex (one, or a handful on a seam): a
             * linear scan beats hashing here. */
            for (int j = first; j < n && found < 0; j++)
                if (out->uv[2 * j] == t[0] && out->uv[2 * j + 1] == t[1]) found = j;
            if (found < 0) {
                found = n++;
                out->src[found] = v;
                out->uv[2 * found] = t[0];
                out->uv[2 * found + 1] = t[1];
            }
            out->tri[c] = found;
        }
    }
    mem_free(start);
    mem_free(corner);
    out->nv = n;
    return NEUV_OK;
}
