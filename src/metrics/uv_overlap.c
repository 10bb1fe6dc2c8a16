#include "metrics/uv_overlap.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/mem.h"

/* Rows per sweep of the difference buffer (32 x 2049 x 4 bytes = 256 KiB). */
#define RASTER_BAND 32

/* One directed triangle edge A -> B, with what the coverage test needs. */
typedef struct raster_edge {
    double px, py, dx, dy; /* origin and direction from the lexicographically smaller endpoint */
    double sign;           /* +1 when A is that endpoint, -1 otherwise */
    int top_left;          /* a centre exactly on the edge counts as inside */
    int grows;             /* the edge function grows with x (keeps the right part of a row) */
    double slope;          /* dx / dy: where the edge crosses a row, only to start the search */
} raster_edge;

static void edge_setup(raster_edge *e, double ax, double ay, double bx, double by)
{
    /* Evaluating from the same endpoint whatever the direction makes the two
     * faces of a shared edge see exactly opposite values, so rounding cannot
     * put a centre near the edge inside both (or neither). */
    int a_first = ax < bx || (ax == bx && ay < by);
    e->px = a_first ? ax : bx;
    e->py = a_first ? ay : by;
    e->dx = a_first ? bx - ax : ax - bx;
    e->dy = a_first ? by - ay : ay - by;
    e->sign = a_first ? 1.0 : -1.0;
    /* Exactly one of the two directions of any edge qualifies. */
    e->top_left = by < ay || (by == ay && bx > ax);
    e->grows = e->sign * e->dy < 0;
    e->slope = e->dy != 0 ? e->dx / e->dy : 0;
}

static int edge_inside(const raster_edge *e, double cx, double cy)
{
    double w = e->sign * (e->dx * (cy - e->py) - e->dy * (cx - e->px));
    return w > 0 || (w == 0 && e->top_left);
}

/* Narrows [*lo, *hi] to the centres of row cy inside edge e. The edge
 * function as evaluated in floating point is monotone along a row (each
 * rounding step is), so the inside centres form a half-line: a guess from the
 * exact crossing, corrected by a step or two of exact tests, finds the same
 * centres as testing every pixel would. */
static void edge_clip_span(const raster_edge *e, double cy, int *lo, int *hi)
{
    if (e->dy == 0) { /* horizontal: the whole row is in or out */
        if (!edge_inside(e, *lo + 0.5, cy)) *hi = *lo - 1;
        return;
    }
    /* Column where w = 0, clamped before the cast; truncation is fine as it
     * only starts the exact search. */
    double cross = e->px + e->slope * (cy - e->py) - 0.5;
    if (e->grows) { /* keep the right part */
        int k = (int)fmax(*lo, fmin(*hi + 1, cross));
        while (k > *lo && edge_inside(e, k - 0.5, cy)) k--;
        while (k <= *hi && !edge_inside(e, k + 0.5, cy)) k++;
        *lo = k;
    } else { /* keep the left part */
        int k = (int)fmax(*lo - 1, fmin(*hi, cross));
        while (k < *hi && edge_inside(e, k + 1.5, cy)) k++;
        while (k >= *lo && !edge_inside(e, k + 0.5, cy)) k--;
        *hi = k;
    }
}

static double clamp_index(double x, double hi)
{
    return x < 0 ? 0 : (x > hi ? hi : x);
}

/* The raster edges of face f's UV triangle (pixel units: (uv - lo) * s),
 * counter-clockwise, and its box (xmin, xmax, ymin, ymax). Returns 0 for a
 * flat triangle, which covers no centre under the rule. */
