/* Charts from per-face labels: pieces, fragment merging, disks, splitting,
 * submeshes and chart adjacency, on procedural shapes and fertility.off. */
#include "check.h"

#include "charts/charts.h"
#include "charts/face_graph.h"
#include "core/error.h"
#include "core/rng.h"
#include "core/timer.h"
#include "mesh/clean.h"
#include "mesh/mesh.h"
#include "mesh/shapes.h"
#include "mesh/topology.h"

#if defined(__has_include)
#if __has_include("flatten/lscm.h")
#include "flatten/lscm.h"
#define HAVE_LSCM 1
#endif
#endif

/* Independent check of a chart assignment: every face covered once by an id
 * in 0..n-1, every chart non-empty, one edge-connected piece (via its
 * submesh), one boundary loop of distinct vertices, genus 0, Euler 1.
 * Returns the number of charts that fail. */
static int count_bad_charts(const neuv_mesh *m, const int *face_chart, int n)
{
    int bad = 0;
    for (int f = 0; f < m->nf; f++)
        if (face_chart[f] < 0 || face_chart[f] >= n) bad++;
    if (bad) return bad;
    int *seen = calloc((size_t)m->nv, sizeof(int));
    for (int c = 0; c < n; c++) {
        component_topology t;
        int ok = mesh_subset_topology(m, face_chart, c, &t) == NEUV_OK;
        ok = ok && t.faces > 0 && t.boundary_loops == 1 && t.genus == 0 && t.euler == 1;
        int *ls = NULL, *lv = NULL;
        int loops = mesh_boundary_loops(m, face_chart, c, &ls, &lv);
        ok = ok && loops == 1;
        if (loops == 1)
            for (int i = ls[0]; i < ls[1]; i++) {
                if (seen[lv[i]] == c + 1) ok = 0;
                seen[lv[i]] = c + 1;
            }
        free(ls); free(lv);
        neuv_mesh *sub = NULL;
        int *vmap = NULL, *fmap = NULL;
        if (ok && chart_submesh(m, face_chart, c, &sub, &vmap, &fmap) == NEUV_OK) {
            int *comp = malloc(sizeof(int) * (size_t)sub->nf);
            ok = mesh_face_components(sub, comp) == 1;
            free(comp);
        } else {
            ok = 0;
        }
        ok = ok && chart_is_disk(m, face_chart, c) == 1;
        mesh_free(sub); free(vmap); free(fmap);
        if (!ok) {
            fprintf(stderr, "  chart %d: faces %d loops %d genus %d euler %d\n", c, t.faces, loops, t.genus,
                    t.euler);
            bad++;
        }
    }
    free(seen);
    return bad;
}

/* Flattens every chart with LSCM (when built) and counts charts with
 * flipped faces (negative UV area; LSCM orients each chart positively).
 * Every chart must flatten: LSCM refuses anything that is not a disk. */
static void check_lscm(const neuv_mesh *m, const int *face_chart, int n, const char *what)
{
#ifdef HAVE_LSCM
    int failed = 0, charts_flipped = 0, faces_flipped = 0;
    for (int c = 0; c < n; c++) {
        neuv_mesh *sub;
        int *vmap, *fmap;
        if (chart_submesh(m, face_chart, c, &sub, &vmap, &fmap) != NEUV_OK) { failed++; continue; }
        double *uv = malloc(sizeof(double) * 2 * (size_t)sub->nv);
        if (lscm(sub, uv) != NEUV_OK) {
            fprintf(stderr, "  %s chart %d: %s\n", what, c, neuv_last_error());
            failed++;
        } else {
            int flips = 0;
            for (int f = 0; f < sub->nf; f++) {
                const double *a = uv + 2 * sub->tri[3 * f], *b = uv + 2 * sub->tri[3 * f + 1],
                             *d = uv + 2 * sub->tri[3 * f + 2];
                flips += (b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]) < 0;
            }
            charts_flipped += flips > 0;
            faces_flipped += flips;
        }
        free(uv); free(vmap); free(fmap);
        mesh_free(sub);
    }
    printf("  %-28s LSCM: %d charts, %d failed, %d with flipped faces (%d faces)\n", what, n, failed,
           charts_flipped, faces_flipped);
    CHECK_INT(failed, 0);
    CHECK(charts_flipped * 4 <= n);
