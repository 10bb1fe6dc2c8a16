/* OFF reader (Geomview's Object File Format): OFF, COFF, NOFF, STOFF and
 * their combinations, '#' comments anywhere. Records are one per line:
 * a vertex line is x y z [normal] [colour] [s t]; a face line is
 * n i1 .. in [colour]. Own parser for the same reasons as OBJ (float64,
 * vertex order kept). */
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/mem.h"
#include "io/mesh_builder.h"
#include "io/mesh_io.h"
#include "io/text_scan.h"

static neuv_status malformed(text_cursor *c, const char *what)
{
    char tok[32];
    text_token(c, tok);
    return error_set(NEUV_ERR_INPUT, "line %d: malformed %s '%s'", c->line, what, tok);
}

static neuv_status read_count(text_cursor *c, long long *x, const char *what)
{
    if (!text_skip_space(c, 1))
        return error_set(NEUV_ERR_INPUT, "truncated: the OFF header has no %s count", what);
    int r = text_read_long(c, x);
    if (r <= 0 || *x < 0) return malformed(c, "count");
    if (*x > INT_MAX / 4)
        return error_set(NEUV_ERR_INPUT, "header declares %lld %s; too large for neuv", *x, what);
    return NEUV_OK;
}

neuv_status io_read_off(const char *text, size_t len, neuv_mesh **out)
{
    *out = NULL;
    text_cursor c = {text, 1};
    if (!text_skip_space(&c, 1)) return error_set(NEUV_ERR_INPUT, "empty file");
    char kw[32];
    text_token(&c, kw);
    size_t kl = strlen(kw);
    if (kl < 3 || strcmp(kw + kl - 3, "OFF") != 0)
        return error_set(NEUV_ERR_INPUT, "not an OFF file: it starts with '%s' instead of 'OFF'", kw);
    if (strchr(kw, '4') || strchr(kw, 'n'))
        return error_set(NEUV_ERR_INPUT, "%s (4D or n-dimensional OFF) is not supported", kw);
    int has_st = strstr(kw, "ST") != NULL;
    c.p += kl;
    {
        text_cursor look = c;
        char w[32];
        text_skip_blanks(&look);
        text_token(&look, w);
        if (!strcmp(w, "BINARY")) return error_set(NEUV_ERR_INPUT, "binary OFF is not supported");
    }
    long long nv, nf, ne;
    neuv_status s;
    if ((s = read_count(&c, &nv, "vertices")) != NEUV_OK) return s;
    if ((s = read_count(&c, &nf, "faces")) != NEUV_OK) return s;
    if ((s = read_count(&c, &ne, "edges")) != NEUV_OK) return s;
    text_next_line(&c);

    mesh_builder b;
    mesh_builder_init(&b);
    double *st = NULL;
    int *corners = NULL;
    /* The header's counts are only believed as far as the file could hold
     * them, so a lying header cannot make us allocate gigabytes. */
    long long rv = nv < (long long)(len / 6) + 16 ? nv : (long long)(len / 6) + 16;
    long long rf = nf < (long long)(len / 8) + 16 ? nf : (long long)(len / 8) + 16;
    if ((s = mesh_builder_reserve(&b, rv, rf)) != NEUV_OK) goto fail;

    if (has_st && !(st = mem_alloc(sizeof(double) * 2 * (size_t)(nv > 0 ? nv : 1)))) {
        s = error_nomem("texture coordinates");
        goto fail;
    }
    for (long long i = 0; i < nv; i++) {
        if (!text_skip_space(&c, 1)) {
            s = error_set(NEUV_ERR_INPUT, "truncated: header declares %lld vertices, data ends after %lld", nv, i);
            goto fail;
        }
        double x[3];
        for (int k = 0; k < 3; k++) {
            int r = text_read_double(&c, &x[k]);
            if (r < 0) { s = malformed(&c, "number"); goto fail; }
            if (r == 0) { s = error_set(NEUV_ERR_INPUT, "line %d: vertex %lld needs 3 coordinates", c.line, i); goto fail; }
        }
        if (!isfinite(x[0]) || !isfinite(x[1]) || !isfinite(x[2])) {
            s = error_set(NEUV_ERR_INPUT, "line %d: vertex %lld has a non-finite coordinate", c.line, i);
            goto fail;
        }
        if (has_st) {
            /* s t are the last two numbers, after optional normal and colour. */
            double prev = 0, last = 0, y;
            int n = 0, r;
            while ((r = text_read_double(&c, &y)) > 0) { prev = last; last = y; n++; }
            if (r < 0) { s = malformed(&c, "number"); goto fail; }
            if (n < 2) { s = error_set(NEUV_ERR_INPUT, "line %d: STOFF vertex %lld has no s t", c.line, i); goto fail; }
            st[2 * i] = prev;
            st[2 * i + 1] = last;
        }
        if ((s = mesh_builder_add_vertex(&b, x[0], x[1], x[2])) != NEUV_OK) goto fail;
        text_next_line(&c);
    }
    int cap = 0;
    for (long long f = 0; f < nf; f++) {
        if (!text_skip_space(&c, 1)) {
            s = error_set(NEUV_ERR_INPUT, "truncated: header declares %lld faces, data ends after %lld", nf, f);
            break;
        }
        long long n;
        int r = text_read_long(&c, &n);
        if (r <= 0) { s = malformed(&c, "corner count"); break; }
        if (n < 3) { s = error_set(NEUV_ERR_INPUT, "line %d: face %lld has %lld corners; a face needs at least 3", c.line, f, n); break; }
        if (n > 1000000) { s = error_set(NEUV_ERR_INPUT, "line %d: face %lld claims %lld corners", c.line, f, n); break; }
        if (n > cap) {
            int *a = mem_realloc(corners, sizeof(int) * (size_t)n);
            if (!a) { s = error_nomem("a face"); break; }
            corners = a;
            cap = (int)n;
        }
        for (int k = 0; k < n && s == NEUV_OK; k++) {
            long long v;
            r = text_read_long(&c, &v);
            if (r < 0) s = malformed(&c, "vertex index");
            else if (r == 0) s = error_set(NEUV_ERR_INPUT, "line %d: face %lld has fewer indices than its count %lld", c.line, f, n);
            else if (v < 0 || v >= nv)
                s = error_set(NEUV_ERR_INPUT, "face %lld references vertex %lld, but there are %lld vertices", f, v, nv);
            else corners[k] = (int)v;
        }
        if (s != NEUV_OK) break;
        /* An optional face colour may follow; ignored. */
        s = mesh_builder_add_polygon(&b, (int)n, corners, has_st ? corners : NULL, (int)f);
        if (s != NEUV_OK) break;
        text_next_line(&c);
    }
    if (s == NEUV_OK && has_st) {
        for (long long i = 0; i < nv && s == NEUV_OK; i++) s = mesh_builder_add_uv(&b, st[2 * i], st[2 * i + 1]);
    }
    if (s != NEUV_OK) goto fail;
    mem_free(corners);
    mem_free(st);
    mesh_builder_style style = {0, 0};
    return mesh_builder_finish(&b, style, out);
fail:
    mem_free(corners);
    mem_free(st);
    mesh_builder_free(&b);
    return s;
}
