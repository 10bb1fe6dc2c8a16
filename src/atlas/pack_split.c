/* Splitting charts for packing: see pack_split.h. */
#include "atlas/pack_split.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "atlas/convex_hull.h"
#include "charts/charts.h"
#include "core/error.h"
#include "core/log.h"
#include "core/mem.h"
#include "core/timer.h"

void pack_split_default_options(pack_split_options *o)
{
    o->max_trials = 16;
    o->max_splits = 12;
    o->max_charts = 64;
    o->max_convexity = 0.8;
    o->min_gain = 0.005;
    atlas_pack_options_default(&o->pack);
}

/* UV area over convex-hull area of every chart (1 for a chart with no area). */
static neuv_status chart_convexity(const neuv_mesh *m, const int *face_chart, int n_charts, double *cvx)
{
    int *count = mem_calloc((size_t)n_charts + 1, sizeof(int));
    int *start = mem_calloc((size_t)n_charts + 2, sizeof(int));
    double *pts = mem_alloc(sizeof(double) * 6 * (size_t)m->nf);
    int *hull = mem_alloc(sizeof(int) * 3 * (size_t)m->nf);
    double *area = mem_calloc((size_t)n_charts + 1, sizeof(double));
    neuv_status s = NEUV_OK;
    if (!count || !start || !pts || !hull || !area) { s = error_nomem("chart convexity"); goto done; }
    for (int f = 0; f < m->nf; f++) count[face_chart[f]]++;
    for (int c = 0; c < n_charts; c++) start[c + 1] = start[c] + count[c];
    memset(count, 0, sizeof(int) * (size_t)n_charts);
    for (int f = 0; f < m->nf; f++) {
        int c = face_chart[f], at = start[c] + count[c]++;
        const double *a = m->uv + 2 * m->tri_uv[3 * f], *b = m->uv + 2 * m->tri_uv[3 * f + 1],
                     *d = m->uv + 2 * m->tri_uv[3 * f + 2];
        memcpy(pts + 6 * (size_t)at, a, 2 * sizeof(double));
        memcpy(pts + 6 * (size_t)at + 2, b, 2 * sizeof(double));
        memcpy(pts + 6 * (size_t)at + 4, d, 2 * sizeof(double));
        area[c] += 0.5 * fabs((b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]));
    }
    for (int c = 0; c < n_charts; c++) {
        int n = 3 * (start[c + 1] - start[c]);
        const double *p = pts + 6 * (size_t)start[c];
        int h = convex_hull_2d(p, n, hull);
        if (h < 0) { s = error_nomem("chart convexity"); break; }
        double ha = 0;
        for (int i = 0; i < h; i++) {
            const double *u = p + 2 * hull[i], *v = p + 2 * hull[(i + 1) % h];
            ha += 0.5 * (u[0] * v[1] - u[1] * v[0]);
        }
        cvx[c] = ha > 0 ? area[c] / ha : 1;
    }
done:
    mem_free(count); mem_free(start); mem_free(pts); mem_free(hull); mem_free(area);
    return s;
}

#define TRIAL_RESOLUTION 256

/* Efficiency of a quick packing of m with these charts (m is not modified). */
static neuv_status trial_pack(const neuv_mesh *m, const int *face_chart, int n_charts, const atlas_pack_options *po,
                              double *eff)
{
    neuv_mesh *c = mesh_clone(m);
    if (!c) return error_nomem("trial packing");
    atlas_pack_options q = *po;
    q.quick = 1;
    q.texels_per_unit = 0; /* the trials compare chart sets by how well they fill one square */
    /* A quarter of the atlas side: the trials compare chart sets, and a
     * packing costs about the square of the side. */
    if (q.resolution > TRIAL_RESOLUTION) {
        q.padding = (int)ceil(q.padding * (double)TRIAL_RESOLUTION / q.resolution);
        q.resolution = TRIAL_RESOLUTION;
    }
    atlas_pack_result res;
    neuv_status s = atlas_pack(c, face_chart, n_charts, &q, NULL, &res);
    mesh_free(c);
    if (s == NEUV_OK) *eff = res.efficiency;
    return s;
}

