#include "atlas/footprint.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/mem.h"

/* Pixels are grown by this much so that the similarity applied to the final
 * UVs (computed afresh, rounding differently) never leaves a marked pixel. */
static const double raster_eps = 1e-7;

static int footprint_alloc(footprint *f, int w, int h)
{
    f->w = w; f->h = h;
    f->bits = mem_calloc((size_t)w * (size_t)h > 0 ? (size_t)w * (size_t)h : 1, 1);
    return f->bits ? 0 : -1;
}

void footprint_free(footprint *f)
{
    if (!f) return;
    mem_free(f->bits);
    f->bits = NULL;
    f->w = f->h = 0;
}

/* x-range of triangle (a,b,c) inside the horizontal slab y0 <= y <= y1;
 * returns 0 when the triangle misses the slab. */
static int slab_range(const double *a, const double *b, const double *c, double y0, double y1,
                      double *xlo, double *xhi)
{
    const double *v[3] = {a, b, c};
    double lo = INFINITY, hi = -INFINITY;
    for (int k = 0; k < 3; k++) {
        const double *s = v[k], *t = v[(k + 1) % 3];
        if (s[1] >= y0 && s[1] <= y1) {
            if (s[0] < lo) lo = s[0];
            if (s[0] > hi) hi = s[0];
        }
        double ylo = s[1] < t[1] ? s[1] : t[1], yhi = s[1] < t[1] ? t[1] : s[1];
        if (yhi == ylo) continue;
        double ys[2] = {y0, y1};
        for (int e = 0; e < 2; e++) {
            if (ys[e] < ylo || ys[e] > yhi) continue;
            double x = s[0] + (t[0] - s[0]) * (ys[e] - s[1]) / (t[1] - s[1]);
            if (x < lo) lo = x;
            if (x > hi) hi = x;
        }
    }
    if (lo > hi) return 0;
    *xlo = lo; *xhi = hi;
    return 1;
}

int footprint_rasterize(const double *p, const int *tri, int ntri, int w, int h, footprint *out)
{
    if (footprint_alloc(out, w, h) != 0) return -1;
    for (int t = 0; t < ntri; t++) {
        const double *a = p + 2 * tri[3 * t], *b = p + 2 * tri[3 * t + 1], *c = p + 2 * tri[3 * t + 2];
        double ymin = fmin(a[1], fmin(b[1], c[1])), ymax = fmax(a[1], fmax(b[1], c[1]));
        int j0 = (int)floor(ymin - raster_eps), j1 = (int)floor(ymax + raster_eps);
        if (j0 == j1 && j0 >= 0 && j0 < h) {
            /* Inside one row's slab, clear of its grown edges: slab_range
             * would find every corner inside and no edge crossing, so the
             * range is the corners' (most triangles of a large chart at a
             * trial packing's scale are this small). */
            double xlo = fmin(a[0], fmin(b[0], c[0])), xhi = fmax(a[0], fmax(b[0], c[0]));
            int i0 = (int)floor(xlo - raster_eps), i1 = (int)floor(xhi + raster_eps);
            if (i0 < 0) i0 = 0;
            if (i1 > w - 1) i1 = w - 1;
            if (i1 >= i0) memset(out->bits + (size_t)j0 * w + i0, 1, (size_t)(i1 - i0 + 1));
            continue;
        }
        if (j0 < 0) j0 = 0;
        if (j1 > h - 1) j1 = h - 1;
        for (int j = j0; j <= j1; j++) {
            double xlo, xhi;
            if (!slab_range(a, b, c, j - raster_eps, j + 1 + raster_eps, &xlo, &xhi)) continue;
            int i0 = (int)floor(xlo - raster_eps), i1 = (int)floor(xhi + raster_eps);
            if (i0 < 0) i0 = 0;
            if (i1 > w - 1) i1 = w - 1;
            if (i1 >= i0) memset(out->bits + (size_t)j * w + i0, 1, (size_t)(i1 - i0 + 1));
        }
    }
    return 0;
}

