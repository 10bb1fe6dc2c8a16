/* The metrics of SPEC.md section 5, for any mesh with UVs. The exact
 * definitions (which faces count, the percentile rule, the raster rule) are
 * in docs/metrics.md; tests/reference_metrics.py implements them separately. */
#ifndef NEUV_METRICS_UV_METRICS_H
#define NEUV_METRICS_UV_METRICS_H

#include "mesh/mesh.h"
#include "core/json_writer.h"

/* Faces with 3D area below this times the mean are left out of every metric. */
#define UV_METRICS_AREA_EPS 1e-12
/* How far a UV may lie outside its unit square (or tile) and still count as inside. */
#define UV_METRICS_UNIT_TOL 1e-9

typedef struct uv_metrics {
    int charts;
    double qce_mean, qce_p95, qce_max;
    double ase_mean, ase_abs_mean, ase_abs_mean_chart;
    double l2_stretch, linf_stretch;
    double sym_dirichlet_mean;
    int flipped, degenerate_uv;
    double overlap_fraction;
    double packing_efficiency; /* NaN (written as null) when UVs leave [0,1]² */
    double seam_length;
    int excluded_faces;        /* faces with 3D area below 1e-12 x mean, left out of everything */
} uv_metrics;

/* Computes every metric. The mesh is used as given (callers weld exactly
 * duplicated positions first so that seams are found across shared edges).
 * Inputs: m with UVs (nuv > 0, tri_uv #F by 3).
 * Outputs: out; metrics with no face to measure are NaN.
 * Returns NEUV_OK, NEUV_ERR_INPUT when m has no UVs, or NEUV_ERR_NOMEM. */
neuv_status uv_metrics_compute(const neuv_mesh *m, uv_metrics *out);
/* The same without the overlap raster (a 2048 px coverage count):
 * overlap_fraction is NaN, every other metric is uv_metrics_compute's. */
neuv_status uv_metrics_compute_no_overlap(const neuv_mesh *m, uv_metrics *out);
/* Writes the metrics as the members of the current JSON object. */
void uv_metrics_write_json(const uv_metrics *mt, json_writer *w);

/* Singular values s1 >= s2 of the Jacobian of the affine map from a 3D
 * triangle, flattened isometrically into its plane, to its UV triangle.
 * Inputs: p 3 by 3 corner positions, q 3 by 2 corner UVs.
 * Outputs: s (2) = {s1, s2}; both 0 when the 3D triangle has no area.
 * Returns the signed Jacobian determinant (UV area / 3D area, negative when
 * the UV triangle turns clockwise). */
double uv_jacobian_singular_values(const double p[3][3], const double q[3][2], double s[2]);

#endif
