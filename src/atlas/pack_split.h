/* Splitting charts so that they pack better. A chart whose UV footprint
 * is far from convex (long arms, a crescent) leaves most of its bounding
 * box empty, and no placement order recovers that space. Cutting such a
 * chart in two (charts_split: along its long axis, both parts disks) keeps
 * every UV as it is, so angle and area distortion do not change; only the
 * seams grow. A split is kept when a quick packing of the atlas gains
 * enough; otherwise the chart is left whole.
 *
 * Rule: up to max_trials times, take the least convex chart (UV area over
 * the area of its convex hull, below max_convexity) not tried yet, split
 * it, and keep the split when the quick packing efficiency (scale search
 * only, at a 256 px side: a quarter of the default atlas, 1/16 of the
 * cost) grows by at least min_gain (relative). Only atlases of at most max_charts charts are
 * considered: many charts already fill the square well, and each trial is
 * one packing. */
#ifndef NEUV_ATLAS_PACK_SPLIT_H
#define NEUV_ATLAS_PACK_SPLIT_H

#include "atlas/pack.h"
#include "mesh/mesh.h"

typedef struct pack_split_options {
    int max_trials;        /* splits tried (16) */
    int max_splits;        /* splits kept (12) */
    int max_charts;        /* no splitting above this many charts (64) */
    double max_convexity;  /* only charts less convex than this are split (0.8, as the chart merge rule) */
    double min_gain;       /* relative packing gain a split must bring (0.005) */
    atlas_pack_options pack; /* resolution and padding of the trial packings */
} pack_split_options;

typedef struct pack_split_report {
    int trials, splits;
    double efficiency_before, efficiency_after; /* quick packings */
    double seconds;
} pack_split_report;

void pack_split_default_options(pack_split_options *o);

/* Inputs:  m           mesh with per-corner UVs (each chart in its own frame; not modified)
 *          face_chart  #F chart ids in 0..*n_charts-1 (modified in place)
 *          n_charts    chart count (updated)
 *          o           options (NULL: defaults)
 * Outputs: *parent     malloc'd, one entry per final chart: the chart it was
 *                      cut from (itself for a chart that was not split;
 *                      the caller frees)
 *          rep         may be NULL
 * Returns NEUV_OK, NEUV_ERR_INPUT or NEUV_ERR_NOMEM. */
neuv_status pack_split_charts(const neuv_mesh *m, int *face_chart, int *n_charts, const pack_split_options *o,
                              int **parent, pack_split_report *rep);

#endif
