#include "atlas/pack.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "atlas/footprint.h"
#include "atlas/min_area_rect.h"
#include "atlas/occupancy.h"
#include "core/error.h"
#include "core/mem.h"
#include "core/rng.h"

static const double half_pi = 1.57079632679489661923;
/* Finest extra turn: a placement index j < pack_turns_max is the turn j * (pi/2) / pack_turns_max. */
enum { pack_turns_max = 8 };

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
    double fit_angle;       /* extra turn (on top of theta) that minimizes the longer box side */
    double fit_side;        /* that longer side: the chart fits the atlas only if g fit_side does */
} chart_info;

/* Where a chart went: turned by extra angle j (see chart_angle) then
 * by k quarter turns, its w by h pixel box with corner (x, y). */
typedef struct placement { int x, y, k, w, h, j; } placement;

/* Orders the charts are placed in (largest first by each key). */
enum { order_rect_area, order_perimeter, order_short_side, order_long_side, order_shuffled, PACK_ORDERS };

typedef struct pack_ctx {
    int ncharts;
    chart_info *ch;
    int *sorted[PACK_ORDERS]; /* chart ids in the order of each placement heuristic (order_shuffled: pack_polish's) */
    int *ltri;              /* #F by 3, chart-local UV indices, faces grouped by chart */
    double *L;              /* #UV' by 2, chart UVs scaled, rotated, corner at the origin */
    int max_verts;
    int resolution, padding;
    const unsigned char *done; /* tiles: charts placed on an earlier tile, left out (NULL: none) */
    int allow_miss;            /* tiles: a chart that finds no room is left for the next tile (k = -1) */
} pack_ctx;

