#include "charts/charts.h"

#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/mem.h"

neuv_status chart_submesh(const neuv_mesh *m, const int *face_chart, int id,
                          neuv_mesh **sub, int **vmap, int **fmap)
{
    *sub = NULL;
    *vmap = NULL;
    *fmap = NULL;
    int nf = 0;
    for (int f = 0; f < m->nf; f++) nf += face_chart[f] == id;
    if (nf == 0) return error_set(NEUV_ERR_INPUT, "chart %d has no faces", id);
    int *local = mem_alloc(sizeof(int) * (size_t)(m->nv > 0 ? m->nv : 1));
    int *fm = mem_alloc(sizeof(int) * (size_t)nf);
    int *vm = mem_alloc(sizeof(int) * (size_t)nf * 3);
    if (!local || !fm || !vm) {
        mem_free(local); mem_free(fm); mem_free(vm);
        return error_nomem("chart submesh");
    }
    for (int v = 0; v < m->nv; v++) local[v] = -1;
    int nv = 0, i = 0;
    for (int f = 0; f < m->nf; f++) {
        if (face_chart[f] != id) continue;
        fm[i++] = f;
        for (int k = 0; k < 3; k++) {
            int v = m->tri[3 * f + k];
            if (local[v] < 0) { local[v] = nv; vm[nv++] = v; }
        }
    }
    neuv_mesh *s = mesh_create(nv, nf, 0);
    if (!s) {
        mem_free(local); mem_free(fm); mem_free(vm);
        return error_nomem("chart submesh");
    }
    for (int v = 0; v < nv; v++) memcpy(s->pos + 3 * v, m->pos + 3 * vm[v], sizeof(double) * 3);
    for (int j = 0; j < nf; j++)
        for (int k = 0; k < 3; k++) s->tri[3 * j + k] = local[m->tri[3 * fm[j] + k]];
    mem_free(local);
    /* Shrink the vertex map to its size. The larger block would do, but a
     * failed allocation is reported, never worked around (the caller's
     * allocator is out of memory). */
    int *vm_small = mem_realloc(vm, sizeof(int) * (size_t)nv);
    if (!vm_small) {
        mesh_free(s); mem_free(fm); mem_free(vm);
        return error_nomem("chart submesh");
    }
    *sub = s;
    *vmap = vm_small;
    *fmap = fm;
    return NEUV_OK;
}
