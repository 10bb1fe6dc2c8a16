#include "charts/min_heap.h"

#include <stdlib.h>

#include "core/mem.h"

static int before(const min_heap *h, int i, int j)
{
    if (h->key[i] != h->key[j]) return h->key[i] < h->key[j];
    return h->id[i] < h->id[j];
}

static void swap_entries(min_heap *h, int i, int j)
{
    double k = h->key[i]; h->key[i] = h->key[j]; h->key[j] = k;
    int d = h->id[i]; h->id[i] = h->id[j]; h->id[j] = d;
}

int min_heap_init(min_heap *h, int cap)
{
    h->n = 0;
    h->cap = cap > 16 ? cap : 16;
    h->key = mem_alloc(sizeof(double) * (size_t)h->cap);
    h->id = mem_alloc(sizeof(int) * (size_t)h->cap);
    if (!h->key || !h->id) { min_heap_free(h); return -1; }
    return 0;
}

void min_heap_free(min_heap *h)
{
    mem_free(h->key); mem_free(h->id);
    h->key = NULL; h->id = NULL;
    h->n = h->cap = 0;
}

int min_heap_push(min_heap *h, double key, int id)
{
    if (h->n == h->cap) {
        int cap = h->cap * 2;
        double *k = mem_realloc(h->key, sizeof(double) * (size_t)cap);
        if (!k) return -1;
        h->key = k;
        int *d = mem_realloc(h->id, sizeof(int) * (size_t)cap);
        if (!d) return -1;
        h->id = d;
        h->cap = cap;
    }
    int i = h->n++;
    h->key[i] = key;
    h->id[i] = id;
    while (i > 0) {
        int p = (i - 1) / 2;
        if (!before(h, i, p)) break;
        swap_entries(h, i, p);
        i = p;
    }
    return 0;
}

int min_heap_pop(min_heap *h, double *key, int *id)
{
    if (h->n == 0) return -1;
    *key = h->key[0];
    *id = h->id[0];
    h->n--;
    if (h->n > 0) {
        h->key[0] = h->key[h->n];
        h->id[0] = h->id[h->n];
        int i = 0;
        for (;;) {
            int l = 2 * i + 1, r = l + 1, s = i;
            if (l < h->n && before(h, l, s)) s = l;
            if (r < h->n && before(h, r, s)) s = r;
            if (s == i) break;
            swap_entries(h, i, s);
            i = s;
        }
    }
    return 0;
}
