/* Atlas packing: hull and minimum rectangle, then packed charts checked by
 * an independent raster (pixel centres at 4x the atlas resolution): no two
 * charts share a sample, samples of different charts are at least `padding`
 * pixels apart, UVs stay inside [0,1]^2 with the border padding, every
 * chart's qce is unchanged (a similarity) and the output is deterministic. */
#include "check.h"

#include <omp.h>

#include <stdint.h>

#include "atlas/convex_hull.h"
#include "atlas/min_area_rect.h"
#include "atlas/pack.h"
#include "atlas/pack_split.h"
#include "charts/charts.h"
#include "atlas/uv_charts.h"
#include "core/rng.h"
#include "mesh/clean.h"
#include "mesh/mesh.h"

/* ---- procedural charts ------------------------------------------------ */

typedef struct builder {
    double *pos, *uv;
    int *tri;
    int nv, nf, cap_v, cap_f;
} builder;

static int add_vertex(builder *b, double x, double y, double z)
{
    if (b->nv == b->cap_v) {
        b->cap_v = b->cap_v ? 2 * b->cap_v : 256;
        b->pos = realloc(b->pos, sizeof(double) * 3 * b->cap_v);
        b->uv = realloc(b->uv, sizeof(double) * 2 * b->cap_v);
    }
    b->pos[3 * b->nv] = x; b->pos[3 * b->nv + 1] = y; b->pos[3 * b->nv + 2] = z;
    return b->nv++;
}

static void add_face(builder *b, int i, int j, int k)
{
    if (b->nf == b->cap_f) {
        b->cap_f = b->cap_f ? 2 * b->cap_f : 256;
        b->tri = realloc(b->tri, sizeof(int) * 3 * b->cap_f);
    }
    b->tri[3 * b->nf] = i; b->tri[3 * b->nf + 1] = j; b->tri[3 * b->nf + 2] = k;
    b->nf++;
}

/* An n by n grid of unit/n cells in the plane z = zc; cells where keep()
 * says no are left out (L and U shapes are concave). */
/* The mesh the builder holds (each vertex its own UV corner), the builder's arrays freed. */
static neuv_mesh *mesh_of_builder(builder *b)
{
    neuv_mesh *m = mesh_create(b->nv, b->nf, b->nv);
    memcpy(m->pos, b->pos, sizeof(double) * 3 * b->nv);
    memcpy(m->tri, b->tri, sizeof(int) * 3 * b->nf);
    memcpy(m->uv, b->uv, sizeof(double) * 2 * b->nv);
    memcpy(m->tri_uv, b->tri, sizeof(int) * 3 * b->nf);
    free(b->pos); free(b->uv); free(b->tri);
    return m;
}

static void add_grid_chart(builder *b, int n, double sx, double sy, double zc, int shape)
{
    int base = b->nv;
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) add_vertex(b, sx * i / n, sy * j / n, zc);
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            int h = n / 2;
            if (shape == 1 && i >= h && j >= h) continue;                 /* L */
            if (shape == 2 && i >= n / 3 && i < n - n / 3 && j >= h) continue; /* U */
            if (shape == 3 && i >= n / 6 && j >= n / 6) continue; /* L with thin arms */
            int a = base + j * (n + 1) + i;
            add_face(b, a, a + 1, a + n + 2);
            add_face(b, a, a + n + 2, a + n + 1);
        }
}

static void add_annulus_chart(builder *b, int seg, double r0, double r1, double zc)
{
    int base = b->nv;
    for (int s = 0; s < seg; s++) {
        double t = 6.283185307179586 * s / seg;
        add_vertex(b, r0 * cos(t), r0 * sin(t), zc);
        add_vertex(b, r1 * cos(t), r1 * sin(t), zc);
    }
    for (int s = 0; s < seg; s++) {
        int a = base + 2 * s, c = base + 2 * ((s + 1) % seg);
        add_face(b, a, a + 1, c + 1);
        add_face(b, a, c + 1, c);
    }
}

