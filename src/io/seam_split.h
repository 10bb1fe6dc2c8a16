/* Per-vertex UVs for the formats that have no per-corner UVs (PLY, glTF):
 * a vertex whose corners carry different UVs is split into one copy per
 * distinct UV, so the seam survives the export. */
#ifndef NEUV_IO_SEAM_SPLIT_H
#define NEUV_IO_SEAM_SPLIT_H

#include "mesh/mesh.h"

typedef struct seam_split {
    int nv;      /* output vertices (#V' >= #V) */
    int *src;    /* #V': the input vertex each output vertex copies */
    double *uv;  /* #V' by 2, NULL when the mesh has no UVs */
    int *tri;    /* #F by 3 into the output vertices */
} seam_split;

/* Splits vertices of m so that each output vertex has one UV. Output vertices
 * follow input vertex order (copies of vertex v are consecutive, in order of
 * first use), so a mesh without seams comes out unchanged; an unreferenced
 * vertex is kept with UV (0,0). Corners whose UVs are equal value for value
 * share a copy, whatever their UV indices.
 * Inputs:  m   mesh (UVs optional)
 * Outputs: out filled; release with seam_split_free */
neuv_status seam_split_vertices(const neuv_mesh *m, seam_split *out);
void seam_split_free(seam_split *s);

#endif
