/* Heat-method geodesics against exact distances: great circles on the unit
 * sphere, straight lines on a flat grid. */
#include <math.h>
#include <sys/resource.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#include "check.h"
#include "core/timer.h"
#include "geometry/heat_geodesics.h"
#include "mesh/shapes.h"

static double dist3(const double *a, const double *b)
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

static double great_circle(const double *a, const double *b)
{
    double c = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) /
               (sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]) * sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]));
    return acos(c > 1 ? 1 : c < -1 ? -1 : c);
}

static double mean_edge(const neuv_mesh *m)
{
    double s = 0;
    for (int f = 0; f < m->nf; f++)
        for (int c = 0; c < 3; c++) s += dist3(m->pos + 3 * m->tri[3 * f + c], m->pos + 3 * m->tri[3 * f + (c + 1) % 3]);
    return s / (3.0 * m->nf);
}

static long peak_rss_kb(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return ru.ru_maxrss;
}

/* Unit sphere: single source, batch = single, face distances, diameter. */
static void test_sphere(void)
{
    neuv_mesh *m = shape_icosphere(5, 1.0);
    CHECK(m != NULL);
    if (!m) return;
    heat_geodesics *g = NULL;
    double t0 = now_seconds();
    CHECK_INT(heat_geodesics_create(m, 1.0, &g), NEUV_OK);
    if (!g) { mesh_free(m); return; }
    double t_setup = now_seconds() - t0;
    double *d = malloc(sizeof(double) * m->nv);
    const int src = 17;
    t0 = now_seconds();
    CHECK_INT(heat_geodesics_from_vertex(g, src, d), NEUV_OK);
    double t_solve = now_seconds() - t0;
    double err = 0; int n = 0;
    double max_abs = 0;
    for (int v = 0; v < m->nv; v++) {
        double truth = great_circle(m->pos + 3 * src, m->pos + 3 * v);
        if (fabs(d[v] - truth) > max_abs) max_abs = fabs(d[v] - truth);
        if (truth < 0.05 || truth > 2.5) continue;
        err += fabs(d[v] - truth) / truth;
        n++;
    }
    err /= n;
    printf("sphere (%d vertices): setup %.3f s, solve %.4f s, mean relative error %.4f%% over %d vertices "
           "with true distance in [0.05, 2.5], max abs error %.4f\n", m->nv, t_setup, t_solve, 100 * err, n, max_abs);
    CHECK(err < 0.02);
    CHECK_NEAR(d[src], 0.0, 0.0);
    CHECK(max_abs < 0.1);

    /* Batched independent sources equal the one-at-a-time answers. */
    int srcs[3] = {src, 400, 9000};
    double *db = malloc(sizeof(double) * m->nv * 3);
    CHECK_INT(heat_geodesics_batch(g, srcs, 3, db), NEUV_OK);
    double worst = 0;
    for (int v = 0; v < m->nv; v++) worst = fmax(worst, fabs(db[v] - d[v]));
    CHECK(worst < 1e-10);
    CHECK_NEAR(db[2 * m->nv + 9000], 0.0, 0.0);
    double d400 = 0;
    heat_geodesics_from_vertex(g, 400, d);
    for (int v = 0; v < m->nv; v++) d400 = fmax(d400, fabs(db[m->nv + v] - d[v]));
    CHECK(d400 < 1e-10);

    /* Nearest of two antipodal-ish sources: the minimum of the two great circles. */
    double *dn = malloc(sizeof(double) * m->nv);
    int far = 0;
    for (int v = 0; v < m->nv; v++)
        if (great_circle(m->pos + 3 * src, m->pos + 3 * v) > great_circle(m->pos + 3 * src, m->pos + 3 * far)) far = v;
    int two[2] = {src, far};
    CHECK_INT(heat_geodesics_nearest(g, two, 2, dn), NEUV_OK);
    err = 0; n = 0;
    for (int v = 0; v < m->nv; v++) {
        double truth = fmin(great_circle(m->pos + 3 * src, m->pos + 3 * v), great_circle(m->pos + 3 * far, m->pos + 3 * v));
        if (truth < 0.05) continue;
        err += fabs(dn[v] - truth) / truth;
        n++;
    }
    err /= n;
    printf("sphere, nearest of two opposite sources: mean relative error %.4f%%\n", 100 * err);
    CHECK(err < 0.03);

    /* Face distances: against great circles between centroids, D_ff = 0,
     * nearly symmetric, and consistent with the vertex distances. */
    int faces[2] = {5, 12345};
    double *df = malloc(sizeof(double) * m->nf * 2);
    CHECK_INT(heat_geodesics_face_distances(g, m, faces, 2, df), NEUV_OK);
    double *cen = malloc(sizeof(double) * 3 * m->nf);
    for (int f = 0; f < m->nf; f++)
        for (int k = 0; k < 3; k++)
            cen[3 * f + k] = (m->pos[3 * m->tri[3 * f] + k] + m->pos[3 * m->tri[3 * f + 1] + k] + m->pos[3 * m->tri[3 * f + 2] + k]) / 3;
    err = 0; n = 0;
    for (int f = 0; f < m->nf; f++) {
        double truth = great_circle(cen + 3 * faces[0], cen + 3 * f);
        if (truth < 0.05 || truth > 2.5) continue;
        err += fabs(df[f] - truth) / truth;
        n++;
    }
    err /= n;
    printf("sphere face distances: mean relative error %.4f%% over %d faces\n", 100 * err, n);
    CHECK(err < 0.02);
    CHECK_NEAR(df[faces[0]], 0.0, 0.0);
    CHECK_NEAR(df[m->nf + faces[1]], 0.0, 0.0);
    CHECK_NEAR(df[faces[1]], df[m->nf + faces[0]], 0.02 * M_PI);
    /* From the face's first vertex, a face's centroid distance is the mean of
     * its vertex distances; the two sources are within one edge of each other. */
    double h = mean_edge(m);
    heat_geodesics_from_vertex(g, m->tri[3 * faces[0]], d);
    worst = 0;
    for (int f = 0; f < m->nf; f++) {
        const int *v = m->tri + 3 * f;
        worst = fmax(worst, fabs(df[f] - (d[v[0]] + d[v[1]] + d[v[2]]) / 3));
    }
    printf("face vs vertex distances: max difference %.4f (mean edge %.4f)\n", worst, h);
    CHECK(worst < 2 * h);

    double diam = 0;
    CHECK_INT(heat_geodesics_diameter(g, &diam), NEUV_OK);
    printf("sphere diameter estimate %.4f (pi = %.4f)\n", diam, M_PI);
    CHECK_NEAR(diam, M_PI, 0.02 * M_PI);

    /* Bad sources. */
    CHECK_INT(heat_geodesics_from_vertex(g, m->nv, d), NEUV_ERR_INPUT);
    CHECK_INT(heat_geodesics_from_vertex(g, -1, d), NEUV_ERR_INPUT);
    int badf = m->nf;
    CHECK_INT(heat_geodesics_face_distances(g, m, &badf, 1, df), NEUV_ERR_INPUT);

    free(d); free(db); free(dn); free(df); free(cen);
    heat_geodesics_free(g);
    mesh_free(m);
}

