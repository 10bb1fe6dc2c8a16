#include "mesh/edge_map.h"

#include <stdlib.h>

#include "core/mem.h"

static uint64_t edge_key(int a, int b) { return ((uint64_t)(uint32_t)a << 32) | (uint32_t)b; }

/* A 64-bit mixer (splitmix64 finalizer) so that neighbouring keys from a
 * regular grid do not cluster in the table. */
static size_t edge_hash(uint64_t k, size_t mask)
{
    k ^= k >> 30; k *= 0xbf58476d1ce4e5b9ULL;
    k ^= k >> 27; k *= 0x94d049bb133111ebULL;
    k ^= k >> 31;
    return (size_t)k & mask;
}

static int edge_map_alloc(edge_map *e, size_t cap)
{
    e->keys = mem_alloc(sizeof(uint64_t) * cap);
    e->vals = mem_alloc(sizeof(int) * cap);
    if (!e->keys || !e->vals) { mem_free(e->keys); mem_free(e->vals); e->keys = NULL; e->vals = NULL; return -1; }
    for (size_t i = 0; i < cap; i++) e->keys[i] = EDGE_MAP_EMPTY;
    e->cap = cap;
    e->count = 0;
    return 0;
}

int edge_map_init(edge_map *e, size_t expected)
{
    size_t cap = 16;
    while (cap < 2 * expected + 2) cap <<= 1;
    return edge_map_alloc(e, cap);
}

void edge_map_free(edge_map *e)
{
    mem_free(e->keys); mem_free(e->vals);
    e->keys = NULL; e->vals = NULL;
    e->cap = e->count = 0;
}

int edge_map_get(const edge_map *e, int a, int b)
{
    uint64_t k = edge_key(a, b);
    size_t mask = e->cap - 1;
    for (size_t i = edge_hash(k, mask);; i = (i + 1) & mask) {
        if (e->keys[i] == k) return e->vals[i];
        if (e->keys[i] == EDGE_MAP_EMPTY) return -1;
    }
}

static int edge_map_grow(edge_map *e)
{
    edge_map bigger;
    if (edge_map_alloc(&bigger, e->cap * 2) != 0) return -1;
    size_t mask = bigger.cap - 1;
    for (size_t s = 0; s < e->cap; s++) {
        if (e->keys[s] == EDGE_MAP_EMPTY) continue;
        size_t i = edge_hash(e->keys[s], mask);
        while (bigger.keys[i] != EDGE_MAP_EMPTY) i = (i + 1) & mask;
        bigger.keys[i] = e->keys[s];
        bigger.vals[i] = e->vals[s];
    }
    bigger.count = e->count;
    edge_map_free(e);
    *e = bigger;
    return 0;
}

int *edge_map_slot(edge_map *e, int a, int b, int init, int *inserted)
{
    /* Keep the load under one half so probe chains stay short. */
    if (2 * (e->count + 1) > e->cap && edge_map_grow(e) != 0) return NULL;
    uint64_t k = edge_key(a, b);
    size_t mask = e->cap - 1;
    size_t i = edge_hash(k, mask);
    while (e->keys[i] != EDGE_MAP_EMPTY) {
        if (e->keys[i] == k) { if (inserted) *inserted = 0; return &e->vals[i]; }
        i = (i + 1) & mask;
    }
    e->keys[i] = k;
    e->vals[i] = init;
    e->count++;
    if (inserted) *inserted = 1;
    return &e->vals[i];
}
