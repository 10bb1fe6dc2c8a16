/* PLY reader (ascii, binary_little_endian, binary_big_endian).
 *
 * Positions of any scalar type are read into float64; optional per-vertex
 * UVs (s,t / u,v / texture_u,texture_v) or a per-face `texcoord` list (two
 * numbers per corner, which wins over per-vertex UVs); faces from a
 * `vertex_indices` (or `vertex_index`) list of any count and index type.
 * Every other property or element is skipped by its declared type. */
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/mem.h"
#include "io/mesh_builder.h"
#include "io/mesh_io.h"
#include "io/text_scan.h"

typedef enum ply_type { T_NONE, T_I8, T_U8, T_I16, T_U16, T_I32, T_U32, T_F32, T_F64 } ply_type;

static const struct { const char *name; ply_type type; } type_names[] = {
    {"char", T_I8},   {"int8", T_I8},     {"uchar", T_U8},  {"uint8", T_U8},    {"short", T_I16},
    {"int16", T_I16}, {"ushort", T_U16},  {"uint16", T_U16}, {"int", T_I32},    {"int32", T_I32},
    {"uint", T_U32},  {"uint32", T_U32},  {"float", T_F32}, {"float32", T_F32}, {"double", T_F64},
    {"float64", T_F64},
};

static ply_type type_of(const char *name)
{
    for (size_t i = 0; i < sizeof type_names / sizeof type_names[0]; i++)
        if (!strcmp(name, type_names[i].name)) return type_names[i].type;
    return T_NONE;
}

static size_t type_size(ply_type t)
{
    switch (t) {
    case T_I8: case T_U8: return 1;
    case T_I16: case T_U16: return 2;
    case T_I32: case T_U32: case T_F32: return 4;
    case T_F64: return 8;
    default: return 0;
    }
}

typedef enum ply_role { R_NONE, R_X, R_Y, R_Z, R_U, R_V, R_FACE_VERTICES, R_FACE_TEXCOORD, R_NX, R_NY, R_NZ,
                        R_COUNT } ply_role;

typedef struct ply_prop {
    ply_type type, count_type; /* count_type != T_NONE for a list */
    ply_role role;
} ply_prop;

typedef enum ply_kind { K_OTHER, K_VERTEX, K_FACE } ply_kind;

typedef struct ply_element {
    char name[64];
    long long count;
    ply_kind kind;
    ply_prop *props;
    int nprops;
} ply_element;

typedef enum ply_format { F_ASCII, F_LE, F_BE } ply_format;

typedef struct ply_reader {
    ply_format format;
    const unsigned char *p, *end; /* binary data */
    text_cursor c;                /* ascii data */
} ply_reader;

/* Reads one value of type t. Returns 1, 0 at the end of the data, or -1 for a
 * malformed ascii token. */
static int read_value(ply_reader *r, ply_type t, double *x)
{
    if (r->format == F_ASCII) {
        if (!text_skip_space(&r->c, 0)) return 0;
        if (t == T_F32 || t == T_F64) return text_read_double(&r->c, x);
        long long v;
        int k = text_read_long(&r->c, &v);
        if (k > 0) *x = (double)v;
        return k;
    }
    size_t n = type_size(t);
    if ((size_t)(r->end - r->p) < n) return 0;
    uint64_t u = 0;
    if (r->format == F_LE)
        for (size_t i = 0; i < n; i++) u |= (uint64_t)r->p[i] << (8 * i);
    else
        for (size_t i = 0; i < n; i++) u = (u << 8) | r->p[i];
    r->p += n;
    switch (t) {
    case T_I8: *x = (int8_t)(uint8_t)u; break;
    case T_U8: *x = (uint8_t)u; break;
    case T_I16: *x = (int16_t)(uint16_t)u; break;
    case T_U16: *x = (uint16_t)u; break;
    case T_I32: *x = (int32_t)(uint32_t)u; break;
    case T_U32: *x = (uint32_t)u; break;
    case T_F32: { uint32_t w = (uint32_t)u; float f; memcpy(&f, &w, 4); *x = f; break; }
    case T_F64: memcpy(x, &u, 8); break;
    default: return -1;
    }
    return 1;
}

/* ---- header ---------------------------------------------------------- */

typedef struct ply_header {
    ply_format format;
    ply_element *elems;
    int nelems;
    size_t data_offset;
    int data_line; /* line number where the data starts (ascii messages) */
} ply_header;

static void header_free(ply_header *h)
{
    for (int i = 0; i < h->nelems; i++) mem_free(h->elems[i].props);
    mem_free(h->elems);
    memset(h, 0, sizeof *h);
}