/* Mean relative error of a centre-source distance against the Euclidean one,
 * over vertices with 2h <= |x - source| <= 0.4: inside the unit square, so the
 * straight segment is the geodesic, and past the first rings where the heat
 * method rounds the cone tip. */
static double flat_error(const neuv_mesh *m, int src, double h, double *signed_err, int *count)
{
    heat_geodesics *g = NULL;
    double err = INFINITY;
    *signed_err = 0; *count = 0;
    if (heat_geodesics_create(m, 1.0, &g) != NEUV_OK) return err;
    double *d = malloc(sizeof(double) * m->nv);
    if (heat_geodesics_from_vertex(g, src, d) == NEUV_OK) {
        err = 0;
        for (int v = 0; v < m->nv; v++) {
            double truth = dist3(m->pos + 3 * src, m->pos + 3 * v);
            if (truth < 2 * h || truth > 0.4) continue;
            err += fabs(d[v] - truth) / truth;
            *signed_err += (d[v] - truth) / truth;
            ++*count;
        }
        err /= *count;
        *signed_err /= *count;
    }
    free(d);
    heat_geodesics_free(g);
    return err;
}

/* A flat equilateral triangle lattice, n by n rows of spacing 1/n. */
static neuv_mesh *equilateral_lattice(int n)
{
    neuv_mesh *m = mesh_create((n + 1) * (n + 1), 2 * n * n, 0);
    const double s = 1.0 / n, hy = s * sqrt(3.0) / 2;
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            int v = j * (n + 1) + i;
            m->pos[3 * v] = i * s + (j % 2) * 0.5 * s;
            m->pos[3 * v + 1] = j * hy;
        }
    int f = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++, f += 2) {
            int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
            int t[6] = {a, b, c, b, d, c};
            if (j % 2) { int u[6] = {a, b, d, a, d, c}; memcpy(t, u, sizeof t); }
            memcpy(m->tri + 3 * f, t, sizeof t);
        }
    return m;
}

