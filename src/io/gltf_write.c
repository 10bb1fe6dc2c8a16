/* glTF 2.0 writer: one node, one mesh with a primitive per material
 * (triangles; faces grouped by face_material, in its order), one vertex
 * buffer shared by the primitives, each with its own uint32 indices.
 * Attributes: POSITION float32 with min/max (the spec requires them), NORMAL
 * (the mesh's per-corner normals, made unit length), TEXCOORD_0 and, when the
 * atlas is the second set (attr->nuv0 > 0), TEXCOORD_0 = the kept first set
 * and TEXCOORD_1 = the atlas, COLOR_0 (float VEC3/VEC4). Vertices are split
 * only where a corner's UV, normal or first-set UV differs (glTF attributes
 * are per vertex). What the reader kept comes back: the materials array as
 * read (each primitive's "material" the file's index), the textures,
 * samplers and images it refers to, the node's name; a mesh from OBJ gets a
 * material per name. glTF puts the UV origin at the image's top-left, so v
 * is written as 1 - v (Assimp flips it back on import, as do Blender and
 * three.js). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/json_writer.h"
#include "core/mem.h"
#include "io/base64.h"
#include "io/byte_order.h"
#include "io/mesh_io.h"
#include "io/seam_split.h"
#include "mesh/mesh_attributes.h"

enum { GL_FLOAT = 5126, GL_UNSIGNED_INT = 5125, GL_ARRAY_BUFFER = 34962, GL_ELEMENT_ARRAY_BUFFER = 34963 };

static void buffer_view(json_writer *w, size_t offset, size_t length, int target)
{
    json_begin_object(w);
    json_key(w, "buffer"); json_int(w, 0);
    json_key(w, "byteOffset"); json_int(w, (long long)offset);
    json_key(w, "byteLength"); json_int(w, (long long)length);
    json_key(w, "target"); json_int(w, target);
    json_end_object(w);
}

static void accessor(json_writer *w, int view, size_t offset, int component, long long count, const char *type,
                     const float *lo, const float *hi)
{
    json_begin_object(w);
    json_key(w, "bufferView"); json_int(w, view);
    if (offset) { json_key(w, "byteOffset"); json_int(w, (long long)offset); }
    json_key(w, "componentType"); json_int(w, component);
    json_key(w, "count"); json_int(w, count);
    json_key(w, "type"); json_string(w, type);
    if (lo) {
        json_key(w, "min"); json_begin_array(w);
        for (int k = 0; k < 3; k++) json_number(w, lo[k]);
        json_end_array(w);
        json_key(w, "max"); json_begin_array(w);
        for (int k = 0; k < 3; k++) json_number(w, hi[k]);
        json_end_array(w);
    }
    json_end_object(w);
}

/* The vertex attributes, in the buffer's order. */
enum { A_POSITION, A_NORMAL, A_TEXCOORD_0, A_TEXCOORD_1, A_COLOR, A_COUNT };

/* The file's material index for faces of face_material `key`, -1 for none. */
static int material_of(const neuv_mesh *m, int key)
{
    const mesh_attributes *a = m->attr;
    if (!m->face_material || !a || key < 0 || key >= a->n_materials) return -1;
    if (a->gltf_materials) return a->gltf_material ? a->gltf_material[key] : -1;
    return key;
}

