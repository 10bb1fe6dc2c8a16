/* Wavefront OBJ reader.
 *
 * neuv parses OBJ itself rather than through Assimp: Assimp's OBJ importer
 * reads coordinates in single precision and un-indexes the mesh (one vertex
 * per face corner), which would break two promises: positions exactly as read
 * (float64, bit for bit) and seams detected from shared vertex indices. */
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/mem.h"
#include "io/mesh_builder.h"
#include "io/mesh_io.h"
#include "io/text_scan.h"
#include "mesh/mesh_attributes.h"

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
    int *v, *uv, *vn;
    int n, cap;
} corner_buf;

static int corner_push(corner_buf *cb, int v, int uv, int vn)
{
    if (cb->n == cb->cap) {
        int c = cb->cap ? 2 * cb->cap : 16;
        int *a = mem_realloc(cb->v, sizeof(int) * (size_t)c);
        if (a) cb->v = a;
        int *b = mem_realloc(cb->uv, sizeof(int) * (size_t)c);
        if (b) cb->uv = b;
        int *d = mem_realloc(cb->vn, sizeof(int) * (size_t)c);
        if (d) cb->vn = d;
        if (!a || !b || !d) return 0;
        cb->cap = c;
    }
    cb->v[cb->n] = v;
    cb->uv[cb->n] = uv;
    cb->vn[cb->n] = vn;
    cb->n++;
    return 1;
}

/* Material names in order of first use (`usemtl`): a face's material is
 * its index here. */
typedef struct name_list {
    char **name;
    int n, cap;
} name_list;

static void name_list_free(name_list *l)
{
    for (int i = 0; i < l->n; i++) mem_free(l->name[i]);
    mem_free(l->name);
}

/* The index of the name at p (up to the line end, trailing blanks cut),
 * added when new; -1 when memory runs out. */
static int name_index(name_list *l, const char *p)
{
    size_t len = 0;
    while (p[len] && p[len] != '\n' && p[len] != '#') len++;
    while (len > 0 && (p[len - 1] == ' ' || p[len - 1] == '\t' || p[len - 1] == '\r')) len--;
    for (int i = 0; i < l->n; i++)
        if (strlen(l->name[i]) == len && !memcmp(l->name[i], p, len)) return i;
    if (l->n == l->cap) {
        int c = l->cap ? 2 * l->cap : 8;
        char **q = mem_realloc(l->name, sizeof(char *) * (size_t)c);
        if (!q) return -1;
        l->name = q;
        l->cap = c;
    }
    char *copy = mem_alloc(len + 1);
    if (!copy) return -1;
    memcpy(copy, p, len);
    copy[len] = '\0';
    l->name[l->n] = copy;
    return l->n++;
}

/* The argument of a statement at p: up to the line end or a comment,
 * trailing blanks cut; NULL when memory runs out. */
static char *statement_argument(const char *p)
{
    size_t len = 0;
    while (p[len] && p[len] != '\n' && p[len] != '#') len++;
    while (len > 0 && (p[len - 1] == ' ' || p[len - 1] == '\t' || p[len - 1] == '\r')) len--;
    return attr_strndup(p, len);
}

/* The OBJ grouping statements in force: `o`, `g` and `s` set one part of
 * the state; faces remember the state's index in the attributes. */
static neuv_status set_group_part(mesh_builder *b, int part, const char *p)
{
    mesh_attributes *a = mesh_builder_attributes(b);
    char *arg = statement_argument(p);
    if (!a || !arg) { mem_free(arg); return error_nomem("group names"); }
    obj_group_state now = {NULL, NULL, NULL};
    if (b->group >= 0) now = a->groups[b->group];
    char **slot = part == 0 ? &now.object : part == 1 ? &now.group : &now.smooth;
    *slot = arg;
    for (int i = 0; i < a->n_groups; i++)
        if (attr_same_text(a->groups[i].object, now.object) && attr_same_text(a->groups[i].group, now.group) &&
            attr_same_text(a->groups[i].smooth, now.smooth)) {
            b->group = i;
            mem_free(arg);
            return NEUV_OK;
        }
    obj_group_state *g = mem_realloc(a->groups, sizeof *g * ((size_t)a->n_groups + 1));
    if (!g) { mem_free(arg); return error_nomem("group names"); }
    a->groups = g;
    obj_group_state *n = &g[a->n_groups];
    memset(n, 0, sizeof *n);
    n->object = now.object && now.object != arg ? attr_strndup(now.object, strlen(now.object)) : now.object;
    n->group = now.group && now.group != arg ? attr_strndup(now.group, strlen(now.group)) : now.group;
    n->smooth = now.smooth && now.smooth != arg ? attr_strndup(now.smooth, strlen(now.smooth)) : now.smooth;
    a->n_groups++;
    if ((now.object && !n->object) || (now.group && !n->group) || (now.smooth && !n->smooth))
        return error_nomem("group names");
    b->group = a->n_groups - 1;
    return NEUV_OK;
}