/* Flat grids: Euclidean distance; open meshes, so the Neumann/Dirichlet
 * average is exercised. */
static void test_grid(void)
{
    /* shape_grid's right triangles: the cotangent weight of every diagonal
     * is 0, so the heat flows on a 4-neighbour lattice whose kernel is not
     * round at t = h²; the error plateaus near 1.5% under refinement. */
    const int n = 60;
    neuv_mesh *m = shape_grid(n, n, 1.0, 1.0, 0);
    const int src = (n / 2) * (n + 1) + n / 2; /* centre (0.5, 0.5) */
    double sgn; int cnt;
    double err = flat_error(m, src, 1.0 / n, &sgn, &cnt);
    printf("right-triangle grid %dx%d, centre source: mean relative error %.4f%% (signed %.4f%%) over %d vertices\n",
           n, n, 100 * err, 100 * sgn, cnt);
    CHECK(err < 0.02);
    /* An equilateral lattice of ~10k vertices (like the sphere's): under 1%. */
    neuv_mesh *e = equilateral_lattice(100);
    int esrc = 50 * 101 + 50;
    double eerr = flat_error(e, esrc, 0.01, &sgn, &cnt);
    printf("equilateral lattice 100x100, centre source: mean relative error %.4f%% (signed %.4f%%) over %d vertices\n",
           100 * eerr, 100 * sgn, cnt);
    CHECK(eerr < 0.01);
    mesh_free(e);

    heat_geodesics *g = NULL;
    CHECK_INT(heat_geodesics_create(m, 1.0, &g), NEUV_OK);
    if (!g) { mesh_free(m); return; }
    double *d = malloc(sizeof(double) * m->nv);
    /* A corner source lies on the boundary: Neumann part only. */
    CHECK_INT(heat_geodesics_from_vertex(g, 0, d), NEUV_OK);
    err = 0; cnt = 0;
    for (int v = 0; v < m->nv; v++) {
        double truth = dist3(m->pos, m->pos + 3 * v);
        if (truth < 2.0 / n) continue;
        err += fabs(d[v] - truth) / truth; cnt++;
    }
    err /= cnt;
    printf("grid, corner source: mean relative error %.4f%%\n", 100 * err);
    CHECK(err < 0.02);

    double diam = 0;
    CHECK_INT(heat_geodesics_diameter(g, &diam), NEUV_OK);
    printf("grid diameter estimate %.4f (sqrt 2 = %.4f)\n", diam, sqrt(2.0));
    CHECK_NEAR(diam, sqrt(2.0), 0.02 * sqrt(2.0));
    free(d);
    heat_geodesics_free(g);
    mesh_free(m);
}

