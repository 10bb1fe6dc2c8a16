/* Overlap of a UV map by rasterization (docs/metrics.md, `overlap_fraction`):
 * every triangle is drawn into a coverage-count raster at `resolution`
 * pixels on the longer side of the UV bounding box, sampling pixel centres
 * with a top-left fill rule, so faces that tile the plane cover each centre
 * exactly once and only true overlaps count twice. */
#ifndef NEUV_METRICS_UV_OVERLAP_H
#define NEUV_METRICS_UV_OVERLAP_H

#include "neuv/neuv.h"

typedef struct uv_coverage {
    long long covered;    /* pixel centres covered at least once */
    long long overlapped; /* pixel centres covered at least twice */
} uv_coverage;

/* Counts covered and overlapped pixel centres of a set of UV triangles.
 * Inputs:
 *   uv          #UV by 2 texture coordinates
 *   nf, tri_uv  #F by 3 UV indices per face
 *   face_mask   #F, nonzero for the faces to draw (NULL: all faces)
 *   resolution  pixels on the longer side of the bounding box of the drawn
 *               faces' UVs (2048 for the metric)
 * Outputs:
 *   out         the counts (both zero when nothing is drawn or the box is a point)
 * Returns NEUV_OK, NEUV_ERR_INPUT for a resolution outside [1, 32768],
 * or NEUV_ERR_NOMEM. */
neuv_status uv_coverage_count(const double *uv, int nf, const int *tri_uv,
                              const unsigned char *face_mask, int resolution, uv_coverage *out);

/* The pairs of charts that share a covered pixel centre, under the same
 * rule and raster as uv_coverage_count over all faces.
 * Inputs: uv, nf, tri_uv as above; face_chart (#F) chart id per face;
 *         resolution as above.
 * Outputs: *pairs (2 x *n_pairs ints, a < b per pair, sorted; caller frees;
 *          NULL when there is none), *n_pairs.
 * Returns NEUV_OK, NEUV_ERR_INPUT (resolution), NEUV_ERR_NOMEM. */
neuv_status uv_overlap_chart_pairs(const double *uv, int nf, const int *tri_uv, const int *face_chart,
                                   int resolution, int **pairs, int *n_pairs);

/* The faces that cover a pixel centre which faces of two or more charts
 * cover, under the same rule and raster as uv_overlap_chart_pairs.
 * Outputs: hit (#F): 1 for such a face, else 0.
 * Returns NEUV_OK, NEUV_ERR_INPUT (resolution), NEUV_ERR_NOMEM. */
neuv_status uv_overlap_faces(const double *uv, int nf, const int *tri_uv, const int *face_chart, int resolution,
                             unsigned char *hit);

/* overlapped / covered (0 when nothing is covered). */
double uv_coverage_overlap_fraction(const uv_coverage *c);

#endif