static ply_role role_of(ply_kind kind, const char *name, int is_list)
{
    if (kind == K_VERTEX && !is_list) {
        if (!strcmp(name, "x")) return R_X;
        if (!strcmp(name, "y")) return R_Y;
        if (!strcmp(name, "z")) return R_Z;
        if (!strcmp(name, "s") || !strcmp(name, "u") || !strcmp(name, "texture_u") || !strcmp(name, "texture_s"))
            return R_U;
        if (!strcmp(name, "t") || !strcmp(name, "v") || !strcmp(name, "texture_v") || !strcmp(name, "texture_t"))
            return R_V;
        if (!strcmp(name, "nx")) return R_NX;
        if (!strcmp(name, "ny")) return R_NY;
        if (!strcmp(name, "nz")) return R_NZ;
    }
    if (kind == K_FACE && is_list) {
        if (!strcmp(name, "vertex_indices") || !strcmp(name, "vertex_index")) return R_FACE_VERTICES;
        if (!strcmp(name, "texcoord")) return R_FACE_TEXCOORD;
    }
    return R_NONE;
}

/* Splits a header line into at most 8 words (modifies line). */
static int words(char *line, char **w)
{
    int n = 0;
    char *save = NULL;
    for (char *tok = strtok_r(line, " \t\r", &save); tok && n < 8; tok = strtok_r(NULL, " \t\r", &save)) w[n++] = tok;
    return n;
}

static neuv_status parse_header(const char *data, size_t len, ply_header *h)
{
    memset(h, 0, sizeof *h);
    if (len < 4 || strncmp(data, "ply", 3) != 0 || !(data[3] == '\n' || data[3] == '\r'))
        return error_set(NEUV_ERR_INPUT, "not a PLY file: it does not start with 'ply'");
    size_t pos = 0;
    int line_no = 0, have_format = 0;
    char line[1024];
    for (;;) {
        if (pos >= len) return error_set(NEUV_ERR_INPUT, "truncated: the PLY header has no end_header");
        const char *nl = memchr(data + pos, '\n', len - pos);
        size_t n = nl ? (size_t)(nl - (data + pos)) : len - pos;
        line_no++;
        if (n >= sizeof line) return error_set(NEUV_ERR_INPUT, "line %d: PLY header line too long", line_no);
        memcpy(line, data + pos, n);
        line[n] = '\0';
        pos += n + (nl ? 1 : 0);
        char *w[8];
        int nw = words(line, w);
        if (nw == 0 || !strcmp(w[0], "comment") || !strcmp(w[0], "obj_info") || !strcmp(w[0], "ply")) continue;
        if (!strcmp(w[0], "end_header")) break;
        if (!strcmp(w[0], "format")) {
            if (nw < 2) return error_set(NEUV_ERR_INPUT, "line %d: PLY format line without a format", line_no);
            if (!strcmp(w[1], "ascii")) h->format = F_ASCII;
            else if (!strcmp(w[1], "binary_little_endian")) h->format = F_LE;
            else if (!strcmp(w[1], "binary_big_endian")) h->format = F_BE;
            else return error_set(NEUV_ERR_INPUT, "line %d: unknown PLY format '%s'", line_no, w[1]);
            have_format = 1;
        } else if (!strcmp(w[0], "element")) {
            char *end;
            long long count = nw >= 3 ? strtoll(w[2], &end, 10) : -1;
            if (nw < 3 || *end || count < 0)
                return error_set(NEUV_ERR_INPUT, "line %d: malformed PLY element line", line_no);
            ply_element *e = mem_realloc(h->elems, sizeof *e * (size_t)(h->nelems + 1));
            if (!e) return error_nomem("the PLY header");
            h->elems = e;
            e = &h->elems[h->nelems++];
            memset(e, 0, sizeof *e);
            snprintf(e->name, sizeof e->name, "%s", w[1]);
            e->count = count;
            int first_vertex = 1, first_face = 1;
            for (int i = 0; i + 1 < h->nelems; i++) {
                if (h->elems[i].kind == K_VERTEX) first_vertex = 0;
                if (h->elems[i].kind == K_FACE) first_face = 0;
            }
            if (!strcmp(w[1], "vertex") && first_vertex) e->kind = K_VERTEX;
            else if (!strcmp(w[1], "face") && first_face) e->kind = K_FACE;
            if (e->kind != K_OTHER && count > INT_MAX / 4)
                return error_set(NEUV_ERR_INPUT, "header declares %lld %s; too large for neuv", count,
                                 e->kind == K_VERTEX ? "vertices" : "faces");
        } else if (!strcmp(w[0], "property")) {
            if (h->nelems == 0) return error_set(NEUV_ERR_INPUT, "line %d: PLY property before any element", line_no);
            ply_element *e = &h->elems[h->nelems - 1];
            ply_prop pr = {T_NONE, T_NONE, R_NONE};
            const char *name;
            if (nw >= 5 && !strcmp(w[1], "list")) {
                pr.count_type = type_of(w[2]);
                pr.type = type_of(w[3]);
                name = w[4];
                if (pr.count_type == T_NONE || pr.type == T_NONE || pr.count_type == T_F32 || pr.count_type == T_F64)
                    return error_set(NEUV_ERR_INPUT, "line %d: unknown PLY list types '%s %s'", line_no, w[2], w[3]);
            } else if (nw >= 3) {
                pr.type = type_of(w[1]);
                name = w[2];
                if (pr.type == T_NONE) return error_set(NEUV_ERR_INPUT, "line %d: unknown PLY type '%s'", line_no, w[1]);
            } else {
                return error_set(NEUV_ERR_INPUT, "line %d: malformed PLY property line", line_no);
            }
            pr.role = role_of(e->kind, name, pr.count_type != T_NONE);
            ply_prop *ps = mem_realloc(e->props, sizeof *ps * (size_t)(e->nprops + 1));
            if (!ps) return error_nomem("the PLY header");
            e->props = ps;
            e->props[e->nprops++] = pr;
        } else {
            return error_set(NEUV_ERR_INPUT, "line %d: unknown PLY header keyword '%s'", line_no, w[0]);
        }
    }
    if (!have_format) return error_set(NEUV_ERR_INPUT, "the PLY header has no format line");
    h->data_offset = pos;
    h->data_line = line_no + 1;
    return NEUV_OK;
}

