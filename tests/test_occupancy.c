/* The packer's pixel machinery against plain per-pixel versions: footprint
 * turns and spans, marking with the padding, each row's longest free run,
 * which of 64 placements of a run hit a taken pixel, and the
 * lowest-then-leftmost place a footprint fits. */
#include <math.h>

#include "atlas/footprint.h"
#include "atlas/occupancy.h"
#include "check.h"
#include "core/rng.h"

static void random_footprint_uncropped(rng *r, int w, int h, footprint *f)
{
    f->w = w; f->h = h;
    f->bits = calloc((size_t)w * h, 1);
    for (int e = 0; e < 6; e++) {
        double cx = rng_uniform(r) * w, cy = rng_uniform(r) * h;
        double rx = 1 + rng_uniform(r) * w / 2, ry = 1 + rng_uniform(r) * h / 2;
        unsigned char v = e < 4; /* the last two cut holes */
        for (int j = 0; j < h; j++)
            for (int i = 0; i < w; i++) {
                double dx = (i + 0.5 - cx) / rx, dy = (j + 0.5 - cy) / ry;
                if (dx * dx + dy * dy <= 1) f->bits[(size_t)j * w + i] = v;
            }
    }
    f->bits[(size_t)(h / 2) * w + w / 2] = 1; /* never empty */
}

/* A random footprint: a few filled ellipses and holes, so rows have several
 * runs, cropped to its covered pixels as a rasterized chart is. */
static void random_footprint(rng *r, int w, int h, footprint *f)
{
    footprint full;
    random_footprint_uncropped(r, w, h, &full);
    int x0 = w, x1 = -1, y0 = h, y1 = -1;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++)
            if (full.bits[(size_t)j * w + i]) {
                if (i < x0) x0 = i;
                if (i > x1) x1 = i;
                if (j < y0) y0 = j;
                if (j > y1) y1 = j;
            }
    f->w = x1 - x0 + 1; f->h = y1 - y0 + 1;
    f->bits = malloc((size_t)f->w * f->h);
    for (int j = 0; j < f->h; j++) memcpy(f->bits + (size_t)j * f->w, full.bits + (size_t)(y0 + j) * w + x0, (size_t)f->w);
    free(full.bits);
}

static void test_rotate_and_spans(rng *r)
{
    int bad_rot = 0, bad_spans = 0, bad_half = 0, symmetric = 0;
    for (int trial = 0; trial < 40; trial++) {
        footprint f;
        int w = 1 + (int)(rng_uniform(r) * 90), h = 1 + (int)(rng_uniform(r) * 70);
        random_footprint_uncropped(r, w, h, &f); /* empty border rows and columns too */
        if (trial < 2) memset(f.bits, 1, (size_t)w * h); /* a full box: its own half turn */
        for (int k = 0; k < 4; k++) {
            footprint g;
            CHECK(footprint_rotate(&f, k, &g) == 0);
            CHECK_INT(g.w, k & 1 ? h : w);
            for (int j = 0; j < h; j++)
                for (int i = 0; i < w; i++) {
                    int oi = k == 0 ? i : k == 1 ? h - 1 - j : k == 2 ? w - 1 - i : j;
                    int oj = k == 0 ? j : k == 1 ? i : k == 2 ? h - 1 - j : w - 1 - i;
                    bad_rot += g.bits[(size_t)oj * g.w + oi] != f.bits[(size_t)j * w + i];
                }
            footprint_free(&g);
        }
        footprint_spans s;
        CHECK(footprint_to_spans(&f, &s) == 0);
        long covered = 0;
        for (int j = 0; j < h; j++) {
            int widest = 0, n = s.row_first[j];
            for (int i = 0; i < w; i++) {
                if (!f.bits[(size_t)j * w + i] || (i > 0 && f.bits[(size_t)j * w + i - 1])) continue;
                int e = i;
                while (e + 1 < w && f.bits[(size_t)j * w + e + 1]) e++;
                bad_spans += n >= s.row_first[j + 1] || s.x0[n] != i || s.x1[n] != e;
                n++;
                if (e - i + 1 > widest) widest = e - i + 1;
                covered += e - i + 1;
            }
            bad_spans += n != s.row_first[j + 1] || s.row_width[j] != widest;
        }
        CHECK_INT(covered, footprint_count(&f));
        for (int t = 1; t < h; t++) bad_spans += s.row_width[s.row_order[t - 1]] < s.row_width[s.row_order[t]];
        /* The half turn from the spans: every array as the turned bitmap's spans have it. */
        footprint r2;
        footprint_spans want, got;
        CHECK(footprint_rotate(&f, 2, &r2) == 0 && footprint_to_spans(&r2, &want) == 0);
        CHECK(footprint_spans_half_turn(&s, &got) == 0);
        int n = want.count;
        bad_half += got.w != want.w || got.h != want.h || got.count != n ||
                    memcmp(got.row_first, want.row_first, sizeof(int) * (size_t)(h + 1)) ||
                    memcmp(got.x0, want.x0, sizeof(int) * (size_t)n) || memcmp(got.x1, want.x1, sizeof(int) * (size_t)n) ||
                    memcmp(got.row_width, want.row_width, sizeof(int) * (size_t)h) ||
                    memcmp(got.row_order, want.row_order, sizeof(int) * (size_t)h);
        bad_half += footprint_spans_equal(&got, &s) != footprint_equal(&r2, &f);
        symmetric += footprint_equal(&r2, &f);
        footprint_spans_free(&want);
        footprint_spans_free(&got);
        footprint_free(&r2);
        footprint_spans_free(&s);
        free(f.bits);
    }
    CHECK_INT(bad_rot, 0);
    CHECK_INT(bad_spans, 0);
    CHECK_INT(bad_half, 0);
    CHECK(symmetric >= 1); /* a footprint its own half turn was met (the one-pixel ones at least) */
}

