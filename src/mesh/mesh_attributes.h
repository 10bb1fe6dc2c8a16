/* What a file carries beyond the surface, kept so that the unwrapped mesh
 * can be written back with it: material names and library, OBJ object /
 * group / smoothing statements, vertex colours, the glTF node's name and
 * materials, PLY's other properties, and a UV set to keep before the atlas
 * (--uv-channel 1). None of it changes the unwrap; io/ fills it and the
 * writers use what their format can say. Cleaning drops it. */
#ifndef NEUV_MESH_MESH_ATTRIBUTES_H
#define NEUV_MESH_MESH_ATTRIBUTES_H

#include <stddef.h>

/* OBJ's grouping statements in force for a face ("o", "g", "s" arguments,
 * NULL when not given). */
typedef struct obj_group_state {
    char *object, *group, *smooth;
} obj_group_state;

/* Properties of one PLY element that neuv does not interpret, in the file's
 * order with the file's types (values as doubles: every PLY scalar fits). */
typedef struct ply_extra {
    int count;          /* properties */
    int elements;       /* vertices, or polygons for the face element */
    char **name;
    int *type;          /* ply_scalar_type */
    double *value;      /* #elements by count */
} ply_extra;

typedef enum ply_scalar_type {
    PLY_NONE, PLY_I8, PLY_U8, PLY_I16, PLY_U16, PLY_I32, PLY_U32, PLY_F32, PLY_F64
} ply_scalar_type;

typedef struct mesh_attributes {
    int n_materials;
    char **material_name;      /* n_materials: by face_material index; NULL: unnamed */
    char *material_library;    /* OBJ `mtllib` argument(s), NULL when none */
    char *gltf_materials;      /* glTF: the file's materials array as JSON text, NULL when none */
    int *gltf_material;        /* n_materials: the glTF file's material index of each face_material
                                * value (-1: none, or one the file does not have); NULL when not glTF */
    char *gltf_textures;       /* glTF: a JSON object text with what the materials refer to (the file's
                                * "textures", "samplers", "images" (embedded ones as data URIs) and
                                * their "extensionsUsed"), NULL when none */
    int n_groups;
    obj_group_state *groups;   /* n_groups */
    int *face_group;           /* #F into groups, or NULL */
    int color_channels;        /* 3 (RGB) or 4 (RGBA); 0: no colours */
    float *color;              /* #V by color_channels, in [0,1] */
    int color_type;            /* PLY type the colours were read as (PLY_U8 or PLY_F32), 0 otherwise */
    char *node_name;           /* glTF node's name, NULL when none */
    ply_extra ply_vertex, ply_face;
    char *ply_uv_name[2];      /* the PLY file's names of its UV pair ("s", "t"), NULL when none */
    int nuv0;                  /* UVs to write as the first set, the atlas's second (0: none) */
    double *uv0;               /* nuv0 by 2 */
    int *tri_uv0;              /* #F by 3 */
} mesh_attributes;

mesh_attributes *mesh_attributes_new(void);
/* A deep copy for a mesh of nv vertices and nf faces; NULL on allocation failure. */
mesh_attributes *mesh_attributes_clone(const mesh_attributes *a, int nv, int nf);
void mesh_attributes_free(mesh_attributes *a);
void ply_extra_free(ply_extra *e);
/* Whether two optional names are equal (both NULL, or the same text). */
int attr_same_text(const char *a, const char *b);
/* A copy of the n bytes at s with a NUL after them; NULL on failure. */
char *attr_strndup(const char *s, size_t n);

#endif
