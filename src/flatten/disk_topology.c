#include "flatten/disk_topology.h"

#include <stdio.h>
#include <stdlib.h>

#include "core/error.h"
#include "core/mem.h"
#include "mesh/topology.h"

neuv_status flatten_require_disk(const neuv_mesh *m, int **boundary, int *nboundary)
{
    if (boundary) *boundary = NULL;
    if (nboundary) *nboundary = 0;
    if (!m || m->nf <= 0) return error_set(NEUV_ERR_INPUT, "not a disk: the mesh has no faces");
    int *comp = mem_alloc(sizeof(int) * (size_t)m->nf);
    if (!comp) return error_nomem("face components");
    int ncomp = mesh_face_components(m, comp);
    mem_free(comp);
    if (ncomp < 0) return error_nomem("face components");
    component_topology t;
    neuv_status s = mesh_subset_topology(m, NULL, 0, &t);
    if (s) return s;
    if (ncomp != 1 || t.boundary_loops != 1 || t.genus != 0) {
        char loops[48];
        if (t.boundary_loops == 0) snprintf(loops, sizeof loops, "closed");
        else snprintf(loops, sizeof loops, "%d boundary loop%s", t.boundary_loops, t.boundary_loops == 1 ? "" : "s");
        /* With several components the genus formula mixes them, so it is
         * named only for one. */
        if (ncomp != 1) return error_set(NEUV_ERR_INPUT, "not a disk: %d components, %s", ncomp, loops);
        return error_set(NEUV_ERR_INPUT, "not a disk: 1 component, %s, genus %d", loops, t.genus);
    }
    int *start = NULL, *verts = NULL;
    int nloops = mesh_boundary_loops(m, NULL, 0, &start, &verts);
    if (nloops < 0) return error_nomem("boundary loops");
    if (nloops != 1 || start[1] - start[0] < 3) {
        int len = nloops >= 1 ? start[1] - start[0] : 0;
        mem_free(start); mem_free(verts);
        return error_set(NEUV_ERR_INPUT, "not a disk: boundary found as %d loop%s (first of %d vertices)",
                         nloops, nloops == 1 ? "" : "s", len);
    }
    int len = start[1] - start[0];
    for (int k = 0; k < len; k++) verts[k] = verts[start[0] + k];
    if (nboundary) *nboundary = len;
    if (boundary) *boundary = verts;
    else mem_free(verts);
    mem_free(start);
    return NEUV_OK;
}
