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
    /* What the file says beyond the geometry (io/ fills them; NULL / 0 when
     * it says nothing). They mark the default seams (mesh/hard_edges.h). */
    int nn;
    double *normal;     /* #N by 3: the file's normals */
    int *tri_normal;    /* #F by 3 into normal: each corner's normal */
    int *face_material; /* #F: the material of each face, numbered from 0 in order of first use */
    /* The file's polygons (np == 0: it gave triangles, or they are not
     * known). A polygon's triangles are consecutive faces. */
    int np;
    int *face_polygon;  /* #F: the polygon each face is a triangle of */
    int *poly_start;    /* np + 1: first corner of each polygon in poly_corner */
    int *poly_corner;   /* poly_start[np]: the face corner (3 f + k) standing for each polygon corner, in the file's order */
    struct mesh_attributes *attr; /* what else the file carries (mesh/mesh_attributes.h), or NULL */
};
typedef struct neuv_mesh neuv_mesh;

/* Allocates a zeroed mesh with room for nv vertices, nf faces and nuv UVs
 * (tri_uv is allocated when nuv > 0). NULL on allocation failure. */
neuv_mesh *mesh_create(int nv, int nf, int nuv);
/* A copy of the geometry, UVs, normals and face materials; polygons and
 * attributes are copied only by mesh_copy_file_structure. */
neuv_mesh *mesh_clone(const neuv_mesh *m);
/* Replaces the normals of m (takes a copy); nn == 0 removes them. */
neuv_status mesh_set_normals(neuv_mesh *m, int nn, const double *normal, const int *tri_normal);
/* Replaces the face materials of m (takes a copy); NULL removes them. */
neuv_status mesh_set_face_material(neuv_mesh *m, const int *face_material);
/* The normals, face materials and polygons of `joined`, whose faces are
 * those of a (may be NULL) then those of b: normals when both have them
 * (b's indices shifted), materials when either has them (b's numbered
 * after a's; a mesh without materials counts as one), polygons when either
 * has them (a mesh without gives one per triangle). Not the attributes.
 * NEUV_ERR_NOMEM on allocation failure. */
neuv_status mesh_join_marks(neuv_mesh *joined, const neuv_mesh *a, const neuv_mesh *b);
/* Copies the polygons and attributes of src into m, which has src's faces
 * (m's own are replaced). NEUV_ERR_NOMEM on allocation failure. */
neuv_status mesh_copy_file_structure(neuv_mesh *m, const neuv_mesh *src);
/* Removes m's polygons and attributes (after a change of its faces). */
void mesh_drop_file_structure(neuv_mesh *m);
/* Removes m's polygons only. */
void mesh_drop_polygons(neuv_mesh *m);
/* Replaces the UVs of m (takes a copy); nuv == 0 removes them. */
neuv_status mesh_set_uv(neuv_mesh *m, int nuv, const double *uv, const int *tri_uv);
void mesh_free(neuv_mesh *m);

/* Geometry helpers used everywhere. */
double mesh_face_area(const neuv_mesh *m, int f);
void mesh_face_normal(const neuv_mesh *m, int f, double n[3]); /* unit, zero if degenerate */
/* Unit vertex normals: area-weighted sums of the faces' normals (zero where
 * the sum is). n: #V by 3, caller allocates. */
void mesh_vertex_normals(const neuv_mesh *m, double *n);
double mesh_total_area(const neuv_mesh *m);
void mesh_bounding_box(const neuv_mesh *m, double lo[3], double hi[3]);

#endif
