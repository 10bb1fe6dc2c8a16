/* Atlas packing: every chart scaled to one texel density, turned to its
 * minimum-area rectangle and placed, by its rasterized footprint, into one
 * square texture with `padding` pixels between charts and to the border.
 * Each chart's UVs change only by a similarity (rotation, uniform scale,
 * translation), kept per chart so a saved model can reapply the layout. */
#ifndef NEUV_ATLAS_PACK_H
#define NEUV_ATLAS_PACK_H

#include "mesh/mesh.h"

typedef struct atlas_pack_options {
    int resolution; /* atlas side in pixels (default 1024) */
    int padding;    /* empty pixels between charts and to the border (default 2) */
    int keep_scale; /* 1: keep the given relative scales of the charts instead of equal texel density */
    int quick;      /* 1: the scale search only (no shuffled-order polish): to compare chart sets */
    double texels_per_unit; /* > 0: a fixed density, this many pixels per unit of 3D length, and
                               as many resolution-sized tiles as the charts need (UDIM layout:
                               tile k is the UV square [k mod 10, +1] x [k div 10, +1]); 0: one
                               square at the largest density that fits */
} atlas_pack_options;

/* The similarity that took chart UVs to the atlas:
 * uv' = scale * [cos a, -sin a; sin a, cos a] * uv + (tx, ty). */
typedef struct atlas_chart_transform {
    double scale, angle, tx, ty;
} atlas_chart_transform;

typedef struct atlas_pack_result {
    double efficiency;    /* total UV area of the packed atlas (share of the unit square) */
    double texel_scale;   /* pixels per unit of 3D length (texel density) */
    int attempts;         /* packings tried while searching the scale */
    int tiles;            /* unit squares used (1 without texels_per_unit) */
} atlas_pack_result;

/* Most tiles a packing may use: UDIM 1001..1100. */
#define ATLAS_PACK_MAX_TILES 100

void atlas_pack_options_default(atlas_pack_options *o);

/* Packs the charts of m in place.
 * With texels_per_unit, the charts are scaled to that density and placed
 * greedily: each tile takes, largest first, every remaining chart that
 * still finds room, and the rest go to the next tile; a chart too large for
 * one tile at that density is refused (NEUV_ERR_INPUT), as are keep_scale
 * with it and more than ATLAS_PACK_MAX_TILES tiles.
 * Inputs: m with per-corner UVs (nuv > 0), face_chart (#F) chart id per
 * face in [0, ncharts) (e.g. from uv_charts), options (NULL: defaults).
 * Outputs: m's UVs replaced by UVs in [0,1]^2, or in the tiles (a UV shared by faces of two
 * charts is duplicated, so nuv can grow); xf (ncharts, may be NULL) the
 * transform of each chart; res (may be NULL).
 * Deterministic: the same input gives the same output bit for bit. */
neuv_status atlas_pack(neuv_mesh *m, const int *face_chart, int ncharts,
                       const atlas_pack_options *opt, atlas_chart_transform *xf,
                       atlas_pack_result *res);

/* Applies a chart transform to one UV. */
void atlas_chart_transform_apply(const atlas_chart_transform *t, const double uv[2], double out[2]);

#endif
