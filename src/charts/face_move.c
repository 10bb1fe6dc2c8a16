#include "charts/face_move.h"

#include <string.h>

#include "core/error.h"
#include "core/mem.h"


void face_star_free(face_star *s)
{
    mem_free(s->start); mem_free(s->face); mem_free(s->open);
}

neuv_status face_star_build(const neuv_mesh *m, const face_graph *g, face_star *s)
{
    int nv = m->nv, nf = m->nf;
    s->start = mem_calloc((size_t)nv + 1, sizeof(int));
    s->face = mem_alloc(sizeof(int) * 3 * (size_t)(nf > 0 ? nf : 1));
    s->open = mem_calloc((size_t)(nv > 0 ? nv : 1), 1);
    if (!s->start || !s->face || !s->open) { face_star_free(s); return error_nomem("vertex stars"); }
    for (int i = 0; i < 3 * nf; i++) s->start[m->tri[i] + 1]++;
    for (int v = 0; v < nv; v++) s->start[v + 1] += s->start[v];
    int *fill = mem_alloc(sizeof(int) * (size_t)(nv > 0 ? nv : 1));
    if (!fill) { face_star_free(s); return error_nomem("vertex stars"); }
    memcpy(fill, s->start, sizeof(int) * (size_t)nv);
    for (int f = 0; f < nf; f++)
        for (int k = 0; k < 3; k++) {
            int v = m->tri[3 * f + k];
            s->face[fill[v]++] = f;
            if (g->adj[3 * f + k] < 0) s->open[v] = s->open[m->tri[3 * f + (k + 1) % 3]] = 1;
        }
    mem_free(fill);
    return NEUV_OK;
}

/* Whether a face other than f around v belongs to chart c. */
static int star_touches(const face_star *s, const int *face_chart, int v, int f, int c)
{
    for (int i = s->start[v]; i < s->start[v + 1]; i++)
        if (s->face[i] != f && face_chart[s->face[i]] == c) return 1;
    return 0;
}

/* Whether every face around v is in chart c and v is not on an open edge. */
static int star_inside(const face_star *s, const int *face_chart, int v, int c)
{
    if (s->open[v]) return 0;
    for (int i = s->start[v]; i < s->start[v + 1]; i++)
        if (face_chart[s->face[i]] != c) return 0;
    return 1;
}

/* Whether chart c minus f (when f is in c) or plus f (when not) stays a
 * disk, by the one-arc condition (face_move.h). */
int face_move_keeps_disk(const neuv_mesh *m, const face_graph *g, const face_star *s, const int *face_chart,
                         int f, int c, int removing)
{
    const int *t = m->tri + 3 * f;
    int k = 0, shared[3];
    for (int e = 0; e < 3; e++) {
        int o = g->adj[3 * f + e];
        shared[e] = o >= 0 && face_chart[o] == c;
        k += shared[e];
    }
    int v = 0;
    for (int j = 0; j < 3; j++) v += star_touches(s, face_chart, t[j], f, c);
    if (k == 1) return v == 2;
    if (k != 2 || v != 3) return 0;
    if (!removing) return 1;
    /* Edge e runs t[e] -> t[e+1]; the vertex between the two shared edges
     * is the one both contain. */
    int mid = !shared[0] ? t[2] : !shared[1] ? t[0] : t[1];
    return star_inside(s, face_chart, mid, c);
}