#else
    (void)m; (void)face_chart; (void)n; (void)what;
#endif
}

static void centroid(const neuv_mesh *m, int f, double c[3])
{
    for (int k = 0; k < 3; k++)
        c[k] = (m->pos[3 * m->tri[3 * f] + k] + m->pos[3 * m->tri[3 * f + 1] + k] +
                m->pos[3 * m->tri[3 * f + 2] + k]) / 3.0;
}

static void print_report(const char *what, const charts_report *r)
{
    printf("  %-28s pieces %4d merged %4d separated %3d annulus_cuts %3d region_splits %3d -> charts %3d\n",
           what, r->pieces, r->merged, r->separated, r->annulus_cuts, r->region_splits, r->charts);
}

/* Cube labelled by the axis of the dominant normal (3 labels): opposite
 * sides share a label but not an edge, so step (a) must give the 6 sides. */
static void test_cube_sides(void)
{
    neuv_mesh *m = shape_cube(8);
    int *label = malloc(sizeof(int) * (size_t)m->nf), *chart = malloc(sizeof(int) * (size_t)m->nf);
    for (int f = 0; f < m->nf; f++) {
        double n[3];
        mesh_face_normal(m, f, n);
        int axis = 0;
        for (int k = 1; k < 3; k++)
            if (fabs(n[k]) > fabs(n[axis])) axis = k;
        label[f] = axis;
    }
    int nc = -1;
    charts_report r;
    CHECK_INT(charts_from_labels(m, label, NULL, chart, &nc, &r), NEUV_OK);
    print_report("cube(8) by normal axis", &r);
    CHECK_INT(nc, 6);
    CHECK_INT(r.pieces, 6);
    CHECK_INT(r.merged, 0);
    CHECK_INT(count_bad_charts(m, chart, nc), 0);
    /* Each chart is exactly one side: 128 faces sharing one normal. */
    for (int c = 0; c < nc; c++) {
        int count = 0, first = -1, same = 1;
        double n0[3] = {0, 0, 0}, n[3];
        for (int f = 0; f < m->nf; f++) {
            if (chart[f] != c) continue;
            mesh_face_normal(m, f, n);
            if (first < 0) { first = f; n0[0] = n[0]; n0[1] = n[1]; n0[2] = n[2]; }
            same = same && n[0] * n0[0] + n[1] * n0[1] + n[2] * n0[2] > 0.999;
            count++;
        }
        CHECK_INT(count, 8 * 8 * 2);
        CHECK(same);
    }
    /* Chart ids follow the first face. */
    int next = 0;
    for (int f = 0; f < m->nf; f++)
        if (chart[f] == next) next++;
        else CHECK(chart[f] < next);
    CHECK_INT(next, 6);

    /* Adjacency: 12 cube edges, each of length 2 and shared by two sides. */
    chart_adjacency adj;
    CHECK_INT(chart_adjacency_build(m, chart, &adj), NEUV_OK);
    CHECK_INT(adj.n, 12);
    for (int i = 0; i < adj.n; i++) {
        CHECK(adj.a[i] < adj.b[i]);
        CHECK_NEAR(adj.length[i], 2.0, 1e-9);
        if (i > 0) CHECK(adj.a[i - 1] < adj.a[i] || (adj.a[i - 1] == adj.a[i] && adj.b[i - 1] < adj.b[i]));
    }
    chart_adjacency_free(&adj);

    /* Submesh of side 0: a 9 by 9 vertex grid, maps back to the mesh. */
    neuv_mesh *sub;
    int *vmap, *fmap;
    CHECK_INT(chart_submesh(m, chart, 0, &sub, &vmap, &fmap), NEUV_OK);
    CHECK_INT(sub->nv, 81);
    CHECK_INT(sub->nf, 128);
    int maps_ok = 1;
    for (int j = 0; j < sub->nf; j++) {
        maps_ok = maps_ok && chart[fmap[j]] == 0 && (j == 0 || fmap[j] > fmap[j - 1]);
        for (int k = 0; k < 3; k++) maps_ok = maps_ok && vmap[sub->tri[3 * j + k]] == m->tri[3 * fmap[j] + k];
    }
    for (int v = 0; v < sub->nv; v++)
        for (int k = 0; k < 3; k++) maps_ok = maps_ok && sub->pos[3 * v + k] == m->pos[3 * vmap[v] + k];
    CHECK(maps_ok);
    CHECK_NEAR(mesh_total_area(sub), 4.0, 1e-9);
    mesh_free(sub); free(vmap); free(fmap);
    CHECK_INT(chart_submesh(m, chart, 6, &sub, &vmap, &fmap), NEUV_ERR_INPUT);
    CHECK(sub == NULL);

    /* Splitting one side (a disk) gives two disks of about half each. */
    int nc2 = nc;
    CHECK_INT(charts_split(m, chart, &nc2, 2), NEUV_OK);
    CHECK_INT(nc2, 7);
    CHECK_INT(count_bad_charts(m, chart, nc2), 0);
    int n2 = 0, n6 = 0;
    for (int f = 0; f < m->nf; f++) { n2 += chart[f] == 2; n6 += chart[f] == 6; }
    CHECK_INT(n2 + n6, 128);
    CHECK(n2 >= 40 && n6 >= 40);
    CHECK_INT(charts_split(m, chart, &nc2, 9), NEUV_ERR_INPUT);
    free(label); free(chart);
    mesh_free(m);
}

