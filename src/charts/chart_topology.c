/* Topology of one chart: connected parts, pinched vertices, boundary loops,
 * Euler characteristic; a chart is a disk when all four say so. */
#include "charts/chart_local.h"
#include "charts/charts.h"

#include <stdlib.h>

#include "core/error.h"
#include "core/mem.h"

neuv_status chart_local_shape(const chart_local *L, chart_shape *s, int *vloop)
{
    int nv = L->nv, nf = L->nf;
    int *out = mem_calloc((size_t)(nv > 0 ? nv : 1), sizeof(int));
    int *nxt = mem_alloc(sizeof(int) * (size_t)(nv > 0 ? nv : 1));
    int *comp = mem_alloc(sizeof(int) * (size_t)(nf > 0 ? nf : 1));
    if (!out || !nxt || !comp) {
        mem_free(out); mem_free(nxt); mem_free(comp);
        return error_nomem("chart topology");
    }
    s->components = chart_local_components(L, NULL, NULL, comp);
    mem_free(comp);
    if (s->components < 0) {
        mem_free(out); mem_free(nxt);
        return error_nomem("chart topology");
    }
    /* Boundary half-edges are those with no chart face across. On an
     * oriented manifold each boundary vertex is left by exactly one of them;
     * a vertex left by two is where two fans of the chart meet. */
    int boundary = 0;
    for (int v = 0; v < nv; v++) nxt[v] = -1;
    for (int i = 0; i < nf; i++)
        for (int k = 0; k < 3; k++)
            if (L->adj[3 * i + k] < 0) {
                int a = L->tri[3 * i + k];
                out[a]++;
                nxt[a] = L->tri[3 * i + (k + 1) % 3];
                boundary++;
            }
    s->pinched = 0;
    for (int v = 0; v < nv; v++) s->pinched += out[v] > 1;
    if (vloop)
        for (int v = 0; v < nv; v++) vloop[v] = -1;
    s->loops = 0;
    if (!s->pinched) {
        /* out[] doubles as the visited mark: 2 once a vertex is on a loop. */
        for (int v = 0; v < nv; v++) {
            if (out[v] != 1) continue;
            int w = v, steps = 0;
            while (w >= 0 && out[w] == 1 && steps <= nv) {
                out[w] = 2;
                if (vloop) vloop[w] = s->loops;
                w = nxt[w];
                steps++;
            }
            /* A walk that does not close on its start only happens with
             * inconsistent orientation; count it as pinched (not a disk). */
            if (w != v) s->pinched++;
            s->loops++;
        }
    }
    int edges = (3 * nf + boundary) / 2;
    s->euler = nv - edges + nf;
    s->genus = (s->components == 1 && !s->pinched) ? (2 - s->euler - s->loops) / 2 : -1;
    s->disk = s->components == 1 && !s->pinched && s->loops == 1 && s->euler == 1;
    mem_free(out); mem_free(nxt);
    return NEUV_OK;
}

int chart_is_disk(const neuv_mesh *m, const int *face_chart, int id)
{
    int n = 0;
    for (int f = 0; f < m->nf; f++) n += face_chart[f] == id;
    if (n == 0) return 0;
    int *faces = mem_alloc(sizeof(int) * (size_t)n);
    face_graph g;
    chart_scratch s = {0};
    chart_local L = {0};
    chart_shape shape = {0};
    int result = -1;
    if (!faces) return -1;
    n = 0;
    for (int f = 0; f < m->nf; f++)
        if (face_chart[f] == id) faces[n++] = f;
    if (face_graph_build(m, &g) != NEUV_OK) { mem_free(faces); return -1; }
    if (chart_scratch_init(&s, m->nf, m->nv) == NEUV_OK &&
        chart_local_build(m, &g, faces, n, &s, &L) == NEUV_OK &&
        chart_local_shape(&L, &shape, NULL) == NEUV_OK)
        result = shape.disk;
    chart_local_free(&L);
    chart_scratch_free(&s);
    face_graph_free(&g);
    mem_free(faces);
    return result;
}
