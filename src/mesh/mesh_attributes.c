#include "mesh/mesh_attributes.h"

#include <string.h>

#include "core/mem.h"

mesh_attributes *mesh_attributes_new(void) { return mem_calloc(1, sizeof(mesh_attributes)); }

char *attr_strndup(const char *s, size_t n)
{
    char *c = mem_alloc(n + 1);
    if (!c) return NULL;
    memcpy(c, s, n);
    c[n] = '\0';
    return c;
}

static char *copy_string(const char *s, int *failed)
{
    if (!s) return NULL;
    char *c = attr_strndup(s, strlen(s));
    if (!c) *failed = 1;
    return c;
}

static void *copy_block(const void *src, size_t bytes, int *failed)
{
    if (!src) return NULL;
    void *d = mem_alloc(bytes > 0 ? bytes : 1);
    if (!d) { *failed = 1; return NULL; }
    memcpy(d, src, bytes);
    return d;
}

void ply_extra_free(ply_extra *e)
{
    for (int i = 0; e->name && i < e->count; i++) mem_free(e->name[i]);
    mem_free(e->name);
    mem_free(e->type);
    mem_free(e->value);
    memset(e, 0, sizeof *e);
}

static void copy_ply_extra(ply_extra *d, const ply_extra *s, int *failed)
{
    memset(d, 0, sizeof *d);
    if (s->count == 0) return;
    d->name = mem_calloc((size_t)s->count, sizeof(char *));
    if (!d->name) { *failed = 1; return; }
    d->count = s->count;
    d->elements = s->elements;
    for (int i = 0; i < s->count; i++) d->name[i] = copy_string(s->name[i], failed);
    d->type = copy_block(s->type, sizeof(int) * (size_t)s->count, failed);
    d->value = copy_block(s->value, sizeof(double) * (size_t)s->count * (size_t)s->elements, failed);
}

mesh_attributes *mesh_attributes_clone(const mesh_attributes *a, int nv, int nf)
{
    if (!a) return NULL;
    mesh_attributes *c = mesh_attributes_new();
    if (!c) return NULL;
    int failed = 0;
    if (a->n_materials > 0) {
        c->material_name = mem_calloc((size_t)a->n_materials, sizeof(char *));
        if (!c->material_name) failed = 1;
        else c->n_materials = a->n_materials;
        for (int i = 0; c->material_name && i < a->n_materials; i++)
            c->material_name[i] = copy_string(a->material_name[i], &failed);
    }
    c->material_library = copy_string(a->material_library, &failed);
    c->gltf_materials = copy_string(a->gltf_materials, &failed);
    if (c->material_name) c->gltf_material = copy_block(a->gltf_material, sizeof(int) * (size_t)a->n_materials, &failed);
    c->gltf_textures = copy_string(a->gltf_textures, &failed);
    if (a->n_groups > 0) {
        c->groups = mem_calloc((size_t)a->n_groups, sizeof *c->groups);
        if (!c->groups) failed = 1;
        else c->n_groups = a->n_groups;
        for (int i = 0; c->groups && i < a->n_groups; i++) {
            c->groups[i].object = copy_string(a->groups[i].object, &failed);
            c->groups[i].group = copy_string(a->groups[i].group, &failed);
            c->groups[i].smooth = copy_string(a->groups[i].smooth, &failed);
        }
    }
    c->face_group = copy_block(a->face_group, sizeof(int) * (size_t)nf, &failed);
    c->color_channels = a->color_channels;
    c->color_type = a->color_type;
    c->color = copy_block(a->color, sizeof(float) * (size_t)a->color_channels * (size_t)nv, &failed);
    c->node_name = copy_string(a->node_name, &failed);
    copy_ply_extra(&c->ply_vertex, &a->ply_vertex, &failed);
    copy_ply_extra(&c->ply_face, &a->ply_face, &failed);
    for (int k = 0; k < 2; k++) c->ply_uv_name[k] = copy_string(a->ply_uv_name[k], &failed);
    c->nuv0 = a->nuv0;
    c->uv0 = copy_block(a->uv0, sizeof(double) * 2 * (size_t)a->nuv0, &failed);
    c->tri_uv0 = copy_block(a->tri_uv0, sizeof(int) * 3 * (size_t)nf, &failed);
    if (failed) { mesh_attributes_free(c); return NULL; }
    return c;
}

void mesh_attributes_free(mesh_attributes *a)
{
    if (!a) return;
    for (int i = 0; a->material_name && i < a->n_materials; i++) mem_free(a->material_name[i]);
    mem_free(a->material_name);
    mem_free(a->material_library);
    mem_free(a->gltf_materials);
    mem_free(a->gltf_material);
    mem_free(a->gltf_textures);
    for (int i = 0; a->groups && i < a->n_groups; i++) {
        mem_free(a->groups[i].object);
        mem_free(a->groups[i].group);
        mem_free(a->groups[i].smooth);
    }
    mem_free(a->groups);
    mem_free(a->face_group);
    mem_free(a->color);
    mem_free(a->node_name);
    ply_extra_free(&a->ply_vertex);
    ply_extra_free(&a->ply_face);
    for (int k = 0; k < 2; k++) mem_free(a->ply_uv_name[k]);
    mem_free(a->uv0);
    mem_free(a->tri_uv0);
    mem_free(a);
}

int attr_same_text(const char *a, const char *b) { return a == b || (a && b && !strcmp(a, b)); }
