/* A test allocator for neuv_set_allocator that counts live blocks and
 * fails the Nth allocation (alloc or realloc call) after arm(N); arm(0)
 * fails none. Only the Nth fails, not every one after it, so a failure the
 * library swallows shows up as a success. Header-only, for the tests that
 * run calls under failing allocations. */
#ifndef NEUV_TESTS_FAILING_ALLOC_H
#define NEUV_TESTS_FAILING_ALLOC_H

#include <stdatomic.h>
#include <stdlib.h>

#include "neuv/neuv.h"

static atomic_long n_calls; /* alloc and realloc calls since arm() */
static atomic_long n_live;  /* blocks allocated and not yet freed */
static atomic_long fail_at; /* the call that fails; 0: none */

static void *count_alloc(void *user, size_t size)
{
    (void)user;
    if (atomic_fetch_add(&n_calls, 1) + 1 == atomic_load(&fail_at)) return NULL;
    void *p = malloc(size);
    if (p) atomic_fetch_add(&n_live, 1);
    return p;
}

static void *count_realloc(void *user, void *ptr, size_t size)
{
    (void)user;
    if (atomic_fetch_add(&n_calls, 1) + 1 == atomic_load(&fail_at)) return NULL;
    return realloc(ptr, size);
}

static void count_free(void *user, void *ptr)
{
    (void)user;
    atomic_fetch_sub(&n_live, 1);
    free(ptr);
}

static void arm(long n)
{
    atomic_store(&n_calls, 0);
    atomic_store(&fail_at, n);
}

/* The allocator to pass to neuv_set_allocator. */
static const neuv_allocator failing_allocator = {count_alloc, count_realloc, count_free, NULL};

#endif
