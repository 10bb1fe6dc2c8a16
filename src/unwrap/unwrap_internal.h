/* The state of one unwrap, shared by the pipeline (unwrap.c) and its report
 * (unwrap_report.c). */
#ifndef NEUV_UNWRAP_UNWRAP_INTERNAL_H
#define NEUV_UNWRAP_UNWRAP_INTERNAL_H

#include <stddef.h>

#include "neuv/neuv.h"
#include "atlas/pack.h"
#include "mesh/clean.h"
#include "mesh/hard_edges.h"
#include "mesh/mesh.h"
#include "metrics/uv_metrics.h"
#include "models/param_net.h"
#include "models/patchnet.h"
#include "unwrap/chart_source.h"

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
    /* The cleaned mesh's positions were multiplied by 2^pos_exp (exact) so
     * that its size is near 1 while the charts and maps are made: an extreme
     * scale (1e30, 1e-30) overflows or underflows the float networks. 0 for
     * ordinary sizes and for a saved model, made or applied (its surface and
     * chart frames are stored in the mesh's units); undone before the metrics
     * (unwrap_stage_pack). */
    int pos_exp;
    mesh_clean_report clean;
    int *face_chart;          /* #F */
    int n_charts;
    int patches;              /* K the segmentation used */
    int patch_iterations;
    int patch_reseeds;        /* emptied patches re-seeded in training */
    double patch_iters_per_second;
    int param_iterations;
    int param_face_points;    /* face points per training step (param_net_report.face_points) */
    double param_loss;
    int neural_charts;        /* charts the networks mapped injectively (source network or network+refined) */
    /* Provenance (n_charts each, chart_source.h): where each chart's final map
     * came from, the networks' own qce_mean on it before anything else touched
     * it (NaN: the networks made no map of it) and LSCM's qce_mean on the same
     * chart (NaN: not computed). */
    int *chart_source;
    double *chart_net_qce, *chart_lscm_qce;
    int refine_steps;         /* vertex refinement steps taken (flatten/uv_refine.h) */
    double refine_seconds;
    int refine_stopped;       /* charts whose refinement stopped early at the last injective map */
    int pack_splits;          /* charts cut so that the atlas packs better (atlas/pack_split.h) */
    int pack_split_trials;
    double pack_split_seconds; /* the trials' wall seconds, within the pack stage's */
    atlas_chart_transform *transforms; /* n_charts */
    /* A model's apply keeping a model of this mesh (unwrap_apply_options.keep_heads):
     * each chart's transform from its network's frame to its UVs before the fresh
     * packing, which then composes it into `transforms` (NULL: none). */
    atlas_chart_transform *frame_xf;
    atlas_pack_result pack;
    unwrap_repair *repairs;
    int n_repairs, cap_repairs;
    int repairs_lost;         /* a note did not fit in memory: the call that made r fails with NEUV_ERR_NOMEM */
    double seconds[STAGE_COUNT];
    double total_seconds;
    uv_metrics metrics;
    int cache_hit;

    /* Required seams (mesh/seam_cut.h; opts.seam_angle, opts.seam_edges): the
     * mesh is cut open along them from the charts stage to the metrics. */
    int seam_edges;           /* required seam edges of the cleaned mesh */
    int seam_edges_angle;     /* of which above opts.seam_angle */
    int seam_unmatched;       /* pairs of opts.seam_edges that are no edge of the mesh */
    hard_edge_report hard;    /* the file's hard and material edges (opts.hard_edges) */
    int hard_edges_not_kept;  /* of which left out: a model made the charts */
    int seam_crossed;         /* seam edges the final atlas joins (same UVs on both sides) */
    int *seam_pair;           /* seam_edges by 2: their vertices in the cleaned mesh */
    int *seam_origin;         /* while cut: the cleaned mesh's vertex each vertex copies; else NULL */
    int seam_nv;              /* the cleaned mesh's vertex count */

    /* The file's polygons (charts/polygon_charts.c): each face's polygon
     * (a polygon's triangles are consecutive faces), NULL when the input
     * gave only triangles. */
    int *face_polygon;        /* #F or NULL */
    int polygons;             /* polygons of more than 3 corners in the input */
    int polygons_split;       /* of which the charts still split (written back as their triangles) */

    /* Kept for --save-model (NULL / 0 otherwise). */
    int *chart_net;           /* n_charts: network chart whose map chart c uses, -1 for a classic map */
    int *chart_mirrored;      /* n_charts: 1 when the injectivity check mirrored the chart before packing */
    int *chart_tried;         /* n_charts: network chart whose map was tried on chart c, kept or not
                                 (chart_net, or the one that folded there), -1 none */
    int *face_label;          /* #F PatchNet argmax on this mesh */
    patchnet_model *patchnet;
    param_net_model *param;

    /* Set when the atlas came from a saved model (unwrap_apply.h). */
    struct {
        int used;                 /* 1: --model or trained on a simplified copy */
        int trained_on_copy;      /* 1: --train-faces: trained on a simplified copy of the input */
        int train_faces;          /* faces of the copy the model was trained on */
        double train_seconds;     /* the whole training unwrap of the copy */
        double copy_simplify_seconds;            /* making the copy */
        double copy_seconds[STAGE_COUNT];        /* the copy's training unwrap, stage by stage */
        int network_charts;       /* charts mapped by MLP_f */
        int transferred_charts;   /* charts whose UVs came from the source surface by closest point */
        int empty_charts;         /* source charts that got no face on this mesh */
        int merged_fragments;     /* pieces of a transferred chart merged into a neighbour */
        int fragment_charts;      /* charts that are a second or further piece of a source chart */
        int settled_faces;        /* border faces given to the neighbour whose source map takes them unflipped */
        int shrunk_charts;        /* charts shrunk about their centroid to end an overlap */
        int moved_charts;         /* charts not where the source atlas put them (shrunk or moved) */
        int pulled_vertices;      /* corners past a source seam pulled toward their chart's island */
        int refinement_carried;   /* 1: the source's refinement of the networks' map was carried over */
        int repacked;             /* --train-faces only: overlaps survived the shrinking, the atlas was packed afresh */
        int heads_solved;         /* --train-faces only: network charts whose map is their head solved on this mesh */
        double surface_distance;  /* largest face-centroid distance to the source surface / its bbox diagonal */
        double inference_seconds; /* from the cleaned mesh to the packed atlas (no metrics) */
        double label_agreement;   /* -1, or PatchNet inference vs stored labels (--check-inference) */
        int category;             /* 1: a category model unwrapped this (unseen) shape */
        int finetune;             /* category: training steps from the model's weights (0: inference only) */
        int shared_layer;         /* category inference: 1, the shared output layer maps every chart; 0, a
                                     head per chart solved on this shape (param_net_infer) */
        /* Surface model, between the charts and param stages only (NULL otherwise): */
        int *source_chart;        /* n_charts: the model's chart each chart was carried from */
        int *vertex_source_chart; /* #V: the model's chart under each vertex (closest point) */
    } model;
};

