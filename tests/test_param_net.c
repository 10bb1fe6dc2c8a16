/* The parameterization networks: a flat grid chart and a curved cap trained
 * for a bounded number of steps reach near-conformal maps with no flipped
 * face and a small cycle error; the same seed and threads give the same
 * bytes; the kept model reapplies to the same points, maps charts given anew
 * (param_net_infer) exactly as trained, and fine-tuning starts from it; bad
 * input is refused. */
#include "check.h"

#include "core/rng.h"
#include "metrics/uv_metrics.h"
#include "mesh/shapes.h"
#include "models/param_net.h"
#include "nn/nn.h"

#ifdef __SANITIZE_ADDRESS__
enum { ITERS = 60, GRID = 8 };
#define QCE_GRID 1.6 /* measured 1.138 */
#define QCE_CAP 5.0 /* measured 1.91 */
#define CYCLE_GRID 0.2
#define CYCLE_CAP 0.3
#define QCE_TWO 1.3 /* measured 1.068 */
#define CYCLE_TWO 0.1 /* measured 0.020 */
#else
enum { ITERS = 400, GRID = 16 };
/* Measured (Release, 1 thread, 400 iterations, fast preset): grid 1.0125, hemisphere
 * 1.107 (LSCM on the same hemisphere: 1.079); before the warm start and the
 * output-layer solve 1.037 and 1.125, which these bounds refuse. */
#define QCE_GRID 1.025 /* measured 1.0125 */
#define QCE_CAP 1.118 /* measured 1.107 (1.125 with Adam alone, 1.796 before the barrier) */
#define CYCLE_GRID 0.02 /* measured 0.0040 */
#define CYCLE_CAP 0.05  /* measured 0.0053 */
#define QCE_TWO 1.06  /* measured 1.029 */
#define CYCLE_TWO 0.04 /* measured 0.018 */
#endif

/* Upper half (z > 0) of a 24 by 12 latitude-longitude unit sphere: a curved disk. */
static neuv_mesh *half_sphere(void)
{
    neuv_mesh *s = shape_uv_sphere(24, 12, 1.0);
    int *keep = calloc((size_t)s->nv, sizeof(int)), nv = 0, nf = 0;
    char *in = calloc((size_t)s->nf, 1);
    for (int f = 0; f < s->nf; f++) {
        double z = 0;
        for (int k = 0; k < 3; k++) z += s->pos[3 * s->tri[3 * f + k] + 2];
        if (z > 0) { in[f] = 1; nf++; for (int k = 0; k < 3; k++) keep[s->tri[3 * f + k]] = 1; }
    }
    for (int v = 0; v < s->nv; v++) keep[v] = keep[v] ? nv++ : -1;
    neuv_mesh *c = mesh_create(nv, nf, 0);
    for (int v = 0; v < s->nv; v++)
        if (keep[v] >= 0) memcpy(c->pos + 3 * keep[v], s->pos + 3 * v, 3 * sizeof(double));
    nf = 0;
    for (int f = 0; f < s->nf; f++)
        if (in[f]) { for (int k = 0; k < 3; k++) c->tri[3 * nf + k] = keep[s->tri[3 * f + k]]; nf++; }
    free(keep); free(in); mesh_free(s);
    return c;
}

static int corner_metrics(const neuv_mesh *m, const double *corner_uv, uv_metrics *mt)
{
    neuv_mesh *c = mesh_clone(m);
    int *tri_uv = malloc((size_t)m->nf * 3 * sizeof(int));
    if (!c || !tri_uv) return -1;
    for (int i = 0; i < 3 * m->nf; i++) tri_uv[i] = i;
    int ok = mesh_set_uv(c, 3 * m->nf, corner_uv, tri_uv) == NEUV_OK && uv_metrics_compute(c, mt) == NEUV_OK;
    free(tri_uv);
    mesh_free(c);
    return ok ? 0 : -1;
}

static void train(const neuv_mesh *m, const char *name, param_net_options *o, uv_metrics *mt, param_net_report *rep,
                  double *uv)
{
    int *chart = calloc((size_t)m->nf, sizeof(int));
    CHECK_INT(param_net_flatten(m, chart, 1, NULL, 0, o, uv, rep), NEUV_OK);
    CHECK(corner_metrics(m, uv, mt) == 0);
    printf("%s: %d iters, qce_mean %.4f, ase_abs %.4f, flipped %d, cycle_rms %.4f, loss %.5f, %.2f s\n", name,
           rep->iters, mt->qce_mean, mt->ase_abs_mean, mt->flipped, rep->cycle_rms, rep->loss, rep->seconds);
    free(chart);
}

