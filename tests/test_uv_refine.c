/* Vertex refinement: a sheared map of a flat patch is refined to (nearly) the
 * conformal identity, the accept test holds a chart at its last accepted map,
 * the result is the same for the same input, charts refined together with
 * the losses scaled by their count end as each does alone, and bad options
 * are refused. */
#include "check.h"

#include "flatten/uv_refine.h"
#include "mesh/shapes.h"

/* Area-weighted mean of s1/s2 over the faces (3D triangles in the xy plane). */
static double qce_mean(const neuv_mesh *m, const double *corner_uv)
{
    double sum = 0, wsum = 0;
    for (int f = 0; f < m->nf; f++) {
        const int *t = m->tri + 3 * f;
        const double *p0 = m->pos + 3 * t[0], *p1 = m->pos + 3 * t[1], *p2 = m->pos + 3 * t[2];
        const double *u = corner_uv + 6 * f;
        double a[4] = {p1[0] - p0[0], p2[0] - p0[0], p1[1] - p0[1], p2[1] - p0[1]}; /* columns: edges */
        double b[4] = {u[2] - u[0], u[4] - u[0], u[3] - u[1], u[5] - u[1]};
        double det = a[0] * a[3] - a[1] * a[2];
        double inv[4] = {a[3] / det, -a[1] / det, -a[2] / det, a[0] / det};
        double J[4] = {b[0] * inv[0] + b[1] * inv[2], b[0] * inv[1] + b[1] * inv[3],
                       b[2] * inv[0] + b[3] * inv[2], b[2] * inv[1] + b[3] * inv[3]};
        double fro = J[0] * J[0] + J[1] * J[1] + J[2] * J[2] + J[3] * J[3], dj = fabs(J[0] * J[3] - J[1] * J[2]);
        double disc = sqrt(fmax(fro * fro / 4 - dj * dj, 0));
        double s1 = sqrt(fro / 2 + disc), s2 = sqrt(fmax(fro / 2 - disc, 1e-300));
        sum += fabs(det) / 2 * s1 / s2;
        wsum += fabs(det) / 2;
    }
    return sum / wsum;
}

static int flipped(const neuv_mesh *m, const double *corner_uv)
{
    int n = 0;
    for (int f = 0; f < m->nf; f++) {
        const double *u = corner_uv + 6 * f;
        if ((u[2] - u[0]) * (u[5] - u[1]) - (u[3] - u[1]) * (u[4] - u[0]) <= 0) n++;
    }
    return n;
}

/* u = x + 0.3 y², v = y: injective (det J = 1) but not conformal. */
static void sheared(const neuv_mesh *m, double *corner_uv)
{
    for (int f = 0; f < m->nf; f++)
        for (int k = 0; k < 3; k++) {
            const double *p = m->pos + 3 * m->tri[3 * f + k];
            corner_uv[6 * f + 2 * k] = p[0] + 0.3 * p[1] * p[1];
            corner_uv[6 * f + 2 * k + 1] = p[1];
        }
}

static int rejects_all(void *user, int chart, const double *corner_uv)
{
    (void)corner_uv;
    int *calls = user;
    calls[chart]++;
    return 0;
}