int footprint_rotate(const footprint *in, int k, footprint *out)
{
    k &= 3;
    int w = in->w, h = in->h;
    int ow = (k & 1) ? h : w, oh = (k & 1) ? w : h;
    if (footprint_alloc(out, ow, oh) != 0) return -1;
    const unsigned char *src = in->bits;
    unsigned char *dst = out->bits;
    /* Pixel (i, j) goes to (oi, oj) = k 1: (h-1-j, i), 2: (w-1-i, h-1-j), 3: (j, w-1-i). */
    if (k == 0) {
        memcpy(dst, src, (size_t)w * h);
    } else if (k == 2) {
        for (int j = 0; j < h; j++) {
            const unsigned char *row = src + (size_t)j * w;
            unsigned char *orow = dst + (size_t)(h - 1 - j) * w;
            for (int i = 0; i < w; i++) orow[w - 1 - i] = row[i];
        }
    } else {
        /* A transpose (with one axis reversed), in 32 by 32 tiles so that the
         * column reads stay in cache: k 1: (i, j) -> (h-1-j, i); k 3: (j, w-1-i). */
        enum { tile = 32 };
        for (int j0 = 0; j0 < h; j0 += tile)
            for (int i0 = 0; i0 < w; i0 += tile) {
                int j1 = j0 + tile < h ? j0 + tile : h, i1 = i0 + tile < w ? i0 + tile : w;
                for (int j = j0; j < j1; j++) {
                    const unsigned char *row = src + (size_t)j * w;
                    if (k == 1)
                        for (int i = i0; i < i1; i++) dst[(size_t)i * ow + (h - 1 - j)] = row[i];
                    else
                        for (int i = i0; i < i1; i++) dst[(size_t)(w - 1 - i) * ow + j] = row[i];
                }
            }
    }
    return 0;
}

/* Appends run [a, b] to the spans (capacity *cap, doubled when full). Returns 0 or -1. */
static int spans_push(footprint_spans *s, int *cap, int a, int b)
{
    if (s->count == *cap) {
        int nc = *cap * 2;
        int *x0 = mem_realloc(s->x0, sizeof(int) * (size_t)nc);
        if (x0) s->x0 = x0;
        int *x1 = x0 ? mem_realloc(s->x1, sizeof(int) * (size_t)nc) : NULL;
        if (x1) s->x1 = x1;
        if (!x0 || !x1) return -1;
        *cap = nc;
    }
    s->x0[s->count] = a;
    s->x1[s->count] = b;
    s->count++;
    return 0;
}

/* row_order from row_width: wide rows first (a blocked wide span lets the
 * search jump far), ties by row, by a counting sort. Returns 0 or -1. */
static int spans_order_rows(footprint_spans *s)
{
    s->row_order = mem_alloc(sizeof(int) * (size_t)(s->h > 0 ? s->h : 1));
    if (!s->row_order) return -1;
    int maxw = 0;
    for (int j = 0; j < s->h; j++) if (s->row_width[j] > maxw) maxw = s->row_width[j];
    int *count = mem_calloc((size_t)maxw + 2, sizeof *count);
    if (!count) return -1;
    for (int j = 0; j < s->h; j++) count[maxw - s->row_width[j] + 1]++;
    for (int k = 1; k <= maxw + 1; k++) count[k] += count[k - 1];
    for (int j = 0; j < s->h; j++) s->row_order[count[maxw - s->row_width[j]]++] = j;
    mem_free(count);
    return 0;
}

