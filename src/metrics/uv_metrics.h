/* The metrics of SPEC.md section 5, for any mesh with UVs. */
#ifndef NEUV_METRICS_UV_METRICS_H
#define NEUV_METRICS_UV_METRICS_H

#include "mesh/mesh.h"
#include "core/json_writer.h"

typedef struct uv_metrics {
    int charts;
    double qce_mean, qce_p95, qce_max;
    double ase_mean, ase_abs_mean, ase_abs_mean_chart;
    double l2_stretch, linf_stretch;
    double sym_dirichlet_mean;
    int flipped, degenerate_uv;
    double overlap_fraction;
    double packing_efficiency; /* negative (written as null) when UVs leave [0,1]² */
    double seam_length;
} uv_metrics;

/* Computes every metric. The mesh is used as given (callers weld exactly
 * duplicated positions first so that seams are found across shared edges). */
neuv_status uv_metrics_compute(const neuv_mesh *m, uv_metrics *out);
/* Writes the metrics as the members of the current JSON object. */
void uv_metrics_write_json(const uv_metrics *mt, json_writer *w);

#endif