static int compare_int(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

/* text with `members` (JSON object members, no braces) added before its
 * closing brace; NULL on allocation failure. */
static char *with_members(const char *text, const char *members)
{
    size_t tl = strlen(text), ml = strlen(members);
    char *r = mem_alloc(tl + ml + 2);
    if (!r) return NULL;
    memcpy(r, text, tl - 1);
    r[tl - 1] = ',';
    memcpy(r + tl, members, ml);
    r[tl + ml] = '}';
    r[tl + ml + 1] = '\0';
    return r;
}

neuv_status io_write_gltf(const neuv_mesh *m, FILE *fp, int binary)
{
    if (m->nf == 0 || m->nv == 0)
        return error_set(NEUV_ERR_INPUT, "the mesh has no faces; glTF needs at least one triangle");
    seam_split sp;
    neuv_status s = seam_split_vertices(m, &sp);
    if (s != NEUV_OK) return s;
    const mesh_attributes *a = m->attr;
    int channels = a && a->color && (a->color_channels == 3 || a->color_channels == 4) ? a->color_channels : 0;
    const double *tc0 = sp.uv0 ? sp.uv0 : sp.uv, *tc1 = sp.uv0 ? sp.uv : NULL;
    size_t nv = (size_t)sp.nv, bytes[A_COUNT] = {
        nv * 12, sp.normal ? nv * 12 : 0, tc0 ? nv * 8 : 0, tc1 ? nv * 8 : 0, nv * 4 * (size_t)channels};
    size_t idx_offset = 0;
    for (int k = 0; k < A_COUNT; k++) idx_offset += bytes[k];
    size_t idx_bytes = (size_t)m->nf * 12, total = idx_offset + idx_bytes; /* all multiples of 4 */

    /* Faces grouped by material, in the order of the material values (a
     * counting sort over the distinct values keeps the faces' order; the
     * values may be sparse). */
    int *keys = mem_alloc(sizeof(int) * (size_t)m->nf);
    int *group = mem_alloc(sizeof(int) * (size_t)m->nf);
    int *first = mem_calloc((size_t)m->nf + 1, sizeof(int));
    int *order = mem_alloc(sizeof(int) * (size_t)m->nf);
    unsigned char *buf = mem_alloc(total);
    if (!keys || !group || !first || !order || !buf) {
        mem_free(keys); mem_free(group); mem_free(first); mem_free(order); mem_free(buf); seam_split_free(&sp);
        return error_nomem("the glTF buffer");
    }
    for (int f = 0; f < m->nf; f++) keys[f] = m->face_material ? m->face_material[f] : 0;
    qsort(keys, (size_t)m->nf, sizeof(int), compare_int);
    int nkeys = 0;
    for (int f = 0; f < m->nf; f++)
        if (nkeys == 0 || keys[f] != keys[nkeys - 1]) keys[nkeys++] = keys[f];
    for (int f = 0; f < m->nf; f++) {
        int key = m->face_material ? m->face_material[f] : 0, lo = 0, hi = nkeys - 1;
        while (lo < hi) {
            int mid = (lo + hi) / 2;
            if (keys[mid] < key) lo = mid + 1;
            else hi = mid;
        }
        group[f] = lo;
        first[lo + 1]++;
    }
    for (int k = 0; k < nkeys; k++) first[k + 1] += first[k];
    for (int f = 0; f < m->nf; f++) order[first[group[f]]++] = f; /* first[k] moves to group k's end */
    for (int k = nkeys; k > 0; k--) first[k] = first[k - 1];
    first[0] = 0;
    mem_free(group);

    float lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    unsigned char *q = buf;
    for (size_t v = 0; v < nv; v++)
        for (int k = 0; k < 3; k++) {
            /* min/max must bound the stored float32 values, so take them after rounding. */
            float x = (float)m->pos[3 * (size_t)sp.src[v] + k];
            if (v == 0 || x < lo[k]) lo[k] = x;
            if (v == 0 || x > hi[k]) hi[k] = x;
            q = put_f32le(q, x);
        }
    for (size_t v = 0; sp.normal && v < nv; v++) {
        const double *n = sp.normal + 3 * v;
        double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        /* glTF wants unit normals; one of no direction is given +z. */
        if (!(len > 0) || !isfinite(len)) { q = put_f32le(put_f32le(put_f32le(q, 0), 0), 1); continue; }
        for (int k = 0; k < 3; k++) q = put_f32le(q, (float)(n[k] / len));
    }
    for (size_t v = 0; tc0 && v < nv; v++) {
        q = put_f32le(q, (float)tc0[2 * v]);
        q = put_f32le(q, (float)(1.0 - tc0[2 * v + 1]));
    }
    for (size_t v = 0; tc1 && v < nv; v++) {
        q = put_f32le(q, (float)tc1[2 * v]);
        q = put_f32le(q, (float)(1.0 - tc1[2 * v + 1]));
    }
    for (size_t v = 0; v < nv; v++)
        for (int c = 0; c < channels; c++) q = put_f32le(q, a->color[(size_t)channels * (size_t)sp.src[v] + (size_t)c]);
    for (int i = 0; i < m->nf; i++)
        for (int k = 0; k < 3; k++) q = put_u32le(q, (uint32_t)sp.tri[3 * (size_t)order[i] + k]);
    mem_free(order);
    seam_split_free(&sp);

    /* Accessor and view numbers: the present attributes in order, then one
     * index accessor per primitive over one view. */
    int view_of[A_COUNT], nviews = 0;
    for (int k = 0; k < A_COUNT; k++) view_of[k] = bytes[k] ? nviews++ : -1;
    static const char *attr_names[A_COUNT] = {"POSITION", "NORMAL", "TEXCOORD_0", "TEXCOORD_1", "COLOR_0"};

    json_writer w;
    json_init(&w);
    json_begin_object(&w);
    json_key(&w, "asset"); json_begin_object(&w);
    json_key(&w, "version"); json_string(&w, "2.0");
    char gen[64];
    snprintf(gen, sizeof gen, "neuv %s", neuv_version());
    json_key(&w, "generator"); json_string(&w, gen);
    json_end_object(&w);
    json_key(&w, "scene"); json_int(&w, 0);
    json_key(&w, "scenes"); json_begin_array(&w); json_begin_object(&w);
    json_key(&w, "nodes"); json_begin_array(&w); json_int(&w, 0); json_end_array(&w);
    json_end_object(&w); json_end_array(&w);
    json_key(&w, "nodes"); json_begin_array(&w); json_begin_object(&w);
    if (a && a->node_name) { json_key(&w, "name"); json_string(&w, a->node_name); }
    json_key(&w, "mesh"); json_int(&w, 0);
    json_end_object(&w); json_end_array(&w);
    json_key(&w, "meshes"); json_begin_array(&w); json_begin_object(&w);
    json_key(&w, "primitives"); json_begin_array(&w);
    int nprims = 0;
    for (int key = 0; key < nkeys; key++) {
        if (first[key] == first[key + 1]) continue;
        json_begin_object(&w);
        json_key(&w, "attributes"); json_begin_object(&w);
        for (int k = 0; k < A_COUNT; k++)
            if (view_of[k] >= 0) { json_key(&w, attr_names[k]); json_int(&w, view_of[k]); }
        json_end_object(&w);
        json_key(&w, "indices"); json_int(&w, nviews + nprims++);
        int mat = material_of(m, keys[key]);
        if (mat >= 0) { json_key(&w, "material"); json_int(&w, mat); }
        json_key(&w, "mode"); json_int(&w, 4); /* TRIANGLES */
        json_end_object(&w);
    }
    json_end_array(&w);
    json_end_object(&w); json_end_array(&w);
    if (a && !a->gltf_materials && a->n_materials > 0 && a->material_name && m->face_material) {
        json_key(&w, "materials"); json_begin_array(&w);
        for (int i = 0; i < a->n_materials; i++) {
            json_begin_object(&w);
            if (a->material_name[i]) { json_key(&w, "name"); json_string(&w, a->material_name[i]); }
            json_end_object(&w);
        }
        json_end_array(&w);
    }
    json_key(&w, "accessors"); json_begin_array(&w);
    accessor(&w, view_of[A_POSITION], 0, GL_FLOAT, (long long)nv, "VEC3", lo, hi);
    if (view_of[A_NORMAL] >= 0) accessor(&w, view_of[A_NORMAL], 0, GL_FLOAT, (long long)nv, "VEC3", NULL, NULL);
    if (view_of[A_TEXCOORD_0] >= 0) accessor(&w, view_of[A_TEXCOORD_0], 0, GL_FLOAT, (long long)nv, "VEC2", NULL, NULL);
    if (view_of[A_TEXCOORD_1] >= 0) accessor(&w, view_of[A_TEXCOORD_1], 0, GL_FLOAT, (long long)nv, "VEC2", NULL, NULL);
    if (view_of[A_COLOR] >= 0)
        accessor(&w, view_of[A_COLOR], 0, GL_FLOAT, (long long)nv, channels == 4 ? "VEC4" : "VEC3", NULL, NULL);
    for (int key = 0; key < nkeys; key++)
        if (first[key] < first[key + 1])
            accessor(&w, nviews, 12 * (size_t)first[key], GL_UNSIGNED_INT, 3LL * (first[key + 1] - first[key]), "SCALAR",
                     NULL, NULL);
    json_end_array(&w);
    mem_free(first);
    mem_free(keys);
    json_key(&w, "bufferViews"); json_begin_array(&w);
    size_t at = 0;
    for (int k = 0; k < A_COUNT; k++)
        if (bytes[k]) { buffer_view(&w, at, bytes[k], GL_ARRAY_BUFFER); at += bytes[k]; }
    buffer_view(&w, idx_offset, idx_bytes, GL_ELEMENT_ARRAY_BUFFER);
    json_end_array(&w);
    json_key(&w, "buffers"); json_begin_array(&w); json_begin_object(&w);
    json_key(&w, "byteLength"); json_int(&w, (long long)total);
    if (!binary) {
        char *b64 = base64_encode(buf, total);
        if (!b64) { mem_free(buf); json_free(&w); return error_nomem("the glTF buffer"); }
        static const char prefix[] = "data:application/octet-stream;base64,";
        char *uri = mem_alloc(sizeof prefix + strlen(b64));
        if (!uri) { mem_free(b64); mem_free(buf); json_free(&w); return error_nomem("the glTF buffer"); }
        memcpy(uri, prefix, sizeof prefix - 1);
        strcpy(uri + sizeof prefix - 1, b64);
        mem_free(b64);
        json_key(&w, "uri"); json_string(&w, uri);
        mem_free(uri);
    }
    json_end_object(&w); json_end_array(&w);
    json_end_object(&w);
    if (w.failed) { mem_free(buf); json_free(&w); return error_nomem("the glTF header"); }

    /* The kept materials and what they refer to, as the reader wrote them. */
    char *kept = NULL;
    if (a && a->gltf_materials && a->gltf_materials[0] == '[') {
        const char *tex = a->gltf_textures && a->gltf_textures[0] == '{' ? a->gltf_textures : "{}";
        size_t ml = strlen(a->gltf_materials), tl = strlen(tex);
        char *members = mem_alloc(ml + tl + 16);
        if (members) {
            int n = snprintf(members, ml + tl + 16, "\"materials\":%s", a->gltf_materials);
            if (tl > 2) snprintf(members + n, ml + tl + 16 - (size_t)n, ",%.*s", (int)(tl - 2), tex + 1);
            kept = with_members(json_text(&w), members);
            mem_free(members);
        }
        if (!kept) { mem_free(buf); json_free(&w); return error_nomem("the glTF header"); }
    }
    const char *text = kept ? kept : json_text(&w);
    size_t tlen = strlen(text);
    if (binary) {
        /* GLB: 12-byte header, JSON chunk padded with spaces, BIN chunk. */
        size_t jpad = (4 - tlen % 4) % 4;
        size_t length = 12 + 8 + tlen + jpad + 8 + total;
        if (length > UINT32_MAX) {
            mem_free(buf); mem_free(kept); json_free(&w);
            return error_set(NEUV_ERR_INPUT, "the mesh is too large for GLB (over 4 GiB)");
        }
        unsigned char head[20], *h = head;
        h = put_u32le(h, 0x46546C67u); /* "glTF" */
        h = put_u32le(h, 2);
        h = put_u32le(h, (uint32_t)length);
        h = put_u32le(h, (uint32_t)(tlen + jpad));
        h = put_u32le(h, 0x4E4F534Au); /* "JSON" */
        fwrite(head, 1, sizeof head, fp);
        fwrite(text, 1, tlen, fp);
        fwrite("   ", 1, jpad, fp);
        unsigned char bh[8];
        put_u32le(put_u32le(bh, (uint32_t)total), 0x004E4942u); /* "BIN\0" */
        fwrite(bh, 1, sizeof bh, fp);
        fwrite(buf, 1, total, fp);
    } else {
        fwrite(text, 1, tlen, fp);
        fputc('\n', fp);
    }
    mem_free(buf);
    mem_free(kept);
    json_free(&w);
    return ferror(fp) ? error_set(NEUV_ERR_IO, "write failed (disk full?)") : NEUV_OK;
}