void atlas_pack_options_default(atlas_pack_options *o)
{
    o->resolution = 1024;
    o->padding = 2;
    o->keep_scale = 0;
    o->quick = 0;
    o->texels_per_unit = 0;
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
enum { choose_lowest_top, choose_lowest_bottom };
/* turns: extra turns j * (pi/2) / turns tried per quarter turn (plus the
 * turn of the chart's smallest bounding square). */
typedef struct pack_heuristic { int order, choose, turns; } pack_heuristic;
#define PACK_HEURISTICS 10
static const pack_heuristic heuristics[PACK_HEURISTICS] = {
    {order_perimeter, choose_lowest_bottom, 1},
    {order_short_side, choose_lowest_top, 1},
    {order_rect_area, choose_lowest_bottom, 1},
    {order_rect_area, choose_lowest_top, 1},
    {order_perimeter, choose_lowest_bottom, 4},
    {order_rect_area, choose_lowest_top, 4},
    {order_long_side, choose_lowest_top, 4},
    {order_perimeter, choose_lowest_bottom, 8},
    {order_rect_area, choose_lowest_top, 8},
    {order_long_side, choose_lowest_top, 8},
};

typedef struct chart_order { double key; int id; } chart_order;

/* Largest minimum-area rectangle first (the hardest to place), then by id. */
static int cmp_chart_order(const void *a, const void *b)
{
    const chart_order *x = a, *y = b;
    if (x->key != y->key) return x->key > y->key ? -1 : 1;
    return x->id - y->id;
}

/* Extra turn j of chart c on top of its minimum-area rectangle. */
static double chart_angle(const chart_info *c, int j)
{
    return j < pack_turns_max ? j * half_pi / pack_turns_max : c->fit_angle;
}

/* Chart c turned by its extra angle j (chart_angle) and scaled by the
 * global scale g, its bounding corner moved to the origin: q (#V by 2) in
 * pixels, *w by *h its pixel box, (*mx, *my) the corner that was removed,
 * so q = g Rot_j L - (mx, my). The packer rasterizes these points and
 * writes them out, so both must come from this one function. */
static void chart_oriented(const pack_ctx *P, const chart_info *c, int j, double g, double *q,
                           int *w, int *h, double *mx, double *my)
{
    int nv = c->v_end - c->v_begin;
    const double *L = P->L + 2 * (size_t)c->v_begin;
    double a = chart_angle(c, j), cs = j ? cos(a) : 1, sn = j ? sin(a) : 0;
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (int v = 0; v < nv; v++) {
        double x = g * (cs * L[2 * v] - sn * L[2 * v + 1]), y = g * (sn * L[2 * v] + cs * L[2 * v + 1]);
        q[2 * v] = x; q[2 * v + 1] = y;
        if (x < lo[0]) lo[0] = x;
        if (x > hi[0]) hi[0] = x;
        if (y < lo[1]) lo[1] = y;
        if (y > hi[1]) hi[1] = y;
    }
    if (nv == 0) lo[0] = lo[1] = hi[0] = hi[1] = 0;
    for (int v = 0; v < nv; v++) { q[2 * v] -= lo[0]; q[2 * v + 1] -= lo[1]; }
    *mx = lo[0]; *my = lo[1];
    *w = (int)floor(hi[0] - lo[0] + 1e-7) + 1;
    *h = (int)floor(hi[1] - lo[1] + 1e-7) + 1;
}

/* A chart's footprint at one extra turn and the current scale, in its four
 * quarter turns, as spans. Every heuristic tried at a scale places the same
 * shapes, so they are made once per scale (pack_cache). */
typedef struct turn_shape {
    int state;              /* 0: not made yet, 1: made, 2: does not fit the atlas at this turn */
    int w, h;               /* pixel box before the quarter turns */
    int have[4];            /* quarter turn k is distinct (a half turn can repeat the shape) */
    footprint_spans sp[4];
    size_t bytes;
} turn_shape;

static void turn_shape_clear(turn_shape *t)
{
    for (int k = 0; k < 4; k++) footprint_spans_free(&t->sp[k]);
    memset(t, 0, sizeof *t);
}

/* Makes chart c's shape at extra turn j and scale g (q: scratch, 2 max_verts). Returns 0 or -1 (no memory). */
static int turn_shape_make(const pack_ctx *P, const chart_info *c, int j, double g, double *q, turn_shape *t)
{
    const int R = P->resolution, pad = P->padding;
    double mx, my;
    chart_oriented(P, c, j, g, q, &t->w, &t->h, &mx, &my);
    if ((t->w > R - 2 * pad && t->h > R - 2 * pad) || t->w > R || t->h > R) { t->state = 2; return 0; }
    /* The bitmap and its quarter turn; the half turns of both come from
     * their spans, which is all the placements read. */
    footprint fp0, fp1;
    memset(&fp1, 0, sizeof fp1);
    if (footprint_rasterize(q, P->ltri + 3 * (size_t)c->f_begin, c->f_end - c->f_begin, t->w, t->h, &fp0) != 0)
        return -1;
    int rc = footprint_to_spans(&fp0, &t->sp[0]) != 0 || footprint_rotate(&fp0, 1, &fp1) != 0 ||
             footprint_to_spans(&fp1, &t->sp[1]) != 0 ? -1 : 0;
    footprint_free(&fp0);
    footprint_free(&fp1);
    if (rc) return -1;
    for (int k = 0; k < 4; k++) {
        if (k >= 2) {
            if (footprint_spans_half_turn(&t->sp[k - 2], &t->sp[k]) != 0) return -1;
            /* A half turn that maps the footprint onto itself finds the same places. */
            if (footprint_spans_equal(&t->sp[k], &t->sp[k - 2])) footprint_spans_free(&t->sp[k]);
        }
        t->have[k] = t->sp[k].row_first != NULL;
        if (t->have[k]) t->bytes += (size_t)t->sp[k].count * 8 + (size_t)t->sp[k].h * 16;
    }
    t->state = 1;
    return 0;
}

/* The shapes of every chart and turn at one scale, up to a memory budget
 * (beyond it a shape is made for the moment and dropped). */
typedef struct pack_cache {
    double g;               /* the scale the shapes are for (0: none) */
    int n;                  /* ncharts x (pack_turns_max + 1) */
    turn_shape *t;
    size_t bytes, budget;
} pack_cache;

static void pack_cache_reset(pack_cache *pc, double g)
{
    for (int i = 0; i < pc->n; i++)
        if (pc->t[i].state) turn_shape_clear(&pc->t[i]);
    pc->bytes = 0;
    pc->g = g;
}

/* One way to place a chart: its shape at extra turn j in quarter turn k,
 * and the lowest place found for it (found = 0: none under the bound). */
typedef struct place_candidate {
    const turn_shape *t;
    int j, k;
    int found, x, y, value; /* value: the top edge (choose_lowest_top) or the bottom row */
} place_candidate;

/* Finds every candidate's lowest place, side by side on the OpenMP
 * threads. Each is searched only below the best value found so far (ties
 * included): that drops only candidates that lose, so the winner
 * (candidate_best) is the one an unbounded search of every candidate gives,
 * whatever the threads and the order their searches end in. Nothing here
 * allocates, so a failed allocation stops the packer at the same point on
 * any number of threads. */
static void candidates_search(const occupancy *occ, int choose, place_candidate *cand, int n)
{
    int bound = choose == choose_lowest_top ? occ->size + 1 : occ->size;
#pragma omp parallel for schedule(dynamic, 1) if (n > 1 && omp_get_max_threads() > 1)
    for (int i = 0; i < n; i++) {
        place_candidate *c = &cand[i];
        const footprint_spans *sp = &c->t->sp[c->k];
        int b;
#pragma omp atomic read
        b = bound;
        c->found = occupancy_find(occ, sp, choose == choose_lowest_top ? b : b + sp->h, &c->x, &c->y);
        if (!c->found) continue;
        c->value = choose == choose_lowest_top ? c->y + sp->h : c->y;
#pragma omp critical(pack_candidate_bound)
        {
            if (c->value < bound) bound = c->value;
        }
    }
}

/* The winner: lowest value, then leftmost, then first in the list (-1: none found). */
static int candidate_best(const place_candidate *cand, int n)
{
    int best = -1;
    for (int i = 0; i < n; i++) {
        const place_candidate *c = &cand[i];
        if (c->found && (best < 0 || c->value < cand[best].value ||
                         (c->value == cand[best].value && c->x < cand[best].x)))
            best = i;
    }
    return best;
}

/* One packing at global scale g (pixels per world unit). Returns 1 when all
 * charts fit (pl filled), 0 when one does not (*frac_placed: share of the
 * charts' box area placed so far), -1 on allocation failure. Charts in
 * P->done are left out; with P->allow_miss a chart that finds no room gets
 * k = -1 and the others are still placed. */
static int pack_attempt(const pack_ctx *P, pack_cache *pc, const pack_heuristic *hs, double g, placement *pl,
                        double *frac_placed)
{
    const int R = P->resolution, pad = P->padding;
    occupancy occ;
    /* A chart's shapes at its turns are made side by side, each thread with its own scratch. */
    int nt = omp_get_max_threads() > 0 ? omp_get_max_threads() : 1;
    size_t qn = 2 * (size_t)(P->max_verts > 0 ? P->max_verts : 1);
    double *q = mem_alloc(sizeof *q * qn * (size_t)nt);
    if (!q || occupancy_init(&occ, R, pad) != 0) { mem_free(q); return -1; }
    if (pc->g != g) pack_cache_reset(pc, g);
    double placed = 0, total = 0;
    for (int i = 0; i < P->ncharts; i++) {
        const chart_info *c = &P->ch[i];
        if (c->f_end > c->f_begin && !(P->done && P->done[i])) total += (g * c->W + 1) * (g * c->H + 1);
    }
    int rc = 1, missed = 0;
    /* Shapes made over the cache's budget live here until the chart is placed. */
    turn_shape scratch[pack_turns_max + 1];
    place_candidate cand[4 * (pack_turns_max + 1)];
    memset(scratch, 0, sizeof scratch);
    for (int n = 0; n < P->ncharts && rc == 1; n++) {
        int ci = P->sorted[hs->order][n];
        const chart_info *c = &P->ch[ci];
        if (c->f_end == c->f_begin || (P->done && P->done[ci])) continue;
        int ncand = 0, want[pack_turns_max + 1], nwant = 0, make[pack_turns_max + 1], nmake = 0, failed = 0;
        for (int j = 0; j <= pack_turns_max; j++) {
            /* Turn j is one of this heuristic's turns, or the smallest square's turn when it is
             * new and either this heuristic tries free turns or the chart fits no other way. */
            if (j < pack_turns_max ? j % (pack_turns_max / hs->turns) != 0
                                   : c->fit_angle == 0 || (hs->turns == 1 && g * fmax(c->W, c->H) + 1 <= R - 2 * pad))
                continue;
            want[nwant++] = j;
            if (!pc->t[(size_t)ci * (pack_turns_max + 1) + j].state) make[nmake++] = j;
        }
        /* The shapes not made yet at this scale, side by side (each depends
         * only on the chart, the turn and the scale); they are then kept or
         * not in turn order, as when they were made one by one. */
#pragma omp parallel for schedule(dynamic, 1) reduction(|| : failed) if (nmake > 1 && nt > 1)
        for (int k = 0; k < nmake; k++) {
            int th = omp_get_thread_num() < nt ? omp_get_thread_num() : 0;
            turn_shape *t = &scratch[make[k]];
            if (turn_shape_make(P, c, make[k], g, q + qn * (size_t)th, t) != 0) { turn_shape_clear(t); failed = 1; }
        }
        if (failed) rc = -1;
        for (int w = 0; w < nwant && rc == 1; w++) {
            int j = want[w];
            turn_shape *t = &pc->t[(size_t)ci * (pack_turns_max + 1) + j];
            if (!t->state) { /* made above: kept in the cache, or over budget used now and dropped */
                if (pc->bytes + scratch[j].bytes > pc->budget) {
                    t = &scratch[j];
                } else {
                    *t = scratch[j];
                    memset(&scratch[j], 0, sizeof scratch[j]);
                    pc->bytes += t->bytes;
                }
            }
            if (t->state != 1) continue;
            for (int k = 0; k < 4; k++)
                if (t->have[k]) cand[ncand++] = (place_candidate){.t = t, .j = j, .k = k};
        }
        if (rc == 1) {
            candidates_search(&occ, hs->choose, cand, ncand);
            int b = candidate_best(cand, ncand);
            if (b < 0) {
                if (P->allow_miss) { pl[ci].k = -1; missed = 1; }
                else rc = 0;
            } else {
                const place_candidate *w = &cand[b];
                occupancy_mark(&occ, &w->t->sp[w->k], w->x, w->y, pad);
                pl[ci] = (placement){.x = w->x, .y = w->y, .k = w->k, .w = w->t->w, .h = w->t->h, .j = w->j};
                placed += (g * c->W + 1) * (g * c->H + 1);
            }
        }
        for (int j = 0; j <= pack_turns_max; j++)
            if (scratch[j].state) turn_shape_clear(&scratch[j]);
    }
    occupancy_free(&occ);
    mem_free(q);
    *frac_placed = total > 0 ? placed / total : 1;
    return rc == 1 && missed ? 0 : rc;
}

/* The extra turn in [0, pi/2) whose bounding box has the shortest longer
 * side, sampled every half degree: a long thin (or curved) chart fits the
 * square along its diagonal at a scale where its minimum-area rectangle
 * would not. Kept only when it beats the rectangle by more than 1%. */
static void chart_fit_angle(const double *L, int nv, chart_info *c)
{
    const int steps = 180;
    c->fit_angle = 0;
    c->fit_side = fmax(c->W, c->H);
    double best = c->fit_side;
    for (int t = 1; t < steps; t++) {
        double a = t * half_pi / steps, cs = cos(a), sn = sin(a);
        double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
        for (int v = 0; v < nv; v++) {
            double x = cs * L[2 * v] - sn * L[2 * v + 1], y = sn * L[2 * v] + cs * L[2 * v + 1];
            if (x < lo[0]) lo[0] = x;
            if (x > hi[0]) hi[0] = x;
            if (y < lo[1]) lo[1] = y;
            if (y > hi[1]) hi[1] = y;
        }
        double side = fmax(hi[0] - lo[0], hi[1] - lo[1]);
        if (side < best) { best = side; c->fit_angle = a; }
    }
    if (best < 0.99 * c->fit_side) c->fit_side = best;
    else c->fit_angle = 0;
}

/* Builds the per-chart data: faces grouped by chart, UVs split per chart,
 * density scale, minimum-area rectangle. */
static neuv_status pack_prepare(const neuv_mesh *m, const int *face_chart, int ncharts, int keep_scale,
                                pack_ctx *P, int **new_tri_uv, int **old_of_new, int *nuv_new)
{
    int nf = m->nf;
    P->ncharts = ncharts;
    P->ch = mem_calloc((size_t)ncharts + 1, sizeof *P->ch);
    for (int h = 0; h < PACK_ORDERS; h++) P->sorted[h] = mem_alloc(sizeof *P->sorted[h] * ((size_t)ncharts + 1));
    P->ltri = mem_alloc(sizeof *P->ltri * 3 * ((size_t)nf + 1));
    int *order = mem_alloc(sizeof *order * ((size_t)nf + 1));
    int *start = mem_calloc((size_t)ncharts + 2, sizeof *start);
    int *stamp = mem_alloc(sizeof *stamp * ((size_t)m->nuv + 1));
    int *map = mem_alloc(sizeof *map * ((size_t)m->nuv + 1));
    *new_tri_uv = mem_alloc(sizeof **new_tri_uv * 3 * ((size_t)nf + 1));
    *old_of_new = mem_alloc(sizeof **old_of_new * 3 * ((size_t)nf + 1));
    neuv_status st = NEUV_OK;
    int sorted_ok = 1;
    for (int h = 0; h < PACK_ORDERS; h++) sorted_ok = sorted_ok && P->sorted[h];
    if (!P->ch || !sorted_ok || !P->ltri || !order || !start || !stamp || !map || !*new_tri_uv || !*old_of_new) {
        st = error_nomem("atlas packing");
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
    P->L = mem_alloc(sizeof *P->L * 2 * ((size_t)next + 1));
    if (!P->L) { st = error_nomem("atlas packing"); goto done; }
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
        if (min_area_rect(L, nv, &ci->theta, &W, &H) != 0) { st = error_nomem("atlas packing"); goto done; }
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
        chart_fit_angle(L, nv, ci);
    }
    chart_order *co = mem_alloc(sizeof *co * ((size_t)ncharts + 1));
    if (!co) { st = error_nomem("atlas packing"); goto done; }
    for (int h = 0; h < PACK_ORDERS; h++) {
        for (int c = 0; c < ncharts; c++) {
            const chart_info *ci = &P->ch[c];
            co[c].key = h == order_rect_area || h == order_shuffled ? ci->W * ci->H
                        : h == order_perimeter                     ? ci->W + ci->H
                        : h == order_short_side                    ? fmin(ci->W, ci->H)
                                                                   : ci->fit_side;
            co[c].id = c;
        }
        qsort(co, (size_t)ncharts, sizeof *co, cmp_chart_order);
        for (int c = 0; c < ncharts; c++) P->sorted[h][c] = co[c].id;
    }
    mem_free(co);
done:
    mem_free(order); mem_free(start); mem_free(stamp); mem_free(map);
    return st;
}

static void pack_ctx_free(pack_ctx *P)
{
    mem_free(P->ch); for (int h = 0; h < PACK_ORDERS; h++) mem_free(P->sorted[h]);
    mem_free(P->ltri); mem_free(P->L);
    memset(P, 0, sizeof *P);
}

/* The similarity of chart c placed by pl at global scale g (see pack.h):
 * uv' = (1/R) (Rot_k (g Rot_j (Rot_theta s uv - min) - m_j) + off_k + (x, y)),
 * with m_j the corner chart_oriented removed. */
static atlas_chart_transform chart_transform(const pack_ctx *P, const chart_info *c, const placement *pl,
                                             double g, double mjx, double mjy)
{
    const int R = P->resolution;
    atlas_chart_transform t;
    double a = chart_angle(c, pl->j), cs = pl->j ? cos(a) : 1, sn = pl->j ? sin(a) : 0;
    t.scale = g * c->s / R;
    t.angle = c->theta + a + pl->k * half_pi;
    /* Everything subtracted before the quarter turn: q = g Rot_j Rot_theta s uv - (mx, my). */
    double mx = g * (cs * c->minx - sn * c->miny) + mjx, my = g * (sn * c->minx + cs * c->miny) + mjy, ox, oy;
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

/* Same map as atlas_chart_transform_apply but from the very points that
 * were rasterized (q, from chart_oriented) with the quarter turn done
 * exactly, so the UVs land where the footprint was. */
static void chart_place_uv(const placement *pl, int R, const double q[2], double out[2])
{
    double x = q[0], y = q[1], px, py;
    switch (pl->k) {
    case 0: px = x; py = y; break;
    case 1: px = pl->h - y; py = x; break;
    case 2: px = pl->w - x; py = pl->h - y; break;
    default: px = y; py = pl->w - x; break;
    }
    out[0] = (px + pl->x) / R;
    out[1] = (py + pl->y) / R;
}

/* How many of the heuristics to try. With thousands of charts the time
 * goes to placements, and small charts fill the gaps whatever the order:
 * one is enough; the free turns (4 times the placements each) pay off on
 * tens to hundreds of large, long or concave charts. */
/* Memory the shapes of one scale may keep (256 MiB: a 1024 px atlas needs a few MiB). */
#define PACK_CACHE_BYTES ((size_t)256 << 20)

static int pack_heuristic_count(int ncharts)
{
    return ncharts > 1000 ? 1 : ncharts > 300 ? 4 : PACK_HEURISTICS;
}

/* Polish after the scale search (up to PACK_POLISH_MAX_CHARTS charts, where
 * a placement pass is cheap): the fixed orders are only four of the many
 * orders a few large charts can go in, and which one fits best is chaotic.
 * Try orders shuffled around the largest-rectangle-first order (each key
 * times a log-normal factor) at scales a step above the best fit; a fit
 * raises the scale and the same step is tried again, PACK_POLISH_TRIES
 * misses in a row move to a smaller step. The generator has a fixed seed,
 * so the result depends only on the charts. Returns -1 on allocation
 * failure, else 0 (*g and best_pl raised where a fit was found). */
#define PACK_POLISH_MAX_CHARTS 64
#define PACK_POLISH_TRIES 24

static int pack_polish(pack_ctx *P, pack_cache *pc, double *g, placement *pl, placement *best_pl, int *attempts)
{
    static const double steps[] = {0.03, 0.01, 0.004};
    if (P->ncharts < 2 || P->ncharts > PACK_POLISH_MAX_CHARTS) return 0;
    chart_order *co = mem_alloc(sizeof *co * (size_t)P->ncharts);
    if (!co) return -1;
    rng r;
    rng_seed(&r, 0x70ac4u);
    int rc = 0;
    /* Two charts have two orders, and with the two placement sides and two
     * turn counts 8 distinct tries: more misses in a row only repeat them. */
    int tries = P->ncharts == 2 ? 8 : PACK_POLISH_TRIES;
    for (size_t s = 0; s < sizeof steps / sizeof steps[0] && rc == 0; s++) {
        for (int misses = 0; misses < tries && rc == 0;) {
            for (int c = 0; c < P->ncharts; c++) {
                const chart_info *ci = &P->ch[c];
                co[c].key = ci->W * ci->H * exp(0.7 * rng_normal(&r));
                co[c].id = c;
            }
            qsort(co, (size_t)P->ncharts, sizeof *co, cmp_chart_order);
            for (int c = 0; c < P->ncharts; c++) P->sorted[order_shuffled][c] = co[c].id;
            pack_heuristic hs = {order_shuffled, misses % 2 ? choose_lowest_top : choose_lowest_bottom, misses % 3 ? 4 : 8};
            double g_try = *g * (1 + steps[s]), frac;
            int fit = pack_attempt(P, pc, &hs, g_try, pl, &frac);
            ++*attempts;
            if (fit < 0) rc = -1;
            else if (fit == 1) {
                *g = g_try;
                memcpy(best_pl, pl, sizeof *pl * (size_t)P->ncharts);
                misses = 0;
            } else {
                misses++;
            }
        }
    }
    mem_free(co);
    return rc;
}

/* One square: the largest global scale g at which every chart fits, by
 * shrinking from an upper bound and bisecting, then the polish. best_pl
 * holds the placements at *g_out. */
static neuv_status pack_search_scale(pack_ctx *P, pack_cache *cache, const atlas_pack_options *po, placement *pl,
                                     placement *best_pl, double *g_out, int *attempts_out)
{
    const atlas_pack_options o = *po;
    const int ncharts = P->ncharts;
    neuv_status st = NEUV_OK;
    /* Upper bound on the global scale: the charts' total area cannot exceed
     * the free square, nor can the longest chart side. Then shrink until
     * everything fits and bisect between the best fit and the first miss. */
    double inner = o.resolution - 2.0 * o.padding, area = 0, longest = 0;
    for (int c = 0; c < ncharts; c++) {
        const chart_info *ci = &P->ch[c];
        if (ci->f_end == ci->f_begin) continue;
        area += ci->area;
        if (ci->fit_side > longest) longest = ci->fit_side;
    }
    double g = INFINITY;
    if (area > 0) g = inner / sqrt(area);
    if (longest > 0) g = fmin(g, (inner - 1) / longest);
    if (!isfinite(g) || g <= 0) g = 1;
    double lo = 0, hi = 0, g0 = g;
    int attempts = 0, steps = 0;
    for (;;) {
        double frac = 0;
        int rc = 0;
        int nh = pack_heuristic_count(ncharts);
        for (int h = 0; h < nh && rc == 0; h++) {
            double fh;
            rc = pack_attempt(P, cache, &heuristics[h], g, pl, &fh);
            attempts++;
            if (fh > frac) frac = fh;
        }
        if (rc < 0) { st = error_nomem("atlas packing"); goto done; }
        if (rc == 1) {
            lo = g;
            memcpy(best_pl, pl, sizeof *pl * (size_t)ncharts);
            if (hi == 0) break; /* fits at the upper bound: nothing better exists */
        } else {
            hi = g;
        }
        if (lo > 0 && hi / lo < 1.001) break;
        /* Scale steps, not tries: a failing step costs one try per heuristic. */
        if (++steps >= 30) break;
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
        st = error_set(NEUV_ERR_INPUT, "%d charts do not fit in a %d px atlas with %d px padding",
                       ncharts, o.resolution, o.padding);
        goto done;
    }
    if (!o.quick && pack_polish(P, cache, &lo, pl, best_pl, &attempts) != 0) {
        st = error_nomem("atlas packing");
        goto done;
    }
    *g_out = lo;
done:
    *attempts_out = attempts;
    return st;
}

/* Fixed scale g (texels_per_unit): tiles filled one after another. For
 * each tile every heuristic places what fits of the charts left, and the
 * one that places the most chart area wins; those charts stay on the tile.
 * With few charts, orders shuffled as in pack_polish are tried too until
 * one places every chart left (at the density the one-square search
 * reaches, only a shuffled order may fit them all). best_pl and tile
 * (#charts) get each chart's place and tile, *ntiles the tiles used. */
static neuv_status pack_tiles(pack_ctx *P, pack_cache *cache, const atlas_pack_options *o, double g, placement *pl,
                              placement *best_pl, int *tile, int *ntiles, int *attempts)
{
    const int n = P->ncharts;
    unsigned char *done = mem_calloc((size_t)n + 1, 1);
    if (!done) return error_nomem("atlas packing");
    int left = 0;
    for (int c = 0; c < n; c++) {
        tile[c] = 0;
        if (P->ch[c].f_end == P->ch[c].f_begin) done[c] = 1;
        else left++;
    }
    P->done = done;
    P->allow_miss = 1;
    neuv_status st = NEUV_OK;
    int nt = 0, nh = pack_heuristic_count(left);
    int shuffles = left <= PACK_POLISH_MAX_CHARTS ? 2 * PACK_POLISH_TRIES : 0;
    chart_order *co = mem_alloc(sizeof *co * ((size_t)n + 1));
    if (!co) { mem_free(done); return error_nomem("atlas packing"); }
    rng r;
    rng_seed(&r, 0x711e5u);
    while (left > 0 && st == NEUV_OK) {
        if (nt == ATLAS_PACK_MAX_TILES) {
            st = error_set(NEUV_ERR_INPUT, "the charts need more than %d tiles of %d px at %g texels per unit",
                           ATLAS_PACK_MAX_TILES, o->resolution, o->texels_per_unit);
            break;
        }
        double best_area = 0;
        int best_n = 0;
        for (int h = 0; h < nh + shuffles; h++) {
            double frac;
            pack_heuristic hs;
            if (h < nh) {
                hs = heuristics[h];
            } else {
                int k = h - nh;
                for (int c = 0; c < n; c++) {
                    co[c].key = P->ch[c].W * P->ch[c].H * exp(0.7 * rng_normal(&r));
                    co[c].id = c;
                }
                qsort(co, (size_t)n, sizeof *co, cmp_chart_order);
                for (int c = 0; c < n; c++) P->sorted[order_shuffled][c] = co[c].id;
                hs.order = order_shuffled;
                hs.choose = k % 2 ? choose_lowest_top : choose_lowest_bottom;
                hs.turns = k % 3 ? 4 : 8;
            }
            int fit = pack_attempt(P, cache, &hs, g, pl, &frac);
            ++*attempts;
            if (fit < 0) { st = error_nomem("atlas packing"); break; }
            double area = 0;
            int placed = 0;
            for (int c = 0; c < n; c++)
                if (!done[c] && pl[c].k >= 0) { area += P->ch[c].area; placed++; }
            if (placed > 0 && area > best_area) {
                best_area = area;
                best_n = placed;
                for (int c = 0; c < n; c++)
                    if (!done[c]) best_pl[c] = pl[c];
            }
            if (fit == 1) break; /* everything left fits this tile */
        }
        if (st != NEUV_OK) break;
        if (best_n == 0) { /* not even the largest chart left fits an empty tile */
            int big = -1;
            for (int i = 0; i < n && big < 0; i++)
                if (!done[P->sorted[order_long_side][i]]) big = P->sorted[order_long_side][i];
            const chart_info *c = &P->ch[big];
            st = error_set(NEUV_ERR_INPUT,
                           "chart %d is %.0f x %.0f px at %g texels per unit, too large for one %d px tile with %d px "
                           "padding: lower texels_per_unit or raise the resolution",
                           big, ceil(g * c->W), ceil(g * c->H), o->texels_per_unit, o->resolution, o->padding);
            break;
        }
        for (int c = 0; c < n; c++)
            if (!done[c] && best_pl[c].k >= 0) { done[c] = 1; tile[c] = nt; left--; }
        nt++;
    }
    P->done = NULL;
    P->allow_miss = 0;
    mem_free(done);
    mem_free(co);
    *ntiles = nt > 0 ? nt : 1;
    return st;
}

neuv_status atlas_pack(neuv_mesh *m, const int *face_chart, int ncharts,
                       const atlas_pack_options *opt, atlas_chart_transform *xf,
                       atlas_pack_result *res)
{
    atlas_pack_options o;
    if (opt) o = *opt;
    else atlas_pack_options_default(&o);
    if (!m || m->nuv <= 0 || !m->tri_uv) return error_set(NEUV_ERR_INPUT, "packing needs a mesh with UVs");
    if (o.resolution < 8 || o.resolution > 32768)
        return error_set(NEUV_ERR_INPUT, "atlas resolution %d px is outside 8..32768", o.resolution);
    if (o.padding < 0 || 2 * o.padding + 1 > o.resolution)
        return error_set(NEUV_ERR_INPUT, "padding %d px does not fit in a %d px atlas", o.padding, o.resolution);
    if (ncharts < 0) return error_set(NEUV_ERR_INPUT, "negative chart count");
    for (int f = 0; f < m->nf; f++)
        if (face_chart[f] < 0 || face_chart[f] >= ncharts)
            return error_set(NEUV_ERR_INPUT, "face %d has chart id %d outside 0..%d", f, face_chart[f], ncharts - 1);
    for (int f = 0; f < 3 * m->nf; f++)
        if (m->tri_uv[f] < 0 || m->tri_uv[f] >= m->nuv)
            return error_set(NEUV_ERR_INPUT, "face %d uses UV index %d outside 0..%d", f / 3, m->tri_uv[f], m->nuv - 1);
    for (int u = 0; u < 2 * m->nuv; u++)
        if (!isfinite(m->uv[u])) return error_set(NEUV_ERR_INPUT, "UV %d is not a finite number", u / 2);
    if (!(o.texels_per_unit >= 0) || !isfinite(o.texels_per_unit))
        return error_set(NEUV_ERR_INPUT, "texels per unit must be a finite number >= 0, got %g", o.texels_per_unit);
    if (o.texels_per_unit > 0 && o.keep_scale)
        return error_set(NEUV_ERR_INPUT, "texels per unit sets every chart's scale: it cannot keep the charts' relative scales");

    pack_ctx P;
    memset(&P, 0, sizeof P);
    pack_cache cache;
    memset(&cache, 0, sizeof cache);
    P.resolution = o.resolution;
    P.padding = o.padding;
    int *new_tri_uv = NULL, *old_of_new = NULL, nuv_new = 0;
    placement *pl = NULL, *best_pl = NULL;
    double *uv_new = NULL, *q = NULL;
    int *tile = NULL;
    neuv_status st = pack_prepare(m, face_chart, ncharts, o.keep_scale, &P, &new_tri_uv, &old_of_new, &nuv_new);
    if (st != NEUV_OK) goto done;
    cache.n = ncharts * (pack_turns_max + 1);
    cache.t = mem_calloc((size_t)cache.n + 1, sizeof *cache.t);
    cache.budget = PACK_CACHE_BYTES;
    if (!cache.t) { st = error_nomem("atlas packing"); goto done; }
    pl = mem_calloc((size_t)ncharts + 1, sizeof *pl);
    best_pl = mem_calloc((size_t)ncharts + 1, sizeof *best_pl);
    uv_new = mem_alloc(sizeof *uv_new * 2 * ((size_t)nuv_new + 1));
    q = mem_alloc(sizeof *q * 2 * ((size_t)P.max_verts + 1));
    if (!pl || !best_pl || !uv_new || !q) { st = error_nomem("atlas packing"); goto done; }

    int ntiles = 1, attempts = 0;
    double g = 0;
    if (o.texels_per_unit > 0) {
        g = o.texels_per_unit;
        tile = mem_alloc(sizeof *tile * ((size_t)ncharts + 1));
        if (!tile) { st = error_nomem("atlas packing"); goto done; }
        st = pack_tiles(&P, &cache, &o, g, pl, best_pl, tile, &ntiles, &attempts);
    } else {
        st = pack_search_scale(&P, &cache, &o, pl, best_pl, &g, &attempts);
    }
    if (st != NEUV_OK) goto done;
    for (int c = 0; c < ncharts; c++) {
        const chart_info *ci = &P.ch[c];
        if (ci->f_end == ci->f_begin) {
            if (xf) { xf[c].scale = 1; xf[c].angle = 0; xf[c].tx = 0; xf[c].ty = 0; }
            continue;
        }
        int w, h;
        double mjx, mjy;
        /* Tile k is the unit square whose corner is (k mod 10, k div 10) (UDIM 1001 + k). */
        int u0 = tile ? tile[c] % 10 : 0, v0 = tile ? tile[c] / 10 : 0;
        chart_oriented(&P, ci, best_pl[c].j, g, q, &w, &h, &mjx, &mjy);
        if (xf) {
            xf[c] = chart_transform(&P, ci, &best_pl[c], g, mjx, mjy);
            xf[c].tx += u0;
            xf[c].ty += v0;
        }
        for (int v = ci->v_begin; v < ci->v_end; v++) {
            double *out = uv_new + 2 * (size_t)v;
            chart_place_uv(&best_pl[c], o.resolution, q + 2 * (size_t)(v - ci->v_begin), out);
            out[0] += u0;
            out[1] += v0;
        }
    }
    st = mesh_set_uv(m, nuv_new, uv_new, new_tri_uv);
    if (st != NEUV_OK) goto done;
    if (res) {
        double a = 0, a3 = mesh_total_area(m);
        for (int f = 0; f < m->nf; f++) {
            const int *t = m->tri_uv + 3 * f;
            a += fabs(tri_area_2d(m->uv + 2 * t[0], m->uv + 2 * t[1], m->uv + 2 * t[2]));
        }
        res->efficiency = a / ntiles;
        res->texel_scale = a3 > 0 ? o.resolution * sqrt(a / a3) : 0;
        res->attempts = attempts;
        res->tiles = ntiles;
    }
done:
    if (cache.t) pack_cache_reset(&cache, 0);
    mem_free(cache.t);
    pack_ctx_free(&P);
    mem_free(new_tri_uv); mem_free(old_of_new); mem_free(pl); mem_free(best_pl); mem_free(uv_new); mem_free(q);
    mem_free(tile);
    return st;
}
