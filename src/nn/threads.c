/* One switch for the engine's threads: OpenMP loops and OpenBLAS products. */
#include "nn/nn.h"

#include <cblas.h>
#include <omp.h>

static int nn_threads;

void nn_set_threads(int n)
{
    if (n <= 0) n = omp_get_num_procs();
    nn_threads = n;
    omp_set_num_threads(n);
    openblas_set_num_threads(n);
}

int nn_get_threads(void) { return nn_threads > 0 ? nn_threads : omp_get_max_threads(); }
