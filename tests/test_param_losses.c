/* The parameterization losses and the fold barrier: hand-checkable values (the
 * identity map of a flat chart costs nothing; a uniform scaling costs what the
 * formulas say) and
 * finite-difference gradients of each loss with respect to the UVs. */
#include "check.h"

#include "core/rng.h"
#include "losses/param_losses.h"
#include "mesh/shapes.h"
#include "nn/nn.h"

typedef nn_tensor *(*loss_fn)(nn_ctx *ctx, nn_tensor *uv, void *user);

typedef struct fixture {
    const neuv_mesh *m;
    param_corners c;
    float *cos3d, *area3d, *orient, *g, *x3, *frame_inv, *weight;
    int *pi, *pj, np;
} fixture;

static nn_tensor *f_iso(nn_ctx *ctx, nn_tensor *uv, void *u)
{
    fixture *f = u;
    return param_loss_iso(ctx, uv, f->pi, f->pj, nn_from(ctx, f->np, 1, f->g), f->np);
}
static nn_tensor *f_angle(nn_ctx *ctx, nn_tensor *uv, void *u)
{
    fixture *f = u;
    return param_loss_angle(ctx, uv, &f->c, nn_from(ctx, 3 * f->c.nf, 1, f->cos3d));
}
static nn_tensor *f_area(nn_ctx *ctx, nn_tensor *uv, void *u)
{
    fixture *f = u;
    return param_loss_area(ctx, uv, &f->c, nn_from(ctx, f->c.nf, 1, f->area3d), nn_from(ctx, f->c.nf, 1, f->orient));
}
/* The fold barrier with ε = 0.05. */
static nn_tensor *f_fold(nn_ctx *ctx, nn_tensor *uv, void *u)
{
    fixture *f = u;
    return param_loss_fold_barrier(ctx, uv, &f->c, nn_from(ctx, f->c.nf, 1, f->area3d),
                                   nn_from(ctx, f->c.nf, 1, f->orient), 0.05f);
}
static nn_tensor *f_conf(nn_ctx *ctx, nn_tensor *uv, void *u)
{
    fixture *f = u;
    return param_loss_conformal(ctx, uv, &f->c, nn_from(ctx, f->c.nf, 4, f->frame_inv),
                                nn_from(ctx, f->c.nf, 1, f->weight), nn_from(ctx, f->c.nf, 1, f->orient));
}
/* L_cycle with the "reconstruction" a fixed smooth function of uv (uv, uv0 uv1), so that
 * the gradient reaches uv through both of x_rec's columns. */
static nn_tensor *f_cycle(nn_ctx *ctx, nn_tensor *uv, void *u)
{
    fixture *f = u;
    nn_tensor *z = nn_mul(ctx, nn_slice_cols(ctx, uv, 0, 1), nn_slice_cols(ctx, uv, 1, 1));
    nn_tensor *xr = nn_concat_cols(ctx, uv, z);
    return param_loss_cycle(ctx, nn_from(ctx, uv->rows, 3, f->x3), xr);
}

static double loss_at(loss_fn fn, fixture *f, nn_tensor *uv)
{
    nn_ctx *ctx = nn_ctx_create(0);
    nn_tensor *l = fn(ctx, uv, f);
    double v = l ? l->data[0] : NAN;
    nn_ctx_free(ctx);
    return v;
}

/* Worst |analytic − numeric| / (1e-4 + 2e-2 |numeric|) over every UV entry. */
static double gradcheck(const char *name, loss_fn fn, fixture *f, const float *uv0, int nv)
{
    nn_params ps;
    nn_params_init(&ps);
    nn_tensor *uv = nn_params_add(&ps, nv, 2, "uv");
    memcpy(uv->data, uv0, (size_t)nv * 2 * sizeof(float));
    nn_ctx *ctx = nn_ctx_create(0);
    nn_tensor *l = fn(ctx, uv, f);
    CHECK_INT(nn_backward(ctx, l), NEUV_OK);
    double worst = 0;
    const float eps = 1e-3f;
    for (int i = 0; i < 2 * nv; i++) {
        float keep = uv->data[i];
        uv->data[i] = keep + eps;
        double lp = loss_at(fn, f, uv);
        uv->data[i] = keep - eps;
        double lm = loss_at(fn, f, uv);
        uv->data[i] = keep;
        double num = (lp - lm) / (2.0 * eps), ana = uv->grad[i];
        double r = fabs(ana - num) / (1e-4 * fabs(l->data[0]) / nv + 1e-6 + 2e-2 * fabs(num));
        if (r > worst) worst = r;
    }
    printf("%s: loss %.6g, worst gradient mismatch ratio %.3f\n", name, l->data[0], worst);
    nn_ctx_free(ctx);
    nn_params_free(&ps);
    return worst;
}

