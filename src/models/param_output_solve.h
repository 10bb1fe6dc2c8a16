/* Exact solves for the output layers of the parameterization networks (a
 * neuv extension; docs/method.md and bench/RESULTS.md, "The networks' own
 * map").
 *
 * MLP_f(x, ψ) = tanh(h(x, ψ) W + b) with h the last hidden layer. Adam on all
 * weights leaves the map's angle distortion far above what the hidden
 * features can express. For fixed h, the conformal energy of the map over
 * the charts' triangles is nearly quadratic in the output layer (W, b), so
 * a few Gauss-Newton steps on (W, b) alone reach its minimum over everything
 * the features can represent:
 *
 *   E(W, b) = Σ_f w_f [(J11 − σ J22)² + (J12 + σ J21)²] + μ Σ_v m_v ‖uv_v − uv⁰_v‖²
 *
 * J the Jacobian of the map on face f (in the face's isometric 2D frame),
 * σ = ±1 the chart's orientation in uv⁰ (the map before the solve), w_f the
 * face's share of the normalized 3D area. The first term (the LSCM energy)
 * is zero exactly when the map is conformal; it also falls when a region
 * shrinks, so, as LSCM pins two points, each chart holds two far-apart
 * vertices where uv⁰ has them (m_v = 10 × the chart's area share / μ there,
 * a third of the incident faces' shares elsewhere, μ small). tanh is
 * linearized at the current weights in each step; a step is halved until
 * E falls and is kept only if it flips no more faces than uv⁰ did.
 *
 * Two uses: one shared output layer for all charts (what a category model
 * applies to charts it never saw), and one output layer ("head") per chart
 * of the training mesh, selected by the chart (an auto-decoder: as DeepSDF
 * keeps a code per training shape, the model keeps a head per training
 * chart). Heads are what per-shape unwraps and saved surface models apply.
 *
 * MLP_f⁻¹'s output layer is then refitted by least squares so that
 * MLP_f⁻¹(MLP_f(x)) = x again at the chart vertices. */
#ifndef NEUV_MODELS_PARAM_OUTPUT_SOLVE_H
#define NEUV_MODELS_PARAM_OUTPUT_SOLVE_H

#include "models/param_mlp.h"

/* The charts' vertices and triangles in normalized units, as training sees them. */
typedef struct param_solve_data {
    int nv, nf, n_charts;
    const float *x;          /* nv by 3 normalized positions (MLP_f⁻¹'s targets) */
    const float *f_in;       /* nv by f_in_dim: MLP_f's inputs */
    int f_in_dim;
    const int *vchart;       /* nv: chart of each vertex */
    const float *psi;        /* n_charts by psi_dim (pooled) or nv by psi_dim (per vertex) */
    int psi_dim, psi_per_vertex;
    const int *tri;          /* nf by 3 vertex indices, counter-clockwise seen from outside */
    const int *fchart;       /* nf */
    const float *frame_inv;  /* nf by 4 (param_conformal_targets) */
    const float *face_w;     /* nf: share of the normalized 3D area */
    /* Fold barrier (0: off): fold_weight Σ_f w_f (ε s̄² − σ det J_f)² / s̄² over
     * the faces where σ det J_f < ε s̄², s̄² the chart's area-weighted mean
     * |det J| in uv⁰ and ε = fold_eps. */
    double fold_weight, fold_eps;
    const float *fold_w;     /* nf: each face's weight in the barrier (NULL: face_w); a face
                                with face_w 0 and fold_w > 0 carries the barrier only */
    /* Then, on a chart the map leaves unfolded, Gauss-Newton steps on the
     * scale-free conformal energy 2 Σ_f w_f (MIPS_f − 1), MIPS = (s1/s2 +
     * s2/s1)/2, whose barrier at det J = 0 keeps every face unfolded
     * (0: none). */
    int mips_steps;
    /* A second start for the per-chart heads (param_output_solve_heads): the
     * vertices below fit_nv have a target map fit_uv (fit_nv by 2, MLP_f's
     * output units; training gives each chart's LSCM map, its warm-start
     * target). A chart whose head still folds faces after its solve from the
     * shared layer is solved again from the head that fits these targets by
     * least squares over the same features, and keeps whichever solve folds
     * fewer faces (NULL: no second start). */
    const float *fit_uv;
    int fit_nv;
    /* A chart's step with more vertices than features is solved in the span
     * of its features' singular directions above rank_tol of the largest
     * (0: PARAM_SOLVE_RANK_TOL; < 0: every direction, in feature space). */
    double rank_tol;
} param_solve_data;

#define PARAM_SOLVE_RANK_TOL 1e-7

typedef struct param_solve_report {
    double energy_before, energy_after; /* conformal term at the vertices, before and after */
    int steps;                          /* shared solve: Gauss-Newton steps kept */
    int heads_improved;                 /* per-chart solve: charts whose head moved from the shared one */
    int heads_refit;                    /* per-chart solve: charts whose head came from the fit start (fit_uv) */
} param_solve_report;

