/* Minimum-area bounding rectangle of a point set (Freeman & Shapira 1975:
 * the optimal rectangle has a side collinear with a convex hull edge, so
 * rotating calipers over the hull edges find it). */
#ifndef NEUV_ATLAS_MIN_AREA_RECT_H
#define NEUV_ATLAS_MIN_AREA_RECT_H

/* Inputs: p (#P by 2) points, n = #P.
 * Outputs: *angle, the rotation (radians, in [0, pi/2)) that, applied to the
 * points (x' = cos a x - sin a y, y' = sin a x + cos a y), makes the minimum
 * rectangle axis-aligned; *width, *height its sides after that rotation.
 * Returns 0, or -1 on allocation failure. */
int min_area_rect(const double *p, int n, double *angle, double *width, double *height);

#endif