/* pairs_within against brute-force Euclidean pairs on a grid. */
static void test_pairs(void)
{
    const int n = 30;
    neuv_mesh *m = shape_grid(n, n, 1.0, 1.0, 0);
    heat_geodesics *g = NULL;
    CHECK_INT(heat_geodesics_create(m, 1.0, &g), NEUV_OK);
    if (!g) { mesh_free(m); return; }
    /* Tolerances: between vertices at least `margin` from the boundary, 10% of
     * the radius (the right-triangle grid's ~1.7% bias plus the rounded
     * cone tip, about h/3 here); anywhere, 30%: a source on the boundary gets the Neumann
     * heat alone, whose isolines meet the boundary at right angles, so near
     * the square's corners its distances are too short (up to ~0.9 h here). */
    const double r = 0.15, tol = 0.1 * r, tol_all = 0.3 * r, margin = 0.1;
    geodesic_pairs p = {0};
    CHECK_INT(heat_geodesics_pairs_within(g, r, NULL, 0, &p), NEUV_OK);
    unsigned char *inner = malloc(m->nv);
    for (int v = 0; v < m->nv; v++) {
        double x = m->pos[3 * v], y = m->pos[3 * v + 1];
        inner[v] = fmin(fmin(x, 1 - x), fmin(y, 1 - y)) >= margin;
    }
    /* Every found pair: i < j, under the radius, distance close to Euclidean. */
    int ordered = 1, under = 1;
    double worst = 0, worst_inner = 0;
    unsigned char *found = calloc((size_t)m->nv * m->nv, 1); /* test only: 961² bytes */
    for (size_t k = 0; k < p.n; k++) {
        ordered &= p.i[k] < p.j[k];
        under &= p.d[k] < r;
        double e = fabs(p.d[k] - dist3(m->pos + 3 * p.i[k], m->pos + 3 * p.j[k]));
        worst = fmax(worst, e);
        if (inner[p.i[k]] && inner[p.j[k]]) worst_inner = fmax(worst_inner, e);
        found[(size_t)p.i[k] * m->nv + p.j[k]]++;
    }
    CHECK(ordered);
    CHECK(under);
    CHECK(worst_inner < tol);
    CHECK(worst < tol_all);
    /* Every Euclidean pair clearly inside the radius is found, exactly once;
     * none clearly outside it is. */
    int missing = 0, extra = 0, dup = 0;
    size_t brute = 0;
    for (int i = 0; i < m->nv; i++)
        for (int j = i + 1; j < m->nv; j++) {
            double e = dist3(m->pos + 3 * i, m->pos + 3 * j);
            unsigned char f = found[(size_t)i * m->nv + j];
            double t = inner[i] && inner[j] ? tol : tol_all;
            if (e < r) brute++;
            if (e < r - t && !f) missing++;
            if (e > r + t && f) extra++;
            if (f > 1) dup++;
        }
    printf("pairs within %.2f on a %dx%d grid: %zu found, %zu Euclidean; max error %.5f "
           "(%.5f between vertices %.2f from the boundary); %d missing, %d extra\n",
           r, n, n, p.n, brute, worst, worst_inner, margin, missing, extra);
    CHECK_INT(missing, 0);
    CHECK_INT(extra, 0);
    CHECK_INT(dup, 0);
    CHECK(p.n > brute * 0.9 && p.n < brute * 1.1);
    free(inner);

    /* Restricted to a subset: exactly the full list's pairs with both ends in it. */
    int *subset = malloc(sizeof(int) * m->nv);
    unsigned char *in = calloc(m->nv, 1);
    int ns = 0;
    for (int v = m->nv - 1; v >= 0; v--) /* descending order on purpose */
        if ((v * 7) % 3 == 0 && m->pos[3 * v] < 0.6) { subset[ns++] = v; in[v] = 1; }
    geodesic_pairs q = {0};
    CHECK_INT(heat_geodesics_pairs_within(g, r, subset, ns, &q), NEUV_OK);
    size_t expect = 0;
    for (size_t k = 0; k < p.n; k++) expect += in[p.i[k]] && in[p.j[k]];
    int same = 1;
    for (size_t k = 0; k < q.n; k++) {
        same &= in[q.i[k]] && in[q.j[k]] && q.i[k] < q.j[k];
        same &= found[(size_t)q.i[k] * m->nv + q.j[k]] == 1;
    }
    CHECK_INT(q.n, expect);
    CHECK(same);
    geodesic_pairs_free(&q);
    geodesic_pairs_free(&p);
    free(found); free(subset); free(in);
    heat_geodesics_free(g);
    mesh_free(m);

    /* Memory: on a 23k-vertex grid a dense V×V matrix of doubles would be
     * 4 GB; the peak resident size may grow by far less than that. */
    m = shape_grid(150, 150, 1.0, 1.0, 0);
    CHECK_INT(heat_geodesics_create(m, 1.0, &g), NEUV_OK);
    if (!g) { mesh_free(m); return; }
    ns = 0;
    subset = malloc(sizeof(int) * 300);
    for (int k = 0; k < 300; k++) subset[ns++] = (int)(((long)k * 7919) % m->nv);
    long before = peak_rss_kb();
    geodesic_pairs big = {0};
    CHECK_INT(heat_geodesics_pairs_within(g, 0.3, subset, ns, &big), NEUV_OK);
    long grown_kb = peak_rss_kb() - before;
    double dense_kb = (double)m->nv * m->nv * 8 / 1024;
    printf("pairs on %d vertices (subset of %d): %zu pairs, peak memory grew %ld KiB (dense V×V: %.0f KiB)\n",
           m->nv, ns, big.n, grown_kb, dense_kb);
    CHECK(grown_kb < dense_kb / 16);
    CHECK(big.n > 0);
    geodesic_pairs_free(&big);
    free(subset);
    heat_geodesics_free(g);
    mesh_free(m);
}