/* A long strip is split across its long axis, not along it. */
static void test_split_long_axis(void)
{
    neuv_mesh *m = shape_grid(40, 8, 5.0, 1.0, 0);
    int *chart = calloc((size_t)m->nf, sizeof(int));
    int nc = 1;
    CHECK_INT(charts_split(m, chart, &nc, 0), NEUV_OK);
    CHECK_INT(nc, 2);
    CHECK_INT(count_bad_charts(m, chart, nc), 0);
    double cx[2] = {0, 0}, cy[2] = {0, 0};
    int cnt[2] = {0, 0};
    for (int f = 0; f < m->nf; f++) {
        double c[3];
        centroid(m, f, c);
        cx[chart[f]] += c[0]; cy[chart[f]] += c[1]; cnt[chart[f]]++;
    }
    for (int i = 0; i < 2; i++) { cx[i] /= cnt[i]; cy[i] /= cnt[i]; }
    /* Halves along x: centroids 2.5 apart in x (1.25 and 3.75), same y. */
    CHECK_NEAR(fabs(cx[0] - cx[1]), 2.5, 0.25);
    CHECK_NEAR(cy[0], cy[1], 0.1);
    CHECK(abs(cnt[0] - cnt[1]) <= m->nf / 10);
    /* A single face cannot be split. */
    neuv_mesh *one = shape_grid(1, 1, 1.0, 1.0, 0);
    int two[2] = {0, 1}, n1 = 2;
    CHECK_INT(charts_split(one, two, &n1, 1), NEUV_ERR_INPUT);
    mesh_free(one);
    free(chart);
    mesh_free(m);
}

static int *labels_constant(const neuv_mesh *m, int value)
{
    int *l = malloc(sizeof(int) * (size_t)m->nf);
    for (int f = 0; f < m->nf; f++) l[f] = value;
    return l;
}

/* Runs charts_from_labels and checks the result; returns the chart ids
 * (caller frees) and writes the count. */
static int *run_charts(const neuv_mesh *m, const int *label, const char *what, int *nc, charts_report *r)
{
    int *chart = malloc(sizeof(int) * (size_t)m->nf);
    double t0 = now_seconds();
    neuv_status st = charts_from_labels(m, label, NULL, chart, nc, r);
    double t1 = now_seconds();
    CHECK_INT(st, NEUV_OK);
    if (st != NEUV_OK) {
        fprintf(stderr, "  %s: %s\n", what, neuv_last_error());
        *nc = 0;
        return chart;
    }
    print_report(what, r);
    printf("  %-28s %.3f s for %d faces\n", "", t1 - t0, m->nf);
    int bad = count_bad_charts(m, chart, *nc);
    CHECK_INT(bad, 0);
    CHECK_INT(r->charts, *nc);
    check_lscm(m, chart, *nc, what);
    return chart;
}