/* Longest run of free pixels of row y, pixel by pixel. */
static int naive_free_run(const occupancy *o, int y)
{
    int best = 0, run = 0;
    for (int x = 0; x < o->size; x++) {
        run = occupancy_get(o, x, y) ? 0 : run + 1;
        if (run > best) best = run;
    }
    return best;
}

/* levels < 0: occupancy_init's own choice. steps footprints up to size / div
 * pixels on a side are placed one after another (many small ones crowd the
 * atlas: rows fail the free-run test and the search skips them). */
static void test_mark_and_find(rng *r, int size, int border, int pad, int levels, int steps, int div)
{
    occupancy o;
    CHECK((levels < 0 ? occupancy_init(&o, size, border) : occupancy_init_levels(&o, size, border, levels)) == 0);
    CHECK_INT(o.levels, levels < 0 ? OCCUPANCY_LEVELS : levels);
    unsigned char *naive = calloc((size_t)size * size, 1);
    for (int y = 0; y < size; y++)
        for (int x = 0; x < size; x++)
            naive[(size_t)y * size + x] = x < border || y < border || x >= size - border || y >= size - border;
    int bad_mark = 0, bad_run = 0, bad_find = 0, found = 0, bad_nearest = 0, near_found = 0, bad_bound = 0;
    for (int step = 0; step < steps; step++) {
        footprint f;
        random_footprint(r, 3 + (int)(rng_uniform(r) * size / div), 3 + (int)(rng_uniform(r) * size / div), &f);
        footprint_spans s;
        CHECK(footprint_to_spans(&f, &s) == 0);
        /* Where it fits, pixel by pixel: every covered pixel free, inside the atlas. */
        int bx = -1, by = -1;
        for (int y = 0; y + f.h <= size && by < 0; y++)
            for (int x = 0; x + f.w <= size && bx < 0; x++) {
                int fits = 1;
                for (int j = 0; j < f.h && fits; j++)
                    for (int i = 0; i < f.w && fits; i++)
                        fits = !f.bits[(size_t)j * f.w + i] || !naive[(size_t)(y + j) * size + x + i];
                if (fits) { bx = x; by = y; }
            }
        int x, y, ok = occupancy_find(&o, &s, size, &x, &y);
        bad_find += ok != (by >= 0) || (ok && (x != bx || y != by));
        if (ok) {
            /* The top bound includes its row (the packer keeps ties), and excludes the next one. */
            int tx, ty;
            bad_bound += !occupancy_find(&o, &s, by + f.h, &tx, &ty) || tx != bx || ty != by;
            bad_bound += occupancy_find(&o, &s, by + f.h - 1, &tx, &ty);
        }
        /* The fit nearest to a random point, pixel by pixel (ties: lower y, then lower x). */
        int px = (int)(rng_uniform(r) * size), py = (int)(rng_uniform(r) * size), nx = -1, ny = -1;
        long long nd = -1;
        for (int yy = 0; yy + f.h <= size; yy++)
            for (int xx = 0; xx + f.w <= size; xx++) {
                long long dd = (long long)(xx - px) * (xx - px) + (long long)(yy - py) * (yy - py);
                if (nd >= 0 && dd >= nd) continue;
                int fits = 1;
                for (int j = 0; j < f.h && fits; j++)
                    for (int i = 0; i < f.w && fits; i++)
                        fits = !f.bits[(size_t)j * f.w + i] || !naive[(size_t)(yy + j) * size + xx + i];
                if (fits) { nd = dd; nx = xx; ny = yy; }
            }
        int qx, qy, qok = occupancy_find_nearest(&o, &s, px, py, &qx, &qy);
        bad_nearest += qok != (nx >= 0) || (qok && (qx != nx || qy != ny));
        near_found += qok;
        if (!ok) { x = (int)(rng_uniform(r) * size) - f.w / 2; y = (int)(rng_uniform(r) * size) - f.h / 2; }
        else found++;
        /* Marked with the padding, anywhere (partly outside the atlas too). */
        occupancy_mark(&o, &s, x, y, pad);
        for (int j = 0; j < f.h; j++)
            for (int i = 0; i < f.w; i++) {
                if (!f.bits[(size_t)j * f.w + i]) continue;
                for (int dy = -pad; dy <= pad; dy++)
                    for (int dx = -pad; dx <= pad; dx++) {
                        int ax = x + i + dx, ay = y + j + dy;
                        if (ax >= 0 && ay >= 0 && ax < size && ay < size) naive[(size_t)ay * size + ax] = 1;
                    }
            }
        for (int yy = 0; yy < size; yy++) {
            for (int xx = 0; xx < size; xx++) bad_mark += occupancy_get(&o, xx, yy) != naive[(size_t)yy * size + xx];
            bad_run += o.free_run[yy] != naive_free_run(&o, yy);
        }
        footprint_spans_free(&s);
        free(f.bits);
    }
    CHECK_INT(bad_mark, 0);
    CHECK_INT(bad_run, 0);
    CHECK_INT(bad_find, 0);
    CHECK_INT(bad_bound, 0);
    CHECK_INT(bad_nearest, 0);
    CHECK(near_found >= 5);
    CHECK(found >= 5); /* the search was exercised on real fits, not only misses */
    occupancy_free(&o);
    free(naive);
}

