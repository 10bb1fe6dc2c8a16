/* glTF 2.0 reader (.gltf JSON and .glb binary), neuv's own rather than
 * Assimp's: fuzzing found Assimp 5.2's glTF importer reading past its
 * buffers on malformed files (bench/RESULTS.md, "Fuzzing"), and a reader
 * that checks every offset against the bytes it has is short.
 *
 * What is read: the default scene's node tree (every node once; matrix or
 * translation/rotation/scale), each mesh's primitives of mode TRIANGLES,
 * TRIANGLE_STRIP or TRIANGLE_FAN (points and lines are skipped: they are no
 * surface), POSITION (float VEC3), TEXCOORD_0 (float, or normalized unsigned
 * byte/short, VEC2; v flipped to neuv's bottom-left origin), NORMAL (float
 * VEC3, turned with the node; left out otherwise) and each primitive's
 * material (they mark hard edges: mesh/hard_edges.h), indices
 * (unsigned byte/short/int), COLOR_0 (float, or normalized unsigned
 * byte/short, VEC3 or VEC4; kept when every primitive has it).
 * Kept in the mesh's attributes to be written back (io/gltf_write.c): the
 * materials array (re-serialized from the parsed JSON: the same values and
 * key order, numbers in their shortest exact form) with the textures,
 * samplers and images it refers to (images stored in a bufferView become
 * data URIs), the material names, each face_material value's index in the
 * file (attr->gltf_material; face_material is the file's index, shifted by
 * one when some primitive has no material) and the first mesh node's name.
 * TEXCOORD_0 is the mesh's UVs; TEXCOORD_1 and other sets are not kept.
 * Buffers come from the GLB's BIN chunk, base64
 * data URIs, or files beside the .gltf. Refused with a message: sparse
 * accessors, accessors without a bufferView, Draco or other required
 * extensions, offsets or counts that leave their buffer, node trees that are
 * not trees. Vertices are never joined (mesh/clean.h welds). */
#include <ctype.h>
#include <limits.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/json_reader.h"
#include "core/json_writer.h"
#include "core/log.h"
#include "core/mem.h"
#include "io/base64.h"
#include "io/mesh_builder.h"
#include "io/mesh_io.h"
#include "mesh/mesh_attributes.h"

/* More vertices than this, after instancing, is refused rather than risked. */
#define GLTF_MAX_VERTICES 50000000LL

enum {
    GL_BYTE = 5120, GL_UNSIGNED_BYTE = 5121, GL_SHORT = 5122, GL_UNSIGNED_SHORT = 5123,
    GL_UNSIGNED_INT = 5125, GL_FLOAT = 5126
};

typedef struct byte_span {
    const unsigned char *p;
    size_t n;
    unsigned char *owned; /* decoded or read from a file; mem_free */
} byte_span;

typedef struct gltf_file {
    json_value root;
    const json_value *accessors, *views, *meshes, *nodes;
    byte_span *buffers;
    int nbuffers;
    mesh_builder *b;
    long long vertices; /* added so far, instances included */
    int faces;          /* primitives' triangles, for messages */
    float *color;       /* #V by 4: COLOR_0 of the vertices added */
    size_t cap_color;
    int prims_with_color, prims_without_color, color4;
    const char *node_name; /* the first mesh node's name (in root) */
} gltf_file;

typedef struct affine { double m[3][4]; } affine;