static void test_sphere(void)
{
    neuv_mesh *m = shape_icosphere(3, 1.0);
    int *label = labels_constant(m, 0), nc;
    charts_report r;
    int *chart = run_charts(m, label, "icosphere(3) one label", &nc, &r);
    /* A closed genus-0 piece is split into two disks by one region split. */
    CHECK_INT(nc, 2);
    CHECK_INT(r.region_splits, 1);
    free(chart);

    /* Octants: 8 disks, each 1/8 of the faces. */
    for (int f = 0; f < m->nf; f++) {
        double c[3];
        centroid(m, f, c);
        label[f] = (c[0] > 0) | (c[1] > 0) << 1 | (c[2] > 0) << 2;
    }
    chart = run_charts(m, label, "icosphere(3) octants", &nc, &r);
    CHECK_INT(nc, 8);
    CHECK_INT(r.pieces, 8);
    CHECK_INT(r.merged, 0);

    /* Octants with a few one-face islands of another label: the islands are
     * merged back and the 8 octant charts come out unchanged. */
    int *noisy = malloc(sizeof(int) * (size_t)m->nf), *chart2;
    memcpy(noisy, label, sizeof(int) * (size_t)m->nf);
    const int islands[5] = {17, 400, 777, 1001, 1200};
    for (int i = 0; i < 5; i++) noisy[islands[i]] = 9 + i % 2;
    charts_report r2;
    int nc2;
    chart2 = run_charts(m, noisy, "icosphere(3) octants+islands", &nc2, &r2);
    CHECK_INT(nc2, 8);
    CHECK(r2.pieces >= 8 + 5);
    CHECK_INT(r2.merged, r2.pieces - 8);
    CHECK(memcmp(chart, chart2, sizeof(int) * (size_t)m->nf) == 0);
    /* With no threshold the islands stay as one-face charts, and each
     * octant holding one (an annulus) is cut in two. */
    charts_options o;
    charts_default_options(&o);
    o.min_area_share = 0.0;
    /* Smoothing would let an island take in the faces beside the annulus
     * cuts (that shortens the boundary); this case is about the threshold. */
    o.smooth_sweeps = 0;
    int nc3;
    CHECK_INT(charts_from_labels(m, noisy, &o, chart2, &nc3, &r2), NEUV_OK);
    CHECK_INT(r2.merged, 0);
    CHECK(r2.annulus_cuts >= 1);
    CHECK(nc3 >= 8 + 5 + r2.annulus_cuts + r2.region_splits + r2.separated);
    CHECK(nc3 <= 8 + 5 + 3 * (r2.annulus_cuts + r2.region_splits + r2.separated));
    for (int i = 0; i < 5; i++) {
        int same = 0;
        for (int f = 0; f < m->nf; f++) same += chart2[f] == chart2[islands[i]];
        CHECK_INT(same, 1);
    }
    CHECK_INT(count_bad_charts(m, chart2, nc3), 0);

    /* Bad input. */
    noisy[3] = -1;
    CHECK_INT(charts_from_labels(m, noisy, NULL, chart2, &nc3, NULL), NEUV_ERR_INPUT);
    o.min_area_share = 1.5;
    CHECK_INT(charts_from_labels(m, label, &o, chart2, &nc3, NULL), NEUV_ERR_INPUT);
    o.min_area_share = NAN;
    CHECK_INT(charts_from_labels(m, label, &o, chart2, &nc3, NULL), NEUV_ERR_INPUT);
    free(noisy); free(chart2); free(chart); free(label);
    mesh_free(m);
}

