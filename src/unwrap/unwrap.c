/* The pipeline: clean → charts → parameterization and repair → pack →
 * metrics, one sequence of stages for every path (trained on the mesh, a
 * category model's inference, a surface model carried to another
 * triangulation: unwrap_plan). Each stage is timed by one clock; every
 * repair is recorded. */
#include "unwrap/unwrap_internal.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "atlas/pack_split.h"
#include "charts/charts.h"
#include "core/error.h"
#include "core/log.h"
#include "core/mem.h"
#include "core/timer.h"
#include "flatten/harmonic.h"
#include "flatten/lscm.h"
#include "flatten/uv_refine.h"
#include "geometry/operator_cache.h"
#include "geometry/operators.h"
#include "metrics/chart_uv_check.h"
#include "models/param_net.h"
#include "models/patchnet.h"
#include "nn/nn.h"
#include "segment/patchnet_segment.h"
#include "unwrap/memory_budget.h"
#include "unwrap/unwrap_apply.h"
#include "unwrap/unwrap_model.h"
#include "unwrap/unwrap_seams.h"

void neuv_unwrap_options_init(neuv_unwrap_options *o)
{
    memset(o, 0, sizeof *o);
    o->method = NEUV_METHOD_NEURAL;
    o->preset = NEUV_PRESET_FAST;
    o->charts = 0;
    o->max_distortion = 1.15;
    o->seed = 1;
    o->resolution = 1024;
    o->padding = 2;
    o->use_cache = 1;
    o->hard_edges = 1;
    uv_refine_options ro;
    uv_refine_default_options(&ro);
    o->refine = ro.iters;
}

void unwrap_add_repair(struct neuv_unwrap_result *r, int chart, const char *fmt, ...)
{
    if (r->n_repairs == r->cap_repairs) {
        int cap = r->cap_repairs ? 2 * r->cap_repairs : 16;
        unwrap_repair *nr = mem_realloc(r->repairs, sizeof *nr * (size_t)cap);
        if (!nr) { r->repairs_lost = 1; return; }
        r->repairs = nr;
        r->cap_repairs = cap;
    }
    unwrap_repair *rep = &r->repairs[r->n_repairs++];
    rep->chart = chart;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(rep->what, sizeof rep->what, fmt, ap);
    va_end(ap);
    log_message(NEUV_LOG_DEBUG, "repair: chart %d: %s", chart, rep->what);
}

void unwrap_piece_clear(chart_piece *p)
{
    mesh_free(p->sub);
    mem_free(p->vmap);
    mem_free(p->fmap);
    mem_free(p->uv);
    memset(p, 0, sizeof *p);
    p->net = p->tried = -1;
    p->net_qce = NAN;
    p->lscm_qce = NAN;
}

neuv_status unwrap_piece_build(const neuv_mesh *m, const int *face_chart, int id, chart_piece *p)
{
    int from_split = p->from_split, net_split = p->net_split, net_head = p->net_head, net_depth = p->net_depth;
    int net_solved = p->net_solved;
    unwrap_piece_clear(p);
    p->from_split = from_split;
    p->net_split = net_split;
    p->net_head = net_head;
    p->net_depth = net_depth;
    p->net_solved = net_solved;
    neuv_status s = chart_submesh(m, face_chart, id, &p->sub, &p->vmap, &p->fmap);
    if (s != NEUV_OK) return s;
    p->uv = mem_calloc((size_t)p->sub->nv * 2, sizeof(double));
    return p->uv ? NEUV_OK : error_nomem("chart UVs");
}

static const char *classic_name(neuv_method method)
{
    return method == NEUV_METHOD_HARMONIC ? "harmonic" : "LSCM";
}

static neuv_status flatten_classic(neuv_method method, const chart_piece *p)
{
    return method == NEUV_METHOD_HARMONIC ? harmonic(p->sub, p->uv) : lscm(p->sub, p->uv);
}

/* Copies the network's per-corner UVs of the chart's faces to its vertices. */
static void piece_uv_from_corners(chart_piece *p, const double *corner_uv)
{
    for (int lf = 0; lf < p->sub->nf; lf++)
        for (int k = 0; k < 3; k++) {
            int lv = p->sub->tri[3 * lf + k];
            const double *c = corner_uv + 2 * (3 * (size_t)p->fmap[lf] + k);
            p->uv[2 * lv] = c[0];
            p->uv[2 * lv + 1] = c[1];
        }
}

static void describe_failure(char *buf, size_t n, const chart_uv_check *c)
{
    snprintf(buf, n, "%d flipped, %d degenerate faces, %d boundary crossings", c->flipped, c->degenerate,
             c->boundary_crossings);
}

static int grow_pieces(chart_piece **pieces, int *cap, int need)
{
    if (need <= *cap) return 0;
    int nc = *cap ? *cap : 16;
    while (nc < need) nc *= 2;
    chart_piece *np = mem_realloc(*pieces, sizeof *np * (size_t)nc);
    if (!np) return -1;
    memset(np + *cap, 0, sizeof *np * (size_t)(nc - *cap));
    for (int i = *cap; i < nc; i++) { np[i].net = np[i].tried = -1; np[i].net_qce = NAN; np[i].lscm_qce = NAN; }
    *pieces = np;
    *cap = nc;
    return 0;
}

/* The repair stage: every chart ends with an injective map (no flipped or
 * degenerate face, simple boundary). A folded neural chart is re-flattened
 * with LSCM; a chart the classic method cannot flatten without folds is
 * split in two and both halves are flattened again. */

static int piece_accepts(void *user, int chart, const double *corner_uv)
{
    (void)chart;
    const chart_piece *p = user;
    double *uv = mem_alloc(sizeof(double) * 2 * (size_t)p->sub->nv);
    if (!uv) return -1;
    for (int f = 0; f < p->sub->nf; f++)
        for (int k = 0; k < 3; k++) {
            int v = p->sub->tri[3 * f + k];
            uv[2 * v] = corner_uv[6 * f + 2 * k];
            uv[2 * v + 1] = corner_uv[6 * f + 2 * k + 1];
        }
    chart_uv_check chk;
    int ok = chart_uv_check_run(p->sub, uv, &chk);
    mem_free(uv);
    return ok < 0 ? -1 : ok && !chk.mirrored;
}

/* The conformal step that opens the refinement: LSCM anchored to the
 * networks' map (flatten/lscm.h) with this weight, kept when it is injective
 * with the same orientation. λ = 1: moving the whole chart by its own size
 * costs what a unit conformal residual over the chart does, so the map
 * keeps the networks' placement, orientation and scale while the solve
 * removes the angle distortion the networks leave (their capacity bounds
 * it; Adam on vertices alone takes thousands of steps to do the same). */
#define REFINE_ANCHOR_LAMBDA 1.0

