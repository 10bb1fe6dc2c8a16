/* Recursive descent over the text, depth bounded by JSON_MAX_DEPTH so that
 * no input can exhaust the stack. Containers grow by doubling. */
#include "core/json_reader.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/mem.h"

typedef struct parser {
    const char *p, *end;
    int line;
} parser;

static neuv_status fail(const parser *ps, const char *what)
{
    return error_set(NEUV_ERR_INPUT, "JSON: line %d: %s", ps->line, what);
}

static void skip_space(parser *ps)
{
    while (ps->p < ps->end) {
        char c = *ps->p;
        if (c == '\n') ps->line++;
        else if (c != ' ' && c != '\t' && c != '\r') return;
        ps->p++;
    }
}

static int hex4(const char *p, unsigned *out)
{
    unsigned v = 0;
    for (int i = 0; i < 4; i++) {
        char c = p[i];
        int d = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
        if (d < 0) return 0;
        v = v * 16 + (unsigned)d;
    }
    *out = v;
    return 1;
}

static size_t put_utf8(char *o, unsigned cp)
{
    if (cp < 0x80) { o[0] = (char)cp; return 1; }
    if (cp < 0x800) { o[0] = (char)(0xC0 | cp >> 6); o[1] = (char)(0x80 | (cp & 0x3F)); return 2; }
    if (cp < 0x10000) {
        o[0] = (char)(0xE0 | cp >> 12); o[1] = (char)(0x80 | (cp >> 6 & 0x3F)); o[2] = (char)(0x80 | (cp & 0x3F));
        return 3;
    }
    o[0] = (char)(0xF0 | cp >> 18); o[1] = (char)(0x80 | (cp >> 12 & 0x3F));
    o[2] = (char)(0x80 | (cp >> 6 & 0x3F)); o[3] = (char)(0x80 | (cp & 0x3F));
    return 4;
}

/* A string at ps->p (the opening quote); the decoded text is never longer
 * than the escaped one, so one allocation of the raw length suffices. */
static neuv_status parse_string(parser *ps, char **out, size_t *out_len)
{
    const char *s = ++ps->p;
    const char *q = s;
    while (q < ps->end && *q != '"') {
        if ((unsigned char)*q < 0x20) return fail(ps, "control character in a string");
        q += *q == '\\' && q + 1 < ps->end ? 2 : 1;
    }
    if (q >= ps->end) return fail(ps, "unterminated string");
    char *buf = mem_alloc((size_t)(q - s) + 1);
    if (!buf) return error_nomem("a JSON string");
    size_t n = 0;
    const char *p = s;
    while (p < q) {
        if (*p != '\\') { buf[n++] = *p++; continue; }
        p++;
        char c = *p++;
        switch (c) {
        case '"': buf[n++] = '"'; break;
        case '\\': buf[n++] = '\\'; break;
        case '/': buf[n++] = '/'; break;
        case 'b': buf[n++] = '\b'; break;
        case 'f': buf[n++] = '\f'; break;
        case 'n': buf[n++] = '\n'; break;
        case 'r': buf[n++] = '\r'; break;
        case 't': buf[n++] = '\t'; break;
        case 'u': {
            unsigned cp, lo;
            if (q - p < 4 || !hex4(p, &cp)) { mem_free(buf); return fail(ps, "bad \\u escape"); }
            p += 4;
            if (cp >= 0xD800 && cp < 0xDC00) {
                if (q - p < 6 || p[0] != '\\' || p[1] != 'u' || !hex4(p + 2, &lo) || lo < 0xDC00 || lo >= 0xE000) {
                    mem_free(buf);
                    return fail(ps, "unpaired surrogate in a \\u escape");
                }
                p += 6;
                cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
            } else if (cp >= 0xDC00 && cp < 0xE000) {
                mem_free(buf);
                return fail(ps, "unpaired surrogate in a \\u escape");
            }
            n += put_utf8(buf + n, cp); /* at most 4 bytes for 6 or 12 escaped ones */
            break;
        }
        default: mem_free(buf); return fail(ps, "bad escape in a string");
        }
    }
    buf[n] = '\0';
    ps->p = q + 1;
    *out = buf;
    *out_len = n;
    return NEUV_OK;
}

static neuv_status parse_number(parser *ps, double *out)
{
    /* The grammar first (strtod takes more: hex, inf, nan, leading '+'). */
    const char *p = ps->p, *e = ps->end;
    if (p < e && *p == '-') p++;
    if (p >= e || !(*p >= '0' && *p <= '9')) return fail(ps, "bad number");
    if (*p == '0') p++;
    else while (p < e && *p >= '0' && *p <= '9') p++;
    if (p < e && *p == '.') {
        p++;
        if (p >= e || !(*p >= '0' && *p <= '9')) return fail(ps, "bad number");
        while (p < e && *p >= '0' && *p <= '9') p++;
    }
    if (p < e && (*p == 'e' || *p == 'E')) {
        p++;
        if (p < e && (*p == '+' || *p == '-')) p++;
        if (p >= e || !(*p >= '0' && *p <= '9')) return fail(ps, "bad number");
        while (p < e && *p >= '0' && *p <= '9') p++;
    }
    char tmp[64];
    size_t n = (size_t)(p - ps->p);
    if (n >= sizeof tmp) {
        /* Long digit strings: strtod needs a terminated copy. */
        char *big = mem_alloc(n + 1);
        if (!big) return error_nomem("a JSON number");
        memcpy(big, ps->p, n);
        big[n] = '\0';
        *out = strtod(big, NULL);
        mem_free(big);
    } else {
        memcpy(tmp, ps->p, n);
        tmp[n] = '\0';
        *out = strtod(tmp, NULL);
    }
    if (!isfinite(*out)) return fail(ps, "number out of range");
    ps->p = p;
    return NEUV_OK;
}

