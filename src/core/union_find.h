/* Disjoint sets over 0..n-1 with path halving and union by size. */
#ifndef NEUV_CORE_UNION_FIND_H
#define NEUV_CORE_UNION_FIND_H

typedef struct union_find { int *parent, *size; int n; } union_find;

int uf_init(union_find *u, int n); /* 0 on success, -1 on allocation failure */
void uf_free(union_find *u);
int uf_find(union_find *u, int x);
void uf_union(union_find *u, int a, int b);
/* Writes a dense label per element, numbered in order of first appearance
 * (so labels are deterministic); returns the number of sets. */
int uf_labels(union_find *u, int *label);

#endif
