/* Growing arrays the readers fill (positions, UVs, polygons), then one
 * validation pass that turns them into a neuv_mesh. Readers never weld or
 * clean: vertex order and values stay exactly as in the file (mesh/clean.h
 * repairs later, and says what it did). */
#ifndef NEUV_IO_MESH_BUILDER_H
#define NEUV_IO_MESH_BUILDER_H

#include <stddef.h>

#include "mesh/mesh.h"

typedef struct mesh_builder {
    double *pos;           /* #V by 3 */
    int nv;
    size_t cap_v;
    double *uv;            /* #UV by 2 */
    int nuv;
    size_t cap_uv;
    double *normal;        /* #N by 3 */
    int nn;
    size_t cap_n;
    int *tri, *tri_uv;     /* #F by 3; tri_uv is -1 for faces given without UVs */
    int *tri_normal;       /* #F by 3; -1 for faces given without normals */
    int *face_material;    /* #F: `material` when the face was added */
    int material;          /* the material of the faces added next (-1: none named yet) */
    int *origin;           /* #F: file face number (or line) each triangle came from */
    int *face_polygon;     /* #F: the polygon each triangle came from */
    int *face_group;       /* #F: `group` when the face was added */
    int group;             /* the group state of the faces added next (-1: none; OBJ o/g/s) */
    int np;                /* polygons added */
    int *poly_start;       /* np + 1 */
    size_t cap_p;
    int *poly_corner;      /* poly_start[np]: a triangle corner (3 f + k) for each polygon corner */
    size_t cap_pc;
    int any_polygon;       /* a polygon of more than 3 corners was added */
    struct mesh_attributes *attr; /* what the reader keeps beyond the surface (finish hands it to the mesh) */
    int nf;
    size_t cap_f;
    int faces_with_uv;     /* polygons given with UVs */
    int faces_without_uv;  /* polygons given without */
    int faces_with_normal, faces_without_normal;
    /* scratch for triangulating polygons */
    double *scratch_pos, *scratch_xy;
    int *scratch_idx, *scratch_tri;
    size_t cap_scratch;
} mesh_builder;

/* How messages name a triangle's origin and number vertices. */
typedef struct mesh_builder_style {
    int origin_is_line; /* 1: "line L: face ..." (OBJ); 0: "face N ..." */
    int index_base;     /* 1 for OBJ (indices as written in the file), else 0 */
} mesh_builder_style;

void mesh_builder_init(mesh_builder *b);
void mesh_builder_free(mesh_builder *b);
/* Reserves room (a hint; the arrays still grow as needed). */
neuv_status mesh_builder_reserve(mesh_builder *b, long long nv, long long nf);
neuv_status mesh_builder_add_vertex(mesh_builder *b, double x, double y, double z);
neuv_status mesh_builder_add_uv(mesh_builder *b, double u, double v);
neuv_status mesh_builder_add_normal(mesh_builder *b, double x, double y, double z);
/* Adds a polygon of n >= 3 corners, triangulated (see polygon_triangulate.h).
 * Inputs:
 *   v       n vertex indices (0-based; range checked in finish)
 *   uv      n UV indices, or NULL for a face without UVs
 *   origin  number shown in messages about this face
 */
neuv_status mesh_builder_add_polygon(mesh_builder *b, int n, const int *v, const int *uv, int origin);
/* The same with normal indices per corner (vn may be NULL). */
neuv_status mesh_builder_add_polygon_normals(mesh_builder *b, int n, const int *v, const int *uv, const int *vn,
                                             int origin);
/* Validates (faces present, finite coordinates, indices in range) and moves
 * the arrays into a new mesh; UVs are kept when every face has them (a
 * warning is logged when only some do), normals likewise (dropped with a
 * warning when an index is out of range or a normal not finite), face
 * materials when any face has one (faces before the first get material 0
 * with the others renumbered after it; the attributes' material names
 * follow), polygons when one has more than 3 corners or the attributes
 * have per-polygon values, group states when any face has one. The builder is emptied either way. */
/* The builder's attributes, made on first use; NULL when memory runs out. */
struct mesh_attributes *mesh_builder_attributes(mesh_builder *b);
neuv_status mesh_builder_finish(mesh_builder *b, mesh_builder_style style, neuv_mesh **out);

#endif
