/* The faces around every undirected edge of a triangle mesh, in face order. */
#ifndef NEUV_MESH_EDGE_FACES_H
#define NEUV_MESH_EDGE_FACES_H

#include "mesh/mesh.h"

struct edge_map;

typedef struct edge_faces {
    int ne;          /* number of undirected edges */
    int *face_edge;  /* #F by 3: edge id of the side from corner k to corner k+1 (-1 if its ends coincide) */
    int *start;      /* #E+1 offsets into side */
    int *side;       /* 3F entries f*3+k, grouped by edge, faces in increasing order */
    int *edge_v;     /* #E by 2: the edge's vertices, smaller first */
} edge_faces;

/* Builds the table in O(F) expected time. Returns 0, or -1 on allocation failure. */
int edge_faces_build(edge_faces *t, const neuv_mesh *m);
void edge_faces_free(edge_faces *t);
/* A map from each edge's (smaller, larger) vertex pair to its edge id.
 * Returns 0, or -1 on allocation failure (map left empty). */
int edge_faces_index(const edge_faces *t, struct edge_map *map);
static inline int edge_faces_count(const edge_faces *t, int e) { return t->start[e + 1] - t->start[e]; }

#endif
