/* Mesh simplification by edge collapse (meshoptimizer's quadric simplifier,
 * CGAL's topology-preserving edge collapse where meshoptimizer tears). */
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
 * Topology: meshoptimizer checks no link condition and can tear a surface
 * (a fine regular grid, a subdivided torus). The copy's components,
 * boundary loops, Euler characteristic and directed edges used twice are
 * compared with the input's; where they differ and the input is manifold,
 * oriented and has no UVs, the copy is made again by mesh_edge_collapse
 * (remesh/edge_collapse.h: same topology, but new positions, and the
 * subset guarantee above does not hold). With UVs, or where the edge
 * collapse refuses the input, the torn copy is kept and a warning logged.
 * Returns NEUV_OK, NEUV_ERR_INPUT (ratio out of range, no faces),
 * NEUV_ERR_NOMEM, NEUV_ERR_INTERNAL (CGAL failed). */
neuv_status mesh_simplify(const neuv_mesh *m, double ratio, neuv_mesh **out);

#endif
