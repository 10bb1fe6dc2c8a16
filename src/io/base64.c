/* RFC 4648 base64 (the standard alphabet, '=' padding). */
#include "io/base64.h"

#include <stdint.h>

#include "core/mem.h"

#define BASE64_DIGITS "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/"

char *base64_encode(const unsigned char *data, size_t n)
{
    const char *digits = BASE64_DIGITS;
    char *out = mem_alloc(4 * ((n + 2) / 3) + 1), *q = out;
    if (!out) return NULL;
    size_t i = 0;
    for (; i + 2 < n; i += 3) {
        uint32_t w = (uint32_t)data[i] << 16 | (uint32_t)data[i + 1] << 8 | data[i + 2];
        *q++ = digits[w >> 18]; *q++ = digits[(w >> 12) & 63]; *q++ = digits[(w >> 6) & 63]; *q++ = digits[w & 63];
    }
    if (i < n) {
        uint32_t w = (uint32_t)data[i] << 16 | (i + 1 < n ? (uint32_t)data[i + 1] << 8 : 0);
        *q++ = digits[w >> 18];
        *q++ = digits[(w >> 12) & 63];
        *q++ = i + 1 < n ? digits[(w >> 6) & 63] : '=';
        *q++ = '=';
    }
    *q = '\0';
    return out;
}

static int digit_value(unsigned char c)
{
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
}

int base64_decode(const char *text, size_t len, unsigned char **out, size_t *out_len)
{
    *out = NULL;
    *out_len = 0;
    while (len > 0 && text[len - 1] == '=' ) len--; /* padding is optional here */
    if (len % 4 == 1) return -1;
    unsigned char *buf = mem_alloc(len / 4 * 3 + 3);
    if (!buf) return -2;
    size_t n = 0;
    uint32_t w = 0;
    int bits = 0;
    for (size_t i = 0; i < len; i++) {
        int d = digit_value((unsigned char)text[i]);
        if (d < 0) { mem_free(buf); return -1; }
        w = w << 6 | (uint32_t)d;
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            buf[n++] = (unsigned char)(w >> bits);
            w &= (1u << bits) - 1;
        }
    }
    *out = buf;
    *out_len = n;
    return 0;
}