/* ---- data ------------------------------------------------------------ */

static neuv_status data_error(ply_reader *r, int k, const ply_element *e, long long i)
{
    if (k < 0) {
        char tok[32];
        text_token(&r->c, tok);
        return error_set(NEUV_ERR_INPUT, "line %d: malformed number '%s'", r->c.line, tok);
    }
    if (e->kind == K_VERTEX)
        return error_set(NEUV_ERR_INPUT, "truncated: header declares %lld vertices, data ends after %lld", e->count, i);
    if (e->kind == K_FACE)
        return error_set(NEUV_ERR_INPUT, "truncated: header declares %lld faces, data ends after %lld", e->count, i);
    return error_set(NEUV_ERR_INPUT, "truncated: header declares %lld '%s' elements, data ends after %lld",
                     e->count, e->name, i);
}

typedef struct face_scratch {
    int *v, *uv;
    double *tc;
    size_t cap;
} face_scratch;

static int scratch_fit(face_scratch *fs, size_t n)
{
    if (n <= fs->cap) return 1;
    size_t c = n < 64 ? 64 : n;
    int *a = mem_realloc(fs->v, c * sizeof(int));
    if (a) fs->v = a;
    int *b = mem_realloc(fs->uv, c * sizeof(int));
    if (b) fs->uv = b;
    double *t = mem_realloc(fs->tc, 2 * c * sizeof(double));
    if (t) fs->tc = t;
    if (!a || !b || !t) return 0;
    fs->cap = c;
    return 1;
}

/* The most corners a face may claim: far above any real polygon, low enough
 * that a corrupt count cannot ask for gigabytes. */
#define MAX_CORNERS 1000000

