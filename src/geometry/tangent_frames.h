/* Per-vertex tangent frames: an orthonormal basis (e1, e2, n) at each vertex,
 * n the area-weighted vertex normal (sum of face cross products), e1 the
 * coordinate axis least aligned with n projected onto the tangent plane,
 * e2 = n × e1. A vertex whose faces cancel (or that has none) gets the
 * unweighted mean of its unit face normals, then +z as a last resort.
 *
 * Inputs:  m      mesh
 * Outputs: frames #V by 3 by 3 (caller allocates): frames[9i + 0..2] = e1,
 *          [9i + 3..5] = e2, [9i + 6..8] = n */
#ifndef NEUV_GEOMETRY_TANGENT_FRAMES_H
#define NEUV_GEOMETRY_TANGENT_FRAMES_H

#include "mesh/mesh.h"

void tangent_frames(const neuv_mesh *m, double *frames);

#endif