/* Charts of several shapes at random 3D sizes; UVs are each chart's plane
 * coordinates under a random rotation, scale, offset and a mild shear, so
 * qce is not 1 and must survive packing unchanged. */
static neuv_mesh *procedural_charts(uint64_t seed, int count)
{
    builder b = {0};
    rng r;
    rng_seed(&r, seed);
    int *chart_v0 = malloc(sizeof(int) * (count + 1));
    for (int c = 0; c < count; c++) {
        chart_v0[c] = b.nv;
        double size = 0.2 + 2.0 * rng_uniform(&r);
        int kind = c % 4;
        if (kind == 3) add_annulus_chart(&b, 24, 0.5 * size, size, c);
        else add_grid_chart(&b, 6, size, size * (0.3 + rng_uniform(&r)), c, kind);
    }
    chart_v0[count] = b.nv;
    for (int c = 0; c < count; c++) {
        double ang = 6.283185307179586 * rng_uniform(&r), sc = 0.1 + 5 * rng_uniform(&r);
        double shear = 0.3 * rng_uniform(&r), ox = 10 * rng_normal(&r), oy = 10 * rng_normal(&r);
        for (int v = chart_v0[c]; v < chart_v0[c + 1]; v++) {
            double x = b.pos[3 * v] + shear * b.pos[3 * v + 1], y = b.pos[3 * v + 1];
            b.uv[2 * v] = sc * (cos(ang) * x - sin(ang) * y) + ox;
            b.uv[2 * v + 1] = sc * (sin(ang) * x + cos(ang) * y) + oy;
        }
    }
    free(chart_v0);
    return mesh_of_builder(&b);
}

/* ---- independent checks ---------------------------------------------- */

/* Quasi-conformal error s1/s2 of face f (SPEC.md section 5), 0 if degenerate. */
static double face_qce(const neuv_mesh *m, int f)
{
    const double *p0 = m->pos + 3 * m->tri[3 * f], *p1 = m->pos + 3 * m->tri[3 * f + 1],
                 *p2 = m->pos + 3 * m->tri[3 * f + 2];
    double e1[3], e2[3];
    for (int d = 0; d < 3; d++) { e1[d] = p1[d] - p0[d]; e2[d] = p2[d] - p0[d]; }
    double l1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    if (l1 == 0) return 0;
    double x2 = (e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2]) / l1;
    double y2sq = e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2] - x2 * x2;
    double y2 = y2sq > 0 ? sqrt(y2sq) : 0;
    if (y2 == 0) return 0;
    const double *u0 = m->uv + 2 * m->tri_uv[3 * f], *u1 = m->uv + 2 * m->tri_uv[3 * f + 1],
                 *u2 = m->uv + 2 * m->tri_uv[3 * f + 2];
    /* J maps the flattened triangle (0,0),(l1,0),(x2,y2) to the UV triangle. */
    double a = (u1[0] - u0[0]) / l1, c = (u1[1] - u0[1]) / l1;
    double b = ((u2[0] - u0[0]) - a * x2) / y2, d = ((u2[1] - u0[1]) - c * x2) / y2;
    double fro = a * a + b * b + c * c + d * d, det = fabs(a * d - b * c);
    double disc = sqrt(fmax(fro * fro - 4 * det * det, 0));
    double s1 = sqrt(0.5 * (fro + disc)), s2 = sqrt(fmax(0.5 * (fro - disc), 0));
    return s2 > 0 ? s1 / s2 : 0;
}

static void chart_qce(const neuv_mesh *m, const int *fc, int nc, double *q)
{
    double *w = calloc(nc, sizeof *w);
    for (int c = 0; c < nc; c++) q[c] = 0;
    for (int f = 0; f < m->nf; f++) {
        double a = mesh_face_area(m, f);
        q[fc[f]] += a * face_qce(m, f);
        w[fc[f]] += a;
    }
    for (int c = 0; c < nc; c++) q[c] = w[c] > 0 ? q[c] / w[c] : 0;
    free(w);
}