static int literal(parser *ps, const char *word)
{
    size_t n = strlen(word);
    if ((size_t)(ps->end - ps->p) < n || memcmp(ps->p, word, n)) return 0;
    ps->p += n;
    return 1;
}

static neuv_status parse_value(parser *ps, json_value *v, int depth);

/* Appends a zeroed slot to a container; *slot points at it. */
static neuv_status grow(json_value *v, int *cap, int with_keys, json_value **slot)
{
    if (v->n == *cap) {
        if (*cap > (1 << 28)) return error_nomem("a JSON container");
        int c = *cap ? 2 * *cap : 4;
        json_value *items = mem_realloc(v->items, (size_t)c * sizeof *items);
        if (!items) return error_nomem("a JSON container");
        v->items = items;
        if (with_keys) {
            char **keys = mem_realloc(v->keys, (size_t)c * sizeof *keys);
            if (!keys) return error_nomem("a JSON container");
            v->keys = keys;
        }
        *cap = c;
    }
    *slot = &v->items[v->n];
    memset(*slot, 0, sizeof **slot);
    return NEUV_OK;
}

static neuv_status parse_container(parser *ps, json_value *v, int depth, int object)
{
    char close = object ? '}' : ']';
    v->type = object ? JSON_OBJECT : JSON_ARRAY;
    ps->p++;
    skip_space(ps);
    if (ps->p < ps->end && *ps->p == close) { ps->p++; return NEUV_OK; }
    int cap = 0;
    for (;;) {
        json_value *slot = NULL;
        neuv_status s = grow(v, &cap, object, &slot);
        if (s) return s;
        char *key = NULL;
        if (object) {
            skip_space(ps);
            if (ps->p >= ps->end || *ps->p != '"') return fail(ps, "expected a key");
            size_t kl;
            if ((s = parse_string(ps, &key, &kl))) return s;
            skip_space(ps);
            if (ps->p >= ps->end || *ps->p != ':') { mem_free(key); return fail(ps, "expected ':'"); }
            ps->p++;
        }
        s = parse_value(ps, slot, depth + 1);
        if (object) v->keys[v->n] = key;
        v->n++; /* counted even on failure, so json_value_free releases it */
        if (s) return s;
        skip_space(ps);
        if (ps->p < ps->end && *ps->p == ',') { ps->p++; continue; }
        if (ps->p < ps->end && *ps->p == close) { ps->p++; return NEUV_OK; }
        return fail(ps, object ? "expected ',' or '}'" : "expected ',' or ']'");
    }
}

static neuv_status parse_value(parser *ps, json_value *v, int depth)
{
    if (depth > JSON_MAX_DEPTH) return fail(ps, "nested too deeply");
    skip_space(ps);
    if (ps->p >= ps->end) return fail(ps, "unexpected end of text");
    char c = *ps->p;
    if (c == '{' || c == '[') return parse_container(ps, v, depth, c == '{');
    if (c == '"') { v->type = JSON_STRING; return parse_string(ps, &v->string, &v->string_len); }
    if (c == '-' || (c >= '0' && c <= '9')) { v->type = JSON_NUMBER; return parse_number(ps, &v->number); }
    if (literal(ps, "true")) { v->type = JSON_BOOL; v->boolean = 1; return NEUV_OK; }
    if (literal(ps, "false")) { v->type = JSON_BOOL; return NEUV_OK; }
    if (literal(ps, "null")) { v->type = JSON_NULL; return NEUV_OK; }
    return fail(ps, "unexpected character");
}

neuv_status json_parse(const char *text, size_t len, json_value *out)
{
    memset(out, 0, sizeof *out);
    parser ps = {text, text + len, 1};
    neuv_status s = parse_value(&ps, out, 0);
    if (s == NEUV_OK) {
        skip_space(&ps);
        if (ps.p != ps.end) s = fail(&ps, "text after the value");
    }
    if (s != NEUV_OK) {
        json_value_free(out);
        memset(out, 0, sizeof *out);
    }
    return s;
}

void json_value_free(json_value *v)
{
    if (!v) return;
    for (int i = 0; i < v->n; i++) {
        json_value_free(&v->items[i]);
        if (v->keys) mem_free(v->keys[i]);
    }
    mem_free(v->items);
    mem_free(v->keys);
    mem_free(v->string);
    memset(v, 0, sizeof *v);
}

const json_value *json_get(const json_value *v, const char *key)
{
    if (!v || v->type != JSON_OBJECT) return NULL;
    for (int i = v->n - 1; i >= 0; i--)
        if (!strcmp(v->keys[i], key)) return &v->items[i];
    return NULL;
}

const json_value *json_at(const json_value *v, int i)
{
    if (!v || v->type != JSON_ARRAY || i < 0 || i >= v->n) return NULL;
    return &v->items[i];
}

int json_int_in(const json_value *v, long long lo, long long hi, long long *out)
{
    if (!v || v->type != JSON_NUMBER || v->number != floor(v->number)) return 0;
    if (v->number < (double)lo || v->number > (double)hi) return 0;
    *out = (long long)v->number;
    return 1;
}
