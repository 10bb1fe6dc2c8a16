#include "spatial/triangle_closest_point.h"

static double dot3(const double *u, const double *v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; }

static double dist2_to(const double a[3], const double b[3], const double c[3], const double p[3],
                       const double bary[3])
{
    double s = 0;
    for (int i = 0; i < 3; i++) {
        double q = bary[0] * a[i] + bary[1] * b[i] + bary[2] * c[i];
        s += (p[i] - q) * (p[i] - q);
    }
    return s;
}

/* Closest point on segment (u, v) as its parameter t in [0,1]. */
static double segment_param(const double u[3], const double v[3], const double p[3])
{
    double d[3] = {v[0] - u[0], v[1] - u[1], v[2] - u[2]}, w[3] = {p[0] - u[0], p[1] - u[1], p[2] - u[2]};
    double len2 = dot3(d, d);
    if (len2 <= 0) return 0;
    double t = dot3(w, d) / len2;
    return t < 0 ? 0 : t > 1 ? 1 : t;
}

/* Zero-area triangle: the best of its three edges. */
static double degenerate_closest(const double a[3], const double b[3], const double c[3], const double p[3],
                                 double bary[3])
{
    double cand[3][3], best = -1;
    double t = segment_param(a, b, p);
    cand[0][0] = 1 - t; cand[0][1] = t; cand[0][2] = 0;
    t = segment_param(b, c, p);
    cand[1][0] = 0; cand[1][1] = 1 - t; cand[1][2] = t;
    t = segment_param(c, a, p);
    cand[2][0] = t; cand[2][1] = 0; cand[2][2] = 1 - t;
    for (int k = 0; k < 3; k++) {
        double d = dist2_to(a, b, c, p, cand[k]);
        if (best < 0 || d < best) { best = d; bary[0] = cand[k][0]; bary[1] = cand[k][1]; bary[2] = cand[k][2]; }
    }
    return best;
}

double triangle_closest_point(const double a[3], const double b[3], const double c[3], const double p[3],
                              double bary[3])
{
    double ab[3], ac[3], ap[3], bp[3], cp[3];
    for (int i = 0; i < 3; i++) {
        ab[i] = b[i] - a[i]; ac[i] = c[i] - a[i];
        ap[i] = p[i] - a[i]; bp[i] = p[i] - b[i]; cp[i] = p[i] - c[i];
    }
    double d1 = dot3(ab, ap), d2 = dot3(ac, ap);
    if (d1 <= 0 && d2 <= 0) { bary[0] = 1; bary[1] = 0; bary[2] = 0; goto done; }
    double d3 = dot3(ab, bp), d4 = dot3(ac, bp);
    if (d3 >= 0 && d4 <= d3) { bary[0] = 0; bary[1] = 1; bary[2] = 0; goto done; }
    double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        double v = d1 / (d1 - d3);
        bary[0] = 1 - v; bary[1] = v; bary[2] = 0;
        goto done;
    }
    double d5 = dot3(ab, cp), d6 = dot3(ac, cp);
    if (d6 >= 0 && d5 <= d6) { bary[0] = 0; bary[1] = 0; bary[2] = 1; goto done; }
    double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        double w = d2 / (d2 - d6);
        bary[0] = 1 - w; bary[1] = 0; bary[2] = w;
        goto done;
    }
    double va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
        double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        bary[0] = 0; bary[1] = 1 - w; bary[2] = w;
        goto done;
    }
    double sum = va + vb + vc;
    if (!(sum > 0)) return degenerate_closest(a, b, c, p, bary);
    double v = vb / sum, w = vc / sum;
    bary[0] = 1 - v - w; bary[1] = v; bary[2] = w;
done:
    return dist2_to(a, b, c, p, bary);
}

void triangle_barycentric(const double a[3], const double b[3], const double c[3], const double p[3],
                          double bary[3])
{
    double e0[3], e1[3], e2[3];
    for (int i = 0; i < 3; i++) { e0[i] = b[i] - a[i]; e1[i] = c[i] - a[i]; e2[i] = p[i] - a[i]; }
    double d00 = dot3(e0, e0), d01 = dot3(e0, e1), d11 = dot3(e1, e1);
    double d20 = dot3(e2, e0), d21 = dot3(e2, e1);
    double den = d00 * d11 - d01 * d01;
    if (!(den > 1e-300)) { bary[0] = bary[1] = bary[2] = 1.0 / 3.0; return; }
    double v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den;
    bary[0] = 1 - v - w; bary[1] = v; bary[2] = w;
}
