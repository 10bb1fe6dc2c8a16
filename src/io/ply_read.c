/* PLY reader (ascii, binary_little_endian, binary_big_endian).
 *
 * Positions of any scalar type are read into float64; optional per-vertex
 * UVs (s,t / u,v / texture_u,texture_v) or a per-face `texcoord` list (two
 * numbers per corner, which wins over per-vertex UVs); faces from a
 * `vertex_indices` (or `vertex_index`) list of any count and index type;
 * vertex normals nx, ny, nz (per corner in the mesh).
 * Kept in the mesh's attributes to be written back (io/ply_write.c): vertex
 * colours red, green, blue[, alpha] (any type; integers scaled to [0,1] by
 * their type's largest value, the type kept in color_type), the names of the
 * UV pair, and every other scalar property of the vertex and face elements
 * with its name and type (ply_vertex, ply_face; face values per polygon,
 * which the mesh records). A file written by neuv with two UV pairs reads
 * its first pair as the UVs; the second (s1 t1) is kept as two other
 * properties. List properties other than vertex_indices and texcoord, and
 * elements other than vertex and face, are skipped by their declared type. */
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
#include "mesh/mesh_attributes.h"

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
                        R_RED, R_GREEN, R_BLUE, R_ALPHA, R_COUNT } ply_role;

