/* PatchNet's charts (Pokhariya et al. 2022, section 3.1): the network of
 * models/patchnet.h trained on the shape, its per-face argmax turned into
 * charts that are topological disks (charts/charts.h), and each chart judged
 * by how its LSCM flattening turns out (segment/chart_judge.h).
 *
 * Number of charts: a fixed K (`charts` > 0), or auto (`charts` = 0): train
 * with a small K, then split every chart whose LSCM flattening has qce_mean
 * >= max_distortion or a flipped face, until all pass or max_charts is
 * reached (see patchnet_segment.c for why splitting rather than retraining),
 * then merge adjacent charts back while their union flattens well.
 *
 * Usage:
 *     patchnet_options o;  patchnet_default_options(&o);
 *     int *chart = mem_alloc(nf * sizeof(int)), n; float *feat; int dim;
 *     patchnet_report rep;
 *     if (patchnet_segment(m, &ops, &o, chart, &n, &feat, &dim, &rep)) ...
 *     mem_free(feat); mem_free(chart); */
#ifndef NEUV_SEGMENT_PATCHNET_SEGMENT_H
#define NEUV_SEGMENT_PATCHNET_SEGMENT_H

#include "geometry/operators.h"
#include "mesh/mesh.h"
#include "models/patchnet.h"

/* Whole stage: train, argmax, charts_from_labels, and for auto K the split
 * loop until every chart flattens by LSCM with qce_mean < max_distortion
 * and no flipped face (or max_charts is reached: the report says so through
 * worst_qce).
 * Inputs:  m (cleaned mesh), ops (its operators), o (NULL: defaults)
 * Outputs: face_chart #F chart ids (caller allocates), n_charts,
 *          vertex_features #V by *feature_dim (malloc'd; caller frees; may be
 *          NULL), rep (may be NULL) */
neuv_status patchnet_segment(const neuv_mesh *m, const operators *ops, const patchnet_options *o,
                             int *face_chart, int *n_charts, float **vertex_features, int *feature_dim,
                             patchnet_report *rep);

/* As patchnet_segment, also handing over the trained model (*model_out
 * filled; caller frees with patchnet_model_free); model_out may be NULL. */
neuv_status patchnet_segment_model(const neuv_mesh *m, const operators *ops, const patchnet_options *o,
                                   int *face_chart, int *n_charts, float **vertex_features, int *feature_dim,
                                   patchnet_report *rep, patchnet_model *model_out);

/* The chart half of patchnet_segment with a trained model (inference only):
 * argmax, charts_from_labels, and for auto K (o->charts = 0) the split and
 * merge loop. Outputs as patchnet_segment; rep's chart fields are filled. */
neuv_status patchnet_charts_from_model(const patchnet_model *model, const neuv_mesh *m, const operators *ops,
                                      const patchnet_options *o, int *face_chart, int *n_charts,
                                      float **vertex_features, int *feature_dim, patchnet_report *rep);

#endif
