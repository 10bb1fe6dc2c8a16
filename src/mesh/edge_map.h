/* A hash map from an ordered vertex pair (a, b) to an int, with open
 * addressing. Used to find the faces across each edge in O(1) expected time,
 * so cleaning and topology stay linear in the number of faces. */
#ifndef NEUV_MESH_EDGE_MAP_H
#define NEUV_MESH_EDGE_MAP_H

#include <stddef.h>
#include <stdint.h>

typedef struct edge_map {
    uint64_t *keys; /* cap slots; EDGE_MAP_EMPTY when free */
    int *vals;      /* cap slots */
    size_t cap, count;
} edge_map;

#define EDGE_MAP_EMPTY UINT64_MAX

/* Inputs: expected number of keys (the table grows past it when needed).
 * Returns 0, or -1 on allocation failure. */
int edge_map_init(edge_map *e, size_t expected);
void edge_map_free(edge_map *e);
/* Value stored for (a, b), or -1 when absent. The pair is ordered: (a, b)
 * and (b, a) are different keys; pass min/max for an undirected edge. */
int edge_map_get(const edge_map *e, int a, int b);
/* Slot of the value for (a, b), inserting it with value `init` when absent.
 * *inserted (may be NULL) says whether it was new. NULL on allocation failure. */
int *edge_map_slot(edge_map *e, int a, int b, int init, int *inserted);

#endif
