/* Footprint of a chart in the atlas: the set of pixels its triangles touch,
 * as a bitmap and as per-row spans (the form the placement tests use). */
#ifndef NEUV_ATLAS_FOOTPRINT_H
#define NEUV_ATLAS_FOOTPRINT_H

typedef struct footprint {
    int w, h;            /* size in pixels */
    unsigned char *bits; /* #h by #w, row-major, 1 = covered */
} footprint;

typedef struct footprint_spans {
    int w, h;
    int *row_first; /* #h+1: spans of row r are row_first[r] .. row_first[r+1]-1 */
    int *x0, *x1;   /* inclusive pixel ranges, left to right */
    int *row_width; /* #h: widest span of each row (0 for an empty row) */
    int *row_order; /* #h: rows by decreasing width (ties by row), the order collision tests use */
    int count;
} footprint_spans;

/* Conservative rasterization: every pixel [i,i+1]x[j,j+1] that a triangle
 * touches (boundary included, grown by a tiny epsilon so that rounding in a
 * later transform cannot reach an unmarked pixel) is set.
 * Inputs: p (#P by 2) points in pixel units with coordinates >= 0, tri
 * (#T by 3) indices into p, w by h the bitmap size (points must lie below it).
 * Outputs: out, allocated here (footprint_free).
 * Returns 0, or -1 on allocation failure. */
int footprint_rasterize(const double *p, const int *tri, int ntri, int w, int h, footprint *out);
/* Rotation by k quarter turns counter-clockwise (y up): pixel (i,j) goes to
 * (h-1-j, i) for k = 1, i.e. the map (x,y) -> (h-y, x) of the pixel square.
 * Returns 0, or -1 on allocation failure. */
int footprint_rotate(const footprint *in, int k, footprint *out);
/* Covered pixels as runs per row. Returns 0, or -1 on allocation failure. */
int footprint_to_spans(const footprint *in, footprint_spans *out);
/* The spans of `in` turned by a half turn, as footprint_to_spans gives them
 * for footprint_rotate(.., 2, ..), without the bitmap. Returns 0, or -1 on
 * allocation failure. */
int footprint_spans_half_turn(const footprint_spans *in, footprint_spans *out);
/* 1 when a and b cover the same pixels in boxes of the same size. */
int footprint_spans_equal(const footprint_spans *a, const footprint_spans *b);
/* Number of covered pixels. */
long footprint_count(const footprint *in);
int footprint_equal(const footprint *a, const footprint *b);
void footprint_free(footprint *f);
void footprint_spans_free(footprint_spans *s);

#endif