static void test_torus_genus2(void)
{
    neuv_mesh *m = shape_torus(1.0, 0.3, 48, 16);
    int *label = labels_constant(m, 0), nc;
    charts_report r;
    int *chart = run_charts(m, label, "torus one label", &nc, &r);
    CHECK(nc >= 2 && nc <= 6);
    free(chart);
    /* Two labels by the sign of x: two tubes (annuli), each cut in two. */
    for (int f = 0; f < m->nf; f++) {
        double c[3];
        centroid(m, f, c);
        label[f] = c[0] > 0;
    }
    chart = run_charts(m, label, "torus two labels", &nc, &r);
    CHECK_INT(r.pieces, 2);
    CHECK_INT(r.annulus_cuts, 2);
    CHECK_INT(nc, 4);
    free(chart); free(label);
    mesh_free(m);

    m = shape_genus2(4);
    label = labels_constant(m, 0);
    chart = run_charts(m, label, "genus2 one label", &nc, &r);
    CHECK(nc >= 2);
    free(chart); free(label);
    mesh_free(m);

    /* An open cylinder (annulus) is cut lengthwise into two half-tubes. */
    m = shape_cylinder(0.5, 4.0, 32, 40);
    label = labels_constant(m, 0);
    chart = run_charts(m, label, "long cylinder one label", &nc, &r);
    CHECK_INT(r.annulus_cuts, 1);
    CHECK_INT(nc, 2);
    free(chart); free(label);
    mesh_free(m);
}

static neuv_mesh *load_fertility(void)
{
    const char *path = shared_path("meshes/fertility.off");
    if (!path) return NULL;
    struct stat st;
    if (stat(path, &st) != 0) return NULL;
    neuv_mesh *m = NULL;
    if (neuv_mesh_load(path, NULL, &m) != NEUV_OK) return NULL;
    mesh_clean_report cr;
    if (mesh_clean(m, NULL, &cr) != NEUV_OK) { mesh_free(m); return NULL; }
    return m;
}

static void test_fertility(const neuv_mesh *m)
{
    int *label = labels_constant(m, 0), nc;
    charts_report r;
    int *chart = run_charts(m, label, "fertility one label", &nc, &r);
    CHECK(nc >= 2);
    free(chart);

    /* Noisy patches: 12 random sites, label = nearest site in space (so a
     * label can come in several pieces and wrap handles), 3% of the faces
     * then given a random label (one-face islands). */
    rng g;
    rng_seed(&g, 42);
    double site[12][3];
    for (int s = 0; s < 12; s++) centroid(m, rng_below(&g, m->nf), site[s]);
    for (int f = 0; f < m->nf; f++) {
        double c[3], best = INFINITY;
        centroid(m, f, c);
        for (int s = 0; s < 12; s++) {
            double d = (c[0] - site[s][0]) * (c[0] - site[s][0]) + (c[1] - site[s][1]) * (c[1] - site[s][1]) +
                       (c[2] - site[s][2]) * (c[2] - site[s][2]);
            if (d < best) { best = d; label[f] = s; }
        }
        if (rng_uniform(&g) < 0.03) label[f] = rng_below(&g, 12);
    }
    chart = run_charts(m, label, "fertility 12 noisy patches", &nc, &r);
    CHECK(r.merged > 100);
    CHECK(nc >= 12 && nc < 60);
    /* No chart made of whole merged pieces stays under the threshold unless
     * a cut made it; at least most charts are large. */
    double total = mesh_total_area(m);
    int small = 0;
    for (int c = 0; c < nc; c++) {
        double a = 0;
        for (int f = 0; f < m->nf; f++)
            if (chart[f] == c) a += mesh_face_area(m, f);
        small += a < 0.002 * total;
    }
    printf("  charts under 0.2%% of the area after cuts: %d of %d\n", small, nc);
    CHECK(small <= nc / 4);

    /* Determinism: the same input gives identical charts. */
    int nc2;
    int *chart2 = malloc(sizeof(int) * (size_t)m->nf);
    CHECK_INT(charts_from_labels(m, label, NULL, chart2, &nc2, NULL), NEUV_OK);
    CHECK_INT(nc2, nc);
    CHECK(memcmp(chart, chart2, sizeof(int) * (size_t)m->nf) == 0);
    free(chart); free(chart2);

    /* Every face its own random label: everything is a fragment. */
    for (int f = 0; f < m->nf; f++) label[f] = rng_below(&g, 8);
    chart = run_charts(m, label, "fertility random per face", &nc, &r);
    CHECK(nc >= 1);
    free(chart); free(label);
}

