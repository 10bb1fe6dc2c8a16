/* UV metrics (docs/metrics.md) on maps whose values are known in closed form. */
#include "check.h"

#include "metrics/uv_metrics.h"
#include "metrics/uv_overlap.h"
#include "metrics/uv_tiles.h"
#include "core/mem.h"
#include "mesh/shapes.h"
#include "core/rng.h"
#include "unwrap/chart_source.h"

static uv_metrics measure(const neuv_mesh *m)
{
    uv_metrics mt, light;
    neuv_status st = uv_metrics_compute(m, &mt);
    CHECK_INT(st, NEUV_OK);
    /* Without the overlap raster: overlap NaN, every other figure to the bit. */
    CHECK_INT(uv_metrics_compute_no_overlap(m, &light), NEUV_OK);
    CHECK(isnan(light.overlap_fraction));
    light.overlap_fraction = mt.overlap_fraction;
    CHECK(memcmp(&light, &mt, sizeof mt) == 0);
    return mt;
}

/* The Jacobian of a known linear map A, embedded in a tilted plane. */
static void test_jacobian(void)
{
    const double local[3][2] = {{0, 0}, {1, 0.2}, {0.3, 1.1}};
    const double A[2][2] = {{3, 1}, {0, 2}};
    /* Orthonormal frame of a tilted plane: r1 = (1,2,2)/3, r2 = (2,1,-2)/3. */
    const double r1[3] = {1 / 3.0, 2 / 3.0, 2 / 3.0}, r2[3] = {2 / 3.0, 1 / 3.0, -2 / 3.0};
    double p[3][3], q[3][2], s[2];
    for (int k = 0; k < 3; k++) {
        for (int d = 0; d < 3; d++) p[k][d] = 0.5 + local[k][0] * r1[d] + local[k][1] * r2[d];
        for (int d = 0; d < 2; d++) q[k][d] = A[d][0] * local[k][0] + A[d][1] * local[k][1];
    }
    double det = uv_jacobian_singular_values(p, q, s);
    /* AᵀA = [[9,3],[3,5]]: eigenvalues 7 ± √13. */
    CHECK_NEAR(s[0], sqrt(7 + sqrt(13)), 1e-12);
    CHECK_NEAR(s[1], sqrt(7 - sqrt(13)), 1e-12);
    CHECK_NEAR(det, 6, 1e-12);
    /* Mirrored UVs: same singular values, negative determinant. */
    for (int k = 0; k < 3; k++) q[k][0] = -q[k][0];
    det = uv_jacobian_singular_values(p, q, s);
    CHECK_NEAR(s[0], sqrt(7 + sqrt(13)), 1e-12);
    CHECK_NEAR(det, -6, 1e-12);
}

static void test_identity(void)
{
    neuv_mesh *m = shape_grid(8, 6, 2.0, 1.5, 1);
    CHECK(m != NULL);
    uv_metrics mt = measure(m);
    CHECK_INT(mt.charts, 1);
    CHECK_NEAR(mt.qce_mean, 1, 1e-12);
    CHECK_NEAR(mt.qce_p95, 1, 1e-12);
    CHECK_NEAR(mt.qce_max, 1, 1e-12);
    CHECK_NEAR(mt.ase_mean, 0, 1e-12);
    CHECK_NEAR(mt.ase_abs_mean, 0, 1e-12);
    CHECK_NEAR(mt.ase_abs_mean_chart, 0, 1e-12);
    CHECK_NEAR(mt.l2_stretch, 1, 1e-12);
    CHECK_NEAR(mt.linf_stretch, 1, 1e-12);
    CHECK_NEAR(mt.sym_dirichlet_mean, 4, 1e-12);
    CHECK_INT(mt.flipped, 0);
    CHECK_INT(mt.degenerate_uv, 0);
    CHECK_INT(mt.excluded_faces, 0);
    CHECK_NEAR(mt.overlap_fraction, 0, 0);
    CHECK_NEAR(mt.seam_length, 0, 0);
    CHECK(isnan(mt.packing_efficiency)); /* UVs reach u = 2 */
    mesh_free(m);
}

/* u doubled: J = diag(2,1). After scaling by σ = 1/√2 the singular values
 * are √2 and 1/√2, so Γ = √2, γ = 1/√2 (docs/metrics.md). */