/* One chart's trial cut: the atlas's charts with it cut, and their quick packing. */
typedef struct split_trial {
    int chart;
    int skip;       /* fewer than two faces: passed over, no trial */
    int *face_chart; /* #F, the charts with this one cut */
    int n;          /* their count */
    double eff;     /* their quick packing's efficiency */
    neuv_status s;  /* NEUV_OK, or why the cut or its packing failed */
} split_trial;

/* Trial t against the atlas face_chart (n charts): the cut and its quick packing. */
static void run_trial(const neuv_mesh *m, const int *face_chart, int n, const atlas_pack_options *po, split_trial *t)
{
    if (t->skip) return;
    memcpy(t->face_chart, face_chart, sizeof(int) * (size_t)m->nf);
    t->n = n;
    t->s = charts_split(m, t->face_chart, &t->n, t->chart);
    if (t->s == NEUV_OK) t->s = trial_pack(m, t->face_chart, t->n, po, &t->eff);
}

static int grow(int **a, int *cap, int need)
{
    if (need <= *cap) return 0;
    int nc = *cap ? *cap : 16;
    while (nc < need) nc *= 2;
    int *na = mem_realloc(*a, sizeof(int) * (size_t)nc);
    if (!na) return -1;
    *a = na;
    *cap = nc;
    return 0;
}

