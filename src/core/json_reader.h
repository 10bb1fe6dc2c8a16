/* A small JSON parser into a tree of values (RFC 8259), for the files neuv
 * reads that are JSON (glTF). Strict: one value, no trailing commas, no
 * comments, strings decoded to UTF-8 (\u escapes and surrogate pairs
 * included), nesting deeper than JSON_MAX_DEPTH refused. Errors are
 * NEUV_ERR_INPUT with "JSON: line L: what" (or NEUV_ERR_NOMEM).
 *
 *     json_value root;
 *     if (json_parse(text, len, &root) != NEUV_OK) return error_last();
 *     const json_value *v = json_get(&root, "asset");
 *     json_value_free(&root);
 */
#ifndef NEUV_CORE_JSON_READER_H
#define NEUV_CORE_JSON_READER_H

#include <stddef.h>

#include "neuv/neuv.h"

#define JSON_MAX_DEPTH 64

typedef enum json_type { JSON_NULL, JSON_BOOL, JSON_NUMBER, JSON_STRING, JSON_ARRAY, JSON_OBJECT } json_type;

typedef struct json_value {
    json_type type;
    int boolean;              /* JSON_BOOL */
    double number;            /* JSON_NUMBER */
    char *string;             /* JSON_STRING: NUL-terminated UTF-8 (may hold \u0000 as a byte) */
    size_t string_len;
    int n;                    /* JSON_ARRAY, JSON_OBJECT: number of items */
    struct json_value *items; /* #n values */
    char **keys;              /* JSON_OBJECT: #n keys, NUL-terminated */
} json_value;

/* Parses len bytes of text (need not be NUL-terminated) into *out; on
 * failure *out is a JSON_NULL that needs no freeing. */
neuv_status json_parse(const char *text, size_t len, json_value *out);
void json_value_free(json_value *v);

/* The value under `key` of an object (the last one when a key repeats), or
 * NULL when v is not an object or has no such key. */
const json_value *json_get(const json_value *v, const char *key);
/* Item i of an array, or NULL (not an array, or i out of range). */
const json_value *json_at(const json_value *v, int i);
/* 1 when v is a number that is an integer in [lo, hi], its value in *out. */
int json_int_in(const json_value *v, long long lo, long long hi, long long *out);

#endif
