/* One switch for the engine's threads: OpenMP loops and OpenBLAS products. */
#include "nn/nn.h"

#include <cblas.h>
#include <omp.h>

/* OpenMP keeps the thread count per calling thread, so two unwraps on two
 * threads each keep their own. OpenBLAS always runs on one thread: every
 * product worth splitting is split by the engine itself (ops_linalg.c), and
 * OpenBLAS's own split of a
 * product depends on its thread count, which made results differ between
 * --threads 1 and 2 at the last bits with some CPU kernels (OPENBLAS_CORETYPE=
 * Haswell: a surface model's atlas differed from the 9th decimal). */
void nn_set_threads(int n)
{
    if (n > 0) omp_set_num_threads(n);
    openblas_set_num_threads(1);
}