neuv_status pack_split_charts(const neuv_mesh *m, int *face_chart, int *n_charts, const pack_split_options *opts,
                              int **parent_out, pack_split_report *rep)
{
    pack_split_options o;
    if (opts) o = *opts;
    else pack_split_default_options(&o);
    pack_split_report local;
    if (!rep) rep = &local;
    memset(rep, 0, sizeof *rep);
    *parent_out = NULL;
    if (!m || m->nuv <= 0 || !m->tri_uv || *n_charts < 1)
        return error_set(NEUV_ERR_INPUT, "splitting for packing needs a mesh with UVs and charts");
    double t0 = now_seconds();
    int n = *n_charts, cap = 0, *parent = NULL, *tried = NULL, tcap = 0;
    int width = omp_get_max_threads() > 1 ? omp_get_max_threads() : 1;
    if (width > o.max_trials) width = o.max_trials > 0 ? o.max_trials : 1;
    /* Picks for one round: up to `width` trials and the small charts passed
     * over between them, each chart once (so at most as many as the charts). */
    split_trial *pick = NULL;
    int pick_cap = 0;
    int *trial = mem_alloc(sizeof(int) * (size_t)m->nf * (size_t)width);
    double *cvx = NULL;
    neuv_status s = NEUV_OK;
    if (!trial || grow(&parent, &cap, n) || grow(&tried, &tcap, n)) { s = error_nomem("chart splitting"); goto done; }
    for (int c = 0; c < n; c++) { parent[c] = c; tried[c] = 0; }
    if (n > o.max_charts || o.max_trials <= 0) goto done;
    double eff;
    /* A trial that cannot be made (a chart charts_split refuses, a packing
     * that does not fit at the trial size) is a rejected trial; only running
     * out of memory stops the stage with an error. */
    if ((s = trial_pack(m, face_chart, n, &o.pack, &eff)) != NEUV_OK) goto done;
    rep->efficiency_before = rep->efficiency_after = eff;
    int cvx_charts = 0; /* charts cvx was computed for: it changes only with a kept cut */
    while (rep->trials < o.max_trials && rep->splits < o.max_splits && n < o.max_charts) {
        if (cvx_charts != n) {
            mem_free(cvx);
            cvx = mem_alloc(sizeof(double) * (size_t)n);
            if (!cvx) { s = error_nomem("chart splitting"); break; }
            if ((s = chart_convexity(m, face_chart, n, cvx)) != NEUV_OK) break;
            cvx_charts = n;
        }
        /* The charts the one-by-one rule would try next if every trial were
         * rejected: least convex first, then lowest id (a chart of fewer
         * than two faces is passed over without a trial). Up to `width` of
         * them are tried side by side against the same atlas; their results
         * are then taken in that order, as one by one, up to the first kept
         * cut, and the trials past it (made against an atlas that no longer
         * stands) are dropped. So the cuts kept are those of the one-by-one
         * rule on any number of threads. */
        if (pick_cap < n) {
            split_trial *p = mem_realloc(pick, sizeof *pick * (size_t)n);
            if (!p) { s = error_nomem("chart splitting"); break; }
            pick = p;
            pick_cap = n;
        }
        int npick = 0, ntry = 0;
        while (ntry < width && rep->trials + ntry < o.max_trials) {
            int worst = -1;
            for (int c = 0; c < n; c++)
                if (!tried[c] && cvx[c] < o.max_convexity && (worst < 0 || cvx[c] < cvx[worst])) worst = c;
            if (worst < 0) break;
            tried[worst] = 1; /* for this pick only: set again below as the results are taken */
            int faces = 0;
            for (int f = 0; f < m->nf; f++) faces += face_chart[f] == worst;
            pick[npick] = (split_trial){.chart = worst, .skip = faces < 2, .face_chart = trial + (size_t)m->nf * ntry};
            ntry += faces >= 2;
            npick++;
        }
        for (int i = 0; i < npick; i++) tried[pick[i].chart] = 0;
        if (npick == 0) break;
        /* One trial alone runs outside any parallel construct, so that its
         * packing's own parallel loops get the threads (inside even a
         * one-thread region they are nested, and slower than serial). */
        if (ntry > 1) {
#pragma omp parallel for schedule(dynamic, 1)
            for (int i = 0; i < npick; i++) run_trial(m, face_chart, n, &o.pack, &pick[i]);
        } else {
            for (int i = 0; i < npick; i++) run_trial(m, face_chart, n, &o.pack, &pick[i]);
        }
        int kept = -1;
        for (int i = 0; i < npick && kept < 0; i++) {
            split_trial *t = &pick[i];
            tried[t->chart] = 1;
            if (t->skip) continue;
            rep->trials++;
            if (t->s == NEUV_ERR_NOMEM) { s = error_nomem("a trial packing"); break; } /* its message was the worker's */
            if (t->s != NEUV_OK) continue; /* a cut charts_split refuses, or a packing that does not fit */
            log_progress("pack", 0, "split chart %d: packing %.3f -> %.3f", t->chart, eff, t->eff);
            if (t->eff >= eff * (1 + o.min_gain)) kept = i;
        }
        if (s != NEUV_OK) break;
        if (kept < 0) continue;
        split_trial *t = &pick[kept];
        int worst = t->chart, n2 = t->n;
        if (grow(&parent, &cap, n2) || grow(&tried, &tcap, n2)) { s = error_nomem("chart splitting"); break; }
        for (int c = n; c < n2; c++) { parent[c] = parent[worst]; tried[c] = 0; }
        tried[worst] = 0; /* its remaining part may be worth another cut */
        memcpy(face_chart, t->face_chart, sizeof(int) * (size_t)m->nf);
        n = n2;
        eff = t->eff;
        rep->splits++;
        rep->efficiency_after = eff;
    }
done:
    mem_free(pick);
    mem_free(trial);
    mem_free(tried);
    mem_free(cvx);
    if (s != NEUV_OK && s != NEUV_ERR_NOMEM) s = NEUV_OK; /* the charts stand as they were */
    rep->seconds = now_seconds() - t0;
    if (s != NEUV_OK) { mem_free(parent); return s; }
    *n_charts = n;
    *parent_out = parent;
    return NEUV_OK;
}
