#include "atlas/pack.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "atlas/footprint.h"
#include "atlas/min_area_rect.h"
#include "atlas/occupancy.h"
#include "core/error.h"

static const double half_pi = 1.57079632679489661923;

/* One chart as the packer sees it: its faces and UVs (ranges into the
 * packer's own arrays) and its shape after density scaling and turning to
 * its minimum-area rectangle, in "world" units (before the global scale). */
typedef struct chart_info {
    int f_begin, f_end;     /* into order / ltri */
    int v_begin, v_end;     /* into the new UV array */
    double s;               /* density scale */
    double theta;           /* rotation to the minimum-area rectangle */
    double minx, miny;      /* corner of the rectangle after scale and rotation */
    double W, H;            /* rectangle sides */
    double area;            /* UV area after density scaling */
} chart_info;

typedef struct placement { int x, y, k, w, h; } placement;

typedef struct pack_ctx {
    int ncharts;
    chart_info *ch;
    int *sorted[3];         /* chart ids in the order of each placement heuristic */
    int *ltri;              /* #F by 3, chart-local UV indices, faces grouped by chart */
    double *L;              /* #UV' by 2, chart UVs scaled, rotated, corner at the origin */
    int max_verts;
    int resolution, padding;
} pack_ctx;

void atlas_pack_options_default(atlas_pack_options *o)
{
    o->resolution = 1024;
    o->padding = 2;
    o->keep_scale = 0;
}

void atlas_chart_transform_apply(const atlas_chart_transform *t, const double uv[2], double out[2])
{
    double c = cos(t->angle), s = sin(t->angle);
    double x = uv[0], y = uv[1];
    out[0] = t->scale * (c * x - s * y) + t->tx;
    out[1] = t->scale * (s * x + c * y) + t->ty;
}

static double tri_area_2d(const double *a, const double *b, const double *c)
{
    return 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
}

/* Placement heuristics tried at each scale, best first on the samples:
 * (order of charts, choice among rotations). A scale counts as fitting when
 * any of them fits, so trying more only ever raises the final scale. */
enum { order_rect_area, order_perimeter, order_short_side };
enum { choose_lowest_top, choose_lowest_bottom };
typedef struct pack_heuristic { int order, choose; } pack_heuristic;
#define PACK_HEURISTICS 4
static const pack_heuristic heuristics[PACK_HEURISTICS] = {
    {order_perimeter, choose_lowest_bottom},
    {order_short_side, choose_lowest_top},
    {order_rect_area, choose_lowest_bottom},
    {order_rect_area, choose_lowest_top},
};

typedef struct chart_order { double key; int id; } chart_order;

/* Largest minimum-area rectangle first (the hardest to place), then by id. */
static int cmp_chart_order(const void *a, const void *b)
{
    const chart_order *x = a, *y = b;
    if (x->key != y->key) return x->key > y->key ? -1 : 1;
    return x->id - y->id;
}

/* One packing at global scale g (pixels per world unit). Returns 1 when all
 * charts fit (pl filled), 0 when one does not (placed_px: pixels placed so
 * far, total_px: all pixels), -1 on allocation failure. */
