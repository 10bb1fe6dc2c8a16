#include "core/json_writer.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/mem.h"

void json_init(json_writer *w) { memset(w, 0, sizeof *w); }

void json_free(json_writer *w)
{
    mem_free(w->buf);
    memset(w, 0, sizeof *w);
}

const char *json_text(const json_writer *w) { return w->buf ? w->buf : ""; }

static void append(json_writer *w, const char *s, size_t n)
{
    if (w->failed) return;
    if (w->len + n + 1 > w->cap) {
        size_t cap = w->cap ? w->cap : 256;
        while (cap < w->len + n + 1) cap *= 2;
        char *nb = mem_realloc(w->buf, cap);
        if (!nb) { w->failed = 1; return; }
        w->buf = nb;
        w->cap = cap;
    }
    memcpy(w->buf + w->len, s, n);
    w->len += n;
    w->buf[w->len] = '\0';
}

static void puts_raw(json_writer *w, const char *s) { append(w, s, strlen(s)); }

/* Called before every value: separates it from the previous sibling. */
static void before_value(json_writer *w)
{
    if (w->after_key) { w->after_key = 0; return; }
    if (w->need_comma[w->depth]) puts_raw(w, ",");
    w->need_comma[w->depth] = 1;
}

static void open(json_writer *w, const char *c)
{
    before_value(w);
    puts_raw(w, c);
    if (w->depth < 63) w->depth++;
    w->need_comma[w->depth] = 0;
}

void json_begin_object(json_writer *w) { open(w, "{"); }
void json_begin_array(json_writer *w) { open(w, "["); }
void json_end_object(json_writer *w) { if (w->depth > 0) w->depth--; puts_raw(w, "}"); }
void json_end_array(json_writer *w) { if (w->depth > 0) w->depth--; puts_raw(w, "]"); }

static void put_escaped(json_writer *w, const char *s)
{
    puts_raw(w, "\"");
    for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
        char esc[8];
        if (*p == '"' || *p == '\\') { esc[0] = '\\'; esc[1] = (char)*p; append(w, esc, 2); }
        else if (*p == '\n') puts_raw(w, "\\n");
        else if (*p == '\t') puts_raw(w, "\\t");
        else if (*p < 0x20) { snprintf(esc, sizeof esc, "\\u%04x", *p); puts_raw(w, esc); }
        else append(w, (const char *)p, 1);
    }
    puts_raw(w, "\"");
}

void json_key(json_writer *w, const char *key)
{
    before_value(w);
    put_escaped(w, key);
    puts_raw(w, ":");
    w->after_key = 1;
}

void json_string(json_writer *w, const char *s) { before_value(w); put_escaped(w, s ? s : ""); }

void format_double_exact(char out[32], double x)
{
    for (int prec = 15; prec <= 17; prec++) {
        snprintf(out, 32, "%.*g", prec, x);
        if (strtod(out, NULL) == x) return;
    }
}

void json_number(json_writer *w, double x)
{
    before_value(w);
    if (!isfinite(x)) { puts_raw(w, "null"); return; }
    char buf[32];
    format_double_exact(buf, x);
    puts_raw(w, buf);
}

void json_int(json_writer *w, long long x)
{
    before_value(w);
    char buf[32];
    snprintf(buf, sizeof buf, "%lld", x);
    puts_raw(w, buf);
}

void json_bool(json_writer *w, int b) { before_value(w); puts_raw(w, b ? "true" : "false"); }
void json_null(json_writer *w) { before_value(w); puts_raw(w, "null"); }
