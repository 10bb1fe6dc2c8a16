/* How well one chart of a face-to-chart assignment flattens on its own, the
 * test PatchNet's split and merge loop (segment/patchnet_segment.h) applies:
 * the chart is cut out, flattened by LSCM and measured (qce_mean, flipped and
 * degenerate faces), and on request its boundary self-crossings
 * (metrics/chart_uv_check.h: the self-overlaps the repair stage would
 * otherwise split later) and how much of its UV footprint's convex hull the
 * footprint fills (snakes and combs pack badly). A chart LSCM cannot
 * flatten stays at qce_mean INFINITY, so the split loop cuts it smaller. */
#ifndef NEUV_SEGMENT_CHART_JUDGE_H
#define NEUV_SEGMENT_CHART_JUDGE_H

#include "mesh/mesh.h"

/* Inputs:  m, face_chart #F chart ids, id the chart to judge
 * Outputs: qce_mean (INFINITY when LSCM fails), flipped (flipped + degenerate
 *          UV faces); crossings (may be NULL: not checked) boundary
 *          self-crossings; convexity (may be NULL; measured only along with
 *          crossings, else 1) UV area over its convex hull's area
 * Returns NEUV_OK, or the error of cutting the chart out or of an allocation
 * (a chart LSCM fails on is judged, not an error). */
neuv_status chart_lscm_judge(const neuv_mesh *m, const int *face_chart, int id, double *qce_mean,
                             int *flipped, int *crossings, double *convexity);

/* LSCM quality of one chart: flattens chart `id` alone and measures it.
 * Outputs: qce_mean (INFINITY when LSCM fails), flipped faces. */
neuv_status patchnet_chart_lscm_quality(const neuv_mesh *m, const int *face_chart, int id, double *qce_mean,
                                        int *flipped);

#endif
