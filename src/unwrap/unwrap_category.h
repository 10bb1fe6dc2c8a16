/* Category models (`neuv train -o M.neuv IN...`, issue 8): PatchNet and the
 * parameterization networks trained over many shapes at once, so that an
 * unseen shape of the category is unwrapped by inference
 * (`neuv unwrap --model M.neuv NEW`, unwrap_with_category).
 *
 * Training:
 *   1. every shape is cleaned and gets its operators (cached);
 *   2. one PatchNet with a fixed K (--charts, or 8 when auto) trains on all
 *      shapes, one shape per step in turn (patchnet_train_shapes);
 *   3. each shape's charts come from that network as at inference
 *      (patchnet_charts_from_model: argmax, disks, and with auto charts the
 *      split / merge loop), with its own DiffusionNet features;
 *   4. one pair of MLPs trains on every chart of every shape at once (the
 *      shapes side by side as one mesh with many components), ψ pooled from
 *      each shape's own features; the ψ standardization over all training
 *      charts is kept in the model, so an unseen shape's charts get codes on
 *      the same scale (param_net_infer). ψ gets Gaussian noise of 0.5 column
 *      standard deviations every step (param_net_options.psi_noise), and the
 *      networks take twice the preset's steps with no plateau stop.
 * The model holds no surface, charts or packing: an unseen shape gets its
 * own charts, map, repairs and packing. */
#ifndef NEUV_UNWRAP_UNWRAP_CATEGORY_H
#define NEUV_UNWRAP_UNWRAP_CATEGORY_H

#include "neuv/neuv.h"
#include "unwrap/unwrap_model.h"

typedef struct category_train_report {
    int shapes;
    int faces;                /* over all shapes, after cleaning */
    int charts;               /* over all shapes */
    int patch_k;
    int patch_iterations;
    double patch_loss;        /* last step (one shape's L_cos + L_geo) */
    int param_iterations;
    double param_loss;
    double seconds_operators, seconds_patches, seconds_charts, seconds_param, seconds;
} category_train_report;

/* Default PatchNet steps for n shapes: every shape seen about 40 times,
 * never fewer than one shape's cap (300). */
int category_default_patch_iters(int n_shapes);

/* Trains a category model.
 * Inputs:  meshes[n] (n >= 1; cleaned on copies), opts: method must be
 *          neural; preset, charts (0: auto after a K = 8 network), seed,
 *          iters (parameterization steps; 0: twice the preset's), refine,
 *          resolution, padding and max_distortion are stored in the model
 *          and used when it is applied; threads and use_cache apply here.
 *          patch_iters: PatchNet steps (0: category_default_patch_iters).
 * Outputs: *out (free with unwrap_model_free), rep (may be NULL)
 * Returns NEUV_OK, NEUV_ERR_INPUT (no shapes, a shape with no faces or zero
 * area, another method), NEUV_ERR_NOMEM or NEUV_ERR_INTERNAL. */
neuv_status unwrap_category_train(const neuv_mesh *const *meshes, int n, const neuv_unwrap_options *opts,
                                  int patch_iters, unwrap_model **out, category_train_report *rep);

#endif
