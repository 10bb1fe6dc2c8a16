/* Required seams: edges that no chart may cross (hard edges above a dihedral
 * angle, edges the user marks). The unwrap cuts the mesh open along them
 * before the charts are made, so every chart step sees a boundary there, and
 * joins the copies again before the atlas is written. */
#ifndef NEUV_MESH_SEAM_CUT_H
#define NEUV_MESH_SEAM_CUT_H

#include "mesh/edge_faces.h"
#include "mesh/mesh.h"

/* Marks (seam[e] = 1) every edge of ef with exactly two faces whose normals
 * differ by more than `degrees` (the dihedral angle's supplement: 0 for a
 * flat edge, 90 for a cube's edge). Faces of zero area mark nothing.
 * Returns the number of edges newly marked. */
int seam_mark_angle(const neuv_mesh *m, const edge_faces *ef, double degrees, unsigned char *seam);

/* Marks the edges whose two end points have exactly the positions of the
 * pairs in `ends` (n pairs, each two points of 3 doubles): positions, not
 * indices, so edges given on a mesh before cleaning find their copies in the
 * cleaned one (cleaning moves no vertex). A pair that is no edge of m counts
 * in *unmatched. Returns the number of edges newly marked, -1 on allocation
 * failure. */
int seam_mark_positions(const neuv_mesh *m, const edge_faces *ef, const double *ends, int n,
                        unsigned char *seam, int *unmatched);

/* Cuts m open along the marked edges: the corners around a vertex are
 * grouped into fans joined across unmarked edges, and each fan after the
 * first (in corner order) gets its own copy of the vertex, appended after
 * the original vertices. Faces and UVs keep their order and values.
 * Outputs: *out (mesh_free), *origin (#V' ints: the vertex of m each vertex
 * of *out copies; mem_free). NEUV_ERR_NOMEM on allocation failure. */
neuv_status mesh_cut_seams(const neuv_mesh *m, const edge_faces *ef, const unsigned char *seam,
                           neuv_mesh **out, int **origin);

/* Joins the copies made by mesh_cut_seams again, in place: every corner
 * refers to origin[v], and the mesh keeps its first nv_before vertices. */
void mesh_join_seams(neuv_mesh *m, const int *origin, int nv_before);

#endif