neuv_status io_read_ply(const char *data, size_t len, neuv_mesh **out)
{
    *out = NULL;
    ply_header h;
    neuv_status s = parse_header(data, len, &h);
    if (s != NEUV_OK) { header_free(&h); return s; }

    ply_reader r = {h.format, (const unsigned char *)data + h.data_offset, (const unsigned char *)data + len,
                    {data + h.data_offset, h.data_line}};
    mesh_builder b;
    mesh_builder_init(&b);
    face_scratch fs = {0};
    int vertex_uv = 0;      /* the vertex element has UV properties */
    int vertex_normal = 0;  /* ... normal properties (nx, ny, nz) */
    long long nverts = 0;   /* vertices declared */
    int face_texcoord = 0;  /* the face element has a texcoord list */
    for (int ei = 0; ei < h.nelems && s == NEUV_OK; ei++) {
        const ply_element *e = &h.elems[ei];
        if (e->kind == K_VERTEX) {
            int have[R_COUNT] = {0};
            for (int k = 0; k < e->nprops; k++) have[e->props[k].role] = 1;
            if (!have[R_X] || !have[R_Y] || !have[R_Z]) {
                s = error_set(NEUV_ERR_INPUT, "the PLY vertex element has no x, y, z properties");
                break;
            }
            vertex_uv = have[R_U] && have[R_V];
            vertex_normal = have[R_NX] && have[R_NY] && have[R_NZ];
            nverts = e->count;
            long long room = h.format == F_ASCII ? (long long)(len / 6) + 16 : (long long)(len / 12) + 16;
            s = mesh_builder_reserve(&b, e->count < room ? e->count : room, 0);
        }
        if (e->kind == K_FACE) {
            int have_v = 0;
            for (int k = 0; k < e->nprops; k++) {
                have_v |= e->props[k].role == R_FACE_VERTICES;
                face_texcoord |= e->props[k].role == R_FACE_TEXCOORD;
            }
            if (!have_v) { s = error_set(NEUV_ERR_INPUT, "the PLY face element has no vertex_indices list"); break; }
            /* Per-corner texcoords replace per-vertex UVs read before. */
            if (face_texcoord) b.nuv = 0;
            long long room = (long long)(len / 8) + 16;
            s = mesh_builder_reserve(&b, 0, e->count < room ? e->count : room);
        }
        if (s != NEUV_OK || e->nprops == 0) continue;
        for (long long i = 0; i < e->count && s == NEUV_OK; i++) {
            double x[R_COUNT] = {0};
            int nc = 0, ntc = -1;
            for (int k = 0; k < e->nprops && s == NEUV_OK; k++) {
                const ply_prop *pr = &e->props[k];
                double val;
                int got;
                if (pr->count_type == T_NONE) {
                    if ((got = read_value(&r, pr->type, &val)) <= 0) { s = data_error(&r, got, e, i); break; }
                    if (pr->role != R_NONE) x[pr->role] = val;
                    continue;
                }
                double cnt;
                if ((got = read_value(&r, pr->count_type, &cnt)) <= 0) { s = data_error(&r, got, e, i); break; }
                if (cnt < 0 || cnt > MAX_CORNERS) {
                    s = error_set(NEUV_ERR_INPUT, "%s %lld has a list of %.0f items", e->name, i, cnt);
                    break;
                }
                size_t n = (size_t)cnt;
                if (pr->role == R_NONE && r.format != F_ASCII) {
                    size_t bytes = n * type_size(pr->type);
                    if ((size_t)(r.end - r.p) < bytes) { s = data_error(&r, 0, e, i); break; }
                    r.p += bytes;
                    continue;
                }
                if (pr->role != R_NONE && !scratch_fit(&fs, pr->role == R_FACE_TEXCOORD ? (n + 1) / 2 : n)) {
                    s = error_nomem("a face");
                    break;
                }
                for (size_t j = 0; j < n; j++) {
                    if ((got = read_value(&r, pr->type, &val)) <= 0) { s = data_error(&r, got, e, i); break; }
                    if (pr->role == R_FACE_VERTICES) {
                        if (!(val >= 0 && val < (double)nverts)) {
                            s = error_set(NEUV_ERR_INPUT, "face %lld references vertex %.0f, but there are %lld vertices",
                                          i, val, nverts);
                            break;
                        }
                        fs.v[j] = (int)val;
                    } else if (pr->role == R_FACE_TEXCOORD) {
                        fs.tc[j] = val;
                    }
                }
                if (pr->role == R_FACE_VERTICES) nc = (int)n;
                if (pr->role == R_FACE_TEXCOORD) ntc = (int)n;
            }
            if (s != NEUV_OK) break;
            if (e->kind == K_VERTEX) {
                s = mesh_builder_add_vertex(&b, x[R_X], x[R_Y], x[R_Z]);
                if (s == NEUV_OK && vertex_uv) s = mesh_builder_add_uv(&b, x[R_U], x[R_V]);
                if (s == NEUV_OK && vertex_normal) s = mesh_builder_add_normal(&b, x[R_NX], x[R_NY], x[R_NZ]);
            } else if (e->kind == K_FACE) {
                if (nc < 3) {
                    s = error_set(NEUV_ERR_INPUT, "face %lld has %d corners; a face needs at least 3", i, nc);
                    break;
                }
                const int *uv = NULL;
                if (face_texcoord && ntc == 2 * nc) {
                    for (int j = 0; j < nc && s == NEUV_OK; j++) {
                        fs.uv[j] = b.nuv;
                        s = mesh_builder_add_uv(&b, fs.tc[2 * j], fs.tc[2 * j + 1]);
                    }
                    uv = fs.uv;
                } else if (!face_texcoord && vertex_uv) {
                    uv = fs.v;
                }
                if (s == NEUV_OK)
                    s = mesh_builder_add_polygon_normals(&b, nc, fs.v, uv, vertex_normal ? fs.v : NULL, (int)i);
            }
        }
    }
    mem_free(fs.v);
    mem_free(fs.uv);
    mem_free(fs.tc);
    header_free(&h);
    if (s != NEUV_OK) { mesh_builder_free(&b); return s; }
    mesh_builder_style style = {0, 0};
    return mesh_builder_finish(&b, style, out);
}
