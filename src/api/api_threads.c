/* The OpenMP threads of the calls whose options have no `threads` field. */
#include "neuv/neuv.h"
#include "nn/nn.h"

void neuv_set_threads(int threads)
{
    if (threads >= 1) nn_set_threads(threads);
}
