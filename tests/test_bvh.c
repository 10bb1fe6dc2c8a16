/* BVH closest points against brute force over every triangle, on an
 * icosphere and a torus; points on the surface have distance 0 and their
 * own barycentric coordinates. */
#include <string.h>

#include "check.h"
#include "core/rng.h"
#include "mesh/shapes.h"
#include "spatial/bvh.h"
#include "spatial/triangle_closest_point.h"

static double brute_force(const neuv_mesh *m, const double p[3])
{
    double best = INFINITY;
    for (int f = 0; f < m->nf; f++) {
        double w[3];
        const int *t = m->tri + 3 * f;
        double d = triangle_closest_point(m->pos + 3 * t[0], m->pos + 3 * t[1], m->pos + 3 * t[2], p, w);
        if (d < best) best = d;
    }
    return best;
}

/* Random points in the bounding box grown by `pad`, against brute force. */
static void check_against_brute_force(const neuv_mesh *m, double pad, int n, uint64_t seed)
{
    bvh b;
    CHECK_INT(bvh_build(&b, m), NEUV_OK);
    double lo[3], hi[3];
    mesh_bounding_box(m, lo, hi);
    rng r;
    rng_seed(&r, seed);
    int bad = 0, bad_point = 0;
    double *pts = malloc(sizeof(double) * 3 * n), *d2 = malloc(sizeof(double) * n);
    int *face = malloc(sizeof(int) * n);
    double *bary = malloc(sizeof(double) * 3 * n);
    for (int i = 0; i < 3 * n; i++) pts[i] = lo[i % 3] - pad + (hi[i % 3] - lo[i % 3] + 2 * pad) * rng_uniform(&r);
    bvh_closest_points(&b, n, pts, face, bary, d2);
    for (int i = 0; i < n; i++) {
        double ref = brute_force(m, pts + 3 * i);
        if (fabs(ref - d2[i]) > 1e-12) bad++;
        /* The reported face and weights reproduce the reported distance. */
        const int *t = m->tri + 3 * face[i];
        double q2 = 0;
        for (int k = 0; k < 3; k++) {
            double x = bary[3 * i] * m->pos[3 * t[0] + k] + bary[3 * i + 1] * m->pos[3 * t[1] + k] +
                       bary[3 * i + 2] * m->pos[3 * t[2] + k];
            q2 += (x - pts[3 * i + k]) * (x - pts[3 * i + k]);
        }
        if (fabs(q2 - d2[i]) > 1e-12) bad_point++;
    }
    CHECK_INT(bad, 0);
    CHECK_INT(bad_point, 0);
    /* The single-query path gives the same answers as the batch. */
    int f0; double w0[3], e0;
    bvh_closest_point(&b, pts, &f0, w0, &e0);
    CHECK_INT(f0, face[0]);
    CHECK(e0 == d2[0]);
    free(pts); free(d2); free(face); free(bary);
    bvh_free(&b);
}

/* Points at known barycentric coordinates of random faces. */
static void check_on_surface(const neuv_mesh *m, int n, uint64_t seed)
{
    bvh b;
    CHECK_INT(bvh_build(&b, m), NEUV_OK);
    rng r;
    rng_seed(&r, seed);
    double worst_d = 0, worst_w = 0;
    int wrong_face = 0;
    for (int i = 0; i < n; i++) {
        int f = rng_below(&r, m->nf);
        /* Strictly inside, away from edges, so the face is unique. */
        double w[3] = {0.1 + 0.8 * rng_uniform(&r), 0.1 + 0.8 * rng_uniform(&r), 0.1 + 0.8 * rng_uniform(&r)};
        double s = w[0] + w[1] + w[2];
        for (int k = 0; k < 3; k++) w[k] /= s;
        double p[3];
        const int *t = m->tri + 3 * f;
        for (int k = 0; k < 3; k++) p[k] = w[0] * m->pos[3 * t[0] + k] + w[1] * m->pos[3 * t[1] + k] + w[2] * m->pos[3 * t[2] + k];
        int g; double wb[3], d2;
        bvh_closest_point(&b, p, &g, wb, &d2);
        if (g != f) { wrong_face++; continue; }
        worst_d = fmax(worst_d, sqrt(d2));
        for (int k = 0; k < 3; k++) worst_w = fmax(worst_w, fabs(wb[k] - w[k]));
        double wp[3];
        triangle_barycentric(m->pos + 3 * t[0], m->pos + 3 * t[1], m->pos + 3 * t[2], p, wp);
        for (int k = 0; k < 3; k++) worst_w = fmax(worst_w, fabs(wp[k] - w[k]));
    }
    CHECK_INT(wrong_face, 0);
    CHECK(worst_d < 1e-12);
    CHECK(worst_w < 1e-9);
    bvh_free(&b);
}

