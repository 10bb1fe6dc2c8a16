/* The surface parameterization networks of Pokhariya et al. 2022
 * ("Discretization-Agnostic Deep Self-Supervised 3D Surface Parameterization",
 * section 3.2; SPEC.md section 1.3): one pair of MLPs, MLP_f(x, ψ) -> uv and
 * MLP_f⁻¹(uv, ψ) -> x, conditioned on a per-chart code ψ, flattens every chart
 * of a shape; the charts are trained together (every step mixes all charts).
 *
 * Loss (param_losses.h): λ1 L_cycle + λ2 L_iso + λ3 L_angle + λ4 L_area.
 *
 * Chart normalization: a chart is centred at its area-weighted centroid and
 * scaled by s so that its geodesic radius (largest heat-method distance from
 * the vertex nearest the centroid) is `radius` (0.6): an isometric map then
 * stays inside tanh's range with margin, and σ = 0.2 means the same share of
 * every chart. The chart is also turned into its own frame (z along its mean
 * normal, x along its principal axis) so that all charts look alike to the
 * networks. normalized = R (x − centre) s; UVs come back divided by s, so they
 * are in the mesh's length units (what a packer wants).
 *
 * ψ: pooled (default) = [mean, max] over the chart's vertices of the input
 * per-vertex features (#V by D, e.g. DiffusionNet's), 2D numbers; with no
 * features, [centroid, mean unit normal] of the chart (centroid relative to the
 * mesh's bounding box, 6 numbers). Every ψ column is standardized (zero mean,
 * unit variance over the rows, then rows scaled by 1/sqrt(dim)): raw DiffusionNet
 * features saturate the output and collapse the map. It enters the first layer linearly, so a
 * learned projection before it would only factor that layer's ψ block and is
 * left out. Per-vertex (the paper's ablation): each point's own features
 * (barycentric inside faces; with no features the point's position relative to
 * the bounding box and its interpolated vertex normal). */
#ifndef NEUV_MODELS_PARAM_NET_H
#define NEUV_MODELS_PARAM_NET_H

#include <stdint.h>

#include "mesh/mesh.h"
#include "models/param_mlp.h"
#include "models/param_output_solve.h"
#include "nn/nn.h"

typedef enum param_preset { PARAM_PRESET_FAST = 0, PARAM_PRESET_PAPER = 1 } param_preset;
typedef enum param_psi_mode { PARAM_PSI_POOLED = 0, PARAM_PSI_PER_VERTEX = 1 } param_psi_mode;

typedef struct param_net_model param_net_model;