/* Rasterizes every face at pixel centres of an S by S grid into a chart id
 * image, counting samples claimed by two different charts; then checks that
 * samples of different charts are at least pad_sub sub-pixels apart. Sample
 * centres lie inside the charts, so their distance bounds the charts'
 * distance from above: no slack is needed. */
static void check_layout(const neuv_mesh *m, const int *fc, int S, double pad_sub,
                         long *overlaps, long *too_close)
{
    int32_t *img = malloc(sizeof *img * (size_t)S * S);
    for (size_t i = 0; i < (size_t)S * S; i++) img[i] = -1;
    *overlaps = 0; *too_close = 0;
    for (int f = 0; f < m->nf; f++) {
        double p[3][2];
        for (int k = 0; k < 3; k++)
            for (int d = 0; d < 2; d++) p[k][d] = m->uv[2 * m->tri_uv[3 * f + k] + d] * S;
        double area = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
        if (area == 0) continue;
        double sgn = area > 0 ? 1 : -1;
        int x0 = (int)floor(fmin(p[0][0], fmin(p[1][0], p[2][0]))), x1 = (int)ceil(fmax(p[0][0], fmax(p[1][0], p[2][0])));
        int y0 = (int)floor(fmin(p[0][1], fmin(p[1][1], p[2][1]))), y1 = (int)ceil(fmax(p[0][1], fmax(p[1][1], p[2][1])));
        if (x0 < 0) x0 = 0;
        if (y0 < 0) y0 = 0;
        if (x1 > S - 1) x1 = S - 1;
        if (y1 > S - 1) y1 = S - 1;
        for (int y = y0; y <= y1; y++)
            for (int x = x0; x <= x1; x++) {
                double cx = x + 0.5, cy = y + 0.5, in = 1;
                for (int k = 0; k < 3 && in; k++) {
                    const double *a = p[k], *b = p[(k + 1) % 3];
                    double e = (b[0] - a[0]) * (cy - a[1]) - (b[1] - a[1]) * (cx - a[0]);
                    if (sgn * e < 0) in = 0;
                }
                if (!in) continue;
                int32_t *px = &img[(size_t)y * S + x];
                if (*px >= 0 && *px != fc[f]) (*overlaps)++;
                *px = fc[f];
            }
    }
    int rad = (int)ceil(pad_sub);
    for (int y = 0; y < S; y++)
        for (int x = 0; x < S; x++) {
            int32_t c = img[(size_t)y * S + x];
            if (c < 0) continue;
            /* Only boundary samples can be closest to another chart. */
            int interior = x > 0 && y > 0 && x < S - 1 && y < S - 1 && img[(size_t)y * S + x - 1] == c &&
                           img[(size_t)y * S + x + 1] == c && img[(size_t)(y - 1) * S + x] == c &&
                           img[(size_t)(y + 1) * S + x] == c;
            if (interior) continue;
            for (int dy = -rad; dy <= rad; dy++)
                for (int dx = -rad; dx <= rad; dx++) {
                    int xx = x + dx, yy = y + dy;
                    if (xx < 0 || yy < 0 || xx >= S || yy >= S) continue;
                    if ((double)dx * dx + (double)dy * dy >= pad_sub * pad_sub) continue;
                    int32_t o = img[(size_t)yy * S + xx];
                    if (o >= 0 && o != c) (*too_close)++;
                }
        }
    free(img);
}

/* Everything the packer promises, on one mesh. */
/* The largest distance between a packed UV of m and its chart's stored
 * transform applied to the same corner's UV in orig. */
static double transform_error(const neuv_mesh *m, const neuv_mesh *orig, const int *fc, const atlas_chart_transform *xf)
{
    double err = 0;
    for (int f = 0; f < m->nf; f++)
        for (int k = 0; k < 3; k++) {
            double out[2];
            atlas_chart_transform_apply(&xf[fc[f]], orig->uv + 2 * orig->tri_uv[3 * f + k], out);
            const double *nu = m->uv + 2 * m->tri_uv[3 * f + k];
            err = fmax(err, fmax(fabs(out[0] - nu[0]), fabs(out[1] - nu[1])));
        }
    return err;
}