static void test_u_doubled(void)
{
    neuv_mesh *m = shape_grid(5, 7, 1.0, 1.0, 1);
    for (int i = 0; i < m->nuv; i++) m->uv[2 * i] *= 2;
    uv_metrics mt = measure(m);
    CHECK_NEAR(mt.qce_mean, 2, 1e-12);
    CHECK_NEAR(mt.qce_p95, 2, 1e-12);
    CHECK_NEAR(mt.qce_max, 2, 1e-12);
    CHECK_NEAR(mt.ase_abs_mean, 0, 1e-12);
    CHECK_NEAR(mt.l2_stretch, sqrt(1.25), 1e-12);
    CHECK_NEAR(mt.linf_stretch, sqrt(2), 1e-12);
    CHECK_NEAR(mt.sym_dirichlet_mean, 5, 1e-12);
    CHECK_INT(mt.flipped, 0);
    CHECK(isnan(mt.packing_efficiency));
    mesh_free(m);
}

/* The per-chart figures the repair compares maps by (unwrap/chart_source.h):
 * the same values as the metrics for one chart, whatever the map's scale,
 * rotation or mirroring (u doubled then everything scaled by 3 and mirrored:
 * qce 2, L2 stretch √1.25; a similarity: 1 and 1). */
static void test_chart_figures(void)
{
    neuv_mesh *m = shape_grid(5, 7, 1.0, 1.0, 0);
    double *uv = malloc(sizeof(double) * 2 * (size_t)m->nv);
    for (int v = 0; v < m->nv; v++) { uv[2 * v] = -6 * m->pos[3 * v]; uv[2 * v + 1] = 3 * m->pos[3 * v + 1]; }
    double area;
    CHECK_NEAR(chart_qce_mean(m, uv, &area), 2, 1e-12);
    CHECK_NEAR(area, 1, 1e-12);
    CHECK_NEAR(chart_l2_stretch(m, uv), sqrt(1.25), 1e-12);
    for (int v = 0; v < m->nv; v++) { /* turned by 30 degrees, scaled by 0.1 */
        double x = m->pos[3 * v], y = m->pos[3 * v + 1];
        uv[2 * v] = 0.1 * (cos(0.5236) * x - sin(0.5236) * y);
        uv[2 * v + 1] = 0.1 * (sin(0.5236) * x + cos(0.5236) * y);
    }
    CHECK_NEAR(chart_qce_mean(m, uv, NULL), 1, 1e-12);
    CHECK_NEAR(chart_l2_stretch(m, uv), 1, 1e-12);
    free(uv);
    mesh_free(m);
}

/* Reflects the UV of a vertex used by a single face across the line through
 * the face's two other UVs: that face alone turns over, still joined to its
 * neighbour, and lands on top of it. */
static void test_one_flip(void)
{
    neuv_mesh *m = shape_grid(4, 3, 1.0, 1.0, 1);
    int *uses = calloc((size_t)m->nv, sizeof *uses);
    for (int c = 0; c < 3 * m->nf; c++) uses[m->tri[c]]++;
    int face = -1, corner = -1;
    for (int c = 0; c < 3 * m->nf && face < 0; c++)
        if (uses[m->tri[c]] == 1) { face = c / 3; corner = c % 3; }
    CHECK(face >= 0);
    const double *a = m->uv + 2 * m->tri_uv[3 * face + (corner + 1) % 3];
    const double *b = m->uv + 2 * m->tri_uv[3 * face + (corner + 2) % 3];
    double *p = m->uv + 2 * m->tri_uv[3 * face + corner];
    double dx = b[0] - a[0], dy = b[1] - a[1];
    double t = ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy);
    double fx = a[0] + t * dx, fy = a[1] + t * dy;
    p[0] = 2 * fx - p[0];
    p[1] = 2 * fy - p[1];
    uv_metrics mt = measure(m);
    CHECK_INT(mt.flipped, 1);
    CHECK_INT(mt.charts, 1);
    CHECK(mt.overlap_fraction > 0);
    CHECK_NEAR(mt.qce_max, 1, 1e-12); /* a reflection is conformal */
    free(uses);
    mesh_free(m);
}

/* Folds a grid over [0, w] x [0, 1] at u = 1: u' = 2 - u beyond it. The map
 * covers [0,1]^2 and [2 - w, 1] twice: overlap_fraction = w - 1. */
