#include "metrics/chart_uv_check.h"

#include <math.h>
#include <stdlib.h>

#include "core/mem.h"
#include "mesh/topology.h"

static double uv_area2(const double *uv, const int *t)
{
    const double *a = uv + 2 * t[0], *b = uv + 2 * t[1], *c = uv + 2 * t[2];
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

static double orient(const double *a, const double *b, const double *c)
{
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

static int on_segment(const double *a, const double *b, const double *p)
{
    return fmin(a[0], b[0]) <= p[0] && p[0] <= fmax(a[0], b[0]) &&
           fmin(a[1], b[1]) <= p[1] && p[1] <= fmax(a[1], b[1]);
}

/* Closed segments ab and cd touch or cross (exact sign tests on doubles). */
static int segments_meet(const double *a, const double *b, const double *c, const double *d)
{
    double o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
    if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0)))
        return 1;
    if (o1 == 0 && on_segment(a, b, c)) return 1;
    if (o2 == 0 && on_segment(a, b, d)) return 1;
    if (o3 == 0 && on_segment(c, d, a)) return 1;
    if (o4 == 0 && on_segment(c, d, b)) return 1;
    return 0;
}

/* Counts crossings among the n segments of a closed loop (segment i joins
 * loop[i] and loop[i+1]). Segments are bucketed in a uniform grid so long
 * boundaries stay near-linear; each pair is tested once (in the cell of
 * the lower-left corner of the overlap of their boxes). */
static int loop_crossings(const double *uv, const int *loop, int n)
{
    if (n < 4) return 0;
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY}, len = 0;
    for (int i = 0; i < n; i++) {
        const double *p = uv + 2 * loop[i], *q = uv + 2 * loop[(i + 1) % n];
        for (int k = 0; k < 2; k++) { lo[k] = fmin(lo[k], p[k]); hi[k] = fmax(hi[k], p[k]); }
        len += hypot(q[0] - p[0], q[1] - p[1]);
    }
    double cell = len / n;
    if (!(cell > 0)) return 0;
    int gx = (int)fmin(1024, (hi[0] - lo[0]) / cell + 1), gy = (int)fmin(1024, (hi[1] - lo[1]) / cell + 1);
    double cx = (hi[0] - lo[0]) / gx + 1e-300, cy = (hi[1] - lo[1]) / gy + 1e-300;
    /* Two passes: count entries per cell, then fill. */
    int *start = mem_calloc((size_t)gx * gy + 1, sizeof(int));
    if (!start) return -1;
    for (int pass = 0; pass < 2; pass++) {
        int *fill = NULL, *items = NULL;
        if (pass == 1) {
            for (int c = 0; c < gx * gy; c++) start[c + 1] += start[c];
            fill = mem_alloc(sizeof(int) * (size_t)gx * gy);
            items = mem_alloc(sizeof(int) * (size_t)(start[gx * gy] > 0 ? start[gx * gy] : 1));
            if (!fill || !items) { mem_free(fill); mem_free(items); mem_free(start); return -1; }
            for (int c = 0; c < gx * gy; c++) fill[c] = start[c];
        }
        for (int i = 0; i < n; i++) {
            const double *p = uv + 2 * loop[i], *q = uv + 2 * loop[(i + 1) % n];
            int x0 = (int)((fmin(p[0], q[0]) - lo[0]) / cx), x1 = (int)((fmax(p[0], q[0]) - lo[0]) / cx);
            int y0 = (int)((fmin(p[1], q[1]) - lo[1]) / cy), y1 = (int)((fmax(p[1], q[1]) - lo[1]) / cy);
            if (x1 >= gx) x1 = gx - 1;
            if (y1 >= gy) y1 = gy - 1;
            for (int y = y0; y <= y1; y++)
                for (int x = x0; x <= x1; x++) {
                    if (pass == 0) start[y * gx + x + 1]++;
                    else items[fill[y * gx + x]++] = i;
                }
        }
        if (pass == 1) {
            int crossings = 0;
            for (int c = 0; c < gx * gy; c++)
                for (int s = start[c]; s < start[c + 1]; s++)
                    for (int t = s + 1; t < start[c + 1]; t++) {
                        int i = items[s], j = items[t];
                        if (i == j || (i + 1) % n == j || (j + 1) % n == i) continue;
                        const double *a = uv + 2 * loop[i], *b = uv + 2 * loop[(i + 1) % n];
                        const double *d0 = uv + 2 * loop[j], *d1 = uv + 2 * loop[(j + 1) % n];
                        /* Test the pair only in the cell holding the low corner of the
                         * overlap of the two boxes, so it is counted once. */
                        double ox = fmax(fmin(a[0], b[0]), fmin(d0[0], d1[0]));
                        double oy = fmax(fmin(a[1], b[1]), fmin(d0[1], d1[1]));
                        int ocx = (int)((ox - lo[0]) / cx), ocy = (int)((oy - lo[1]) / cy);
                        if (ocx >= gx) ocx = gx - 1;
                        if (ocy >= gy) ocy = gy - 1;
                        if (ocy * gx + ocx != c) continue;
                        if (segments_meet(a, b, d0, d1)) crossings++;
                    }
            mem_free(fill);
            mem_free(items);
            mem_free(start);
            return crossings;
        }
    }
    mem_free(start);
    return 0;
}

int chart_uv_check_run(const neuv_mesh *sub, double *uv, chart_uv_check *out)
{
    out->flipped = out->degenerate = out->boundary_crossings = out->mirrored = 0;
    double total = 0, mean_abs = 0;
    for (int f = 0; f < sub->nf; f++) {
        double a = uv_area2(uv, sub->tri + 3 * f);
        total += a;
        mean_abs += fabs(a);
    }
    if (!isfinite(total)) { out->degenerate = sub->nf; return 0; }
    if (total < 0) {
        for (int v = 0; v < sub->nv; v++) uv[2 * v] = -uv[2 * v];
        out->mirrored = 1;
    }
    mean_abs /= sub->nf > 0 ? sub->nf : 1;
    for (int f = 0; f < sub->nf; f++) {
        double a = uv_area2(uv, sub->tri + 3 * f);
        if (fabs(a) <= 1e-9 * mean_abs) out->degenerate++;
        else if (a < 0) out->flipped++;
    }
    int *start = NULL, *verts = NULL;
    int nloops = mesh_boundary_loops(sub, NULL, 0, &start, &verts);
    if (nloops < 0) return -1;
    for (int l = 0; l < nloops; l++) {
        int c = loop_crossings(uv, verts + start[l], start[l + 1] - start[l]);
        if (c < 0) { mem_free(start); mem_free(verts); return -1; }
        out->boundary_crossings += c;
    }
    mem_free(start);
    mem_free(verts);
    return out->flipped == 0 && out->degenerate == 0 && out->boundary_crossings == 0;
}