static double check_pack(const char *name, neuv_mesh *m, int resolution, int padding, double min_eff)
{
    int *fc = malloc(sizeof(int) * m->nf);
    int nc = uv_charts(m, fc);
    CHECK(nc > 0);
    double *q0 = malloc(sizeof(double) * nc), *q1 = malloc(sizeof(double) * nc);
    chart_qce(m, fc, nc, q0);
    neuv_mesh *orig = mesh_clone(m);
    atlas_pack_options o;
    atlas_pack_options_default(&o);
    o.resolution = resolution;
    o.padding = padding;
    atlas_chart_transform *xf = malloc(sizeof *xf * nc);
    atlas_pack_result res;
    CHECK_INT(atlas_pack(m, fc, nc, &o, xf, &res), NEUV_OK);
    printf("%s: %d charts, efficiency %.3f, %d attempts\n", name, nc, res.efficiency, res.attempts);
    CHECK(res.efficiency >= min_eff);

    /* Inside the square, border padding kept. */
    double lo = 1, hi = 0;
    for (int u = 0; u < m->nuv; u++)
        for (int d = 0; d < 2; d++) { lo = fmin(lo, m->uv[2 * u + d]); hi = fmax(hi, m->uv[2 * u + d]); }
    CHECK(lo >= (double)padding / resolution - 1e-9);
    CHECK(hi <= 1 - (double)padding / resolution + 1e-9);

    /* Charts unchanged (same faces together), qce unchanged per chart. */
    int *fc2 = malloc(sizeof(int) * m->nf);
    CHECK_INT(uv_charts(m, fc2), nc);
    chart_qce(m, fc, nc, q1);
    double worst = 0;
    for (int c = 0; c < nc; c++) worst = fmax(worst, fabs(q1[c] - q0[c]));
    CHECK(worst <= 1e-6);

    /* The stored transform reproduces the UVs from the original ones. */
    double err = transform_error(m, orig, fc, xf);
    CHECK(err <= 1e-9);

    long overlaps, close;
    check_layout(m, fc, 4 * resolution, 4.0 * padding, &overlaps, &close);
    CHECK_INT(overlaps, 0);
    CHECK_INT(close, 0);

    /* Deterministic: the same input packs to the same bits. */
    neuv_mesh *again = mesh_clone(orig);
    CHECK_INT(atlas_pack(again, fc, nc, &o, NULL, NULL), NEUV_OK);
    CHECK_INT(again->nuv, m->nuv);
    CHECK(again->nuv == m->nuv && !memcmp(again->uv, m->uv, sizeof(double) * 2 * m->nuv));
    mesh_free(again);
    mesh_free(orig);
    free(fc); free(fc2); free(q0); free(q1); free(xf);
    return res.efficiency;
}

static void test_hull_and_rect(void)
{
    /* A 3 by 1 rectangle turned by 0.3 rad, with interior points. */
    double p[2 * 8];
    double base[8][2] = {{0, 0}, {3, 0}, {3, 1}, {0, 1}, {1, 0.5}, {2, 0.2}, {1.5, 0.9}, {3, 0.5}};
    double a = 0.3;
    for (int i = 0; i < 8; i++) {
        p[2 * i] = cos(a) * base[i][0] - sin(a) * base[i][1] + 5;
        p[2 * i + 1] = sin(a) * base[i][0] + cos(a) * base[i][1] - 2;
    }
    int hull[8];
    CHECK_INT(convex_hull_2d(p, 8, hull), 4);
    double ang, w, h;
    CHECK_INT(min_area_rect(p, 8, &ang, &w, &h), 0);
    CHECK_NEAR(w * h, 3.0, 1e-9);
    /* Turning back by -0.3 (mod a quarter turn) makes it axis-aligned. */
    CHECK_NEAR(fmod(ang + a, 1.5707963267948966), 0.0, 1e-9);
    double one[2] = {1, 2};
    CHECK_INT(convex_hull_2d(one, 1, hull), 1);
    CHECK_INT(min_area_rect(one, 1, &ang, &w, &h), 0);
    CHECK_NEAR(w + h, 0.0, 0);
}

