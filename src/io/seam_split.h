/* Per-vertex attributes for the formats that have no per-corner ones (PLY,
 * glTF): a vertex whose corners carry different UVs, normals or first-set
 * UVs (attr->uv0, written before the atlas) is split into one copy per
 * distinct combination, so seams and hard edges survive the export and a
 * vertex is split nowhere else. Per-vertex values (colours, PLY extras)
 * follow `src`. */
#ifndef NEUV_IO_SEAM_SPLIT_H
#define NEUV_IO_SEAM_SPLIT_H

#include "mesh/mesh.h"

typedef struct seam_split {
    int nv;         /* output vertices (#V' >= #V) */
    int *src;       /* #V': the input vertex each output vertex copies */
    double *uv;     /* #V' by 2: the atlas, NULL when the mesh has no UVs */
    double *normal; /* #V' by 3, NULL when the mesh has no normals */
    double *uv0;    /* #V' by 2: attr->uv0, NULL when attr->nuv0 == 0 */
    int *tri;       /* #F by 3 into the output vertices */
} seam_split;

/* Splits vertices of m so that each output vertex has one UV, one normal
 * and one first-set UV. Output vertices follow input vertex order (copies of
 * vertex v are consecutive, in order of first use), so a mesh without seams
 * comes out unchanged; an unreferenced vertex is kept with zero UVs and
 * normal. Corners whose values are equal value for value share a copy,
 * whatever their indices.
 * Inputs:  m   mesh (UVs, normals, attr->uv0 optional)
 * Outputs: out filled; release with seam_split_free */
neuv_status seam_split_vertices(const neuv_mesh *m, seam_split *out);
void seam_split_free(seam_split *s);

#endif
