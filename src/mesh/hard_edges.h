/* The seams a mesh's file marks: hard edges (the two faces' normals at a
 * corner of the edge differ) and borders between materials. Found on the
 * mesh as read, positions welded on a copy, and given as pairs of end
 * points for seam_mark_positions (mesh/seam_cut.h), so that they survive
 * cleaning. */
#ifndef NEUV_MESH_HARD_EDGES_H
#define NEUV_MESH_HARD_EDGES_H

#include "mesh/mesh.h"

typedef struct hard_edge_report {
    int from_normals;    /* edges whose corner normals differ */
    int from_materials;  /* edges between two materials (and not already hard) */
    int flat_shaded;     /* 1: every corner's normal is its face's own, so the normals mark every
                            edge and none is taken from them (a faceted export says nothing about
                            where the artist wants seams; --seam-angle does) */
} hard_edge_report;

/* Inputs: m with its file's normals and face materials (either may be
 * absent). Outputs: *ends (n by 6 doubles: two end points per edge;
 * mem_free; NULL when n is 0), *n, *rep. Corner normals count as different
 * when their directions differ by more than about 0.1 degree.
 * NEUV_ERR_NOMEM on allocation failure. */
neuv_status mesh_hard_edges(const neuv_mesh *m, double **ends, int *n, hard_edge_report *rep);

#endif