static void test_bad_input(void)
{
    neuv_mesh *m = procedural_charts(1, 2);
    int *fc = malloc(sizeof(int) * m->nf);
    int nc = uv_charts(m, fc);
    atlas_pack_options o;
    atlas_pack_options_default(&o);
    o.padding = 600;
    CHECK_INT(atlas_pack(m, fc, nc, &o, NULL, NULL), NEUV_ERR_INPUT);
    atlas_pack_options_default(&o);
    fc[0] = nc;
    CHECK_INT(atlas_pack(m, fc, nc, &o, NULL, NULL), NEUV_ERR_INPUT);
    fc[0] = 0;
    m->uv[0] = NAN;
    CHECK_INT(atlas_pack(m, fc, nc, &o, NULL, NULL), NEUV_ERR_INPUT);
    free(fc);
    mesh_free(m);
}

/* Splitting for packing: an L-shaped chart with thin arms (UV = its plane)
 * is cut, every part a disk with its UVs untouched, and the full packing
 * gains; a square chart (convexity 1) is never tried. */
static double packed_efficiency(const neuv_mesh *m, const int *fc, int nc)
{
    neuv_mesh *c = mesh_clone(m);
    atlas_pack_result res;
    CHECK_INT(atlas_pack(c, fc, nc, NULL, NULL, &res), NEUV_OK);
    mesh_free(c);
    return res.efficiency;
}

static void test_split_for_packing(void)
{
    for (int shape = 0; shape <= 3; shape += 3) {
        builder b = {0};
        add_grid_chart(&b, 12, 1.0, 1.0, 0, shape);
        for (int v = 0; v < b.nv; v++) { b.uv[2 * v] = b.pos[3 * v]; b.uv[2 * v + 1] = b.pos[3 * v + 1]; }
        neuv_mesh *m = mesh_of_builder(&b);
        int *fc = calloc((size_t)m->nf, sizeof(int)), nc = 1, *parent = NULL;
        pack_split_report rep;
        double before = packed_efficiency(m, fc, 1);
        CHECK_INT(pack_split_charts(m, fc, &nc, NULL, &parent, &rep), NEUV_OK);
        double after = packed_efficiency(m, fc, nc);
        printf("%s chart: %d trials, %d splits -> %d charts; quick packing %.3f -> %.3f, full %.3f -> %.3f, %.2f s\n",
               shape ? "thin L" : "square", rep.trials, rep.splits, nc, rep.efficiency_before, rep.efficiency_after, before,
               after, rep.seconds);
        if (shape == 0) {
            CHECK_INT(rep.trials, 0);
            CHECK_INT(nc, 1);
        } else {
            CHECK(rep.splits >= 1 && nc >= 2);
            CHECK(rep.efficiency_after >= rep.efficiency_before * 1.005);
            CHECK(after > before);
            for (int c = 0; c < nc; c++) {
                CHECK_INT(parent[c], 0);
                CHECK_INT(chart_is_disk(m, fc, c), 1);
            }
        }
        free(parent); free(fc); mesh_free(m);
    }
}

/* The splitting's trials run side by side, a round of as many as there are
 * threads against the same atlas, taken in the one-by-one order up to the
 * first kept cut: on 1, 2 and 3 threads the same cuts, trials and charts.
 * Thin Ls (their cuts gain, at first), annuli (less convex than the
 * rule's 0.8, tried) and rectangles (never tried) of several sizes, each chart's UVs its plane, give
 * rounds where a trial is kept after rejected ones and where trials past
 * a kept one are dropped; max_trials 7 (odd) ends a round part-way. */