typedef struct param_net_options {
    int width, depth;       /* hidden width and linear layers of each MLP */
    float leaky_slope;      /* 0.01 */
    float lr;               /* Adam learning rate, 1e-3 */
    double lr_final;        /* > 0: cosine decay of the rate to lr x lr_final at `iters` (neuv); 0: constant */
    double lambda[4];       /* cycle, iso, angle, area: [1, 1, 0.001, 0.001] */
    /* fast-preset deviation (documented in bench/RESULTS.md): after
     * `warmup_iters`, λ_angle and λ_area become lambda_late[0..1] (0: unchanged). */
    int warmup_iters;
    double lambda_late[2];
    /* neuv extension (param_losses.h, bench/RESULTS.md): fold barrier weight
     * and area ratio; 0 weight: off. Zero on a map without folds. */
    double lambda_fold, fold_eps;
    /* neuv extensions for a map that stands on its own (bench/RESULTS.md,
     * "The networks' own map"):
     *   warm_iters   the first steps also pull MLP_f's map at the chart
     *                vertices towards the chart's LSCM map, laid in the
     *                chart's frame (similarity-aligned to the projection on
     *                the tangent plane, area of the chart), with weight
     *                lambda_warm (0 iterations: off); the target is only a
     *                start: the self-supervised losses train on alone after
     *   solve_steps  after Adam, Gauss-Newton steps on MLP_f's output layer
     *                for the conformal energy of its map over the charts'
     *                triangles, anchored with weight solve_anchor, then a
     *                least-squares refit of MLP_f⁻¹'s output layer
     *                (param_output_solve.h; 0: off) */
    int warm_iters;
    double lambda_warm;
    int solve_steps;
    double solve_anchor;
    /* With solve_steps: also one output layer per chart (param_output_solve.h),
     * used for this mesh's charts (and a saved model's); 0: the shared one only. */
    int chart_heads;
    /* The heads' solve with a fold barrier, then steps on the scale-free
     * conformal energy (param_solve_data; 0: off). */
    double solve_fold, solve_fold_eps;
    int solve_mips;
    /* With chart_heads and warm_iters: a chart whose head still folds after
     * its solve is solved again from the head fitted by least squares to its
     * LSCM map (the warm-start target) over MLP_f's features
     * (param_solve_data.fit_uv; 0: off). */
    int solve_refit;
    /* Fourier directions the heads also read (param_mlp.h; 0: none). */
    int head_fourier;
    /* param_net_infer builds the conformal targets for solving heads. */
    int infer_heads;
    /* With solve_fold: the barrier also holds on the faces split in four at
     * their edge midpoints (param_solve_subdivide; 0: the faces only). */
    int solve_subdivide;
    /* With solve_subdivide: the share of each face's conformal energy weight
     * that its four sub-faces carry (param_solve_subdivide), so that the
     * solved map is judged between the vertices too (0: barrier only). */
    double solve_subdivide_energy;
    /* Chart vertices per output-layer feature (param_head_size / 2) from
     * which a chart's sub-faces carry the barrier only: its vertices already
     * outnumber the weights that could bend the map between them, and its
     * solve costs a fifth of the rows (0: every chart shares its energy). */
    double solve_subdivide_dense;
    double sigma;           /* L_iso pair radius in normalized units, 0.2 */
    double radius;          /* normalized geodesic radius of every chart, 0.6 */
    int iters;              /* iteration cap */
    int min_iters;          /* no plateau stop before this */
    int plateau_window;     /* iterations per window of the plateau test */
    double plateau_tol;     /* stop when a window's mean loss improves by less than this share */
    int face_points;        /* random points inside faces per step (L_cycle); fewer, down to an eighth, on charts of fewer vertices in all */
    int iso_pairs;          /* geodesic pairs per step (all when there are fewer) */
    /* Geodesic pairs kept for L_iso over all charts, so that memory is linear
     * in the mesh: each chart's pairs come from budget / (chart vertices in
     * all) source vertices (at least 64, drawn with the seed); a chart with no
     * more vertices than that uses every vertex, all pairs under sigma as the
     * paper has them. 0: every vertex of every chart (quadratic). */
    long iso_pair_budget;
    param_psi_mode psi_mode;
    uint64_t seed;
    int threads;            /* nn_set_threads(threads) before training (0: OpenMP's count as is) */
    int keep_model;         /* 1: the trained model is returned in report->model */
    /* Fine-tuning: start from this model's weights and ψ standardization
     * (same width, depth and ψ size) instead of a random initialization. */
    const param_net_model *init;
    /* Category training (pooled ψ): every step adds Gaussian noise of this
     * many column standard deviations to every chart's standardized ψ, so
     * the networks learn maps that vary smoothly with ψ instead of one map
     * per training code (0: off, per-shape training). */
    double psi_noise;
} param_net_options;

typedef struct param_net_report {
    int iters;              /* iterations run */
    int face_points;        /* face points drawn per step (param_net_options.face_points, fewer on small charts) */
    int stopped_on_plateau;
    long parameters;        /* per MLP (both have nearly the same count; this is MLP_f) */
    double loss, loss_cycle, loss_iso, loss_angle, loss_area; /* last step, unweighted terms */
    double loss_barrier;    /* last step, unweighted fold barrier (0 when inactive) */
    double loss_warm;       /* last warm-start step, unweighted distance to the LSCM target (0: none) */
    double solve_energy_before, solve_energy_after; /* conformal energy around the output-layer solve */
    int solve_steps;        /* Gauss-Newton steps taken (shared output layer) */
    int heads_improved;     /* charts whose own output layer improved on the shared one */
    int heads_refit;        /* charts whose head was solved from its fit to the LSCM map (solve_refit) */
    double setup_seconds, train_seconds, seconds;
    long pairs;             /* geodesic pairs under σ over all charts */
    int flipped;            /* faces whose UV orientation disagrees with their chart's */
    double cycle_rms;       /* RMS of ‖MLP_f⁻¹(MLP_f(x)) − x‖ at the vertices, normalized units */
    param_net_model *model; /* when keep_model: the trained model (free with param_net_model_free) */
} param_net_report;

