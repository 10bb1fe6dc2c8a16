/* One chart as a small indexed mesh of its own, with its face graph cut at
 * the chart's boundary, and the operations the disk-making step runs on it.
 * Building it costs O(chart size) thanks to mesh-sized scratch maps that are
 * restored after each use. Internal to charts/. */
#ifndef NEUV_CHARTS_CHART_LOCAL_H
#define NEUV_CHARTS_CHART_LOCAL_H

#include "charts/face_graph.h"
#include "mesh/mesh.h"

typedef struct chart_local {
    int nf, nv;
    int *face;     /* #CF mesh face of each local face (the order given) */
    int *vert;     /* #CV mesh vertex of each local vertex, in order of first use */
    int *tri;      /* #CF by 3 local vertex ids */
    int *adj;      /* #CF by 3 local face across edge k, -1 outside the chart */
    double *elen;  /* #CF by 3 edge lengths */
    double *cen;   /* #CF by 3 face centroids */
    double *vpos;  /* #CV by 3 vertex positions */
} chart_local;

/* Mesh-sized maps, all -1 between uses. */
typedef struct chart_scratch {
    int *face_map; /* #F */
    int *vert_map; /* #V */
} chart_scratch;

neuv_status chart_scratch_init(chart_scratch *s, int nf, int nv);
void chart_scratch_free(chart_scratch *s);

/* Inputs: m, g (its face graph), faces (n mesh faces of one chart), s.
 * Output: L (free with chart_local_free). Returns NEUV_OK or NEUV_ERR_NOMEM. */
neuv_status chart_local_build(const neuv_mesh *m, const face_graph *g, const int *faces, int n,
                              chart_scratch *s, chart_local *L);
void chart_local_free(chart_local *L);

/* Connected parts of the chart: faces joined across a local edge when
 * part (#CF, may be NULL) is equal on both sides and the edge is not marked
 * in cut (#CF by 3, may be NULL). Output comp (#CF), numbered in local face
 * order. Returns the number of parts, or -1 on allocation failure. */
int chart_local_components(const chart_local *L, const int *part, const unsigned char *cut, int *comp);

typedef struct chart_shape {
    int components; /* edge-connected parts */
    int pinched;    /* vertices left by more than one boundary edge */
    int loops;      /* boundary loops (meaningful when pinched == 0) */
    int euler;      /* V - E + F */
    int genus;      /* (2 - euler - loops) / 2 when connected and not pinched */
    int disk;       /* components == 1, pinched == 0, loops == 1, euler == 1 */
} chart_shape;

/* Topology of the chart. vloop (#CV, may be NULL) receives the loop index of
 * each boundary vertex (-1 for interior ones; set only when not pinched).
 * Returns NEUV_OK or NEUV_ERR_NOMEM. */
neuv_status chart_local_shape(const chart_local *L, chart_shape *s, int *vloop);

/* Multi-source Dijkstra on the chart's face graph, edge weights the
 * distances between face centroids, never crossing a half-edge marked in
 * cut (#CF by 3, may be NULL). Inputs: seeds (n_seeds local faces),
 * seed_label (n_seeds, may be NULL). Outputs: dist (#CF, INFINITY when
 * unreached), label (#CF, label of the nearest seed, may be NULL).
 * Returns NEUV_OK or NEUV_ERR_NOMEM. */
neuv_status chart_local_face_dijkstra(const chart_local *L, const int *seeds, const int *seed_label,
                                      int n_seeds, const unsigned char *cut, double *dist, int *label);

/* Splits the chart in two by growing regions from the pair of faces
 * farthest apart (a double sweep of face-graph Dijkstra), so the cut runs
 * across the chart's long axis. Output part (#CF) in {0, 1}, each part
 * edge-connected and non-empty. Needs a connected chart with >= 2 faces.
 * Returns NEUV_OK or NEUV_ERR_NOMEM. */
neuv_status chart_local_grow2(const chart_local *L, int *part);

/* Two shortest cuts across a genus-0 chart with two or more loops (an
 * annulus when two): the shortest edge path from loop 0 to another loop,
 * then the shortest path between the same two loops that avoids the first
 * one (and every other loop) and starts where loop 0 is farthest from it.
 * For an annulus the two paths split it into two disks.
 * Output cut (#CF by 3): 1 on the local half-edges of both paths.
 * vloop: from chart_local_shape. Returns 1 when both paths were found, 0
 * when not (cut is then all zero), -1 on allocation failure. */
int chart_local_annulus_cut(const chart_local *L, const int *vloop, unsigned char *cut);

/* The fallback when the second path does not exist (a strip one face
 * wide): cut along the first path only, which makes an annulus a disk with
 * the path on two sides, and grow two regions from the faces along either
 * side of it, so they meet half way round. Output part (#CF) in {0, 1}.
 * Returns 1 on success, 0 when no path exists, -1 on allocation failure. */
int chart_local_cut_and_grow(const chart_local *L, const int *vloop, int *part);

#endif