static neuv_status refine_conformal_step(chart_piece *p)
{
    size_t bytes = sizeof(double) * 2 * (size_t)p->sub->nv;
    double *solved = mem_alloc(bytes);
    if (!solved) return error_nomem("chart UVs");
    neuv_status s = lscm_anchored(p->sub, p->uv, REFINE_ANCHOR_LAMBDA, solved);
    if (s == NEUV_ERR_NOMEM) { mem_free(solved); return s; }
    if (s == NEUV_OK) {
        chart_uv_check chk;
        int ok = chart_uv_check_run(p->sub, solved, &chk);
        if (ok < 0) s = error_nomem("chart check");
        else if (ok && !chk.mirrored) memcpy(p->uv, solved, bytes);
    }
    mem_free(solved);
    return s == NEUV_ERR_NOMEM ? s : NEUV_OK; /* a failed solve keeps the networks' map */
}

neuv_status unwrap_refine_piece(chart_piece *p, int steps, uv_refine_report *rep)
{
    if (steps > 0) {
        neuv_status s = refine_conformal_step(p);
        if (s != NEUV_OK) return s;
    }
    uv_refine_options ro;
    uv_refine_default_options(&ro);
    ro.iters = steps;
    ro.accept = piece_accepts;
    ro.accept_user = p;
    ro.check_every = 10;
    return uv_refine_chart(p->sub, &ro, p->uv, rep);
}

neuv_status unwrap_piece_lscm_qce(chart_piece *p)
{
    double *uv = mem_alloc(sizeof(double) * 2 * (size_t)p->sub->nv);
    if (!uv) return error_nomem("chart UVs");
    neuv_status s = lscm(p->sub, uv);
    if (s == NEUV_OK) p->lscm_qce = chart_qce_mean(p->sub, uv, NULL);
    mem_free(uv);
    return s == NEUV_ERR_NOMEM ? s : NEUV_OK; /* a failed solve leaves NaN */
}

neuv_status unwrap_keep_provenance(struct neuv_unwrap_result *r, const chart_piece *pieces)
{
    size_t n = (size_t)(r->n_charts > 0 ? r->n_charts : 1);
    mem_free(r->chart_source); mem_free(r->chart_net_qce); mem_free(r->chart_lscm_qce);
    r->chart_source = mem_alloc(sizeof(int) * n);
    r->chart_net_qce = mem_alloc(sizeof(double) * n);
    r->chart_lscm_qce = mem_alloc(sizeof(double) * n);
    if (!r->chart_source || !r->chart_net_qce || !r->chart_lscm_qce) return error_nomem("chart provenance");
    r->neural_charts = 0;
    for (int c = 0; c < r->n_charts; c++) {
        r->chart_source[c] = (int)pieces[c].source;
        r->chart_net_qce[c] = pieces[c].net_qce;
        r->chart_lscm_qce[c] = pieces[c].lscm_qce;
        r->neural_charts += chart_source_is_network(pieces[c].source);
    }
    return NEUV_OK;
}

/* After a split of chart c (or of each parent[k]) into it and the charts
 * from `first` on: their polygons whole again (charts/polygon_charts.c), between them only, so
 * that no chart already flattened changes. */
static neuv_status rejoin_polygons(struct neuv_unwrap_result *r, const neuv_mesh *m, const int *parent, int c,
                                   int first)
{
    if (!r->face_polygon) return NEUV_OK;
    int *act = mem_calloc((size_t)r->n_charts, sizeof(int));
    if (!act) return error_nomem("the polygons");
    for (int k = first; k < r->n_charts; k++) act[k] = act[parent ? parent[k] : c] = 1;
    neuv_status s = charts_keep_polygons(m, r->face_polygon, act, r->face_chart, NULL);
    mem_free(act);
    return s;
}

/* Pieces of at most this many faces are refined together, in one
 * uv_refine over all of them: a step's cost on such a piece is the step's
 * fixed cost (building the loss graph, its parallel loops, Adam), 0.39 ms
 * on a two-face piece (200 of them: 31 s one by one, 0.3 s together; 2000,
 * from 1000 tetrahedra, some 310 s one by one). Larger pieces are refined
 * one by one as before; 16 is under the smallest chart of the meshes
 * measured (spot: 17 faces), whose maps therefore stay bit for bit. */
#define REFINE_BATCH_FACES 16

typedef struct refine_batch {
    chart_piece *pieces;
    const int *ids;   /* the batch's pieces */
    const int *face0; /* n + 1: each piece's first face in the joined mesh */
} refine_batch;

static int batch_accepts(void *user, int chart, const double *corner_uv)
{
    const refine_batch *b = user;
    return piece_accepts(&b->pieces[b->ids[chart]], 0, corner_uv + 6 * (size_t)b->face0[chart]);
}

/* unwrap_refine_piece's vertex refinement (after its conformal step, done
 * by the caller) on n pieces at once: their charts side by side in one
 * mesh, each accepted or held back by its own injectivity check. uv_refine's
 * losses are means over the whole mesh, so each is scaled by n: a piece's
 * gradient is then what it was alone when the pieces have the same size
 * (Adam follows the gradient's direction, but its ε does not scale). */
static neuv_status refine_pieces_together(chart_piece *pieces, const int *ids, int n, int steps, uv_refine_report *rep)
{
    int nv = 0, nf = 0;
    for (int k = 0; k < n; k++) { nv += pieces[ids[k]].sub->nv; nf += pieces[ids[k]].sub->nf; }
    neuv_mesh *joined = mesh_create(nv, nf, 0);
    int *fchart = mem_alloc(sizeof(int) * (size_t)(nf > 0 ? nf : 1)), *face0 = mem_alloc(sizeof(int) * ((size_t)n + 1));
    double *corner = mem_alloc(sizeof(double) * 6 * (size_t)(nf > 0 ? nf : 1));
    neuv_status s = NEUV_OK;
    if (!joined || !fchart || !face0 || !corner) { s = error_nomem("UV refinement"); goto done; }
    int v0 = 0, f0 = 0;
    for (int k = 0; k < n; k++) {
        const chart_piece *p = &pieces[ids[k]];
        face0[k] = f0;
        memcpy(joined->pos + 3 * (size_t)v0, p->sub->pos, sizeof(double) * 3 * (size_t)p->sub->nv);
        for (int f = 0; f < p->sub->nf; f++) {
            fchart[f0 + f] = k;
            for (int q = 0; q < 3; q++) {
                int v = p->sub->tri[3 * f + q];
                joined->tri[3 * (size_t)(f0 + f) + q] = v0 + v;
                corner[6 * (size_t)(f0 + f) + 2 * q] = p->uv[2 * v];
                corner[6 * (size_t)(f0 + f) + 2 * q + 1] = p->uv[2 * v + 1];
            }
        }
        v0 += p->sub->nv;
        f0 += p->sub->nf;
    }
    face0[n] = f0;
    uv_refine_options ro;
    uv_refine_default_options(&ro);
    ro.iters = steps;
    ro.lambda_iso *= n; ro.lambda_angle *= n; ro.lambda_conformal *= n; ro.lambda_area *= n; ro.lambda_fold *= n;
    refine_batch b = {pieces, ids, face0};
    ro.accept = batch_accepts;
    ro.accept_user = &b;
    ro.check_every = 10;
    s = uv_refine(joined, fchart, n, &ro, corner, rep);
    if (s == NEUV_OK)
        for (int k = 0; k < n; k++) {
            chart_piece *p = &pieces[ids[k]];
            const double *cu = corner + 6 * (size_t)face0[k];
            for (int f = 0; f < p->sub->nf; f++)
                for (int q = 0; q < 3; q++) {
                    int v = p->sub->tri[3 * f + q];
                    p->uv[2 * v] = cu[6 * (size_t)f + 2 * q];
                    p->uv[2 * v + 1] = cu[6 * (size_t)f + 2 * q + 1];
                }
        }
done:
    mesh_free(joined);
    mem_free(fchart); mem_free(face0); mem_free(corner);
    return s;
}