static double folded_overlap(int nx, double w)
{
    neuv_mesh *m = shape_grid(nx, 4, w, 1.0, 1);
    for (int i = 0; i < m->nuv; i++)
        if (m->uv[2 * i] > 1) m->uv[2 * i] = 2 - m->uv[2 * i];
    uv_metrics mt = measure(m);
    CHECK_INT(mt.charts, 1);
    CHECK(mt.flipped > 0);
    mesh_free(m);
    return mt.overlap_fraction;
}

static void test_fold(void)
{
    /* Grid lines on pixel boundaries and diagonals through pixel centres:
     * the fill rule must make this exact. */
    CHECK_NEAR(folded_overlap(6, 1.5), 0.5, 1e-12);
    /* A fold line between pixel columns: within one column of pixels. */
    CHECK_NEAR(folded_overlap(13, 1.3), 0.3, 1.0 / 2048);
}

/* Every centre of the unit square covered exactly once by a grid whose
 * diagonals pass through pixel centres and whose vertices are pixel corners. */
static void test_fill_rule(void)
{
    neuv_mesh *m = shape_grid(8, 8, 1.0, 1.0, 1);
    uv_coverage cov;
    CHECK_INT(uv_coverage_count(m->uv, m->nf, m->tri_uv, NULL, 2048, &cov), NEUV_OK);
    CHECK_INT(cov.covered, 2048LL * 2048);
    CHECK_INT(cov.overlapped, 0);
    /* Reversed faces cover the same centres (each is oriented before the test). */
    for (int f = 0; f < m->nf; f++) {
        int t = m->tri_uv[3 * f + 1];
        m->tri_uv[3 * f + 1] = m->tri_uv[3 * f + 2];
        m->tri_uv[3 * f + 2] = t;
    }
    CHECK_INT(uv_coverage_count(m->uv, m->nf, m->tri_uv, NULL, 2048, &cov), NEUV_OK);
    CHECK_INT(cov.covered, 2048LL * 2048);
    CHECK_INT(cov.overlapped, 0);
    CHECK_INT(uv_coverage_count(m->uv, m->nf, m->tri_uv, NULL, 0, &cov), NEUV_ERR_INPUT);
    mesh_free(m);
}

/* Chart pairs sharing a pixel centre: the unit-square grid cut into four
 * quadrant charts tiles the square (no pair, as the fill rule promises);
 * moving the top-right chart left by a tenth puts it on the top-left one
 * only, and a chart put on all three others meets all three. */