int main(void)
{
    neuv_mesh *m = shape_grid(12, 12, 1.0, 1.0, 0);
    int nf = m->nf;
    int *chart = calloc((size_t)nf, sizeof(int));
    double *uv = malloc(sizeof(double) * 6 * nf), *uv2 = malloc(sizeof(double) * 6 * nf);
    uv_refine_options o;
    uv_refine_default_options(&o);

    /* One chart: the shear is refined away. */
    sheared(m, uv);
    double q0 = qce_mean(m, uv);
    CHECK(q0 > 1.15);
    uv_refine_report rep;
    CHECK_INT(uv_refine(m, chart, 1, &o, uv, &rep), NEUV_OK);
    double q1 = qce_mean(m, uv);
    printf("sheared grid: qce_mean %.4f -> %.4f in %d steps (loss %.4g -> %.4g)\n", q0, q1, rep.iters,
           rep.loss_start, rep.loss_end);
    CHECK_INT(rep.iters, o.iters);
    CHECK(q1 < 1.02);
    CHECK(rep.loss_end < 0.05 * rep.loss_start);
    CHECK_INT(flipped(m, uv), 0);
    CHECK_INT(rep.charts_reverted, 0);

    /* Same input, same bytes. */
    sheared(m, uv2);
    CHECK_INT(uv_refine(m, chart, 1, &o, uv2, NULL), NEUV_OK);
    CHECK(memcmp(uv, uv2, sizeof(double) * 6 * nf) == 0);

    /* Two charts (left and right halves); an accept test that refuses
     * everything keeps both at their starting map (no boundary meets itself,
     * so each stops at its first test). */
    for (int f = 0; f < nf; f++) {
        const int *t = m->tri + 3 * f;
        double cx = (m->pos[3 * t[0]] + m->pos[3 * t[1]] + m->pos[3 * t[2]]) / 3;
        chart[f] = cx > 0.5;
    }
    int calls[2] = {0, 0};
    o.accept = rejects_all;
    o.accept_user = calls;
    o.check_every = 25;
    sheared(m, uv);
    CHECK_INT(uv_refine(m, chart, 2, &o, uv, &rep), NEUV_OK);
    sheared(m, uv2);
    double moved = 0; /* the map goes through float32, the networks' precision */
    for (int i = 0; i < 6 * nf; i++) moved = fmax(moved, fabs(uv[i] - uv2[i]));
    CHECK(moved < 1e-6);
    CHECK_INT(calls[0], 1);
    CHECK_INT(calls[1], 1);
    CHECK_INT(rep.charts_stopped, 2);
    CHECK_INT(rep.charts_reverted, 0);
    CHECK(rep.iters <= 25);

    /* Without a test both halves are refined, each in its own frame. */
    o.accept = NULL;
    CHECK_INT(uv_refine(m, chart, 2, &o, uv, &rep), NEUV_OK);
    double q2 = qce_mean(m, uv);
    printf("two charts: qce_mean %.4f -> %.4f\n", q0, q2);
    CHECK(q2 < 1.02);
    CHECK_INT(flipped(m, uv), 0);

    /* Charts refined together (as unwrap does with its smallest pieces),
     * the losses scaled by their count: two copies of a small sheared grid
     * side by side end where one ends alone. */
    {
        neuv_mesh *g = shape_grid(3, 3, 1.0, 1.0, 0), *two = mesh_create(2 * g->nv, 2 * g->nf, 0);
        int gf = g->nf, *gchart = calloc((size_t)gf, sizeof(int)), *tchart = malloc(sizeof(int) * 2 * (size_t)gf);
        double *alone = malloc(sizeof(double) * 6 * gf), *both = malloc(sizeof(double) * 12 * gf);
        for (int k = 0; k < 2; k++) {
            memcpy(two->pos + 3 * (size_t)k * g->nv, g->pos, sizeof(double) * 3 * (size_t)g->nv);
            for (int i = 0; i < 3 * gf; i++) two->tri[3 * (size_t)k * gf + i] = g->tri[i] + k * g->nv;
            for (int f = 0; f < gf; f++) tchart[k * gf + f] = k;
        }
        uv_refine_options ot;
        uv_refine_default_options(&ot);
        sheared(g, alone);
        memcpy(both, alone, sizeof(double) * 6 * gf);
        memcpy(both + 6 * gf, alone, sizeof(double) * 6 * gf);
        CHECK_INT(uv_refine(g, gchart, 1, &ot, alone, NULL), NEUV_OK);
        ot.lambda_iso *= 2; ot.lambda_angle *= 2; ot.lambda_conformal *= 2; ot.lambda_area *= 2; ot.lambda_fold *= 2;
        CHECK_INT(uv_refine(two, tchart, 2, &ot, both, NULL), NEUV_OK);
        double gap = 0;
        for (int i = 0; i < 6 * gf; i++) gap = fmax(gap, fmax(fabs(both[i] - alone[i]), fabs(both[6 * gf + i] - alone[i])));
        printf("two charts refined together vs one alone: max |uv difference| %.3g\n", gap);
        /* The same map: each gradient is the same number (scaling by 2 is
         * exact); unscaled, Adam's ε moves it by 3e-7. */
        CHECK(gap < 1e-12);
        free(gchart); free(tchart); free(alone); free(both);
        mesh_free(g); mesh_free(two);
    }

    /* Bad input. */
    o.lr = 0;
    CHECK_INT(uv_refine(m, chart, 2, &o, uv, NULL), NEUV_ERR_INPUT);
    uv_refine_default_options(&o);
    chart[0] = 5;
    CHECK_INT(uv_refine(m, chart, 2, &o, uv, NULL), NEUV_ERR_INPUT);
    o.iters = 0; /* off: nothing checked, nothing changed */
    chart[0] = 0;
    sheared(m, uv);
    CHECK_INT(uv_refine(m, chart, 2, &o, uv, NULL), NEUV_OK);
    sheared(m, uv2);
    CHECK(memcmp(uv, uv2, sizeof(double) * 6 * nf) == 0);

    free(chart); free(uv); free(uv2);
    mesh_free(m);
    return check_report("test_uv_refine");
}
