/* Signed volume enclosed by a set of faces. */
#ifndef NEUV_MESH_SIGNED_VOLUME_H
#define NEUV_MESH_SIGNED_VOLUME_H

#include "mesh/mesh.h"

/* Sum over faces of det(a, b, c) / 6 (divergence theorem): the enclosed
 * volume for a closed surface, positive when the faces point outward.
 * Positions are taken relative to the faces' first vertex, which leaves
 * the result of a closed surface unchanged but reduces cancellation.
 * Inputs: m; faces (#nfaces) face indices, or NULL for all faces of m. */
double mesh_signed_volume(const neuv_mesh *m, const int *faces, int nfaces);

#endif