static neuv_status flatten_and_repair(struct neuv_unwrap_result *r, neuv_mesh *m, const double *corner_uv,
                                      chart_piece **pieces_out, int *cap_out)
{
    neuv_method classic = r->opts.method == NEUV_METHOD_HARMONIC ? NEUV_METHOD_HARMONIC : NEUV_METHOD_LSCM;
    chart_piece *pieces = NULL;
    int cap = 0;
    neuv_status s = NEUV_OK;
    int splits = 0, n_small = 0, *small = NULL; /* pieces refined together after the loop */
    for (int c = 0; c < r->n_charts; c++) {
        if (grow_pieces(&pieces, &cap, r->n_charts) != 0) { s = error_nomem("charts"); break; }
        chart_piece *p = &pieces[c];
        if ((s = unwrap_piece_build(m, r->face_chart, c, p)) != NEUV_OK) break;
        log_progress("repair", (double)c / r->n_charts, "chart %d of %d", c + 1, r->n_charts);
        chart_uv_check chk;
        char why[160];
        if (corner_uv && (!p->from_split || p->net_split)) {
            int head = p->net_split ? p->net_head : c;
            p->tried = head;
            float *solved = NULL; /* a fold's piece: the output layer solved on it */
            double gain = 1, piece_qce = NAN; /* qce_mean of p->uv once a net_solved piece is checked */
            int poor = 0; /* injective, but far less conformal than LSCM on the piece */
            piece_uv_from_corners(p, corner_uv);
            int ok = chart_uv_check_run(p->sub, p->uv, &chk);
            /* A piece of a chart the networks folded: their learnt map if it
             * is injective and conformal enough here, else the map of an
             * output layer solved on the piece, under the same bound. */
            if (ok > 0 && p->net_solved) {
                if ((s = unwrap_piece_lscm_qce(p)) != NEUV_OK) break;
                piece_qce = chart_qce_mean(p->sub, p->uv, NULL);
                if (!(piece_qce <= SOLVED_HEAD_MAX_QCE_RATIO * p->lscm_qce)) ok = 0;
            }
            if (ok == 0 && p->net_solved) {
                solved = mem_alloc(sizeof(float) * (size_t)param_head_size(&r->param->f));
                s = solved ? param_net_solve_head(r->param, head, p->sub, p->uv, solved, &gain) : error_nomem("charts");
                if (s == NEUV_OK) ok = chart_uv_check_run(p->sub, p->uv, &chk);
                if (s == NEUV_OK && ok > 0 && isnan(p->lscm_qce)) s = unwrap_piece_lscm_qce(p);
                if (s != NEUV_OK) { mem_free(solved); break; }
                piece_qce = chart_qce_mean(p->sub, p->uv, NULL);
                if (ok > 0 && !(piece_qce <= SOLVED_HEAD_MAX_QCE_RATIO * p->lscm_qce)) { poor = 1; ok = 0; }
            }
            if (ok > 0 && solved) { /* the model keeps the piece's map as a chart of its own */
                s = param_net_add_chart(r->param, head, solved, gain, &head);
                p->tried = head;
            }
            mem_free(solved);
            if (s != NEUV_OK) break;
            if (ok < 0) { s = error_nomem("chart check"); break; }
            p->net_qce = isnan(piece_qce) ? chart_qce_mean(p->sub, p->uv, NULL) : piece_qce;
            if (ok && isnan(p->lscm_qce) && (s = unwrap_piece_lscm_qce(p)) != NEUV_OK) break;
            p->source = ok && r->opts.refine > 0 ? CHART_SOURCE_NETWORK_REFINED : CHART_SOURCE_NETWORK;
            if (ok && r->opts.refine > 0 && p->sub->nf <= REFINE_BATCH_FACES) {
                if ((s = refine_conformal_step(p)) != NEUV_OK) break;
                int *grown = mem_realloc(small, sizeof(int) * ((size_t)n_small + 1));
                if (!grown) { s = error_nomem("charts"); break; }
                small = grown;
                small[n_small++] = c;
            } else if (ok && r->opts.refine > 0) {
                uv_refine_report rr;
                if ((s = unwrap_refine_piece(p, r->opts.refine, &rr)) != NEUV_OK) break;
                r->refine_seconds += rr.seconds;
                if (rr.iters > r->refine_steps) r->refine_steps = rr.iters;
                r->refine_stopped += rr.charts_stopped;
            }
            if (!ok) p->source = CHART_SOURCE_NETWORK_FOLDED;
            if (ok || r->opts.allow_overlaps) {
                p->net = head;
                p->mirrored = chk.mirrored;
                continue;
            }
            int can_solve = param_net_can_add_chart(r->param);
            int refold = (chk.flipped > 0 || chk.degenerate > 0 || poor) && can_solve;
            if (poor)
                snprintf(why, sizeof why, "injective, but its output layer solved on the piece gives qce_mean %.3f, "
                         "over %.2f times LSCM's %.3f", piece_qce, SOLVED_HEAD_MAX_QCE_RATIO, p->lscm_qce);
            else
                describe_failure(why, sizeof why, &chk);
            if ((refold || (chk.flipped == 0 && chk.degenerate == 0 && !poor)) && p->net_depth < NET_SPLIT_DEPTH &&
                p->sub->nf >= 2 && splits < m->nf) {
                /* Locally injective but its boundary crosses itself: the
                 * halves may each be injective under the same map. Folded:
                 * the output layer solved on each half alone (as many weights
                 * for fewer vertices) may not fold (refold). */
                int before = r->n_charts, depth = p->net_depth + 1;
                if ((s = charts_split(m, r->face_chart, &r->n_charts, c)) != NEUV_OK) break;
                if ((s = rejoin_polygons(r, m, NULL, c, before)) != NEUV_OK) break;
                splits++;
                if (refold) {
                    unwrap_add_repair(r, c, "the networks' map %s (%s); split into %d charts, each taking the "
                                      "same map or an output layer solved on it", poor ? "too distorted" : "folded",
                                      why, r->n_charts - before + 1);
                } else {
                    unwrap_add_repair(r, c, "the networks' map crossed the chart's own boundary (%d crossings); split "
                                      "into %d charts, each checked under the same map%s", chk.boundary_crossings,
                                      r->n_charts - before + 1, can_solve ? " or an output layer solved on it" : "");
                }
                if (grow_pieces(&pieces, &cap, r->n_charts) != 0) { s = error_nomem("charts"); break; }
                for (int k = before; k <= r->n_charts; k++) {
                    chart_piece *q = &pieces[k < r->n_charts ? k : c];
                    q->from_split = q->net_split = 1;
                    q->net_head = head;
                    q->net_depth = depth;
                    q->net_solved = can_solve;
                }
                c--;
                continue;
            }
            unwrap_add_repair(r, c, poor ? "the networks' map too distorted (%s); re-flattened with LSCM"
                                         : "neural map folded (%s); re-flattened with LSCM", why);
        }
        s = flatten_classic(corner_uv ? NEUV_METHOD_LSCM : classic, p);
        if (s != NEUV_OK) break;
        neuv_method used = corner_uv ? NEUV_METHOD_LSCM : classic;
        if (p->from_split)
            p->source = used == NEUV_METHOD_HARMONIC ? CHART_SOURCE_HARMONIC_AFTER_SPLIT : CHART_SOURCE_LSCM_AFTER_SPLIT;
        else if (corner_uv) p->source = CHART_SOURCE_LSCM_AFTER_FOLD;
        else p->source = used == NEUV_METHOD_HARMONIC ? CHART_SOURCE_HARMONIC : CHART_SOURCE_LSCM;
        int ok = chart_uv_check_run(p->sub, p->uv, &chk);
        if (ok < 0) { s = error_nomem("chart check"); break; }
        if (used == NEUV_METHOD_LSCM) p->lscm_qce = chart_qce_mean(p->sub, p->uv, NULL);
        p->mirrored = chk.mirrored;
        if (ok || r->opts.allow_overlaps) continue;
        if (p->sub->nf < 2 || splits >= m->nf) {
            s = error_set(NEUV_ERR_INTERNAL, "chart %d cannot be flattened without folds", c);
            break;
        }
        describe_failure(why, sizeof why, &chk);
        int before = r->n_charts;
        s = charts_split(m, r->face_chart, &r->n_charts, c);
        if (s == NEUV_OK) s = rejoin_polygons(r, m, NULL, c, before);
        if (s != NEUV_OK) break;
        splits++;
        unwrap_add_repair(r, c, "%s map folded (%s); split into %d charts and re-flattened",
                          classic_name(corner_uv ? NEUV_METHOD_LSCM : classic), why, r->n_charts - before + 1);
        if (grow_pieces(&pieces, &cap, r->n_charts) != 0) { s = error_nomem("charts"); break; }
        for (int k = before; k < r->n_charts; k++) pieces[k].from_split = 1;
        pieces[c].from_split = 1;
        pieces[c].net_split = 0; /* the classic method's pieces stay the classic method's */
        c--; /* flatten the smaller chart that kept this id again */
    }
    if (s == NEUV_OK && n_small > 0) {
        uv_refine_report rr;
        memset(&rr, 0, sizeof rr);
        s = refine_pieces_together(pieces, small, n_small, r->opts.refine, &rr);
        r->refine_seconds += rr.seconds;
        if (rr.iters > r->refine_steps) r->refine_steps = rr.iters;
        r->refine_stopped += rr.charts_stopped;
    }
    mem_free(small);
    *pieces_out = pieces;
    *cap_out = cap;
    return s;
}

