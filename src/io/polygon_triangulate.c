#include "io/polygon_triangulate.h"

#include <math.h>

/* Twice the signed area of triangle (a,b,c) in the plane. */
static double orient2d(const double *a, const double *b, const double *c)
{
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

static void fan(int n, int first, const int *idx, int *tri)
{
    for (int i = 1; i + 1 < n; i++) {
        tri[3 * (first + i - 1)] = idx[0];
        tri[3 * (first + i - 1) + 1] = idx[i];
        tri[3 * (first + i - 1) + 2] = idx[i + 1];
    }
}

void polygon_triangulate(int n, const double *P, int *tri, double *xy, int *idx)
{
    for (int i = 0; i < n; i++) idx[i] = i;
    /* Newell's normal: robust for non-planar and non-convex polygons, and it
     * points the way the corners wind, so projecting onto a basis (u, v) with
     * u x v = normal makes the polygon counter-clockwise in 2D. */
    double N[3] = {0, 0, 0};
    for (int i = 0; i < n; i++) {
        const double *a = P + 3 * i, *b = P + 3 * ((i + 1) % n);
        N[0] += (a[1] - b[1]) * (a[2] + b[2]);
        N[1] += (a[2] - b[2]) * (a[0] + b[0]);
        N[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    double len = sqrt(N[0] * N[0] + N[1] * N[1] + N[2] * N[2]);
    if (!(len > 0) || n == 3) { fan(n, 0, idx, tri); return; }
    for (int k = 0; k < 3; k++) N[k] /= len;
    double u[3];
    if (fabs(N[0]) < 0.6) { u[0] = 0; u[1] = N[2]; u[2] = -N[1]; }  /* N x e_x */
    else { u[0] = -N[2]; u[1] = 0; u[2] = N[0]; }                   /* e_y x N */
    double ul = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    for (int k = 0; k < 3; k++) u[k] /= ul;
    double v[3] = {N[1] * u[2] - N[2] * u[1], N[2] * u[0] - N[0] * u[2], N[0] * u[1] - N[1] * u[0]};
    for (int i = 0; i < n; i++) {
        const double *p = P + 3 * i;
        xy[2 * i] = p[0] * u[0] + p[1] * u[1] + p[2] * u[2];
        xy[2 * i + 1] = p[0] * v[0] + p[1] * v[1] + p[2] * v[2];
    }

    int m = n, t = 0;
    while (m > 3) {
        int ear = -1;
        /* Scanning from corner 1 makes a convex polygon come out as a fan. */
        for (int s = 0; s < m && ear < 0; s++) {
            int i = (s + 1) % m;
            int a = idx[(i + m - 1) % m], b = idx[i], c = idx[(i + 1) % m];
            const double *A = xy + 2 * a, *B = xy + 2 * b, *C = xy + 2 * c;
            if (!(orient2d(A, B, C) > 0)) continue; /* reflex or flat corner */
            int blocked = 0;
            for (int j = 0; j < m && !blocked; j++) {
                int q = idx[j];
                if (q == a || q == b || q == c) continue;
                const double *Q = xy + 2 * q;
                blocked = orient2d(A, B, Q) > 0 && orient2d(B, C, Q) > 0 && orient2d(C, A, Q) > 0;
            }
            if (!blocked) ear = i;
        }
        if (ear < 0) break; /* no ear: degenerate polygon, fan the rest */
        tri[3 * t] = idx[(ear + m - 1) % m];
        tri[3 * t + 1] = idx[ear];
        tri[3 * t + 2] = idx[(ear + 1) % m];
        t++;
        for (int j = ear; j + 1 < m; j++) idx[j] = idx[j + 1];
        m--;
    }
    fan(m, t, idx, tri);
}