/* Length of the edges whose two faces lie in different charts. */
static double cut_length(const neuv_mesh *m, const int *chart)
{
    double len = 0;
    for (int f = 0; f < m->nf; f++)
        for (int g = f + 1; g < m->nf; g++) {
            if (chart[f] == chart[g]) continue;
            int shared[2], n = 0;
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++)
                    if (m->tri[3 * f + i] == m->tri[3 * g + j] && n < 2) shared[n++] = m->tri[3 * f + i];
            if (n == 2) {
                const double *p = m->pos + 3 * shared[0], *q = m->pos + 3 * shared[1];
                len += sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                            (p[2] - q[2]) * (p[2] - q[2]));
            }
        }
    return len;
}

/* Even rows of the 16 x 16 grid, away from its top and bottom edges (at a
 * mesh edge a tooth's partner face may follow it: open edges count for no
 * chart, so the pair is as short as the straight cut). */
static int tooth_row(double y)
{
    int row = (int)(y * 16);
    return row % 2 == 0 && row >= 2 && row <= 13;
}

/* Boundary smoothing: single-triangle teeth along a straight cut go back,
 * leaving the straight cut; charts stay disks without the global fallback;
 * inactive charts keep their faces; the result is deterministic. */
static void test_smooth_boundaries(void)
{
    neuv_mesh *m = shape_grid(16, 16, 1.0, 1.0, 0);
    int *chart = malloc(sizeof(int) * (size_t)m->nf);
    int teeth = 0;
    for (int f = 0; f < m->nf; f++) {
        double c[3];
        centroid(m, f, c);
        chart[f] = c[0] < 0.5 ? 0 : 1;
    }
    double straight = cut_length(m, chart);
    CHECK_NEAR(straight, 1.0, 1e-9);
    /* Teeth: faces of chart 1 with an edge on x = 0.5, every other row. */
    for (int f = 0; f < m->nf; f++) {
        double c[3];
        centroid(m, f, c);
        int on_line = 0;
        for (int k = 0; k < 3; k++) on_line += fabs(m->pos[3 * m->tri[3 * f + k]] - 0.5) < 1e-9;
        if (chart[f] == 1 && on_line == 2 && tooth_row(c[1])) { chart[f] = 0; teeth++; }
    }
    CHECK(teeth >= 6);
    CHECK_INT(count_bad_charts(m, chart, 2), 0);
    CHECK(cut_length(m, chart) > straight + 0.5);
    int moves = -1;
    CHECK_INT(charts_smooth_boundaries(m, NULL, chart, 50, &moves), NEUV_OK);
    CHECK_INT(moves, teeth);
    CHECK_NEAR(cut_length(m, chart), straight, 1e-9);
    CHECK_INT(count_bad_charts(m, chart, 2), 0);
    /* With chart 1 inactive nothing may move. */
    int *copy = malloc(sizeof(int) * (size_t)m->nf);
    for (int f = 0; f < m->nf; f++) {
        double c[3];
        centroid(m, f, c);
        chart[f] = c[0] < 0.5 ? 0 : 1;
        int on_line = 0;
        for (int k = 0; k < 3; k++) on_line += fabs(m->pos[3 * m->tri[3 * f + k]] - 0.5) < 1e-9;
        if (chart[f] == 1 && on_line == 2 && tooth_row(c[1])) chart[f] = 0;
    }
    memcpy(copy, chart, sizeof(int) * (size_t)m->nf);
    int active[2] = {1, 0};
    CHECK_INT(charts_smooth_boundaries(m, active, chart, 50, &moves), NEUV_OK);
    CHECK_INT(moves, 0);
    CHECK(memcmp(copy, chart, sizeof(int) * (size_t)m->nf) == 0);
    free(copy);
    free(chart);
    mesh_free(m);

    /* Random labels on a sphere give ragged disks; smoothing them directly
     * (no fallback) must keep every chart a disk and shorten the cuts. */
    m = shape_icosphere(3, 1.0);
    int *label = malloc(sizeof(int) * (size_t)m->nf);
    rng r;
    rng_seed(&r, 7);
    for (int f = 0; f < m->nf; f++) label[f] = (int)rng_below(&r, 6);
    charts_options o;
    charts_default_options(&o);
    CHECK_INT(o.smooth_sweeps, 50);
    o.smooth_sweeps = 0;
    int nc = 0;
    chart = malloc(sizeof(int) * (size_t)m->nf);
    CHECK_INT(charts_from_labels(m, label, &o, chart, &nc, NULL), NEUV_OK);
    CHECK_INT(count_bad_charts(m, chart, nc), 0);
    double before = cut_length(m, chart);
    int *again = malloc(sizeof(int) * (size_t)m->nf);
    memcpy(again, chart, sizeof(int) * (size_t)m->nf);
    CHECK_INT(charts_smooth_boundaries(m, NULL, chart, 50, &moves), NEUV_OK);
    CHECK(moves > 0);
    double after = cut_length(m, chart);
    printf("  icosphere(3) random 6 labels: %d charts, cut length %.2f -> %.2f after %d moves\n", nc, before,
           after, moves);
    CHECK(after < before);
    CHECK_INT(count_bad_charts(m, chart, nc), 0);
    int moves2 = 0;
    CHECK_INT(charts_smooth_boundaries(m, NULL, again, 50, &moves2), NEUV_OK);
    CHECK_INT(moves2, moves);
    CHECK(memcmp(again, chart, sizeof(int) * (size_t)m->nf) == 0);
    /* A second pass finds nothing left to move. */
    CHECK_INT(charts_smooth_boundaries(m, NULL, chart, 50, &moves2), NEUV_OK);
    CHECK_INT(moves2, 0);
    CHECK_INT(charts_smooth_boundaries(NULL, NULL, chart, 50, &moves2), NEUV_ERR_INPUT);
    free(again); free(chart); free(label);
    mesh_free(m);
}