int footprint_to_spans(const footprint *in, footprint_spans *out)
{
    memset(out, 0, sizeof *out);
    out->w = in->w; out->h = in->h;
    int cap = 2 * (in->h > 0 ? in->h : 1);
    out->row_first = mem_alloc(sizeof(int) * (size_t)(in->h + 1));
    out->row_width = mem_alloc(sizeof(int) * (size_t)(in->h > 0 ? in->h : 1));
    out->x0 = mem_alloc(sizeof(int) * (size_t)cap);
    out->x1 = mem_alloc(sizeof(int) * (size_t)cap);
    if (!out->row_first || !out->row_width || !out->x0 || !out->x1) { footprint_spans_free(out); return -1; }
    for (int j = 0; j < in->h; j++) {
        const unsigned char *row = in->bits + (size_t)j * in->w, *end = row + in->w;
        out->row_first[j] = out->count;
        out->row_width[j] = 0;
        /* Runs found with memchr (covered pixels are 1, free ones 0). */
        for (const unsigned char *a = memchr(row, 1, (size_t)in->w); a;) {
            const unsigned char *b = memchr(a, 0, (size_t)(end - a));
            if (!b) b = end;
            if (spans_push(out, &cap, (int)(a - row), (int)(b - row) - 1) != 0) { footprint_spans_free(out); return -1; }
            if (b - a > out->row_width[j]) out->row_width[j] = (int)(b - a);
            a = b < end ? memchr(b, 1, (size_t)(end - b)) : NULL;
        }
    }
    out->row_first[in->h] = out->count;
    if (spans_order_rows(out) != 0) { footprint_spans_free(out); return -1; }
    return 0;
}

int footprint_spans_half_turn(const footprint_spans *in, footprint_spans *out)
{
    memset(out, 0, sizeof *out);
    const int w = in->w, h = in->h, n = in->count;
    out->w = w; out->h = h; out->count = n;
    out->row_first = mem_alloc(sizeof(int) * (size_t)(h + 1));
    out->row_width = mem_alloc(sizeof(int) * (size_t)(h > 0 ? h : 1));
    out->x0 = mem_alloc(sizeof(int) * (size_t)(n > 0 ? n : 1));
    out->x1 = mem_alloc(sizeof(int) * (size_t)(n > 0 ? n : 1));
    if (!out->row_first || !out->row_width || !out->x0 || !out->x1) { footprint_spans_free(out); return -1; }
    /* Pixel (i, j) goes to (w-1-i, h-1-j): rows in reverse, each row's runs mirrored and in reverse. */
    int at = 0;
    for (int j = 0; j < h; j++) {
        int src = h - 1 - j;
        out->row_first[j] = at;
        out->row_width[j] = in->row_width[src];
        for (int k = in->row_first[src + 1] - 1; k >= in->row_first[src]; k--, at++) {
            out->x0[at] = w - 1 - in->x1[k];
            out->x1[at] = w - 1 - in->x0[k];
        }
    }
    out->row_first[h] = at;
    if (spans_order_rows(out) != 0) { footprint_spans_free(out); return -1; }
    return 0;
}

int footprint_spans_equal(const footprint_spans *a, const footprint_spans *b)
{
    return a->w == b->w && a->h == b->h && a->count == b->count &&
           !memcmp(a->row_first, b->row_first, sizeof(int) * (size_t)(a->h + 1)) &&
           !memcmp(a->x0, b->x0, sizeof(int) * (size_t)a->count) && !memcmp(a->x1, b->x1, sizeof(int) * (size_t)a->count);
}

long footprint_count(const footprint *in)
{
    long n = 0;
    for (size_t i = 0; i < (size_t)in->w * (size_t)in->h; i++) n += in->bits[i];
    return n;
}

int footprint_equal(const footprint *a, const footprint *b)
{
    return a->w == b->w && a->h == b->h && !memcmp(a->bits, b->bits, (size_t)a->w * (size_t)a->h);
}

void footprint_spans_free(footprint_spans *s)
{
    if (!s) return;
    mem_free(s->row_first); mem_free(s->row_width); mem_free(s->row_order); mem_free(s->x0); mem_free(s->x1);
    memset(s, 0, sizeof *s);
}