typedef struct ply_prop {
    ply_type type, count_type; /* count_type != T_NONE for a list */
    ply_role role;
    char *name;
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
    for (int i = 0; i < h->nelems; i++) {
        for (int k = 0; k < h->elems[i].nprops; k++) mem_free(h->elems[i].props[k].name);
        mem_free(h->elems[i].props);
    }
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
        if (!strcmp(name, "red")) return R_RED;
        if (!strcmp(name, "green")) return R_GREEN;
        if (!strcmp(name, "blue")) return R_BLUE;
        if (!strcmp(name, "alpha")) return R_ALPHA;
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
            ply_prop pr = {T_NONE, T_NONE, R_NONE, NULL};
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
            pr.name = attr_strndup(name, strlen(name));
            if (!pr.name) { e->props = ps; return error_nomem("the PLY header"); }
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

/* What the reader keeps beyond the surface while it reads. */
typedef struct ply_keep {
    ply_extra vertex, face; /* the other scalar properties */
    size_t cap_vertex, cap_face;
    float *color;           /* #V by 4 */
    size_t cap_color;
    int color_channels, color_type;
    const char *uv_name[2];
} ply_keep;

/* Sets up the other scalar properties of element e. */
static neuv_status extra_setup(ply_extra *x, const ply_element *e)
{
    for (int k = 0; k < e->nprops; k++) x->count += e->props[k].role == R_NONE && e->props[k].count_type == T_NONE;
    if (x->count == 0) return NEUV_OK;
    x->name = mem_calloc((size_t)x->count, sizeof(char *));
    x->type = mem_alloc(sizeof(int) * (size_t)x->count);
    if (!x->name || !x->type) return error_nomem("PLY properties");
    int j = 0;
    for (int k = 0; k < e->nprops; k++) {
        const ply_prop *pr = &e->props[k];
        if (pr->role != R_NONE || pr->count_type != T_NONE) continue;
        x->type[j] = (int)pr->type; /* ply_scalar_type has ply_type's order */
        if (!(x->name[j++] = attr_strndup(pr->name, strlen(pr->name)))) return error_nomem("PLY properties");
    }
    return NEUV_OK;
}

/* Room for element i's values (grown as the data is read, so that a header
 * claiming billions costs nothing until they come); NULL when memory runs
 * out. */
static double *extra_row(ply_extra *x, size_t *cap, long long i)
{
    size_t need = ((size_t)i + 1) * (size_t)x->count;
    if (need > *cap) {
        size_t c = need > 2 * *cap ? need : 2 * *cap;
        if (c < 64) c = 64;
        double *v = mem_realloc(x->value, c * sizeof(double));
        if (!v) return NULL;
        x->value = v;
        *cap = c;
    }
    x->elements = (int)i + 1;
    return x->value + (size_t)i * (size_t)x->count;
}

/* The largest value of an integer type (colours are scaled by it), 1 for floats. */
static double type_scale(ply_type t)
{
    switch (t) {
    case T_I8: return 127;
    case T_U8: return 255;
    case T_I16: return 32767;
    case T_U16: return 65535;
    case T_I32: return 2147483647.0;
    case T_U32: return 4294967295.0;
    default: return 1;
    }
}

/* Hands what was kept to the builder's attributes. */
static neuv_status keep_attributes(ply_keep *k, mesh_builder *b)
{
    if (k->vertex.count == 0 && k->face.count == 0 && !k->color_channels && !k->uv_name[0]) return NEUV_OK;
    mesh_attributes *a = mesh_builder_attributes(b);
    if (!a) return error_nomem("the PLY attributes");
    if (k->vertex.count > 0 && k->vertex.elements == b->nv) { a->ply_vertex = k->vertex; memset(&k->vertex, 0, sizeof k->vertex); }
    if (k->face.count > 0 && k->face.elements == b->np) { a->ply_face = k->face; memset(&k->face, 0, sizeof k->face); }
    if (k->color_channels && b->nv > 0) {
        int ch = k->color_channels;
        a->color = mem_alloc(sizeof(float) * (size_t)ch * (size_t)b->nv);
        if (!a->color) return error_nomem("vertex colours");
        for (size_t v = 0; v < (size_t)b->nv; v++)
            for (int c = 0; c < ch; c++) a->color[(size_t)ch * v + (size_t)c] = k->color[4 * v + (size_t)c];
        a->color_channels = ch;
        a->color_type = k->color_type;
    }
    for (int c = 0; c < 2 && k->uv_name[0] && k->uv_name[1]; c++)
        if (!(a->ply_uv_name[c] = attr_strndup(k->uv_name[c], strlen(k->uv_name[c])))) return error_nomem("UV names");
    return NEUV_OK;
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
    ply_keep keep;
    memset(&keep, 0, sizeof keep);
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
            if (have[R_RED] && have[R_GREEN] && have[R_BLUE]) keep.color_channels = have[R_ALPHA] ? 4 : 3;
            for (int k = 0; k < e->nprops; k++) {
                const ply_prop *pr = &e->props[k];
                if (pr->role == R_RED) keep.color_type = (int)pr->type;
                if (pr->role == R_U && !keep.uv_name[0]) keep.uv_name[0] = pr->name;
                if (pr->role == R_V && !keep.uv_name[1]) keep.uv_name[1] = pr->name;
            }
            if (!vertex_uv) keep.uv_name[0] = keep.uv_name[1] = NULL;
            s = extra_setup(&keep.vertex, e);
            if (s != NEUV_OK) break;
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
            if ((s = extra_setup(&keep.face, e)) != NEUV_OK) break;
            /* Per-corner texcoords replace per-vertex UVs read before. */
            if (face_texcoord) b.nuv = 0;
            long long room = (long long)(len / 8) + 16;
            s = mesh_builder_reserve(&b, 0, e->count < room ? e->count : room);
        }
        if (s != NEUV_OK || e->nprops == 0) continue;
        ply_extra *xe = e->kind == K_VERTEX ? &keep.vertex : e->kind == K_FACE ? &keep.face : NULL;
        size_t *xcap = e->kind == K_VERTEX ? &keep.cap_vertex : &keep.cap_face;
        for (long long i = 0; i < e->count && s == NEUV_OK; i++) {
            double x[R_COUNT] = {0};
            int nc = 0, ntc = -1, xi = 0;
            double *row = NULL;
            if (xe && xe->count > 0 && !(row = extra_row(xe, xcap, i))) { s = error_nomem("PLY properties"); break; }
            for (int k = 0; k < e->nprops && s == NEUV_OK; k++) {
                const ply_prop *pr = &e->props[k];
                double val;
                int got;
                if (pr->count_type == T_NONE) {
                    if ((got = read_value(&r, pr->type, &val)) <= 0) { s = data_error(&r, got, e, i); break; }
                    if (pr->role != R_NONE) x[pr->role] = val;
                    else if (row) row[xi++] = val;
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
                if (s == NEUV_OK && keep.color_channels) {
                    size_t need = 4 * (size_t)b.nv;
                    if (need > keep.cap_color) {
                        size_t c = need > 2 * keep.cap_color ? need : 2 * keep.cap_color;
                        float *col = mem_realloc(keep.color, c * sizeof(float));
                        if (!col) { s = error_nomem("vertex colours"); break; }
                        keep.color = col;
                        keep.cap_color = c;
                    }
                    double sc = type_scale((ply_type)keep.color_type);
                    float *col = keep.color + 4 * ((size_t)b.nv - 1);
                    col[0] = (float)(x[R_RED] / sc);
                    col[1] = (float)(x[R_GREEN] / sc);
                    col[2] = (float)(x[R_BLUE] / sc);
                    col[3] = (float)(x[R_ALPHA] / sc);
                }
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
    if (s == NEUV_OK) s = keep_attributes(&keep, &b);
    mem_free(fs.v);
    mem_free(fs.uv);
    mem_free(fs.tc);
    ply_extra_free(&keep.vertex);
    ply_extra_free(&keep.face);
    mem_free(keep.color);
    header_free(&h);
    if (s != NEUV_OK) { mesh_builder_free(&b); return s; }
    mesh_builder_style style = {0, 0};
    return mesh_builder_finish(&b, style, out);
}
