#include "core/union_find.h"

#include <stdlib.h>

#include "core/mem.h"

int uf_init(union_find *u, int n)
{
    u->n = n;
    u->parent = mem_alloc(sizeof(int) * (size_t)(n > 0 ? n : 1));
    u->size = mem_alloc(sizeof(int) * (size_t)(n > 0 ? n : 1));
    if (!u->parent || !u->size) { uf_free(u); return -1; }
    for (int i = 0; i < n; i++) { u->parent[i] = i; u->size[i] = 1; }
    return 0;
}

void uf_free(union_find *u)
{
    mem_free(u->parent); mem_free(u->size);
    u->parent = u->size = NULL;
    u->n = 0;
}

int uf_find(union_find *u, int x)
{
    while (u->parent[x] != x) {
        u->parent[x] = u->parent[u->parent[x]];
        x = u->parent[x];
    }
    return x;
}

void uf_union(union_find *u, int a, int b)
{
    a = uf_find(u, a);
    b = uf_find(u, b);
    if (a == b) return;
    if (u->size[a] < u->size[b]) { int t = a; a = b; b = t; }
    u->parent[b] = a;
    u->size[a] += u->size[b];
}

int uf_labels(union_find *u, int *label)
{
    int *root_label = mem_alloc(sizeof(int) * (size_t)(u->n > 0 ? u->n : 1));
    if (!root_label) return -1;
    for (int i = 0; i < u->n; i++) root_label[i] = -1;
    int count = 0;
    for (int i = 0; i < u->n; i++) {
        int r = uf_find(u, i);
        if (root_label[r] < 0) root_label[r] = count++;
        label[i] = root_label[r];
    }
    mem_free(root_label);
    return count;
}
