/* Mesh simplification by edge collapse (meshoptimizer's quadric simplifier). */
#ifndef NEUV_REMESH_SIMPLIFY_H
#define NEUV_REMESH_SIMPLIFY_H

#include "mesh/mesh.h"

/* Simplifies m towards ratio * #F faces.
 * Inputs: m; ratio in (0, 1].
 * Outputs: *out a new mesh whose vertex positions are exactly (bit for bit)
 * a subset of m's, in m's order (meshoptimizer only removes vertices; the
 * unreferenced ones are dropped). UVs, when present, are kept per corner:
 * the simplifier works on one vertex per distinct (position, UV) pair, so
 * it sees UV seams as attribute seams and keeps them consistent, and every
 * kept corner maps back to an input (vertex, UV) pair. The face count may
 * stay above the target where seams or borders stop collapses.
 * Returns NEUV_OK, NEUV_ERR_INPUT (ratio out of range, no faces), NEUV_ERR_NOMEM. */
neuv_status mesh_simplify(const neuv_mesh *m, double ratio, neuv_mesh **out);

#endif