/* Two components: a source reaches only its own; a lone mesh with no faces is refused. */
static void test_components(void)
{
    neuv_mesh *a = shape_grid(10, 10, 1.0, 1.0, 0);
    neuv_mesh *m = mesh_create(2 * a->nv, 2 * a->nf, 0);
    for (int v = 0; v < a->nv; v++)
        for (int k = 0; k < 3; k++) {
            m->pos[3 * v + k] = a->pos[3 * v + k];
            m->pos[3 * (a->nv + v) + k] = a->pos[3 * v + k] + (k == 0 ? 5.0 : 0.0);
        }
    for (int f = 0; f < a->nf; f++)
        for (int k = 0; k < 3; k++) {
            m->tri[3 * f + k] = a->tri[3 * f + k];
            m->tri[3 * (a->nf + f) + k] = a->tri[3 * f + k] + a->nv;
        }
    heat_geodesics *g = NULL;
    CHECK_INT(heat_geodesics_create(m, 1.0, &g), NEUV_OK);
    double *d = malloc(sizeof(double) * m->nv);
    CHECK_INT(heat_geodesics_from_vertex(g, 0, d), NEUV_OK);
    CHECK(isfinite(d[a->nv - 1]) && fabs(d[a->nv - 1] - sqrt(2.0)) < 0.05);
    CHECK(isinf(d[a->nv]) && isinf(d[m->nv - 1]));
    double diam = 0;
    CHECK_INT(heat_geodesics_diameter(g, &diam), NEUV_OK);
    CHECK_NEAR(diam, sqrt(2.0), 0.03);
    heat_geodesics_free(g);
    free(d);
    mesh_free(m);
    mesh_free(a);

    neuv_mesh *empty = mesh_create(3, 0, 0);
    g = NULL;
    CHECK_INT(heat_geodesics_create(empty, 1.0, &g), NEUV_ERR_INPUT);
    CHECK(g == NULL);
    mesh_free(empty);
}

