/* DiffusionNet: finite-difference gradient checks through whole blocks and
 * the network, and invariance of the HKS-input network to rigid motions. */
#include <math.h>

#include "check.h"
#include "core/rng.h"
#include "geometry/operators.h"
#include "mesh/shapes.h"
#include "models/diffusion_net.h"

/* A sphere with seeded radial bumps: no symmetry, so the eigenvalues are
 * distinct and a truncated eigenbasis is determined up to signs. */
static neuv_mesh *bumpy_sphere(int level, uint64_t seed)
{
    neuv_mesh *m = shape_icosphere(level, 1.0);
    rng r;
    rng_seed(&r, seed);
    double a[6];
    for (int i = 0; i < 6; i++) a[i] = 0.15 * (2 * rng_uniform(&r) - 1);
    for (int v = 0; v < m->nv; v++) {
        double *p = m->pos + 3 * v;
        double s = 1 + a[0] * p[0] + a[1] * p[1] * p[1] + a[2] * p[2] * p[0] + a[3] * sin(3 * p[1])
                   + a[4] * p[2] * p[2] * p[2] + a[5] * cos(2 * p[0] + p[2]);
        for (int d = 0; d < 3; d++) p[d] *= s;
    }
    return m;
}

typedef struct fixture {
    neuv_mesh *m;
    operators ops;
    diffusion_net_geometry g;
    float *x;
    int dim;
} fixture;

static void fixture_make(fixture *fx, neuv_mesh *m, int k)
{
    fx->m = m;
    operators_params p = operators_default_params();
    p.k = k;
    p.n_hks = 8;
    CHECK(operators_compute(m, &p, &fx->ops) == NEUV_OK);
    CHECK(diffusion_net_geometry_create(m, &fx->ops, k, &fx->g) == NEUV_OK);
    CHECK(diffusion_net_input_features(m, &fx->ops, DIFFUSION_NET_HKS, &fx->x, &fx->dim) == NEUV_OK);
}

static void fixture_free(fixture *fx)
{
    free(fx->x);
    diffusion_net_geometry_free(&fx->g);
    operators_free(&fx->ops);
    mesh_free(fx->m);
}

/* Loss Σ w ⊙ block(x) with fixed random weights w, x a parameter so the
 * input gradient is checked too. */
static double block_loss(nn_ctx *ctx, const diffusion_net_block *b, const fixture *fx, nn_tensor *xp,
                         const float *w, int C)
{
    nn_ctx_reset(ctx);
    nn_tensor *y = diffusion_net_block_forward(ctx, b, &fx->g, xp);
    nn_tensor *l = nn_sum(ctx, nn_mul(ctx, y, nn_from(ctx, fx->g.nv, C, w)), NN_ALL);
    return l ? l->data[0] : NAN;
}

/* Directional finite differences (central, step h relative to the tensor's
 * scale) against the analytic gradient along 3 random directions per tensor. */
static void check_tensor_grad(nn_ctx *ctx, const diffusion_net_block *b, const fixture *fx, nn_tensor *xp,
                              const float *w, int C, nn_tensor *t, const char *name, rng *r)
{
    int n = t->rows * t->cols;
    float *dir = malloc(sizeof(float) * n), *save = malloc(sizeof(float) * n);
    double scale = 0;
    for (int i = 0; i < n; i++) scale = fmax(scale, fabs(t->data[i]));
    double h = 2e-3 * (scale > 0 ? scale : 1);
    for (int trial = 0; trial < 3; trial++) {
        double g_dot = 0;
        for (int i = 0; i < n; i++) {
            dir[i] = (float)(2 * rng_uniform(r) - 1);
            g_dot += (double)t->grad[i] * dir[i];
        }
        memcpy(save, t->data, sizeof(float) * n);
        for (int i = 0; i < n; i++) t->data[i] = save[i] + (float)h * dir[i];
        double lp = block_loss(ctx, b, fx, xp, w, C);
        for (int i = 0; i < n; i++) t->data[i] = save[i] - (float)h * dir[i];
        double lm = block_loss(ctx, b, fx, xp, w, C);
        memcpy(t->data, save, sizeof(float) * n);
        double fd = (lp - lm) / (2 * h);
        double tol = 2e-2 * fmax(fabs(fd), fabs(g_dot)) + 1e-3;
        if (!(fabs(fd - g_dot) <= tol))
            fprintf(stderr, "gradient of %s: finite difference %.6g, backward %.6g\n", name, fd, g_dot);
        CHECK_NEAR(fd, g_dot, tol);
    }
    free(dir);
    free(save);
}