static int triangle_edges(const double *uv, const int *t, const double lo[2], double s, raster_edge e[3], double box[4])
{
    double x[3], y[3];
    for (int k = 0; k < 3; k++) {
        const double *q = uv + 2 * (size_t)t[k];
        x[k] = (q[0] - lo[0]) * s;
        y[k] = (q[1] - lo[1]) * s;
    }
    double area2 = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
    if (area2 == 0) return 0;
    int b = area2 > 0 ? 1 : 2, c = area2 > 0 ? 2 : 1; /* counter-clockwise order 0, b, c */
    edge_setup(&e[0], x[0], y[0], x[b], y[b]);
    edge_setup(&e[1], x[b], y[b], x[c], y[c]);
    edge_setup(&e[2], x[c], y[c], x[0], y[0]);
    box[0] = fmin(x[0], fmin(x[1], x[2]));
    box[1] = fmax(x[0], fmax(x[1], x[2]));
    box[2] = fmin(y[0], fmin(y[1], y[2]));
    box[3] = fmax(y[0], fmax(y[1], y[2]));
    return 1;
}

neuv_status uv_coverage_count(const double *uv, int nf, const int *tri_uv,
                              const unsigned char *face_mask, int resolution, uv_coverage *out)
{
    out->covered = out->overlapped = 0;
    if (resolution < 1 || resolution > 32768)
        return error_set(NEUV_ERR_INPUT, "raster resolution %d is outside [1, 32768]", resolution);
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (int f = 0; f < nf; f++) {
        if (face_mask && !face_mask[f]) continue;
        for (int k = 0; k < 3; k++) {
            const double *q = uv + 2 * (size_t)tri_uv[3 * (size_t)f + k];
            for (int d = 0; d < 2; d++) {
                if (q[d] < lo[d]) lo[d] = q[d];
                if (q[d] > hi[d]) hi[d] = q[d];
            }
        }
    }
    double ext_u = hi[0] - lo[0], ext_v = hi[1] - lo[1];
    double side = ext_u > ext_v ? ext_u : ext_v;
    if (!(side > 0) || !isfinite(side)) return NEUV_OK; /* nothing drawn, or all on one point */
    double s = resolution / side;
    int width = (int)clamp_index(ceil(ext_u * s), resolution);
    int height = (int)clamp_index(ceil(ext_v * s), resolution);
    if (width < 1) width = 1;
    if (height < 1) height = 1;
    /* Row range of each drawn face (empty when not drawn). */
    int *rows = mem_alloc(sizeof *rows * 2 * (size_t)(nf > 0 ? nf : 1));
    /* Coverage is counted through per-row difference arrays: +1 where a
     * triangle's span starts, -1 after it ends. The cost is the number of rows
     * a triangle spans, not its pixels, so maps that stack many faces on the
     * same region (every face on the unit square) stay fast. The raster is
     * swept in bands of rows small enough to stay in cache. */
    size_t stride = (size_t)width + 1;
    int32_t *diff = mem_calloc(stride * RASTER_BAND, sizeof *diff);
    int nbands = (height + RASTER_BAND - 1) / RASTER_BAND;
    /* Faces by the band of their first row (counting sort), and the faces
     * that reach the band being drawn: each band visits only its own faces,
     * so the sweep costs the bands each face spans, not bands times faces
     * (a 1.4M-face atlas at 2048 px visited every face 64 times per test). */
    int *band_first = mem_calloc((size_t)nbands + 1, sizeof *band_first);
    int *fill = mem_alloc(sizeof *fill * (size_t)nbands);
    int *by_band = mem_alloc(sizeof *by_band * (size_t)(nf > 0 ? nf : 1));
    int *active = mem_alloc(sizeof *active * (size_t)(nf > 0 ? nf : 1));
    if (!rows || !diff || !band_first || !fill || !by_band || !active) {
        mem_free(rows); mem_free(diff); mem_free(band_first); mem_free(fill); mem_free(by_band); mem_free(active);
        return error_nomem("overlap raster");
    }
    for (int f = 0; f < nf; f++) {
        rows[2 * f] = 1;
        rows[2 * f + 1] = 0;
        if (face_mask && !face_mask[f]) continue;
        double ymin = INFINITY, ymax = -INFINITY;
        for (int k = 0; k < 3; k++) {
            double y = (uv[2 * (size_t)tri_uv[3 * (size_t)f + k] + 1] - lo[1]) * s;
            ymin = fmin(ymin, y);
            ymax = fmax(ymax, y);
        }
        /* One row of margin: the edge functions alone decide, the box only bounds the work. */
        rows[2 * f] = (int)clamp_index(floor(ymin - 0.5), height - 1);
        rows[2 * f + 1] = (int)clamp_index(ceil(ymax - 0.5), height - 1);
    }

    for (int f = 0; f < nf; f++)
        if (rows[2 * f] <= rows[2 * f + 1]) band_first[rows[2 * f] / RASTER_BAND + 1]++;
    for (int b = 0; b < nbands; b++) band_first[b + 1] += band_first[b];
    memcpy(fill, band_first, sizeof *fill * (size_t)nbands);
    for (int f = 0; f < nf; f++)
        if (rows[2 * f] <= rows[2 * f + 1]) by_band[fill[rows[2 * f] / RASTER_BAND]++] = f;
    int nactive = 0;
    for (int band = 0; band < height; band += RASTER_BAND) {
        int band_end = band + RASTER_BAND - 1 < height - 1 ? band + RASTER_BAND - 1 : height - 1;
        for (int k = band_first[band / RASTER_BAND]; k < band_first[band / RASTER_BAND + 1]; k++)
            active[nactive++] = by_band[k];
        memset(diff, 0, sizeof *diff * stride * RASTER_BAND);
        for (int a = 0; a < nactive; a++) {
            int f = active[a];
            int j0 = rows[2 * f] > band ? rows[2 * f] : band;
            int j1 = rows[2 * f + 1] < band_end ? rows[2 * f + 1] : band_end;
            if (j0 > j1) continue;
            raster_edge e[3];
            double box[4];
            if (!triangle_edges(uv, tri_uv + 3 * (size_t)f, lo, s, e, box)) continue;
            double xmin = box[0], xmax = box[1];
            int i0 = (int)clamp_index(floor(xmin - 0.5), width - 1);
            int i1 = (int)clamp_index(ceil(xmax - 0.5), width - 1);
            for (int j = j0; j <= j1; j++) {
                double cy = j + 0.5;
                int span_lo = i0, span_hi = i1;
                for (int k = 0; k < 3 && span_lo <= span_hi; k++)
                    edge_clip_span(&e[k], cy, &span_lo, &span_hi);
                if (span_lo > span_hi) continue;
                diff[(size_t)(j - band) * stride + span_lo] += 1;
                diff[(size_t)(j - band) * stride + span_hi + 1] -= 1;
            }
        }
        int kept = 0;
        for (int a = 0; a < nactive; a++)
            if (rows[2 * active[a] + 1] > band_end) active[kept++] = active[a];
        nactive = kept;
        for (int j = band; j <= band_end; j++) {
            const int32_t *row = diff + (size_t)(j - band) * stride;
            long long depth = 0;
            for (int i = 0; i < width; i++) {
                depth += row[i];
                out->covered += depth >= 1;
                out->overlapped += depth >= 2;
            }
        }
    }
    mem_free(rows); mem_free(diff); mem_free(band_first); mem_free(fill); mem_free(by_band); mem_free(active);
    return NEUV_OK;
}

