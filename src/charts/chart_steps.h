/* The steps of charts_from_labels, shared with charts_split. Internal to charts/. */
#ifndef NEUV_CHARTS_CHART_STEPS_H
#define NEUV_CHARTS_CHART_STEPS_H

#include "charts/charts.h"
#include "charts/face_graph.h"

/* Merges every piece with area below min_area into the neighbour it shares
 * the longest boundary with, smallest piece first (ties: smaller id), the
 * neighbour with the smaller id on equal lengths, until no piece below
 * min_area has a neighbour left. Pieces are then renumbered by first face.
 * Inputs: m, g, piece (#F ids 0..*n_pieces-1, modified), n_pieces (updated),
 * min_area. Output: merged, the number of merges.
 * Returns NEUV_OK or NEUV_ERR_NOMEM. */
neuv_status charts_merge_fragments(const neuv_mesh *m, const face_graph *g, int *piece, int *n_pieces,
                                   double min_area, int *merged);

/* Makes chart only_id (or every chart when only_id < 0) a topological disk
 * by recursive splitting: a chart in several edge-connected parts is
 * separated, an annulus is cut by two shortest paths between its loops,
 * anything else is split by chart_local_grow2; the part holding the first
 * face keeps the id, the others get new ids from *n_charts on.
 * Inputs: m, g, face_chart (#F, modified), n_charts (updated), only_id.
 * Output: report counters separated/annulus_cuts/region_splits incremented
 * (may be NULL). Returns NEUV_OK, NEUV_ERR_NOMEM or NEUV_ERR_INTERNAL. */
neuv_status charts_make_disks(const neuv_mesh *m, const face_graph *g, int *face_chart, int *n_charts,
                              int only_id, charts_report *report);

#endif
