/* Charts of a UV map: connected components of faces joined across an edge
 * whose two endpoints have the same UV values on both sides (SPEC.md §5). */
#ifndef NEUV_ATLAS_UV_CHARTS_H
#define NEUV_ATLAS_UV_CHARTS_H

#include "mesh/mesh.h"

/* Inputs: m with UVs (nuv > 0).
 * Outputs: face_chart (#F) chart id per face, numbered by first face.
 * Returns the number of charts, or -1 on allocation failure. */
int uv_charts(const neuv_mesh *m, int *face_chart);

#endif
