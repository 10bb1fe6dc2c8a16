/* Applying a saved unwrap model to another triangulation of the same
 * surface (`neuv unwrap --model M.neuv IN`), and training on a simplified
 * copy of a large mesh (`--train-faces`).
 *
 * Charts on the new mesh come from the stored source charts by closest
 * point (each face takes the chart of the source face nearest its
 * centroid; pieces cut off from their chart are merged into the neighbour
 * sharing the longest border; then border faces that their chart's source
 * map turns over go to a neighbour whose map does not), not from PatchNet
 * inference: closest-point
 * transfer reproduces the source charts up to the border zigzag whatever
 * the triangulation, while argmax labels of a re-run network then need the
 * label-to-chart cutting and splitting to come out the same (measured in
 * bench/RESULTS.md; --check-inference reports PatchNet's agreement).
 *
 * UVs, in the source's atlas frame (each chart placed by its stored packing
 * similarity, so the layout is the source's and a texture painted on the
 * source stays valid):
 * - a chart the source mapped with MLP_f is evaluated by MLP_f at the new
 *   vertices (param_net_apply); a vertex past the source chart's seam (its
 *   closest source point lies in another chart: a triangulation that shares
 *   no edge with the source cannot follow the seam) takes MLP_f at its
 *   closest point of the chart, continued by the source atlas's linear
 *   extension there, since the networks never learnt what lies past their
 *   chart. When the source refined the networks' map (--refine with
 *   --save-model), the difference the refinement made is carried over,
 *   interpolated at the closest point of the chart, unless the options ask
 *   to refine on this mesh (training on a simplified copy does);
 * - a chart with a classic map (lscm/harmonic models, and neural charts the
 *   source repaired) takes the source's UVs at the closest point of that
 *   chart, the face's affine map extended past its border.
 *
 * A network chart whose map at the new vertices lies farther from the
 * source atlas (the same map at the source's vertices) than the packing's
 * gutter, on average over the chart's own vertices, takes the source atlas.
 *
 * Guarantee: every chart passes chart_uv_check (positive areas, simple
 * boundary: injective); a folded chart is first relaxed locally (the folded
 * faces' inner vertices), then tried with its corners past the seam pulled
 * onto the source island, then (network charts) with the source atlas,
 * else re-flattened by LSCM anchored to the map (harmonic if LSCM folds
 * too, split if both do). docs/transfer.md has the whole sequence. Then the whole atlas is
 * rasterized (uv_overlap.h). Corners past a seam reach into the packing's
 * gutter and, on a coarse mesh, onto the next island: in a chart that
 * overlaps another or leaves [0,1]^2 they are pulled toward their chart's
 * island (to half the gutter, then onto the island's border), relaxed if
 * that folds. Only what this cannot mend moves a chart (shrunk about its
 * centroid, moved inside the square), and the report lists each chart
 * moved and by how much; the atlas is never packed afresh. Every repair
 * is reported. */
#ifndef NEUV_UNWRAP_UNWRAP_APPLY_H
#define NEUV_UNWRAP_UNWRAP_APPLY_H

#include "neuv/neuv.h"
#include "unwrap/unwrap_model.h"

typedef struct unwrap_apply_options {
    int threads;          /* > 0: thread count */
    int use_cache;        /* operators cache (only --check-inference computes operators) */
    int check_inference;  /* 1: also run PatchNet on the mesh and report its label agreement */
    int refine_on_mesh;   /* 1: the source is a simplified copy of this mesh (--train-faces): the
                           * networks' map is refined here, and a chart is never replaced by the
                           * copy's atlas (quality on this mesh matters, not the copy's layout);
                           * 0: carry the source's refinement over, so the atlas is the source's */
    int lscm_baseline;    /* 1: a baseline, not the model's map: each chart flattened by LSCM on this
                           * mesh and placed by the least-squares similarity onto the model's map */
    double texels_per_unit; /* with refine_on_mesh (the fresh packing): as neuv_unwrap_options' (0: off) */
    int keep_model;       /* with refine_on_mesh: a model of this mesh will be made of the result,
                           * which then keeps which network chart maps each of its charts */
    param_net_model *keep_heads; /* with keep_model: the model's own networks (the same as
                                  * model->param; NULL for a classic method), to which each head
                                  * solved on this mesh is added as a chart of its own */
} unwrap_apply_options;

/* Inputs:  mesh  any triangulation of the model's source surface (cleaned on a copy)
 *          model a loaded or freshly trained model
 *          o     options (NULL: defaults)
 * Outputs: *out  the result (neuv_unwrap_mesh, report JSON with a "model" section)
 * Returns NEUV_OK, NEUV_ERR_INPUT (empty mesh), NEUV_ERR_NOMEM or NEUV_ERR_INTERNAL. */
neuv_status unwrap_apply(const neuv_mesh *mesh, const unwrap_model *model, const unwrap_apply_options *o,
                         neuv_unwrap_result **out);

/* The bodies of the pipeline's stages (unwrap_internal.h unwrap_run_stages)
 * for a surface model carried to r->mesh, already cleaned:
 * charts: each face takes the model's chart by closest point, fragments
 *   merged, border faces settled (r->face_chart, r->n_charts); with
 *   o->check_inference also PatchNet's agreement with the stored labels.
 * param: each chart's UVs in the source's atlas frame (the networks at the
 *   new vertices, or the source's map), checked and repaired; then corners
 *   past a seam pulled onto their island; per-corner UVs in r->mesh and
 *   r->transforms (the source's placement of each chart).
 * place: the charts kept where the source's atlas has them: moved inside
 *   the square, overlaps shrunk, then moved to free space (repacked afresh
 *   only with o->refine_on_mesh, where the layout is a copy's).
 * Each returns NEUV_OK, NEUV_ERR_NOMEM or NEUV_ERR_INTERNAL, and times itself
 * into r->seconds. */
struct neuv_unwrap_result;
neuv_status unwrap_apply_charts(struct neuv_unwrap_result *r, const unwrap_model *model, const unwrap_apply_options *o);
neuv_status unwrap_apply_param(struct neuv_unwrap_result *r, const unwrap_model *model, const unwrap_apply_options *o);
neuv_status unwrap_apply_place(struct neuv_unwrap_result *r, const unwrap_apply_options *o);

/* The pipeline with a face budget: when mesh has more than train_faces faces
 * (train_faces > 0), trains on a simplified copy (mesh_simplify) and applies
 * the model to the full mesh; otherwise runs unwrap_train. With model_out
 * (may be NULL) the trained model is handed over (for --save-model).
 * Returns what unwrap_train / unwrap_apply return. */
neuv_status unwrap_budgeted(const neuv_mesh *mesh, const neuv_unwrap_options *opts, int train_faces,
                            unwrap_model **model_out, neuv_unwrap_result **out);

#endif