static void test_split_threads(void)
{
    static const int shapes[] = {3, 4, 0, 3, 3, 4, 0, 3, 4, 3, 0, 3}; /* 4: an annulus */
    builder b = {0};
    for (int c = 0; c < 12; c++) {
        if (shapes[c] == 4) add_annulus_chart(&b, 24, 0.3 + 0.05 * c, 0.6 + 0.05 * c, 3.0 * c);
        else add_grid_chart(&b, 12, 0.5 + 0.15 * c, 0.4 + 0.1 * (c % 5), 3.0 * c, shapes[c]);
    }
    for (int v = 0; v < b.nv; v++) { b.uv[2 * v] = b.pos[3 * v] + 2.0 * b.pos[3 * v + 2]; b.uv[2 * v + 1] = b.pos[3 * v + 1]; }
    neuv_mesh *m = mesh_of_builder(&b);
    int *fc0 = malloc(sizeof(int) * m->nf), nc0 = uv_charts(m, fc0);
    pack_split_options so;
    pack_split_default_options(&so);
    so.max_trials = 7;
    int *ref = NULL, ref_nc = 0, *ref_parent = NULL;
    pack_split_report ref_rep = {0};
    int saved = omp_get_max_threads();
    for (int threads = 1; threads <= 3; threads++) {
        omp_set_num_threads(threads);
        int *fc = malloc(sizeof(int) * m->nf), nc = nc0, *parent = NULL;
        memcpy(fc, fc0, sizeof(int) * m->nf);
        pack_split_report rep;
        CHECK_INT(pack_split_charts(m, fc, &nc, &so, &parent, &rep), NEUV_OK);
        printf("split on %d threads: %d trials, %d splits, %d -> %d charts, quick packing %.4f -> %.4f\n", threads,
               rep.trials, rep.splits, nc0, nc, rep.efficiency_before, rep.efficiency_after);
        if (threads == 1) {
            /* Something to compare: cuts kept and cuts rejected. */
            CHECK_INT(rep.trials, 7);
            CHECK(rep.splits >= 1 && rep.splits < rep.trials);
            CHECK_INT(nc, nc0 + rep.splits);
            ref = fc; ref_nc = nc; ref_parent = parent; ref_rep = rep;
            continue;
        }
        CHECK_INT(nc, ref_nc);
        CHECK_INT(rep.trials, ref_rep.trials);
        CHECK_INT(rep.splits, ref_rep.splits);
        CHECK(rep.efficiency_after == ref_rep.efficiency_after);
        CHECK_INT(memcmp(fc, ref, sizeof(int) * m->nf), 0);
        CHECK_INT(memcmp(parent, ref_parent, sizeof(int) * nc), 0);
        free(fc); free(parent);
    }
    omp_set_num_threads(saved);
    free(ref); free(ref_parent); free(fc0);
    mesh_free(m);
}

/* Tile t of the layout (the unit square with corner (t mod 10, t div 10)),
 * its faces moved to [0,1]^2; the other faces left out. */
static neuv_mesh *tile_submesh(const neuv_mesh *m, const int *face_tile, int t, const int *fc, int *fc_out)
{
    int nf = 0;
    for (int f = 0; f < m->nf; f++) nf += face_tile[f] == t;
    neuv_mesh *s = mesh_create(m->nv, nf, m->nuv);
    memcpy(s->pos, m->pos, sizeof(double) * 3 * m->nv);
    for (int u = 0; u < m->nuv; u++) {
        s->uv[2 * u] = m->uv[2 * u] - t % 10;
        s->uv[2 * u + 1] = m->uv[2 * u + 1] - t / 10;
    }
    for (int f = 0, i = 0; f < m->nf; f++) {
        if (face_tile[f] != t) continue;
        memcpy(s->tri + 3 * i, m->tri + 3 * f, sizeof(int) * 3);
        memcpy(s->tri_uv + 3 * i, m->tri_uv + 3 * f, sizeof(int) * 3);
        fc_out[i++] = fc[f];
    }
    return s;
}

