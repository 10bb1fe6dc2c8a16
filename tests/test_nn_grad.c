/* Finite-difference gradient checks for every op of the neural engine and for
 * a whole 8-layer MLP. The loss is L = sum_ij W_ij out_ij with fixed random W;
 * the numerical side evaluates L in double from the op's outputs with central
 * differences, so the only noise is float rounding of the op itself. */
#include "check.h"

#include <omp.h>

#include "core/rng.h"
#include "nn/mlp.h"
#include "nn/nn.h"

#define MAX_IN 3

typedef nn_tensor *(*build_fn)(nn_ctx *ctx, nn_tensor **in);

typedef struct input_spec {
    int rows, cols;
    float lo, hi;      /* uniform range */
    float avoid;       /* keep |x - avoid_at| >= avoid (kinks); 0: no constraint */
    float avoid_at;
} input_spec;

static rng gen;
static int ops_seen[NN_OP_COUNT];

static float draw(const input_spec *s)
{
    for (;;) {
        float x = (float)(s->lo + (s->hi - s->lo) * rng_uniform(&gen));
        if (s->avoid == 0 || fabsf(x - s->avoid_at) >= s->avoid) return x;
    }
}

static double weighted_output(nn_tensor *out, const float *w)
{
    double s = 0;
    for (long i = 0; i < (long)out->rows * out->cols; i++) s += (double)w[i] * out->data[i];
    return s;
}

/* Optional test on drawn inputs (1 = usable): redraw until it accepts. */
typedef int (*accept_fn)(nn_tensor **in);
static accept_fn accept_inputs;

/* Smallest |pre-activation| of the (leaky) ReLUs in the tape ending at t: the
 * input itself for relu ops, |y| (or |y| / slope) for fused linear layers. */
static float closest_to_kink(nn_tensor *t)
{
    float closest = INFINITY;
    for (; t; t = t->prev) {
        int lin = t->op == NN_OP_LINEAR && (t->iparam[0] == NN_ACT_RELU || t->iparam[0] == NN_ACT_LEAKY_RELU);
        if (t->op != NN_OP_LEAKY_RELU && t->op != NN_OP_RELU && !lin) continue;
        for (int i = 0; i < t->rows * t->cols; i++) {
            float v;
            if (!lin) v = fabsf(t->src[0]->data[i]);
            else if (t->iparam[0] == NN_ACT_RELU) v = t->data[i] > 0 ? t->data[i] : INFINITY; /* z <= 0 unseen */
            else v = t->data[i] > 0 ? t->data[i] : -t->data[i] / t->fparam[0];
            if (v < closest) closest = v;
        }
    }
    return closest;
}

/* Returns the largest violation ratio |analytic - numeric| / tolerance (<= 1 passes). */
static double gradcheck(const char *name, build_fn f, int nin, const input_spec *spec, float eps)
{
    nn_params ps;
    nn_params_init(&ps);
    nn_tensor *in[MAX_IN];
    for (int k = 0; k < nin; k++) {
        char nm[16];
        snprintf(nm, sizeof nm, "in%d", k);
        in[k] = nn_params_add(&ps, spec[k].rows, spec[k].cols, nm);
    }
    for (int attempt = 0; attempt < 1000; attempt++) {
        for (int k = 0; k < nin; k++)
            for (long i = 0; i < (long)spec[k].rows * spec[k].cols; i++) in[k]->data[i] = draw(&spec[k]);
        if (!accept_inputs || accept_inputs(in)) break;
    }
    nn_ctx *ctx = nn_ctx_create(0);
    nn_tensor *out = f(ctx, in);
    CHECK(out != NULL);
    if (!out) { fprintf(stderr, "%s: %s\n", name, neuv_last_error()); nn_ctx_free(ctx); nn_params_free(&ps); return 1e9; }
    ops_seen[out->op] = 1;
    long nout = (long)out->rows * out->cols;
    float *w = malloc((size_t)nout * sizeof *w);
    for (long i = 0; i < nout; i++) w[i] = (float)(2 * rng_uniform(&gen) - 1);
    nn_tensor *loss = nn_sum(ctx, nn_mul(ctx, out, nn_from(ctx, out->rows, out->cols, w)), NN_ALL);
    CHECK_INT(nn_backward(ctx, loss), NEUV_OK);
    double worst = 0;
    for (int k = 0; k < nin; k++) {
        long n = (long)in[k]->rows * in[k]->cols;
        for (long i = 0; i < n; i++) {
            float keep = in[k]->data[i];
            in[k]->data[i] = keep + eps;
            nn_ctx_reset(ctx);
            double lp = weighted_output(f(ctx, in), w);
            in[k]->data[i] = keep - eps;
            nn_ctx_reset(ctx);
            double lm = weighted_output(f(ctx, in), w);
            in[k]->data[i] = keep;
            double num = (lp - lm) / (2.0 * (double)eps);
            double ana = in[k]->grad[i];
            double tol = 1e-3 + 1e-2 * fabs(num);
            double r = fabs(ana - num) / tol;
            if (r > worst) worst = r;
            if (r > 1)
                fprintf(stderr, "%s: input %d entry %ld: analytic %.6g numeric %.6g\n", name, k, i, ana, num);
        }
    }
    CHECK(worst <= 1);
    printf("  %-28s worst error/tolerance %.3f\n", name, worst);
    free(w);
    nn_ctx_free(ctx);
    nn_params_free(&ps);
    return worst;
}

