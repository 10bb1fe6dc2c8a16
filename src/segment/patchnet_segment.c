/* PatchNet's charts: see patchnet_segment.h.
 *
 * Decisions (measured, see bench/RESULTS.md "PatchNet (issue 6)"):
 *   - Auto K splits failing charts with charts_split instead of retraining
 *     with a larger K: one LSCM per new chart costs milliseconds, a retrain
 *     costs the whole training time again, and the split loop always
 *     terminates on a disk that flattens (small enough charts are nearly flat).
 *   - After the split loop, adjacent charts merge back while the union
 *     flattens with qce_mean < 1.03 and fills >= 0.8 of its UV convex hull:
 *     merging up to the split limit 1.15 left spot with 2 charts, qce_mean
 *     1.12 and packing 0.55; 1.05 gave 7 charts and qce_mean 1.049, too
 *     close to the 1.05 bar; without the convexity rule cow packed at 0.24
 *     (bench/RESULTS.md "Charts quality (issues 6-7)"). */
#include "segment/patchnet_segment.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "charts/charts.h"
#include "core/error.h"
#include "core/log.h"
#include "core/mem.h"
#include "core/timer.h"
#include "segment/chart_judge.h"

/* Grows a per-chart array to n entries (new entries: dirty). */
static neuv_status grow_quality(double **q, int **flip, int **dirty, int *cap, int n)
{
    if (n <= *cap) return NEUV_OK;
    int c = *cap ? *cap : 16;
    while (c < n) c *= 2;
    double *nq = mem_realloc(*q, sizeof(double) * (size_t)c);
    if (!nq) return error_nomem("chart qualities");
    *q = nq;
    int *nfl = mem_realloc(*flip, sizeof(int) * (size_t)c);
    if (!nfl) return error_nomem("chart qualities");
    *flip = nfl;
    int *nd = mem_realloc(*dirty, sizeof(int) * (size_t)c);
    if (!nd) return error_nomem("chart qualities");
    *dirty = nd;
    for (int i = *cap; i < c; i++) { nd[i] = 1; nq[i] = INFINITY; nfl[i] = 0; }
    *cap = c;
    return NEUV_OK;
}

/* Merges adjacent charts back together while the union still flattens:
 * the split loop and the argmax both cut more than needed (a split can go
 * across a chart that one of its neighbours could take whole). Pairs are
 * tried longest shared boundary first, each chart in one merge per round;
 * a merge stands when the union is a disk whose LSCM has qce_mean below
 * `limit`, no flipped face, no boundary self-crossing, and a UV footprint
 * filling at least min_cvx of its convex hull (snakes and combs pack badly). The surviving
 * ids are compacted in order, with their qualities. */
