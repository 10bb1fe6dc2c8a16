/* A small RGB canvas for the preview pictures: pixels, blended lines,
 * triangles at pixel centres, and digits for legends. */
#ifndef NEUV_ATLAS_RASTER_IMAGE_H
#define NEUV_ATLAS_RASTER_IMAGE_H

#include <stdint.h>

typedef struct raster_image {
    int w, h;
    uint8_t *rgb; /* #h by #w by 3, top row first */
} raster_image;

/* Allocates a w by h image filled with colour c. Returns 0, or -1 on allocation failure. */
int raster_image_init(raster_image *img, int w, int h, const uint8_t c[3]);
void raster_image_free(raster_image *img);
/* Blends colour c over pixel (x, y) with opacity alpha in [0,1]; ignores pixels outside. */
void raster_blend(raster_image *img, int x, int y, const uint8_t c[3], double alpha);
/* A one-pixel line between two points (pixel units, pixel centres at +0.5). */
void raster_line(raster_image *img, double x0, double y0, double x1, double y1, const uint8_t c[3], double alpha);
/* Filled axis-aligned rectangle [x0, x1) by [y0, y1). */
void raster_fill_rect(raster_image *img, int x0, int y0, int x1, int y1, const uint8_t c[3]);
/* Text of digits, '.', '-', '+' and spaces in a 3 by 5 pixel font magnified
 * `scale` times, top-left corner at (x, y). */
void raster_text(raster_image *img, int x, int y, const char *s, int scale, const uint8_t c[3]);

/* Calls fn for every pixel of a w by h grid whose centre lies inside the
 * triangle p (#3 by 2, pixel units), either orientation, with barycentric
 * coordinates b (summing to 1). Edges follow a top-left rule computed the
 * same way for both triangles sharing an edge, so a shared edge's pixels go
 * to exactly one of them. Degenerate triangles draw nothing. */
typedef void (*raster_pixel_fn)(void *user, int x, int y, const double b[3]);
void raster_triangle(const double p[3][2], int w, int h, raster_pixel_fn fn, void *user);

/* A distinct colour for integer id (deterministic, not too dark). */
void raster_palette(int id, uint8_t c[3]);

#endif