double uv_coverage_overlap_fraction(const uv_coverage *c)
{
    return c->covered > 0 ? (double)c->overlapped / (double)c->covered : 0.0;
}

/* One covered run of pixel centres of one face in one row. */
typedef struct face_span_px {
    int row, lo, hi, face;
} face_span_px;

/* The pixel-centre spans of every face on the overlap raster, sorted by
 * row: *spans (caller frees), row_start (#height + 1, caller frees).
 * *height 0: nothing drawn. Returns NEUV_OK, NEUV_ERR_INPUT, NEUV_ERR_NOMEM. */
static neuv_status face_spans_by_row(const double *uv, int nf, const int *tri_uv, int resolution,
                                     face_span_px **spans, int **row_start_out, int *width_out, int *height_out)
{
    *spans = NULL;
    *row_start_out = NULL;
    *width_out = *height_out = 0;
    if (resolution < 1 || resolution > 32768)
        return error_set(NEUV_ERR_INPUT, "raster resolution %d is outside [1, 32768]", resolution);
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (size_t c = 0; c < 3 * (size_t)(nf > 0 ? nf : 0); c++)
        for (int d = 0; d < 2; d++) {
            double q = uv[2 * (size_t)tri_uv[c] + d];
            if (q < lo[d]) lo[d] = q;
            if (q > hi[d]) hi[d] = q;
        }
    double side = fmax(hi[0] - lo[0], hi[1] - lo[1]);
    if (!(side > 0) || !isfinite(side)) return NEUV_OK;
    double s = resolution / side;
    int width = (int)clamp_index(ceil((hi[0] - lo[0]) * s), resolution);
    int height = (int)clamp_index(ceil((hi[1] - lo[1]) * s), resolution);
    if (width < 1) width = 1;
    if (height < 1) height = 1;
    size_t cap = 4 * (size_t)(nf > 0 ? nf : 1), n = 0;
    face_span_px *sp = mem_alloc(sizeof *sp * cap);
    if (!sp) return error_nomem("overlap raster");
    for (int f = 0; f < nf; f++) {
        raster_edge e[3];
        double box[4];
        if (!triangle_edges(uv, tri_uv + 3 * (size_t)f, lo, s, e, box)) continue;
        double xmin = box[0], xmax = box[1], ymin = box[2], ymax = box[3];
        int j0 = (int)clamp_index(floor(ymin - 0.5), height - 1), j1 = (int)clamp_index(ceil(ymax - 0.5), height - 1);
        int i0 = (int)clamp_index(floor(xmin - 0.5), width - 1), i1 = (int)clamp_index(ceil(xmax - 0.5), width - 1);
        for (int j = j0; j <= j1; j++) {
            int span_lo = i0, span_hi = i1;
            for (int k = 0; k < 3 && span_lo <= span_hi; k++) edge_clip_span(&e[k], j + 0.5, &span_lo, &span_hi);
            if (span_lo > span_hi) continue;
            if (n == cap) {
                face_span_px *g = mem_realloc(sp, sizeof *sp * cap * 2);
                if (!g) { mem_free(sp); return error_nomem("overlap raster"); }
                sp = g;
                cap *= 2;
            }
            sp[n++] = (face_span_px){j, span_lo, span_hi, f};
        }
    }
    /* By row (counting sort). */
    int *row_start = mem_calloc((size_t)height + 1, sizeof *row_start);
    face_span_px *sorted = mem_alloc(sizeof *sorted * (n > 0 ? n : 1));
    if (!row_start || !sorted) {
        mem_free(sp); mem_free(row_start); mem_free(sorted);
        return error_nomem("overlap raster");
    }
    for (size_t i = 0; i < n; i++) row_start[sp[i].row + 1]++;
    for (int j = 0; j < height; j++) row_start[j + 1] += row_start[j];
    for (size_t i = 0; i < n; i++) sorted[row_start[sp[i].row]++] = sp[i];
    for (int j = height; j > 0; j--) row_start[j] = row_start[j - 1];
    row_start[0] = 0;
    mem_free(sp);
    *spans = sorted;
    *row_start_out = row_start;
    *width_out = width;
    *height_out = height;
    return NEUV_OK;
}