/* The data with every face also split in four at its edge midpoints: each
 * midpoint becomes a vertex (x and the inputs the mean of the edge's ends,
 * the face's chart), and the four sub-faces carry the fold barrier (fold_w a
 * quarter of the face's) and `energy_share` of the face's conformal energy
 * weight (a quarter of that each; the face keeps the rest), so that a solve
 * keeps the map unfolded, and close to conformal, between the vertices too,
 * where a finer triangulation of the surface has its own. energy_share 0:
 * the sub-faces carry the barrier only. Charts with at least
 * `dense_vertices` vertices (> 0; 0: no such bound) carry the barrier only
 * too: their vertices outnumber the output layer's weights, so the solve
 * cannot bend between them (param_net_options.solve_subdivide_dense). The
 * original vertices and faces come first, in order.
 * Needs a pooled ψ. Returns NEUV_OK, NEUV_ERR_INPUT or NEUV_ERR_NOMEM (free
 * with param_solve_subdivided_free; out->d views its arrays). */
typedef struct param_solve_subdivided {
    param_solve_data d;
    float *x, *f_in, *frame_inv, *face_w, *fold_w;
    int *vchart, *tri, *fchart;
} param_solve_subdivided;

neuv_status param_solve_subdivide(const param_solve_data *d, double energy_share, int dense_vertices,
                                  param_solve_subdivided *out);
void param_solve_subdivided_free(param_solve_subdivided *sd);

/* Floats per head: (width + 1) x 2, u's weights and bias then v's. */
int param_head_size(const param_mlp *f);

/* Gauss-Newton steps on MLP_f's shared output layer (in place), all charts together.
 * Returns NEUV_OK, NEUV_ERR_INPUT (depth < 2 or out != 2) or NEUV_ERR_NOMEM
 * (a singular system ends the steps and keeps the last weights). */
neuv_status param_output_solve_conformal(param_mlp *f, const param_solve_data *d, double anchor, int steps,
                                         param_solve_report *rep);

/* One head per chart (heads: n_charts x param_head_size(f), written), each
 * Gauss-Newton from the shared output layer on the chart's own faces.
 * Returns NEUV_OK, NEUV_ERR_INPUT or NEUV_ERR_NOMEM. */
neuv_status param_output_solve_heads(const param_mlp *f, const param_solve_data *d, double anchor, int steps,
                                     float *heads, param_solve_report *rep);

/* One chart's head solved as param_output_solve_heads does, but from `start`
 * (param_head_size(f) floats, e.g. the head a model learnt for this chart
 * on another triangulation of it) instead of the shared output layer: the
 * chart keeps start's orientation, and the fold barrier's scale and the
 * pins come from start's map on d. d must hold one chart. head (written)
 * may be start. Returns NEUV_OK, NEUV_ERR_INPUT or NEUV_ERR_NOMEM. */
neuv_status param_output_solve_head_from(const param_mlp *f, const param_solve_data *d, double anchor, int steps,
                                         const float *start, float *head, param_solve_report *rep);

/* Least-squares fit of MLP_f⁻¹'s output layer (in place) so that it maps
 * MLP_f's outputs at the vertices (through `heads` when not NULL) back to x.
 * Returns NEUV_OK, NEUV_ERR_INPUT, NEUV_ERR_NOMEM or NEUV_ERR_INTERNAL. */
neuv_status param_output_solve_inverse(param_mlp *g, const param_mlp *f, const float *heads,
                                       const param_solve_data *d);

/* MLP_f's output through per-row heads: uv_i = tanh(hidden_i W_{c_i} + b_{c_i}).
 * Inputs: hidden #N by f->width, head_of #N head index per row, heads.
 * Outputs: uv #N by 2 (float). */
void param_heads_apply(const param_mlp *f, const float *hidden, int n, const int *head_of, const float *heads,
                       float *uv);

/* For tests: the largest difference, relative to the largest gradient
 * entry, between the gradient of E that the Gauss-Newton rows give at f's
 * shared output layer (2 Jᵀ r) and a central finite difference of E, over
 * n_probe of its coordinates; E is the scale-free energy when
 * d->mips_steps > 0 (then f's map must fold no face). INFINITY on bad input
 * or allocation failure. */
double param_output_solve_gradient_error(const param_mlp *f, const param_solve_data *d, double anchor, int n_probe);

/* For tests: the largest difference, relative to the largest entry, between
 * the Gauss-Newton step of f's shared output layer solved in feature space
 * (2(H+1) unknowns) and in vertex space (2 #V: what a block with fewer
 * vertices than features uses); the same step in exact arithmetic. The rows
 * are the scale-free energy's when d->mips_steps > 0. INFINITY on bad input,
 * a singular system or allocation failure. */
double param_output_solve_dual_error(const param_mlp *f, const param_solve_data *d, double anchor);

/* For tests: the largest difference, relative to the step's largest change,
 * between the maps (pre-tanh, at the vertices) of one Gauss-Newton step of
 * the per-chart heads' start (the shared layer, over every hidden layer's
 * features, all vertices one block) solved in feature space and in the
 * features' span above rank_tol (the reduced system); *rank: that span's
 * dimension. INFINITY on bad input, a span as large as the features (no
 * reduced system), a singular system or allocation failure. */
double param_output_solve_reduced_error(const param_mlp *f, const param_solve_data *d, double anchor, double rank_tol,
                                       int *rank);

#endif
