/* Orientation of a flattening: both classic methods return maps whose total
 * signed UV area is positive, so their faces keep the 3D orientation. */
#ifndef NEUV_FLATTEN_UV_ORIENT_H
#define NEUV_FLATTEN_UV_ORIENT_H

#include "mesh/mesh.h"

/* Mirrors u (u -> -u) when the total signed area of the faces in uv is negative.
 * Inputs:  m   #F by 3 faces
 * In/out:  uv  #V by 2 per-vertex UVs */
void flatten_orient_ccw(const neuv_mesh *m, double *uv);

#endif
