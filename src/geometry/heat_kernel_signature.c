/* Heat kernel signature features. See heat_kernel_signature.h. */
#include <math.h>
#include <stdlib.h>

#include "core/error.h"

#include "core/mem.h"
#include "geometry/heat_kernel_signature.h"

void heat_kernel_times(int k, const double *evals, int n, double *times)
{
    double lmax = 0.0;
    for (int a = 0; a < k; a++)
        if (evals[a] > lmax) lmax = evals[a];
    double lmin = 0.0;
    for (int a = 0; a < k; a++)
        if (evals[a] > 1e-8 * lmax && (lmin == 0.0 || evals[a] < lmin)) lmin = evals[a];
    if (!(lmax > 0) || !(lmin > 0)) {
        for (int j = 0; j < n; j++) times[j] = 1.0;
        return;
    }
    double lo = log(4.0 * log(10.0) / lmax), hi = log(4.0 * log(10.0) / lmin);
    for (int j = 0; j < n; j++) times[j] = exp(n > 1 ? lo + (hi - lo) * j / (n - 1) : lo);
}

neuv_status heat_kernel_signature(int nv, int k, const double *evals, const double *evecs, double area,
                                  int n, const double *times, double *hks)
{
    /* w[a][j] = A exp(−λ_a t_j), so the per-vertex loop is multiply-adds only. */
    double *w = mem_alloc(((size_t)k * n + 1) * sizeof *w);
    if (!w) return error_nomem("heat kernel signature");
    for (int a = 0; a < k; a++)
        for (int j = 0; j < n; j++)
            /* Zero eigenvalues (round-off slightly negative) decay as exp(0). */
            w[(size_t)a * n + j] = area * exp(-fmax(evals[a], 0.0) * times[j]);
    for (int i = 0; i < nv; i++) {
        double *h = hks + (size_t)i * n;
        for (int j = 0; j < n; j++) h[j] = 0.0;
        for (int a = 0; a < k; a++) {
            double p = evecs[(size_t)i * k + a], p2 = p * p;
            const double *wa = w + (size_t)a * n;
            for (int j = 0; j < n; j++) h[j] += wa[j] * p2;
        }
    }
    mem_free(w);
    return NEUV_OK;
}