int main(void)
{
    nn_set_threads(1);
    param_net_options o;
    param_net_default_options(&o, PARAM_PRESET_FAST);
    o.iters = ITERS;
    o.min_iters = ITERS;

    neuv_mesh *grid = shape_grid(GRID, GRID, 1.0, 1.0, 0);
    double *uv = malloc((size_t)grid->nf * 6 * sizeof(double));
    uv_metrics mt;
    param_net_report rep;
    train(grid, "flat grid", &o, &mt, &rep, uv);
    CHECK_INT(rep.iters, ITERS);
    /* A grid of fewer vertices than face points draws one face point per
     * vertex, and never fewer than an eighth of the 1024 (GRID is smaller
     * under the sanitizers: 81 vertices, below that floor). */
    CHECK(grid->nv < 1024);
    CHECK_INT(rep.face_points, grid->nv > 128 ? grid->nv : 128);
#ifndef __SANITIZE_ADDRESS__
    CHECK_INT(mt.flipped, 0);
#endif
    CHECK(mt.qce_mean < QCE_GRID);
    CHECK(rep.cycle_rms < CYCLE_GRID);

    /* Determinism: same seed and threads, same bytes; the kept model reproduces the UVs. */
    param_net_options d = o;
    d.iters = d.min_iters = 30;
    d.keep_model = 1;
    double *uv1 = malloc((size_t)grid->nf * 6 * sizeof(double)), *uv2 = malloc((size_t)grid->nf * 6 * sizeof(double));
    param_net_report r1, r2;
    int *chart = calloc((size_t)grid->nf, sizeof(int));
    CHECK_INT(param_net_flatten(grid, chart, 1, NULL, 0, &d, uv1, &r1), NEUV_OK);
    CHECK_INT(param_net_flatten(grid, chart, 1, NULL, 0, &d, uv2, &r2), NEUV_OK);
    CHECK(memcmp(uv1, uv2, (size_t)grid->nf * 6 * sizeof(double)) == 0);
    /* Face points: never below an eighth of the option's count, never above it. */
    {
        param_net_options fp = d;
        fp.iters = fp.min_iters = 1;
        fp.keep_model = 0;
        param_net_report rf;
        fp.face_points = 4096;
        CHECK_INT(param_net_flatten(grid, chart, 1, NULL, 0, &fp, uv2, &rf), NEUV_OK);
        CHECK_INT(rf.face_points, 512);
        fp.face_points = 100; /* fewer than the grid's vertices (289), or more (81) */
        CHECK_INT(param_net_flatten(grid, chart, 1, NULL, 0, &fp, uv2, &rf), NEUV_OK);
        CHECK_INT(rf.face_points, grid->nv < 100 ? grid->nv : 100);
    }
    CHECK(r1.model != NULL);
    if (r1.model) {
        double p[3], q[2], back[3];
        int v = grid->tri[3 * 7 + 1];
        memcpy(p, grid->pos + 3 * v, sizeof p);
        CHECK_INT(param_net_apply(r1.model, 0, p, 1, q), NEUV_OK);
        /* float32 inference on 1 row vs 289: the BLAS kernels may round differently */
        CHECK_NEAR(q[0], uv1[6 * 7 + 2], 1e-6);
        CHECK_NEAR(q[1], uv1[6 * 7 + 3], 1e-6);
        CHECK_INT(param_net_apply_inverse(r1.model, 0, q, 1, back), NEUV_OK);
        CHECK(fabs(back[0] - p[0]) + fabs(back[1] - p[1]) + fabs(back[2] - p[2]) < 0.5);
        CHECK_INT(param_net_apply(r1.model, 1, p, 1, q), NEUV_ERR_INPUT);

        /* A head solved on a piece (the grid's left half), kept as a chart of
         * its own (what the repair of a folded chart does): the model then
         * gives that piece's map by plain inference, the parent's map is
         * unchanged, and a bad parent is refused. */
        CHECK(r1.model->heads != NULL && r1.model->uv_gain != NULL);
        int hs = param_head_size(&r1.model->f), n = grid->nv, nf = 0;
        neuv_mesh *half = mesh_create(n, grid->nf, 0);
        memcpy(half->pos, grid->pos, sizeof(double) * 3 * (size_t)n);
        for (int f = 0; f < grid->nf; f++) {
            const int *t = grid->tri + 3 * f;
            if (grid->pos[3 * t[0]] + grid->pos[3 * t[1]] + grid->pos[3 * t[2]] < 1.5) {
                memcpy(half->tri + 3 * nf, t, sizeof(int) * 3);
                nf++;
            }
        }
        half->nf = nf;
        float *head = malloc(sizeof(float) * (size_t)hs);
        double gain = 0, *su = malloc(sizeof(double) * 2 * (size_t)n), *sa = malloc(sizeof(double) * 2 * (size_t)n);
        double *before = malloc(sizeof(double) * 2 * (size_t)n), *after = malloc(sizeof(double) * 2 * (size_t)n);
        CHECK_INT(param_net_solve_head(r1.model, 0, half, su, head, &gain), NEUV_OK);
        CHECK_INT(param_net_apply_solved(r1.model, 0, half, sa, NULL, NULL, NULL), NEUV_OK);
        /* The kept head is also judged between the vertices (half the
         * energy on the faces split in four); the map for this mesh alone
         * is not: two different solves of the same start (on this 8x8 grid
         * and a network trained for few steps, 0.33 of the span apart). */
        double apart = 0, extent = 0;
        for (int i = 0; i < 2 * n; i++) {
            apart = fmax(apart, fabs(su[i] - sa[i]));
            extent = fmax(extent, fabs(su[i]));
        }
        printf("kept head against this-mesh head: %.3g of the span\n", apart / extent);
        CHECK(apart > 1e-3 * extent);
        CHECK(gain > 0);
        CHECK_INT(param_net_apply(r1.model, 0, grid->pos, n, before), NEUV_OK);
        int id = -1;
        CHECK_INT(param_net_add_chart(r1.model, 5, head, gain, &id), NEUV_ERR_INPUT);
        CHECK_INT(r1.model->n_charts, 1);
        CHECK_INT(param_net_add_chart(r1.model, 0, head, gain, &id), NEUV_OK);
        CHECK_INT(id, 1);
        CHECK_INT(r1.model->n_charts, 2);
        CHECK_INT(param_net_apply(r1.model, 1, grid->pos, n, sa), NEUV_OK);
        CHECK_INT(param_net_apply(r1.model, 0, grid->pos, n, after), NEUV_OK);
        double worst = 0, span = 0, moved = 0;
        for (int i = 0; i < 2 * n; i++) {
            worst = fmax(worst, fabs(sa[i] - su[i]));
            span = fmax(span, fabs(su[i]));
            moved = fmax(moved, fabs(su[i] - before[i]));
        }
        CHECK(worst <= 1e-5 * span); /* float32 inference, rows batched differently */
        CHECK(moved > 1e-3 * span);   /* the solved head is not the learnt one */
        CHECK(memcmp(before, after, sizeof(double) * 2 * (size_t)n) == 0);
        free(head); free(su); free(sa); free(before); free(after);
        mesh_free(half);
    }
    param_net_model_free(r1.model);
    param_net_model_free(r2.model);
    /* Bad input: a chart id out of range, no charts. */
    chart[3] = 1;
    CHECK_INT(param_net_flatten(grid, chart, 1, NULL, 0, &d, uv1, NULL), NEUV_ERR_INPUT);
    CHECK_INT(param_net_flatten(grid, chart, 0, NULL, 0, &d, uv1, NULL), NEUV_ERR_INPUT);
    free(chart); free(uv1); free(uv2);
    free(uv);
    mesh_free(grid);

    /* DiffusionNet-sized features (O(20), like spot's) on two charts (the left
     * and right halves of the grid): ψ is standardized, so the position still
     * drives the map. Unstandardized, such features saturated the output tanh
     * and collapsed every chart to a point (qce_mean NaN, L_cycle 1.1). */
    {
        neuv_mesh *g2 = shape_grid(GRID, GRID, 1.0, 1.0, 0);
        int *ch = malloc(sizeof(int) * (size_t)g2->nf);
        for (int f = 0; f < g2->nf; f++) {
            double cx = 0;
            for (int k = 0; k < 3; k++) cx += g2->pos[3 * g2->tri[3 * f + k]] / 3;
            ch[f] = cx > 0.5;
        }
        enum { FD = 16 };
        float *feat = malloc(sizeof(float) * FD * (size_t)g2->nv);
        for (int v = 0; v < g2->nv; v++)
            for (int k = 0; k < FD; k++)
                feat[FD * v + k] = (float)(20.0 + 5.0 * sin((k + 1) * g2->pos[3 * v] + k * g2->pos[3 * v + 1]));
        double *uvf = malloc(sizeof(double) * 6 * (size_t)g2->nf);
        param_net_options ok = o;
        ok.keep_model = 1;
        /* The category path: charts the model never saw use the shared output
         * layer, so train without per-chart heads to compare with it. */
        ok.chart_heads = 0;
        CHECK_INT(param_net_flatten(g2, ch, 2, feat, FD, &ok, uvf, &rep), NEUV_OK);
        CHECK(corner_metrics(g2, uvf, &mt) == 0);
        printf("two charts, large features: qce_mean %.4f, flipped %d, cycle_rms %.4f\n", mt.qce_mean, mt.flipped,
               rep.cycle_rms);
        CHECK(isfinite(mt.qce_mean) && mt.qce_mean < QCE_TWO);
        CHECK(rep.cycle_rms < CYCLE_TWO);
#ifndef __SANITIZE_ADDRESS__
        CHECK_INT(mt.flipped, 0);
#endif
        param_net_model *model = rep.model;
        CHECK(model && model->psi_shift && model->psi_mul);

        /* Inference on charts given anew (a category model's path): the chart
         * frames, ψ with the stored standardization and MLP_f reproduce the
         * trained map (same rows, so the same float products). */
        double *uvi = malloc(sizeof(double) * 6 * (size_t)g2->nf);
        param_net_report ir;
        CHECK_INT(param_net_infer(model, g2, ch, 2, feat, FD, 0, uvi, &ir, NULL), NEUV_OK);
        double worst = 0;
        for (long k = 0; k < 6L * g2->nf; k++) worst = fmax(worst, fabs(uvi[k] - uvf[k]));
        printf("inference on the training charts: largest UV difference %.3g\n", worst);
        CHECK(worst < 1e-6);
        CHECK_INT(ir.flipped, 0);
        /* With a head per chart solved on these charts (what a category model
         * does on a shape it never saw): unfolded, and no more distorted than
         * the shared layer it starts from. */
        uv_metrics mh;
        param_net_model *shape = NULL;
        CHECK_INT(param_net_infer(model, g2, ch, 2, feat, FD, 1, uvi, &ir, &shape), NEUV_OK);
        CHECK(corner_metrics(g2, uvi, &mh) == 0);
        printf("inference with heads solved on the charts: qce_mean %.4f (shared layer %.4f), flipped %d\n",
               mh.qce_mean, mt.qce_mean, ir.flipped);
        CHECK_INT(ir.flipped, 0);
        CHECK(mh.qce_mean <= mt.qce_mean + 1e-9);
        /* The shape model of these charts gives their inferred map again by
         * plain inference at a corner of each chart. */
        CHECK(shape != NULL && shape->borrowed && shape->n_charts == 2 && shape->heads != NULL);
        for (int f = 0; shape && f < g2->nf; f += g2->nf - 1) {
            double q[2];
            const double *pt = g2->pos + 3 * g2->tri[3 * f];
            CHECK_INT(param_net_apply(shape, ch[f], pt, 1, q), NEUV_OK);
            CHECK_NEAR(q[0], uvi[6 * f], 1e-5);
            CHECK_NEAR(q[1], uvi[6 * f + 1], 1e-5);
        }
        param_net_model_free(shape);
        CHECK_INT(param_net_infer(model, g2, ch, 2, feat, FD, 0, uvi, &ir, &shape), NEUV_OK);
        CHECK(shape == NULL); /* the shared layer: no heads of these charts to keep */
        /* Features of another size, or a model without the standardization: refused. */
        CHECK_INT(param_net_infer(model, g2, ch, 2, feat, FD / 2, 1, uvi, NULL, NULL), NEUV_ERR_INPUT);
        double *shift = model->psi_shift;
        model->psi_shift = NULL;
        CHECK_INT(param_net_infer(model, g2, ch, 2, feat, FD, 1, uvi, NULL, NULL), NEUV_ERR_INPUT);
        model->psi_shift = shift;

        /* Fine-tuning starts from the model: one step's loss is the trained
         * loss, far below a fresh network's first step. */
        param_net_options ft = o;
        ft.iters = ft.min_iters = 1;
        param_net_report fresh, tuned;
        CHECK_INT(param_net_flatten(g2, ch, 2, feat, FD, &ft, uvi, &fresh), NEUV_OK);
        ft.init = model;
        CHECK_INT(param_net_flatten(g2, ch, 2, feat, FD, &ft, uvi, &tuned), NEUV_OK);
        printf("one step: fresh loss %.5f, from the model %.5f (trained %.5f)\n", fresh.loss, tuned.loss, rep.loss);
        CHECK(tuned.loss < 0.1 * fresh.loss);
        CHECK(tuned.loss < 3 * rep.loss + 1e-3);
        ft.width = o.width / 2;
        CHECK_INT(param_net_flatten(g2, ch, 2, feat, FD, &ft, uvi, NULL), NEUV_ERR_INPUT);
        param_net_model_free(model);
        free(uvi); free(uvf); free(feat); free(ch); mesh_free(g2);
    }

    /* A curved disk: the upper half of a sphere. */
    neuv_mesh *cap = half_sphere();
    uv = malloc((size_t)cap->nf * 6 * sizeof(double));
    train(cap, "hemisphere", &o, &mt, &rep, uv);
    CHECK(mt.qce_mean < QCE_CAP);
    CHECK(rep.cycle_rms < CYCLE_CAP);
    free(uv);
    mesh_free(cap);
    return check_report("test_param_net");
}