neuv_status unwrap_assemble_uvs(neuv_mesh *m, const chart_piece *pieces, int n_charts)
{
    int nuv = 0;
    for (int c = 0; c < n_charts; c++) nuv += pieces[c].sub->nv;
    double *uv = mem_alloc(sizeof(double) * 2 * (size_t)nuv);
    int *tri_uv = mem_alloc(sizeof(int) * 3 * (size_t)m->nf);
    if (!uv || !tri_uv) { mem_free(uv); mem_free(tri_uv); return error_nomem("UVs"); }
    int base = 0;
    neuv_status s = NEUV_OK;
    for (int c = 0; c < n_charts && s == NEUV_OK; c++) {
        const chart_piece *p = &pieces[c];
        memcpy(uv + 2 * base, p->uv, sizeof(double) * 2 * (size_t)p->sub->nv);
        for (int lf = 0; lf < p->sub->nf; lf++)
            for (int k = 0; k < 3; k++) {
                int f = p->fmap[lf], lv = p->sub->tri[3 * lf + k];
                if (p->vmap[lv] != m->tri[3 * f + k]) {
                    s = error_set(NEUV_ERR_INTERNAL, "chart %d: corner order differs from the mesh", c);
                    break;
                }
                tri_uv[3 * f + k] = base + lv;
            }
        base += p->sub->nv;
    }
    if (s == NEUV_OK) s = mesh_set_uv(m, nuv, uv, tri_uv);
    mem_free(uv);
    mem_free(tri_uv);
    return s;
}

neuv_status unwrap_metrics(const neuv_mesh *m, uv_metrics *out)
{
    neuv_mesh *welded = mesh_clone(m);
    if (!welded) return error_nomem("the metrics");
    if (mesh_weld_positions(welded) < 0) { mesh_free(welded); return error_nomem("the metrics"); }
    neuv_status s = uv_metrics_compute(welded, out);
    mesh_free(welded);
    return s;
}

/* Cuts charts that pack badly (atlas/pack_split.h); their UVs do not
 * change, so a piece keeps its parent's network map and mirror flag. */
static neuv_status split_for_packing(struct neuv_unwrap_result *r, const neuv_mesh *m)
{
    pack_split_options so;
    pack_split_default_options(&so);
    so.pack.resolution = r->opts.resolution;
    so.pack.padding = r->opts.padding;
    int *parent = NULL, before = r->n_charts;
    pack_split_report rep;
    neuv_status s = pack_split_charts(m, r->face_chart, &r->n_charts, &so, &parent, &rep);
    /* A piece keeps its parent's map, so a triangle may go back to a sibling. */
    if (s == NEUV_OK && r->n_charts > before) s = rejoin_polygons(r, m, parent, -1, before);
    if (s != NEUV_OK) { mem_free(parent); return s; }
    r->pack_splits = rep.splits;
    r->pack_split_trials = rep.trials;
    r->pack_split_seconds = rep.seconds;
    if (r->n_charts > before && r->chart_source) {
        /* A piece keeps its parent's map, so its source; the qce figures are the parent's. */
        int *src = mem_realloc(r->chart_source, sizeof(int) * (size_t)r->n_charts);
        if (src) r->chart_source = src;
        double *nq = mem_realloc(r->chart_net_qce, sizeof(double) * (size_t)r->n_charts);
        if (nq) r->chart_net_qce = nq;
        double *lq = mem_realloc(r->chart_lscm_qce, sizeof(double) * (size_t)r->n_charts);
        if (lq) r->chart_lscm_qce = lq;
        if (!src || !nq || !lq) { mem_free(parent); return error_nomem("chart provenance"); }
        for (int c = before; c < r->n_charts; c++) {
            r->chart_source[c] = r->chart_source[parent[c]];
            r->chart_net_qce[c] = r->chart_net_qce[parent[c]];
            r->chart_lscm_qce[c] = r->chart_lscm_qce[parent[c]];
        }
    }
    if (r->n_charts > before && r->chart_net) {
        int *net = mem_realloc(r->chart_net, sizeof(int) * (size_t)r->n_charts);
        if (net) r->chart_net = net;
        int *mir = mem_realloc(r->chart_mirrored, sizeof(int) * (size_t)r->n_charts);
        if (mir) r->chart_mirrored = mir;
        int *tried = mem_realloc(r->chart_tried, sizeof(int) * (size_t)r->n_charts);
        if (tried) r->chart_tried = tried;
        if (!net || !mir || !tried) { mem_free(parent); return error_nomem("the model"); }
        for (int c = before; c < r->n_charts; c++) {
            r->chart_net[c] = r->chart_net[parent[c]];
            r->chart_mirrored[c] = r->chart_mirrored[parent[c]];
            r->chart_tried[c] = r->chart_tried[parent[c]];
        }
    }
    if (r->n_charts > before && r->frame_xf) {
        atlas_chart_transform *xf = mem_realloc(r->frame_xf, sizeof *xf * (size_t)r->n_charts);
        if (!xf) { mem_free(parent); return error_nomem("chart transforms"); }
        r->frame_xf = xf;
        for (int c = before; c < r->n_charts; c++) r->frame_xf[c] = r->frame_xf[parent[c]];
    }
    mem_free(parent);
    return NEUV_OK;
}