/* ---- the graphs under test ------------------------------------------ */

static int ta_flag, tb_flag, axis_flag;
static nn_tensor *g_matmul(nn_ctx *c, nn_tensor **x) { return nn_matmul_t(c, x[0], ta_flag, x[1], tb_flag); }
static nn_tensor *g_add(nn_ctx *c, nn_tensor **x) { return nn_add(c, x[0], x[1]); }
static nn_tensor *g_sub(nn_ctx *c, nn_tensor **x) { return nn_sub(c, x[0], x[1]); }
static nn_tensor *g_mul(nn_ctx *c, nn_tensor **x) { return nn_mul(c, x[0], x[1]); }
static nn_tensor *g_div(nn_ctx *c, nn_tensor **x) { return nn_div(c, x[0], x[1]); }
static nn_tensor *g_square_self(nn_ctx *c, nn_tensor **x) { return nn_mul(c, x[0], x[0]); }
static nn_tensor *g_add_const(nn_ctx *c, nn_tensor **x) { return nn_add_const(c, x[0], 0.7f); }
static nn_tensor *g_scale(nn_ctx *c, nn_tensor **x) { return nn_scale(c, x[0], -1.7f); }
static nn_tensor *g_sum(nn_ctx *c, nn_tensor **x) { return nn_sum(c, x[0], axis_flag); }
static nn_tensor *g_mean(nn_ctx *c, nn_tensor **x) { return nn_mean(c, x[0], axis_flag); }
static nn_tensor *g_concat(nn_ctx *c, nn_tensor **x) { return nn_concat_cols(c, x[0], x[1]); }
static nn_tensor *g_slice(nn_ctx *c, nn_tensor **x) { return nn_slice_cols(c, x[0], 1, 3); }
static const int gather_index[7] = {2, 0, 2, 3, 1, 2, 0};
static nn_tensor *g_gather(nn_ctx *c, nn_tensor **x) { return nn_gather_rows(c, x[0], gather_index, 7); }
static nn_tensor *g_scatter(nn_ctx *c, nn_tensor **x) { return nn_scatter_add_rows(c, x[0], gather_index, 5); }
static nn_sparse sparse;
static nn_tensor *g_spmm(nn_ctx *c, nn_tensor **x) { return nn_spmm(c, &sparse, x[0]); }
static nn_tensor *g_relu(nn_ctx *c, nn_tensor **x) { return nn_relu(c, x[0]); }
static nn_tensor *g_leaky(nn_ctx *c, nn_tensor **x) { return nn_leaky_relu(c, x[0], 0.2f); }
static nn_tensor *g_tanh(nn_ctx *c, nn_tensor **x) { return nn_tanh(c, x[0]); }
static nn_tensor *g_sigmoid(nn_ctx *c, nn_tensor **x) { return nn_sigmoid(c, x[0]); }
static nn_tensor *g_softmax(nn_ctx *c, nn_tensor **x) { return nn_softmax_rows(c, x[0]); }
static nn_tensor *g_exp(nn_ctx *c, nn_tensor **x) { return nn_exp(c, x[0]); }
static nn_tensor *g_log(nn_ctx *c, nn_tensor **x) { return nn_log(c, x[0]); }
static nn_tensor *g_sqrt(nn_ctx *c, nn_tensor **x) { return nn_sqrt(c, x[0]); }
static nn_tensor *g_square(nn_ctx *c, nn_tensor **x) { return nn_square(c, x[0]); }
static nn_tensor *g_row_norm(nn_ctx *c, nn_tensor **x) { return nn_row_norm(c, x[0], 1e-6f); }
static nn_tensor *g_row_dot(nn_ctx *c, nn_tensor **x) { return nn_row_dot(c, x[0], x[1]); }
static nn_tensor *g_row_dot_self(nn_ctx *c, nn_tensor **x) { return nn_row_dot(c, x[0], x[0]); }
static nn_tensor *g_row_cosine(nn_ctx *c, nn_tensor **x) { return nn_row_cosine(c, x[0], x[1], 1e-8f); }
static nn_tensor *g_clamp(nn_ctx *c, nn_tensor **x) { return nn_clamp_min(c, x[0], 0.1f); }
static nn_activation act_flag;
static nn_tensor *g_linear(nn_ctx *c, nn_tensor **x) { return nn_linear_act(c, x[0], x[1], x[2], act_flag, 0.2f); }
/* Pre-activations x W + b at least 0.05 from zero (a 5e-3 step cannot cross the kink). */
static int linear_away_from_kink(nn_tensor **x)
{
    for (int i = 0; i < x[0]->rows; i++)
        for (int j = 0; j < x[1]->cols; j++) {
            double z = x[2]->data[j];
            for (int p = 0; p < x[0]->cols; p++) z += (double)x[0]->data[i * x[0]->cols + p] * x[1]->data[p * x[1]->cols + j];
            if (fabs(z) < 0.05) return 0;
        }
    return 1;
}

