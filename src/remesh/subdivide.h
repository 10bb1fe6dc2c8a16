/* Subdivision of triangle meshes: every face split in four through its
 * edge midpoints, with positions either kept on the input surface
 * (midpoint) or smoothed by Loop's rules. */
#ifndef NEUV_REMESH_SUBDIVIDE_H
#define NEUV_REMESH_SUBDIVIDE_H

#include "mesh/mesh.h"

typedef enum subdivide_scheme {
    SUBDIVIDE_MIDPOINT = 0, /* old vertices fixed, new ones at edge midpoints: same surface */
    SUBDIVIDE_LOOP = 1,     /* Loop (1987) smoothing, boundary rules; the limit is a smooth surface */
} subdivide_scheme;

/* `rounds` rounds of 1-to-4 subdivision.
 * Inputs: m (#V by 3 positions, #F by 3 faces, optional per-corner UVs);
 * rounds >= 0; scheme.
 * Outputs: *out a new mesh with #F * 4^rounds faces. Old vertices keep
 * their indices (0..#V-1), each round appends one vertex per edge (in
 * edge order). Corner UVs are interpolated linearly: a new corner gets the
 * midpoint of its edge's two corner UVs, so a seam stays a seam; with Loop
 * the UVs are still linear (the UV map is not smoothed).
 * Loop rules (Loop 1987, "Smooth subdivision surfaces based on triangles"):
 * interior edge point 3/8 (a + b) + 1/8 (c + d); interior vertex
 * (1 - n beta) v + beta sum(neighbours), beta = (5/8 - (3/8 + 1/4 cos(2 pi/n))^2) / n;
 * boundary edge point the midpoint; boundary vertex 3/4 v + 1/8 (its two
 * boundary neighbours). Vertices on non-manifold edges stay where they are.
 * Returns NEUV_OK, NEUV_ERR_INPUT (a face with a repeated vertex, or a mesh
 * too large to subdivide), NEUV_ERR_NOMEM. */
neuv_status mesh_subdivide(const neuv_mesh *m, int rounds, subdivide_scheme scheme, neuv_mesh **out);

#endif