static void test_overlap_pairs(void)
{
    neuv_mesh *m = shape_grid(8, 8, 1.0, 1.0, 1);
    int *chart = malloc(sizeof(int) * m->nf), *pairs = NULL, np = -1;
    for (int f = 0; f < m->nf; f++) {
        double cx = 0, cy = 0;
        for (int k = 0; k < 3; k++) { cx += m->uv[2 * m->tri_uv[3 * f + k]] / 3; cy += m->uv[2 * m->tri_uv[3 * f + k] + 1] / 3; }
        chart[f] = (cx > 0.5) + 2 * (cy > 0.5);
    }
    CHECK_INT(uv_overlap_chart_pairs(m->uv, m->nf, m->tri_uv, chart, 2048, &pairs, &np), NEUV_OK);
    CHECK_INT(np, 0);
    free(pairs);
    unsigned char *hit = malloc((size_t)m->nf);
    CHECK_INT(uv_overlap_faces(m->uv, m->nf, m->tri_uv, chart, 2048, hit), NEUV_OK);
    int nhit = 0;
    for (int f = 0; f < m->nf; f++) nhit += hit[f];
    CHECK_INT(nhit, 0);
    /* Per-corner UVs for chart 3 alone, shifted left by 0.1. */
    int nuv = m->nuv;
    double *uv = malloc(sizeof(double) * 2 * (nuv + 3 * m->nf));
    int *tuv = malloc(sizeof(int) * 3 * m->nf);
    memcpy(uv, m->uv, sizeof(double) * 2 * nuv);
    memcpy(tuv, m->tri_uv, sizeof(int) * 3 * m->nf);
    for (int f = 0; f < m->nf; f++)
        if (chart[f] == 3)
            for (int k = 0; k < 3; k++) {
                uv[2 * nuv] = m->uv[2 * m->tri_uv[3 * f + k]] - 0.1;
                uv[2 * nuv + 1] = m->uv[2 * m->tri_uv[3 * f + k] + 1];
                tuv[3 * f + k] = nuv++;
            }
    CHECK_INT(uv_overlap_chart_pairs(uv, m->nf, tuv, chart, 2048, &pairs, &np), NEUV_OK);
    CHECK_INT(np, 1);
    if (np == 1) { CHECK_INT(pairs[0], 2); CHECK_INT(pairs[1], 3); }
    free(pairs);
    /* The faces hit: those of chart 2 in its right column of cells (x > 0.375) and those of
     * chart 3 in its left column (x < 0.625 before the shift), and no other. */
    CHECK_INT(uv_overlap_faces(uv, m->nf, tuv, chart, 2048, hit), NEUV_OK);
    int hit2 = 0, hit3 = 0, stray = 0;
    for (int f = 0; f < m->nf; f++) {
        if (!hit[f]) continue;
        double cx = 0;
        for (int k = 0; k < 3; k++) cx += m->uv[2 * m->tri_uv[3 * f + k]] / 3;
        if (chart[f] == 2 && cx > 0.375) hit2++;
        else if (chart[f] == 3 && cx < 0.625) hit3++;
        else stray++;
    }
    CHECK(hit2 >= 4 && hit2 <= 8);
    CHECK_INT(hit3, 8); /* every face of the column reaches into [0.4, 0.5) */
    CHECK_INT(stray, 0);
    /* Chart 3 shrunk to a small square about the centre: on all three others. */
    for (int f = 0; f < m->nf; f++)
        if (chart[f] == 3)
            for (int k = 0; k < 3; k++) {
                double *q = uv + 2 * tuv[3 * f + k];
                q[0] = 0.5 + 0.4 * (q[0] + 0.1 - 0.75);
                q[1] = 0.5 + 0.4 * (q[1] - 0.75);
            }
    CHECK_INT(uv_overlap_chart_pairs(uv, m->nf, tuv, chart, 2048, &pairs, &np), NEUV_OK);
    CHECK_INT(np, 3);
    if (np == 3) { CHECK_INT(pairs[0], 0); CHECK_INT(pairs[1], 3); CHECK_INT(pairs[4], 2); CHECK_INT(pairs[5], 3); }
    free(pairs);
    CHECK_INT(uv_overlap_chart_pairs(uv, m->nf, tuv, chart, 0, &pairs, &np), NEUV_ERR_INPUT);
    CHECK_INT(uv_overlap_faces(uv, m->nf, tuv, chart, 0, hit), NEUV_ERR_INPUT);
    free(uv); free(tuv); free(chart); free(hit);
    mesh_free(m);
}

/* docs/metrics.md's raster rule written out pixel by pixel, independently
 * of the span rasterizer in src/metrics/uv_overlap.c. */
static int brute_inside(double ax, double ay, double bx, double by, double cx, double cy)
{
    double w;
    if (ax < bx || (ax == bx && ay < by)) w = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
    else w = -((ax - bx) * (cy - by) - (ay - by) * (cx - bx));
    return w > 0 || (w == 0 && (by < ay || (by == ay && bx > ax)));
}

static uv_coverage brute_coverage(const double *uv, int nf, const int *tri_uv, int res)
{
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (int c = 0; c < 3 * nf; c++)
        for (int d = 0; d < 2; d++) {
            lo[d] = fmin(lo[d], uv[2 * tri_uv[c] + d]);
            hi[d] = fmax(hi[d], uv[2 * tri_uv[c] + d]);
        }
    double s = res / fmax(hi[0] - lo[0], hi[1] - lo[1]);
    int *count = calloc((size_t)res * res, sizeof *count);
    for (int f = 0; f < nf; f++) {
        double x[3], y[3];
        for (int k = 0; k < 3; k++) {
            x[k] = (uv[2 * tri_uv[3 * f + k]] - lo[0]) * s;
            y[k] = (uv[2 * tri_uv[3 * f + k] + 1] - lo[1]) * s;
        }
        double a2 = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
        if (a2 == 0) continue;
        if (a2 < 0) { double t = x[1]; x[1] = x[2]; x[2] = t; t = y[1]; y[1] = y[2]; y[2] = t; }
        for (int j = 0; j < res; j++)
            for (int i = 0; i < res; i++) {
                double cx = i + 0.5, cy = j + 0.5;
                count[j * res + i] += brute_inside(x[0], y[0], x[1], y[1], cx, cy) &&
                                      brute_inside(x[1], y[1], x[2], y[2], cx, cy) &&
                                      brute_inside(x[2], y[2], x[0], y[0], cx, cy);
            }
    }
    uv_coverage c = {0, 0};
    for (int p = 0; p < res * res; p++) { c.covered += count[p] >= 1; c.overlapped += count[p] >= 2; }
    free(count);
    return c;
}