/* A DiffusionNet-like chain: spectral coefficients, learned times clamped
 * positive, exp(-lambda t) scaling, back to vertices; exercises transposed
 * products, broadcasting and an outer product in one graph. */
static float evecs[6 * 3], evals[3], mass[6];
static nn_tensor *g_diffusion(nn_ctx *c, nn_tensor **x)
{
    nn_tensor *phi = nn_view(c, 6, 3, evecs), *lam = nn_view(c, 3, 1, evals), *m = nn_view(c, 6, 1, mass);
    nn_tensor *coef = nn_matmul_t(c, phi, 1, nn_mul(c, x[0], m), 0);           /* 3 by C */
    nn_tensor *t = nn_clamp_min(c, x[1], 1e-8f);                                /* 1 by C */
    nn_tensor *scale = nn_exp(c, nn_scale(c, nn_matmul(c, lam, t), -1.0f));    /* 3 by C */
    return nn_matmul(c, phi, nn_mul(c, coef, scale));                          /* 6 by C */
}


/* The unfused activation with the slope the fused checks use. */
static nn_tensor *nn_activate_ref(nn_ctx *c, nn_tensor *z, nn_activation act)
{
    return nn_activate(c, z, act, 0.1f);
}

static nn_mlp mlp_under_test;
static nn_tensor *mlp_input;
static nn_tensor *g_mlp(nn_ctx *c, nn_tensor **x)
{
    (void)x;
    return nn_mlp_forward(c, &mlp_under_test, nn_from(c, mlp_input->rows, mlp_input->cols, mlp_input->data));
}