/* Polygons kept whole: a 16 x 16 grid of quads (two triangles each) cut
 * by a slanted line through the cells, so that many quads have a triangle
 * on each side; charts_keep_polygons puts every quad on one chart, keeps
 * both charts disks, and moves nothing where a chart is inactive. */
static int quads_split(const neuv_mesh *m, const int *chart)
{
    int n = 0;
    for (int f = 0; f < m->nf; f += 2) n += chart[f] != chart[f + 1];
    return n;
}

static void test_keep_polygons(void)
{
    neuv_mesh *m = shape_grid(16, 16, 1.0, 1.0, 0);
    int *poly = malloc(sizeof(int) * (size_t)m->nf);
    int *chart = malloc(sizeof(int) * (size_t)m->nf);
    int *copy = malloc(sizeof(int) * (size_t)m->nf);
    for (int f = 0; f < m->nf; f++) {
        double c[3];
        centroid(m, f, c);
        poly[f] = f / 2;
        chart[f] = c[0] - 0.8 * c[1] < 0.1 ? 0 : 1;
    }
    int before = quads_split(m, chart);
    CHECK(before >= 8);
    CHECK_INT(count_bad_charts(m, chart, 2), 0);
    CHECK_INT(charts_count_split_polygons(m->nf, poly, chart), before);
    memcpy(copy, chart, sizeof(int) * (size_t)m->nf);
    int left = -1, active[2] = {1, 0};
    CHECK_INT(charts_keep_polygons(m, poly, active, chart, &left), NEUV_OK);
    CHECK_INT(left, before);
    CHECK(memcmp(copy, chart, sizeof(int) * (size_t)m->nf) == 0);
    CHECK_INT(charts_keep_polygons(m, poly, NULL, chart, &left), NEUV_OK);
    CHECK_INT(left, 0);
    CHECK_INT(quads_split(m, chart), 0);
    CHECK_INT(charts_count_split_polygons(m->nf, poly, chart), 0);
    CHECK_INT(count_bad_charts(m, chart, 2), 0);
    /* Only triangles of split quads moved. */
    int moved = 0, wrong = 0;
    for (int f = 0; f < m->nf; f++) {
        if (chart[f] == copy[f]) continue;
        moved++;
        wrong += copy[f ^ 1] == copy[f];
    }
    CHECK_INT(moved, before);
    CHECK_INT(wrong, 0);
    /* Faces of no polygon (negative ids) are left alone. */
    for (int f = 0; f < m->nf; f++) poly[f] = -1 - f;
    memcpy(chart, copy, sizeof(int) * (size_t)m->nf);
    CHECK_INT(charts_keep_polygons(m, poly, NULL, chart, &left), NEUV_OK);
    CHECK_INT(left, 0);
    CHECK(memcmp(copy, chart, sizeof(int) * (size_t)m->nf) == 0);
    CHECK_INT(charts_keep_polygons(NULL, poly, NULL, chart, &left), NEUV_ERR_INPUT);
    free(poly); free(chart); free(copy);
    mesh_free(m);
}

