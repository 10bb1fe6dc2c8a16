/* Mesh cleaning: the repairs every input goes through before unwrapping.
 * Each repair is counted in a mesh_clean_report so the CLI can say what changed. */
#ifndef NEUV_MESH_CLEAN_H
#define NEUV_MESH_CLEAN_H

#include "mesh/mesh.h"

typedef struct mesh_clean_report {
    int welded_vertices;        /* vertices merged into an earlier one with identical position */
    int degenerate_faces;       /* faces dropped: repeated vertex index or zero area */
    int duplicate_faces;        /* faces dropped: same vertex set as an earlier face */
    int unreferenced_vertices;  /* vertices dropped: used by no face */
    int flipped_faces;          /* faces reversed to make orientation consistent */
    int nonmanifold_edges;      /* edges found with more than two faces */
    int nonmanifold_vertices;   /* vertices whose faces form more than one fan */
    int split_vertices;         /* vertices added when splitting non-manifold parts */
    int nonorientable_components; /* components left as they are: no consistent orientation (Moebius) */
} mesh_clean_report;

typedef struct mesh_clean_options {
    int split_nonmanifold;      /* 1: split into manifold pieces (default); 0: refuse with an error */
} mesh_clean_options;

/* Welds vertices with exactly identical positions (keeps the first index,
 * in order). UVs, when present, are kept per corner. Returns the number of
 * vertices removed, or -1 on allocation failure. */
int mesh_weld_positions(neuv_mesh *m);

/* All repairs, in order: weld, drop degenerate and duplicate faces, split
 * non-manifold edges and vertices, drop unreferenced vertices, orient each
 * component consistently (closed components outward). opts may be NULL.
 *
 * Degenerate: a repeated vertex or |cross product| <= 1e-14 times the
 * longest edge squared. Non-manifold edge: the first face and the first
 * later face running the other way (else the second face) stay attached,
 * the others get their own copies of the two vertices. Non-manifold vertex:
 * each fan of faces after the first (in face order) gets its own copy.
 * Open components keep the orientation of most of their faces; closed
 * ones point outward (positive signed volume). Non-orientable components
 * are left as they are and counted. UVs stay with their corners; the
 * file's normals and face materials are dropped.
 * On error m is unchanged: NEUV_ERR_INPUT for out-of-range indices or, with
 * split_nonmanifold == 0, a non-manifold edge or vertex (input numbering).
 * Runs in O(F) expected time. */
neuv_status mesh_clean(neuv_mesh *m, const mesh_clean_options *opts, mesh_clean_report *report);

#endif