/* Checks every parameter of an 8-layer MLP (tanh output). */
static void mlp_check(nn_activation hidden, const char *name)
{
    nn_params ps;
    nn_params_init(&ps);
    nn_mlp_config cfg = {.in = 3, .width = 10, .out = 2, .depth = 8, .hidden = hidden,
                         .output = NN_ACT_TANH, .leaky_slope = 0.1f, .seed = 11};
    CHECK_INT(nn_mlp_create(&mlp_under_test, &cfg, &ps, "mlp"), NEUV_OK);
    CHECK_INT(ps.n, 16);
    float xin[4 * 3];
    nn_tensor holder = {.rows = 4, .cols = 3, .data = xin};
    mlp_input = &holder;
    nn_ctx *ctx = nn_ctx_create(0);
    nn_tensor *out = NULL;
    /* Central differences are meaningless across a ReLU kink: draw inputs until
     * every pre-activation is at least 0.02 away from zero (a perturbation of
     * 1e-3 then cannot cross one). */
    for (int attempt = 0; attempt < 1000; attempt++) {
        for (int i = 0; i < 12; i++) xin[i] = (float)(2 * rng_uniform(&gen) - 1);
        nn_ctx_reset(ctx);
        out = g_mlp(ctx, NULL);
        if (closest_to_kink(out) >= 0.02f) break;
    }
    float w[8];
    for (int i = 0; i < 8; i++) w[i] = (float)(2 * rng_uniform(&gen) - 1);
    nn_tensor *loss = nn_sum(ctx, nn_mul(ctx, out, nn_from(ctx, 4, 2, w)), NN_ALL);
    nn_params_zero_grad(&ps);
    CHECK_INT(nn_backward(ctx, loss), NEUV_OK);
    double worst = 0;
    const float eps = 1e-3f;
    for (int k = 0; k < ps.n; k++) {
        nn_tensor *p = ps.t[k];
        for (long i = 0; i < (long)p->rows * p->cols; i++) {
            float keep = p->data[i];
            p->data[i] = keep + eps;
            nn_ctx_reset(ctx);
            double lp = weighted_output(g_mlp(ctx, NULL), w);
            p->data[i] = keep - eps;
            nn_ctx_reset(ctx);
            double lm = weighted_output(g_mlp(ctx, NULL), w);
            p->data[i] = keep;
            double num = (lp - lm) / (2.0 * eps), ana = p->grad[i];
            double r = fabs(ana - num) / (1e-3 + 1e-2 * fabs(num));
            if (r > worst) worst = r;
            if (r > 1) fprintf(stderr, "%s: %s[%ld]: analytic %.6g numeric %.6g\n", name, p->name, i, ana, num);
        }
    }
    CHECK(worst <= 1);
    printf("  %-28s worst error/tolerance %.3f (%zu parameters)\n", name, worst, nn_params_count(&ps));
    nn_ctx_free(ctx);
    nn_mlp_free(&mlp_under_test);
    nn_params_free(&ps);
}

/* Products large enough to be split across threads (row blocks, or column
 * blocks when the result is wide) match a double-precision reference, forward
 * and backward, for every transpose combination and sizes that are not
 * multiples of the block rounding. */
