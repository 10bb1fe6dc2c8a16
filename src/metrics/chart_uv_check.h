/* Whether one chart's flattening is usable: every face keeps a positive,
 * non-degenerate UV area and the boundary loop does not cross itself.
 * For a disk these two together mean the map is injective (a locally
 * injective map of a disk whose boundary is a simple curve is a bijection
 * onto the region it bounds), so passing charts have neither flips nor
 * self-overlaps, whatever the overlap raster's resolution. */
#ifndef NEUV_METRICS_CHART_UV_CHECK_H
#define NEUV_METRICS_CHART_UV_CHECK_H

#include "mesh/mesh.h"

typedef struct chart_uv_check {
    int flipped;             /* faces with negative UV area (after orienting the chart CCW) */
    int degenerate;          /* faces with |UV area| <= 1e-9 x mean |UV area| */
    int boundary_crossings;  /* pairs of non-adjacent boundary segments that touch or cross */
    int mirrored;            /* 1 when the chart was clockwise and has been mirrored */
} chart_uv_check;

/* Inputs:  sub  one disk chart as a mesh (#CV by 3, #CF by 3)
 *          uv   #CV by 2 per-vertex UVs; mirrored (u -> -u) in place when
 *               the chart's total UV area is negative
 * Outputs: out  the counts
 * Returns 1 when the chart is usable, 0 when not, -1 on allocation failure. */
int chart_uv_check_run(const neuv_mesh *sub, double *uv, chart_uv_check *out);

#endif