/* The span rasterizer against the pixel-by-pixel rule: random triangles,
 * half of them with corners on a lattice so that edges run exactly through
 * pixel centres (the tie cases), and some slivers. */
static void test_raster_matches_rule(void)
{
    rng r;
    rng_seed(&r, 7);
    enum { NF = 120, RES = 96 };
    double uv[2 * 3 * NF];
    int tri_uv[3 * NF];
    for (int trial = 0; trial < 4; trial++) {
        for (int c = 0; c < 3 * NF; c++) {
            int lattice = (c / 3) % 2 == 0;
            for (int d = 0; d < 2; d++)
                uv[2 * c + d] = lattice ? rng_below(&r, 9) / 8.0 : rng_uniform(&r);
            tri_uv[c] = c;
        }
        for (int f = 0; f < NF; f += 10) /* slivers: third corner near the first edge */
            for (int d = 0; d < 2; d++)
                uv[2 * (3 * f + 2) + d] = (uv[2 * (3 * f) + d] + uv[2 * (3 * f + 1) + d]) / 2 + 1e-4 * d;
        uv_coverage fast, slow = brute_coverage(uv, NF, tri_uv, RES);
        CHECK_INT(uv_coverage_count(uv, NF, tri_uv, NULL, RES, &fast), NEUV_OK);
        CHECK_INT(fast.covered, slow.covered);
        CHECK_INT(fast.overlapped, slow.overlapped);
        CHECK(slow.overlapped > 0);
    }
}