static int pack_attempt(const pack_ctx *P, const pack_heuristic *hs, double g, placement *pl, double *frac_placed)
{
    const int R = P->resolution, pad = P->padding;
    occupancy occ;
    double *q = malloc(sizeof *q * 2 * (size_t)(P->max_verts > 0 ? P->max_verts : 1));
    if (!q || occupancy_init(&occ, R, pad) != 0) { free(q); return -1; }
    double placed = 0, total = 0;
    for (int i = 0; i < P->ncharts; i++) {
        const chart_info *c = &P->ch[i];
        if (c->f_end > c->f_begin) total += (g * c->W + 1) * (g * c->H + 1);
    }
    int rc = 1;
    for (int n = 0; n < P->ncharts && rc == 1; n++) {
        int ci = P->sorted[hs->order][n];
        const chart_info *c = &P->ch[ci];
        if (c->f_end == c->f_begin) continue;
        int nv = c->v_end - c->v_begin;
        for (int v = 0; v < nv; v++) {
            q[2 * v] = g * P->L[2 * (size_t)(c->v_begin + v)];
            q[2 * v + 1] = g * P->L[2 * (size_t)(c->v_begin + v) + 1];
        }
        int w = (int)floor(g * c->W + 1e-7) + 1, h = (int)floor(g * c->H + 1e-7) + 1;
        if ((w > R - 2 * pad && h > R - 2 * pad) || w > R || h > R) { rc = 0; break; }
        footprint fp[4];
        footprint_spans sp[4];
        int have[4] = {0, 0, 0, 0};
        memset(fp, 0, sizeof fp);
        memset(sp, 0, sizeof sp);
        if (footprint_rasterize(q, P->ltri + 3 * (size_t)c->f_begin, c->f_end - c->f_begin, w, h, &fp[0]) != 0) {
            rc = -1;
            break;
        }
        have[0] = 1;
        for (int k = 1; k < 4 && rc == 1; k++) {
            if (footprint_rotate(&fp[0], k, &fp[k]) != 0) { rc = -1; break; }
            /* A half turn that maps the footprint onto itself finds the same places. */
            have[k] = !(k >= 2 && footprint_equal(&fp[k], &fp[k - 2]));
        }
        for (int k = 0; k < 4 && rc == 1; k++)
            if (have[k] && footprint_to_spans(&fp[k], &sp[k]) != 0) rc = -1;
        int best_k = -1, bx = 0, by = 0, best_top = R + 1;
        for (int k = 0; k < 4 && rc == 1; k++) {
            if (!have[k]) continue;
            int x, y;
            /* Lowest top edge wins (keeps the filled part of the square low), then leftmost. */
            if (hs->choose == choose_lowest_top) {
                /* Lowest top edge wins (keeps the filled part of the square low), then leftmost. */
                if (occupancy_find(&occ, &sp[k], best_top, &x, &y)) {
                    int top = y + fp[k].h;
                    if (top < best_top || (top == best_top && x < bx)) {
                        best_top = top; best_k = k; bx = x; by = y;
                    }
                }
            } else if (occupancy_find(&occ, &sp[k], best_k < 0 ? R + 1 : by + fp[k].h + 1, &x, &y)) {
                /* Lowest bottom edge wins, then leftmost. */
                if (best_k < 0 || y < by || (y == by && x < bx)) { best_k = k; bx = x; by = y; }
            }
        }
        if (rc == 1 && best_k < 0) rc = 0;
        if (rc == 1) {
            if (pad > 0) {
                footprint dil;
                if (footprint_dilate(&fp[best_k], pad, &dil) != 0) rc = -1;
                else occupancy_mark(&occ, &dil, bx - pad, by - pad);
                footprint_free(&dil);
            } else {
                occupancy_mark(&occ, &fp[best_k], bx, by);
            }
            pl[ci].x = bx; pl[ci].y = by; pl[ci].k = best_k; pl[ci].w = w; pl[ci].h = h;
            placed += (g * c->W + 1) * (g * c->H + 1);
        }
        for (int k = 0; k < 4; k++) { footprint_free(&fp[k]); footprint_spans_free(&sp[k]); }
    }
    occupancy_free(&occ);
    free(q);
    *frac_placed = total > 0 ? placed / total : 1;
    return rc;
}

/* Builds the per-chart data: faces grouped by chart, UVs split per chart,
 * density scale, minimum-area rectangle. */
