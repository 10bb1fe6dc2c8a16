/* Vertex refinement of a chart atlas (a neuv extension of the paper's method,
 * see bench/RESULTS.md "Vertex refinement"): the parameterization networks
 * give a smooth map that is injective but limited by their capacity (qce_mean
 * ≈ 1.11 on spot where LSCM reaches 1.04 on the same charts). Refinement keeps
 * the networks' map as the starting point and continues to minimize the
 * paper's distortion losses with the UV of every chart vertex as the free
 * variable, on the mesh's own discretization:
 *
 *   E = λ_iso L_iso(edges) + λ_angle L_angle + λ_area L_area + λ_fold L_fold
 *
 * L_iso on the mesh edges (3D edge length is the geodesic distance between
 * adjacent vertices), L_angle and L_area as in losses/param_losses.h, and the
 * fold barrier that keeps every face at least fold_eps of its 3D area with the
 * chart's orientation. Each chart is scaled so that its mean 3D edge length is
 * 1, so the rate is a share of an edge per step whatever the mesh units.
 * Adam with a cosine decay of the rate to 0 over `iters`.
 *
 * A chart whose refined map has more flipped or degenerate faces than its
 * starting map gets its starting map back (counted in the report), so
 * refinement never makes an atlas worse in that respect. With an `accept`
 * test (e.g. the repair stage's injectivity check, which also sees boundary
 * self-crossings) every `check_every` steps and at the end, a chart that fails
 * it goes back to its last accepted map and goes on with its boundary vertices
 * held there (interior refinement cannot make a simple boundary cross); when
 * it fails again it stays at its last accepted map. */
#ifndef NEUV_FLATTEN_UV_REFINE_H
#define NEUV_FLATTEN_UV_REFINE_H

#include "mesh/mesh.h"

/* 1: chart `chart` is acceptable as corner_uv (#F by 3 by 2, the chart's faces
 * filled, mesh units) holds it; 0: not; -1: error (refinement stops with NOMEM). */
typedef int (*uv_refine_accept_fn)(void *user, int chart, const double *corner_uv);

typedef struct uv_refine_options {
    int iters;              /* Adam steps; 0: refinement off */
    double lr;              /* base rate, in mean edge lengths per step */
    double lambda_iso, lambda_angle, lambda_area, lambda_fold;
    double lambda_conformal; /* L_conf of losses/param_losses.h */
    double fold_eps;        /* area ratio under which the fold barrier acts */
    uv_refine_accept_fn accept; /* NULL: only the flip count is compared */
    void *accept_user;
    int check_every;        /* steps between accept tests (> 0 when accept is set) */
} uv_refine_options;

typedef struct uv_refine_report {
    int iters;              /* steps taken */
    int charts_reverted;    /* charts given back their starting map */
    int charts_pinned;      /* charts whose boundary was held after a failed accept test */
    int charts_stopped;     /* charts kept at an earlier accepted step (a test failed with the boundary held) */
    double loss_start, loss_end; /* E at the first and the last step */
    double seconds;
} uv_refine_report;

/* Defaults chosen by measurement (bench/RESULTS.md). */
void uv_refine_default_options(uv_refine_options *o);

/* Refines every chart in place.
 * Inputs:
 *   m           mesh, #V by 3, #F by 3
 *   face_chart  #F chart id per face, 0..n_charts-1
 *   corner_uv   #F by 3 by 2 UV of each face corner, continuous inside a chart
 *               (corners of one vertex in one chart share the UV of the first)
 * Outputs: corner_uv refined (same units and frame per chart); rep may be NULL.
 * Returns NEUV_OK, NEUV_ERR_INPUT (bad charts or options), NEUV_ERR_NOMEM or
 * NEUV_ERR_INTERNAL (a step was not finite). */
neuv_status uv_refine(const neuv_mesh *m, const int *face_chart, int n_charts, const uv_refine_options *o,
                      double *corner_uv, uv_refine_report *rep);

/* The same for one chart given as its own mesh with per-vertex UVs.
 * Inputs: sub one chart, #V by 3; uv #V by 2. Outputs: uv refined in place. */
neuv_status uv_refine_chart(const neuv_mesh *sub, const uv_refine_options *o, double *uv, uv_refine_report *rep);

#endif