/* pairs_from: with every vertex a source it gives exactly pairs_within's
 * pairs (same order, same distances); with some sources, exactly the pairs
 * of pairs_within that have a source at one end, each once. */
static void test_pairs_from(void)
{
    neuv_mesh *m = shape_grid(20, 20, 1.0, 1.0, 0);
    heat_geodesics *g = NULL;
    CHECK_INT(heat_geodesics_create(m, 1.0, &g), NEUV_OK);
    if (!g) { mesh_free(m); return; }
    const double r = 0.2;
    geodesic_pairs all = {0}, from_all = {0}, some = {0};
    CHECK_INT(heat_geodesics_pairs_within(g, r, NULL, 0, &all), NEUV_OK);
    int *every = malloc(sizeof(int) * (size_t)m->nv);
    for (int v = 0; v < m->nv; v++) every[v] = v;
    CHECK_INT(heat_geodesics_pairs_from(g, r, every, m->nv, &from_all), NEUV_OK);
    CHECK_INT(from_all.n, all.n);
    int same = from_all.n == all.n;
    for (size_t k = 0; same && k < all.n; k++)
        same = all.i[k] == from_all.i[k] && all.j[k] == from_all.j[k] && all.d[k] == from_all.d[k];
    CHECK(same);
    /* Every 7th vertex a source (two of them are neighbours of each other). */
    int ns = 0;
    unsigned char *src = calloc((size_t)m->nv, 1);
    for (int v = 0; v < m->nv; v += 7) { every[ns++] = v; src[v] = 1; }
    CHECK_INT(heat_geodesics_pairs_from(g, r, every, ns, &some), NEUV_OK);
    unsigned char *found = calloc((size_t)m->nv * m->nv, 1);
    int ordered = 1, touches = 1;
    for (size_t k = 0; k < some.n; k++) {
        ordered &= some.i[k] < some.j[k];
        touches &= src[some.i[k]] || src[some.j[k]];
        found[(size_t)some.i[k] * m->nv + some.j[k]]++;
    }
    CHECK(ordered);
    CHECK(touches);
    /* Against pairs_within: the same set, distances within the heat method's
     * asymmetry (a pair found from its larger end reads that end's solve). */
    size_t expected = 0;
    int missing = 0, dup = 0;
    double worst = 0;
    for (size_t k = 0; k < all.n; k++) {
        if (!src[all.i[k]] && !src[all.j[k]]) continue;
        expected++;
        unsigned char f = found[(size_t)all.i[k] * m->nv + all.j[k]];
        missing += f == 0;
        dup += f > 1;
    }
    for (size_t k = 0; k < some.n; k++) {
        for (size_t q = 0; q < all.n; q++)
            if (all.i[q] == some.i[k] && all.j[q] == some.j[k]) { worst = fmax(worst, fabs(all.d[q] - some.d[k])); break; }
    }
    CHECK_INT(dup, 0);
    /* A pair near the radius may fall on either side of it from the other end. */
    CHECK(missing <= (int)(expected / 50));
    CHECK(some.n <= expected + expected / 50);
    CHECK(some.n > 0 && worst < 0.3 * r); /* as test_pairs: 30% of the radius near the boundary */
    CHECK_INT(heat_geodesics_pairs_from(g, r, (int[]){3, 3}, 2, &some), NEUV_ERR_INPUT);
    printf("pairs_from: %zu pairs from all %d vertices (= pairs_within), %zu from %d sources (%zu expected, %d missing, "
           "distance difference %.2g)\n", from_all.n, m->nv, some.n, ns, expected, missing, worst);
    free(found); free(src); free(every);
    geodesic_pairs_free(&all); geodesic_pairs_free(&from_all); geodesic_pairs_free(&some);
    heat_geodesics_free(g);
    mesh_free(m);
}

int main(void)
{
    test_sphere();
    test_grid();
    test_pairs();
    test_pairs_from();
    test_components();
    return check_report("test_geodesics");
}
