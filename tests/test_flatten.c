/* Classic flattenings: LSCM and harmonic reproduce flat meshes up to a
 * similarity, refuse non-disks, and behave on a real disk (camelhead). */
#include <math.h>

#include "check.h"
#include "core/timer.h"
#include "flatten/harmonic.h"
#include "flatten/lscm.h"
#include "mesh/clean.h"
#include "mesh/shapes.h"
#include "metrics/uv_metrics.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Metrics of m with per-vertex UVs uv (#V by 2). */
static uv_metrics metrics_of(const neuv_mesh *m, const double *uv)
{
    uv_metrics mt;
    memset(&mt, 0, sizeof mt);
    mt.qce_mean = INFINITY;
    neuv_mesh *c = mesh_clone(m);
    if (!c) return mt;
    if (mesh_set_uv(c, c->nv, uv, c->tri) == NEUV_OK && uv_metrics_compute(c, &mt) != NEUV_OK) mt.qce_mean = INFINITY;
    mesh_free(c);
    return mt;
}

/* Largest relative deviation of |uv_i - uv_j| / |p_i - p_j| from its mean
 * over all edges: 0 for a similarity. */
static double similarity_defect(const neuv_mesh *m, const double *uv)
{
    double sum = 0, lo = INFINITY, hi = 0;
    int n = 0;
    for (int f = 0; f < m->nf; f++)
        for (int c = 0; c < 3; c++) {
            int a = m->tri[3 * f + c], b = m->tri[3 * f + (c + 1) % 3];
            const double *p = m->pos + 3 * a, *q = m->pos + 3 * b;
            double l3 = sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
            double l2 = hypot(uv[2 * a] - uv[2 * b], uv[2 * a + 1] - uv[2 * b + 1]);
            double r = l2 / l3;
            sum += r; n++;
            lo = fmin(lo, r); hi = fmax(hi, r);
        }
    double mean = sum / n;
    return fmax(hi - mean, mean - lo) / mean;
}

/* A flat disk of radius 1: ring k (k = 1..rings) holds 6k vertices at equal
 * angles, the centre one more; consecutive rings are zipped by angle. */
static neuv_mesh *flat_disk(int rings)
{
    int nv = 1 + 3 * rings * (rings + 1);
    int nf = 6 * rings * rings;
    neuv_mesh *m = mesh_create(nv, nf, 0);
    if (!m) return NULL;
    int f = 0, first_prev = 0, n_prev = 1;
    for (int k = 1; k <= rings; k++) {
        int first = 1 + 3 * (k - 1) * k, n = 6 * k;
        double r = (double)k / rings;
        for (int j = 0; j < n; j++) {
            double a = 2 * M_PI * j / n;
            m->pos[3 * (first + j)] = r * cos(a);
            m->pos[3 * (first + j) + 1] = r * sin(a);
        }
        /* Walk both rings counter-clockwise, always advancing the one whose
         * next vertex comes first in angle. */
        int i = 0, j = 0;
        while (j < n || (n_prev > 1 && i < n_prev)) {
            double ai = (double)(i + 1) / n_prev, aj = (double)(j + 1) / n;
            int a = first_prev + i % n_prev, b = first + j % n;
            if (j < n && (n_prev == 1 || i >= n_prev || aj <= ai)) {
                int c = first + (j + 1) % n;
                m->tri[3 * f] = a; m->tri[3 * f + 1] = b; m->tri[3 * f + 2] = c;
                j++;
            } else {
                int c = first_prev + (i + 1) % n_prev;
                m->tri[3 * f] = a; m->tri[3 * f + 1] = b; m->tri[3 * f + 2] = c;
                i++;
            }
            f++;
        }
        first_prev = first;
        n_prev = n;
    }
    m->nf = f;
    return m;
}

static void check_similarity(const char *what, const neuv_mesh *m, neuv_status (*method)(const neuv_mesh *, double *))
{
    double *uv = malloc(sizeof(double) * 2 * m->nv);
    neuv_status s = method(m, uv);
    CHECK_INT(s, NEUV_OK);
    if (s) { fprintf(stderr, "%s: %s\n", what, neuv_last_error()); free(uv); return; }
    uv_metrics mt = metrics_of(m, uv);
    double defect = similarity_defect(m, uv);
    printf("%s: qce_mean - 1 = %.3g, similarity defect %.3g, flipped %d\n", what, mt.qce_mean - 1, defect, mt.flipped);
    CHECK_NEAR(mt.qce_mean, 1.0, 1e-6);
    CHECK(defect < 1e-6);
    CHECK_INT(mt.flipped, 0);
    /* Orientation kept: every face counter-clockwise, like the flat input. */
    int ccw = 0;
    for (int f = 0; f < m->nf; f++) {
        const double *a = uv + 2 * m->tri[3 * f], *b = uv + 2 * m->tri[3 * f + 1], *c = uv + 2 * m->tri[3 * f + 2];
        ccw += (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]) > 0;
    }
    CHECK_INT(ccw, m->nf);
    free(uv);
}