static neuv_status merge_charts(const neuv_mesh *m, double limit, double min_cvx, int *face_chart,
                                int *n_charts, double *q, int *flip, int *merges)
{
    int nf = m->nf;
    int *gone = NULL, *moved = NULL, *order = NULL;
    double *len = NULL;
    neuv_status st = NEUV_OK;
    for (;;) {
        chart_adjacency adj;
        if ((st = chart_adjacency_build(m, face_chart, &adj))) break;
        int nc = *n_charts;
        mem_free(gone); mem_free(moved); mem_free(order); mem_free(len);
        gone = mem_calloc((size_t)nc, sizeof(int));
        moved = mem_alloc(sizeof(int) * (size_t)nf);
        order = mem_alloc(sizeof(int) * (size_t)(adj.n > 0 ? adj.n : 1));
        len = mem_alloc(sizeof(double) * (size_t)(adj.n > 0 ? adj.n : 1));
        if (!gone || !moved || !order || !len) { chart_adjacency_free(&adj); st = error_nomem("chart merge"); break; }
        /* Insertion order by length, descending (ties: pair order), stable. */
        for (int i = 0; i < adj.n; i++) {
            int j = i;
            while (j > 0 && adj.length[order[j - 1]] < adj.length[i]) { order[j] = order[j - 1]; j--; }
            order[j] = i;
        }
        int any = 0;
        for (int r = 0; r < adj.n && !st; r++) {
            int a = adj.a[order[r]], b = adj.b[order[r]];
            if (gone[a] || gone[b] || gone[a] < 0 || gone[b] < 0) continue;
            int n = 0;
            for (int f = 0; f < nf; f++)
                if (face_chart[f] == b) { face_chart[f] = a; moved[n++] = f; }
            int disk = chart_is_disk(m, face_chart, a);
            double qa = INFINITY;
            int fl = 1, cross = 1;
            double cvx = 0;
            if (disk < 0) st = error_nomem("chart merge");
            else if (disk) st = chart_lscm_judge(m, face_chart, a, &qa, &fl, &cross, &cvx);
            if (!st && disk == 1 && qa < limit && fl == 0 && cross == 0 && cvx >= min_cvx) {
                q[a] = qa;
                flip[a] = 0;
                gone[b] = 1;
                gone[a] = -1; /* changed: no second merge this round */
                any = 1;
                (*merges)++;
            } else {
                for (int i = 0; i < n; i++) face_chart[moved[i]] = b;
            }
        }
        chart_adjacency_free(&adj);
        if (st || !any) break;
        /* Compact: new id = old id minus the merged-away ids below it. */
        int k = 0;
        for (int c = 0; c < nc; c++) {
            int keep = gone[c] != 1;
            if (keep) { q[k] = q[c]; flip[k] = flip[c]; gone[c] = k++; }
            else gone[c] = -2;
        }
        for (int f = 0; f < nf; f++) face_chart[f] = gone[face_chart[f]];
        *n_charts = k;
    }
    mem_free(gone); mem_free(moved); mem_free(order); mem_free(len);
    return st;
}

/* The chart check and split loop (auto K), or only the check (fixed K). */
static neuv_status refine_charts(const neuv_mesh *m, const patchnet_options *o, int *face_chart, int *n_charts,
                                 patchnet_report *rep)
{
    double t0 = now_seconds();
    double *q = NULL;
    int *flip = NULL, *dirty = NULL, cap = 0, splits = 0;
    int *count = NULL;
    neuv_status st = grow_quality(&q, &flip, &dirty, &cap, *n_charts);
    int auto_k = o->charts <= 0;
    int max_charts = o->max_charts > 0 ? o->max_charts : 64;
    while (!st) {
        for (int c = 0; c < *n_charts && !st; c++)
            if (dirty[c]) {
                int cross = 0;
                st = chart_lscm_judge(m, face_chart, c, &q[c], &flip[c], &cross, NULL);
                /* A self-overlapping boundary fails like a flip. */
                flip[c] += cross;
                dirty[c] = 0;
            }
        if (st || !auto_k) break;
        /* Failing charts, worst first, each split once this round. */
        mem_free(count);
        count = mem_calloc((size_t)*n_charts, sizeof(int));
        if (!count) { st = error_nomem("chart sizes"); break; }
        for (int f = 0; f < m->nf; f++) count[face_chart[f]]++;
        int any = 0;
        for (;;) {
            int worst = -1;
            double wq = 0;
            for (int c = 0; c < *n_charts; c++) {
                if (dirty[c] || count[c] < 2) continue;
                int fails = !(q[c] < o->max_distortion) || flip[c] > 0;
                double score = flip[c] > 0 ? INFINITY : q[c];
                if (fails && (worst < 0 || score > wq)) { worst = c; wq = score; }
            }
            if (worst < 0 || *n_charts >= max_charts) break;
            int before = *n_charts;
            if ((st = charts_split(m, face_chart, n_charts, worst))) break;
            if ((st = grow_quality(&q, &flip, &dirty, &cap, *n_charts))) break;
            dirty[worst] = 1;
            for (int c = before; c < *n_charts; c++) dirty[c] = 1;
            splits++;
            any = 1;
        }
        if (!any) break;
        log_progress("charts", 1.0, "%d charts after %d splits", *n_charts, splits);
    }
    /* Merging back is stricter than the split loop (see this file's header
     * and bench/RESULTS.md): a union passes under merge_distortion and
     * min_convexity, or the mean distortion and the packing suffer. */
    int merges = 0;
    if (!st && auto_k && o->merge_distortion > 0)
        st = merge_charts(m, o->merge_distortion, o->min_convexity, face_chart, n_charts, q, flip, &merges);
    if (!st && rep) {
        rep->merges = merges;
        rep->splits = splits;
        rep->charts = *n_charts;
        rep->worst_qce = 0;
        rep->flipped = 0;
        for (int c = 0; c < *n_charts; c++) {
            if (q[c] > rep->worst_qce) rep->worst_qce = q[c];
            rep->flipped += flip[c];
        }
        rep->chart_check_seconds = now_seconds() - t0;
    }
    mem_free(q); mem_free(flip); mem_free(dirty); mem_free(count);
    return st;
}