static void test_block_gradients(void)
{
    fixture fx;
    fixture_make(&fx, bumpy_sphere(1, 3), 16);
    int C = 5;
    nn_params ps;
    nn_params_init(&ps);
    diffusion_net net;
    diffusion_net_config cfg = {.in = fx.dim, .width = C, .out = 3, .blocks = 1, .seed = 7};
    CHECK(diffusion_net_create(&net, &cfg, &ps, "dn") == NEUV_OK);
    const diffusion_net_block *b = &net.block[0];
    /* Diffusion times of order 1 (unit-area units), so the decay matters in the check. */
    for (int c = 0; c < C; c++) b->time->data[c] = 0.005f + 0.01f * c;
    rng r;
    rng_seed(&r, 11);
    nn_tensor *xp = nn_param_create(fx.g.nv, C, "x");
    /* Small inputs keep the tanh of the gradient features out of saturation,
     * where float32 central differences lose their accuracy. */
    for (int i = 0; i < fx.g.nv * C; i++) xp->data[i] = (float)(0.2 * (2 * rng_uniform(&r) - 1));
    float *w = malloc(sizeof(float) * fx.g.nv * C);
    for (int i = 0; i < fx.g.nv * C; i++) w[i] = (float)(2 * rng_uniform(&r) - 1);
    nn_ctx *ctx = nn_ctx_create(0);
    double l0 = block_loss(ctx, b, &fx, xp, w, C);
    CHECK(isfinite(l0));
    nn_params_zero_grad(&ps);
    memset(xp->grad, 0, sizeof(float) * fx.g.nv * C);
    nn_tensor *y = diffusion_net_block_forward(ctx, b, &fx.g, xp);
    CHECK(nn_backward(ctx, nn_sum(ctx, nn_mul(ctx, y, nn_from(ctx, fx.g.nv, C, w)), NN_ALL)) == NEUV_OK);
    /* Copy the grads out first: the finite-difference passes reset the ctx. */
    check_tensor_grad(ctx, b, &fx, xp, w, C, b->time, "time", &r);
    check_tensor_grad(ctx, b, &fx, xp, w, C, b->rot_re, "rot_re", &r);
    check_tensor_grad(ctx, b, &fx, xp, w, C, b->rot_im, "rot_im", &r);
    check_tensor_grad(ctx, b, &fx, xp, w, C, b->mlp0.w, "mlp0.w", &r);
    check_tensor_grad(ctx, b, &fx, xp, w, C, b->mlp1.w, "mlp1.w", &r);
    check_tensor_grad(ctx, b, &fx, xp, w, C, xp, "x", &r);
    /* The time gradient is nonzero: diffusion really depends on t. */
    double tg = 0;
    for (int c = 0; c < C; c++) tg += fabs(b->time->grad[c]);
    CHECK(tg > 1e-6);
    nn_ctx_free(ctx);
    nn_param_free(xp);
    free(w);
    diffusion_net_free(&net);
    nn_params_free(&ps);
    fixture_free(&fx);
}

/* Diffusion with t -> 0 is the identity on the span of the basis, and a
 * constant function stays constant for any t (λ_0 = 0). */
