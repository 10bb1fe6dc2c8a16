/* One switch for the engine's threads: OpenMP loops and OpenBLAS products. */
#include "nn/nn.h"

#include <cblas.h>
#include <omp.h>

/* OpenMP keeps the thread count per calling thread, so two unwraps on two
 * threads each keep their own; OpenBLAS's count is process-wide. */
void nn_set_threads(int n)
{
    if (n <= 0) n = omp_get_num_procs();
    omp_set_num_threads(n);
    openblas_set_num_threads(n);
}

