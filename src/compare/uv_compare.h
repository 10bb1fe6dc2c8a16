/* UV consistency of two UV maps of the same surface (possibly two
 * different triangulations of it): how far B's UVs are from A's UVs at the
 * same points of the surface, and how well their charts agree. */
#ifndef NEUV_COMPARE_UV_COMPARE_H
#define NEUV_COMPARE_UV_COMPARE_H

#include "mesh/mesh.h"

#define UV_COMPARE_WORST 5

typedef struct uv_compare_result {
    double uv_mean, uv_p95, uv_max; /* UV distance in atlas units (UV coordinates), in the matched chart */
    double nearest_mean, nearest_p95, nearest_max; /* the same at the closest point whatever its chart */
    double across_seam;             /* share of B's corners lying past their matched A chart's seam */
    double chart_agreement;         /* headline: share of B's surface AREA whose chart agrees */
    double chart_agreement_faces;   /* the same share counted in faces */
    double chart_agreement_facing;  /* the area share with the closest point among A's faces facing the
                                       B face's way (bvh_closest_point_facing), as `neuv unwrap --model`
                                       finds each face's chart: where two sheets are closer than the
                                       triangulations differ (a lid resting on its pot, the two sides of a
                                       thin part) the plain closest point can lie on the other sheet */
    int faces_a, faces_b;
    int charts_a, charts_b;
    int vertices_compared;          /* distinct (vertex, UV) corners of B */
    double max_surface_distance;    /* largest distance from a compared B vertex to A's surface */
    int worst_chart[UV_COMPARE_WORST];   /* B charts with the largest mean UV distance (-1: none) */
    int worst_match[UV_COMPARE_WORST];   /* the A chart each is matched to */
    int worst_corners[UV_COMPARE_WORST]; /* its corners compared */
    double worst_mean[UV_COMPARE_WORST]; /* their mean UV distance */
} uv_compare_result;

/* Compares B's UV map against A's.
 * Chart agreement: charts are uv_charts of each mesh. Each B face's
 * centroid is located on A (closest point) to get the A chart under it;
 * each B chart is matched to the A chart holding most of its area; a B
 * face agrees when the A chart under its centroid is its chart's match.
 * The headline share is by area (a few tiny faces along chart borders do
 * not dominate it); the share by face count is reported too.
 * UV distance (uv_*): for every distinct (vertex, UV) corner of B, A's UV
 * map OF THE A CHART MATCHED TO THE CORNER'S B CHART at the closest point of
 * the surface, and the Euclidean distance to B's UV. Where the closest
 * point lies on an edge or vertex of A, every A face of that chart touching
 * it is a candidate and the nearest UV value counts (on A's seams the UV is
 * multi-valued and B's corner belongs to one side). A corner past its
 * chart's seam (a triangulation that shares no edge with A cannot follow
 * the seam exactly: a face across it belongs to one side) is compared
 * with the chart's map extended linearly past its border: the closest
 * point of that chart, its face's affine UV map at the corner's projection.
 * That is where a texture painted on A, with the usual gutter dilation,
 * is read. across_seam is the share of corners compared that way.
 * nearest_*: the plain measure, A's UV at the closest point of the whole
 * surface whatever its chart (a corner past a seam then counts the
 * distance between the two charts' places in the atlas).
 * Inputs: a, b meshes with UVs.
 * Outputs: *res.
 * Returns NEUV_OK, NEUV_ERR_INPUT (a mesh without faces or UVs), NEUV_ERR_NOMEM. */
neuv_status uv_compare(const neuv_mesh *a, const neuv_mesh *b, uv_compare_result *res);

#endif