/* Per chart of the final atlas: faces, 3D area and area-weighted qce
 * (docs/metrics.md; faces of zero area left out), from r->mesh's UVs.
 * NULL when memory runs out; caller frees. */
typedef struct unwrap_chart_figures { int faces; double area, qce_num, qce_den; } unwrap_chart_figures;
unwrap_chart_figures *unwrap_chart_figures_compute(const struct neuv_unwrap_result *r);

/* Charts and 3D area per source, the share of area the networks mapped
 * injectively, their own qce_mean there and LSCM's on the same charts (NaN
 * when not measured), from r's provenance arrays (which must be set). */
typedef struct unwrap_provenance {
    int count[CHART_SOURCE_COUNT];
    double area[CHART_SOURCE_COUNT];
    double total_area, network_area_fraction, network_qce_mean, lscm_qce_mean_same_charts;
} unwrap_provenance;
void unwrap_provenance_compute(const struct neuv_unwrap_result *r, const unwrap_chart_figures *cf,
                               unwrap_provenance *out);

/* "11 network+refined, 3 lscm_after_fold": how many charts each source made. */
void unwrap_source_summary(const struct neuv_unwrap_result *r, char *buf, size_t n);

/* Appends a repair note (formatted). When memory runs out the note is lost
 * and r->repairs_lost set: the call making r then fails with NEUV_ERR_NOMEM
 * (unwrap_train, unwrap_with_category, unwrap_apply and unwrap_budgeted look). */
