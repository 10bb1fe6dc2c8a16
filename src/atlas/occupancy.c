#include "atlas/occupancy.h"

#include <stdlib.h>
#include <string.h>

#include "core/mem.h"

static uint64_t *row_of(const occupancy *o, int y) { return o->bits + (size_t)y * o->stride; }

/* Row y of blocked-run level k (0: the taken bits themselves). */
static uint64_t *level_row(const occupancy *o, int k, int y)
{
    return k == 0 ? row_of(o, y) : o->runs + ((size_t)(k - 1) * o->size + y) * o->stride;
}

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

/* Longest run of free pixels of a row of `words` words (pixels from `size` on: taken). */
static int free_run_of(const uint64_t *row, int words, int size)
{
    int best = 0, run = 0; /* run: free pixels ending at the current position */
    for (int w = 0; w < words; w++) {
        int bits = (w == words - 1 && (size & 63)) ? (size & 63) : 64;
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

static int row_free_run(const occupancy *o, int y) { return free_run_of(row_of(o, y), o->words, o->size); }

/* Recomputes row y's blocked-run levels from its taken bits: a run of 2^k
 * pixels is blocked where either of its halves is (pixels past the row: taken). */
static void row_levels_update(const occupancy *o, int y)
{
    for (int k = 1; k <= o->levels; k++) {
        const uint64_t *prev = level_row(o, k - 1, y);
        uint64_t *cur = level_row(o, k, y);
        int sh = 1 << (k - 1); /* 1..32 */
        for (int i = 0; i < o->stride; i++) {
            uint64_t next = i + 1 < o->stride ? prev[i + 1] : ~(uint64_t)0;
            cur[i] = prev[i] | prev[i] >> sh | next << (64 - sh);
        }
    }
}

/* Levels kept by default: as many as fit LEVELS_BUDGET bytes (a 1024 px atlas needs under 1 MiB). */
#define LEVELS_BUDGET ((size_t)64 << 20)

int occupancy_init(occupancy *o, int size, int border)
{
    size_t level_bytes = (size_t)size * (size_t)((size + 63) / 64 + 1) * sizeof(uint64_t);
    int levels = OCCUPANCY_LEVELS;
    while (levels > 0 && (size_t)levels * level_bytes > LEVELS_BUDGET) levels--;
    return occupancy_init_levels(o, size, border, levels);
}

int occupancy_init_levels(occupancy *o, int size, int border, int levels)
{
    memset(o, 0, sizeof *o);
    if (size < 1 || size > OCCUPANCY_MAX_SIZE) return -1;
    o->size = size;
    o->words = (size + 63) / 64;
    o->stride = o->words + 1;
    o->levels = levels < 0 ? 0 : levels > OCCUPANCY_LEVELS ? OCCUPANCY_LEVELS : levels;
    o->bits = mem_calloc((size_t)size * o->stride, sizeof *o->bits);
    o->runs = mem_alloc(sizeof *o->runs * ((size_t)o->levels * size * o->stride + 1));
    o->free_run = mem_alloc(sizeof *o->free_run * (size_t)size);
    if (!o->bits || !o->runs || !o->free_run) { occupancy_free(o); return -1; }
    for (int y = 0; y < size; y++) {
        uint64_t *row = row_of(o, y);
        if (y < border || y >= size - border) set_range(row, 0, size - 1);
        else if (border > 0) { set_range(row, 0, border - 1); set_range(row, size - border, size - 1); }
        set_range(row, size, 64 * o->stride - 1);
        o->free_run[y] = row_free_run(o, y);
        row_levels_update(o, y);
    }
    o->first_open = 0;
    while (o->first_open < size && o->free_run[o->first_open] == 0) o->first_open++;
    return 0;
}

void occupancy_free(occupancy *o)
{
    mem_free(o->bits); mem_free(o->runs); mem_free(o->free_run);
    memset(o, 0, sizeof *o);
}

int occupancy_get(const occupancy *o, int x, int y)
{
    return (int)(row_of(o, y)[x >> 6] >> (x & 63) & 1);
}

/* Pixels p .. p + 63 of a row as one word (bit i: pixel p + i); p + 64 must stay within the row's stride. */
static uint64_t bits_at(const uint64_t *row, int p)
{
    int w = p >> 6, b = p & 63;
    return b ? row[w] >> b | row[w + 1] << (64 - b) : row[w];
}

/* occupancy_run_blocked, inlined where the search calls it. */
static inline uint64_t run_blocked(const occupancy *o, int y, int x, int len)
{
    int k = 31 - __builtin_clz((unsigned)len); /* 2^k <= len < 2^(k+1) */
    if (k > o->levels) k = o->levels;
    /* Runs of 2^k pixels starting at x + i and at x + i + len - 2^k cover the run
     * (beyond the top level, top-level runs every 2^k pixels do). */
    const uint64_t *row = level_row(o, k, y);
    int step = 1 << k, last = x + len - step;
    uint64_t m = bits_at(row, last);
    for (int p = x; p < last; p += step) m |= bits_at(row, p);
    return m;
}

uint64_t occupancy_run_blocked(const occupancy *o, int y, int x, int len) { return run_blocked(o, y, x, len); }

/* Of the placements x0 + i (bit i of m) at row y, those where footprint row r's spans land on free pixels. */
static inline uint64_t row_placements_free(const occupancy *o, const footprint_spans *s, int r, int y, int x0,
                                           uint64_t m)
{
    for (int k = s->row_first[r]; k < s->row_first[r + 1] && m; k++)
        m &= ~run_blocked(o, y + r, x0 + s->x0[k], s->x1[k] - s->x0[k] + 1);
    return m;
}

/* Of the placements x0 + i (bit i of m) at row y, those where every span of
 * s lands on free pixels. Footprint row *lead first (the one that ruled out
 * the last 64: next to the same obstacle, the likeliest to again), then the
 * rows from the edges in (bottom, top, second from the bottom, ...): below
 * its place, a shape mostly runs into the charts under it or over it, which
 * widest-first reaches last (on spot-xatlas 1.5 -> 1.1 s);
 * *lead becomes the row that ruled these out. */
static uint64_t placements_free(const occupancy *o, const footprint_spans *s, int y, int x0, uint64_t m, int *lead)
{
    if (s->h == 0) return m;
    int first = *lead;
    m = row_placements_free(o, s, first, y, x0, m);
    for (int t = 0; t < s->h && m; t++) {
        int r = t & 1 ? s->h - 1 - t / 2 : t / 2;
        if (r == first) continue;
        m = row_placements_free(o, s, r, y, x0, m);
        if (!m) *lead = r;
    }
    return m;
}

/* -1 when every footprint row of s is at most as wide as the longest free
 * run of its atlas row at y, else a footprint row that is not (widest rows
 * first: they are the likeliest to fail). */
static int row_too_wide(const occupancy *o, const footprint_spans *s, int y)
{
    for (int t = 0; t < s->h; t++) {
        int r = s->row_order[t];
        if (s->row_width[r] > o->free_run[y + r]) return r;
    }
    return -1;
}

/* 1 when row_too_wide finds no row: the same test without the order and the
 * early exit, a vector of rows at a time (where it passes, every row is
 * tested anyway). */
static int rows_all_fit(const occupancy *o, const footprint_spans *s, int y)
{
    const int *w = s->row_width, *f = o->free_run + y;
    int bad = 0;
#pragma omp simd reduction(| : bad)
    for (int r = 0; r < s->h; r++) bad |= w[r] > f[r];
    return !bad;
}

/* The next y above y where footprint row r's failure at y does not repeat:
 * atlas row a = y + r has no free run as wide as row r, so a placement
 * further up passes a only with a lower footprint row r' < r at most that
 * wide (at y' = a - r'), or above it (a + 1). Each row stepped over is a
 * placement skipped, so the walk costs no more than testing them. */
static int next_row_past(const occupancy *o, const footprint_spans *s, int y, int r)
{
    int a = y + r, f = o->free_run[a];
    for (int r2 = r - 1; r2 >= 0; r2--)
        if (s->row_width[r2] <= f) return a - r2;
    return a + 1;
}

#define FILTER_RECENT 4

int occupancy_find(const occupancy *o, const footprint_spans *s, int y_end, int *ox, int *oy)
{
    if (s->w > o->size || s->h > o->size) return 0;
    int ylast = o->size - s->h, xlast = o->size - s->w;
    if (y_end - s->h < ylast) ylast = y_end - s->h;
    if (s->h == 0) { *ox = 0; *oy = o->first_open; return o->first_open <= ylast; }
    /* Per 64 placements, the atlas row that last ruled them all out: one
     * row up, the footprint row next below meets it, and the shape's rows
     * change little from one to the next, so it is tested first. */
    int lead_at[OCCUPANCY_MAX_SIZE / 64];
    for (int b = 0; b <= xlast / 64; b++) lead_at[b] = -1;
    /* The atlas rows that last failed the row test: crowded rows fail again. */
    int recent[FILTER_RECENT], next_recent = 0;
    for (int i = 0; i < FILTER_RECENT; i++) recent[i] = -1;
    for (int y = o->first_open; y <= ylast;) {
        /* Cheap rejection: some footprint row is wider than any free run of its
         * atlas row; the placements that would meet the same row are skipped. */
        int r = -1;
        for (int i = 0; i < FILTER_RECENT && r < 0; i++) {
            int rr = recent[i] - y;
            if (rr >= 0 && rr < s->h && s->row_width[rr] > o->free_run[recent[i]]) r = rr;
        }
        if (r < 0 && !rows_all_fit(o, s, y)) {
            r = row_too_wide(o, s, y);
            recent[next_recent] = y + r;
            next_recent = (next_recent + 1) % FILTER_RECENT;
        }
        if (r >= 0) { y = next_row_past(o, s, y, r); continue; }
        /* 64 placements at a time, left to right: the first free one is the
         * leftmost. Each span rules out its blocked placements in two reads
         * (run_blocked), where jumping over the taken pixels one by one took a
         * hundred and more per row on a crowded atlas. */
        for (int x0 = 0, b = 0; x0 <= xlast; x0 += 64, b++) {
            uint64_t m = xlast - x0 >= 63 ? ~(uint64_t)0 : ((uint64_t)1 << (xlast - x0 + 1)) - 1;
            int lead = lead_at[b] - y;
            if (lead < 0 || lead >= s->h) lead = s->row_order[0];
            m = placements_free(o, s, y, x0, m, &lead);
            if (m) { *ox = x0 + __builtin_ctzll(m); *oy = y; return 1; }
            lead_at[b] = lead + y;
        }
        y++;
    }
    return 0;
}

int occupancy_find_nearest(const occupancy *o, const footprint_spans *s, int x0, int y0, int *ox, int *oy)
{
    if (s->w > o->size || s->h > o->size) return 0;
    int ylast = o->size - s->h, xlast = o->size - s->w;
    int lead = s->h > 0 ? s->row_order[0] : 0, found = 0, bx = 0, by = 0;
    long long best = 0;
    /* Rows by distance from y0 (y0 - d before y0 + d); none farther than the best so far can win. */
    for (int d = 0;; d++) {
        long long dy2 = (long long)d * d;
        if (found && dy2 > best) break;
        if (y0 - d < 0 && y0 + d > ylast) break;
        for (int side = 0; side < (d ? 2 : 1); side++) {
            int y = side ? y0 + d : y0 - d;
            if (y < 0 || y > ylast || !rows_all_fit(o, s, y)) continue;
            for (int xb = 0; xb <= xlast; xb += 64) {
                uint64_t m = xlast - xb >= 63 ? ~(uint64_t)0 : ((uint64_t)1 << (xlast - xb + 1)) - 1;
                m = placements_free(o, s, y, xb, m, &lead);
                while (m) {
                    int x = xb + __builtin_ctzll(m);
                    m &= m - 1;
                    long long dist = dy2 + (long long)(x - x0) * (x - x0);
                    if (!found || dist < best || (dist == best && (y < by || (y == by && x < bx)))) {
                        found = 1; best = dist; bx = x; by = y;
                    }
                }
            }
        }
    }
    if (found) { *ox = bx; *oy = by; }
    return found;
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
        if (ay >= 0 && ay < o->size) { o->free_run[ay] = row_free_run(o, ay); row_levels_update(o, ay); }
    while (o->first_open < o->size && o->free_run[o->first_open] == 0) o->first_open++;
}