int main(void)
{
    nn_set_threads(1);
    /* A 4 by 3 grid over [0,0.8] by [0,0.6]: flat, so its identity map is isometric. */
    neuv_mesh *m = shape_grid(4, 3, 0.8, 0.6, 0);
    fixture f = {.m = m};
    CHECK_INT(param_corners_build(m->tri, m->nf, &f.c), NEUV_OK);
    int nf = m->nf, nv = m->nv;
    f.cos3d = malloc(sizeof(float) * 3 * nf);
    f.area3d = malloc(sizeof(float) * nf);
    f.orient = malloc(sizeof(float) * nf);
    f.x3 = malloc(sizeof(float) * 3 * nv);
    param_corner_targets(m->pos, &f.c, f.cos3d, f.area3d);
    f.frame_inv = malloc(sizeof(float) * 4 * nf);
    f.weight = malloc(sizeof(float) * nf);
    param_conformal_targets(m->pos, &f.c, f.frame_inv, f.weight);
    double wsum = 0;
    for (int i = 0; i < nf; i++) wsum += f.weight[i];
    CHECK_NEAR(wsum, 1, 1e-6);
    double asum = 0;
    for (int i = 0; i < nf; i++) { asum += f.area3d[i]; f.orient[i] = 1; }
    CHECK_NEAR(asum, 0.48, 1e-6);
    /* Corner rows: row k*nf + fa is corner k of face fa. */
    CHECK_INT(f.c.p0[nf + 2], m->tri[3 * 2 + 1]);
    CHECK_INT(f.c.p1[nf + 2], m->tri[3 * 2 + 2]);
    CHECK_INT(f.c.p2[nf + 2], m->tri[3 * 2 + 0]);
    /* Every pair of vertices closer than 0.45 with its Euclidean (= geodesic) distance. */
    f.pi = malloc(sizeof(int) * nv * nv); f.pj = malloc(sizeof(int) * nv * nv); f.g = malloc(sizeof(float) * nv * nv);
    for (int i = 0; i < nv; i++)
        for (int j = i + 1; j < nv; j++) {
            double dx = m->pos[3 * i] - m->pos[3 * j], dy = m->pos[3 * i + 1] - m->pos[3 * j + 1];
            double dd = sqrt(dx * dx + dy * dy);
            if (dd < 0.45) { f.pi[f.np] = i; f.pj[f.np] = j; f.g[f.np] = (float)dd; f.np++; }
        }
    float *uv = malloc(sizeof(float) * 2 * nv);
    for (int v = 0; v < nv; v++) {
        uv[2 * v] = (float)m->pos[3 * v];
        uv[2 * v + 1] = (float)m->pos[3 * v + 1];
        for (int q = 0; q < 3; q++) f.x3[3 * v + q] = (float)m->pos[3 * v + q];
    }
    nn_ctx *ctx = nn_ctx_create(0);
    nn_tensor *t = nn_from(ctx, nv, 2, uv);
    /* Identity: nothing to pay. */
    CHECK_NEAR(f_iso(ctx, t, &f)->data[0], 0, 1e-12);
    CHECK_NEAR(f_angle(ctx, t, &f)->data[0], 0, 1e-10);
    CHECK_NEAR(f_area(ctx, t, &f)->data[0], 0, 1e-14);
    CHECK_NEAR(f_fold(ctx, t, &f)->data[0], 0, 1e-14);
    CHECK_NEAR(f_conf(ctx, t, &f)->data[0], 0, 1e-5);
    /* u = 2x, v = y: every face has singular values 2 and 1, so s1/s2 + s2/s1 − 2 = 0.5. */
    {
        float *st = malloc(sizeof(float) * 2 * nv);
        for (int v = 0; v < nv; v++) { st[2 * v] = 2 * uv[2 * v]; st[2 * v + 1] = uv[2 * v + 1]; }
        CHECK_NEAR(f_conf(ctx, nn_from(ctx, nv, 2, st), &f)->data[0], 0.5, 1e-5);
        /* a rotation by 90 degrees and a uniform scaling are conformal */
        for (int v = 0; v < nv; v++) { st[2 * v] = -3 * uv[2 * v + 1]; st[2 * v + 1] = 3 * uv[2 * v]; }
        CHECK_NEAR(f_conf(ctx, nn_from(ctx, nv, 2, st), &f)->data[0], 0, 1e-5);
        free(st);
    }
    /* A triangle standing in the yz plane: its own plane frame, not the xy projection. */
    {
        int tri[3] = {0, 1, 2};
        param_corners c1;
        CHECK_INT(param_corners_build(tri, 1, &c1), NEUV_OK);
        double p3[9] = {0, 0, 0, 0, 1, 0, 0, 0, 1};
        float B[4], w[1], one[1] = {1};
        param_conformal_targets(p3, &c1, B, w);
        CHECK_NEAR(w[0], 1, 1e-7);
        float q[6] = {0, 0, 1, 0, 0, 1}, q2[6] = {0, 0, 2, 0, 0, 1};
        nn_tensor *l = param_loss_conformal(ctx, nn_from(ctx, 3, 2, q), &c1, nn_from(ctx, 1, 4, B), nn_from(ctx, 1, 1, w),
                                            nn_from(ctx, 1, 1, one));
        CHECK_NEAR(l->data[0], 0, 1e-6);
        l = param_loss_conformal(ctx, nn_from(ctx, 3, 2, q2), &c1, nn_from(ctx, 1, 4, B), nn_from(ctx, 1, 1, w),
                                 nn_from(ctx, 1, 1, one));
        CHECK_NEAR(l->data[0], 0.5, 1e-6);
        param_corners_free(&c1);
    }
    /* x_rec = (u, v, u v) against x = (x, y, 0): L_cycle = mean (x y)². */
    double cyc = 0;
    for (int v = 0; v < nv; v++) cyc += pow(m->pos[3 * v] * m->pos[3 * v + 1], 2);
    CHECK_NEAR(f_cycle(ctx, t, &f)->data[0], cyc / nv, 1e-7);
    /* Uniform scaling by 2: angles kept (L_angle 0), every length doubled
     * (L_iso = mean g²), every area quadrupled (L_area = mean (3 a)²). */
    float *uv2 = malloc(sizeof(float) * 2 * nv);
    for (int i = 0; i < 2 * nv; i++) uv2[i] = 2 * uv[i];
    nn_tensor *t2 = nn_from(ctx, nv, 2, uv2);
    double g2 = 0;
    for (int p = 0; p < f.np; p++) g2 += (double)f.g[p] * f.g[p];
    CHECK_NEAR(f_iso(ctx, t2, &f)->data[0], g2 / f.np, 1e-6);
    CHECK_NEAR(f_angle(ctx, t2, &f)->data[0], 0, 1e-10);
    double a2 = 0;
    for (int i = 0; i < nf; i++) a2 += 9.0 * f.area3d[i] * f.area3d[i];
    CHECK_NEAR(f_area(ctx, t2, &f)->data[0], a2 / nf, 1e-9);
    CHECK_NEAR(f_fold(ctx, t2, &f)->data[0], 0, 1e-14); /* area ratio 4: above ε */
    /* A mirror image keeps lengths and angles but flips every face: with the
     * chart orientation +1, each face pays (−a − a)² = 4a². */
    for (int v = 0; v < nv; v++) { uv2[2 * v] = -uv[2 * v]; uv2[2 * v + 1] = uv[2 * v + 1]; }
    nn_tensor *tm = nn_from(ctx, nv, 2, uv2);
    CHECK_NEAR(f_iso(ctx, tm, &f)->data[0], 0, 1e-12);
    CHECK_NEAR(f_angle(ctx, tm, &f)->data[0], 0, 1e-10);
    CHECK_NEAR(f_area(ctx, tm, &f)->data[0], 4.0 * a2 / 9.0 / nf, 1e-9);
    /* ... and the barrier sees area ratio −1 on every face: (ε + 1)². */
    CHECK_NEAR(f_fold(ctx, tm, &f)->data[0], 1.05 * 1.05, 1e-5);
    /* Half the size, not flipped: ratio 1/4, above ε, free; a face squashed to
     * ratio 0.01 pays (0.05 − 0.01)² / #F. */
    for (int i = 0; i < 2 * nv; i++) uv2[i] = 0.5f * uv[i];
    CHECK_NEAR(f_fold(ctx, nn_from(ctx, nv, 2, uv2), &f)->data[0], 0, 1e-14);
    {
        int tri[3] = {0, 1, 2};
        param_corners c1;
        CHECK_INT(param_corners_build(tri, 1, &c1), NEUV_OK);
        float q[6] = {0, 0, 1, 0, 0, 0.01f}, a3[1] = {0.5f}, o1[1] = {1};
        nn_tensor *l = param_loss_fold_barrier(ctx, nn_from(ctx, 3, 2, q), &c1, nn_from(ctx, 1, 1, a3),
                                               nn_from(ctx, 1, 1, o1), 0.05f);
        CHECK_NEAR(l->data[0], 0.04 * 0.04, 1e-7);
        param_corners_free(&c1);
    }
    /* Shearing one corner angle: angle loss of one right triangle by hand.
     * Triangle (0,0) (1,0) (0,1) mapped to (0,0) (1,0) (1,1): corner cosines
     * 3D (0, 1/√2, 1/√2), UV (1/√2, 0, 1/√2): L = (1/2 + 1/2 + 0)/3 = 1/3. */
    {
        int tri[3] = {0, 1, 2};
        param_corners c1;
        CHECK_INT(param_corners_build(tri, 1, &c1), NEUV_OK);
        double p3[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
        float cs[3], ar[1];
        param_corner_targets(p3, &c1, cs, ar);
        CHECK_NEAR(cs[0], 0, 1e-7);
        CHECK_NEAR(cs[1], sqrt(0.5), 1e-7);
        CHECK_NEAR(ar[0], 0.5, 1e-7);
        float q[6] = {0, 0, 1, 0, 1, 1};
        nn_tensor *l = param_loss_angle(ctx, nn_from(ctx, 3, 2, q), &c1, nn_from(ctx, 3, 1, cs));
        CHECK_NEAR(l->data[0], 1.0 / 3.0, 1e-6);
        param_corners_free(&c1);
    }
    nn_ctx_free(ctx);

    /* Gradients at a random perturbation of the identity. */
    rng r;
    rng_seed(&r, 3);
    for (int i = 0; i < 2 * nv; i++) uv2[i] = uv[i] + (float)(0.1 * (rng_uniform(&r) - 0.5));
    CHECK(gradcheck("L_conf", f_conf, &f, uv2, nv) <= 1);
    for (int i = 0; i < nf; i++) f.orient[i] = i % 3 ? 1.0f : -1.0f;
    CHECK(gradcheck("L_iso", f_iso, &f, uv2, nv) <= 1);
    CHECK(gradcheck("L_angle", f_angle, &f, uv2, nv) <= 1);
    CHECK(gradcheck("L_area", f_area, &f, uv2, nv) <= 1);
    CHECK(gradcheck("L_cycle", f_cycle, &f, uv2, nv) <= 1);
    /* Faces with orientation −1 are folded against it (barrier active), the others not. */
    CHECK(gradcheck("L_fold", f_fold, &f, uv2, nv) <= 1);

    free(uv); free(uv2); free(f.cos3d); free(f.area3d); free(f.orient); free(f.x3); free(f.frame_inv); free(f.weight);
    free(f.pi); free(f.pj); free(f.g);
    param_corners_free(&f.c);
    mesh_free(m);
    return check_report("test_param_losses");
}