/* Texel density and tiles: charts at T pixels per unit of 3D length, as
 * many tiles as they need, each tile checked like one square (no overlap,
 * padding between charts and to the tile border at the tile resolution);
 * a chart too large for a tile and keep_scale with T are refused. */
static void test_tiles(void)
{
    const int R = 256, pad = 2;
    neuv_mesh *m = procedural_charts(42, 24);
    int *fc = malloc(sizeof(int) * m->nf);
    int nc = uv_charts(m, fc);
    double a3 = mesh_total_area(m);
    /* Density at which the charts' area is 2.2 tiles: at least 3 tiles. */
    double T = R * sqrt(2.2 / a3);
    neuv_mesh *orig = mesh_clone(m);
    double *q0 = malloc(sizeof(double) * nc), *q1 = malloc(sizeof(double) * nc);
    chart_qce(m, fc, nc, q0);
    atlas_pack_options o;
    atlas_pack_options_default(&o);
    o.resolution = R;
    o.padding = pad;
    o.texels_per_unit = T;
    atlas_chart_transform *xf = malloc(sizeof *xf * nc);
    atlas_pack_result res;
    CHECK_INT(atlas_pack(m, fc, nc, &o, xf, &res), NEUV_OK);
    printf("tiles: %d charts at %.2f px/unit, %d tiles, efficiency %.3f\n", nc, T, res.tiles, res.efficiency);
    CHECK(res.tiles >= 3 && res.tiles <= 5);
    CHECK_NEAR(res.texel_scale, T, 1e-9 * T);

    /* Every face inside one tile, away from its border by the padding;
     * every tile used; the density is T on every face. */
    int *face_tile = malloc(sizeof(int) * m->nf);
    int *used = calloc((size_t)res.tiles, sizeof(int));
    double uv_area = 0, worst_density = 0, border = 1;
    for (int f = 0; f < m->nf; f++) {
        const double *u[3];
        for (int k = 0; k < 3; k++) u[k] = m->uv + 2 * m->tri_uv[3 * f + k];
        int tx = (int)floor((u[0][0] + u[1][0] + u[2][0]) / 3), ty = (int)floor((u[0][1] + u[1][1] + u[2][1]) / 3);
        face_tile[f] = ty * 10 + tx;
        CHECK(tx >= 0 && tx < 10 && ty >= 0 && face_tile[f] < res.tiles);
        if (face_tile[f] >= 0 && face_tile[f] < res.tiles) used[face_tile[f]]++;
        for (int k = 0; k < 3; k++) {
            border = fmin(border, fmin(u[k][0] - tx, u[k][1] - ty));
            border = fmin(border, fmin(tx + 1 - u[k][0], ty + 1 - u[k][1]));
        }
        double a = 0.5 * fabs((u[1][0] - u[0][0]) * (u[2][1] - u[0][1]) - (u[1][1] - u[0][1]) * (u[2][0] - u[0][0]));
        uv_area += a;
        double f3 = mesh_face_area(m, f);
        if (f3 > 0) worst_density = fmax(worst_density, fabs(sqrt(a / f3) * R / T - 1));
    }
    CHECK(border >= (double)pad / R - 1e-9);
    CHECK(worst_density <= 1e-6);
    for (int t = 0; t < res.tiles; t++) CHECK(used[t] > 0);
    CHECK_NEAR(res.efficiency, uv_area / res.tiles, 1e-9);
    CHECK_NEAR(uv_area, 2.2, 1e-6);

    /* Each tile: no overlap, charts `pad` pixels apart at the tile resolution. */
    int *fct = malloc(sizeof(int) * m->nf);
    for (int t = 0; t < res.tiles; t++) {
        neuv_mesh *s = tile_submesh(m, face_tile, t, fc, fct);
        long overlaps, close;
        check_layout(s, fct, 4 * R, 4.0 * pad, &overlaps, &close);
        CHECK_INT(overlaps, 0);
        CHECK_INT(close, 0);
        mesh_free(s);
    }

    /* A similarity per chart, the tile offset in its transform. */
    chart_qce(m, fc, nc, q1);
    double worst = 0;
    for (int c = 0; c < nc; c++) worst = fmax(worst, fabs(q1[c] - q0[c]));
    CHECK(worst <= 1e-6);
    double err = transform_error(m, orig, fc, xf);
    CHECK(err <= 1e-9);

    /* Deterministic. */
    neuv_mesh *again = mesh_clone(orig);
    CHECK_INT(atlas_pack(again, fc, nc, &o, NULL, NULL), NEUV_OK);
    CHECK(again->nuv == m->nuv && !memcmp(again->uv, m->uv, sizeof(double) * 2 * m->nuv));
    mesh_free(again);

    /* A density whose charts fit one tile: one tile, at that density. */
    again = mesh_clone(orig);
    o.texels_per_unit = R * sqrt(0.3 / a3);
    CHECK_INT(atlas_pack(again, fc, nc, &o, NULL, &res), NEUV_OK);
    CHECK_INT(res.tiles, 1);
    CHECK_NEAR(res.efficiency, 0.3, 1e-6);
    mesh_free(again);

    /* Refused: a chart larger than a tile, keep_scale with T, T not a number. */
    again = mesh_clone(orig);
    o.texels_per_unit = 4 * R; /* the largest chart is over 1 unit long */
    CHECK_INT(atlas_pack(again, fc, nc, &o, NULL, NULL), NEUV_ERR_INPUT);
    CHECK(strstr(neuv_last_error(), "too large for one 256 px tile") != NULL);
    o.texels_per_unit = T;
    o.keep_scale = 1;
    CHECK_INT(atlas_pack(again, fc, nc, &o, NULL, NULL), NEUV_ERR_INPUT);
    o.keep_scale = 0;
    o.texels_per_unit = NAN;
    CHECK_INT(atlas_pack(again, fc, nc, &o, NULL, NULL), NEUV_ERR_INPUT);
    o.texels_per_unit = -1;
    CHECK_INT(atlas_pack(again, fc, nc, &o, NULL, NULL), NEUV_ERR_INPUT);
    mesh_free(again);

    mesh_free(orig);
    mesh_free(m);
    free(fc); free(fct); free(face_tile); free(used); free(q0); free(q1); free(xf);
}

