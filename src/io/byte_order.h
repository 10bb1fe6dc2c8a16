/* Little-endian encoding for the binary writers (PLY, GLB), independent of
 * the host's byte order. */
#ifndef NEUV_IO_BYTE_ORDER_H
#define NEUV_IO_BYTE_ORDER_H

#include <stdint.h>
#include <string.h>

static inline unsigned char *put_u32le(unsigned char *p, uint32_t x)
{
    for (int i = 0; i < 4; i++) p[i] = (unsigned char)(x >> (8 * i));
    return p + 4;
}

static inline unsigned char *put_f32le(unsigned char *p, float x)
{
    uint32_t u;
    memcpy(&u, &x, 4);
    return put_u32le(p, u);
}

static inline unsigned char *put_f64le(unsigned char *p, double x)
{
    uint64_t u;
    memcpy(&u, &x, 8);
    for (int i = 0; i < 8; i++) p[i] = (unsigned char)(u >> (8 * i));
    return p + 8;
}

#endif
