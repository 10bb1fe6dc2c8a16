/* Moving one face from a chart to a neighbouring chart so that both stay
 * topological disks, checked locally. Internal to charts/.
 *
 * A move of face f from chart A to chart B keeps both charts disks when the
 * closed triangle meets each chart in one arc of its boundary (the "simple
 * cell" condition of digital topology): gluing a disk to a disk along an arc
 * gives a disk, and Euler's V - E + F changes by k - v + 1 = 0 for k shared
 * edges and v touched vertices with (k, v) = (1, 2) or (2, 3). Removing f with
 * two edges on A also needs the vertex between those edges to be interior to
 * A, or A would be pinched there. */
#ifndef NEUV_CHARTS_FACE_MOVE_H
#define NEUV_CHARTS_FACE_MOVE_H

#include "charts/face_graph.h"

/* The faces around each vertex. */
typedef struct face_star {
    int *start;          /* #V + 1 offsets into face */
    int *face;           /* 3 #F faces around each vertex */
    unsigned char *open; /* #V: 1 on a mesh boundary (or non-manifold) edge */
} face_star;

neuv_status face_star_build(const neuv_mesh *m, const face_graph *g, face_star *s);
void face_star_free(face_star *s);

/* Whether chart c minus f (removing = 1, f in c) or plus f (removing = 0)
 * stays a disk, by the one-arc condition above. */
int face_move_keeps_disk(const neuv_mesh *m, const face_graph *g, const face_star *s, const int *face_chart, int f,
                         int c, int removing);

#endif