/* occupancy_run_blocked against a pixel-by-pixel scan, on an atlas of random
 * rectangles, for every level count, run lengths from 1 to the whole row and
 * starts up to the row's end (where placements past it count as blocked). */
static void test_run_blocked(rng *r, int size)
{
    int bad = 0, blocked = 0, free_ = 0;
    for (int levels = 0; levels <= OCCUPANCY_LEVELS; levels++) {
        occupancy o;
        CHECK(occupancy_init_levels(&o, size, 1, levels) == 0);
        CHECK_INT(o.levels, levels);
        /* A few random boxes, marked as one-row-span footprints grown by a padding of 0..2. */
        for (int b = 0; b < 12; b++) {
            footprint f;
            random_footprint(r, 2 + (int)(rng_uniform(r) * size / 6), 2 + (int)(rng_uniform(r) * size / 6), &f);
            footprint_spans s;
            CHECK(footprint_to_spans(&f, &s) == 0);
            occupancy_mark(&o, &s, (int)(rng_uniform(r) * size), (int)(rng_uniform(r) * size), b % 3);
            footprint_spans_free(&s);
            free(f.bits);
        }
        for (int t = 0; t < 3000; t++) {
            int y = (int)(rng_uniform(r) * size);
            int len = 1 + (int)(pow(rng_uniform(r), 3) * size); /* mostly short runs, some whole rows */
            if (len > size) len = size;
            int x = (int)(rng_uniform(r) * (size - len + 1));
            uint64_t m = occupancy_run_blocked(&o, y, x, len);
            for (int i = 0; i < 64; i++) {
                int hit = 0;
                for (int p = x + i; p < x + i + len && !hit; p++) hit = p >= size || occupancy_get(&o, p, y);
                bad += hit != (int)(m >> i & 1);
                if (x + i + len <= size) { blocked += hit; free_ += !hit; }
            }
        }
        occupancy_free(&o);
    }
    CHECK_INT(bad, 0);
    CHECK(blocked > 10000 && free_ > 10000); /* both answers were exercised inside the atlas */
}