static int key_order(const void *x, const void *y)
{
    uint64_t a = *(const uint64_t *)x, b = *(const uint64_t *)y;
    return (a > b) - (a < b);
}

neuv_status uv_overlap_chart_pairs(const double *uv, int nf, const int *tri_uv, const int *face_chart,
                                   int resolution, int **pairs_out, int *n_pairs)
{
    *pairs_out = NULL;
    *n_pairs = 0;
    face_span_px *sp;
    int *row_start, width, height;
    neuv_status st = face_spans_by_row(uv, nf, tri_uv, resolution, &sp, &row_start, &width, &height);
    if (st || height == 0) return st;
    /* Each row is painted with chart ids, and a pixel centre painted by another chart gives a pair. */
    int *owner = mem_alloc(sizeof *owner * (size_t)width);
    size_t kcap = 64, nk = 0;
    uint64_t *keys = mem_alloc(sizeof *keys * kcap);
    if (!owner || !keys) {
        mem_free(sp); mem_free(row_start); mem_free(owner); mem_free(keys);
        return error_nomem("overlap raster");
    }
    uint64_t last = UINT64_MAX;
    for (int j = 0; j < height; j++) {
        if (row_start[j] == row_start[j + 1]) continue;
        for (int i = 0; i < width; i++) owner[i] = -1;
        for (int k = row_start[j]; k < row_start[j + 1]; k++) {
            const face_span_px *t = &sp[k];
            int tc = face_chart[t->face];
            for (int i = t->lo; i <= t->hi; i++) {
                int o = owner[i];
                owner[i] = tc;
                if (o < 0 || o == tc) continue;
                int p = o < tc ? o : tc, q = o < tc ? tc : o;
                uint64_t key = (uint64_t)(uint32_t)p << 32 | (uint32_t)q;
                if (key == last) continue;
                if (nk == kcap) {
                    uint64_t *g = mem_realloc(keys, sizeof *keys * kcap * 2);
                    if (!g) { mem_free(sp); mem_free(row_start); mem_free(owner); mem_free(keys); return error_nomem("overlap raster"); }
                    keys = g;
                    kcap *= 2;
                }
                keys[nk++] = last = key;
            }
        }
    }
    mem_free(row_start);
    mem_free(owner);
    qsort(keys, nk, sizeof *keys, key_order);
    size_t nu = 0;
    for (size_t k = 0; k < nk; k++)
        if (nu == 0 || keys[k] != keys[nu - 1]) keys[nu++] = keys[k];
    int *pairs = mem_alloc(sizeof *pairs * 2 * (nu > 0 ? nu : 1));
    if (!pairs) { mem_free(sp); mem_free(keys); return error_nomem("overlap raster"); }
    for (size_t k = 0; k < nu; k++) {
        pairs[2 * k] = (int)(keys[k] >> 32);
        pairs[2 * k + 1] = (int)(keys[k] & 0xffffffffu);
    }
    mem_free(sp); mem_free(keys);
    *pairs_out = pairs;
    *n_pairs = (int)nu;
    return NEUV_OK;
}