void unwrap_stage_time(struct neuv_unwrap_result *r, int stage, double t0)
{
    r->seconds[stage] += now_seconds() - t0;
    double t = 0;
    for (int i = 0; i < STAGE_COUNT; i++) t += r->seconds[i];
    r->total_seconds = t;
}

neuv_status unwrap_clean_copy(const neuv_mesh *in, neuv_mesh **out, mesh_clean_report *report, int **face_origin)
{
    *out = NULL;
    if (face_origin) *face_origin = NULL;
    neuv_mesh *m = mesh_clone(in);
    if (!m) return error_nomem("the mesh");
    mesh_set_uv(m, 0, NULL, NULL);
    neuv_status s = NEUV_OK;
    if (face_origin) {
        /* The copy's UVs are free (the atlas makes its own), and cleaning
         * keeps UV corners with their faces: each corner carries the number
         * of its face through the repairs. */
        int *tri_uv = mem_alloc(sizeof(int) * 3 * (size_t)in->nf);
        double *uv = mem_calloc(2 * (size_t)in->nf, sizeof(double));
        if (!tri_uv || !uv) s = error_nomem("the mesh");
        for (int f = 0; s == NEUV_OK && f < in->nf; f++) tri_uv[3 * f] = tri_uv[3 * f + 1] = tri_uv[3 * f + 2] = f;
        if (s == NEUV_OK) s = mesh_set_uv(m, in->nf, uv, tri_uv);
        mem_free(tri_uv);
        mem_free(uv);
    }
    if (s == NEUV_OK) s = mesh_clean(m, NULL, report);
    if (s == NEUV_OK && m->nf == 0)
        s = error_set(NEUV_ERR_INPUT, "no faces left after cleaning (every face was degenerate)");
    if (s == NEUV_OK && !(mesh_total_area(m) > 0)) s = error_set(NEUV_ERR_INPUT, "the mesh has zero area");
    if (s == NEUV_OK && face_origin) {
        if (!(*face_origin = mem_alloc(sizeof(int) * (size_t)m->nf))) s = error_nomem("the mesh");
        for (int f = 0; s == NEUV_OK && f < m->nf; f++) (*face_origin)[f] = m->tri_uv[3 * f];
        if (s == NEUV_OK) s = mesh_set_uv(m, 0, NULL, NULL);
    }
    if (s != NEUV_OK) {
        mesh_free(m);
        if (face_origin) { mem_free(*face_origin); *face_origin = NULL; }
        return s;
    }
    *out = m;
    return NEUV_OK;
}

/* Multiplies every position by 2^e: exact (no rounding) for sizes far from
 * the ends of the double range. */
static void scale_positions(neuv_mesh *m, int e)
{
    for (size_t i = 0; i < 3 * (size_t)m->nv; i++) m->pos[i] = ldexp(m->pos[i], e);
}

/* The power of two that brings the diagonal of m's bounding box into [1, 2),
 * or 0 when that diagonal is already within 2^-16 .. 2^24 (ordinary meshes
 * are left as they are, bit for bit). */
static int extreme_scale_exponent(const neuv_mesh *m)
{
    if (m->nv == 0) return 0;
    double lo[3], hi[3];
    mesh_bounding_box(m, lo, hi);
    /* Each extent halved before squaring, so that 1e300 does not overflow. */
    double h = 0;
    for (int k = 0; k < 3; k++) h += (0.5 * hi[k] - 0.5 * lo[k]) * (0.5 * hi[k] - 0.5 * lo[k]);
    double d = 2.0 * sqrt(h);
    if (!(d > 0) || !isfinite(d)) return 0;
    if (d >= ldexp(1.0, -16) && d <= ldexp(1.0, 24)) return 0;
    return -ilogb(d);
}

/* The end of every stage: a cancel asked for during it, or a repair note
 * that did not fit in memory, stops the run. */
static neuv_status stage_end(const struct neuv_unwrap_result *r, neuv_status s)
{
    if (s == NEUV_OK && log_cancelled()) s = error_cancelled();
    if (s == NEUV_OK && r->repairs_lost) s = error_nomem("a repair note");
    return s;
}

