/* A binary min-heap of (key, id) pairs for Dijkstra and smallest-first
 * merging. Ties on the key are broken by the smaller id, so every walk that
 * uses it is deterministic. Stale entries are allowed (lazy deletion): the
 * caller skips a popped entry whose key no longer matches. Internal to charts/. */
#ifndef NEUV_CHARTS_MIN_HEAP_H
#define NEUV_CHARTS_MIN_HEAP_H

typedef struct min_heap {
    double *key;
    int *id;
    int n, cap;
} min_heap;

/* Returns 0, or -1 on allocation failure. */
int min_heap_init(min_heap *h, int cap);
void min_heap_free(min_heap *h);
/* Returns 0, or -1 on allocation failure (the heap grows as needed). */
int min_heap_push(min_heap *h, double key, int id);
/* Removes the smallest entry; returns 0, or -1 when the heap is empty. */
int min_heap_pop(min_heap *h, double *key, int *id);

#endif