/* face_graph_build's adjacency against pairing every half-edge with every
 * other: faces join across an edge with exactly two half-edges of two
 * faces. The mesh mixes a grid, a fan of 60 faces round one vertex (the
 * sort's long bucket), an edge shared by three faces, and a face with a
 * repeated vertex, with faces in a shuffled order. */
static void test_face_graph(void)
{
    neuv_mesh *grid = shape_grid(6, 5, 1, 1, 0);
    const int fan = 60, extra = 3 + 1;
    int nv = grid->nv + 1 + fan + 2, nf = grid->nf + fan + extra;
    neuv_mesh *m = mesh_create(nv, nf, 0);
    memcpy(m->pos, grid->pos, sizeof(double) * 3 * (size_t)grid->nv);
    int *tri = malloc(sizeof(int) * 3 * (size_t)nf), t = 0;
    for (int f = 0; f < grid->nf; f++, t++) memcpy(tri + 3 * t, grid->tri + 3 * f, 3 * sizeof(int));
    int c = grid->nv; /* the fan's centre, then its rim */
    m->pos[3 * c] = 3; m->pos[3 * c + 1] = 0; m->pos[3 * c + 2] = 0;
    for (int i = 0; i < fan; i++) {
        double a = 2 * 3.14159265358979 * i / fan;
        m->pos[3 * (c + 1 + i)] = 3 + cos(a); m->pos[3 * (c + 1 + i) + 1] = sin(a); m->pos[3 * (c + 1 + i) + 2] = 0;
        int tr[3] = {c, c + 1 + i, c + 1 + (i + 1) % fan};
        memcpy(tri + 3 * t++, tr, sizeof tr);
    }
    int p = c + 1 + fan; /* two more points: three faces on the grid's edge (0, 1) */
    m->pos[3 * p + 2] = 1; m->pos[3 * (p + 1) + 2] = -1;
    int more[4][3] = {{0, 1, p}, {1, 0, p + 1}, {0, p, p + 1}, {2, 2, 3}};
    for (int i = 0; i < extra; i++) memcpy(tri + 3 * t++, more[i], sizeof more[i]);
    rng r;
    rng_seed(&r, 11);
    for (int i = nf - 1; i > 0; i--) {
        int j = (int)(rng_uniform(&r) * (i + 1));
        for (int k = 0; k < 3; k++) { int x = tri[3 * i + k]; tri[3 * i + k] = tri[3 * j + k]; tri[3 * j + k] = x; }
    }
    memcpy(m->tri, tri, sizeof(int) * 3 * (size_t)nf);
    face_graph g;
    CHECK_INT(face_graph_build(m, &g), NEUV_OK);
    int bad = 0, joined = 0;
    for (int h = 0; h < 3 * nf; h++) {
        int a = tri[h], b = tri[3 * (h / 3) + (h % 3 + 1) % 3], count = 0, other = -1;
        for (int h2 = 0; h2 < 3 * nf; h2++) {
            int a2 = tri[h2], b2 = tri[3 * (h2 / 3) + (h2 % 3 + 1) % 3];
            if ((a2 == a && b2 == b) || (a2 == b && b2 == a)) { count++; if (h2 != h) other = h2; }
        }
        int want = a != b && count == 2 && other / 3 != h / 3 ? other / 3 : -1;
        bad += g.adj[h] != want;
        joined += want >= 0;
    }
    CHECK_INT(bad, 0);
    CHECK(joined > 2 * (grid->nf + fan)); /* the grid's and the fan's inner edges */
    face_graph_free(&g);
    free(tri);
    mesh_free(m);
    mesh_free(grid);
}

int main(void)
{
    test_face_graph();
    test_cube_sides();
    test_split_long_axis();
    test_smooth_boundaries();
    test_keep_polygons();
    test_sphere();
    test_torus_genus2();
    neuv_mesh *m = load_fertility();
    if (m) test_fertility(m);
    else printf("  fertility.off not found: skipped those cases\n");
    mesh_free(m);
    return check_report("test_charts");
}
