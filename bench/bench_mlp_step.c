/* One training step (forward + backward + Adam) of the paper-size MLP against
 * plain cblas_sgemm calls of exactly the same shapes, in the same run.
 *
 *   cmake --build build --target bench_mlp_step && ./build/bench/bench_mlp_step [threads] [runs]
 *
 * The MLP: 8 linear layers, input 3 + psi (psi = 128), width 448, output 2,
 * LeakyReLU hidden, tanh output (about 1.27M parameters), batch 4096 points,
 * mean squared error loss. Both timings count the same flops: those of the
 * sgemm calls the step makes (forward, weight gradients, input gradients of all
 * layers but the first, whose input needs no gradient), so the ratio of rates
 * is the ratio of times. Medians of `runs` (default 7) after 2 warm-up runs;
 * a step and a reference pass alternate so both see the same machine load. */
#include <cblas.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "core/timer.h"
#include "nn/adam.h"
#include "nn/mlp.h"
#include "nn/nn.h"

enum { BATCH = 4096, PSI = 128, IN = 3 + PSI, WIDTH = 448, OUT = 2, DEPTH = 8, MAX_RUNS = 64 };

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median(double *t, int n)
{
    qsort(t, (size_t)n, sizeof *t, cmp_double);
    return n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]);
}

int main(int argc, char **argv)
{
    int threads = argc > 1 ? atoi(argv[1]) : 0;
    int runs = argc > 2 ? atoi(argv[2]) : 7;
    if (runs < 1 || runs > MAX_RUNS) runs = 7;
    nn_set_threads(threads);

    int in_of[DEPTH], out_of[DEPTH];
    double flops = 0;
    for (int l = 0; l < DEPTH; l++) {
        in_of[l] = l == 0 ? IN : WIDTH;
        out_of[l] = l == DEPTH - 1 ? OUT : WIDTH;
        double f = 2.0 * BATCH * in_of[l] * out_of[l];
        flops += l == 0 ? 2 * f : 3 * f; /* forward + dW (+ dX) */
    }

    nn_params ps;
    nn_params_init(&ps);
    nn_mlp mlp;
    nn_mlp_config cfg = {.in = IN, .width = WIDTH, .out = OUT, .depth = DEPTH,
                         .hidden = NN_ACT_LEAKY_RELU, .output = NN_ACT_TANH, .leaky_slope = 0.01f, .seed = 1};
    if (nn_mlp_create(&mlp, &cfg, &ps, "mlp") != NEUV_OK) { fprintf(stderr, "%s\n", neuv_last_error()); return 1; }
    nn_adam adam;
    nn_adam_init(&adam, &ps, NULL);
    float *x = malloc((size_t)BATCH * IN * sizeof(float)), *y = malloc((size_t)BATCH * OUT * sizeof(float));
    rng r;
    rng_seed(&r, 5);
    for (long i = 0; i < (long)BATCH * IN; i++) x[i] = (float)(2 * rng_uniform(&r) - 1);
    for (long i = 0; i < (long)BATCH * OUT; i++) y[i] = (float)(rng_uniform(&r) - 0.5);
    nn_ctx *ctx = nn_ctx_create(0);

    /* Reference buffers: the activations, gradients and weights of the same shapes. */
    float *act[DEPTH + 1], *grad[DEPTH + 1], *w[DEPTH], *gw[DEPTH];
    for (int l = 0; l <= DEPTH; l++) {
        int c = l == 0 ? IN : out_of[l - 1];
        act[l] = calloc((size_t)BATCH * c, sizeof(float));
        grad[l] = calloc((size_t)BATCH * c, sizeof(float));
        for (long i = 0; i < (long)BATCH * c; i++) act[l][i] = grad[l][i] = (float)(rng_uniform(&r) - 0.5);
    }
    for (int l = 0; l < DEPTH; l++) {
        w[l] = malloc((size_t)in_of[l] * out_of[l] * sizeof(float));
        gw[l] = calloc((size_t)in_of[l] * out_of[l], sizeof(float));
        memcpy(w[l], mlp.layers[l].w->data, (size_t)in_of[l] * out_of[l] * sizeof(float));
    }

    /* Step and reference alternate, so both see the same machine load. */
    double t_step[MAX_RUNS], t_ref[MAX_RUNS];
    float last_loss = 0;
    size_t grow_before = 0;
    for (int run = -2; run < runs; run++) {
        if (run == 0) grow_before = nn_ctx_grow_count(ctx);
        double t0 = now_seconds();
        nn_ctx_reset(ctx);
        nn_tensor *out = nn_mlp_forward(ctx, &mlp, nn_from(ctx, BATCH, IN, x));
        nn_tensor *loss = nn_mean(ctx, nn_square(ctx, nn_sub(ctx, out, nn_from(ctx, BATCH, OUT, y))), NN_ALL);
        nn_params_zero_grad(&ps);
        if (nn_backward(ctx, loss) != NEUV_OK) { fprintf(stderr, "%s\n", neuv_last_error()); return 1; }
        nn_adam_step(&adam);
        double t1 = now_seconds();
        if (run >= 0) t_step[run] = t1 - t0;
        last_loss = loss->data[0];

        /* Plain OpenBLAS (its own threads), the same sgemm calls. */
        t0 = now_seconds();
        for (int l = 0; l < DEPTH; l++)
            cblas_sgemm(CblasRowMajor, CblasNoTrans, CblasNoTrans, BATCH, out_of[l], in_of[l], 1.0f, act[l],
                        in_of[l], w[l], out_of[l], 0.0f, act[l + 1], out_of[l]);
        for (int l = DEPTH - 1; l >= 0; l--) {
            cblas_sgemm(CblasRowMajor, CblasTrans, CblasNoTrans, in_of[l], out_of[l], BATCH, 1.0f, act[l],
                        in_of[l], grad[l + 1], out_of[l], 1.0f, gw[l], out_of[l]);
            if (l > 0)
                cblas_sgemm(CblasRowMajor, CblasNoTrans, CblasTrans, BATCH, in_of[l], out_of[l], 1.0f,
                            grad[l + 1], out_of[l], w[l], out_of[l], 0.0f, grad[l], in_of[l]);
        }
        t1 = now_seconds();
        if (run >= 0) t_ref[run] = t1 - t0;
    }
    size_t grown = nn_ctx_grow_count(ctx) - grow_before;
    double ms = median(t_step, runs), mr = median(t_ref, runs);
    printf("MLP %d layers, %d -> %d -> %d, %zu parameters, batch %d, %d threads, median of %d\n", DEPTH, IN,
           WIDTH, OUT, nn_params_count(&ps), BATCH, omp_get_max_threads(), runs);
    printf("sgemm flops per step: %.3f GFLOP (loss %.4f)\n", flops * 1e-9, last_loss);
    printf("training step (fwd+bwd+Adam): %8.2f ms  %7.1f GFLOP/s\n", ms * 1e3, flops / ms * 1e-9);
    printf("plain cblas_sgemm, same shapes: %6.2f ms  %7.1f GFLOP/s\n", mr * 1e3, flops / mr * 1e-9);
    printf("step / sgemm rate: %.1f%%   (arena allocations after warm-up: %zu)\n", 100.0 * mr / ms, grown);
    for (int l = 0; l <= DEPTH; l++) { free(act[l]); free(grad[l]); }
    for (int l = 0; l < DEPTH; l++) { free(w[l]); free(gw[l]); }
    free(x); free(y);
    nn_ctx_free(ctx);
    nn_adam_free(&adam);
    nn_mlp_free(&mlp);
    nn_params_free(&ps);
    return 0;
}
