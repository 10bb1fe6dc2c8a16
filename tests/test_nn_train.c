/* Training with the neural engine: an MLP learns a sphere patch, Adam matches
 * hand-computed steps, clipping and schedules act, the arena stops growing,
 * and two identical runs give identical bytes. */
#include "check.h"

#include "core/rng.h"
#include "core/timer.h"
#include "nn/adam.h"
#include "nn/mlp.h"
#include "nn/nn.h"

/* The target map: (u, v) in [-1, 1]^2 -> a patch of the sphere of radius 0.9
 * (longitude 1.2 u, latitude 0.8 v), smooth and inside tanh's range. */
static void sphere_patch(float u, float v, float *p)
{
    double lon = 1.2 * u, lat = 0.8 * v;
    p[0] = (float)(0.9 * cos(lat) * cos(lon));
    p[1] = (float)(0.9 * cos(lat) * sin(lon));
    p[2] = (float)(0.9 * sin(lat));
}

static void make_samples(uint64_t seed, int n, float *x, float *y)
{
    rng r;
    rng_seed(&r, seed);
    for (int i = 0; i < n; i++) {
        x[2 * i] = (float)(2 * rng_uniform(&r) - 1);
        x[2 * i + 1] = (float)(2 * rng_uniform(&r) - 1);
        sphere_patch(x[2 * i], x[2 * i + 1], y + 3 * i);
    }
}

static float halve_after_1000(void *user, long step, float base)
{
    (void)user;
    return step > 1000 ? base * 0.3f : base;
}

/* Trains for `steps` on a fixed batch; returns the held-out RMS error per coordinate
 * and optionally the final parameters (copied into `final`, size nn_params_count). */
static double train_sphere(int steps, int batch, uint64_t seed, float *final, size_t *growth_after_2)
{
    nn_params ps;
    nn_params_init(&ps);
    nn_mlp mlp;
    nn_mlp_config cfg = {.in = 2, .width = 48, .out = 3, .depth = 4, .hidden = NN_ACT_TANH,
                         .output = NN_ACT_TANH, .seed = seed};
    CHECK_INT(nn_mlp_create(&mlp, &cfg, &ps, "f"), NEUV_OK);
    nn_adam_config acfg = nn_adam_defaults();
    acfg.lr = 5e-3f;
    acfg.schedule = halve_after_1000;
    nn_adam adam;
    CHECK_INT(nn_adam_init(&adam, &ps, &acfg), NEUV_OK);
    float *x = malloc((size_t)batch * 2 * sizeof(float)), *y = malloc((size_t)batch * 3 * sizeof(float));
    make_samples(seed + 100, batch, x, y);
    nn_ctx *ctx = nn_ctx_create(0);
    size_t grow2 = 0;
    for (int step = 0; step < steps; step++) {
        nn_ctx_reset(ctx);
        nn_tensor *out = nn_mlp_forward(ctx, &mlp, nn_from(ctx, batch, 2, x));
        nn_tensor *loss = nn_mean(ctx, nn_square(ctx, nn_sub(ctx, out, nn_from(ctx, batch, 3, y))), NN_ALL);
        nn_params_zero_grad(&ps);
        if (nn_backward(ctx, loss) != NEUV_OK) { CHECK(0); break; }
        nn_adam_step(&adam);
        if (step == 1) grow2 = nn_ctx_grow_count(ctx);
    }
    if (growth_after_2) *growth_after_2 = nn_ctx_grow_count(ctx) - grow2;
    /* Held-out error on fresh points. */
    enum { TEST = 500 };
    float tx[TEST * 2], ty[TEST * 3];
    make_samples(seed + 999, TEST, tx, ty);
    nn_ctx_reset(ctx);
    nn_tensor *out = nn_mlp_forward(ctx, &mlp, nn_from(ctx, TEST, 2, tx));
    double se = 0;
    for (int i = 0; i < TEST * 3; i++) se += (out->data[i] - ty[i]) * (double)(out->data[i] - ty[i]);
    if (final) {
        size_t k = 0;
        for (int i = 0; i < ps.n; i++) {
            size_t n = (size_t)ps.t[i]->rows * ps.t[i]->cols;
            memcpy(final + k, ps.t[i]->data, n * sizeof(float));
            k += n;
        }
    }
    free(x); free(y);
    nn_ctx_free(ctx);
    nn_adam_free(&adam);
    nn_mlp_free(&mlp);
    nn_params_free(&ps);
    return sqrt(se / (TEST * 3));
}

