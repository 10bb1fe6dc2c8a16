/* Isotropic remeshing: a new triangulation of the same surface with edges
 * of one target length, sharing (almost) no vertex with the input, so a
 * method can be measured on a discretization independent of the one it
 * saw. CGAL's Polygon_mesh_processing::isotropic_remeshing (Botsch and
 * Kobbelt 2004, "A remeshing approach to multiresolution modeling": split
 * edges longer than 4/3 L, collapse those shorter than 4/5 L, flip towards
 * valence 6, tangential relaxation, projection onto the input) behind a C
 * interface; the implementation is C++ (isotropic_remesh.cpp). */
#ifndef NEUV_REMESH_ISOTROPIC_REMESH_H
#define NEUV_REMESH_ISOTROPIC_REMESH_H

#include "mesh/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct isotropic_options {
    double target_edge_length; /* > 0: L in the mesh's units; 0: derived from target_faces (0) */
    int target_faces;          /* used when target_edge_length is 0; >= 4 (0) */
    int iterations;            /* split/collapse/flip/relax/project rounds of CGAL (5) */
    double feature_degrees;    /* edges whose dihedral angle exceeds this are kept as polylines;
                                  >= 180: none (60) */
} isotropic_options;

typedef struct isotropic_report {
    int faces_in, faces_out;
    double edge_length;    /* target L of the last remeshing */
    int feature_edges_in;  /* input edges sharper than feature_degrees */
    int feature_edges_out; /* output edges on those polylines (they may be split) */
    int corners;           /* vertices held fixed: where feature/boundary polylines meet, end or turn */
    int rounds;            /* remeshings of the input run (1 to 3 with target_faces) */
    double max_distance;   /* largest distance of an output vertex to the input surface */
} isotropic_report;

/* Default options (values in the comments above). */
void isotropic_default_options(isotropic_options *o);

/* Remeshes m isotropically towards target edge length L.
 * With target_faces N instead, L = sqrt(4 A / (sqrt(3) N)) (equilateral
 * triangles of side L tiling the area A of m); when the result misses N by
 * more than 10%, L is scaled by sqrt(faces / N) and m remeshed again from
 * the start, at most twice; the round closest to N is returned (the count
 * is a step function of L, so a correction can overshoot).
 * Feature edges (PMP::detect_sharp_edges over feature_degrees) and
 * boundary edges are constrained: they may be split and collapsed along
 * their polyline but neither flipped nor relaxed, so input vertices on
 * them can survive. Vertices with 1 or more than 2 feature/boundary edges
 * (ends, a cube's corners) or where such a polyline turns by more than
 * feature_degrees (a square's corners) stay exactly where they are. Every
 * other vertex is projected back onto the input surface (CGAL's
 * do_project, true by default), a new vertex on a polyline onto the
 * input's polylines, so max_distance is rounding-level. Deterministic.
 * Inputs: m (#V by 3 positions, #F by 3 faces): a manifold, consistently
 * oriented triangle mesh (as mesh_clean leaves it); UVs are ignored;
 * opts (NULL: defaults, which need target_edge_length or target_faces set,
 * so NULL is an error).
 * Outputs: *out a new mesh without UVs, faces oriented as m's, no unused
 * vertex (caller frees with mesh_free); report (may be NULL).
 * Returns NEUV_OK; NEUV_ERR_INPUT (no faces, index out of range, a
 * non-manifold or inconsistently oriented input, L <= 0 or N < 4, a target
 * needing over 20M faces); NEUV_ERR_NOMEM; NEUV_ERR_INTERNAL (CGAL failed).
 * No C++ exception leaves this function. */
neuv_status mesh_remesh_isotropic(const neuv_mesh *m, const isotropic_options *opts, neuv_mesh **out,
                                  isotropic_report *report);

#ifdef __cplusplus
}
#endif

#endif
