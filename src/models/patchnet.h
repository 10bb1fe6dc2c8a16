/* PatchNet (Pokhariya et al. 2022, section 3.1; SPEC.md section 1.1): a
 * DiffusionNet whose per-face softmax over K outputs softly assigns every
 * face to a patch, trained on the shape itself with L_cos + L_geo
 * (losses/patch_losses.h, weights 1 and 1) by Adam.
 *
 * This is the network: create, train (one shape or several), infer labels
 * and features, and what a checkpoint saves (patchnet_model). Turning its
 * patches into charts that are topological disks, with the auto-K split and
 * merge loop, is segment/patchnet_segment.h. patchnet_options also carries
 * that stage's settings (charts, max_distortion, max_charts, min_area_share,
 * merge_distortion, min_convexity) and patchnet_report its chart counts, so
 * one struct configures the whole stage and one reports it.
 *
 * Usage:
 *     patchnet_options o;  patchnet_default_options(&o);
 *     patchnet_model model;
 *     if (patchnet_model_create_for_mesh(&model, &o, m, &ops, 8)) ...
 *     if (patchnet_train(&model, m, &ops, &o, NULL)) ...
 *     patchnet_infer(&model, m, &ops, face_label);   // face_label: #F ints
 *     patchnet_model_free(&model); */
#ifndef NEUV_MODELS_PATCHNET_H
#define NEUV_MODELS_PATCHNET_H

#include <stdint.h>

#include "geometry/operators.h"
#include "mesh/mesh.h"
#include "models/diffusion_net.h"
#include "nn/nn.h"

typedef struct patchnet_options {
    int charts;            /* K; 0 = auto (default) */
    double max_distortion; /* auto: every chart's LSCM qce_mean must be below this (1.15) */
    int max_charts;        /* auto: cap on the number of charts (64) */
    int initial_charts;    /* auto: K the network is trained with (8) */
    int iters;             /* training iteration cap (fast 300, paper 2000) */
    int blocks, width;     /* DiffusionNet size (fast 2 x 32, paper 4 x 128) */
    int k_eig;             /* eigenpairs used (64; capped by the operators) */
    diffusion_net_features features; /* input features (HKS, see patchnet.c) */
    uint64_t seed;         /* initialization and source sampling */
    int geo_sources;       /* S source faces of the L_geo estimator (128) */
    int plateau_window;    /* W: stop when the mean loss of the last W iterations */
    double plateau_tol;    /* improves on the W before by less than this share (25, 1e-3) */
    float lr;              /* Adam learning rate (1e-3) */
    double min_area_share; /* charts_from_labels fragment threshold (0.002) */
    double merge_distortion; /* auto: adjacent charts merge while the union's LSCM qce_mean is
                              * below this (1.03); <= 0 turns merging off */
    double min_convexity;  /* auto: and its UV area fills this share of its convex hull (0.8) */
    double empty_share;    /* training: every plateau window, a patch winning less than this share of
                            * the fair area 1/K is re-seeded by splitting the worst-fitting patch
                            * (models/patchnet_split.h; 0.1); 0 turns it off */
} patchnet_options;

/* The `fast` preset (the default). */
void patchnet_default_options(patchnet_options *o);
/* Applies a preset's network size and iteration cap: "fast" or "paper" (4 x 128,
 * 2000 iterations). Returns NEUV_ERR_INPUT for another name. */
neuv_status patchnet_apply_preset(patchnet_options *o, const char *preset);

typedef struct patchnet_report {
    int k;                  /* network outputs (patches) */
    int iterations;         /* training iterations run */
    int plateaued;          /* 1 when training stopped on the plateau rule */
    double loss, loss_cos, loss_geo; /* last iteration */
    double seconds;         /* whole patchnet_segment call */
    double geodesic_seconds; /* L_geo distance sources */
    double train_seconds;
    double iters_per_second;
    int label_charts;       /* charts straight from the argmax labels */
    int splits;             /* charts_split calls of the auto loop */
    int charts;             /* final charts */
    double worst_qce;       /* largest chart LSCM qce_mean */
    int flipped;            /* LSCM flipped faces over all charts */
    double chart_check_seconds;
    int merges;             /* auto: chart pairs merged back after the split loop */
    int reseeds;            /* emptied patches re-seeded during training (kept moves) */
} patchnet_report;

/* The trained network, kept so it can be saved (its nn_params) and applied to
 * another triangulation by inference. */
typedef struct patchnet_model {
    diffusion_net net;
    nn_params params;
    int k;                           /* outputs */
    int k_eig;
    diffusion_net_features features;
    int in_dim;
} patchnet_model;

/* Creates an untrained model with K outputs for the given input features.
 * Parameters are named "patchnet.*". Free with patchnet_model_free. */
neuv_status patchnet_model_create(patchnet_model *model, const patchnet_options *o, int in_dim, int k);
/* patchnet_model_create with the input size of o->features on this mesh. */
neuv_status patchnet_model_create_for_mesh(patchnet_model *model, const patchnet_options *o, const neuv_mesh *m,
                                           const operators *ops, int k);
void patchnet_model_free(patchnet_model *model);

/* Trains the model on one shape (Adam, L_cos + L_geo) until the plateau rule
 * or the iteration cap; reports progress (stage "patches").
 * Inputs:  m (cleaned), ops (its operators, with HKS for HKS input), o
 * Outputs: model trained in place; rep (may be NULL): k, iterations, losses, timings */
neuv_status patchnet_train(patchnet_model *model, const neuv_mesh *m, const operators *ops,
                           const patchnet_options *o, patchnet_report *rep);

/* Trains one model on several shapes at once (a category model, issue 8):
 * shared weights and K; each step takes the next shape in turn and its whole
 * L_cos + L_geo (each shape's own operators, features and geodesic sources,
 * shape i drawing its sources with seed + i); the plateau windows hold whole
 * rounds over the shapes. One shape is exactly patchnet_train.
 * Inputs:  meshes[n_shapes] (cleaned), ops[n_shapes], o
 * Outputs: model trained in place; rep (may be NULL) */
neuv_status patchnet_train_shapes(patchnet_model *model, const neuv_mesh *const *meshes,
                                  const operators *const *ops, int n_shapes, const patchnet_options *o,
                                  patchnet_report *rep);

/* Per-face argmax patch of a (trained) model on any mesh with operators.
 * Inputs:  model, m, ops
 * Outputs: face_label #F (caller allocates) in 0..k-1 */
neuv_status patchnet_infer(const patchnet_model *model, const neuv_mesh *m, const operators *ops, int *face_label);

/* As patchnet_infer, also returning the last hidden per-vertex features.
 * Outputs: face_label #F (may be NULL); vertex_features #V by *feature_dim
 *          (malloc'd, caller frees; may be NULL) */
neuv_status patchnet_infer_features(const patchnet_model *model, const neuv_mesh *m, const operators *ops,
                                    int *face_label, float **vertex_features, int *feature_dim);

#endif
