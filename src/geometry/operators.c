/* Computes the geometry operator bundle. See operators.h. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/log.h"
#include "core/mem.h"
#include "core/timer.h"
#include "geometry/cotan_laplacian.h"
#include "geometry/eigenbasis.h"
#include "geometry/heat_kernel_signature.h"
#include "geometry/lumped_mass.h"
#include "geometry/operators.h"
#include "geometry/spatial_gradient.h"
#include "geometry/tangent_frames.h"

operators_params operators_default_params(void)
{
    operators_params p = {OPERATORS_DEFAULT_K, OPERATORS_DEFAULT_HKS};
    return p;
}

void operators_free(operators *ops)
{
    if (!ops) return;
    sparse_free(&ops->L);
    sparse_free(&ops->grad_x);
    sparse_free(&ops->grad_y);
    mem_free(ops->mass);
    mem_free(ops->evals);
    mem_free(ops->evecs);
    mem_free(ops->frames);
    mem_free(ops->hks);
    mem_free(ops->hks_times);
    memset(ops, 0, sizeof *ops);
}

neuv_status operators_compute(const neuv_mesh *m, const operators_params *params, operators *ops)
{
    memset(ops, 0, sizeof *ops);
    operators_params p = params ? *params : operators_default_params();
    if (!m || m->nv <= 0 || m->nf <= 0)
        return error_set(NEUV_ERR_INPUT, "operators need a mesh with faces (got %d vertices, %d faces)",
                         m ? m->nv : 0, m ? m->nf : 0);
    if (p.k < 1 || p.n_hks < 1)
        return error_set(NEUV_ERR_INPUT, "operators: k (%d) and the number of HKS times (%d) must be positive",
                         p.k, p.n_hks);
    for (size_t i = 0; i < (size_t)m->nv * 3; i++)
        if (!isfinite(m->pos[i])) return error_set(NEUV_ERR_INPUT, "vertex %zu has a non-finite coordinate", i / 3);
    for (size_t i = 0; i < (size_t)m->nf * 3; i++)
        if (m->tri[i] < 0 || m->tri[i] >= m->nv)
            return error_set(NEUV_ERR_INPUT, "face %zu uses vertex %d of %d", i / 3, m->tri[i], m->nv);

    int nv = m->nv, k = p.k < nv ? p.k : nv;
    if (k < p.k) log_message(NEUV_LOG_INFO, "operators: %d eigenpairs asked of a %d-vertex mesh, computing %d", p.k, nv, k);
    ops->nv = nv;
    ops->k = k;
    ops->n_hks = p.n_hks;
    double t_all = now_seconds(), t0 = t_all;
    neuv_status s;

    log_progress("operators", 0.0, "laplacian");
    ops->mass = mem_alloc((size_t)nv * sizeof *ops->mass);
    ops->evals = mem_alloc((size_t)k * sizeof *ops->evals);
    ops->evecs = mem_alloc((size_t)nv * k * sizeof *ops->evecs);
    ops->frames = mem_alloc((size_t)nv * 9 * sizeof *ops->frames);
    ops->hks = mem_alloc((size_t)nv * p.n_hks * sizeof *ops->hks);
    ops->hks_times = mem_alloc((size_t)p.n_hks * sizeof *ops->hks_times);
    if (!ops->mass || !ops->evals || !ops->evecs || !ops->frames || !ops->hks || !ops->hks_times) {
        s = error_nomem("geometry operators");
        goto fail;
    }
    if ((s = cotan_laplacian(m, &ops->L))) goto fail;
    lumped_mass(m, ops->mass);
    ops->seconds.laplacian = now_seconds() - t0;

    log_progress("operators", 0.1, "eigenpairs (k = %d)", k);
    eigenbasis_info info;
    if ((s = eigenbasis(&ops->L, ops->mass, k, ops->evals, ops->evecs, &info))) goto fail;
    ops->sigma = info.sigma;
    ops->seconds.factor = info.factor_seconds;
    ops->seconds.eigen = info.solve_seconds;
    log_message(NEUV_LOG_DEBUG, "eigenbasis: %s, sigma %.3g, %d restarts, %d solves, M-orthonormality error %.2g",
             info.dense ? "dense" : "ARPACK shift-invert", info.sigma, info.restarts, info.op_applies, info.orth_error);

    log_progress("operators", 0.8, "gradients");
    t0 = now_seconds();
    tangent_frames(m, ops->frames);
    if ((s = spatial_gradient(m, ops->frames, &ops->grad_x, &ops->grad_y))) goto fail;
    ops->seconds.gradients = now_seconds() - t0;

    log_progress("operators", 0.9, "heat kernel signature");
    t0 = now_seconds();
    double area = 0.0;
    for (int i = 0; i < nv; i++) area += ops->mass[i];
    heat_kernel_times(k, ops->evals, p.n_hks, ops->hks_times);
    if ((s = heat_kernel_signature(nv, k, ops->evals, ops->evecs, area, p.n_hks, ops->hks_times, ops->hks))) goto fail;
    ops->seconds.hks = now_seconds() - t0;
    ops->seconds.total = now_seconds() - t_all;
    log_progress("operators", 1.0, NULL);
    return NEUV_OK;

fail:
    operators_free(ops);
    return s;
}
