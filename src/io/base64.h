/* Base64 (RFC 4648, standard alphabet) for glTF's data URIs. */
#ifndef NEUV_IO_BASE64_H
#define NEUV_IO_BASE64_H

#include <stddef.h>

/* The encoding of n bytes, '='-padded and NUL-terminated (mem_free it);
 * NULL when memory runs out. */
char *base64_encode(const unsigned char *data, size_t n);
/* Decodes len characters (padding optional) into a new buffer (mem_free it).
 * Returns 0, -1 for a character outside the alphabet or a bad length, -2
 * when memory runs out; *out is NULL unless 0 is returned. */
int base64_decode(const char *text, size_t len, unsigned char **out, size_t *out_len);

#endif