neuv_status uv_overlap_faces(const double *uv, int nf, const int *tri_uv, const int *face_chart, int resolution,
                             unsigned char *hit)
{
    if (nf > 0) memset(hit, 0, (size_t)nf);
    face_span_px *sp;
    int *row_start, width, height;
    neuv_status st = face_spans_by_row(uv, nf, tri_uv, resolution, &sp, &row_start, &width, &height);
    if (st || height == 0) return st;
    /* Per row: the chart that paints each pixel centre first, -2 where a
     * second chart paints it too; then every span over such a centre hits. */
    int *owner = mem_alloc(sizeof *owner * (size_t)width);
    if (!owner) { mem_free(sp); mem_free(row_start); return error_nomem("overlap raster"); }
    for (int j = 0; j < height; j++) {
        if (row_start[j] == row_start[j + 1]) continue;
        for (int i = 0; i < width; i++) owner[i] = -1;
        int any = 0;
        for (int k = row_start[j]; k < row_start[j + 1]; k++) {
            int tc = face_chart[sp[k].face];
            for (int i = sp[k].lo; i <= sp[k].hi; i++) {
                if (owner[i] == -1) owner[i] = tc;
                else if (owner[i] != tc && owner[i] != -2) { owner[i] = -2; any = 1; }
            }
        }
        if (!any) continue;
        for (int k = row_start[j]; k < row_start[j + 1]; k++)
            for (int i = sp[k].lo; i <= sp[k].hi && !hit[sp[k].face]; i++)
                if (owner[i] == -2) hit[sp[k].face] = 1;
    }
    mem_free(sp); mem_free(row_start); mem_free(owner);
    return NEUV_OK;
}
