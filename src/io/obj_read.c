/* Wavefront OBJ reader.
 *
 * neuv parses OBJ itself rather than through Assimp: Assimp's OBJ importer
 * reads coordinates in single precision and un-indexes the mesh (one vertex
 * per face corner), which would break two promises: positions exactly as read
 * (float64, bit for bit) and seams detected from shared vertex indices. */
#include <limits.h>
#include <math.h>
#include <stdlib.h>

#include "core/error.h"
#include "core/mem.h"
#include "io/mesh_builder.h"
#include "io/mesh_io.h"
#include "io/text_scan.h"

/* The statement keyword `kw` at p, followed by a blank or the line end. */
static int statement(const char *p, const char *kw)
{
    while (*kw) if (*p++ != *kw++) return 0;
    return *p == ' ' || *p == '\t' || *p == '\r' || *p == '\n' || *p == '\0';
}

static int is_digit(char ch) { return ch >= '0' && ch <= '9'; }

/* Reads an optionally signed integer at *p; 0 when none is there. */
static int read_index(const char **p, long long *x)
{
    const char *s = *p;
    if (!(is_digit(s[0]) || ((s[0] == '-' || s[0] == '+') && is_digit(s[1])))) return 0;
    char *end;
    *x = strtoll(s, &end, 10);
    *p = end;
    return 1;
}

typedef struct corner_buf {
    int *v, *uv;
    int n, cap;
} corner_buf;

static int corner_push(corner_buf *cb, int v, int uv)
{
    if (cb->n == cb->cap) {
        int c = cb->cap ? 2 * cb->cap : 16;
        int *a = mem_realloc(cb->v, sizeof(int) * (size_t)c);
        if (a) cb->v = a;
        int *b = mem_realloc(cb->uv, sizeof(int) * (size_t)c);
        if (b) cb->uv = b;
        if (!a || !b) return 0;
        cb->cap = c;
    }
    cb->v[cb->n] = v;
    cb->uv[cb->n] = uv;
    cb->n++;
    return 1;
}

/* Turns a 1-based or negative (relative) OBJ index into a 0-based one. */
static neuv_status resolve(long long idx, int count, int line, const char *what, int *out)
{
    if (idx == 0)
        return error_set(NEUV_ERR_INPUT, "line %d: %s index 0 is not valid (OBJ counts from 1)", line, what);
    if (idx < 0) {
        /* Compared without negating idx: strtoll gives LLONG_MIN for a
         * huge negative number, whose negation overflows. */
        if (idx < -(long long)count)
            return error_set(NEUV_ERR_INPUT, "line %d: relative %s index %lld reaches before the first one",
                             line, what, idx);
        *out = (int)(count + idx);
        return NEUV_OK;
    }
    /* Positive indices may point forward (some writers emit faces first), so
     * the range is checked once the whole file is read. */
    if (idx > INT_MAX / 4)
        return error_set(NEUV_ERR_INPUT, "line %d: face references %s %lld, but there are %d", line, what,
                         idx, count);
    *out = (int)(idx - 1);
    return NEUV_OK;
}

static neuv_status parse_face(text_cursor *c, mesh_builder *b, corner_buf *cb)
{
    cb->n = 0;
    int with_uv = 0, without_uv = 0;
    for (;;) {
        text_skip_blanks(c);
        const char *p = c->p;
        if (*p == '\n' || *p == '\0' || *p == '#') break;
        long long vi = 0, ti = 0, ni = 0;
        int has_t = 0;
        int ok = read_index(&p, &vi);
        if (ok && *p == '/') {
            p++;
            if (*p != '/') { ok = read_index(&p, &ti); has_t = ok; }
            if (ok && *p == '/') { p++; if (is_digit(*p) || *p == '-' || *p == '+') ok = read_index(&p, &ni); }
        }
        if (!ok || !(*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n' || *p == '\0')) {
            char tok[32];
            text_token(c, tok);
            return error_set(NEUV_ERR_INPUT, "line %d: malformed face corner '%s'", c->line, tok);
        }
        int v, t = -1;
        neuv_status s = resolve(vi, b->nv, c->line, "vertex", &v);
        if (s == NEUV_OK && has_t) s = resolve(ti, b->nuv, c->line, "texture coordinate", &t);
        if (s != NEUV_OK) return s;
        if (has_t) with_uv++;
        else without_uv++;
        if (!corner_push(cb, v, t)) return error_nomem("a face");
        c->p = p;
    }
    if (cb->n < 3)
        return error_set(NEUV_ERR_INPUT, "line %d: face has %d corner%s; a face needs at least 3", c->line,
                         cb->n, cb->n == 1 ? "" : "s");
    /* A face with texture coordinates on only some corners has none. */
    const int *uv = with_uv > 0 && without_uv == 0 ? cb->uv : NULL;
    return mesh_builder_add_polygon(b, cb->n, cb->v, uv, c->line);
}

static neuv_status bad_number(text_cursor *c, const char *stmt)
{
    char tok[32];
    text_token(c, tok);
    return error_set(NEUV_ERR_INPUT, "line %d: malformed number '%s' in '%s'", c->line, tok, stmt);
}

neuv_status io_read_obj(const char *text, size_t len, neuv_mesh **out)
{
    (void)len;
    *out = NULL;
    mesh_builder b;
    mesh_builder_init(&b);
    corner_buf cb = {0};
    text_cursor c = {text, 1};
    neuv_status s = NEUV_OK;
    while (*c.p && s == NEUV_OK) {
        text_skip_blanks(&c);
        const char *p = c.p;
        if (statement(p, "v")) {
            c.p += 1;
            double x[3];
            for (int k = 0; k < 3 && s == NEUV_OK; k++) {
                int r = text_read_double(&c, &x[k]);
                if (r < 0) s = bad_number(&c, "v");
                else if (r == 0) s = error_set(NEUV_ERR_INPUT, "line %d: 'v' needs 3 coordinates", c.line);
            }
            if (s != NEUV_OK) break;
            /* A 4th value (w) or vertex colours may follow; they are ignored. */
            if (!isfinite(x[0]) || !isfinite(x[1]) || !isfinite(x[2]))
                s = error_set(NEUV_ERR_INPUT, "line %d: vertex %d has a non-finite coordinate", c.line, b.nv + 1);
            else
                s = mesh_builder_add_vertex(&b, x[0], x[1], x[2]);
        } else if (statement(p, "vt")) {
            c.p += 2;
            double t[2] = {0, 0};
            int r = text_read_double(&c, &t[0]);
            if (r == 0) s = error_set(NEUV_ERR_INPUT, "line %d: 'vt' needs a coordinate", c.line);
            if (r > 0) r = text_read_double(&c, &t[1]); /* v is optional (1D textures) */
            if (r < 0) s = bad_number(&c, "vt");
            if (s == NEUV_OK) s = mesh_builder_add_uv(&b, t[0], t[1]);
        } else if (statement(p, "f")) {
            c.p += 1;
            s = parse_face(&c, &b, &cb);
        }
        /* Everything else (vn, vp, o, g, s, usemtl, mtllib, l, p, comments)
         * does not change the surface. */
        text_next_line(&c);
    }
    mem_free(cb.v);
    mem_free(cb.uv);
    if (s != NEUV_OK) { mesh_builder_free(&b); return s; }
    mesh_builder_style style = {1, 1};
    return mesh_builder_finish(&b, style, out);
}