neuv_status patchnet_charts_from_model(const patchnet_model *model, const neuv_mesh *m, const operators *ops,
                                      const patchnet_options *o, int *face_chart, int *n_charts,
                                      float **vertex_features, int *feature_dim, patchnet_report *rep)
{
    patchnet_options def;
    if (!o) { patchnet_default_options(&def); o = &def; }
    if (vertex_features) *vertex_features = NULL;
    if (feature_dim) *feature_dim = 0;
    patchnet_report local;
    if (!rep) { rep = &local; memset(rep, 0, sizeof *rep); }
    int *label = mem_alloc(sizeof(int) * (size_t)m->nf);
    if (!label) return error_nomem("patch labels");
    neuv_status st = patchnet_infer_features(model, m, ops, label, vertex_features, feature_dim);
    if (!st) {
        charts_options copt;
        charts_default_options(&copt);
        if (o->min_area_share > 0) copt.min_area_share = o->min_area_share;
        st = charts_from_labels(m, label, &copt, face_chart, n_charts, NULL);
    }
    if (!st) {
        rep->label_charts = *n_charts;
        st = refine_charts(m, o, face_chart, n_charts, rep);
    }
    mem_free(label);
    if (st && vertex_features) { mem_free(*vertex_features); *vertex_features = NULL; }
    return st;
}

neuv_status patchnet_segment_model(const neuv_mesh *m, const operators *ops, const patchnet_options *o,
                                   int *face_chart, int *n_charts, float **vertex_features, int *feature_dim,
                                   patchnet_report *rep, patchnet_model *model_out)
{
    double t0 = now_seconds();
    patchnet_options def;
    if (!o) { patchnet_default_options(&def); o = &def; }
    if (vertex_features) *vertex_features = NULL;
    if (feature_dim) *feature_dim = 0;
    if (model_out) memset(model_out, 0, sizeof *model_out);
    if (!m || !ops || m->nf < 1) return error_set(NEUV_ERR_INPUT, "PatchNet: mesh has no faces");
    patchnet_report local;
    if (!rep) rep = &local;
    memset(rep, 0, sizeof *rep);
    int k = o->charts > 0 ? o->charts : (o->initial_charts > 0 ? o->initial_charts : 8);
    if (k > m->nf) k = m->nf;
    patchnet_model model;
    neuv_status st = patchnet_model_create_for_mesh(&model, o, m, ops, k);
    if (st) return st;
    if ((st = patchnet_train(&model, m, ops, o, rep))) goto done;
    if ((st = patchnet_charts_from_model(&model, m, ops, o, face_chart, n_charts, vertex_features, feature_dim,
                                         rep)))
        goto done;
    rep->seconds = now_seconds() - t0;
done:
    if (!st && model_out) *model_out = model;
    else patchnet_model_free(&model);
    return st;
}

neuv_status patchnet_segment(const neuv_mesh *m, const operators *ops, const patchnet_options *o,
                             int *face_chart, int *n_charts, float **vertex_features, int *feature_dim,
                             patchnet_report *rep)
{
    return patchnet_segment_model(m, ops, o, face_chart, n_charts, vertex_features, feature_dim, rep, NULL);
}