/* PatchNet's charts of r->mesh: trained on it, or (category) by the model's inference. */
static neuv_status charts_by_patchnet(struct neuv_unwrap_result *r, const unwrap_plan *plan, float **features_out,
                                      int *feature_dim_out)
{
    const neuv_unwrap_options *o = &r->opts;
    neuv_mesh *m = r->mesh;
    const unwrap_model *category = plan->model;
    int keep_model = plan->keep_model;
    neuv_status s;
    double t;

    if (!category && (s = memory_check_training(m->nf, o->max_memory_mb, "this mesh", MEMORY_BUDGET_HINT)) != NEUV_OK)
        return s;
    t = now_seconds();
    log_progress("operators", 0, NULL);
    operators ops;
    memset(&ops, 0, sizeof ops);
    operators_params op = operators_default_params();
    s = operators_get(m, &op, o->use_cache, &ops, NULL, &r->cache_hit);
    unwrap_stage_time(r, STAGE_OPERATORS, t);
    if (s != NEUV_OK) return s;
    if (log_cancelled()) { operators_free(&ops); return error_cancelled(); }

    t = now_seconds();
    r->face_chart = mem_alloc(sizeof(int) * (size_t)m->nf);
    if (!r->face_chart) { operators_free(&ops); return error_nomem("charts"); }
    patchnet_options po;
    patchnet_default_options(&po);
    if (o->preset == NEUV_PRESET_PAPER) patchnet_apply_preset(&po, "paper");
    po.charts = o->charts;
    po.max_distortion = o->max_distortion;
    po.seed = o->seed;
    if (o->iters > 0) po.iters = o->iters;
    float *features = NULL;
    int feature_dim = 0;
    patchnet_report prep;
    memset(&prep, 0, sizeof prep);
    if (category) {
        po.charts = category->charts_auto ? 0 : category->patchnet->k;
        po.max_distortion = category->max_distortion;
        s = patchnet_charts_from_model(category->patchnet, m, &ops, &po, r->face_chart, &r->n_charts, &features,
                                       &feature_dim, &prep);
        prep.k = category->patchnet->k;
    } else if (keep_model) {
        r->patchnet = mem_calloc(1, sizeof *r->patchnet);
        r->face_label = mem_alloc(sizeof(int) * (size_t)m->nf);
        if (!r->patchnet || !r->face_label) { operators_free(&ops); return error_nomem("the model"); }
    }
    if (!category) {
        s = patchnet_segment_model(m, &ops, &po, r->face_chart, &r->n_charts, &features, &feature_dim, &prep,
                                   r->patchnet);
        /* The argmax labels of the source are kept so that a later --check-inference
         * can measure PatchNet inference on another triangulation against them. */
        if (s == NEUV_OK && keep_model) s = patchnet_infer(r->patchnet, m, &ops, r->face_label);
    }
    operators_free(&ops);
    unwrap_stage_time(r, STAGE_PATCHES, t);
    r->patches = prep.k;
    r->patch_iterations = prep.iterations;
    r->patch_reseeds = prep.reseeds;
    r->patch_iters_per_second = prep.iters_per_second;
    if (s != NEUV_OK) { mem_free(features); return s; }
    *features_out = features;
    *feature_dim_out = feature_dim;
    return NEUV_OK;
}

/* r->face_polygon from the input's polygons, through the cleaned faces'
 * origins; polygons of 3 corners are left out (nothing to keep whole). */
static neuv_status polygons_of_faces(struct neuv_unwrap_result *r, const neuv_mesh *in, const int *face_origin)
{
    const neuv_mesh *m = r->mesh;
    r->polygons = 0;
    for (int p = 0; p < in->np; p++) r->polygons += in->poly_start[p + 1] - in->poly_start[p] > 3;
    if (r->polygons == 0) return NEUV_OK;
    r->face_polygon = mem_alloc(sizeof(int) * (size_t)m->nf);
    if (!r->face_polygon) return error_nomem("the polygons");
    for (int f = 0; f < m->nf; f++) {
        int p = in->face_polygon[face_origin[f]];
        r->face_polygon[f] = in->poly_start[p + 1] - in->poly_start[p] > 3 ? p : -1 - f;
    }
    return NEUV_OK;
}

neuv_status unwrap_stage_charts(struct neuv_unwrap_result *r, const neuv_mesh *in, const unwrap_plan *plan,
                                float **features_out, int *feature_dim_out)
{
    *features_out = NULL;
    *feature_dim_out = 0;
    nn_set_threads(r->opts.threads);
    double t = now_seconds();
    r->input_vertices = in->nv;
    r->input_faces = in->nf;
    int *face_origin = NULL;
    neuv_status s = unwrap_clean_copy(in, &r->mesh, &r->clean, in->np > 0 ? &face_origin : NULL);
    if (s == NEUV_OK && face_origin) s = polygons_of_faces(r, in, face_origin);
    mem_free(face_origin);
    if (s == NEUV_OK) s = unwrap_seams_cut(r, in, plan->keep_model, plan->apply != NULL);
    /* Not for a saved model, made or applied: its stored surface and chart
     * frames are in the mesh's own units. */
    if (s == NEUV_OK && !plan->apply && !plan->keep_model) {
        r->pos_exp = extreme_scale_exponent(r->mesh);
        if (r->pos_exp) scale_positions(r->mesh, r->pos_exp);
    }
    unwrap_stage_time(r, STAGE_CLEAN, t);
    if ((s = stage_end(r, s)) != NEUV_OK) return s;
    if (plan->apply) s = unwrap_apply_charts(r, plan->model, plan->apply);
    else s = charts_by_patchnet(r, plan, features_out, feature_dim_out);
    if (s == NEUV_OK && r->face_polygon)
        s = charts_keep_polygons(r->mesh, r->face_polygon, NULL, r->face_chart, &r->polygons_split);
    if ((s = stage_end(r, s)) != NEUV_OK) {
        mem_free(*features_out);
        *features_out = NULL;
        *feature_dim_out = 0;
    }
    return s;
}

/* The networks' map (trained, inferred or fine-tuned) or the classic
 * method, then the repair loop with its refinement. */
static neuv_status param_by_networks(struct neuv_unwrap_result *r, const unwrap_plan *plan, const float *features,
                                     int feature_dim)
{
    const neuv_unwrap_options *o = &r->opts;
    const unwrap_model *category = plan->model;
    int keep_model = plan->keep_model, finetune = plan->finetune;
    neuv_mesh *m = r->mesh;
    neuv_status s = NEUV_OK;
    double *corner_uv = NULL;
    double t = now_seconds();
    r->refine_seconds = 0;
    if (o->method == NEUV_METHOD_NEURAL) {
        corner_uv = mem_alloc(sizeof(double) * 6 * (size_t)m->nf);
        if (!corner_uv) return error_nomem("UVs");
        param_net_options pp;
        param_net_default_options(&pp, o->preset == NEUV_PRESET_PAPER ? PARAM_PRESET_PAPER : PARAM_PRESET_FAST);
        pp.seed = o->seed;
        /* Kept in any case: a chart the networks fold is split and their
         * output layer solved on each piece (flatten_and_repair). */
        pp.keep_model = 1;
        if (o->iters > 0) pp.iters = o->iters;
        param_net_report pr;
        memset(&pr, 0, sizeof pr);
        if (category && finetune == 0) {
            /* The shape model (this shape's charts over the category's
             * networks) lets a folded chart's pieces get heads of their own. */
            s = param_net_infer(category->param, m, r->face_chart, r->n_charts, features, feature_dim,
                                !r->model.shared_layer, corner_uv, &pr, &pr.model);
        } else {
            if (category) { /* fine-tuning: the model's networks, trained `finetune` more steps */
                pp.width = category->param->f.width;
                pp.depth = category->param->f.depth;
                pp.init = category->param;
                pp.iters = pp.min_iters = finetune;
            }
            s = param_net_flatten(m, r->face_chart, r->n_charts, features, feature_dim, &pp, corner_uv, &pr);
        }
        r->param_iterations = pr.iters;
        r->param_face_points = pr.face_points;
        r->param_loss = pr.loss;
        r->param = pr.model;
    }
    unwrap_stage_time(r, STAGE_PARAM, t);
    if (s == NEUV_OK && log_cancelled()) s = error_cancelled();
    if (s != NEUV_OK) { mem_free(corner_uv); return s; }

    t = now_seconds();
    chart_piece *pieces = NULL;
    int cap = 0;
    s = flatten_and_repair(r, m, corner_uv, &pieces, &cap);
    mem_free(corner_uv);
    if (category && finetune == 0) { /* it borrows the category's networks: not kept past them */
        param_net_model_free(r->param);
        r->param = NULL;
    }
    if (s == NEUV_OK) s = unwrap_assemble_uvs(m, pieces, r->n_charts);
    if (s == NEUV_OK) s = unwrap_keep_provenance(r, pieces);
    if (s == NEUV_OK && keep_model) {
        r->chart_net = mem_alloc(sizeof(int) * (size_t)r->n_charts);
        r->chart_mirrored = mem_alloc(sizeof(int) * (size_t)r->n_charts);
        r->chart_tried = mem_alloc(sizeof(int) * (size_t)r->n_charts);
        if (!r->chart_net || !r->chart_mirrored || !r->chart_tried) s = error_nomem("the model");
        for (int c = 0; s == NEUV_OK && c < r->n_charts; c++) {
            r->chart_net[c] = pieces[c].net;
            r->chart_mirrored[c] = pieces[c].mirrored;
            r->chart_tried[c] = pieces[c].net >= 0 ? pieces[c].net : pieces[c].tried;
        }
    }
    for (int c = 0; c < cap; c++) unwrap_piece_clear(&pieces[c]);
    mem_free(pieces);
    /* The refinement ran chart by chart in the repair loop; it belongs to the parameterization. */
    unwrap_stage_time(r, STAGE_REPAIR, t);
    r->seconds[STAGE_REPAIR] -= r->refine_seconds;
    r->seconds[STAGE_PARAM] += r->refine_seconds;
    return s;
}

