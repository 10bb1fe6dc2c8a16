/* One chart's judge: see chart_judge.h. */
#include "segment/chart_judge.h"

#include <math.h>
#include <stdlib.h>

#include "atlas/convex_hull.h"
#include "charts/charts.h"
#include "core/error.h"
#include "core/mem.h"
#include "flatten/lscm.h"
#include "metrics/chart_uv_check.h"
#include "metrics/uv_metrics.h"

/* UV area over the area of its convex hull: 1 for a convex footprint,
 * small for a snake or a comb, which the packer cannot nest. */
static double uv_convexity(const neuv_mesh *sub, const double *uv)
{
    int *hull = mem_alloc(sizeof(int) * (size_t)sub->nv);
    if (!hull) return -1;
    int h = convex_hull_2d(uv, sub->nv, hull);
    double hull_area = 0, area = 0;
    for (int i = 0; i < h; i++) {
        const double *p = uv + 2 * hull[i], *r = uv + 2 * hull[(i + 1) % h];
        hull_area += p[0] * r[1] - p[1] * r[0];
    }
    for (int f = 0; f < sub->nf; f++) {
        const double *a = uv + 2 * sub->tri[3 * f], *b = uv + 2 * sub->tri[3 * f + 1], *c = uv + 2 * sub->tri[3 * f + 2];
        area += (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    }
    mem_free(hull);
    if (h < 0) return -1;
    return hull_area > 0 ? fabs(area) / hull_area : 1.0;
}

/* LSCM's qce_mean and flipped faces on chart `id`; with `crossings`, also
 * its boundary self-crossings and (convexity, when not NULL) the share of
 * its UV footprint's convex hull that the footprint fills. */
neuv_status chart_lscm_judge(const neuv_mesh *m, const int *face_chart, int id, double *qce_mean,
                             int *flipped, int *crossings, double *convexity)
{
    if (convexity) *convexity = 1.0;
    *qce_mean = INFINITY;
    *flipped = 0;
    if (crossings) *crossings = 0;
    neuv_mesh *sub = NULL;
    int *vmap = NULL, *fmap = NULL;
    neuv_status st = chart_submesh(m, face_chart, id, &sub, &vmap, &fmap);
    if (st) return st;
    mem_free(vmap);
    mem_free(fmap);
    double *uv = mem_alloc(sizeof(double) * 2 * (size_t)sub->nv);
    if (!uv) { mesh_free(sub); return error_nomem("chart UVs"); }
    st = lscm(sub, uv);
    if (st == NEUV_ERR_NOMEM) { mem_free(uv); mesh_free(sub); return st; }
    if (st == NEUV_OK) {
        /* A chart LSCM cannot flatten stays at qce INFINITY: the split loop
         * then cuts it smaller. */
        st = mesh_set_uv(sub, sub->nv, uv, sub->tri);
        uv_metrics mt;
        if (!st) st = uv_metrics_compute_no_overlap(sub, &mt); /* only qce and flips are judged */
        if (!st) {
            *qce_mean = isfinite(mt.qce_mean) ? mt.qce_mean : INFINITY;
            *flipped = mt.flipped + mt.degenerate_uv;
        }
        if (!st && crossings) {
            chart_uv_check chk;
            int ok = chart_uv_check_run(sub, uv, &chk);
            if (ok < 0) st = NEUV_ERR_NOMEM;
            else *crossings = chk.boundary_crossings;
            double cvx = convexity ? uv_convexity(sub, uv) : 1.0;
            if (!st && cvx < 0) st = NEUV_ERR_NOMEM;
            if (!st && convexity) *convexity = cvx;
        }
        if (st == NEUV_ERR_NOMEM) { mem_free(uv); mesh_free(sub); return error_nomem("chart check"); }
    }
    mem_free(uv);
    mesh_free(sub);
    return NEUV_OK;
}

neuv_status patchnet_chart_lscm_quality(const neuv_mesh *m, const int *face_chart, int id, double *qce_mean,
                                        int *flipped)
{
    return chart_lscm_judge(m, face_chart, id, qce_mean, flipped, NULL, NULL);
}
