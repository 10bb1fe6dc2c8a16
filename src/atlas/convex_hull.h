/* Convex hull of points in the plane (Andrew's monotone chain). */
#ifndef NEUV_ATLAS_CONVEX_HULL_H
#define NEUV_ATLAS_CONVEX_HULL_H

/* Inputs: p (#P by 2) points, n = #P.
 * Outputs: hull (#P ints, caller-allocated) indices into p of the hull
 * vertices, counter-clockwise, collinear points dropped, starting at the
 * lexicographically smallest point.
 * Returns the number of hull vertices (0 when n == 0, 1 or 2 for degenerate
 * input), or -1 on allocation failure. */
int convex_hull_2d(const double *p, int n, int *hull);

#endif
