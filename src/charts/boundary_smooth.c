/* Boundary smoothing of charts: faces that stick out of their chart (a
 * saw-tooth spike along a boundary grown on the face graph) or fill a notch
 * of a neighbour move to the neighbour they share more boundary length with.
 * Spikes hurt twice downstream: LSCM stretches the thin tips, and the packer
 * sees a footprint with teeth.
 *
 * A move of face f from chart A to chart B keeps both charts disks when the
 * closed triangle meets each chart in one arc of its boundary (the "simple
 * cell" condition of digital topology): gluing a disk to a disk along an arc
 * gives a disk, and Euler's V - E + F changes by k - v + 1 = 0 for k shared
 * edges and v touched vertices with (k, v) = (1, 2) or (2, 3). Removing f with
 * two edges on A also needs the vertex between those edges to be interior to
 * A, or A would be pinched there. Every move shortens the total boundary by
 * a positive length, so the sweeps end. */
#include "charts/charts.h"

#include <stdlib.h>
#include <string.h>

#include "charts/face_graph.h"
#include "core/error.h"
#include "core/mem.h"

typedef struct vertex_star {
    int *start;          /* #V + 1 offsets into face */
    int *face;           /* 3 #F faces around each vertex */
    unsigned char *open; /* #V: 1 on a mesh boundary (or non-manifold) edge */
} vertex_star;

static void vertex_star_free(vertex_star *s)
{
    mem_free(s->start); mem_free(s->face); mem_free(s->open);
}

static neuv_status vertex_star_build(const neuv_mesh *m, const face_graph *g, vertex_star *s)
{
    int nv = m->nv, nf = m->nf;
    s->start = mem_calloc((size_t)nv + 1, sizeof(int));
    s->face = mem_alloc(sizeof(int) * 3 * (size_t)(nf > 0 ? nf : 1));
    s->open = mem_calloc((size_t)(nv > 0 ? nv : 1), 1);
    if (!s->start || !s->face || !s->open) { vertex_star_free(s); return error_nomem("vertex stars"); }
    for (int i = 0; i < 3 * nf; i++) s->start[m->tri[i] + 1]++;
    for (int v = 0; v < nv; v++) s->start[v + 1] += s->start[v];
    int *fill = mem_alloc(sizeof(int) * (size_t)(nv > 0 ? nv : 1));
    if (!fill) { vertex_star_free(s); return error_nomem("vertex stars"); }
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
static int star_touches(const vertex_star *s, const int *face_chart, int v, int f, int c)
{
    for (int i = s->start[v]; i < s->start[v + 1]; i++)
        if (s->face[i] != f && face_chart[s->face[i]] == c) return 1;
    return 0;
}

/* Whether every face around v is in chart c and v is not on an open edge. */
static int star_inside(const vertex_star *s, const int *face_chart, int v, int c)
{
    if (s->open[v]) return 0;
    for (int i = s->start[v]; i < s->start[v + 1]; i++)
        if (face_chart[s->face[i]] != c) return 0;
    return 1;
}

/* Whether chart c minus f (when f is in c) or plus f (when not) stays a
 * disk, by the one-arc condition above. */
static int arc_condition(const neuv_mesh *m, const face_graph *g, const vertex_star *s, const int *face_chart,
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

neuv_status charts_smooth_boundaries(const neuv_mesh *m, const int *active, int *face_chart, int max_sweeps,
                                     int *moves)
{
    if (moves) *moves = 0;
    if (!m || !face_chart) return error_set(NEUV_ERR_INPUT, "charts_smooth_boundaries: missing mesh or charts");
    if (m->nf == 0) return NEUV_OK;
    face_graph g;
    neuv_status st = face_graph_build(m, &g);
    if (st != NEUV_OK) return st;
    vertex_star s = {0};
    if ((st = vertex_star_build(m, &g, &s)) != NEUV_OK) { face_graph_free(&g); return st; }
    int total = 0;
    for (int sweep = 0; sweep < max_sweeps; sweep++) {
        int moved = 0;
        for (int f = 0; f < m->nf; f++) {
            int a = face_chart[f];
            if (active && !active[a]) continue;
            /* Boundary length shared with each neighbouring chart (at most 3). */
            int nb[3], nn = 0;
            double len[3] = {0, 0, 0}, own = 0;
            for (int e = 0; e < 3; e++) {
                int o = g.adj[3 * f + e];
                if (o < 0) continue;
                int c = face_chart[o];
                if (c == a) { own += g.elen[3 * f + e]; continue; }
                int i = 0;
                while (i < nn && nb[i] != c) i++;
                if (i == nn) nb[nn++] = c;
                len[i] += g.elen[3 * f + e];
            }
            int best = -1;
            for (int i = 0; i < nn; i++) {
                if (active && !active[nb[i]]) continue;
                /* Strictly longer (relative margin against round-off), so
                 * the total boundary length falls with every move. */
                if (!(len[i] > own * (1.0 + 1e-9) + 1e-300)) continue;
                if (best < 0 || len[i] > len[best] || (len[i] == len[best] && nb[i] < nb[best])) best = i;
            }
            if (best < 0) continue;
            int b = nb[best];
            if (!arc_condition(m, &g, &s, face_chart, f, a, 1)) continue;
            if (!arc_condition(m, &g, &s, face_chart, f, b, 0)) continue;
            face_chart[f] = b;
            moved++;
        }
        total += moved;
        if (moved == 0) break;
    }
    vertex_star_free(&s);
    face_graph_free(&g);
    if (moves) *moves = total;
    return NEUV_OK;
}
