/* glTF 2.0 writer: one mesh, one primitive (triangles), POSITION float32
 * with min/max (the spec requires them), TEXCOORD_0 float32, uint32 indices.
 * Seam vertices are split (glTF attributes are per vertex). glTF puts the UV
 * origin at the image's top-left, so v is written as 1 - v (Assimp flips it
 * back on import, as do Blender and three.js). */
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

static void accessor(json_writer *w, int view, int component, long long count, const char *type,
                     const float *lo, const float *hi)
{
    json_begin_object(w);
    json_key(w, "bufferView"); json_int(w, view);
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

neuv_status io_write_gltf(const neuv_mesh *m, FILE *fp, int binary)
{
    if (m->nf == 0 || m->nv == 0)
        return error_set(NEUV_ERR_INPUT, "the mesh has no faces; glTF needs at least one triangle");
    seam_split sp;
    neuv_status s = seam_split_vertices(m, &sp);
    if (s != NEUV_OK) return s;

    size_t pos_bytes = (size_t)sp.nv * 12, uv_bytes = sp.uv ? (size_t)sp.nv * 8 : 0;
    size_t idx_bytes = (size_t)m->nf * 12, total = pos_bytes + uv_bytes + idx_bytes; /* all multiples of 4 */
    unsigned char *buf = mem_alloc(total);
    if (!buf) { seam_split_free(&sp); return error_nomem("the glTF buffer"); }
    float lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    unsigned char *q = buf;
    for (int v = 0; v < sp.nv; v++)
        for (int k = 0; k < 3; k++) {
            /* min/max must bound the stored float32 values, so take them after rounding. */
            float x = (float)m->pos[3 * (size_t)sp.src[v] + k];
            if (v == 0 || x < lo[k]) lo[k] = x;
            if (v == 0 || x > hi[k]) hi[k] = x;
            q = put_f32le(q, x);
        }
    if (sp.uv)
        for (int v = 0; v < sp.nv; v++) {
            q = put_f32le(q, (float)sp.uv[2 * (size_t)v]);
            q = put_f32le(q, (float)(1.0 - sp.uv[2 * (size_t)v + 1]));
        }
    for (size_t c = 0; c < 3 * (size_t)m->nf; c++) q = put_u32le(q, (uint32_t)sp.tri[c]);
    int has_uv = sp.uv != NULL;
    int nv = sp.nv;
    seam_split_free(&sp);

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
    json_key(&w, "mesh"); json_int(&w, 0);
    json_end_object(&w); json_end_array(&w);
    json_key(&w, "meshes"); json_begin_array(&w); json_begin_object(&w);
    json_key(&w, "primitives"); json_begin_array(&w); json_begin_object(&w);
    json_key(&w, "attributes"); json_begin_object(&w);
    json_key(&w, "POSITION"); json_int(&w, 0);
    if (has_uv) { json_key(&w, "TEXCOORD_0"); json_int(&w, 1); }
    json_end_object(&w);
    json_key(&w, "indices"); json_int(&w, has_uv ? 2 : 1);
    json_key(&w, "mode"); json_int(&w, 4); /* TRIANGLES */
    json_end_object(&w); json_end_array(&w);
    json_end_object(&w); json_end_array(&w);
    json_key(&w, "accessors"); json_begin_array(&w);
    accessor(&w, 0, GL_FLOAT, nv, "VEC3", lo, hi);
    if (has_uv) accessor(&w, 1, GL_FLOAT, nv, "VEC2", NULL, NULL);
    accessor(&w, has_uv ? 2 : 1, GL_UNSIGNED_INT, 3LL * m->nf, "SCALAR", NULL, NULL);
    json_end_array(&w);
    json_key(&w, "bufferViews"); json_begin_array(&w);
    buffer_view(&w, 0, pos_bytes, GL_ARRAY_BUFFER);
    if (has_uv) buffer_view(&w, pos_bytes, uv_bytes, GL_ARRAY_BUFFER);
    buffer_view(&w, pos_bytes + uv_bytes, idx_bytes, GL_ELEMENT_ARRAY_BUFFER);
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

    const char *text = json_text(&w);
    size_t tlen = strlen(text);
    if (binary) {
        /* GLB: 12-byte header, JSON chunk padded with spaces, BIN chunk. */
        size_t jpad = (4 - tlen % 4) % 4;
        size_t length = 12 + 8 + tlen + jpad + 8 + total;
        if (length > UINT32_MAX) {
            mem_free(buf); json_free(&w);
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
    json_free(&w);
    return ferror(fp) ? error_set(NEUV_ERR_IO, "write failed (disk full?)") : NEUV_OK;
}
