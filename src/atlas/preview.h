/* Pictures users judge UV maps by (PNG).
 *   PREFIX-uv.png      the atlas square: charts filled in their own colours,
 *                      edges drawn, flipped faces red, overlaps highlighted;
 *                      UVs in UDIM tiles (texels per unit) show the tiles
 *                      side by side, each in white
 *   PREFIX-checker.png the mesh rendered with a checkerboard through its UVs
 *                      from four views (front, back, left, top) */
#ifndef NEUV_ATLAS_PREVIEW_H
#define NEUV_ATLAS_PREVIEW_H

#include "mesh/mesh.h"

typedef enum preview_color { PREVIEW_COLOR_CHART = 0, PREVIEW_COLOR_QCE, PREVIEW_COLOR_AREA } preview_color;

/* Writes PREFIX-uv.png and PREFIX-checker.png for a mesh with UVs. */
neuv_status preview_write(const neuv_mesh *m, const char *prefix, preview_color color);
/* Same at `size` px (64..16384) instead of 1024, e.g. for pictures kept in docs/. */
neuv_status preview_write_sized(const neuv_mesh *m, const char *prefix, preview_color color, int size);
/* Writes one picture of the mesh with its faces coloured by face_label
 * (e.g. charts of a segmentation) from the same four views. */
neuv_status preview_write_labels(const neuv_mesh *m, const int *face_label, const char *path);

#endif
