/* The atlas as a bitmap of taken pixels, with the searches the packer needs:
 * does a footprint fit at (x, y), and where is the lowest-then-leftmost
 * place it fits. */
#ifndef NEUV_ATLAS_OCCUPANCY_H
#define NEUV_ATLAS_OCCUPANCY_H

#include <stdint.h>

#include "atlas/footprint.h"

typedef struct occupancy {
    int size;           /* the atlas is size by size pixels */
    int words;          /* 64-bit words of pixels per row; bit i of word k is pixel 64k+i */
    int stride;         /* words + 1: each row ends in taken bits, so a 64-pixel read that
                           starts inside the atlas stays inside the row */
    int levels;         /* blocked-run levels kept in `runs` (0..OCCUPANCY_LEVELS) */
    uint64_t *bits;     /* #size by #stride, 1 = taken (pixels past the atlas are taken) */
    uint64_t *runs;     /* #levels by #size by #stride: in level k (1..levels), bit p of a row
                           is set when a pixel of [p, p + 2^k) in that row is taken */
    int *free_run;      /* #size: longest run of free pixels in each row */
    int first_open;     /* rows below this one are completely taken */
} occupancy;

/* Most blocked-run levels: a span up to 2^OCCUPANCY_LEVELS pixels wide is
 * tested against 64 positions with two reads. */
#define OCCUPANCY_LEVELS 6

/* Largest side (the packer's resolution limit). */
#define OCCUPANCY_MAX_SIZE 32768

/* An empty atlas whose outer `border` pixels are already taken (so that
 * charts keep the padding to the edge), keeping as many blocked-run levels
 * as fit a 64 MiB budget. Returns 0, or -1 on allocation failure or a size
 * outside 1..OCCUPANCY_MAX_SIZE. */
int occupancy_init(occupancy *o, int size, int border);
/* The same with `levels` (0..OCCUPANCY_LEVELS) blocked-run levels: fewer
 * levels save memory and make wide spans slower to test, never different. */
int occupancy_init_levels(occupancy *o, int size, int border, int levels);
void occupancy_free(occupancy *o);
/* Lowest-then-leftmost (y, then x) position where every span of s lands on
 * free pixels, with y + s->h <= y_end. Returns 1 and sets *x, *y when found. */
int occupancy_find(const occupancy *o, const footprint_spans *s, int y_end, int *x, int *y);
/* The position where every span of s lands on free pixels nearest to
 * (x0, y0) (squared pixel distance; ties: lower y, then lower x). Returns 1
 * and sets *x, *y when one exists. */
int occupancy_find_nearest(const occupancy *o, const footprint_spans *s, int x0, int y0, int *x, int *y);
/* Marks the pixels of s placed with its pixel (0,0) at (x, y), grown by a
 * (2 pad + 1)-pixel square (the padding: every pixel within pad of a covered
 * one, in x and in y); parts outside the atlas are ignored. */
void occupancy_mark(occupancy *o, const footprint_spans *s, int x, int y, int pad);
/* Which of the 64 placements x + i (bit i) of a len-pixel run [x + i, x + i + len)
 * on row y hit a taken pixel (pixels past the atlas count as taken).
 * Needs 0 <= x, len >= 1 and x + len <= size. */
uint64_t occupancy_run_blocked(const occupancy *o, int y, int x, int len);
/* 1 when pixel (x, y) is taken. */
int occupancy_get(const occupancy *o, int x, int y);

#endif