neuv_status unwrap_stage_param(struct neuv_unwrap_result *r, const unwrap_plan *plan, const float *features,
                               int feature_dim)
{
    neuv_status s = plan->apply ? unwrap_apply_param(r, plan->model, plan->apply)
                                : param_by_networks(r, plan, features, feature_dim);
    return stage_end(r, s);
}

/* The transform that applies `first`, then `then`: then(first(u)) =
 * s2 R2 (s1 R1 u + t1) + t2 = s1 s2 R(a1 + a2) u + then(t1). */
static atlas_chart_transform compose_transforms(const atlas_chart_transform *first, const atlas_chart_transform *then)
{
    double t1[2] = {first->tx, first->ty}, t[2];
    atlas_chart_transform_apply(then, t1, t);
    atlas_chart_transform c = {first->scale * then->scale, first->angle + then->angle, t[0], t[1]};
    return c;
}

/* Charts split where they pack badly, then packed afresh. */
static neuv_status pack_afresh(struct neuv_unwrap_result *r)
{
    const neuv_unwrap_options *o = &r->opts;
    neuv_mesh *m = r->mesh;
    neuv_status s;
    double t = now_seconds();
    log_progress("pack", 0, "%d charts", r->n_charts);
    if ((s = split_for_packing(r, m)) != NEUV_OK) return s;
    mem_free(r->transforms);
    r->transforms = mem_calloc((size_t)r->n_charts, sizeof *r->transforms);
    if (!r->transforms) return error_nomem("chart transforms");
    atlas_pack_options pk;
    atlas_pack_options_default(&pk);
    pk.resolution = o->resolution;
    pk.padding = o->padding;
    /* Pixels per unit of the mesh as packed: its positions may be scaled by 2^pos_exp. */
    pk.texels_per_unit = ldexp(o->texels_per_unit, -r->pos_exp);
    s = atlas_pack(m, r->face_chart, r->n_charts, &pk, r->transforms, &r->pack);
    if (s == NEUV_OK && r->frame_xf) /* the networks' frame to the atlas: the frame's transform, then the packing's */
        for (int c = 0; c < r->n_charts; c++)
            r->transforms[c] = compose_transforms(&r->frame_xf[c], &r->transforms[c]);
    mem_free(r->frame_xf);
    r->frame_xf = NULL;
    unwrap_stage_time(r, STAGE_PACK, t);
    return s;
}

neuv_status unwrap_stage_pack(struct neuv_unwrap_result *r, const unwrap_plan *plan)
{
    /* A simplified copy's layout is nobody's texture: the charts of its
     * model, mapped and refined on this mesh, are packed as a per-shape
     * unwrap packs its own. */
    int fresh = !plan->apply || plan->apply->refine_on_mesh;
    neuv_status s = fresh ? pack_afresh(r) : unwrap_apply_place(r, plan->apply);
    if (s != NEUV_OK) return s;
    if (plan->apply && fresh) r->model.repacked = 1;
    if (plan->model) /* the model's inference: every stage after cleaning, the metrics aside */
        r->model.inference_seconds = r->seconds[STAGE_PATCHES] + r->seconds[STAGE_PARAM] +
                                     r->seconds[STAGE_REPAIR] + r->seconds[STAGE_PACK] +
                                     (plan->apply ? 0 : r->seconds[STAGE_OPERATORS]);

    /* The input's own size back (UVs are packed into [0,1]^2 and keep theirs). */
    if (r->pos_exp) {
        scale_positions(r->mesh, -r->pos_exp);
        r->pos_exp = 0;
    }
    if ((s = unwrap_seams_join(r)) != NEUV_OK) return s;
    if (r->face_polygon) r->polygons_split = charts_count_split_polygons(r->mesh->nf, r->face_polygon, r->face_chart);
    /* The metrics of the mesh as `neuv eval` will read it back (positions welded). */
    double t = now_seconds();
    s = unwrap_metrics(r->mesh, &r->metrics);
    unwrap_stage_time(r, STAGE_METRICS, t);
    return stage_end(r, s);
}

neuv_status unwrap_run_stages(struct neuv_unwrap_result *r, const neuv_mesh *in, const unwrap_plan *plan)
{
    float *features = NULL;
    int feature_dim = 0;
    neuv_status s = unwrap_stage_charts(r, in, plan, &features, &feature_dim);
    if (s == NEUV_OK) s = unwrap_stage_param(r, plan, features, feature_dim);
    mem_free(features);
    if (s == NEUV_OK) s = unwrap_stage_pack(r, plan);
    return s;
}

static void *copy_block(const void *src, size_t bytes, int *failed)
{
    if (!src) return NULL;
    void *d = mem_alloc(bytes ? bytes : 1);
    if (!d) { *failed = 1; return NULL; }
    memcpy(d, src, bytes);
    return d;
}