static uint32_t get_u32le(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static neuv_status bad(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static neuv_status bad(const char *fmt, ...)
{
    char msg[300];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    /* Names from the file (a version, a URI) may hold control characters:
     * the message stays one line. */
    for (char *c = msg; *c; c++) if ((unsigned char)*c < 0x20) *c = '?';
    return error_set(NEUV_ERR_INPUT, "glTF: %s", msg);
}

/* ---- buffers --------------------------------------------------------- */

static int is_data_uri(const char *uri) { return !strncmp(uri, "data:", 5); }

static neuv_status read_external(const char *dir, const char *uri, int i, byte_span *out)
{
    if (!dir) return bad("buffer %lld refers to a file, which cannot be read from memory", (long long)i);
    /* glTF URIs are percent-encoded; decode %XX, refuse anything odd. */
    size_t ul = strlen(uri), dl = strlen(dir);
    char *path = mem_alloc(dl + ul + 2);
    if (!path) return error_nomem("a buffer's path");
    size_t n = 0;
    if (dl) { memcpy(path, dir, dl); n = dl; if (path[n - 1] != '/') path[n++] = '/'; }
    for (size_t k = 0; k < ul; k++) {
        unsigned v;
        if (uri[k] == '%' && k + 2 < ul && isxdigit((unsigned char)uri[k + 1]) && isxdigit((unsigned char)uri[k + 2]) &&
            sscanf(uri + k + 1, "%2x", &v) == 1 && v > 0) {
            path[n++] = (char)v;
            k += 2;
        } else {
            path[n++] = uri[k];
        }
    }
    path[n] = '\0';
    FILE *fp = fopen(path, "rb");
    if (!fp) {
        neuv_status s = bad("buffer %d: cannot open '%s'", i, uri);
        mem_free(path);
        return s;
    }
    mem_free(path);
    char *buf = NULL;
    size_t len = 0;
    neuv_status s = io_read_all(fp, &buf, &len);
    fclose(fp);
    if (s) return s;
    out->p = out->owned = (unsigned char *)buf;
    out->n = len;
    return NEUV_OK;
}

static neuv_status load_buffers(gltf_file *g, const byte_span *bin, const char *dir)
{
    const json_value *bufs = json_get(&g->root, "buffers");
    if (!bufs) return NEUV_OK;
    if (bufs->type != JSON_ARRAY) return bad("'buffers' is not an array");
    g->buffers = mem_calloc(bufs->n ? (size_t)bufs->n : 1, sizeof *g->buffers);
    if (!g->buffers) return error_nomem("the glTF buffers");
    g->nbuffers = bufs->n;
    for (int i = 0; i < bufs->n; i++) {
        const json_value *bv = json_at(bufs, i);
        long long len;
        if (!json_int_in(json_get(bv, "byteLength"), 1, 1LL << 40, &len))
            return bad("buffer %lld has no valid byteLength", (long long)i);
        const json_value *uri = json_get(bv, "uri");
        byte_span *sp = &g->buffers[i];
        if (!uri) {
            if (i != 0 || !bin) return bad("buffer %lld has no uri and there is no GLB binary chunk", (long long)i);
            *sp = *bin;
        } else if (uri->type != JSON_STRING) {
            return bad("buffer %lld: uri is not a string", (long long)i);
        } else if (is_data_uri(uri->string)) {
            const char *comma = strchr(uri->string, ',');
            if (!comma || comma - uri->string < 7 || strncmp(comma - 7, ";base64", 7))
                return bad("buffer %lld: only base64 data URIs are read", (long long)i);
            size_t tl = uri->string_len - (size_t)(comma + 1 - uri->string);
            int r = base64_decode(comma + 1, tl, &sp->owned, &sp->n);
            if (r == -2) return error_nomem("a glTF buffer");
            if (r) return bad("buffer %lld: bad base64 in its data URI", (long long)i);
            sp->p = sp->owned;
        } else {
            neuv_status s = read_external(dir, uri->string, i, sp);
            if (s) return s;
        }
        if (sp->n < (size_t)len) return bad("buffer %lld is shorter than its byteLength", (long long)i);
        sp->n = (size_t)len;
    }
    return NEUV_OK;
}

/* ---- accessors ------------------------------------------------------- */

typedef struct accessor {
    const unsigned char *p; /* first element */
    size_t stride;
    long long count;
    int comps, type, normalized;
} accessor;

static int component_size(int type)
{
    switch (type) {
    case GL_BYTE: case GL_UNSIGNED_BYTE: return 1;
    case GL_SHORT: case GL_UNSIGNED_SHORT: return 2;
    case GL_UNSIGNED_INT: case GL_FLOAT: return 4;
    default: return 0;
    }
}

static int components_of(const json_value *t)
{
    if (!t || t->type != JSON_STRING) return 0;
    static const char *names[] = {"SCALAR", "VEC2", "VEC3", "VEC4"};
    for (int k = 0; k < 4; k++) if (!strcmp(t->string, names[k])) return k + 1;
    return 0;
}

/* Accessor `index`, its bytes bounds-checked against its view and buffer. */
static neuv_status get_accessor(const gltf_file *g, const json_value *index, accessor *a)
{
    long long ai, vi, bi, off = 0, voff = 0, vlen, stride = 0, type, count;
    if (!json_int_in(index, 0, INT32_MAX, &ai) || !json_at(g->accessors, (int)ai))
        return bad("reference to a missing accessor");
    const json_value *av = json_at(g->accessors, (int)ai);
    if (json_get(av, "sparse")) return bad("accessor %lld is sparse (not supported)", (long long)ai);
    if (!json_get(av, "bufferView")) return bad("accessor %lld has no bufferView (zero-filled accessors are not supported)", (long long)ai);
    if (!json_int_in(json_get(av, "bufferView"), 0, INT32_MAX, &vi) || !json_at(g->views, (int)vi))
        return bad("accessor %lld refers to a missing bufferView", (long long)ai);
    if (json_get(av, "byteOffset") && !json_int_in(json_get(av, "byteOffset"), 0, INT32_MAX, &off))
        return bad("accessor %lld has a bad byteOffset", (long long)ai);
    if (!json_int_in(json_get(av, "componentType"), 0, INT32_MAX, &type) || !component_size((int)type))
        return bad("accessor %lld has a bad componentType", (long long)ai);
    if (!json_int_in(json_get(av, "count"), 1, INT32_MAX, &count)) return bad("accessor %lld has a bad count", (long long)ai);
    int comps = components_of(json_get(av, "type"));
    if (!comps) return bad("accessor %lld has a type other than SCALAR or VEC2-4", (long long)ai);
    const json_value *norm = json_get(av, "normalized");
    const json_value *view = json_at(g->views, (int)vi);
    if (!json_int_in(json_get(view, "buffer"), 0, INT32_MAX, &bi) || bi >= g->nbuffers)
        return bad("bufferView %lld refers to a missing buffer", (long long)vi);
    if (json_get(view, "byteOffset") && !json_int_in(json_get(view, "byteOffset"), 0, INT32_MAX, &voff))
        return bad("bufferView %lld has a bad byteOffset", (long long)vi);
    if (!json_int_in(json_get(view, "byteLength"), 1, INT32_MAX, &vlen)) return bad("bufferView %lld has a bad byteLength", (long long)vi);
    if (json_get(view, "byteStride") && !json_int_in(json_get(view, "byteStride"), 4, 252, &stride))
        return bad("bufferView %lld has a bad byteStride", (long long)vi);
    const byte_span *buf = &g->buffers[bi];
    if ((unsigned long long)voff + (unsigned long long)vlen > buf->n) return bad("bufferView %lld leaves its buffer", (long long)vi);
    long long elem = (long long)comps * component_size((int)type);
    if (!stride) stride = elem;
    if (stride < elem) return bad("bufferView %lld: byteStride is smaller than an element", (long long)vi);
    /* Every operand is below 2^31, so the product fits in 64 bits. */
    if (off + stride * (count - 1) + elem > vlen) return bad("accessor %lld leaves its bufferView", (long long)ai);
    a->p = buf->p + voff + off;
    a->stride = (size_t)stride;
    a->count = count;
    a->comps = comps;
    a->type = (int)type;
    a->normalized = norm && norm->type == JSON_BOOL && norm->boolean;
    return NEUV_OK;
}

static double component(const accessor *a, long long i, int c)
{
    const unsigned char *p = a->p + (size_t)i * a->stride + (size_t)c * (size_t)component_size(a->type);
    uint32_t u;
    switch (a->type) {
    case GL_FLOAT: { float f; u = get_u32le(p); memcpy(&f, &u, 4); return f; }
    case GL_UNSIGNED_INT: return get_u32le(p);
    case GL_UNSIGNED_SHORT: return (double)(p[0] | p[1] << 8);
    case GL_UNSIGNED_BYTE: return p[0];
    case GL_SHORT: return (double)(int16_t)(uint16_t)(p[0] | p[1] << 8);
    default: return (double)(int8_t)p[0];
    }
}

/* ---- meshes ---------------------------------------------------------- */

static neuv_status add_primitive(gltf_file *g, const json_value *prim, long long mi, const affine *T)
{
    long long mode = 4;
    if (json_get(prim, "mode") && !json_int_in(json_get(prim, "mode"), 0, 6, &mode))
        return bad("mesh %lld has a primitive of unknown mode", (long long)mi);
    if (mode < 4) return NEUV_OK; /* points and lines are no surface */
    if (json_get(json_get(prim, "extensions"), "KHR_draco_mesh_compression"))
        return bad("mesh %lld: Draco-compressed primitives are not read (decompress the file first)", mi);
    const json_value *attr = json_get(prim, "attributes");
    accessor pos, uv, idx;
    if (!json_get(attr, "POSITION")) return bad("mesh %lld has a primitive without POSITION", (long long)mi);
    neuv_status s = get_accessor(g, json_get(attr, "POSITION"), &pos);
    if (s) return s;
    if (pos.comps != 3 || pos.type != GL_FLOAT) return bad("mesh %lld: POSITION is not float VEC3", (long long)mi);
    int has_uv = json_get(attr, "TEXCOORD_0") != NULL;
    if (has_uv) {
        if ((s = get_accessor(g, json_get(attr, "TEXCOORD_0"), &uv))) return s;
        if (uv.comps != 2 || !(uv.type == GL_FLOAT || (uv.normalized && (uv.type == GL_UNSIGNED_BYTE || uv.type == GL_UNSIGNED_SHORT))))
            return bad("mesh %lld: TEXCOORD_0 is not float (or normalized unsigned) VEC2", (long long)mi);
        if (uv.count != pos.count) return bad("mesh %lld: TEXCOORD_0 and POSITION differ in count", (long long)mi);
    }
    /* Normals only mark hard edges (mesh/hard_edges.h): one that is not float VEC3 is left out. */
    accessor nrm;
    int has_normal = json_get(attr, "NORMAL") != NULL;
    if (has_normal) {
        if ((s = get_accessor(g, json_get(attr, "NORMAL"), &nrm))) return s;
        has_normal = nrm.comps == 3 && nrm.type == GL_FLOAT && nrm.count == pos.count;
    }
    /* Colours are kept for writing back; one of another layout is left out. */
    accessor col = {0};
    int has_color = json_get(attr, "COLOR_0") != NULL;
    if (has_color) {
        if ((s = get_accessor(g, json_get(attr, "COLOR_0"), &col))) return s;
        has_color = (col.comps == 3 || col.comps == 4) && col.count == pos.count &&
                    (col.type == GL_FLOAT || (col.normalized && (col.type == GL_UNSIGNED_BYTE || col.type == GL_UNSIGNED_SHORT)));
    }
    long long material = -1;
    if (json_get(prim, "material") && !json_int_in(json_get(prim, "material"), 0, INT_MAX / 2, &material))
        return bad("mesh %lld: a primitive's material is not a material index", (long long)mi);
    int has_idx = json_get(prim, "indices") != NULL;
    if (has_idx) {
        if ((s = get_accessor(g, json_get(prim, "indices"), &idx))) return s;
        if (idx.comps != 1 || !(idx.type == GL_UNSIGNED_BYTE || idx.type == GL_UNSIGNED_SHORT || idx.type == GL_UNSIGNED_INT))
            return bad("mesh %lld: indices are not unsigned SCALAR", (long long)mi);
    }
    if (g->vertices + pos.count > GLTF_MAX_VERTICES)
        return bad("more than %lld vertices once every node's mesh is placed", (long long)GLTF_MAX_VERTICES);
    g->vertices += pos.count;

    mesh_builder *b = g->b;
    int base = b->nv, uv_base = b->nuv, normal_base = b->nn;
    if (has_color) {
        g->prims_with_color++;
        g->color4 |= col.comps == 4;
    } else {
        g->prims_without_color++;
    }
    if (g->prims_without_color == 0) {
        size_t need = 4 * ((size_t)base + (size_t)pos.count);
        if (need > g->cap_color) {
            size_t cap = need > 2 * g->cap_color ? need : 2 * g->cap_color;
            float *c = mem_realloc(g->color, cap * sizeof(float));
            if (!c) return error_nomem("vertex colours");
            g->color = c;
            g->cap_color = cap;
        }
        double cs = col.type == GL_FLOAT ? 1 : col.type == GL_UNSIGNED_BYTE ? 1.0 / 255 : 1.0 / 65535;
        for (long long i = 0; i < pos.count; i++)
            for (int k = 0; k < 4; k++)
                g->color[4 * ((size_t)base + (size_t)i) + (size_t)k] = k < col.comps ? (float)(cs * component(&col, i, k)) : 1.0f;
    }
    b->material = (int)material;
    /* Normals go through the cofactor matrix of the node's linear part (the
     * inverse transpose times the determinant), sign fixed so that a
     * mirroring node keeps them pointing out of the faces it mirrors. */
    double cof[3][3], det = 0;
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) {
            int r1 = (r + 1) % 3, r2 = (r + 2) % 3, c1 = (c + 1) % 3, c2 = (c + 2) % 3;
            cof[r][c] = T->m[r1][c1] * T->m[r2][c2] - T->m[r1][c2] * T->m[r2][c1];
        }
    for (int c = 0; c < 3; c++) det += T->m[0][c] * cof[0][c];
    double sign = det < 0 ? -1 : 1;
    double uv_scale = !has_uv || uv.type == GL_FLOAT ? 1 : uv.type == GL_UNSIGNED_BYTE ? 1.0 / 255 : 1.0 / 65535;
    for (long long i = 0; i < pos.count; i++) {
        double x = component(&pos, i, 0), y = component(&pos, i, 1), z = component(&pos, i, 2), q[3];
        for (int r = 0; r < 3; r++) q[r] = T->m[r][0] * x + T->m[r][1] * y + T->m[r][2] * z + T->m[r][3];
        s = mesh_builder_add_vertex(b, q[0], q[1], q[2]);
        if (s == NEUV_OK && has_uv) s = mesh_builder_add_uv(b, uv_scale * component(&uv, i, 0), 1.0 - uv_scale * component(&uv, i, 1));
        if (s == NEUV_OK && has_normal) {
            double nx = component(&nrm, i, 0), ny = component(&nrm, i, 1), nz = component(&nrm, i, 2), n[3];
            for (int r = 0; r < 3; r++) n[r] = sign * (cof[r][0] * nx + cof[r][1] * ny + cof[r][2] * nz);
            s = mesh_builder_add_normal(b, n[0], n[1], n[2]);
        }
        if (s) return s;
    }
    long long n = has_idx ? idx.count : pos.count;
    long long tris = mode == 4 ? n / 3 : n - 2;
    for (long long t = 0; t < tris; t++) {
        long long k[3];
        if (mode == 4) { k[0] = 3 * t; k[1] = 3 * t + 1; k[2] = 3 * t + 2; }
        else if (mode == 5) { k[0] = t + (t & 1); k[1] = t + 1 - (t & 1); k[2] = t + 2; } /* keep strips' winding */
        else { k[0] = 0; k[1] = t + 1; k[2] = t + 2; }
        int v[3], w[3], nn[3];
        for (int c = 0; c < 3; c++) {
            long long vi = has_idx ? (long long)component(&idx, k[c], 0) : k[c];
            if (vi >= pos.count) return bad("mesh %lld: an index is past the vertex count", (long long)mi);
            v[c] = base + (int)vi;
            w[c] = uv_base + (int)vi;
            nn[c] = normal_base + (int)vi;
        }
        if ((s = mesh_builder_add_polygon_normals(b, 3, v, has_uv ? w : NULL, has_normal ? nn : NULL, g->faces++)))
            return s;
    }
    return NEUV_OK;
}

static neuv_status add_mesh(gltf_file *g, const json_value *index, const affine *T)
{
    long long mi;
    if (!json_int_in(index, 0, INT32_MAX, &mi) || !json_at(g->meshes, (int)mi)) return bad("a node refers to a missing mesh");
    const json_value *prims = json_get(json_at(g->meshes, (int)mi), "primitives");
    if (!prims || prims->type != JSON_ARRAY) return bad("mesh %lld has no primitives array", (long long)mi);
    for (int p = 0; p < prims->n; p++) {
        neuv_status s = add_primitive(g, json_at(prims, p), mi, T);
        if (s) return s;
    }
    return NEUV_OK;
}

/* ---- nodes ----------------------------------------------------------- */

static int numbers(const json_value *a, int n, double *out)
{
    if (!a || a->type != JSON_ARRAY || a->n != n) return 0;
    for (int i = 0; i < n; i++) {
        if (a->items[i].type != JSON_NUMBER) return 0;
        out[i] = a->items[i].number;
    }
    return 1;
}

static neuv_status local_transform(const json_value *node, long long ni, affine *L)
{
    double m[16], t[3] = {0, 0, 0}, r[4] = {0, 0, 0, 1}, sc[3] = {1, 1, 1};
    if (json_get(node, "matrix")) {
        if (!numbers(json_get(node, "matrix"), 16, m)) return bad("node %lld: matrix is not 16 numbers", (long long)ni);
        for (int i = 0; i < 3; i++) for (int j = 0; j < 4; j++) L->m[i][j] = m[4 * j + i]; /* column-major */
        return NEUV_OK;
    }
    if ((json_get(node, "translation") && !numbers(json_get(node, "translation"), 3, t)) ||
        (json_get(node, "rotation") && !numbers(json_get(node, "rotation"), 4, r)) ||
        (json_get(node, "scale") && !numbers(json_get(node, "scale"), 3, sc)))
        return bad("node %lld: bad translation, rotation or scale", (long long)ni);
    double x = r[0], y = r[1], z = r[2], w = r[3];
    double R[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                      {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                      {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) L->m[i][j] = R[i][j] * sc[j];
        L->m[i][3] = t[i];
    }
    return NEUV_OK;
}

static affine compose(const affine *a, const affine *b)
{
    affine r;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++) {
            double s = j == 3 ? a->m[i][3] : 0;
            for (int k = 0; k < 3; k++) s += a->m[i][k] * b->m[k][j];
            r.m[i][j] = s;
        }
    return r;
}

/* Depth-first; `seen` marks nodes reached, so that a node reached twice (a
 * cycle, or two parents) is an error rather than a repeated or endless walk. */
static neuv_status add_node(gltf_file *g, const json_value *index, const affine *parent, char *seen, int depth)
{
    long long ni;
    if (!json_int_in(index, 0, INT32_MAX, &ni) || !json_at(g->nodes, (int)ni)) return bad("reference to a missing node");
    if (seen[ni]) return bad("node %lld is reached twice: the nodes do not form a tree", (long long)ni);
    if (depth > 256) return bad("the node tree is deeper than 256");
    seen[ni] = 1;
    const json_value *node = json_at(g->nodes, (int)ni);
    affine L, T;
    neuv_status s = local_transform(node, ni, &L);
    if (s) return s;
    T = compose(parent, &L);
    if (json_get(node, "mesh") && !g->node_name && json_get(node, "name") && json_get(node, "name")->type == JSON_STRING)
        g->node_name = json_get(node, "name")->string;
    if (json_get(node, "mesh") && (s = add_mesh(g, json_get(node, "mesh"), &T))) return s;
    const json_value *kids = json_get(node, "children");
    if (kids && kids->type != JSON_ARRAY) return bad("node %lld: children is not an array", (long long)ni);
    for (int k = 0; kids && k < kids->n; k++)
        if ((s = add_node(g, json_at(kids, k), &T, seen, depth + 1))) return s;
    return NEUV_OK;
}

static neuv_status add_scene(gltf_file *g)
{
    static const affine I = {{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}};
    int nn = g->nodes && g->nodes->type == JSON_ARRAY ? g->nodes->n : 0;
    if (!nn) {
        /* No nodes: every mesh once, untransformed. */
        int nm = g->meshes && g->meshes->type == JSON_ARRAY ? g->meshes->n : 0;
        for (int i = 0; i < nm; i++) {
            json_value idx = {.type = JSON_NUMBER, .number = i};
            neuv_status s = add_mesh(g, &idx, &I);
            if (s) return s;
        }
        return NEUV_OK;
    }
    char *seen = mem_calloc((size_t)nn, 1);
    if (!seen) return error_nomem("the glTF nodes");
    neuv_status s = NEUV_OK;
    const json_value *scenes = json_get(&g->root, "scenes");
    if (scenes && scenes->type == JSON_ARRAY && scenes->n > 0) {
        long long si = 0;
        if (json_get(&g->root, "scene") && !json_int_in(json_get(&g->root, "scene"), 0, scenes->n - 1, &si))
            s = bad("'scene' names a missing scene");
        const json_value *roots = s ? NULL : json_get(json_at(scenes, (int)si), "nodes");
        for (int k = 0; s == NEUV_OK && roots && roots->type == JSON_ARRAY && k < roots->n; k++)
            s = add_node(g, json_at(roots, k), &I, seen, 0);
    } else {
        /* No scene: the nodes that are nobody's child are the roots. */
        char *child = mem_calloc((size_t)nn, 1);
        if (!child) s = error_nomem("the glTF nodes");
        for (int i = 0; s == NEUV_OK && i < nn; i++) {
            const json_value *kids = json_get(json_at(g->nodes, i), "children");
            long long c;
            for (int k = 0; kids && kids->type == JSON_ARRAY && k < kids->n; k++)
                if (json_int_in(json_at(kids, k), 0, nn - 1, &c)) child[c] = 1;
        }
        int roots = 0;
        for (int i = 0; s == NEUV_OK && i < nn; i++) {
            if (child[i]) continue;
            json_value idx = {.type = JSON_NUMBER, .number = i};
            s = add_node(g, &idx, &I, seen, 0);
            roots++;
        }
        if (s == NEUV_OK && roots == 0) s = bad("every node is another's child: the nodes do not form a tree");
        mem_free(child);
    }
    mem_free(seen);
    return s;
}

/* ---- what is kept beyond the surface -------------------------------- */

/* Writes v into w; 0 when it is nested too deep for the writer (the reader
 * allows JSON_MAX_DEPTH, the writer a little less). */
static int put_json(json_writer *w, const json_value *v, int depth)
{
    if (depth > 48) return 0;
    switch (v->type) {
    case JSON_NULL: json_null(w); return 1;
    case JSON_BOOL: json_bool(w, v->boolean); return 1;
    case JSON_NUMBER: json_number(w, v->number); return 1;
    case JSON_STRING: json_string(w, v->string); return 1;
    case JSON_ARRAY:
        json_begin_array(w);
        for (int i = 0; i < v->n; i++)
            if (!put_json(w, &v->items[i], depth + 1)) return 0;
        json_end_array(w);
        return 1;
    default:
        json_begin_object(w);
        for (int i = 0; i < v->n; i++) {
            json_key(w, v->keys[i]);
            if (!put_json(w, &v->items[i], depth + 1)) return 0;
        }
        json_end_object(w);
        return 1;
    }
}

/* An image stored in a bufferView, written with its bytes as a data URI so
 * that it needs no buffer of the source; 0 when its view is not valid. */
static int put_image(const gltf_file *g, json_writer *w, const json_value *img)
{
    long long vi, bi, off = 0, len;
    const json_value *view = json_at(g->views, json_int_in(json_get(img, "bufferView"), 0, INT32_MAX, &vi) ? (int)vi : -1);
    const json_value *mime = json_get(img, "mimeType");
    if (!view || !mime || mime->type != JSON_STRING || strlen(mime->string) > 100 ||
        !json_int_in(json_get(view, "buffer"), 0, INT32_MAX, &bi) || bi >= g->nbuffers ||
        (json_get(view, "byteOffset") && !json_int_in(json_get(view, "byteOffset"), 0, INT32_MAX, &off)) ||
        !json_int_in(json_get(view, "byteLength"), 1, INT32_MAX, &len) ||
        (unsigned long long)off + (unsigned long long)len > g->buffers[bi].n)
        return 0;
    char *b64 = base64_encode(g->buffers[bi].p + off, (size_t)len);
    if (!b64) return 0;
    size_t ul = strlen(b64) + strlen(mime->string) + 16;
    char *uri = mem_alloc(ul);
    if (uri) snprintf(uri, ul, "data:%s;base64,%s", mime->string, b64);
    mem_free(b64);
    if (!uri) return 0;
    json_begin_object(w);
    for (int i = 0; i < img->n; i++) {
        if (!strcmp(img->keys[i], "bufferView") || !strcmp(img->keys[i], "uri")) continue;
        json_key(w, img->keys[i]);
        if (!put_json(w, &img->items[i], 1)) { mem_free(uri); return 0; }
    }
    json_key(w, "uri");
    json_string(w, uri);
    json_end_object(w);
    mem_free(uri);
    return 1;
}

/* The JSON text of v, NULL when it cannot be kept. */
static char *json_text_of(const json_value *v)
{
    json_writer w;
    json_init(&w);
    int ok = put_json(&w, v, 0);
    char *text = ok && !w.failed ? attr_strndup(json_text(&w), strlen(json_text(&w))) : NULL;
    json_free(&w);
    return text;
}

/* Extensions that materials and textures use, which a written file must
 * declare again; geometry ones (compression, quantization) are not kept. */
static int material_extension(const char *name)
{
    return !strncmp(name, "KHR_materials_", 14) || !strncmp(name, "KHR_texture_", 12) ||
           !strncmp(name, "EXT_texture_", 12) || !strncmp(name, "MSFT_texture_", 13);
}

/* "textures", "samplers", "images" and the material extensionsUsed, as one
 * JSON object text; NULL (nothing kept) when there are none or one cannot be
 * written back. */
static char *texture_text(const gltf_file *g)
{
    static const char *keys[] = {"textures", "samplers", "images"};
    json_writer w;
    json_init(&w);
    json_begin_object(&w);
    int any = 0, ok = 1;
    for (int k = 0; k < 3 && ok; k++) {
        const json_value *v = json_get(&g->root, keys[k]);
        if (!v || v->type != JSON_ARRAY) continue;
        json_key(&w, keys[k]);
        if (k == 2) {
            json_begin_array(&w);
            for (int i = 0; ok && i < v->n; i++)
                ok = json_get(&v->items[i], "bufferView") ? put_image(g, &w, &v->items[i]) : put_json(&w, &v->items[i], 1);
            json_end_array(&w);
        } else {
            ok = put_json(&w, v, 1);
        }
        any = 1;
    }
    const json_value *used = json_get(&g->root, "extensionsUsed");
    int nused = 0;
    for (int i = 0; used && used->type == JSON_ARRAY && i < used->n; i++)
        if (used->items[i].type == JSON_STRING && material_extension(used->items[i].string)) {
            if (!nused++) { json_key(&w, "extensionsUsed"); json_begin_array(&w); }
            json_string(&w, used->items[i].string);
        }
    if (nused) { json_end_array(&w); any = 1; }
    json_end_object(&w);
    char *text = ok && any && !w.failed ? attr_strndup(json_text(&w), strlen(json_text(&w))) : NULL;
    if (!ok) log_message(NEUV_LOG_WARN, "glTF: the textures or images cannot be kept; they are not written back");
    json_free(&w);
    return text;
}

/* Fills the builder's attributes: materials (names, the array, what it
 * refers to), colours, the node's name. Before finish. */
static neuv_status keep_attributes(gltf_file *g, mesh_builder *b, int *n_file_materials)
{
    *n_file_materials = 0;
    const json_value *mats = json_get(&g->root, "materials");
    int colors = g->prims_with_color > 0 && g->prims_without_color == 0 && g->color;
    if (!(mats && mats->type == JSON_ARRAY && mats->n > 0) && !colors && !g->node_name) return NEUV_OK;
    mesh_attributes *a = mesh_builder_attributes(b);
    if (!a) return error_nomem("the glTF attributes");
    if (g->node_name && !(a->node_name = attr_strndup(g->node_name, strlen(g->node_name))))
        return error_nomem("the node's name");
    if (colors) {
        int ch = g->color4 ? 4 : 3;
        a->color = mem_alloc(sizeof(float) * (size_t)ch * (size_t)(b->nv > 0 ? b->nv : 1));
        if (!a->color) return error_nomem("vertex colours");
        for (size_t v = 0; v < (size_t)b->nv; v++)
            for (int k = 0; k < ch; k++) a->color[(size_t)ch * v + (size_t)k] = g->color[4 * v + (size_t)k];
        a->color_channels = ch;
    }
    if (!(mats && mats->type == JSON_ARRAY && mats->n > 0)) return NEUV_OK;
    if (!(a->gltf_materials = json_text_of(mats))) {
        log_message(NEUV_LOG_WARN, "glTF: the materials are nested too deep to be kept; they are not written back");
        return NEUV_OK;
    }
    a->gltf_textures = texture_text(g);
    int any_material = 0;
    for (int f = 0; f < b->nf && !any_material; f++) any_material = b->face_material[f] >= 0;
    if (!any_material) return NEUV_OK;
    a->material_name = mem_calloc((size_t)mats->n, sizeof(char *));
    if (!a->material_name) return error_nomem("material names");
    a->n_materials = mats->n;
    for (int i = 0; i < mats->n; i++) {
        const json_value *name = json_get(&mats->items[i], "name");
        if (name && name->type == JSON_STRING && !(a->material_name[i] = attr_strndup(name->string, strlen(name->string))))
            return error_nomem("material names");
    }
    *n_file_materials = mats->n;
    return NEUV_OK;
}

/* After finish: the file's material index of each face_material value
 * (finish put an unnamed material first when some primitive has none). */
static neuv_status map_materials(neuv_mesh *m, int n_file_materials)
{
    mesh_attributes *a = m->attr;
    if (!a || !m->face_material || n_file_materials == 0 || a->n_materials == 0) return NEUV_OK;
    int shift = a->n_materials - n_file_materials;
    a->gltf_material = mem_alloc(sizeof(int) * (size_t)a->n_materials);
    if (!a->gltf_material) return error_nomem("material indices");
    for (int i = 0; i < a->n_materials; i++) a->gltf_material[i] = i - shift;
    return NEUV_OK;
}

/* ---- the file -------------------------------------------------------- */

/* Extensions that change where the geometry's bytes are, refused when the
 * file requires them; others (materials, texture transforms) do not touch
 * positions or texture coordinates. */
static neuv_status check_required_extensions(const json_value *root)
{
    static const char *refused[] = {"KHR_draco_mesh_compression", "EXT_meshopt_compression"};
    const json_value *req = json_get(root, "extensionsRequired");
    for (int i = 0; req && req->type == JSON_ARRAY && i < req->n; i++) {
        const json_value *e = json_at(req, i);
        for (int k = 0; k < 2; k++)
            if (e->type == JSON_STRING && !strcmp(e->string, refused[k]))
                return bad("the file requires %s, which neuv does not read (decompress the file first)", refused[k]);
    }
    return NEUV_OK;
}

neuv_status io_read_gltf(const char *data, size_t len, const char *dir, neuv_mesh **out)
{
    *out = NULL;
    const unsigned char *d = (const unsigned char *)data;
    const char *json = data;
    size_t json_len = len;
    byte_span bin = {0}, *binp = NULL;
    if (len >= 3 && !memcmp(d, "\xEF\xBB\xBF", 3)) { json += 3; json_len -= 3; } /* a UTF-8 byte order mark */
    if (len >= 4 && !memcmp(d, "glTF", 4)) {
        if (len < 20) return error_set(NEUV_ERR_INPUT, "glTF: GLB file shorter than its header");
        if (get_u32le(d + 4) != 2) return error_set(NEUV_ERR_INPUT, "glTF: GLB version %u (only 2 is read)", get_u32le(d + 4));
        size_t total = get_u32le(d + 8);
        if (total > len) return error_set(NEUV_ERR_INPUT, "glTF: GLB header gives %zu bytes, the file has %zu", total, len);
        if (total < 20) return error_set(NEUV_ERR_INPUT, "glTF: GLB header gives %zu bytes, less than a header and a chunk", total);
        size_t clen = get_u32le(d + 12);
        if (get_u32le(d + 16) != 0x4E4F534Au) return error_set(NEUV_ERR_INPUT, "glTF: GLB's first chunk is not JSON");
        if (clen > total - 20) return error_set(NEUV_ERR_INPUT, "glTF: GLB's JSON chunk leaves the file");
        json = data + 20;
        json_len = clen;
        size_t at = 20 + ((clen + 3) & ~(size_t)3);
        if (at + 8 <= total && get_u32le(d + at + 4) == 0x004E4942u) {
            size_t blen = get_u32le(d + at);
            if (blen > total - at - 8) return error_set(NEUV_ERR_INPUT, "glTF: GLB's binary chunk leaves the file");
            bin.p = d + at + 8;
            bin.n = blen;
            binp = &bin;
        }
    }
    gltf_file g;
    memset(&g, 0, sizeof g);
    neuv_status s = json_parse(json, json_len, &g.root);
    if (s == NEUV_ERR_INPUT) {
        char msg[300];
        snprintf(msg, sizeof msg, "%s", neuv_last_error());
        return bad("%s", msg);
    }
    if (s) return s;
    mesh_builder b;
    mesh_builder_init(&b);
    g.b = &b;
    const json_value *asset = json_get(&g.root, "asset");
    const json_value *ver = json_get(asset, "version");
    if (g.root.type != JSON_OBJECT || !ver || ver->type != JSON_STRING) s = error_set(NEUV_ERR_INPUT, "glTF: no asset.version: not a glTF file");
    else if (strncmp(ver->string, "2.", 2)) s = bad("version %.20s (only 2.x is read)", ver->string);
    if (!s) s = check_required_extensions(&g.root);
    if (!s) {
        g.accessors = json_get(&g.root, "accessors");
        g.views = json_get(&g.root, "bufferViews");
        g.meshes = json_get(&g.root, "meshes");
        g.nodes = json_get(&g.root, "nodes");
        s = load_buffers(&g, binp, dir);
    }
    if (!s) s = add_scene(&g);
    if (!s && b.nf == 0) s = error_set(NEUV_ERR_INPUT, "glTF: no triangles in the default scene");
    int n_file_materials = 0;
    if (!s) s = keep_attributes(&g, &b, &n_file_materials);
    for (int i = 0; i < g.nbuffers; i++) mem_free(g.buffers[i].owned);
    mem_free(g.buffers);
    mem_free(g.color);
    json_value_free(&g.root);
    if (s) { mesh_builder_free(&b); return s; }
    mesh_builder_style style = {0, 0};
    s = mesh_builder_finish(&b, style, out);
    if (s == NEUV_OK && (s = map_materials(*out, n_file_materials)) != NEUV_OK) { mesh_free(*out); *out = NULL; }
    return s;
}