/* Vertex colours (`v x y z r g b`), grown with the vertices; a file that
 * gives them on only some vertices has none. */
typedef struct obj_colors {
    float *rgb;
    size_t cap;
    int with, without;
} obj_colors;

static neuv_status add_color(obj_colors *oc, int vertex, const double *rgb)
{
    if ((size_t)vertex >= oc->cap) {
        size_t c = oc->cap ? 2 * oc->cap : 1024;
        while (c <= (size_t)vertex) c *= 2;
        float *q = mem_realloc(oc->rgb, sizeof(float) * 3 * c);
        if (!q) return error_nomem("vertex colours");
        oc->rgb = q;
        oc->cap = c;
    }
    for (int k = 0; k < 3; k++) oc->rgb[3 * (size_t)vertex + k] = (float)rgb[k];
    return NEUV_OK;
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
    int with_uv = 0, without_uv = 0, with_n = 0, without_n = 0;
    for (;;) {
        text_skip_blanks(c);
        const char *p = c->p;
        if (*p == '\n' || *p == '\0' || *p == '#') break;
        long long vi = 0, ti = 0, ni = 0;
        int has_t = 0, has_n = 0;
        int ok = read_index(&p, &vi);
        if (ok && *p == '/') {
            p++;
            if (*p != '/') { ok = read_index(&p, &ti); has_t = ok; }
            if (ok && *p == '/') {
                p++;
                if (is_digit(*p) || *p == '-' || *p == '+') { ok = read_index(&p, &ni); has_n = ok; }
            }
        }
        if (!ok || !(*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n' || *p == '\0')) {
            char tok[32];
            text_token(c, tok);
            return error_set(NEUV_ERR_INPUT, "line %d: malformed face corner '%s'", c->line, tok);
        }
        int v, t = -1, nrm = -1;
        neuv_status s = resolve(vi, b->nv, c->line, "vertex", &v);
        if (s == NEUV_OK && has_t) s = resolve(ti, b->nuv, c->line, "texture coordinate", &t);
        if (s != NEUV_OK) return s;
        /* A bad normal index drops the face's normals (they only mark seams),
         * not the face: normals were never needed to read a surface. */
        if (has_n && resolve(ni, b->nn, c->line, "normal", &nrm) != NEUV_OK) has_n = 0;
        if (has_t) with_uv++;
        else without_uv++;
        if (has_n) with_n++;
        else without_n++;
        if (!corner_push(cb, v, t, nrm)) return error_nomem("a face");
        c->p = p;
    }
    if (cb->n < 3)
        return error_set(NEUV_ERR_INPUT, "line %d: face has %d corner%s; a face needs at least 3", c->line,
                         cb->n, cb->n == 1 ? "" : "s");
    /* A face with texture coordinates on only some corners has none. */
    const int *uv = with_uv > 0 && without_uv == 0 ? cb->uv : NULL;
    const int *vn = with_n > 0 && without_n == 0 ? cb->vn : NULL;
    return mesh_builder_add_polygon_normals(b, cb->n, cb->v, uv, vn, c->line);
}

static neuv_status bad_number(text_cursor *c, const char *stmt)
{
    char tok[32];
    text_token(c, tok);
    return error_set(NEUV_ERR_INPUT, "line %d: malformed number '%s' in '%s'", c->line, tok, stmt);
}

/* The three numbers of statement `stmt` (v, vn). */
static neuv_status read_triple(text_cursor *c, const char *stmt, double x[3])
{
    for (int k = 0; k < 3; k++) {
        int r = text_read_double(c, &x[k]);
        if (r < 0) return bad_number(c, stmt);
        if (r == 0) return error_set(NEUV_ERR_INPUT, "line %d: '%s' needs 3 coordinates", c->line, stmt);
    }
    return NEUV_OK;
}

neuv_status io_read_obj(const char *text, size_t len, neuv_mesh **out)
{
    (void)len;
    *out = NULL;
    mesh_builder b;
    mesh_builder_init(&b);
    corner_buf cb = {0};
    name_list materials = {0};
    obj_colors colors = {0};
    text_cursor c = {text, 1};
    neuv_status s = NEUV_OK;
    while (*c.p && s == NEUV_OK) {
        text_skip_blanks(&c);
        const char *p = c.p;
        if (statement(p, "v")) {
            c.p += 1;
            double x[3];
            if ((s = read_triple(&c, "v", x)) != NEUV_OK) break;
            if (!isfinite(x[0]) || !isfinite(x[1]) || !isfinite(x[2]))
                s = error_set(NEUV_ERR_INPUT, "line %d: vertex %d has a non-finite coordinate", c.line, b.nv + 1);
            else
                s = mesh_builder_add_vertex(&b, x[0], x[1], x[2]);
            /* A 4th value is w; three more after x y z are a colour. */
            double extra[4];
            int ne = 0;
            while (s == NEUV_OK && ne < 4 && text_read_double(&c, &extra[ne]) > 0) ne++;
            if (s == NEUV_OK && ne == 3 && isfinite(extra[0]) && isfinite(extra[1]) && isfinite(extra[2])) {
                colors.with++;
                s = add_color(&colors, b.nv - 1, extra);
            } else {
                colors.without++;
            }
        } else if (statement(p, "vt")) {
            c.p += 2;
            double t[2] = {0, 0};
            int r = text_read_double(&c, &t[0]);
            if (r == 0) s = error_set(NEUV_ERR_INPUT, "line %d: 'vt' needs a coordinate", c.line);
            if (r > 0) r = text_read_double(&c, &t[1]); /* v is optional (1D textures) */
            if (r < 0) s = bad_number(&c, "vt");
            if (s == NEUV_OK) s = mesh_builder_add_uv(&b, t[0], t[1]);
        } else if (statement(p, "vn")) {
            c.p += 2;
            double x[3];
            if ((s = read_triple(&c, "vn", x)) == NEUV_OK) s = mesh_builder_add_normal(&b, x[0], x[1], x[2]);
        } else if (statement(p, "usemtl")) {
            c.p += 6;
            text_skip_blanks(&c);
            b.material = name_index(&materials, c.p);
            if (b.material < 0) s = error_nomem("material names");
        } else if (statement(p, "f")) {
            c.p += 1;
            s = parse_face(&c, &b, &cb);
        } else if (statement(p, "o") || statement(p, "g") || statement(p, "s")) {
            int part = p[0] == 'o' ? 0 : p[0] == 'g' ? 1 : 2;
            c.p += 1;
            text_skip_blanks(&c);
            s = set_group_part(&b, part, c.p);
        } else if (statement(p, "mtllib")) {
            c.p += 6;
            text_skip_blanks(&c);
            mesh_attributes *a = mesh_builder_attributes(&b);
            char *lib = a ? statement_argument(c.p) : NULL;
            if (!lib) s = error_nomem("the material library");
            else if (!a->material_library) a->material_library = lib;
            else mem_free(lib); /* the first library is kept */
        }
        /* Everything else (vp, l, p, comments) does not change the surface
         * or what is written back. */
        text_next_line(&c);
    }
    mem_free(cb.v);
    mem_free(cb.uv);
    mem_free(cb.vn);
    if (s == NEUV_OK && materials.n > 0) { /* the names go with the mesh */
        mesh_attributes *a = mesh_builder_attributes(&b);
        if (!a) s = error_nomem("material names");
        else {
            a->material_name = materials.name;
            a->n_materials = materials.n;
            materials.name = NULL;
            materials.n = 0;
        }
    }
    if (s == NEUV_OK && colors.with > 0 && colors.without == 0) {
        mesh_attributes *a = mesh_builder_attributes(&b);
        if (!a) s = error_nomem("vertex colours");
        else {
            a->color = colors.rgb;
            a->color_channels = 3;
            colors.rgb = NULL;
        }
    }
    mem_free(colors.rgb);
    name_list_free(&materials);
    if (s != NEUV_OK) { mesh_builder_free(&b); return s; }
    mesh_builder_style style = {1, 1};
    return mesh_builder_finish(&b, style, out);
}
