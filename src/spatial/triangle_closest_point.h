/* Closest point on one triangle, and barycentric coordinates of a point in
 * a triangle's plane. The building blocks of the BVH queries. */
#ifndef NEUV_SPATIAL_TRIANGLE_CLOSEST_POINT_H
#define NEUV_SPATIAL_TRIANGLE_CLOSEST_POINT_H

/* Closest point to p on triangle (a, b, c), found by the Voronoi-region
 * tests of Ericson, "Real-Time Collision Detection" (2005), section 5.1.5.
 * Degenerate (collinear) triangles fall back to the closest of their edges.
 * Inputs: a, b, c, p (3 each).
 * Outputs: bary (3) weights of a, b, c (sum 1, each in [0,1]) of the closest point.
 * Returns the squared distance from p to that point. */
double triangle_closest_point(const double a[3], const double b[3], const double c[3], const double p[3],
                              double bary[3]);

/* Barycentric coordinates of the projection of p onto the plane of
 * (a, b, c) (may be negative when it falls outside). Zero-area triangles
 * give (1/3, 1/3, 1/3).
 * Outputs: bary (3), sum 1. */
void triangle_barycentric(const double a[3], const double b[3], const double c[3], const double p[3],
                          double bary[3]);

#endif
