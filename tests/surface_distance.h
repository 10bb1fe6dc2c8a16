/* Test helper: how far a mesh's vertices lie from another mesh's surface. */
#ifndef NEUV_TESTS_SURFACE_DISTANCE_H
#define NEUV_TESTS_SURFACE_DISTANCE_H

#include <math.h>

#include "mesh/mesh.h"
#include "spatial/bvh.h"

/* Largest distance from m's vertices to the surface of ref (INFINITY when the tree cannot be built). */
static inline double max_deviation(const neuv_mesh *ref, const neuv_mesh *m)
{
    bvh b;
    if (bvh_build(&b, ref)) return INFINITY;
    double worst = 0;
    for (int v = 0; v < m->nv; v++) {
        double d2;
        bvh_closest_point(&b, m->pos + 3 * v, NULL, NULL, &d2);
        worst = fmax(worst, sqrt(d2));
    }
    bvh_free(&b);
    return worst;
}

#endif