/* Every face on the same square: the cost is per row, not per pixel. */
static void test_stacked(void)
{
    enum { NF = 20000 };
    const double uv[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    int *tri_uv = malloc(sizeof *tri_uv * 3 * NF);
    for (int f = 0; f < NF; f++) {
        int q = f % 2 ? 2 : 0; /* two halves of the square, alternating */
        tri_uv[3 * f] = 0; tri_uv[3 * f + 1] = q ? 2 : 1; tri_uv[3 * f + 2] = q ? 3 : 2;
    }
    uv_coverage cov;
    CHECK_INT(uv_coverage_count(uv, NF, tri_uv, NULL, 2048, &cov), NEUV_OK);
    CHECK_INT(cov.covered, 2048LL * 2048);
    CHECK_INT(cov.overlapped, 2048LL * 2048);
    free(tri_uv);
}

/* Two unit squares side by side in 3D (2 x 1 grid); the right one gets its
 * own UVs, shifted by 0.5 and scaled by `scale` about its corner. */
static neuv_mesh *two_charts(double scale)
{
    neuv_mesh *m = shape_grid(2, 1, 2.0, 1.0, 1);
    int nuv = m->nuv * 2;
    double *uv = malloc(sizeof *uv * 2 * (size_t)nuv);
    int *tri_uv = malloc(sizeof *tri_uv * 3 * (size_t)m->nf);
    for (int i = 0; i < m->nuv; i++) {
        uv[2 * i] = m->uv[2 * i];
        uv[2 * i + 1] = m->uv[2 * i + 1];
        uv[2 * (m->nuv + i)] = 1.5 + (m->uv[2 * i] - 1) * scale;
        uv[2 * (m->nuv + i) + 1] = m->uv[2 * i + 1] * scale;
    }
    for (int f = 0; f < m->nf; f++) {
        double cx = 0;
        for (int k = 0; k < 3; k++) cx += m->pos[3 * m->tri[3 * f + k]] / 3;
        for (int k = 0; k < 3; k++) tri_uv[3 * f + k] = m->tri_uv[3 * f + k] + (cx > 1 ? m->nuv : 0);
    }
    CHECK_INT(mesh_set_uv(m, nuv, uv, tri_uv), NEUV_OK);
    free(uv);
    free(tri_uv);
    return m;
}

static void test_two_charts(void)
{
    neuv_mesh *m = two_charts(1.0);
    uv_metrics mt = measure(m);
    CHECK_INT(mt.charts, 2);
    /* One cut edge of length 1 over √(3D area 2). */
    CHECK_NEAR(mt.seam_length, 1 / sqrt(2.0), 1e-12);
    CHECK_NEAR(mt.overlap_fraction, 0, 0);
    CHECK_NEAR(mt.ase_abs_mean, 0, 1e-12);
    mesh_free(m);

    /* Right chart scaled by 2: UV/3D area ratios 1 and 4, global 5/2, so
     * ase = -ln 2.5 and ln 1.6 on equal areas: mean |ase| = ln 2 and the
     * signed mean ln 0.8; per chart both are exact. σ² = 2/5, so the scaled
     * singular values are √0.4 and 2√0.4: L2² per face 2.5 and 0.625 (l2 =
     * 1.25), linf = √2.5, sym. Dirichlet (2(0.4 + 2.5) + 2(1.6 + 0.625))/2. */
    m = two_charts(2.0);
    mt = measure(m);
    CHECK_INT(mt.charts, 2);
    CHECK_NEAR(mt.ase_abs_mean, log(2.0), 1e-12);
    CHECK_NEAR(mt.ase_mean, log(0.8), 1e-12);
    CHECK_NEAR(mt.ase_abs_mean_chart, 0, 1e-12);
    CHECK_NEAR(mt.qce_mean, 1, 1e-12);
    CHECK_NEAR(mt.l2_stretch, 1.25, 1e-12);
    CHECK_NEAR(mt.linf_stretch, sqrt(2.5), 1e-12);
    CHECK_NEAR(mt.sym_dirichlet_mean, 5.125, 1e-12);
    CHECK_NEAR(mt.seam_length, 1 / sqrt(2.0), 1e-12);
    mesh_free(m);
}

static void test_packing(void)
{
    neuv_mesh *m = shape_grid(4, 4, 1.0, 1.0, 1);
    for (int i = 0; i < 2 * m->nuv; i++) m->uv[i] *= 0.5;
    uv_metrics mt = measure(m);
    CHECK_NEAR(mt.packing_efficiency, 0.25, 1e-12);
    mesh_free(m);
    /* The unit square itself, nudged within the 1e-9 tolerance. */
    m = shape_grid(3, 3, 1.0, 1.0, 1);
    for (int i = 0; i < 2 * m->nuv; i++) if (m->uv[i] == 1) m->uv[i] = 1 + 1e-10;
    mt = measure(m);
    CHECK_NEAR(mt.packing_efficiency, 1, 1e-9);
    m->uv[0] = -1e-6;
    mt = measure(m);
    CHECK(isnan(mt.packing_efficiency));
    mesh_free(m);
}

/* The identity grid plus (1) a face of zero 3D area with wild UVs and (2) a
 * separate face whose UVs are collinear: the first is left out of
 * everything, the second only counted as degenerate. */
static void test_degenerate(void)
{
    neuv_mesh *g = shape_grid(4, 4, 1.0, 1.0, 1);
    neuv_mesh *m = mesh_create(g->nv + 3, g->nf + 2, g->nuv + 3);
    memcpy(m->pos, g->pos, sizeof(double) * 3 * g->nv);
    memcpy(m->tri, g->tri, sizeof(int) * 3 * g->nf);
    memcpy(m->uv, g->uv, sizeof(double) * 2 * g->nuv);
    memcpy(m->tri_uv, g->tri_uv, sizeof(int) * 3 * g->nf);
    int v = g->nv, t = g->nuv, f = g->nf;
    /* (1) repeats a vertex: zero 3D area. */
    m->tri[3 * f] = 0; m->tri[3 * f + 1] = 1; m->tri[3 * f + 2] = 1;
    m->uv[2 * t] = 5; m->uv[2 * t + 1] = -3;
    m->tri_uv[3 * f] = t; m->tri_uv[3 * f + 1] = 0; m->tri_uv[3 * f + 2] = 1;
    /* (2) a right triangle above the grid, UVs on a line inside [0,1]². */
    const double p[3][3] = {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
    const double q[3][2] = {{0.1, 0.1}, {0.2, 0.2}, {0.4, 0.4}};
    for (int k = 0; k < 3; k++) {
        memcpy(m->pos + 3 * (v + k), p[k], sizeof p[k]);
        memcpy(m->uv + 2 * (t + k), q[k], sizeof q[k]);
        m->tri[3 * (f + 1) + k] = v + k;
        m->tri_uv[3 * (f + 1) + k] = t + k;
    }
    m->nuv = t + 3;
    uv_metrics mt = measure(m);
    CHECK_INT(mt.excluded_faces, 1);
    CHECK_INT(mt.degenerate_uv, 1);
    CHECK_INT(mt.charts, 2);
    CHECK_INT(mt.flipped, 0);
    CHECK_NEAR(mt.qce_mean, 1, 1e-12);
    CHECK_NEAR(mt.qce_max, 1, 1e-12);
    CHECK_NEAR(mt.ase_abs_mean, 0, 1e-12);
    CHECK_NEAR(mt.sym_dirichlet_mean, 4, 1e-12);
    CHECK_NEAR(mt.overlap_fraction, 0, 0);
    CHECK_NEAR(mt.packing_efficiency, 1, 1e-12); /* the excluded face's (5,-3) does not count */
    mesh_free(g);
    mesh_free(m);
}

static void test_no_uv(void)
{
    neuv_mesh *m = shape_grid(2, 2, 1.0, 1.0, 0);
    uv_metrics mt;
    CHECK_INT(uv_metrics_compute(m, &mt), NEUV_ERR_INPUT);
    mesh_free(m);
}

/* UDIM tiles: the left chart fills [0,1]^2 (tile 1001, efficiency 1), the
 * right one, halved, lies in [1.5,2] x [0,0.5] (1002, 0.25), then moved up
 * by one (1012); the unhalved right chart spans u 1.5..2.5, two tiles, so
 * the map is not laid out in tiles. One square: its efficiency is
 * packing_efficiency's. */
static void test_tiles(void)
{
    neuv_mesh *m = two_charts(0.5);
    neuv_uv_tile *t = NULL;
    int n = -1;
    CHECK_INT(uv_tiles_compute(m, &t, &n), NEUV_OK);
    CHECK_INT(n, 2);
    if (n == 2) {
        CHECK_INT(t[0].udim, 1001);
        CHECK_INT(t[1].udim, 1002);
        CHECK_NEAR(t[0].efficiency, 1, 1e-12);
        CHECK_NEAR(t[1].efficiency, 0.25, 1e-12);
        CHECK_INT(t[0].charts, 1);
        CHECK_INT(t[1].charts, 1);
        CHECK_INT(t[0].faces + t[1].faces, m->nf);
        CHECK_INT(t[0].faces, t[1].faces);
    }
    mem_free(t);
    for (int u = m->nuv / 2; u < m->nuv; u++) m->uv[2 * u + 1] += 1; /* the right chart's UVs */
    CHECK_INT(uv_tiles_compute(m, &t, &n), NEUV_OK);
    CHECK_INT(n, 2);
    if (n == 2) CHECK_INT(t[1].udim, 1012);
    mem_free(t);
    mesh_free(m);

    m = two_charts(1.0);
    CHECK_INT(uv_tiles_compute(m, &t, &n), NEUV_OK);
    CHECK_INT(n, 0);
    CHECK(t == NULL);
    mesh_free(m);

    m = shape_grid(4, 4, 1.0, 1.0, 1);
    for (int i = 0; i < 2 * m->nuv; i++) m->uv[i] *= 0.5;
    CHECK_INT(uv_tiles_compute(m, &t, &n), NEUV_OK);
    CHECK_INT(n, 1);
    if (n == 1) {
        CHECK_INT(t[0].udim, 1001);
        CHECK_NEAR(t[0].efficiency, measure(m).packing_efficiency, 1e-15);
        CHECK_INT(t[0].faces, m->nf);
    }
    mem_free(t);
    /* A UV left of u = 0: no tile. */
    m->uv[0] = -0.1;
    CHECK_INT(uv_tiles_compute(m, &t, &n), NEUV_OK);
    CHECK_INT(n, 0);
    mesh_set_uv(m, 0, NULL, NULL);
    CHECK_INT(uv_tiles_compute(m, &t, &n), NEUV_ERR_INPUT);
    mesh_free(m);
}

int main(void)
{
    test_jacobian();
    test_identity();
    test_u_doubled();
    test_chart_figures();
    test_one_flip();
    test_fold();
    test_fill_rule();
    test_overlap_pairs();
    test_raster_matches_rule();
    test_stacked();
    test_two_charts();
    test_packing();
    test_degenerate();
    test_no_uv();
    test_tiles();
    return check_report("test_metrics");
}
