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
 * component consistently (closed components outward). opts may be NULL. */
neuv_status mesh_clean(neuv_mesh *m, const mesh_clean_options *opts, mesh_clean_report *report);

#endif