static neuv_status pack_prepare(const neuv_mesh *m, const int *face_chart, int ncharts, int keep_scale,
                                pack_ctx *P, int **new_tri_uv, int **old_of_new, int *nuv_new)
{
    int nf = m->nf;
    P->ncharts = ncharts;
    P->ch = calloc((size_t)ncharts + 1, sizeof *P->ch);
    for (int h = 0; h < 3; h++) P->sorted[h] = malloc(sizeof *P->sorted[h] * ((size_t)ncharts + 1));
    P->ltri = malloc(sizeof *P->ltri * 3 * ((size_t)nf + 1));
    int *order = malloc(sizeof *order * ((size_t)nf + 1));
    int *start = calloc((size_t)ncharts + 2, sizeof *start);
    int *stamp = malloc(sizeof *stamp * ((size_t)m->nuv + 1));
    int *map = malloc(sizeof *map * ((size_t)m->nuv + 1));
    *new_tri_uv = malloc(sizeof **new_tri_uv * 3 * ((size_t)nf + 1));
    *old_of_new = malloc(sizeof **old_of_new * 3 * ((size_t)nf + 1));
    neuv_status st = NEUV_OK;
    if (!P->ch || !P->sorted[0] || !P->sorted[1] || !P->sorted[2] || !P->ltri || !order || !start || !stamp || !map || !*new_tri_uv || !*old_of_new) {
        st = neuv_fail_nomem("atlas packing");
        goto done;
    }
    /* Faces grouped by chart, in face order within a chart (counting sort). */
    for (int f = 0; f < nf; f++) start[face_chart[f] + 1]++;
    for (int c = 0; c < ncharts; c++) start[c + 1] += start[c];
    {
        int *fill = P->sorted[0]; /* borrowed as a cursor array */
        for (int c = 0; c < ncharts; c++) fill[c] = start[c];
        for (int f = 0; f < nf; f++) order[fill[face_chart[f]]++] = f;
    }
    for (int u = 0; u < m->nuv; u++) stamp[u] = -1;
    int next = 0;
    P->max_verts = 0;
    for (int c = 0; c < ncharts; c++) {
        chart_info *ci = &P->ch[c];
        ci->f_begin = start[c]; ci->f_end = start[c + 1];
        ci->v_begin = next;
        for (int i = start[c]; i < start[c + 1]; i++) {
            int f = order[i];
            for (int k = 0; k < 3; k++) {
                int u = m->tri_uv[3 * f + k];
                if (stamp[u] != c) { stamp[u] = c; map[u] = next; (*old_of_new)[next] = u; next++; }
                (*new_tri_uv)[3 * f + k] = map[u];
                P->ltri[3 * i + k] = map[u] - ci->v_begin;
            }
        }
        ci->v_end = next;
        if (next - ci->v_begin > P->max_verts) P->max_verts = next - ci->v_begin;
    }
    *nuv_new = next;
    P->L = malloc(sizeof *P->L * 2 * ((size_t)next + 1));
    if (!P->L) { st = neuv_fail_nomem("atlas packing"); goto done; }
    for (int c = 0; c < ncharts; c++) {
        chart_info *ci = &P->ch[c];
        double a3 = 0, auv = 0;
        for (int i = ci->f_begin; i < ci->f_end; i++) {
            int f = order[i];
            a3 += mesh_face_area(m, f);
            const int *t = m->tri_uv + 3 * f;
            auv += fabs(tri_area_2d(m->uv + 2 * t[0], m->uv + 2 * t[1], m->uv + 2 * t[2]));
        }
        double *L = P->L + 2 * (size_t)ci->v_begin;
        int nv = ci->v_end - ci->v_begin;
        if (keep_scale) ci->s = 1;
        else if (a3 > 0 && auv > 0) ci->s = sqrt(a3 / auv);
        else {
            /* A chart flattened to a segment or a point: size it by its 3D area
             * over its UV extent so it still gets a footprint in proportion. */
            double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
            for (int v = 0; v < nv; v++)
                for (int d = 0; d < 2; d++) {
                    double x = m->uv[2 * (*old_of_new)[ci->v_begin + v] + d];
                    if (x < lo[d]) lo[d] = x;
                    if (x > hi[d]) hi[d] = x;
                }
            double ext = nv > 0 ? fmax(hi[0] - lo[0], hi[1] - lo[1]) : 0;
            ci->s = (ext > 0 && a3 > 0) ? sqrt(a3) / ext : 1;
        }
        ci->area = auv * ci->s * ci->s;
        for (int v = 0; v < nv; v++) {
            const double *uv = m->uv + 2 * (*old_of_new)[ci->v_begin + v];
            L[2 * v] = ci->s * uv[0];
            L[2 * v + 1] = ci->s * uv[1];
        }
        double W, H;
        if (min_area_rect(L, nv, &ci->theta, &W, &H) != 0) { st = neuv_fail_nomem("atlas packing"); goto done; }
        double cs = cos(ci->theta), sn = sin(ci->theta);
        double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
        for (int v = 0; v < nv; v++) {
            double x = L[2 * v], y = L[2 * v + 1];
            L[2 * v] = cs * x - sn * y;
            L[2 * v + 1] = sn * x + cs * y;
            for (int d = 0; d < 2; d++) {
                if (L[2 * v + d] < lo[d]) lo[d] = L[2 * v + d];
                if (L[2 * v + d] > hi[d]) hi[d] = L[2 * v + d];
            }
        }
        if (nv == 0) { lo[0] = lo[1] = hi[0] = hi[1] = 0; }
        for (int v = 0; v < nv; v++) { L[2 * v] -= lo[0]; L[2 * v + 1] -= lo[1]; }
        ci->minx = lo[0]; ci->miny = lo[1];
        ci->W = hi[0] - lo[0]; ci->H = hi[1] - lo[1];
    }
    chart_order *co = malloc(sizeof *co * ((size_t)ncharts + 1));
    if (!co) { st = neuv_fail_nomem("atlas packing"); goto done; }
    for (int h = 0; h < 3; h++) {
        for (int c = 0; c < ncharts; c++) {
            const chart_info *ci = &P->ch[c];
            co[c].key = h == order_rect_area ? ci->W * ci->H : h == order_perimeter ? ci->W + ci->H : fmin(ci->W, ci->H);
            co[c].id = c;
        }
        qsort(co, (size_t)ncharts, sizeof *co, cmp_chart_order);
        for (int c = 0; c < ncharts; c++) P->sorted[h][c] = co[c].id;
    }
    free(co);
done:
    free(order); free(start); free(stamp); free(map);
    return st;
}

