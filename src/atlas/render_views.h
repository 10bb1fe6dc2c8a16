/* A small software renderer for previews: the mesh from four views (front,
 * back, left, top) in a 2 by 2 grid, perspective camera, depth buffer, flat
 * Lambert shading, textured by a checkerboard through the UVs or coloured
 * by a label per face. */
#ifndef NEUV_ATLAS_RENDER_VIEWS_H
#define NEUV_ATLAS_RENDER_VIEWS_H

#include "atlas/raster_image.h"
#include "mesh/mesh.h"

/* Background colour of the rendered pictures (for tests that measure coverage). */
extern const uint8_t render_background[3];

/* Renders m into a new size by size image (caller frees with raster_image_free).
 * Inputs: m; face_label (#F) colours faces by label (negative: grey), or NULL
 * for a checkerboard of `checker_squares` squares across the UV range (the
 * unit square when the UVs lie in it, otherwise their bounding box).
 * Returns NEUV_OK or NEUV_ERR_NOMEM. */
neuv_status render_four_views(const neuv_mesh *m, const int *face_label, int checker_squares, int size,
                              raster_image *out);

#endif
