/* The triangle mesh every stage works on.
 *
 * Positions are float64 (#V by 3), faces are vertex indices (#F by 3,
 * counter-clockwise seen from outside). UVs are per corner: `tri_uv` (#F by 3)
 * indexes `uv` (#UV by 2), so a vertex on a seam has one UV per side. A mesh
 * without UVs has nuv == 0 and uv == tri_uv == NULL. */
#ifndef NEUV_MESH_MESH_H
#define NEUV_MESH_MESH_H

#include "neuv/neuv.h"

struct neuv_mesh {
    int nv, nf;
    double *pos; /* #V by 3 */
    int *tri;    /* #F by 3 */
    int nuv;
    double *uv;  /* #UV by 2 */
    int *tri_uv; /* #F by 3, or NULL */
};
typedef struct neuv_mesh neuv_mesh;

/* Allocates a zeroed mesh with room for nv vertices, nf faces and nuv UVs
 * (tri_uv is allocated when nuv > 0). NULL on allocation failure. */
neuv_mesh *mesh_create(int nv, int nf, int nuv);
neuv_mesh *mesh_clone(const neuv_mesh *m);
/* Replaces the UVs of m (takes a copy); nuv == 0 removes them. */
neuv_status mesh_set_uv(neuv_mesh *m, int nuv, const double *uv, const int *tri_uv);
void mesh_free(neuv_mesh *m);

/* Geometry helpers used everywhere. */
double mesh_face_area(const neuv_mesh *m, int f);
void mesh_face_normal(const neuv_mesh *m, int f, double n[3]); /* unit, zero if degenerate */
double mesh_total_area(const neuv_mesh *m);
void mesh_bounding_box(const neuv_mesh *m, double lo[3], double hi[3]);

#endif
