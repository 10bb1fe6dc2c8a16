/* UV comparison: a map against itself, against its midpoint subdivision,
 * against a shifted copy, and against maps whose charts differ. */
#include <string.h>

#include "neuv/neuv.h"
#include "check.h"
#include "compare/uv_compare.h"
#include "mesh/shapes.h"
#include "remesh/jitter.h"
#include "remesh/subdivide.h"

/* A bumpy grid over [0,1]² whose UVs form two islands split at x = cut:
 * left faces keep (x, y), right faces are shifted by +dx in u. */
static neuv_mesh *two_chart_grid(int n, double cut, double dx)
{
    neuv_mesh *g = shape_grid(n, n, 1, 1, 0);
    for (int v = 0; v < g->nv; v++) g->pos[3 * v + 2] = 0.1 * sin(4 * g->pos[3 * v]) * cos(3 * g->pos[3 * v + 1]);
    double *uv = malloc(sizeof(double) * 6 * g->nf);
    int *tuv = malloc(sizeof(int) * 3 * g->nf);
    for (int f = 0; f < g->nf; f++) {
        double cx = 0;
        for (int k = 0; k < 3; k++) cx += g->pos[3 * g->tri[3 * f + k]] / 3;
        for (int k = 0; k < 3; k++) {
            int c = 3 * f + k, v = g->tri[c];
            tuv[c] = c;
            uv[2 * c] = g->pos[3 * v] + (cx > cut ? dx : 0);
            uv[2 * c + 1] = g->pos[3 * v + 1];
        }
    }
    /* Per-corner UVs: weld equal ones so the charts are the real islands. */
    int nuv = 0;
    for (int c = 0; c < 3 * g->nf; c++) {
        int found = -1;
        for (int d = 0; d < nuv && found < 0; d++)
            if (uv[2 * d] == uv[2 * c] && uv[2 * d + 1] == uv[2 * c + 1]) found = d;
        if (found < 0) { uv[2 * nuv] = uv[2 * c]; uv[2 * nuv + 1] = uv[2 * c + 1]; found = nuv++; }
        tuv[c] = found;
    }
    mesh_set_uv(g, nuv, uv, tuv);
    free(uv); free(tuv);
    return g;
}

/* Two sheets over [0,1]² 0.01 apart facing each other (the lower one up,
 * the upper one down), each its own UV island: the two sides of a thin part. */
static neuv_mesh *two_sheets(int n)
{
    neuv_mesh *g = shape_grid(n, n, 1, 1, 0);
    double nrm[3];
    mesh_face_normal(g, 0, nrm);
    neuv_mesh *m = mesh_create(2 * g->nv, 2 * g->nf, 0);
    double *uv = malloc(sizeof(double) * 4 * g->nv);
    int *tuv = malloc(sizeof(int) * 6 * g->nf);
    for (int v = 0; v < g->nv; v++)
        for (int s = 0; s < 2; s++) {
            double *p = m->pos + 3 * ((size_t)s * g->nv + v);
            p[0] = g->pos[3 * v]; p[1] = g->pos[3 * v + 1]; p[2] = s ? 0.01 : 0;
            uv[2 * (s * g->nv + v)] = p[0] + 2 * s;
            uv[2 * (s * g->nv + v) + 1] = p[1];
        }
    for (int f = 0; f < g->nf; f++)
        for (int s = 0; s < 2; s++) {
            int up = (nrm[2] > 0) != (s == 1); /* keep the corner order where this sheet faces its way */
            for (int k = 0; k < 3; k++) {
                int c = 3 * (s * g->nf + f) + k;
                m->tri[c] = s * g->nv + g->tri[3 * f + (up ? k : 2 - k)];
                tuv[c] = m->tri[c];
            }
        }
    mesh_set_uv(m, 2 * g->nv, uv, tuv);
    free(uv); free(tuv);
    mesh_free(g);
    return m;
}