/* 1 when triangle (a, b, c) meets the box [x0, x1] x [y0, y1]: no separating
 * axis among the box's two and the triangle's three edge normals. */
static int triangle_meets_box(const double *a, const double *b, const double *c, double x0, double x1, double y0,
                              double y1)
{
    const double *v[3] = {a, b, c};
    double box[4][2] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    if (fmax(a[0], fmax(b[0], c[0])) < x0 || fmin(a[0], fmin(b[0], c[0])) > x1) return 0;
    if (fmax(a[1], fmax(b[1], c[1])) < y0 || fmin(a[1], fmin(b[1], c[1])) > y1) return 0;
    for (int e = 0; e < 3; e++) {
        const double *p = v[e], *q = v[(e + 1) % 3], *o = v[(e + 2) % 3];
        double nx = q[1] - p[1], ny = p[0] - q[0];
        double side = nx * (o[0] - p[0]) + ny * (o[1] - p[1]);
        if (side == 0) continue; /* degenerate: the box axes decide */
        int out = 1;
        for (int k = 0; k < 4 && out; k++)
            if ((nx * (box[k][0] - p[0]) + ny * (box[k][1] - p[1])) * side >= 0) out = 0;
        if (out) return 0;
    }
    return 1;
}

/* Conservative rasterization against the plain per-pixel test: a pixel is
 * set exactly where the triangle meets the pixel's square (grown by the
 * rasterizer's 1e-7, so a test pixel within 1e-6 of the triangle's edge is
 * not judged). Triangles from a thousandth of a pixel (inside one row, the
 * rasterizer's short path) to several pixels across. */
static void test_rasterize(rng *r)
{
    const int w = 12, h = 10;
    int judged = 0, one_row = 0;
    for (int t = 0; t < 3000; t++) {
        double size = pow(10, -3 + 4 * rng_uniform(r)); /* 1e-3 .. 10 px */
        double p[6], cx = 1 + rng_uniform(r) * (w - 2), cy = 1 + rng_uniform(r) * (h - 2);
        for (int k = 0; k < 3; k++) {
            p[2 * k] = fmin(fmax(cx + size * (rng_uniform(r) - 0.5), 0), w - 1e-3);
            p[2 * k + 1] = fmin(fmax(cy + size * (rng_uniform(r) - 0.5), 0), h - 1e-3);
        }
        int tri[3] = {0, 1, 2};
        footprint f;
        CHECK(footprint_rasterize(p, tri, 1, w, h, &f) == 0);
        one_row += floor(fmin(p[1], fmin(p[3], p[5])) - 1e-7) == floor(fmax(p[1], fmax(p[3], p[5])) + 1e-7);
        for (int j = 0; j < h; j++)
            for (int i = 0; i < w; i++) {
                int in = triangle_meets_box(p, p + 2, p + 4, i - 1e-6, i + 1 + 1e-6, j - 1e-6, j + 1 + 1e-6);
                int core = triangle_meets_box(p, p + 2, p + 4, i + 1e-6, i + 1 - 1e-6, j + 1e-6, j + 1 - 1e-6);
                if (in != core) continue; /* within 1e-6 of the square's edge */
                judged++;
                CHECK_INT(f.bits[(size_t)j * w + i], in);
            }
        footprint_free(&f);
    }
    printf("rasterize: %d triangles, %d inside one row, %d pixels judged\n", 3000, one_row, judged);
    CHECK(one_row > 500 && one_row < 2900);
}

int main(void)
{
    rng r;
    rng_seed(&r, 7);
    test_rasterize(&r);
    test_rotate_and_spans(&r);
    test_run_blocked(&r, 150);
    test_run_blocked(&r, 256);
    /* Sizes on and off the 64-pixel word, with and without padding; the
     * search gives the same places with fewer blocked-run levels. */
    test_mark_and_find(&r, 150, 2, 2, -1, 25, 4);
    test_mark_and_find(&r, 128, 0, 0, -1, 25, 4);
    test_mark_and_find(&r, 200, 1, 3, -1, 25, 4);
    test_mark_and_find(&r, 150, 2, 2, 0, 25, 4);
    test_mark_and_find(&r, 200, 1, 3, 2, 25, 4);
    test_mark_and_find(&r, 160, 1, 1, -1, 150, 10);
    return check_report("test_occupancy");
}
