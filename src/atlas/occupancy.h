/* The atlas as a bitmap of taken pixels, with the searches the packer needs:
 * does a footprint fit at (x, y), and where is the lowest-then-leftmost
 * place it fits. */
#ifndef NEUV_ATLAS_OCCUPANCY_H
#define NEUV_ATLAS_OCCUPANCY_H

#include <stdint.h>

#include "atlas/footprint.h"

typedef struct occupancy {
    int size;           /* the atlas is size by size pixels */
    int words;          /* 64-bit words per row; bit i of word k is pixel 64k+i */
    uint64_t *bits;     /* #size by #words */
    int *free_run;      /* #size: longest run of free pixels in each row */
    int first_open;     /* rows below this one are completely taken */
} occupancy;

/* An empty atlas whose outer `border` pixels are already taken (so that
 * charts keep the padding to the edge). Returns 0, or -1 on allocation failure. */
int occupancy_init(occupancy *o, int size, int border);
void occupancy_free(occupancy *o);
/* Lowest-then-leftmost (y, then x) position where every span of s lands on
 * free pixels, with y + s->h <= y_end. Returns 1 and sets *x, *y when found. */
int occupancy_find(const occupancy *o, const footprint_spans *s, int y_end, int *x, int *y);
/* Marks the pixels of s placed with its pixel (0,0) at (x, y), grown by a
 * (2 pad + 1)-pixel square (the padding: every pixel within pad of a covered
 * one, in x and in y); parts outside the atlas are ignored. */
void occupancy_mark(occupancy *o, const footprint_spans *s, int x, int y, int pad);
/* 1 when pixel (x, y) is taken. */
int occupancy_get(const occupancy *o, int x, int y);

#endif