static void test_triangle_regions(void)
{
    double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0}, w[3];
    double p1[3] = {-1, -1, 0.5}; /* vertex region of a */
    CHECK_NEAR(triangle_closest_point(a, b, c, p1, w), 2.25, 1e-15);
    CHECK_NEAR(w[0], 1, 0);
    double p2[3] = {0.5, -2, 0}; /* edge ab */
    CHECK_NEAR(triangle_closest_point(a, b, c, p2, w), 4, 1e-15);
    CHECK_NEAR(w[1], 0.5, 1e-15);
    double p3[3] = {1, 1, 0}; /* edge bc, at its midpoint */
    CHECK_NEAR(triangle_closest_point(a, b, c, p3, w), 0.5, 1e-15);
    CHECK_NEAR(w[1], 0.5, 1e-15); CHECK_NEAR(w[2], 0.5, 1e-15);
    double p4[3] = {0.25, 0.25, -3}; /* face interior */
    CHECK_NEAR(triangle_closest_point(a, b, c, p4, w), 9, 1e-15);
    CHECK_NEAR(w[0], 0.5, 1e-15);
    double d[3] = {2, 0, 0}, p5[3] = {1.5, 1, 0}; /* degenerate (collinear) triangle */
    CHECK_NEAR(triangle_closest_point(a, b, d, p5, w), 1, 1e-15);
}

/* Two sheets of a unit square 0.01 apart facing away from each other (the
 * lower one turned over): a point just above the lower sheet whose normal
 * looks down finds the lower sheet, whatever the upper one's distance; a
 * normal no face shares falls back to the plain closest point. */
static void test_facing(void)
{
    neuv_mesh *m = mesh_create(8, 4, 0);
    static const double p[8][3] = {{0, 0, 0.01}, {1, 0, 0.01}, {1, 1, 0.01}, {0, 1, 0.01},
                                   {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    static const int t[4][3] = {{0, 1, 2}, {0, 2, 3}, {4, 6, 5}, {4, 7, 6}}; /* up, up, down, down */
    memcpy(m->pos, p, sizeof p);
    memcpy(m->tri, t, sizeof t);
    bvh b;
    CHECK_INT(bvh_build(&b, m), NEUV_OK);
    double q[3] = {0.3, 0.6, 0.008}, up[3] = {0, 0, 1}, down[3] = {0, 0, -1}, side[3] = {1, 0, 0}, d2;
    int f = -1;
    bvh_closest_point(&b, q, &f, NULL, &d2);
    CHECK(f == 0 || f == 1);
    CHECK_NEAR(d2, 0.002 * 0.002, 1e-15);
    bvh_closest_point_facing(&b, q, down, &f, NULL, &d2);
    CHECK(f == 2 || f == 3);
    CHECK_NEAR(d2, 0.008 * 0.008, 1e-15);
    bvh_closest_point_facing(&b, q, up, &f, NULL, &d2);
    CHECK(f == 0 || f == 1);
    bvh_closest_point_facing(&b, q, side, &f, NULL, &d2);
    CHECK(f == 0 || f == 1);
    CHECK_NEAR(d2, 0.002 * 0.002, 1e-15);
    bvh_free(&b);
    mesh_free(m);
}

int main(void)
{
    test_triangle_regions();
    test_facing();
    neuv_mesh *ico = shape_icosphere(3, 1.0);
    neuv_mesh *torus = shape_torus(1.0, 0.3, 48, 24);
    CHECK(ico && torus);
    check_against_brute_force(ico, 0.5, 1500, 1);
    check_against_brute_force(torus, 0.4, 1500, 2);
    check_on_surface(ico, 2000, 3);
    check_on_surface(torus, 2000, 4);
    /* A one-face mesh is a valid tree; an empty one is refused. */
    neuv_mesh *one = mesh_create(3, 1, 0), *none = mesh_create(0, 0, 0);
    one->pos[3] = 1; one->pos[7] = 1; one->tri[1] = 1; one->tri[2] = 2;
    bvh b;
    CHECK_INT(bvh_build(&b, one), NEUV_OK);
    double p[3] = {0.2, 0.2, 1}, w[3], d2; int f;
    bvh_closest_point(&b, p, &f, w, &d2);
    CHECK_INT(f, 0); CHECK_NEAR(d2, 1, 1e-15);
    bvh_free(&b);
    CHECK_INT(bvh_build(&b, none), NEUV_ERR_INPUT);
    mesh_free(one); mesh_free(none); mesh_free(ico); mesh_free(torus);
    return check_report("test_bvh");
}