void unwrap_add_repair(struct neuv_unwrap_result *r, int chart, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* One chart during the repair stage: its own mesh and per-vertex UVs. */
/* How many times a network chart whose map crosses its own boundary is
 * halved before its pieces go to LSCM (training, and a simplified copy's
 * model applied to the full mesh). */
#define NET_SPLIT_DEPTH 3
/* A piece of a chart the networks folded keeps the map of an output layer
 * solved on it only when that map's qce_mean is at most this many times
 * LSCM's on the piece (bench/RESULTS.md, "Folded charts split"). */
#define SOLVED_HEAD_MAX_QCE_RATIO 1.10

typedef struct chart_piece {
    neuv_mesh *sub;
    int *vmap, *fmap;
    double *uv;      /* #CV by 2 */
    int from_split;  /* made by a split: flattened by the classic method */
    int net_split;   /* made by splitting a network chart whose map crossed its own
                        boundary only: the networks' map is checked again on it */
    int net_head;    /* with net_split: the network chart whose map it holds */
    int net_depth;   /* with net_split: splits since that network chart */
    int net_solved;  /* with net_split: made by splitting a network chart whose map
                        folded: the networks' output layer is solved on it anew */
    int net;         /* network chart whose map is kept, -1 otherwise */
    int tried;       /* network chart whose map was tried on it, kept or not, -1 none */
    int mirrored;    /* chart_uv_check mirrored it */
    chart_source source;   /* where its final map came from */
    double net_qce;        /* the networks' own qce_mean on it (NaN: none) */
    double lscm_qce;       /* LSCM's qce_mean on it (NaN: not computed) */
} chart_piece;

/* LSCM's qce_mean on the piece's chart into p->lscm_qce (left NaN when the
 * solve fails), for the report's comparison of the networks' map with LSCM
 * on the same charts. Returns NEUV_OK or NEUV_ERR_NOMEM. */
neuv_status unwrap_piece_lscm_qce(chart_piece *p);

/* The provenance arrays of r (chart_source, chart_net_qce, chart_lscm_qce)
 * from the pieces. Returns NEUV_OK or NEUV_ERR_NOMEM. */
neuv_status unwrap_keep_provenance(struct neuv_unwrap_result *r, const chart_piece *pieces);

void unwrap_piece_clear(chart_piece *p);
/* Builds chart `id` of m as a piece with zeroed UVs (keeps from_split and the net_split fields). */
neuv_status unwrap_piece_build(const neuv_mesh *m, const int *face_chart, int id, chart_piece *p);
/* Vertex refinement of a piece whose UVs pass the injectivity check,
 * counter-clockwise: first LSCM anchored to its map (flatten/lscm.h, kept
 * when injective), then `steps` Adam steps of flatten/uv_refine.h, checked
 * every 10; the piece keeps its last map that passes. steps = 0: nothing.
 * Returns NEUV_OK or NEUV_ERR_NOMEM. */
struct uv_refine_report;
neuv_status unwrap_refine_piece(chart_piece *p, int steps, struct uv_refine_report *rep);
/* Per-corner UVs of the whole mesh from the charts' per-vertex UVs: a mesh
 * vertex gets one UV per chart it belongs to (split at seams). */
neuv_status unwrap_assemble_uvs(neuv_mesh *m, const chart_piece *pieces, int n_charts);
/* The metrics of m as `neuv eval` reads the written file (positions welded). */
neuv_status unwrap_metrics(const neuv_mesh *m, uv_metrics *out);

/* A result with opts (NULL: defaults) checked (resolution, padding) and
 * the thread count set. NEUV_ERR_INPUT with the option at fault. */
neuv_status unwrap_result_new(const neuv_unwrap_options *opts, struct neuv_unwrap_result **out);
/* A deep copy of r without its networks (chart_net, chart_mirrored,
 * face_label, patchnet and param left NULL), to run a stage again from. */
neuv_status unwrap_result_clone(const struct neuv_unwrap_result *r, struct neuv_unwrap_result **out);

/* Where a run's charts and maps come from, for the stages below:
 * - model NULL: trained on this mesh (PatchNet, then the parameterization
 *   networks or the classic method of opts);
 * - a category model (model->category): its PatchNet and networks by
 *   inference, or with finetune > 0 that many training steps from its weights;
 * - a surface model with apply set: the model's charts and maps carried to
 *   this triangulation (unwrap_apply.h).
 * keep_model: also keep what a saved model needs (chart_net,
 * chart_mirrored, face_label, patchnet, param); training only. */
struct unwrap_model;
struct unwrap_apply_options;
typedef struct unwrap_plan {
    const struct unwrap_model *model;
    int keep_model;
    int finetune;
    const struct unwrap_apply_options *apply;
} unwrap_plan;

/* The stages of the pipeline, in order, on one result (from
 * unwrap_result_new), whatever the plan: each timed into r->seconds and
 * r->total_seconds (unwrap_stage_time), each stopping with
 * NEUV_ERR_CANCELLED when the progress callback asks, and with
 * NEUV_ERR_NOMEM when a repair note was lost.
 * charts: cleans a copy of `in` into r->mesh; then charts (training:
 *   operators and PatchNet; category: the model's PatchNet by inference;
 *   surface model: carried by closest point); *features (#F by
 *   *feature_dim DiffusionNet features, caller frees; NULL for a surface
 *   model) for the next stage.
 * param: the networks' map (or the classic method, or the model's map
 *   carried), repair, refinement; per-corner chart UVs in r->mesh.
 * pack: charts placed (training and category: split where they pack badly,
 *   then packed; surface model: kept where the source's atlas has them),
 *   then the metrics. */
neuv_status unwrap_stage_charts(struct neuv_unwrap_result *r, const neuv_mesh *in, const unwrap_plan *plan,
                                float **features, int *feature_dim);
neuv_status unwrap_stage_param(struct neuv_unwrap_result *r, const unwrap_plan *plan, const float *features,
                               int feature_dim);
neuv_status unwrap_stage_pack(struct neuv_unwrap_result *r, const unwrap_plan *plan);
/* The three stages one after the other. */
neuv_status unwrap_run_stages(struct neuv_unwrap_result *r, const neuv_mesh *in, const unwrap_plan *plan);
/* Adds the seconds since t0 to stage `stage` and updates r->total_seconds
 * (the sum of the stages): the one clock of every path. */
void unwrap_stage_time(struct neuv_unwrap_result *r, int stage, double t0);
/* A copy of `in` without UVs, cleaned (mesh/clean.h; report may be NULL),
 * refused with NEUV_ERR_INPUT when no face of non-zero area is left.
 * face_origin (may be NULL): the face of `in` each cleaned face is (#F of
 * the copy; the caller frees). */
neuv_status unwrap_clean_copy(const neuv_mesh *in, neuv_mesh **out, mesh_clean_report *report, int **face_origin);

/* The pipeline; keep_model: also keep the networks and per-chart maps
 * (chart_net, chart_mirrored, face_label, patchnet, param) for a saved model. */
neuv_status unwrap_train(const neuv_mesh *mesh, const neuv_unwrap_options *opts, int keep_model,
                         neuv_unwrap_result **out);

/* The pipeline on a shape a category model (unwrap_model.h, category = 1)
 * was not trained on: PatchNet charts and the networks' map by inference
 * (param_net_infer: a head per chart solved on this shape, or with
 * shared_layer the model's shared output layer), or with finetune > 0 that
 * many training steps from the model's weights; then the same repair,
 * refinement, packing and metrics.
 * Preset, seed, refinement, resolution and padding come from the model;
 * threads, use_cache and allow_overlaps from opts (may be NULL).
 * keep_model (with finetune > 0): the result keeps the fine-tuned networks
 * and the charts' maps, for unwrap_model_from_result (a surface model of
 * this shape); the atlas is the same as without. */
neuv_status unwrap_with_category(const neuv_mesh *mesh, const struct unwrap_model *category,
                                 const neuv_unwrap_options *opts, int finetune, int shared_layer, int keep_model,
                                 neuv_unwrap_result **out);

#endif
