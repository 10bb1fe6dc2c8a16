/* Adam (Kingma & Ba 2015, Algorithm 1) with global-norm gradient clipping. */
#include "nn/adam.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/mem.h"

nn_adam_config nn_adam_defaults(void)
{
    nn_adam_config c = {.lr = 1e-3f, .beta1 = 0.9f, .beta2 = 0.999f, .eps = 1e-8f};
    return c;
}

void nn_adam_free(nn_adam *opt)
{
    if (!opt) return;
    if (opt->m)
        for (int i = 0; i < opt->params->n; i++) mem_free(opt->m[i]);
    if (opt->v)
        for (int i = 0; i < opt->params->n; i++) mem_free(opt->v[i]);
    mem_free(opt->m);
    mem_free(opt->v);
    opt->m = opt->v = NULL;
}

neuv_status nn_adam_init(nn_adam *opt, nn_params *params, const nn_adam_config *cfg)
{
    memset(opt, 0, sizeof *opt);
    opt->cfg = cfg ? *cfg : nn_adam_defaults();
    if (!(opt->cfg.lr > 0) || !(opt->cfg.beta1 >= 0 && opt->cfg.beta1 < 1) ||
        !(opt->cfg.beta2 >= 0 && opt->cfg.beta2 < 1) || !(opt->cfg.eps > 0) || !(opt->cfg.clip_norm >= 0))
        return error_set(NEUV_ERR_INPUT, "Adam: lr %g, betas %g/%g, eps %g, clip %g are not usable",
                         opt->cfg.lr, opt->cfg.beta1, opt->cfg.beta2, opt->cfg.eps, opt->cfg.clip_norm);
    opt->params = params;
    int n = params->n;
    opt->m = mem_calloc(n ? (size_t)n : 1, sizeof *opt->m);
    opt->v = mem_calloc(n ? (size_t)n : 1, sizeof *opt->v);
    if (!opt->m || !opt->v) { nn_adam_free(opt); return error_nomem("Adam state"); }
    for (int i = 0; i < n; i++) {
        size_t sz = (size_t)params->t[i]->rows * (size_t)params->t[i]->cols;
        opt->m[i] = mem_calloc(sz, sizeof(float));
        opt->v[i] = mem_calloc(sz, sizeof(float));
        if (!opt->m[i] || !opt->v[i]) { nn_adam_free(opt); return error_nomem("Adam state"); }
    }
    return NEUV_OK;
}

void nn_adam_step(nn_adam *opt)
{
    nn_params *ps = opt->params;
    opt->t++;
    /* Global gradient norm, summed parameter by parameter in a fixed order. */
    double sq = 0;
    for (int i = 0; i < ps->n; i++) {
        const float *g = ps->t[i]->grad;
        long n = (long)ps->t[i]->rows * ps->t[i]->cols;
        double s = 0;
        for (long k = 0; k < n; k++) s += (double)g[k] * g[k];
        sq += s;
    }
    double norm = sqrt(sq);
    opt->last_grad_norm = (float)norm;
    float clip = 1.0f;
    if (opt->cfg.clip_norm > 0 && norm > opt->cfg.clip_norm) clip = (float)(opt->cfg.clip_norm / norm);
    float lr = opt->cfg.schedule ? opt->cfg.schedule(opt->cfg.schedule_user, opt->t, opt->cfg.lr) : opt->cfg.lr;
    opt->last_lr = lr;
    float b1 = opt->cfg.beta1, b2 = opt->cfg.beta2, eps = opt->cfg.eps;
    /* Bias corrections folded into the step size: theta -= lr * m_hat / (sqrt(v_hat) + eps). */
    double c1 = 1.0 - pow(b1, (double)opt->t), c2 = 1.0 - pow(b2, (double)opt->t);
    float inv_c1 = (float)(1.0 / c1), inv_sqrt_c2 = (float)(1.0 / sqrt(c2));
    for (int i = 0; i < ps->n; i++) {
        float *w = ps->t[i]->data, *m = opt->m[i], *v = opt->v[i];
        const float *g = ps->t[i]->grad;
        long n = (long)ps->t[i]->rows * ps->t[i]->cols;
#pragma omp parallel for if (n > 32768) schedule(static)
        for (long k = 0; k < n; k++) {
            float gk = g[k] * clip;
            m[k] = b1 * m[k] + (1 - b1) * gk;
            v[k] = b2 * v[k] + (1 - b2) * gk * gk;
            w[k] -= lr * (m[k] * inv_c1) / (sqrtf(v[k]) * inv_sqrt_c2 + eps);
        }
    }
}