static void test_flat(void)
{
    neuv_mesh *sq = shape_grid(20, 20, 1.0, 1.0, 0);
    neuv_mesh *rect = shape_grid(30, 8, 3.0, 0.6, 0);
    neuv_mesh *disk = flat_disk(12);
    CHECK(sq && rect && disk);
    if (!sq || !rect || !disk) return;
    check_similarity("lscm, square grid", sq, lscm);
    check_similarity("lscm, 3 x 0.6 grid", rect, lscm);
    check_similarity("lscm, flat disk", disk, lscm);
    /* The harmonic map puts the boundary on a circle, so only a flat disk
     * whose boundary is already a circle (equal spacing) can come back as a
     * similarity; the cotangent Laplacian's linear precision does the rest. */
    check_similarity("harmonic, flat disk", disk, harmonic);
    double *uv = malloc(sizeof(double) * 2 * sq->nv);
    CHECK_INT(harmonic(sq, uv), NEUV_OK);
    uv_metrics mt = metrics_of(sq, uv);
    double rmax = 0;
    for (int v = 0; v < sq->nv; v++) rmax = fmax(rmax, hypot(uv[2 * v], uv[2 * v + 1]));
    printf("harmonic, square grid (boundary on a circle): qce_mean %.4f, flipped %d, max radius %.12f\n",
           mt.qce_mean, mt.flipped, rmax);
    CHECK_INT(mt.flipped, 0);
    CHECK_NEAR(rmax, 1.0, 1e-12);
    CHECK(mt.qce_mean > 1.01); /* a square cannot go conformally onto a disk with this boundary map */
    free(uv);
    mesh_free(sq); mesh_free(rect); mesh_free(disk);
}

static void expect_not_disk(neuv_mesh *m, const char *expect)
{
    double *uv = malloc(sizeof(double) * 2 * m->nv);
    CHECK_INT(lscm(m, uv), NEUV_ERR_INPUT);
    printf("lscm refuses: %s\n", neuv_last_error());
    CHECK(strstr(neuv_last_error(), expect) != NULL);
    CHECK_INT(harmonic(m, uv), NEUV_ERR_INPUT);
    CHECK(strstr(neuv_last_error(), expect) != NULL);
    free(uv);
    mesh_free(m);
}

static void test_not_disk(void)
{
    expect_not_disk(shape_icosphere(2, 1.0), "not a disk: 1 component, closed, genus 0");
    expect_not_disk(shape_torus(1.0, 0.3, 16, 8), "not a disk: 1 component, closed, genus 1");
    expect_not_disk(shape_cylinder(1.0, 2.0, 16, 4), "not a disk: 1 component, 2 boundary loops, genus 0");
    /* Two grids side by side. */
    neuv_mesh *a = shape_grid(4, 4, 1.0, 1.0, 0);
    neuv_mesh *two = mesh_create(2 * a->nv, 2 * a->nf, 0);
    for (int v = 0; v < a->nv; v++)
        for (int k = 0; k < 3; k++) {
            two->pos[3 * v + k] = a->pos[3 * v + k];
            two->pos[3 * (a->nv + v) + k] = a->pos[3 * v + k] + (k == 0 ? 3.0 : 0.0);
        }
    for (int i = 0; i < 3 * a->nf; i++) { two->tri[i] = a->tri[i]; two->tri[3 * a->nf + i] = a->tri[i] + a->nv; }
    mesh_free(a);
    expect_not_disk(two, "not a disk: 2 components");
}