static void pack_ctx_free(pack_ctx *P)
{
    free(P->ch); free(P->sorted[0]); free(P->sorted[1]); free(P->sorted[2]); free(P->ltri); free(P->L);
    memset(P, 0, sizeof *P);
}

/* The similarity of chart c placed by pl at global scale g (see pack.h):
 * uv' = (1/R) (Rot_k (g (Rot_theta s uv - min)) + off_k + (x, y)). */
static atlas_chart_transform chart_transform(const chart_info *c, const placement *pl, double g, int R)
{
    atlas_chart_transform t;
    t.scale = g * c->s / R;
    t.angle = c->theta + pl->k * half_pi;
    double mx = g * c->minx, my = g * c->miny, ox, oy;
    switch (pl->k) {
    case 0: ox = -mx; oy = -my; break;
    case 1: ox = my + pl->h; oy = -mx; break;
    case 2: ox = mx + pl->w; oy = my + pl->h; break;
    default: ox = -my; oy = mx + pl->w; break;
    }
    t.tx = (ox + pl->x) / R;
    t.ty = (oy + pl->y) / R;
    return t;
}

/* Same map as atlas_chart_transform_apply but with the quarter turn done
 * exactly, so the UVs land where the footprint was rasterized. */
static void chart_place_uv(const chart_info *c, const placement *pl, double g, int R,
                           const double *L, double out[2])
{
    double x = g * L[0], y = g * L[1], px, py;
    switch (pl->k) {
    case 0: px = x; py = y; break;
    case 1: px = pl->h - y; py = x; break;
    case 2: px = pl->w - x; py = pl->h - y; break;
    default: px = y; py = pl->w - x; break;
    }
    (void)c;
    out[0] = (px + pl->x) / R;
    out[1] = (py + pl->y) / R;
}

