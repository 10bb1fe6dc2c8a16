/* The state of one unwrap, shared by the pipeline (unwrap.c) and its report
 * (unwrap_report.c). */
#ifndef NEUV_UNWRAP_UNWRAP_INTERNAL_H
#define NEUV_UNWRAP_UNWRAP_INTERNAL_H

#include "neuv/neuv.h"
#include "atlas/pack.h"
#include "mesh/clean.h"
#include "mesh/mesh.h"
#include "metrics/uv_metrics.h"

/* One repair, as the report lists it. */
typedef struct unwrap_repair {
    int chart;            /* chart id at the time of the repair */
    char what[160];       /* e.g. "neural map folded 3 faces; re-flattened with LSCM" */
} unwrap_repair;

enum { STAGE_CLEAN, STAGE_OPERATORS, STAGE_PATCHES, STAGE_PARAM, STAGE_REPAIR, STAGE_PACK, STAGE_METRICS, STAGE_COUNT };

struct neuv_unwrap_result {
    neuv_unwrap_options opts;
    neuv_mesh *mesh;          /* cleaned mesh with packed per-corner UVs */
    int input_vertices, input_faces;
    mesh_clean_report clean;
    int *face_chart;          /* #F */
    int n_charts;
    int patches;              /* K the segmentation used */
    int patch_iterations;
    double patch_iters_per_second;
    int param_iterations;
    double param_loss;
    int neural_charts;        /* charts whose final map is the network's */
    atlas_chart_transform *transforms; /* n_charts */
    atlas_pack_result pack;
    unwrap_repair *repairs;
    int n_repairs, cap_repairs;
    double seconds[STAGE_COUNT];
    double total_seconds;
    uv_metrics metrics;
    int cache_hit;
};

/* Appends a repair note (formatted); silently drops it if memory runs out. */
void unwrap_add_repair(struct neuv_unwrap_result *r, int chart, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

#endif