/* Fills o for a preset: PARAM_PRESET_FAST (the default: the smallest networks
 * that reach the quality bar, see bench/RESULTS.md) or PARAM_PRESET_PAPER (8
 * layers, width 464: about 1.3·10^6 parameters per MLP, Adam 1e-3, the paper's
 * loss weights). */
void param_net_default_options(param_net_options *o, param_preset preset);

/* The chart size (vertices) from which heads solved for network f judge
 * their map at the vertices alone (o->solve_subdivide_dense times f's
 * output-layer features; 0: no such size). */
int param_net_dense_vertices(const param_mlp *f, const param_net_options *o);

/* Flattens every chart with one jointly trained pair of networks.
 *
 * Inputs:
 *   m                mesh, #V by 3, #F by 3
 *   face_chart       #F chart id per face, 0..n_charts-1, each chart a disk
 *   vertex_features  #V by feature_dim (row-major float32), or NULL (see ψ above)
 *   o                options (NULL: fast preset)
 * Outputs:
 *   corner_uv        #F by 3 by 2: the UV of each face corner, each chart in
 *                    its own frame, in mesh length units, counter-clockwise,
 *                    scaled so that its UV area is its 3D area
 *   rep              may be NULL
 * Returns NEUV_OK, NEUV_ERR_INPUT (bad charts or options), NEUV_ERR_NOMEM or
 * NEUV_ERR_INTERNAL (a geodesic solve or a training step failed). */
neuv_status param_net_flatten(const neuv_mesh *m, const int *face_chart, int n_charts,
                              const float *vertex_features, int feature_dim,
                              const param_net_options *o, double *corner_uv, param_net_report *rep);

/* A trained pair of networks and what is needed to apply it again. */
struct param_net_model {
    nn_params params;       /* every weight: "f.*" (MLP_f) and "g.*" (MLP_f⁻¹) */
    param_mlp f, g;
    param_psi_mode psi_mode;
    int psi_dim, n_charts;
    float *psi;             /* n_charts by psi_dim (pooled mode) */
    double *center;         /* n_charts by 3: area-weighted centroid, mesh units */
    double *scale;          /* n_charts: normalized = R (x − center) scale */
    double *rot;            /* n_charts by 3 by 3: R, rows x, y (tangent, principal axis first), z (mean normal) */
    int *mirror;            /* n_charts: 1 when u was negated to make the chart counter-clockwise */
    /* ψ standardization of training (psi_dim each: standardized = (raw − shift)·mul),
     * so that charts the model never saw get codes on the same scale; NULL in
     * models saved before it was kept (they map only their own charts). */
    double *psi_shift, *psi_mul;
    /* n_charts by param_head_size(&f): each training chart's own output layer
     * of MLP_f (param_output_solve.h), or NULL (the shared layer for all). */
    float *heads;
    /* n_charts: the factor that brings each chart's map to its 3D area (uv =
     * uv_gain x MLP_f / scale); NULL in models saved before it (factor 1). */
    double *uv_gain;
    /* 1: f, g, params, psi_shift and psi_mul are another model's (a shape
     * model of param_net_infer); param_net_model_free leaves them. */
    int borrowed;
};

void param_net_model_free(param_net_model *model);

/* Maps the charts of a mesh the model was not trained on (a category model,
 * issue 8): each chart is normalized as in training (centre, geodesic
 * radius, frame), its ψ pooled from vertex_features and standardized with
 * the model's psi_shift / psi_mul, and MLP_f evaluated at its vertices; each
 * chart is then turned counter-clockwise. With solve_heads, each chart gets
 * its own output layer over the model's features, solved on its triangles
 * as training solves the heads of its charts (param_output_solve.h: fold
 * barrier, scale-free energy) — an auto-decoder's inference; without, the
 * shared output layer maps every chart.
 * Inputs:  as param_net_flatten (vertex_features: the same kind as in training)
 * Outputs: corner_uv #F by 3 by 2, as param_net_flatten; rep (may be NULL):
 *          flipped, cycle_rms, seconds; shape_model (NULL: not wanted; only
 *          with solve_heads): a model of these charts (their frames, ψ and
 *          solved heads) that borrows `model`'s networks, so that
 *          param_net_solve_head and param_net_add_chart work on them; free it
 *          with param_net_model_free before `model`
 * Returns NEUV_OK, NEUV_ERR_INPUT (no standardization in the model, ψ size
 * mismatch, bad charts), NEUV_ERR_NOMEM or NEUV_ERR_INTERNAL. */
