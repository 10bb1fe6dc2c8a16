/* Re-triangulation that keeps the shape: vertices slide within the surface
 * and nearly flat edge pairs are flipped, so a test or a user gets another
 * discretization of the same surface. */
#ifndef NEUV_REMESH_JITTER_H
#define NEUV_REMESH_JITTER_H

#include <stdint.h>

#include "mesh/mesh.h"

typedef struct jitter_options {
    double max_offset;       /* largest move, as a fraction of the vertex's shortest incident edge (0.3) */
    double flip_probability; /* chance that an eligible edge is flipped (0.5) */
    double flip_max_degrees; /* an edge is eligible when its two faces' normals differ by less (1) */
    double feature_degrees;  /* vertices on an edge sharper than this stay put (20) */
} jitter_options;

typedef struct jitter_report {
    int moved_vertices;   /* interior vertices moved within the surface */
    int slid_vertices;    /* boundary vertices slid along a straight boundary */
    int fixed_vertices;   /* kept: feature, UV seam, non-manifold or corner vertices */
    int flipped_edges;
    double max_deviation; /* largest distance of a moved vertex to the input surface */
} jitter_report;

/* Default options (values in the comments above). */
void jitter_default_options(jitter_options *o);

/* Moves every interior vertex by a random tangential offset of up to
 * max_offset times its shortest incident edge, then projects it back onto
 * the INPUT surface (closest point through a BVH); a move is halved, up to
 * four times, until the projected point lies in one of the vertex's own
 * faces and none of them flips or shrinks below a tenth of its area,
 * otherwise the vertex stays. Vertices on a straight boundary (the two
 * boundary edges within 1 degree of a line) slide along one of them.
 * Vertices stay where the surface has a feature (an incident edge with a
 * dihedral angle above feature_degrees), on UV seams (more than one UV),
 * on non-manifold edges, and at boundary corners, so the shape is kept.
 * Then one pass of random edge flips over pairs of faces within
 * flip_max_degrees of coplanar whose flip keeps both faces' orientation and
 * creates no duplicate edge. UVs are kept consistent: a moved vertex takes
 * the UV interpolated at its new point in the input face holding it, and
 * seam edges are never flipped. Deterministic for a seed.
 * Inputs: m (manifold, cleaned), seed, opts (NULL: defaults).
 * Outputs: m modified in place; report (may be NULL).
 * Returns NEUV_OK, NEUV_ERR_INPUT (no faces), NEUV_ERR_NOMEM. */
neuv_status mesh_jitter(neuv_mesh *m, uint64_t seed, const jitter_options *opts, jitter_report *report);

#endif
