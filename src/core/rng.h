/* Seeded pseudo-random numbers (xoshiro256**, seeded by splitmix64):
 * the same seed gives the same sequence on every machine. */
#ifndef NEUV_CORE_RNG_H
#define NEUV_CORE_RNG_H

#include <stdint.h>

typedef struct rng { uint64_t s[4]; } rng;

void rng_seed(rng *r, uint64_t seed);
uint64_t rng_next(rng *r);
double rng_uniform(rng *r);          /* [0, 1) */
int rng_below(rng *r, int n);        /* [0, n) */
double rng_normal(rng *r);           /* standard normal (Box-Muller) */

#endif
