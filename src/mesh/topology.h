/* Topology of a (cleaned, manifold) triangle mesh or of a subset of its faces. */
#ifndef NEUV_MESH_TOPOLOGY_H
#define NEUV_MESH_TOPOLOGY_H

#include "mesh/mesh.h"

typedef struct component_topology {
    int faces, vertices, edges;
    int boundary_loops;
    int euler;   /* V - E + F */
    int genus;   /* (2 - euler - boundary_loops) / 2 */
    int closed;  /* no boundary */
} component_topology;

/* Inputs: m (#F by 3 faces).
 * Outputs: face_component (#F) component id per face (faces joined across
 * shared edges), numbered by first face. Returns the count, -1 on OOM. */
int mesh_face_components(const neuv_mesh *m, int *face_component);

/* Topology of the faces whose face_label equals `label` (face_label may be
 * NULL for the whole mesh). Returns NEUV_OK or NEUV_ERR_NOMEM.
 * A subset is a disk exactly when euler == 1 and boundary_loops == 1.
 * Where the subset is pinched at a vertex (two fans), boundary loops are
 * traced fan by fan while the vertex is counted once, so a pinched subset
 * has euler below what a disk has and is never reported as one. O(F) to
 * select the faces, then linear in the subset (see mesh_faces_topology). */
neuv_status mesh_subset_topology(const neuv_mesh *m, const int *face_label, int label,
                                 component_topology *out);

/* Boundary loops of the faces with face_label == label (NULL: whole mesh):
 * *loop_start (#loops+1) offsets into *loop_vertices, each loop in order
 * following the faces' orientation. Caller frees both arrays. Returns the
 * number of loops, -1 on OOM. */
int mesh_boundary_loops(const neuv_mesh *m, const int *face_label, int label,
                        int **loop_start, int **loop_vertices);

/* Same as mesh_subset_topology for an explicit face list, in time linear
 * in the list (for callers that already hold their charts' faces).
 * Inputs: faces (#nfaces) face indices into m, each at most once. */
neuv_status mesh_faces_topology(const neuv_mesh *m, const int *faces, int nfaces,
                                component_topology *out);

/* Same as mesh_boundary_loops for an explicit face list (linear time). */
int mesh_faces_boundary_loops(const neuv_mesh *m, const int *faces, int nfaces,
                              int **loop_start, int **loop_vertices);

#endif