static void threaded_matmul_check(int m, int n, int k)
{
    nn_set_threads(2);
    for (int ta = 0; ta < 2; ta++)
        for (int tb = 0; tb < 2; tb++) {
            nn_params ps;
            nn_params_init(&ps);
            nn_tensor *a = nn_params_add(&ps, ta ? k : m, ta ? m : k, "a");
            nn_tensor *b = nn_params_add(&ps, tb ? n : k, tb ? k : n, "b");
            for (long i = 0; i < (long)m * k; i++) a->data[i] = (float)(2 * rng_uniform(&gen) - 1);
            for (long i = 0; i < (long)k * n; i++) b->data[i] = (float)(2 * rng_uniform(&gen) - 1);
            float *w = malloc((size_t)m * n * sizeof *w);
            for (long i = 0; i < (long)m * n; i++) w[i] = (float)(2 * rng_uniform(&gen) - 1);
            nn_ctx *ctx = nn_ctx_create(0);
            nn_tensor *c = nn_matmul_t(ctx, a, ta, b, tb);
            CHECK(c && c->rows == m && c->cols == n);
            CHECK_INT(nn_backward(ctx, nn_sum(ctx, nn_mul(ctx, c, nn_from(ctx, m, n, w)), NN_ALL)), NEUV_OK);
#define A_(i, p) ((double)(ta ? a->data[(long)(p) * m + (i)] : a->data[(long)(i) * k + (p)]))
#define B_(p, j) ((double)(tb ? b->data[(long)(j) * k + (p)] : b->data[(long)(p) * n + (j)]))
            double worst = 0;
            for (int i = 0; i < m; i += 7)
                for (int j = 0; j < n; j++) {
                    double r = 0;
                    for (int p = 0; p < k; p++) r += A_(i, p) * B_(p, j);
                    double e = fabs(c->data[(long)i * n + j] - r) / (1e-4 * (1 + fabs(r)));
                    if (e > worst) worst = e;
                }
            for (int i = 0; i < m; i += 5)      /* dA'(i, p) = sum_j W(i, j) B'(p, j) */
                for (int p = 0; p < k; p++) {
                    double r = 0;
                    for (int j = 0; j < n; j++) r += (double)w[(long)i * n + j] * B_(p, j);
                    double got = ta ? a->grad[(long)p * m + i] : a->grad[(long)i * k + p];
                    double e = fabs(got - r) / (1e-4 * (1 + fabs(r)));
                    if (e > worst) worst = e;
                }
            for (int p = 0; p < k; p += 3)      /* dB'(p, j) = sum_i A'(i, p) W(i, j) */
                for (int j = 0; j < n; j++) {
                    double r = 0;
                    for (int i = 0; i < m; i++) r += A_(i, p) * w[(long)i * n + j];
                    double got = tb ? b->grad[(long)j * k + p] : b->grad[(long)p * n + j];
                    double e = fabs(got - r) / (1e-4 * (1 + fabs(r)));
                    if (e > worst) worst = e;
                }
#undef A_
#undef B_
            CHECK(worst <= 1);
            printf("  threaded matmul %dx%dx%d ta=%d tb=%d  worst error/tolerance %.3f\n", m, n, k, ta, tb, worst);
            free(w);
            nn_ctx_free(ctx);
            nn_params_free(&ps);
        }
    nn_set_threads(1);
}

/* A layer's input x (rows by in), weights w (in by out, small) and bias b,
 * uniform random, as parameters of ps. */
static void random_layer(nn_params *ps, int rows, int in, int out, nn_tensor **x, nn_tensor **w, nn_tensor **b)
{
    nn_params_init(ps);
    *x = nn_params_add(ps, rows, in, "x");
    *w = nn_params_add(ps, in, out, "w");
    *b = nn_params_add(ps, 1, out, "b");
    for (long i = 0; i < (long)rows * in; i++) (*x)->data[i] = (float)(2 * rng_uniform(&gen) - 1);
    for (long i = 0; i < (long)in * out; i++) (*w)->data[i] = (float)((2 * rng_uniform(&gen) - 1) * 0.2);
    for (int i = 0; i < out; i++) (*b)->data[i] = (float)(2 * rng_uniform(&gen) - 1);
}

/* The fused layer on 2 threads (row blocks, split weight-gradient product)
 * agrees with the unfused ops on one thread: values and all three gradients. */
