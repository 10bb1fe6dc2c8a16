/* Topology-preserving simplification: CGAL's edge collapse with the
 * Lindstrom-Turk cost and placement (Lindstrom and Turk, "Fast and
 * memory efficient polygonal simplification", IEEE Visualization 1998).
 * Every collapse passes CGAL's link condition test, so the output keeps
 * the input's components, boundary loops and genus, and stays manifold:
 * what meshoptimizer's simplifier (remesh/simplify.c) does not promise
 * (it tears a regular bumpy grid into pieces; issue 20, item 6). */
#ifndef NEUV_REMESH_EDGE_COLLAPSE_H
#define NEUV_REMESH_EDGE_COLLAPSE_H

#include "mesh/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Inputs: m (#V by 3 positions, #F by 3 faces), a manifold, consistently
 * oriented triangle mesh (as mesh_clean leaves it); target_faces >= 1.
 * Outputs: *out a new mesh without UVs, near target_faces faces (edges
 * are collapsed until their count falls to target / #F of the input's;
 * collapses the link condition or the placement refuses are skipped, so
 * the count may stay above). Positions move (the placement is the
 * Lindstrom-Turk point), unlike meshoptimizer's subset of the input's.
 * Deterministic. Returns NEUV_OK, NEUV_ERR_INPUT (not a manifold oriented
 * triangle mesh, non-finite coordinate), NEUV_ERR_NOMEM, NEUV_ERR_INTERNAL. */
neuv_status mesh_edge_collapse(const neuv_mesh *m, int target_faces, neuv_mesh **out);

#ifdef __cplusplus
}
#endif

#endif
