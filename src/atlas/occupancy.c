#include "atlas/occupancy.h"

#include <stdlib.h>
#include <string.h>

#include "core/mem.h"

static uint64_t *row_of(const occupancy *o, int y) { return o->bits + (size_t)y * o->words; }

static void set_range(uint64_t *row, int lo, int hi)
{
    for (int i = lo; i <= hi;) {
        int w = i >> 6, b = i & 63;
        int n = hi - i + 1;
        if (b == 0 && n >= 64) { row[w] = ~(uint64_t)0; i += 64; continue; }
        int take = 64 - b < n ? 64 - b : n;
        uint64_t m = (take == 64 ? ~(uint64_t)0 : (((uint64_t)1 << take) - 1)) << b;
        row[w] |= m;
        i += take;
    }
}

/* Highest taken pixel in [lo, hi] of a row, or -1. */
static int highest_taken(const uint64_t *row, int lo, int hi)
{
    int wlo = lo >> 6, whi = hi >> 6;
    for (int w = whi; w >= wlo; w--) {
        uint64_t m = row[w];
        if (w == whi && (hi & 63) != 63) m &= ((uint64_t)1 << ((hi & 63) + 1)) - 1;
        if (w == wlo) m &= ~(uint64_t)0 << (lo & 63);
        if (m) return w * 64 + 63 - __builtin_clzll(m);
    }
    return -1;
}

static int row_free_run(const occupancy *o, int y)
{
    const uint64_t *row = row_of(o, y);
    int best = 0, run = 0; /* run: free pixels ending at the current position */
    for (int w = 0; w < o->words; w++) {
        int bits = (w == o->words - 1 && (o->size & 63)) ? (o->size & 63) : 64;
        uint64_t m = row[w];
        if (bits < 64) m |= ~(uint64_t)0 << bits; /* past the atlas: taken */
        if (m == 0) { run += 64; if (run > best) best = run; continue; }
        /* Free bits below the lowest taken one continue the run. */
        int low = __builtin_ctzll(m);
        if (run + low > best) best = run + low;
        /* Runs of free bits between taken ones: each is the zeros above a taken bit. */
        uint64_t free = ~m;
        free &= ~(uint64_t)0 << low; /* the low run is counted */
        while (free) {
            int a = __builtin_ctzll(free);
            uint64_t rest = ~free >> a; /* taken bits from a up */
            int len = rest ? __builtin_ctzll(rest) : 64 - a;
            if (a + len == 64) break; /* the run reaches the word's top: carried on */
            if (len > best) best = len;
            free &= ~(uint64_t)0 << (a + len); /* a + len < 64 here */
        }
        /* Free bits above the highest taken one start the next run. */
        run = __builtin_clzll(m);
        if (run > best) best = run;
    }
    return best;
}

int occupancy_init(occupancy *o, int size, int border)
{
    memset(o, 0, sizeof *o);
    o->size = size;
    o->words = (size + 63) / 64;
    o->bits = mem_calloc((size_t)size * o->words, sizeof *o->bits);
    o->free_run = mem_alloc(sizeof *o->free_run * (size_t)size);
    if (!o->bits || !o->free_run) { occupancy_free(o); return -1; }
    for (int y = 0; y < size; y++) {
        uint64_t *row = row_of(o, y);
        if (y < border || y >= size - border) set_range(row, 0, size - 1);
        else if (border > 0) { set_range(row, 0, border - 1); set_range(row, size - border, size - 1); }
        o->free_run[y] = row_free_run(o, y);
    }
    o->first_open = 0;
    while (o->first_open < size && o->free_run[o->first_open] == 0) o->first_open++;
    return 0;
}

void occupancy_free(occupancy *o)
{
    mem_free(o->bits); mem_free(o->free_run);
    memset(o, 0, sizeof *o);
}

int occupancy_get(const occupancy *o, int x, int y)
{
    return (int)(row_of(o, y)[x >> 6] >> (x & 63) & 1);
}

/* Moves *x right to the first position >= *x where every span of footprint
 * row r lands on free pixels of atlas row `row` (past xlast when none).
 * Returns 1 when x moved. */
static int row_next_fit(const uint64_t *row, const footprint_spans *s, int r, int *x, int xlast)
{
    int moved = 0;
    for (int k = s->row_first[r]; k < s->row_first[r + 1] && *x <= xlast;) {
        int q = highest_taken(row, *x + s->x0[k], *x + s->x1[k]);
        if (q < 0) { k++; continue; }
        /* Any x whose span still covers q collides too: jump past it and recheck the row. */
        *x = q - s->x0[k] + 1;
        moved = 1;
        k = s->row_first[r];
    }
    return moved;
}

int occupancy_find(const occupancy *o, const footprint_spans *s, int y_end, int *ox, int *oy)
{
    if (s->w > o->size || s->h > o->size) return 0;
    int ylast = o->size - s->h;
    if (y_end - s->h < ylast) ylast = y_end - s->h;
    for (int y = o->first_open; y <= ylast; y++) {
        /* Cheap rejection: some footprint row is wider than any free run of its
         * atlas row (widest rows first: they are the likeliest to fail). */
        int ok = 1;
        for (int t = 0; t < s->h; t++) {
            int r = s->row_order[t];
            if (s->row_width[r] > o->free_run[y + r]) { ok = 0; break; }
        }
        if (!ok) continue;
        int x = 0, xlast = o->size - s->w;
        /* Leapfrog over the rows (widest first, cyclically): each row moves x
         * to its own next fit; x is a place when h rows in a row agree. */
        int agreed = 0, t = 0;
        while (x <= xlast && agreed < s->h) {
            int r = s->row_order[t];
            int moved = row_next_fit(row_of(o, y + r), s, r, &x, xlast);
            agreed = moved ? 1 : agreed + 1;
            t = (t + 1) % s->h;
        }
        if (x <= xlast && agreed >= s->h) { *ox = x; *oy = y; return 1; }
    }
    return 0;
}

void occupancy_mark(occupancy *o, const footprint_spans *s, int x, int y, int pad)
{
    /* The square grown around each span is its run widened by pad on rows
     * r - pad .. r + pad: their union is the dilated footprint. */
    for (int r = 0; r < s->h; r++)
        for (int k = s->row_first[r]; k < s->row_first[r + 1]; k++) {
            int lo = x + s->x0[k] - pad, hi = x + s->x1[k] + pad;
            if (lo < 0) lo = 0;
            if (hi > o->size - 1) hi = o->size - 1;
            if (lo > hi) continue;
            for (int ay = y + r - pad; ay <= y + r + pad; ay++)
                if (ay >= 0 && ay < o->size) set_range(row_of(o, ay), lo, hi);
        }
    for (int ay = y - pad; ay < y + s->h + pad; ay++)
        if (ay >= 0 && ay < o->size) o->free_run[ay] = row_free_run(o, ay);
    while (o->first_open < o->size && o->free_run[o->first_open] == 0) o->first_open++;
}
