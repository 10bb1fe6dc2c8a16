#include "charts/chart_local.h"

#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/mem.h"

neuv_status chart_scratch_init(chart_scratch *s, int nf, int nv)
{
    s->face_map = mem_alloc(sizeof(int) * (size_t)(nf > 0 ? nf : 1));
    s->vert_map = mem_alloc(sizeof(int) * (size_t)(nv > 0 ? nv : 1));
    if (!s->face_map || !s->vert_map) {
        chart_scratch_free(s);
        return error_nomem("chart scratch");
    }
    for (int i = 0; i < nf; i++) s->face_map[i] = -1;
    for (int i = 0; i < nv; i++) s->vert_map[i] = -1;
    return NEUV_OK;
}

void chart_scratch_free(chart_scratch *s)
{
    mem_free(s->face_map); mem_free(s->vert_map);
    s->face_map = s->vert_map = NULL;
}

void chart_local_free(chart_local *L)
{
    mem_free(L->face); mem_free(L->vert); mem_free(L->tri); mem_free(L->adj);
    mem_free(L->elen); mem_free(L->cen); mem_free(L->vpos);
    memset(L, 0, sizeof *L);
}

neuv_status chart_local_build(const neuv_mesh *m, const face_graph *g, const int *faces, int n,
                              chart_scratch *s, chart_local *L)
{
    memset(L, 0, sizeof *L);
    size_t n1 = (size_t)(n > 0 ? n : 1);
    L->nf = n;
    L->face = mem_alloc(sizeof(int) * n1);
    L->vert = mem_alloc(sizeof(int) * n1 * 3);
    L->tri = mem_alloc(sizeof(int) * n1 * 3);
    L->adj = mem_alloc(sizeof(int) * n1 * 3);
    L->elen = mem_alloc(sizeof(double) * n1 * 3);
    L->cen = mem_alloc(sizeof(double) * n1 * 3);
    L->vpos = mem_alloc(sizeof(double) * n1 * 9);
    if (!L->face || !L->vert || !L->tri || !L->adj || !L->elen || !L->cen || !L->vpos) {
        chart_local_free(L);
        return error_nomem("chart");
    }
    memcpy(L->face, faces, sizeof(int) * (size_t)n);
    for (int i = 0; i < n; i++) s->face_map[faces[i]] = i;
    int nv = 0;
    for (int i = 0; i < n; i++) {
        int f = faces[i];
        for (int k = 0; k < 3; k++) {
            int v = m->tri[3 * f + k];
            if (s->vert_map[v] < 0) {
                s->vert_map[v] = nv;
                L->vert[nv] = v;
                memcpy(L->vpos + 3 * nv, m->pos + 3 * v, sizeof(double) * 3);
                nv++;
            }
            L->tri[3 * i + k] = s->vert_map[v];
            int o = g->adj[3 * f + k];
            L->adj[3 * i + k] = o >= 0 ? s->face_map[o] : -1;
            L->elen[3 * i + k] = g->elen[3 * f + k];
        }
        memcpy(L->cen + 3 * i, g->centroid + 3 * f, sizeof(double) * 3);
    }
    L->nv = nv;
    for (int i = 0; i < n; i++) s->face_map[faces[i]] = -1;
    for (int i = 0; i < nv; i++) s->vert_map[L->vert[i]] = -1;
    return NEUV_OK;
}

int chart_local_components(const chart_local *L, const int *part, const unsigned char *cut, int *comp)
{
    int *stack = mem_alloc(sizeof(int) * (size_t)(L->nf > 0 ? L->nf : 1));
    if (!stack) return -1;
    for (int i = 0; i < L->nf; i++) comp[i] = -1;
    int count = 0;
    for (int s = 0; s < L->nf; s++) {
        if (comp[s] >= 0) continue;
        int top = 0;
        stack[top++] = s;
        comp[s] = count;
        while (top > 0) {
            int f = stack[--top];
            for (int k = 0; k < 3; k++) {
                int o = L->adj[3 * f + k];
                if (o < 0 || comp[o] >= 0) continue;
                if (part && part[o] != part[f]) continue;
                if (cut && cut[3 * f + k]) continue;
                comp[o] = count;
                stack[top++] = o;
            }
        }
        count++;
    }
    mem_free(stack);
    return count;
}