static void test_adam_by_hand(void)
{
    nn_params ps;
    nn_params_init(&ps);
    nn_tensor *p = nn_params_add(&ps, 1, 2, "p");
    p->data[0] = 1.0f; p->data[1] = -2.0f;
    nn_adam_config cfg = nn_adam_defaults();
    cfg.lr = 0.1f;
    nn_adam opt;
    CHECK_INT(nn_adam_init(&opt, &ps, &cfg), NEUV_OK);
    /* Step 1: bias-corrected m/sqrt(v) = g/|g|, so each weight moves by lr against its gradient's sign. */
    p->grad[0] = 0.5f; p->grad[1] = -0.1f;
    nn_adam_step(&opt);
    CHECK_NEAR(p->data[0], 0.9, 1e-6);
    CHECK_NEAR(p->data[1], -1.9, 1e-6);
    /* Step 2 by hand for weight 0 (g1 = 0.5, g2 = 0.2):
     * m = 0.9*0.05 + 0.1*0.2 = 0.065, v = 0.999*0.00025 + 0.001*0.04 = 0.00028975,
     * m_hat = 0.065/0.19 = 0.3421053, v_hat = 0.00028975/0.001999 = 0.1449475,
     * step = 0.1 * 0.3421053 / 0.3807197 = 0.0898575. */
    p->grad[0] = 0.2f; p->grad[1] = 0.3f;
    nn_adam_step(&opt);
    CHECK_NEAR(p->data[0], 0.9 - 0.0898575, 2e-6);
    CHECK_NEAR(opt.m[0][0], 0.065, 1e-7);
    CHECK_NEAR(opt.v[0][0], 0.00028975, 1e-8); /* float betas: 1 - 0.999f is 0.00099998713 */
    nn_adam_free(&opt);

    /* Clipping by global norm: gradients (3, 4) have norm 5; clipped to 1 -> (0.6, 0.8). */
    cfg.clip_norm = 1.0f;
    CHECK_INT(nn_adam_init(&opt, &ps, &cfg), NEUV_OK);
    p->grad[0] = 3.0f; p->grad[1] = 4.0f;
    nn_adam_step(&opt);
    CHECK_NEAR(opt.last_grad_norm, 5.0, 1e-6);
    CHECK_NEAR(opt.m[0][0], 0.06, 1e-7);
    CHECK_NEAR(opt.m[0][1], 0.08, 1e-7);
    nn_adam_free(&opt);

    /* The schedule hook sets the rate: step 1 moves by exactly the scheduled lr. */
    cfg.clip_norm = 0;
    cfg.schedule = halve_after_1000;
    CHECK_INT(nn_adam_init(&opt, &ps, &cfg), NEUV_OK);
    opt.t = 1000; /* the next step is 1001 (bias correction then ~ v-only; check lr) */
    nn_adam_step(&opt);
    CHECK_NEAR(opt.last_lr, 0.03, 1e-7);
    nn_adam_free(&opt);
    cfg.lr = -1;
    CHECK_INT(nn_adam_init(&opt, &ps, &cfg), NEUV_ERR_INPUT);
    nn_params_free(&ps);
}

int main(void)
{
    test_adam_by_hand();

    /* Learning: 4-layer tanh MLP, 256 points, 2500 Adam steps. */
    nn_set_threads(1);
    double t0 = now_seconds();
    size_t growth = 99;
    double rms = train_sphere(2500, 256, 7, NULL, &growth);
    double secs = now_seconds() - t0;
    printf("  sphere patch: held-out RMS error %.5f after 2500 steps (%.2f s)\n", rms, secs);
    CHECK(rms < 0.01);          /* 1% of the patch radius */
    CHECK_INT(growth, 0);       /* no arena growth after the second step */

    /* Determinism: same seed and thread count -> identical bytes, with 2 threads
     * and a batch big enough that the OpenMP paths run. */
    nn_set_threads(2);
    size_t np = 2 * 48 + 48 + 2 * (48 * 48 + 48) + 48 * 3 + 3;
    float *a = malloc(np * sizeof(float)), *b = malloc(np * sizeof(float));
    double ra = train_sphere(40, 2048, 3, a, NULL);
    double rb = train_sphere(40, 2048, 3, b, NULL);
    CHECK(memcmp(a, b, np * sizeof(float)) == 0);
    CHECK(ra == rb);
    free(a); free(b);
    return check_report("test_nn_train");
}