int main(void)
{
    test_hull_and_rect();
    test_tiles();
    test_bad_input();
    test_split_for_packing();
    test_split_threads();
    neuv_mesh *m = procedural_charts(42, 24);
    check_pack("procedural 24 charts, 256 px pad 2", m, 256, 2, 0.40);
    mesh_free(m);
    /* Few charts, where the order polish (pack_polish) matters most: the four
     * fixed orders alone reach a mean of 0.637 on these seeds (0.616-0.657),
     * the polish 0.661 (0.641-0.679). */
    double few = 0;
    for (uint64_t seed = 3; seed < 7; seed++) {
        m = procedural_charts(seed, 8);
        few += check_pack("procedural 8 charts, 256 px pad 2", m, 256, 2, 0.60) / 4;
        mesh_free(m);
    }
    printf("procedural 8 charts: mean efficiency %.3f\n", few);
    CHECK(few >= 0.65);
    m = procedural_charts(7, 60);
    check_pack("procedural 60 charts, 512 px pad 0", m, 512, 0, 0.55);
    mesh_free(m);

    const char *path = shared_path("uv-samples/spot-xatlas.obj");
    neuv_mesh *s = NULL;
    if (path && neuv_mesh_load(path, NULL, &s) == NEUV_OK) {
        CHECK(mesh_weld_positions(s) >= 0);
        check_pack("spot-xatlas, 512 px pad 2", s, 512, 2, 0.60);
        mesh_free(s);
    } else {
        printf("uv-samples absent: real-mesh case skipped\n");
    }
    return check_report("test_pack");
}
