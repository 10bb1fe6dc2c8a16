/* A small streaming JSON writer into a growing string buffer.
 * Commas and nesting are tracked for the caller:
 *     json_writer w; json_init(&w);
 *     json_begin_object(&w);
 *     json_key(&w, "faces"); json_int(&w, 12);
 *     json_end_object(&w);
 *     fputs(json_text(&w), out); json_free(&w);
 * Non-finite numbers are written as null (JSON has no NaN). */
#ifndef NEUV_CORE_JSON_WRITER_H
#define NEUV_CORE_JSON_WRITER_H

#include <stddef.h>

typedef struct json_writer {
    char *buf;
    size_t len, cap;
    int depth;
    int need_comma[64];
    int after_key;
    int failed; /* an allocation failed; the text is incomplete */
} json_writer;

void json_init(json_writer *w);
void json_free(json_writer *w);
const char *json_text(const json_writer *w);
void json_begin_object(json_writer *w);
void json_end_object(json_writer *w);
void json_begin_array(json_writer *w);
void json_end_array(json_writer *w);
void json_key(json_writer *w, const char *key);
void json_string(json_writer *w, const char *s);
void json_number(json_writer *w, double x); /* shortest text that reads back exactly */
void json_int(json_writer *w, long long x);
void json_bool(json_writer *w, int b);
void json_null(json_writer *w);

/* Shortest decimal text for x that parses back to the same double (%.15g..%.17g). */
void format_double_exact(char out[32], double x);

#endif
