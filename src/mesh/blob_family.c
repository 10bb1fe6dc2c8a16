/* Star-shaped blobs: see blob_family.h. */
#include "mesh/blob_family.h"

#include <math.h>
#include <stddef.h>

#include "core/rng.h"
#include "mesh/shapes.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

void blob_family_params(uint64_t index, blob_params *p)
{
    rng r;
    rng_seed(&r, 0xb10bu + 0x9E3779B97F4A7C15ull * (index + 1));
    p->bumps = 3 + (int)rng_below(&r, BLOB_MAX_BUMPS - 2);
    for (int k = 0; k < p->bumps; k++) {
        /* uniform on the sphere */
        double z = 2 * rng_uniform(&r) - 1, a = 2 * M_PI * rng_uniform(&r), s = sqrt(1 - z * z);
        p->dir[k][0] = s * cos(a);
        p->dir[k][1] = s * sin(a);
        p->dir[k][2] = z;
        p->height[k] = -0.25 + 0.85 * rng_uniform(&r);
        p->width[k] = 0.3 + 0.6 * rng_uniform(&r);
    }
    for (int q = 0; q < 3; q++) p->stretch[q] = 0.6 + 0.9 * rng_uniform(&r);
    for (int q = 0; q < 3; q++) p->turn[q] = 2 * M_PI * rng_uniform(&r);
    p->level = 3 + (int)rng_below(&r, 2);
}

/* R = Rz(c) Ry(b) Rx(a). */
static void rotation(const double t[3], double R[9])
{
    double ca = cos(t[0]), sa = sin(t[0]), cb = cos(t[1]), sb = sin(t[1]), cc = cos(t[2]), sc = sin(t[2]);
    R[0] = cc * cb; R[1] = cc * sb * sa - sc * ca; R[2] = cc * sb * ca + sc * sa;
    R[3] = sc * cb; R[4] = sc * sb * sa + cc * ca; R[5] = sc * sb * ca - cc * sa;
    R[6] = -sb;     R[7] = cb * sa;                R[8] = cb * ca;
}

neuv_mesh *shape_blob(const blob_params *p)
{
    if (p->bumps < 0 || p->bumps > BLOB_MAX_BUMPS || p->level < 0 || p->level > 6) return NULL;
    for (int q = 0; q < 3; q++)
        if (!(p->stretch[q] > 0)) return NULL;
    for (int k = 0; k < p->bumps; k++)
        if (!(p->width[k] > 0)) return NULL;
    neuv_mesh *m = shape_icosphere(p->level, 1.0);
    if (!m) return NULL;
    double R[9];
    rotation(p->turn, R);
    for (int v = 0; v < m->nv; v++) {
        double *x = m->pos + 3 * v, n = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        double u[3] = {x[0] / n, x[1] / n, x[2] / n}, rad = 1;
        for (int k = 0; k < p->bumps; k++) {
            double c = u[0] * p->dir[k][0] + u[1] * p->dir[k][1] + u[2] * p->dir[k][2];
            rad += p->height[k] * exp((c - 1) / (p->width[k] * p->width[k]));
        }
        if (rad < 0.35) rad = 0.35;
        /* stretch along the turned axes: x' = R S Rᵀ (rad u) */
        double y[3], z[3];
        for (int i = 0; i < 3; i++) y[i] = rad * (R[i] * u[0] + R[3 + i] * u[1] + R[6 + i] * u[2]) * p->stretch[i];
        for (int i = 0; i < 3; i++) z[i] = R[3 * i] * y[0] + R[3 * i + 1] * y[1] + R[3 * i + 2] * y[2];
        for (int i = 0; i < 3; i++) x[i] = z[i];
    }
    return m;
}

neuv_mesh *shape_blob_family(uint64_t index)
{
    blob_params p;
    blob_family_params(index, &p);
    return shape_blob(&p);
}
