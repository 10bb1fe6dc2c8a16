/* Charts: sets of faces that can each be flattened on their own.
 *
 * A chart assignment is one int per face (#F), chart ids 0..n_charts-1. A
 * valid chart is a topological disk: its faces are joined across shared
 * manifold edges, its boundary is exactly one loop, its genus is 0 and the
 * loop visits no vertex twice (no pinched vertex, no two fans of the chart
 * meeting at a vertex only). The pipeline stage after PatchNet turns the
 * per-face argmax label into such charts with charts_from_labels; the
 * auto-K loop and the repair stage refine a chart with charts_split. */
#ifndef NEUV_CHARTS_CHARTS_H
#define NEUV_CHARTS_CHARTS_H

#include "mesh/mesh.h"

typedef struct charts_options {
    /* Connected pieces with less than this share of the total surface area
     * are merged into a neighbour (default 0.002, see charts_default_options). */
    double min_area_share;
    /* Sweeps of charts_smooth_boundaries over the final charts (default 50;
     * 0 turns smoothing off). */
    int smooth_sweeps;
} charts_options;

typedef struct charts_report {
    int pieces;         /* connected pieces of equal label (step a) */
    int merged;         /* fragments under the area share merged into a neighbour (step b) */
    int separated;      /* charts that fell apart into edge-connected parts and were separated */
    int annulus_cuts;   /* annuli split in two by two shortest cuts between their loops */
    int region_splits;  /* other non-disks (closed, handles, many loops, pinched) split by 2-seed growing */
    int smoothed;       /* faces moved by boundary smoothing */
    int charts;         /* final number of charts */
} charts_report;

/* Fills o with the defaults: min_area_share = 0.002, smooth_sweeps = 50. */
void charts_default_options(charts_options *o);

/* Charts from a per-face label (e.g. PatchNet's argmax): (a) connected
 * pieces of equal label, (b) pieces under opts->min_area_share of the area
 * merged into the neighbour sharing the longest boundary, repeated smallest
 * first until none is left, (c) every piece made a topological disk (annuli
 * cut along two shortest paths between their loops, anything else split by
 * growing two regions from the farthest pair of faces, recursively), then
 * verified with the mesh topology code. Deterministic for a given input.
 *
 * Inputs:
 *   m           mesh, #F by 3 faces (cleaned: manifold, consistently oriented)
 *   face_label  #F labels, any values >= 0
 *   opts        options, NULL for the defaults
 * Outputs:
 *   face_chart  #F chart id per face, numbered in order of first face
 *   n_charts    number of charts
 *   report      counts of what each step did (may be NULL)
 * Returns NEUV_OK, NEUV_ERR_INPUT (bad label or options), NEUV_ERR_NOMEM,
 * or NEUV_ERR_INTERNAL when a final chart fails the topology check. */
neuv_status charts_from_labels(const neuv_mesh *m, const int *face_label,
                               const charts_options *opts, int *face_chart,
                               int *n_charts, charts_report *report);

/* Splits chart `chart_id` in two along its long axis: regions grown from
 * the two faces farthest apart by face-graph geodesic distance. Each part
 * is then made a disk, so a non-disk part may add further charts. The part
 * holding the chart's first face keeps chart_id; the others get ids
 * *n_charts, *n_charts + 1, ... (ids of other charts are unchanged).
 *
 * Inputs:
 *   m           mesh, #F by 3 faces
 *   face_chart  #F chart ids in 0..*n_charts-1 (modified in place); the
 *               boundaries between the new parts are smoothed by
 *               charts_smooth_boundaries (the other charts keep their faces)
 *   n_charts    number of charts (updated)
 *   chart_id    the chart to split; it needs at least 2 faces
 * Returns NEUV_OK, NEUV_ERR_INPUT or NEUV_ERR_NOMEM. */
neuv_status charts_split(const neuv_mesh *m, int *face_chart, int *n_charts, int chart_id);

/* Smooths chart boundaries: a face moves to the neighbouring chart it
 * shares strictly more boundary length with than with its own chart (a
 * spike out of its chart, or a notch in the neighbour), when the move keeps
 * both charts topological disks (checked locally: the triangle must meet
 * each chart in one arc). Sweeps in face order until nothing moves or
 * max_sweeps; deterministic. Charts must be disks on entry; none empties.
 *
 * Inputs:
 *   m           mesh, #F by 3 faces (manifold, consistently oriented)
 *   active      per chart id, nonzero for charts that may give or take
 *               faces (NULL: all)
 *   face_chart  #F chart ids >= 0 (modified in place)
 *   max_sweeps  sweeps over all faces at most
 * Outputs:
 *   moves       faces moved (may be NULL)
 * Returns NEUV_OK, NEUV_ERR_INPUT or NEUV_ERR_NOMEM. */
neuv_status charts_smooth_boundaries(const neuv_mesh *m, const int *active, int *face_chart, int max_sweeps,
                                     int *moves);

/* Puts every triangle of a polygon (face_polygon: the same id on
 * consecutive faces; < 0: a face of no polygon) in one chart, the one
 * holding most of its area, by moves that keep every chart a disk
 * (charts/polygon_charts.c); only charts with active[c] != 0 give or take
 * faces (active NULL: all). Output: split_left, the polygons still in more
 * than one chart (may be NULL). Returns NEUV_OK or NEUV_ERR_NOMEM. */
neuv_status charts_keep_polygons(const neuv_mesh *m, const int *face_polygon, const int *active, int *face_chart,
                                 int *split_left);

/* Polygons (as in charts_keep_polygons) in more than one chart. */
int charts_count_split_polygons(int nf, const int *face_polygon, const int *face_chart);

/* Renumbers chart ids in order of their first face (ids < 0 are left
 * alone). Inputs: nf, face_chart (#F, modified). Returns the number of
 * charts, or -1 on allocation failure. */
int charts_renumber(int nf, int *face_chart);

/* Whether the faces with face_chart == id form a topological disk (one
 * edge-connected piece, one boundary loop, genus 0, no pinched vertex).
 * Returns 1, 0 (also for an empty chart), or -1 on allocation failure. */
int chart_is_disk(const neuv_mesh *m, const int *face_chart, int id);

/* One chart as a mesh of its own (no UVs).
 * Inputs: m, face_chart (#F), id.
 * Outputs:
 *   sub   new mesh (caller frees with mesh_free): #CV vertices, #CF faces,
 *         vertices in order of first use by the chart's faces
 *   vmap  #CV: mesh vertex of each chart vertex (caller frees)
 *   fmap  #CF: mesh face of each chart face, ascending (caller frees)
 * Returns NEUV_OK, NEUV_ERR_INPUT (no face has that id) or NEUV_ERR_NOMEM. */
neuv_status chart_submesh(const neuv_mesh *m, const int *face_chart, int id,
                          neuv_mesh **sub, int **vmap, int **fmap);

/* Which charts share boundary, and how much. */
typedef struct chart_adjacency {
    int n;          /* number of adjacent pairs */
    int *a, *b;     /* n chart pairs, a < b, sorted by (a, b) */
    double *length; /* n shared boundary lengths */
} chart_adjacency;

/* Inputs: m, face_chart (#F, ids >= 0).
 * Outputs: adj, pairs of charts joined by at least one manifold edge, with
 * the total length of the edges they share (free with chart_adjacency_free).
 * Returns NEUV_OK or NEUV_ERR_NOMEM. */
neuv_status chart_adjacency_build(const neuv_mesh *m, const int *face_chart, chart_adjacency *adj);
void chart_adjacency_free(chart_adjacency *adj);

#endif