neuv_status param_net_infer(const param_net_model *model, const neuv_mesh *m, const int *face_chart, int n_charts,
                            const float *vertex_features, int feature_dim, int solve_heads, double *corner_uv,
                            param_net_report *rep, param_net_model **shape_model);

/* UVs of surface points of chart `chart_id` by inference (pooled ψ only: a
 * per-vertex model needs each point's features).
 * Inputs:  points  #N by 3, mesh units
 * Outputs: uv      #N by 2, the chart's frame in mesh units (as corner_uv)
 * Returns NEUV_OK, NEUV_ERR_INPUT (bad chart id, per-vertex model) or NEUV_ERR_NOMEM. */
neuv_status param_net_apply(const param_net_model *model, int chart_id, const double *points, int n,
                            double *uv);

/* UVs of the vertices of `chart`, a triangulation of chart `chart_id`'s
 * surface other than the one the model learnt (a finer or coarser level of
 * detail), by MLP_f with the chart's head solved again on `chart`'s own
 * triangles: the Gauss-Newton solve of training (conformal energy, fold
 * barrier on the faces and on the faces split in four, then the scale-free
 * energy) started from the chart's learnt head, over the same hidden
 * features. Folds the learnt head leaves between the learnt triangulation's
 * vertices are what it removes. Needs a model with heads.
 * Inputs:  chart  positions in mesh units, triangles counter-clockwise
 * Outputs: uv     #chart->nv by 2, as param_net_apply; head, gain: the
 *          solved output layer and its gain, as param_net_solve_head gives
 *          them (either NULL: not wanted); rep: the solve's energies and
 *          steps kept (NULL: not wanted)
 * Returns NEUV_OK, NEUV_ERR_INPUT (bad chart id, no heads) or NEUV_ERR_NOMEM. */
neuv_status param_net_apply_solved(const param_net_model *model, int chart_id, const neuv_mesh *chart, double *uv,
                                   float *head, double *gain, param_solve_report *rep);

/* As param_net_apply_solved, also giving the solved output layer (head:
 * param_head_size(&model->f) floats) and the gain that brings its map to the
 * chart's 3D area: what param_net_add_chart needs to keep the map. Since the
 * head is kept for other triangulations, its solve also weighs the conformal
 * energy on the faces split in four (solve_subdivide_energy), which
 * param_net_apply_solved, a map for this mesh alone, leaves out. */
neuv_status param_net_solve_head(const param_net_model *model, int chart_id, const neuv_mesh *chart, double *uv,
                                 float *head, double *gain);

/* Appends a chart to the model that is chart `parent` (its frame, mirror
 * and ψ) with its own output layer `head` and `gain` (param_net_solve_head on
 * a piece of the parent's surface), so that the piece's map is the model's
 * and is saved with it. Needs a pooled-ψ model with heads and gains.
 * Outputs: *id, the new chart's index (the old n_charts).
 * Returns NEUV_OK, NEUV_ERR_INPUT or NEUV_ERR_NOMEM (the model unchanged). */
neuv_status param_net_add_chart(param_net_model *model, int parent, const float *head, double gain, int *id);
/* 1 when param_net_add_chart can add charts to the model (pooled ψ, per-chart
 * output layers and gains), 0 otherwise. */
int param_net_can_add_chart(const param_net_model *model);

/* Surface points of chart `chart_id` from UVs by MLP_f⁻¹ (the inverse map).
 * Inputs: uv #N by 2 (as param_net_apply returns). Outputs: points #N by 3, mesh units. */
neuv_status param_net_apply_inverse(const param_net_model *model, int chart_id, const double *uv, int n,
                                    double *points);

#endif
