/* Where each chart's final map came from (the report's per-chart "source"):
 * the networks' own map, the networks' map after a classic or optimization
 * step, or a classic flattening and why. A chart flattened or re-solved by a
 * classic method is that method's, whatever started it. */
#ifndef NEUV_UNWRAP_CHART_SOURCE_H
#define NEUV_UNWRAP_CHART_SOURCE_H

#include "mesh/mesh.h"

typedef enum chart_source {
    CHART_SOURCE_NETWORK = 0,        /* MLP_f's map, untouched (only moved, turned, scaled by packing) */
    CHART_SOURCE_NETWORK_REFINED,    /* MLP_f's injective map, then a classic or optimization step */
    CHART_SOURCE_NETWORK_FOLDED,     /* MLP_f's map kept with its folds (--allow-overlaps) */
    CHART_SOURCE_LSCM_AFTER_FOLD,    /* MLP_f's map folded; LSCM flattened the chart */
    CHART_SOURCE_LSCM_AFTER_SPLIT,   /* a piece of a chart split because its map folded; LSCM */
    CHART_SOURCE_LSCM,               /* --method lscm */
    CHART_SOURCE_HARMONIC,           /* --method harmonic */
    CHART_SOURCE_HARMONIC_AFTER_SPLIT,
    CHART_SOURCE_TRANSFERRED,        /* a saved model's classic chart: UVs taken from its source surface */
    CHART_SOURCE_COUNT
} chart_source;

/* "network", "network+refined", "network_folded", "lscm_after_fold", "lscm_after_split",
 * "lscm", "harmonic", "harmonic_after_split", "transferred". */
const char *chart_source_name(chart_source s);

/* 1 for the sources whose map the networks made injectively (network,
 * network+refined), else 0. */
int chart_source_is_network(chart_source s);

/* Area-weighted mean of qce = s1/s2 (docs/metrics.md) over the faces of a
 * chart with per-vertex UVs, faces of zero 3D or UV area left out; *area
 * (may be NULL) gets the chart's 3D area. Returns NaN when no face counts. */
double chart_qce_mean(const neuv_mesh *sub, const double *uv, double *area);

/* L2 stretch of a chart's map (docs/metrics.md: Sander et al.'s, after the
 * scale that makes the chart's UV area its 3D area), over the faces whose
 * 3D and UV areas are not zero; NaN when there is none. */
double chart_l2_stretch(const neuv_mesh *sub, const double *uv);

#endif