static void threaded_linear_check(int rows, int in, int out, nn_activation act)
{
    nn_params ps;
    nn_tensor *x, *w, *b;
    random_layer(&ps, rows, in, out, &x, &w, &b);
    float *wl = malloc((size_t)rows * out * sizeof *wl);
    for (long i = 0; i < (long)rows * out; i++) wl[i] = (float)(2 * rng_uniform(&gen) - 1);
    size_t nx = (size_t)rows * in, nw = (size_t)in * out;
    float *ref = malloc((size_t)rows * out * sizeof *ref), *rgx = malloc(nx * sizeof *rgx),
          *rgw = malloc(nw * sizeof *rgw), *rgb = malloc((size_t)out * sizeof *rgb);
    nn_ctx *ctx = nn_ctx_create(0);
    for (int pass = 0; pass < 2; pass++) {
        nn_set_threads(pass == 0 ? 1 : 2);
        nn_ctx_reset(ctx);
        nn_params_zero_grad(&ps);
        nn_tensor *y = pass == 0 ? nn_activate_ref(ctx, nn_add(ctx, nn_matmul(ctx, x, w), b), act)
                                 : nn_linear_act(ctx, x, w, b, act, 0.1f);
        CHECK(y != NULL);
        if (!y) break;
        CHECK_INT(nn_backward(ctx, nn_sum(ctx, nn_mul(ctx, y, nn_from(ctx, rows, out, wl)), NN_ALL)), NEUV_OK);
        if (pass == 0) {
            memcpy(ref, y->data, (size_t)rows * out * sizeof *ref);
            memcpy(rgx, x->grad, nx * sizeof *rgx);
            memcpy(rgw, w->grad, nw * sizeof *rgw);
            memcpy(rgb, b->grad, (size_t)out * sizeof *rgb);
            continue;
        }
        double worst = 0;
#define CMP(got, want, n) for (size_t i_ = 0; i_ < (size_t)(n); i_++) { \
            double e_ = fabs((double)(got)[i_] - (want)[i_]) / (1e-4 * (1 + fabs((want)[i_]))); \
            if (e_ > worst) worst = e_; }
        CMP(y->data, ref, (size_t)rows * out);
        CMP(x->grad, rgx, nx);
        CMP(w->grad, rgw, nw);
        CMP(b->grad, rgb, out);
#undef CMP
        CHECK(worst <= 1);
        printf("  threaded linear %dx%d->%d act %d vs unfused  worst error/tolerance %.3f\n", rows, in, out,
               (int)act, worst);
    }
    nn_set_threads(1);
    free(wl); free(ref); free(rgx); free(rgw); free(rgb);
    nn_ctx_free(ctx);
    nn_params_free(&ps);
}

/* Products split for 2 threads give the same bits when called inside a
 * parallel region (charts solved side by side), where their blocks run one
 * after another on the calling thread: a layer and a plain product, forward,
 * each computed at top level on 2 threads and by both threads of a region. */
static void nested_split_check(int rows, int in, int out)
{
    nn_params ps;
    nn_tensor *x, *w, *b;
    random_layer(&ps, rows, in, out, &x, &w, &b);
    size_t n = (size_t)rows * out;
    float *top = malloc(2 * n * sizeof *top), *inner = malloc(4 * n * sizeof *inner);
    nn_set_threads(2);
    nn_ctx *ctx = nn_ctx_create(0);
    nn_tensor *y = nn_linear_act(ctx, x, w, b, NN_ACT_LEAKY_RELU, 0.1f), *p = nn_matmul(ctx, x, w);
    CHECK(y && p);
    if (y && p) { memcpy(top, y->data, n * sizeof *top); memcpy(top + n, p->data, n * sizeof *top); }
    nn_ctx_free(ctx);
    int ran = 0;
#pragma omp parallel num_threads(2) reduction(+ : ran)
    {
        int t = omp_get_thread_num();
        nn_ctx *c2 = nn_ctx_create(0);
        nn_tensor *y2 = c2 ? nn_linear_act(c2, x, w, b, NN_ACT_LEAKY_RELU, 0.1f) : NULL;
        nn_tensor *p2 = c2 ? nn_matmul(c2, x, w) : NULL;
        if (y2 && p2 && t < 2) {
            memcpy(inner + 2 * n * t, y2->data, n * sizeof *inner);
            memcpy(inner + 2 * n * t + n, p2->data, n * sizeof *inner);
            ran++;
        }
        nn_ctx_free(c2);
    }
    nn_set_threads(1);
    CHECK_INT(ran, 2);
    for (int t = 0; t < ran && t < 2; t++) CHECK(memcmp(top, inner + 2 * n * t, 2 * n * sizeof *top) == 0);
    printf("  %dx%d->%d split for 2 threads, inside a parallel region: %s\n", rows, in, out,
           ran == 2 && memcmp(top, inner, 2 * n * sizeof *top) == 0 ? "same bits" : "DIFFERENT");
    free(top); free(inner);
    nn_params_free(&ps);
}

