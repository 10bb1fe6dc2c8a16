#include "atlas/min_area_rect.h"

#include <math.h>
#include <stdlib.h>

#include "atlas/convex_hull.h"
#include "core/mem.h"

static const double half_pi = 1.57079632679489661923;

/* Extent of the hull along the direction (c, s) and its normal. */
static void extents(const double *p, const int *hull, int h, double c, double s, double *w, double *ht)
{
    double lo0 = INFINITY, hi0 = -INFINITY, lo1 = INFINITY, hi1 = -INFINITY;
    for (int i = 0; i < h; i++) {
        const double *q = p + 2 * hull[i];
        double u = c * q[0] - s * q[1], v = s * q[0] + c * q[1];
        if (u < lo0) lo0 = u;
        if (u > hi0) hi0 = u;
        if (v < lo1) lo1 = v;
        if (v > hi1) hi1 = v;
    }
    *w = hi0 - lo0;
    *ht = hi1 - lo1;
}

int min_area_rect(const double *p, int n, double *angle, double *width, double *height)
{
    *angle = 0; *width = 0; *height = 0;
    if (n <= 0) return 0;
    int *hull = mem_alloc(sizeof *hull * (size_t)n);
    if (!hull) return -1;
    int h = convex_hull_2d(p, n, hull);
    if (h < 0) { mem_free(hull); return -1; }
    double best = INFINITY;
    extents(p, hull, h, 1, 0, width, height);
    best = *width * *height;
    /* Hull edges number O(boundary); each costs O(hull) here, which stays
     * small next to rasterizing the chart. The candidate angle rotates the
     * edge onto the x axis, reduced to [0, pi/2) since a rectangle's sides
     * repeat every quarter turn. */
    for (int i = 0; i < h && h >= 2; i++) {
        const double *a = p + 2 * hull[i], *b = p + 2 * hull[(i + 1) % h];
        double ex = b[0] - a[0], ey = b[1] - a[1];
        if (ex == 0 && ey == 0) continue;
        double t = -atan2(ey, ex);
        t = fmod(t, half_pi);
        if (t < 0) t += half_pi;
        if (t >= half_pi) t = 0;
        double w, ht;
        extents(p, hull, h, cos(t), sin(t), &w, &ht);
        /* Relative tolerance keeps the choice stable under rounding. */
        if (w * ht < best * (1 - 1e-12)) { best = w * ht; *angle = t; *width = w; *height = ht; }
    }
    mem_free(hull);
    return 0;
}