static void test_camelhead(void)
{
    const char *path = shared_path("meshes/camelhead.off");
    neuv_mesh *m = NULL;
    if (!path || neuv_mesh_load(path, NULL, &m) != NEUV_OK) {
        printf("SKIP camelhead: %s not available\n", path ? path : "../shared");
        return;
    }
    mesh_clean_report rep;
    CHECK_INT(mesh_clean(m, NULL, &rep), NEUV_OK);
    double *uv_l = malloc(sizeof(double) * 2 * m->nv), *uv_h = malloc(sizeof(double) * 2 * m->nv);
    double t0 = now_seconds();
    CHECK_INT(lscm(m, uv_l), NEUV_OK);
    double t_l = now_seconds() - t0;
    t0 = now_seconds();
    CHECK_INT(harmonic(m, uv_h), NEUV_OK);
    double t_h = now_seconds() - t0;
    uv_metrics ml = metrics_of(m, uv_l), mh = metrics_of(m, uv_h);
    printf("camelhead (%d vertices, %d faces): lscm qce_mean %.5f flipped %d (%.3f s); "
           "harmonic qce_mean %.5f flipped %d (%.3f s)\n",
           m->nv, m->nf, ml.qce_mean, ml.flipped, t_l, mh.qce_mean, mh.flipped, t_h);
    CHECK(ml.qce_mean < mh.qce_mean);
    CHECK_INT(ml.flipped, 0);
    CHECK_INT(mh.flipped, 0);
    CHECK_INT(ml.degenerate_uv, 0);
    CHECK_INT(mh.degenerate_uv, 0);
    free(uv_l); free(uv_h);
    mesh_free(m);
}

/* Anchored LSCM: an exact similarity image of a flat grid is its own
 * optimum (no conformal residual, no offset); a map with one interior
 * vertex dragged across its neighbours (folded faces) comes back without
 * folds and stays near the anchor away from that vertex, nearer as lambda
 * grows; a weight of zero is refused. */
static void test_anchored(void)
{
    neuv_mesh *g = shape_grid(12, 12, 1.0, 1.0, 0);
    CHECK(g != NULL);
    if (!g) return;
    int nv = g->nv;
    double *anchor = malloc(sizeof(double) * 2 * nv), *uv = malloc(sizeof(double) * 2 * nv);
    double c = cos(0.4), s = sin(0.4);
    for (int v = 0; v < nv; v++) {
        double x = g->pos[3 * v], y = g->pos[3 * v + 1];
        anchor[2 * v] = 2.5 * (c * x - s * y) + 3;
        anchor[2 * v + 1] = 2.5 * (s * x + c * y) - 1;
    }
    CHECK_INT(lscm_anchored(g, anchor, 1.0, uv), NEUV_OK);
    double err = 0;
    for (int i = 0; i < 2 * nv; i++) err = fmax(err, fabs(uv[i] - anchor[i]));
    printf("anchored LSCM, similarity anchor: max deviation %.2e\n", err);
    CHECK(err < 1e-9);

    /* Drag the vertex nearest the centre by 2.5 cells: its faces fold. */
    int mid = 0;
    for (int v = 0; v < nv; v++)
        if (hypot(g->pos[3 * v] - 0.5, g->pos[3 * v + 1] - 0.5) < hypot(g->pos[3 * mid] - 0.5, g->pos[3 * mid + 1] - 0.5)) mid = v;
    double cell = 2.5 / 12;
    anchor[2 * mid] += 2.5 * cell;
    uv_metrics folded = metrics_of(g, anchor);
    CHECK(folded.flipped > 0);
    double prev = INFINITY;
    for (double lambda = 0.01; lambda <= 10.0; lambda *= 10) {
        CHECK_INT(lscm_anchored(g, anchor, lambda, uv), NEUV_OK);
        uv_metrics mt = metrics_of(g, uv);
        double far = 0;
        int nfar = 0;
        for (int v = 0; v < nv; v++)
            if (hypot(g->pos[3 * v] - g->pos[3 * mid], g->pos[3 * v + 1] - g->pos[3 * mid + 1]) > 0.3) {
                far += hypot(uv[2 * v] - anchor[2 * v], uv[2 * v + 1] - anchor[2 * v + 1]);
                nfar++;
            }
        far /= nfar;
        printf("anchored LSCM, lambda %g: flipped %d (anchor %d), qce_mean %.4f, mean offset away from the drag %.2e cells\n",
               lambda, mt.flipped, folded.flipped, mt.qce_mean, far / cell);
        CHECK_INT(mt.flipped, 0);
        CHECK(far < 0.05 * cell);
        CHECK(far < prev + 1e-15 || lambda == 0.01);
        prev = far;
    }
    CHECK_INT(lscm_anchored(g, anchor, 0.0, uv), NEUV_ERR_INPUT);
    free(anchor); free(uv);
    mesh_free(g);
}

int main(void)
{
    test_flat();
    test_not_disk();
    test_camelhead();
    test_anchored();
    return check_report("test_flatten");
}
