/* Geodesic distances by the heat method (Crane, Weischedel, Wardetzky 2013,
 * "Geodesics in Heat", Algorithm 1): diffuse heat from the sources for a short
 * time t, normalize its gradient into a unit field X = -∇u/|∇u| pointing away
 * from the sources, and recover the distance φ from the Poisson equation
 * Δφ = ∇·X.
 *
 * Everything expensive is factored once in heat_geodesics_create; every query
 * afterwards costs three triangular solves per source (two on closed meshes)
 * and solves up to HEAT_GEODESICS_BLOCK sources in one CHOLMOD call.
 *
 * Choices (see heat_geodesics.c for why):
 *   - t = h², h the mean edge length (the paper's m = 1), times `t_factor`.
 *   - Heat flow: (M + tL) u = u0 with M the lumped mass and L the cotangent
 *     Laplacian. On meshes with a boundary the heat is the average of the
 *     Neumann solution and the Dirichlet solution (u = 0 on the boundary), as
 *     the paper recommends (section 3.2.2); sources on the boundary are left out
 *     of the Dirichlet problem (they would be forced to zero), and a source set
 *     lying entirely on the boundary uses the Neumann solution alone.
 *   - Poisson: L φ = -∇·X made definite by pinning one vertex per connected
 *     component (its diagonal entry is doubled, a rank-one SPD change whose
 *     solution is the pinned one because the integrated divergence sums to zero
 *     on every component); φ is then shifted so the sources are at 0.
 *   - Vertices in a component that holds no source get INFINITY.
 *
 * Lifetime: heat_geodesics_create returns an object the caller releases with
 * heat_geodesics_free. It keeps no pointer to the mesh. Not thread-safe: one
 * object answers one query at a time. */
#ifndef NEUV_GEOMETRY_HEAT_GEODESICS_H
#define NEUV_GEOMETRY_HEAT_GEODESICS_H

#include <stddef.h>

#include "mesh/mesh.h"

/* Sources solved together in one multi right-hand-side call. */
#define HEAT_GEODESICS_BLOCK 64

typedef struct heat_geodesics heat_geodesics;

/* Prefactors the heat and Poisson systems of a mesh.
 *
 * Inputs:  m         mesh, #V by 3 positions, #F by 3 faces (at least one face)
 *          t_factor  multiplies the time step t = h² (1 for the paper's choice;
 *                    <= 0 also means 1)
 * Outputs: out       new object (NULL on failure)
 * Errors:  NEUV_ERR_INPUT for a mesh without faces or with zero mean edge
 *          length, NEUV_ERR_NOMEM, NEUV_ERR_INTERNAL when a factorization fails. */
neuv_status heat_geodesics_create(const neuv_mesh *m, double t_factor, heat_geodesics **out);
void heat_geodesics_free(heat_geodesics *g);

int heat_geodesics_vertex_count(const heat_geodesics *g);
/* The diffusion time t actually used. */
double heat_geodesics_time(const heat_geodesics *g);

/* Distance from one vertex.
 *
 * Inputs:  source  vertex index in [0, #V)
 * Outputs: dist    #V distances (caller allocates), dist[source] = 0 */
neuv_status heat_geodesics_from_vertex(heat_geodesics *g, int source, double *dist);

/* Distance to the nearest of several vertices (one heat solve with all of
 * them as sources).
 *
 * Inputs:  sources  #S vertex indices
 * Outputs: dist     #V distances (caller allocates) */
neuv_status heat_geodesics_nearest(heat_geodesics *g, const int *sources, int nsources,
                                   double *dist);

/* Independent distances from each of several vertices, solved in blocks of
 * HEAT_GEODESICS_BLOCK right-hand sides.
 *
 * Inputs:  sources  #S vertex indices
 * Outputs: dist     #V by #S column-major (column s: distances from sources[s]) */
neuv_status heat_geodesics_batch(heat_geodesics *g, const int *sources, int nsources,
                                 double *dist);

/* All pairs (i, j), i < j, with distance below a radius: a growing list. */
typedef struct geodesic_pairs {
    size_t n, cap;
    int *i, *j;   /* n vertex indices each, i < j */
    double *d;    /* n distances, heat-method distance from i to j */
} geodesic_pairs;

void geodesic_pairs_free(geodesic_pairs *p);

/* Every vertex pair closer than `radius`, never forming a #V by #V matrix:
 * sources go through in blocks of HEAT_GEODESICS_BLOCK and only the entries
 * under the radius are kept (workspace: a few #V by 64 blocks).
 * The distance reported for a pair is the one computed from its smaller index.
 *
 * Inputs:  radius   distances strictly below it are kept
 *          subset   #S vertex indices to restrict both ends of the pairs to (a
 *                   chart), or NULL for every vertex; distances are still
 *                   measured on the whole mesh the object was made from
 * Outputs: out      pairs appended to it (zero-initialize before the first call) */
neuv_status heat_geodesics_pairs_within(heat_geodesics *g, double radius, const int *subset,
                                        int nsubset, geodesic_pairs *out);

/* The pairs closer than `radius` that have at least one end among `sources`:
 * for each source, every other vertex under the radius. Memory and time grow
 * with nsources x #V rather than #V^2, so a fixed number of sources gives
 * pairs linear in the mesh size. A pair of two sources is kept once (from
 * its smaller index); pairs are stored with i < j.
 *
 * Inputs:  radius    distances strictly below it are kept
 *          sources   #S distinct vertex indices
 * Outputs: out       pairs appended to it (zero-initialize before the first call) */
neuv_status heat_geodesics_pairs_from(heat_geodesics *g, double radius, const int *sources, int nsources,
                                      geodesic_pairs *out);

/* Distances from source faces to every face centroid, for PatchNet's L_geo.
 * The heat source of a face is 1/3 on each of its three vertices; the distance
 * of a face is the mean of its vertices' distances, shifted so the source
 * face's vertices average their distance from its centroid (the source point);
 * the source face itself gets 0 and negative values clamp to 0.
 *
 * Inputs:  m             the mesh the object was made from (#F by 3 faces)
 *          source_faces  #S face indices
 * Outputs: dist          #F by #S column-major (caller allocates) */
neuv_status heat_geodesics_face_distances(heat_geodesics *g, const neuv_mesh *m,
                                          const int *source_faces, int nsources, double *dist);

/* Geodesic diameter estimate by double sweep in every connected component
 * (farthest vertex from the component's first vertex, then farthest from
 * that); the largest over components.
 *
 * Outputs: diameter  the estimate (a lower bound of the true diameter) */
neuv_status heat_geodesics_diameter(heat_geodesics *g, double *diameter);

#endif