neuv_status unwrap_result_clone(const struct neuv_unwrap_result *r, struct neuv_unwrap_result **out)
{
    *out = NULL;
    struct neuv_unwrap_result *c = mem_calloc(1, sizeof *c);
    if (!c) return error_nomem("the result");
    *c = *r;
    c->chart_net = c->chart_mirrored = c->chart_tried = c->face_label = NULL;
    c->frame_xf = NULL; /* lives only between the apply's parameterization and its packing */
    c->patchnet = NULL;
    c->param = NULL;
    int failed = 0;
    size_t nc = (size_t)r->n_charts;
    c->mesh = r->mesh ? mesh_clone(r->mesh) : NULL;
    if (r->mesh && !c->mesh) failed = 1;
    c->face_chart = copy_block(r->face_chart, sizeof(int) * (size_t)(r->mesh ? r->mesh->nf : 0), &failed);
    c->chart_source = copy_block(r->chart_source, sizeof(int) * nc, &failed);
    c->chart_net_qce = copy_block(r->chart_net_qce, sizeof(double) * nc, &failed);
    c->chart_lscm_qce = copy_block(r->chart_lscm_qce, sizeof(double) * nc, &failed);
    c->transforms = copy_block(r->transforms, sizeof *r->transforms * nc, &failed);
    c->repairs = copy_block(r->repairs, sizeof *r->repairs * (size_t)r->n_repairs, &failed);
    c->model.source_chart = copy_block(r->model.source_chart, sizeof(int) * nc, &failed);
    c->model.vertex_source_chart =
        copy_block(r->model.vertex_source_chart, sizeof(int) * (size_t)(r->mesh ? r->mesh->nv : 0), &failed);
    c->seam_pair = copy_block(r->seam_pair, sizeof(int) * 2 * (size_t)r->seam_edges, &failed);
    c->seam_origin = copy_block(r->seam_origin, sizeof(int) * (size_t)(r->mesh ? r->mesh->nv : 0), &failed);
    c->face_polygon = copy_block(r->face_polygon, sizeof(int) * (size_t)(r->mesh ? r->mesh->nf : 0), &failed);
    c->cap_repairs = c->repairs ? r->n_repairs : 0;
    if (failed) { neuv_unwrap_result_free(c); return error_nomem("a copy of the result"); }
    *out = c;
    return NEUV_OK;
}

neuv_status unwrap_result_new(const neuv_unwrap_options *opts, struct neuv_unwrap_result **out)
{
    *out = NULL;
    struct neuv_unwrap_result *r = mem_calloc(1, sizeof *r);
    if (!r) return error_nomem("the result");
    if (opts) r->opts = *opts;
    else neuv_unwrap_options_init(&r->opts);
    int res = r->opts.resolution, pad = r->opts.padding;
    if (res < 64 || res > 16384) {
        mem_free(r);
        return error_set(NEUV_ERR_INPUT, "the atlas resolution must be in 64..16384 pixels (got %d)", res);
    }
    if (pad < 0 || pad > res / 8) {
        mem_free(r);
        return error_set(NEUV_ERR_INPUT, "the padding must be in 0..resolution/8 = 0..%d pixels (got %d)", res / 8, pad);
    }
    double tpu = r->opts.texels_per_unit;
    if (!(tpu >= 0) || !isfinite(tpu)) {
        mem_free(r);
        return error_set(NEUV_ERR_INPUT, "texels_per_unit must be a finite number >= 0 (0: off), got %g", tpu);
    }
    if (tpu > 0 && r->opts.keep_model) {
        mem_free(r);
        return error_set(NEUV_ERR_INPUT, "texels_per_unit cannot be used with keep_model: a model records a layout "
                                         "in one square, not in tiles");
    }
    nn_set_threads(r->opts.threads);
    r->model.label_agreement = -1;
    *out = r;
    return NEUV_OK;
}

neuv_status unwrap_train(const neuv_mesh *mesh, const neuv_unwrap_options *opts, int keep_model,
                         neuv_unwrap_result **out)
{
    *out = NULL;
    if (!mesh || mesh->nf == 0) return error_set(NEUV_ERR_INPUT, "no faces: neuv needs a triangle mesh");
    struct neuv_unwrap_result *r = NULL;
    neuv_status s = unwrap_result_new(opts, &r);
    if (s != NEUV_OK) return s;
    unwrap_plan plan = {NULL, keep_model, 0, NULL};
    s = unwrap_run_stages(r, mesh, &plan);
    if (s != NEUV_OK) { neuv_unwrap_result_free(r); return s; }
    *out = r;
    return NEUV_OK;
}

neuv_status unwrap_with_category(const neuv_mesh *mesh, const unwrap_model *category, const neuv_unwrap_options *opts,
                                 int finetune, int shared_layer, int keep_model, neuv_unwrap_result **out)
{
    *out = NULL;
    if (!mesh || mesh->nf == 0) return error_set(NEUV_ERR_INPUT, "no faces: neuv needs a triangle mesh");
    if (!category || !category->category || !category->patchnet || !category->param)
        return error_set(NEUV_ERR_INPUT, "not a category model");
    if (keep_model && finetune <= 0)
        return error_set(NEUV_ERR_INPUT, "keep_model needs finetune > 0: inference trains no networks of this shape's");
    struct neuv_unwrap_result *r = mem_calloc(1, sizeof *r);
    if (!r) return error_nomem("the result");
    neuv_unwrap_options_init(&r->opts);
    r->opts.method = NEUV_METHOD_NEURAL;
    r->opts.preset = category->preset;
    r->opts.seed = category->seed;
    r->opts.refine = category->refine;
    r->opts.resolution = category->resolution;
    r->opts.padding = category->padding;
    r->opts.max_distortion = category->max_distortion;
    if (opts) {
        r->opts.threads = opts->threads;
        r->opts.use_cache = opts->use_cache;
        r->opts.allow_overlaps = opts->allow_overlaps;
    }
    nn_set_threads(r->opts.threads);
    r->model.label_agreement = -1;
    r->model.used = 1;
    r->model.category = 1;
    r->model.finetune = finetune;
    r->model.shared_layer = shared_layer;
    unwrap_plan plan = {category, keep_model, finetune, NULL};
    neuv_status s = unwrap_run_stages(r, mesh, &plan);
    if (s != NEUV_OK) { neuv_unwrap_result_free(r); return s; }
    r->model.network_charts = r->neural_charts;
    *out = r;
    return NEUV_OK;
}

const neuv_mesh *neuv_unwrap_mesh(const neuv_unwrap_result *r) { return r ? r->mesh : NULL; }
int neuv_unwrap_chart_count(const neuv_unwrap_result *r) { return r ? r->n_charts : 0; }

void neuv_unwrap_result_free(neuv_unwrap_result *r)
{
    if (!r) return;
    mesh_free(r->mesh);
    mem_free(r->face_chart);
    mem_free(r->transforms);
    mem_free(r->frame_xf);
    mem_free(r->repairs);
    mem_free(r->chart_net);
    mem_free(r->chart_mirrored);
    mem_free(r->chart_tried);
    mem_free(r->chart_source);
    mem_free(r->chart_net_qce);
    mem_free(r->chart_lscm_qce);
    mem_free(r->face_label);
    mem_free(r->model.source_chart);
    mem_free(r->model.vertex_source_chart);
    mem_free(r->seam_pair);
    mem_free(r->seam_origin);
    mem_free(r->face_polygon);
    if (r->patchnet) patchnet_model_free(r->patchnet);
    mem_free(r->patchnet);
    param_net_model_free(r->param);
    mem_free(r);
}
