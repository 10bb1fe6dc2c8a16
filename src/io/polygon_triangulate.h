/* Triangulation of one polygonal face (OBJ/OFF/PLY faces with more than
 * three corners). */
#ifndef NEUV_IO_POLYGON_TRIANGULATE_H
#define NEUV_IO_POLYGON_TRIANGULATE_H

/* Splits a simple polygon into n-2 triangles by ear clipping in the plane that
 * best fits it (Newell's normal), keeping the polygon's winding. Convex
 * polygons come out as the fan (0,1,2), (0,2,3), ... that other tools produce.
 * Degenerate or self-intersecting polygons still give n-2 triangles (the
 * remaining corners are fanned) so no face is lost.
 *
 * Inputs:
 *   n     number of corners, n >= 3
 *   P     n by 3 corner positions
 *   work  scratch room for 3*n doubles and n ints (see the two pointers)
 * Outputs:
 *   tri   (n-2) by 3 corner numbers in 0..n-1
 */
void polygon_triangulate(int n, const double *P, int *tri, double *work_xy, int *work_idx);

#endif