int main(void)
{
    uv_compare_result r;
    neuv_mesh *a = two_chart_grid(16, 0.5, 0.5);

    /* Itself: zero distance (even at the seam corners), full agreement. */
    CHECK_INT(uv_compare(a, a, &r), NEUV_OK);
    CHECK(r.uv_max == 0);
    CHECK_NEAR(r.chart_agreement, 1, 0);
    CHECK_NEAR(r.chart_agreement_faces, 1, 0);
    CHECK_INT(r.charts_a, 2); CHECK_INT(r.charts_b, 2);
    CHECK_INT(r.faces_a, a->nf);
    CHECK_INT(r.vertices_compared, 17 * 17 + 17); /* the seam column counts once per side */

    /* Its midpoint subdivision, UVs interpolated. */
    neuv_mesh *s = NULL;
    CHECK_INT(mesh_subdivide(a, 1, SUBDIVIDE_MIDPOINT, &s), NEUV_OK);
    CHECK_INT(uv_compare(a, s, &r), NEUV_OK);
    CHECK(r.uv_max < 1e-9);
    CHECK_NEAR(r.chart_agreement, 1, 0);
    CHECK_INT(r.faces_b, 4 * a->nf);
    /* And the other way round. */
    CHECK_INT(uv_compare(s, a, &r), NEUV_OK);
    CHECK(r.uv_max < 1e-9);

    /* Its jittered subdivision (vertices moved within the surface). */
    CHECK_INT(mesh_jitter(s, 5, NULL, NULL), NEUV_OK);
    CHECK_INT(uv_compare(a, s, &r), NEUV_OK);
    CHECK(r.uv_max < 1e-9);
    CHECK(r.chart_agreement > 0.999);
    mesh_free(s);

    /* UVs shifted by 0.01 in u: every corner is 0.01 away. */
    neuv_mesh *b = mesh_clone(a);
    for (int u = 0; u < b->nuv; u++) b->uv[2 * u] += 0.01;
    CHECK_INT(uv_compare(a, b, &r), NEUV_OK);
    CHECK_NEAR(r.uv_mean, 0.01, 1e-12);
    CHECK_NEAR(r.uv_p95, 0.01, 1e-12);
    CHECK_NEAR(r.uv_max, 0.01, 1e-12);
    CHECK_NEAR(r.chart_agreement, 1, 0);
    mesh_free(b);

    /* The right island placed elsewhere in the atlas (shifted by 0.3
     * instead of 0.5): the charts still agree, its corners are 0.2 away. */
    b = two_chart_grid(16, 0.5, 0.3);
    CHECK_INT(uv_compare(a, b, &r), NEUV_OK);
    CHECK_NEAR(r.chart_agreement, 1, 0);
    CHECK_NEAR(r.uv_max, 0.2, 1e-12);
    /* 17*9 right-side corners of 17*18 are shifted. */
    CHECK_NEAR(r.uv_mean, 0.2 * (17.0 * 9) / (17 * 18), 1e-12);
    mesh_free(b);

    /* Charts split at x = 0.25 instead of 0.5: B's right chart [0.25, 1]
     * matches A's right chart (two thirds of it), so the strip [0.25, 0.5]
     * disagrees: a quarter of the area (the surface is nearly flat). */
    b = two_chart_grid(16, 0.25, 0.5);
    CHECK_INT(uv_compare(a, b, &r), NEUV_OK);
    CHECK_NEAR(r.chart_agreement_faces, 0.75, 1e-12);
    CHECK_NEAR(r.chart_agreement, 0.75, 0.02);
    mesh_free(b);

    /* A triangulation whose edges miss A's seam (11 cells: the seam at
     * x = 0.5 crosses a column of faces, each taken by the side of its
     * centroid) with the same map: corners past the seam are compared with
     * their chart's map extended (exact on a flat grid), while the plain
     * nearest-point measure sees them half an atlas away (the island shift). */
    neuv_mesh *fa = two_chart_grid(16, 0.5, 0.5), *fb = two_chart_grid(11, 0.5, 0.5);
    for (int v = 0; v < fa->nv; v++) fa->pos[3 * v + 2] = 0;
    for (int v = 0; v < fb->nv; v++) fb->pos[3 * v + 2] = 0;
    CHECK_INT(uv_compare(fa, fb, &r), NEUV_OK);
    CHECK(r.uv_max < 1e-12);
    /* The seam column's cells are cut into a left and a right triangle:
     * the corners at x = 6/11 of left faces and at x = 5/11 of right faces
     * (up to 12 each of about 170) lie past their chart's seam. */
    CHECK(r.across_seam > 0.1 && r.across_seam < 0.15);
    CHECK_NEAR(r.nearest_max, 0.5, 1e-12);
    CHECK(r.nearest_mean > 10 * r.uv_mean + 0.01);
    CHECK_NEAR(r.chart_agreement, 1, 0.05);
    /* Bumpy: the extension is the closest face's plane map, exact to the
     * surface's curvature over a cell (a few thousandths here). */
    mesh_free(fb);
    fb = two_chart_grid(11, 0.5, 0.5);
    CHECK_INT(uv_compare(a, fb, &r), NEUV_OK);
    CHECK(r.uv_max < 0.01);
    CHECK(r.uv_mean < 1e-3);
    CHECK(r.across_seam > 0.02);
    mesh_free(fa); mesh_free(fb);

    /* The public call welds identical positions first: a copy whose every
     * face has vertices of its own (a file that repeats vertices at its
     * patches' borders) still has the two charts, and the same map. */
    {
        neuv_mesh *split = mesh_create(3 * a->nf, a->nf, 0);
        for (int c = 0; c < 3 * a->nf; c++) {
            memcpy(split->pos + 3 * c, a->pos + 3 * a->tri[c], sizeof(double) * 3);
            split->tri[c] = c;
        }
        CHECK_INT(mesh_set_uv(split, a->nuv, a->uv, a->tri_uv), NEUV_OK);
        neuv_uv_comparison cmp;
        CHECK_INT(neuv_compare_uvs(a, split, NULL, &cmp), NEUV_OK);
        CHECK_INT(cmp.charts_b, 2);
        CHECK_NEAR(cmp.chart_agreement, 1, 0);
        CHECK(cmp.uv_max == 0);
        CHECK_INT(cmp.vertices_compared, 17 * 17 + 17);
        CHECK_INT(neuv_compare_uvs(split, a, NULL, &cmp), NEUV_OK);
        CHECK_INT(cmp.charts_a, 2);
        CHECK_NEAR(cmp.chart_agreement, 1, 0);
        CHECK(cmp.uv_max == 0);
        CHECK_INT(split->nv, 3 * a->nf); /* the caller's mesh is not welded */
        mesh_free(split);
    }

    /* A sheet facing up, tilted from 0.001 to 0.009 above the lower of two
     * facing sheets 0.01 apart, with the lower sheet's map: past x = 0.5 its
     * plain closest point is on the upper sheet (the other island), while
     * on the faces facing its way every face finds the lower one. */
    {
        neuv_mesh *ts = two_sheets(12), *tilt = shape_grid(12, 12, 1, 1, 1);
        double nrm[3];
        mesh_face_normal(tilt, 0, nrm);
        if (nrm[2] < 0)
            for (int f = 0; f < tilt->nf; f++) {
                int t = tilt->tri[3 * f + 1]; tilt->tri[3 * f + 1] = tilt->tri[3 * f + 2]; tilt->tri[3 * f + 2] = t;
                t = tilt->tri_uv[3 * f + 1]; tilt->tri_uv[3 * f + 1] = tilt->tri_uv[3 * f + 2]; tilt->tri_uv[3 * f + 2] = t;
            }
        for (int v = 0; v < tilt->nv; v++) tilt->pos[3 * v + 2] = 0.001 + 0.008 * tilt->pos[3 * v];
        CHECK_INT(uv_compare(ts, tilt, &r), NEUV_OK);
        CHECK_INT(r.charts_a, 2);
        CHECK_INT(r.charts_b, 1);
        CHECK_NEAR(r.chart_agreement_facing, 1, 0);
        CHECK_NEAR(r.chart_agreement, 0.5, 0.05);
        mesh_free(ts); mesh_free(tilt);
    }

    /* Bad inputs. */
    neuv_mesh *plain = shape_grid(2, 2, 1, 1, 0);
    CHECK_INT(uv_compare(a, plain, &r), NEUV_ERR_INPUT);
    CHECK_INT(uv_compare(plain, a, &r), NEUV_ERR_INPUT);
    mesh_free(plain);
    mesh_free(a);
    return check_report("test_compare");
}