static void test_diffusion_limits(void)
{
    fixture fx;
    fixture_make(&fx, bumpy_sphere(2, 5), 32);
    int nv = fx.g.nv;
    nn_ctx *ctx = nn_ctx_create(0);
    float *c = malloc(sizeof(float) * nv);
    for (int v = 0; v < nv; v++) c[v] = 2.5f;
    float t_big = 0.5f;
    nn_tensor *h = learned_time_diffusion(ctx, &fx.g, nn_from(ctx, nv, 1, c), nn_from(ctx, 1, 1, &t_big));
    double err = 0;
    for (int v = 0; v < nv; v++) err = fmax(err, fabs(h->data[v] - 2.5));
    CHECK(err < 1e-3);
    /* An eigenvector decays by exactly exp(-λ t). */
    int j = 5;
    for (int v = 0; v < nv; v++) c[v] = fx.g.evecs[(size_t)v * fx.g.k + j];
    float t = 0.01f;
    h = learned_time_diffusion(ctx, &fx.g, nn_from(ctx, nv, 1, c), nn_from(ctx, 1, 1, &t));
    double want = exp(fx.g.neg_evals[j] * t), num = 0, den = 0;
    for (int v = 0; v < nv; v++) { num += h->data[v] * c[v]; den += (double)c[v] * c[v]; }
    CHECK_NEAR(num / den, want, 1e-3);
    CHECK(want < 0.9 && want > 0.05);
    free(c);
    nn_ctx_free(ctx);
    fixture_free(&fx);
}

/* Whole-network output on a mesh and on a rotated + translated copy. */
static void test_rigid_invariance(void)
{
    neuv_mesh *a = bumpy_sphere(2, 9), *b = bumpy_sphere(2, 9);
    double c = cos(0.7), s = sin(0.7), c2 = cos(-1.1), s2 = sin(-1.1);
    for (int v = 0; v < b->nv; v++) {
        double *p = b->pos + 3 * v;
        double x = c * p[0] - s * p[1], y = s * p[0] + c * p[1], z = p[2];
        double y2 = c2 * y - s2 * z, z2 = s2 * y + c2 * z;
        p[0] = x + 3.0; p[1] = y2 - 1.5; p[2] = z2 + 0.25;
    }
    fixture fa, fb;
    fixture_make(&fa, a, 24);
    fixture_make(&fb, b, 24);
    nn_params ps;
    nn_params_init(&ps);
    diffusion_net net;
    diffusion_net_config cfg = {.in = fa.dim, .width = 8, .out = 4, .blocks = 2, .seed = 3};
    CHECK(diffusion_net_create(&net, &cfg, &ps, "dn") == NEUV_OK);
    nn_ctx *ca = nn_ctx_create(0), *cb = nn_ctx_create(0);
    nn_tensor *ya = diffusion_net_forward(ca, &net, &fa.g, nn_view(ca, fa.g.nv, fa.dim, fa.x), NULL);
    nn_tensor *yb = diffusion_net_forward(cb, &net, &fb.g, nn_view(cb, fb.g.nv, fb.dim, fb.x), NULL);
    CHECK(ya && yb);
    double diff = 0, mag = 0;
    for (int i = 0; i < fa.g.nv * 4; i++) {
        diff = fmax(diff, fabs(ya->data[i] - yb->data[i]));
        mag = fmax(mag, fabs(ya->data[i]));
    }
    CHECK(mag > 1e-2);
    CHECK(diff < 1e-3 * mag);
    /* xyz input is not invariant: the same check must see a difference. */
    float *xa, *xb;
    int d;
    CHECK(diffusion_net_input_features(a, &fa.ops, DIFFUSION_NET_XYZ, &xa, &d) == NEUV_OK);
    CHECK(diffusion_net_input_features(b, &fb.ops, DIFFUSION_NET_XYZ, &xb, &d) == NEUV_OK);
    double r = 0, dx = 0;
    for (int v = 0; v < a->nv; v++) {
        r = fmax(r, sqrt(xa[3 * v] * xa[3 * v] + xa[3 * v + 1] * xa[3 * v + 1] + xa[3 * v + 2] * xa[3 * v + 2]));
        dx = fmax(dx, fabs(xa[3 * v] - xb[3 * v]));
    }
    CHECK_NEAR(r, 1.0, 1e-6);
    CHECK(dx > 0.1);
    free(xa); free(xb);
    nn_ctx_free(ca); nn_ctx_free(cb);
    diffusion_net_free(&net);
    nn_params_free(&ps);
    fixture_free(&fa);
    fixture_free(&fb);
}

int main(void)
{
    test_block_gradients();
    test_diffusion_limits();
    test_rigid_invariance();
    return check_report("test_diffusion_net");
}
