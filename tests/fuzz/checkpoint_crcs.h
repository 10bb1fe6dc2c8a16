/* Rewriting a mutated checkpoint's CRC fields, shared by the checkpoint and
 * model fuzz targets: without it nearly every mutation stops at the first
 * CRC mismatch and the checks behind the CRCs are never reached. */
#ifndef NEUV_TESTS_FUZZ_CHECKPOINT_CRCS_H
#define NEUV_TESTS_FUZZ_CHECKPOINT_CRCS_H

#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/hash.h"

static inline uint32_t get_u32(const uint8_t *p) { return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24; }
static inline void set_u32(uint8_t *p, uint32_t v) { p[0] = (uint8_t)v; p[1] = (uint8_t)(v >> 8); p[2] = (uint8_t)(v >> 16); p[3] = (uint8_t)(v >> 24); }

/* Rewrites every CRC field that lies inside the buffer to the right value, so
 * mutations reach the checks behind the CRCs (shapes, names, duplicates,
 * trailing bytes) instead of stopping at a CRC mismatch. */
static inline void fix_crcs(uint8_t *b, size_t n)
{
    size_t pos = 12;
    if (n < pos + 4) return;
    uint32_t hlen = get_u32(b + 12);
    pos = 16;
    if (hlen > n - pos || n - pos - hlen < 4) return;
    set_u32(b + pos + hlen, crc32_bytes(0, b + pos, hlen));
    pos += (size_t)hlen + 4;
    if (n - pos < 4) return;
    uint32_t count = get_u32(b + pos);
    pos += 4;
    for (uint32_t i = 0; i < count && i < 1000; i++) {
        if (n - pos < 4) return;
        uint32_t nlen = get_u32(b + pos);
        pos += 4;
        if (nlen > n - pos || n - pos - nlen < 12) return;
        const uint8_t *name = b + pos;
        pos += nlen;
        uint64_t bytes = (uint64_t)get_u32(b + pos) * get_u32(b + pos + 4) * 4;
        uint32_t crc = crc32_bytes(crc32_bytes(0, name, nlen), b + pos, 8);
        size_t crc_at = pos + 8;
        pos += 12;
        if (bytes > n - pos) return;
        set_u32(b + crc_at, crc32_bytes(crc, b + pos, (size_t)bytes));
        pos += (size_t)bytes;
    }
}

/* Runs check(data) on the input as it is, then on a copy with its CRC
 * fields rewritten. */
static inline void fuzz_as_is_and_crcs_fixed(const uint8_t *data, size_t size, void (*check)(const uint8_t *, size_t))
{
    check(data, size);
    uint8_t *copy = malloc(size ? size : 1);
    if (!copy) return;
    memcpy(copy, data, size);
    fix_crcs(copy, size);
    check(copy, size);
    free(copy);
}

#endif
