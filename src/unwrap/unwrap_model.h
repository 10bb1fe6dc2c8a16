/* A saved unwrap (`neuv unwrap --save-model M.neuv`): everything needed to
 * reproduce the atlas on another triangulation of the same surface, in one
 * checkpoint file (nn/checkpoint.h: magic, version, JSON header, named
 * CRC'd float32 tensors).
 *
 * Header (JSON, flat keys): format "neuv-unwrap-model", model_version,
 * method, preset, seed, resolution, padding, charts, source sizes, and the
 * network configurations (param_* for MLP_f / MLP_f⁻¹, patchnet_* for
 * PatchNet). Tensors:
 *   source.pos       #V by 6    positions, float64 stored as bit pairs (exact)
 *   source.tri       #F by 3    faces (integers, exact below 2^24)
 *   source.uv        #UV by 4   final packed atlas UVs, float64 bit pairs
 *   source.tri_uv    #F by 3
 *   source.chart     #F by 1    final chart of every source face
 *   source.label     #F by 1    PatchNet argmax of every source face (when kept)
 *   source.norm      1 by 10    bbox centre (3), bbox diagonal, total area, float64 bit pairs
 *   charts.xf        C by 8     packing similarity (scale, angle, tx, ty), float64 bit pairs
 *   charts.map       C by 2     network chart whose MLP_f map the chart uses (-1: classic map,
 *                               transferred by closest point), mirrored flag
 *   param.psi        N by D     per-network-chart code ψ
 *   param.psi_norm   2 by 2D    ψ standardization (shift, mul), float64 bit pairs (newer files)
 *   param.frame      N by 26    centre (3), scale, rotation (9), float64 bit pairs
 *   param.mirror     N by 1
 *   f.*, g.*                    MLP_f and MLP_f⁻¹ weights (param_mlp.h names)
 *   patchnet.*                  PatchNet (DiffusionNet) weights
 * A category model (`neuv train`, unwrap_category.h) has "kind": "category"
 * in its header (a surface model "surface", or no kind in older files), the
 * keys category_shapes, charts_auto and max_distortion instead of the charts
 * and source sizes, and only param.psi_norm, f.*, g.* and patchnet.*: no
 * surface, charts or packing, since every shape it meets gets its own.
 * Doubles are stored bit for bit (two float32 slots holding the 8 bytes), so
 * a loaded model reproduces the saved atlas exactly. */
#ifndef NEUV_UNWRAP_UNWRAP_MODEL_H
#define NEUV_UNWRAP_UNWRAP_MODEL_H

#include <stdint.h>

#include "neuv/neuv.h"
#include "atlas/pack.h"
#include "mesh/mesh.h"
#include "models/param_net.h"
#include "models/patchnet.h"

#define UNWRAP_MODEL_VERSION 1

typedef struct unwrap_model {
    int category;                /* 1: a category model (unwrap_category.h): no source surface, no charts */
    int category_shapes;         /* category: shapes it was trained on */
    int charts_auto;             /* category: 1 when charts split and merge by distortion after the argmax */
    double max_distortion;       /* category: the split threshold (neuv_unwrap_options) */
    neuv_method method;
    neuv_preset preset;
    uint64_t seed;
    int resolution, padding;
    int refine;                  /* vertex refinement steps after the network (0: none; absent in older files) */
    neuv_mesh *source;           /* cleaned source: positions, faces, packed per-corner UVs */
    int n_charts;
    int *face_chart;             /* #F of source */
    int *face_label;             /* #F of source, or NULL */
    double norm[5];              /* bbox centre (3), bbox diagonal, total area of the source */
    atlas_chart_transform *xf;   /* n_charts */
    int *chart_net;              /* n_charts: network chart id or -1 */
    int *chart_mirrored;         /* n_charts */
    int *chart_tried;            /* n_charts: network chart whose map was tried on it, kept or not (-1
                                    none); in memory only (models read from a file: NULL) */
    param_net_model *param;      /* NULL for lscm / harmonic models */
    patchnet_model *patchnet;    /* NULL when not saved */
} unwrap_model;

struct neuv_unwrap_result;

/* Builds a model from an unwrap run with keep_model (unwrap_train). The
 * result's networks are moved into the model (the result keeps its atlas).
 * Outputs: *out (free with unwrap_model_free).
 * Returns NEUV_OK, NEUV_ERR_INPUT (the run kept no model) or NEUV_ERR_NOMEM. */
neuv_status unwrap_model_from_result(struct neuv_unwrap_result *r, unwrap_model **out);

/* Writes the model atomically. Returns NEUV_OK, NEUV_ERR_IO or NEUV_ERR_NOMEM. */
neuv_status unwrap_model_save(const unwrap_model *model, const char *path);

/* Reads and validates a model file: checkpoint structure and CRCs, header
 * keys and ranges, every tensor's presence and shape, index ranges (faces,
 * charts, network ids). Any defect: NEUV_ERR_INPUT with a one-line message;
 * unreadable file: NEUV_ERR_IO. */
neuv_status unwrap_model_load(const char *path, unwrap_model **out);
/* The same on a model file's bytes in memory (the fuzzing entry point). */
neuv_status unwrap_model_parse(const void *bytes, size_t len, unwrap_model **out);

void unwrap_model_free(unwrap_model *model);

#endif