neuv_status atlas_pack(neuv_mesh *m, const int *face_chart, int ncharts,
                       const atlas_pack_options *opt, atlas_chart_transform *xf,
                       atlas_pack_result *res)
{
    atlas_pack_options o;
    if (opt) o = *opt;
    else atlas_pack_options_default(&o);
    if (!m || m->nuv <= 0 || !m->tri_uv) return neuv_fail(NEUV_ERR_INPUT, "packing needs a mesh with UVs");
    if (o.resolution < 8 || o.resolution > 32768)
        return neuv_fail(NEUV_ERR_INPUT, "atlas resolution %d px is outside 8..32768", o.resolution);
    if (o.padding < 0 || 2 * o.padding + 1 > o.resolution)
        return neuv_fail(NEUV_ERR_INPUT, "padding %d px does not fit in a %d px atlas", o.padding, o.resolution);
    if (ncharts < 0) return neuv_fail(NEUV_ERR_INPUT, "negative chart count");
    for (int f = 0; f < m->nf; f++)
        if (face_chart[f] < 0 || face_chart[f] >= ncharts)
            return neuv_fail(NEUV_ERR_INPUT, "face %d has chart id %d outside 0..%d", f, face_chart[f], ncharts - 1);
    for (int f = 0; f < 3 * m->nf; f++)
        if (m->tri_uv[f] < 0 || m->tri_uv[f] >= m->nuv)
            return neuv_fail(NEUV_ERR_INPUT, "face %d uses UV index %d outside 0..%d", f / 3, m->tri_uv[f], m->nuv - 1);
    for (int u = 0; u < 2 * m->nuv; u++)
        if (!isfinite(m->uv[u])) return neuv_fail(NEUV_ERR_INPUT, "UV %d is not a finite number", u / 2);

    pack_ctx P;
    memset(&P, 0, sizeof P);
    P.resolution = o.resolution;
    P.padding = o.padding;
    int *new_tri_uv = NULL, *old_of_new = NULL, nuv_new = 0;
    placement *pl = NULL, *best_pl = NULL;
    double *uv_new = NULL;
    neuv_status st = pack_prepare(m, face_chart, ncharts, o.keep_scale, &P, &new_tri_uv, &old_of_new, &nuv_new);
    if (st != NEUV_OK) goto done;
    pl = calloc((size_t)ncharts + 1, sizeof *pl);
    best_pl = calloc((size_t)ncharts + 1, sizeof *best_pl);
    uv_new = malloc(sizeof *uv_new * 2 * ((size_t)nuv_new + 1));
    if (!pl || !best_pl || !uv_new) { st = neuv_fail_nomem("atlas packing"); goto done; }

    /* Upper bound on the global scale: the charts' total area cannot exceed
     * the free square, nor can the longest chart side. Then shrink until
     * everything fits and bisect between the best fit and the first miss. */
    double inner = o.resolution - 2.0 * o.padding, area = 0, longest = 0;
    for (int c = 0; c < ncharts; c++) {
        const chart_info *ci = &P.ch[c];
        if (ci->f_end == ci->f_begin) continue;
        area += ci->area;
        if (fmax(ci->W, ci->H) > longest) longest = fmax(ci->W, ci->H);
    }
    double g = INFINITY;
    if (area > 0) g = inner / sqrt(area);
    if (longest > 0) g = fmin(g, (inner - 1) / longest);
    if (!isfinite(g) || g <= 0) g = 1;
    double lo = 0, hi = 0, g0 = g;
    int attempts = 0;
    for (;;) {
        double frac = 0;
        int rc = 0;
        /* With thousands of charts the time goes to placements, and small
         * charts fill the gaps whatever the order: one heuristic is enough. */
        int nh = ncharts > 1000 ? 1 : PACK_HEURISTICS;
        for (int h = 0; h < nh && rc == 0; h++) {
            double fh;
            rc = pack_attempt(&P, &heuristics[h], g, pl, &fh);
            attempts++;
            if (fh > frac) frac = fh;
        }
        if (rc < 0) { st = neuv_fail_nomem("atlas packing"); goto done; }
        if (rc == 1) {
            lo = g;
            memcpy(best_pl, pl, sizeof *pl * (size_t)ncharts);
            if (hi == 0) break; /* fits at the upper bound: nothing better exists */
        } else {
            hi = g;
        }
        if (lo > 0 && hi / lo < 1.003) break;
        if (attempts >= 40) break;
        if (lo > 0) g = sqrt(lo * hi);
        else {
            double shrink = sqrt(frac);
            if (shrink > 0.97) shrink = 0.97;
            if (shrink < 0.5) shrink = 0.5;
            g *= shrink;
            if (g < g0 * 1e-6) break;
        }
    }
    if (lo == 0) {
        st = neuv_fail(NEUV_ERR_INPUT, "%d charts do not fit in a %d px atlas with %d px padding",
                       ncharts, o.resolution, o.padding);
        goto done;
    }
    g = lo;
    for (int c = 0; c < ncharts; c++) {
        const chart_info *ci = &P.ch[c];
        if (xf) {
            if (ci->f_end > ci->f_begin) xf[c] = chart_transform(ci, &best_pl[c], g, o.resolution);
            else { xf[c].scale = 1; xf[c].angle = 0; xf[c].tx = 0; xf[c].ty = 0; }
        }
        for (int v = ci->v_begin; v < ci->v_end; v++)
            chart_place_uv(ci, &best_pl[c], g, o.resolution, P.L + 2 * (size_t)v, uv_new + 2 * (size_t)v);
    }
    st = mesh_set_uv(m, nuv_new, uv_new, new_tri_uv);
    if (st != NEUV_OK) goto done;
    if (res) {
        double a = 0, a3 = mesh_total_area(m);
        for (int f = 0; f < m->nf; f++) {
            const int *t = m->tri_uv + 3 * f;
            a += fabs(tri_area_2d(m->uv + 2 * t[0], m->uv + 2 * t[1], m->uv + 2 * t[2]));
        }
        res->efficiency = a;
        res->texel_scale = a3 > 0 ? o.resolution * sqrt(a / a3) : 0;
        res->attempts = attempts;
    }
done:
    pack_ctx_free(&P);
    free(new_tri_uv); free(old_of_new); free(pl); free(best_pl); free(uv_new);
    return st;
}
