/* The face graph of a mesh: which face lies across each edge. Charts are
 * face sets, so every chart operation walks this graph. Internal to charts/. */
#ifndef NEUV_CHARTS_FACE_GRAPH_H
#define NEUV_CHARTS_FACE_GRAPH_H

#include "mesh/mesh.h"

typedef struct face_graph {
    int nf, nv;
    int *adj;          /* #F by 3: face across edge k = (tri[f][k], tri[f][(k+1)%3]),
                        * -1 on a boundary edge or an edge with more than two faces */
    double *elen;      /* #F by 3: length of edge k */
    double *centroid;  /* #F by 3 */
    double *area;      /* #F */
} face_graph;

/* Inputs: m (#V by 3 positions, #F by 3 faces). Output: g (free with
 * face_graph_free). Returns NEUV_OK or NEUV_ERR_NOMEM. */
neuv_status face_graph_build(const neuv_mesh *m, face_graph *g);
void face_graph_free(face_graph *g);

#endif