int main(void)
{
    rng_seed(&gen, 2024);
    const float E = 5e-3f;
    /* Shapes of the second operand of broadcasting ops: same, row, column, scalar. */
    const int bshape[4][2] = {{4, 5}, {1, 5}, {4, 1}, {1, 1}};
    const char *bname[4] = {"same", "row", "col", "scalar"};
    struct { const char *name; build_fn f; } bin[4] = {{"add", g_add}, {"sub", g_sub}, {"mul", g_mul}, {"div", g_div}};
    for (int o = 0; o < 4; o++)
        for (int s = 0; s < 4; s++) {
            input_spec sp[2] = {{4, 5, -1, 1, 0, 0}, {bshape[s][0], bshape[s][1], -1.5f, 1.5f, 0, 0}};
            if (bin[o].f == g_div) { sp[1].lo = 0.5f; sp[1].hi = 2.0f; }
            char nm[64];
            snprintf(nm, sizeof nm, "%s (%s)", bin[o].name, bname[s]);
            gradcheck(nm, bin[o].f, 2, sp, E);
        }
    for (ta_flag = 0; ta_flag < 2; ta_flag++)
        for (tb_flag = 0; tb_flag < 2; tb_flag++) {
            input_spec sp[2] = {{ta_flag ? 4 : 3, ta_flag ? 3 : 4, -1, 1, 0, 0},
                                {tb_flag ? 5 : 4, tb_flag ? 4 : 5, -1, 1, 0, 0}};
            char nm[64];
            snprintf(nm, sizeof nm, "matmul (ta=%d tb=%d)", ta_flag, tb_flag);
            gradcheck(nm, g_matmul, 2, sp, E);
        }
    input_spec one = {4, 5, -1, 1, 0, 0};
    gradcheck("mul (a*a, same tensor)", g_square_self, 1, &one, E);
    gradcheck("add_const", g_add_const, 1, &one, E);
    gradcheck("scale", g_scale, 1, &one, E);
    const int axes[3] = {NN_ALL, NN_ROWS, NN_COLS};
    for (int a = 0; a < 3; a++) {
        axis_flag = axes[a];
        char nm[64];
        snprintf(nm, sizeof nm, "sum (axis %d)", axes[a]);
        gradcheck(nm, g_sum, 1, &one, E);
        snprintf(nm, sizeof nm, "mean (axis %d)", axes[a]);
        gradcheck(nm, g_mean, 1, &one, E);
    }
    input_spec cc[2] = {{4, 2, -1, 1, 0, 0}, {4, 3, -1, 1, 0, 0}};
    gradcheck("concat_cols", g_concat, 2, cc, E);
    gradcheck("slice_cols", g_slice, 1, &one, E);
    input_spec g4 = {4, 3, -1, 1, 0, 0}, s7 = {7, 3, -1, 1, 0, 0};
    gradcheck("gather_rows (repeats)", g_gather, 1, &g4, E);
    gradcheck("scatter_add_rows (repeats)", g_scatter, 1, &s7, E);
    {
        /* 5 by 4 sparse matrix with an empty row and a repeated column. */
        int rs[6] = {0, 2, 2, 5, 6, 7};
        int col[7] = {0, 3, 1, 2, 3, 0, 3};
        double val[7] = {0.5, -1.0, 2.0, 0.25, -0.75, 1.5, 0.3};
        nn_csr sm = {5, 4, rs, col, val};
        CHECK_INT(nn_sparse_from_csr(&sm, &sparse), NEUV_OK);
        input_spec sp = {4, 3, -1, 1, 0, 0};
        gradcheck("spmm", g_spmm, 1, &sp, E);
        nn_sparse_free(&sparse);
    }
    input_spec kink = {4, 5, -1, 1, 0.05f, 0}; /* |x| >= 0.05: a 5e-3 step cannot cross 0 */
    gradcheck("relu", g_relu, 1, &kink, E);
    gradcheck("leaky_relu", g_leaky, 1, &kink, E);
    gradcheck("tanh", g_tanh, 1, &one, E);
    gradcheck("sigmoid", g_sigmoid, 1, &one, E);
    input_spec wide = {4, 5, -2, 2, 0, 0};
    gradcheck("softmax_rows", g_softmax, 1, &wide, E);
    gradcheck("exp", g_exp, 1, &one, E);
    input_spec pos = {4, 5, 0.3f, 2.0f, 0, 0};
    gradcheck("log", g_log, 1, &pos, E);
    gradcheck("sqrt", g_sqrt, 1, &pos, E);
    gradcheck("square", g_square, 1, &one, E);
    gradcheck("row_norm", g_row_norm, 1, &one, E);
    input_spec two[2] = {{4, 5, -1, 1, 0, 0}, {4, 5, -1, 1, 0, 0}};
    gradcheck("row_dot", g_row_dot, 2, two, E);
    gradcheck("row_dot (a.a, same tensor)", g_row_dot_self, 1, &one, E);
    gradcheck("row_cosine", g_row_cosine, 2, two, E);
    input_spec clampin = {4, 5, -1, 1, 0.05f, 0.1f};
    gradcheck("clamp_min", g_clamp, 1, &clampin, E);
    {
        const char *names[4] = {"linear (none)", "linear (relu)", "linear (leaky_relu)", "linear (tanh)"};
        for (int a = 0; a < 4; a++) {
            act_flag = (nn_activation)a;
            input_spec sp[3] = {{5, 3, -1, 1, 0, 0}, {3, 4, -0.6f, 0.6f, 0, 0}, {1, 4, -0.5f, 0.5f, 0, 0}};
            accept_inputs = linear_away_from_kink;
            gradcheck(names[a], g_linear, 3, sp, E);
            accept_inputs = NULL;
        }
    }
    {
        for (int i = 0; i < 18; i++) evecs[i] = (float)(2 * rng_uniform(&gen) - 1);
        for (int i = 0; i < 3; i++) evals[i] = (float)i * 0.8f;
        for (int i = 0; i < 6; i++) mass[i] = 0.5f + (float)rng_uniform(&gen);
        input_spec sp[2] = {{6, 4, -1, 1, 0, 0}, {1, 4, 0.2f, 1.5f, 0, 0}};
        gradcheck("diffusion chain", g_diffusion, 2, sp, E);
    }
    /* Every op of the enum was the output of at least one check. */
    for (int op = 1; op < NN_OP_COUNT; op++) {
        if (!ops_seen[op]) fprintf(stderr, "op %s has no gradient check\n", nn_op_name((nn_op)op));
        CHECK(ops_seen[op]);
    }
    threaded_matmul_check(301, 77, 190);  /* split by rows */
    threaded_matmul_check(45, 333, 280);  /* split by columns */
    threaded_linear_check(1000, 70, 90, NN_ACT_LEAKY_RELU); /* 15.6 row blocks: a partial last one */
    threaded_linear_check(777, 64, 100, NN_ACT_TANH);
    threaded_linear_check(700, 100, 64, NN_ACT_NONE);
    nested_split_check(3000, 96, 96);
    mlp_check(NN_ACT_LEAKY_RELU, "8-layer MLP (leaky, tanh out)");
    mlp_check(NN_ACT_TANH, "8-layer MLP (tanh, tanh out)");

    /* Errors: bad shapes give NULL, a message, and a failing backward; no crash. */
    {
        nn_ctx *ctx = nn_ctx_create(0);
        nn_tensor *a = nn_fill(ctx, 3, 4, 1.0f), *b = nn_fill(ctx, 2, 4, 1.0f);
        CHECK(nn_add(ctx, a, b) == NULL);
        CHECK(nn_ctx_status(ctx) == NEUV_ERR_INPUT);
        CHECK(strstr(neuv_last_error(), "do not broadcast") != NULL);
        CHECK(nn_tanh(ctx, nn_matmul(ctx, a, a)) == NULL);
        CHECK(strstr(neuv_last_error(), "do not broadcast") != NULL); /* first error kept */
        CHECK_INT(nn_backward(ctx, nn_sum(ctx, a, NN_ALL)), NEUV_ERR_INPUT);
        nn_ctx_reset(ctx);
        CHECK_INT(nn_ctx_status(ctx), NEUV_OK);
        int bad[2] = {0, 3};
        CHECK(nn_gather_rows(ctx, nn_fill(ctx, 3, 2, 0), bad, 2) == NULL);
        CHECK(strstr(neuv_last_error(), "index[1] = 3") != NULL);
        nn_ctx_reset(ctx);
        CHECK(nn_slice_cols(ctx, nn_fill(ctx, 3, 2, 0), 1, 2) == NULL);
        nn_ctx_free(ctx);
    }
    return check_report("test_nn_grad");
}
