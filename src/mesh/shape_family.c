/* Bent capsules: see shape_family.h. */
#include "mesh/shape_family.h"

#include <math.h>
#include <stddef.h>

#include "core/rng.h"
#include "mesh/shapes.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

void capsule_family_params(uint64_t index, capsule_params *p)
{
    rng r;
    rng_seed(&r, 0xca95u + 0x9E3779B97F4A7C15ull * (index + 1));
    p->radius = 0.3 + 0.25 * rng_uniform(&r);
    p->length = 0.8 + 1.7 * rng_uniform(&r);
    p->bulge = -0.1 + 0.35 * rng_uniform(&r);
    p->bend = 1.5 * rng_uniform(&r);
    p->size = 0.5 + 1.5 * rng_uniform(&r);
    p->slices = 20 + rng_below(&r, 13);
    p->stacks = 6 + rng_below(&r, 5);
    /* The bend circle must stay outside the tube: radius >= 2x the widest tube. */
    double total = p->length + 2 * p->radius, widest = p->radius * (1 + (p->bulge > 0 ? p->bulge : 0));
    if (p->bend > total / (2 * widest)) p->bend = total / (2 * widest);
}

neuv_mesh *shape_bent_capsule(const capsule_params *p)
{
    if (!(p->radius > 0) || !(p->length >= 0) || !(p->size > 0) || !(p->bulge > -0.9) || !(p->bend >= 0))
        return NULL;
    neuv_mesh *m = shape_capsule(p->radius, p->length, p->slices, p->stacks);
    if (!m) return NULL;
    double total = p->length + 2 * p->radius;
    double bend_radius = p->bend > 1e-9 ? total / p->bend : 0;
    if (bend_radius > 0 && bend_radius <= p->radius * (1 + fabs(p->bulge))) { mesh_free(m); return NULL; }
    for (int v = 0; v < m->nv; v++) {
        double *x = m->pos + 3 * v;
        double grow = 1 + p->bulge * cos(M_PI * x[2] / total);
        x[0] *= grow;
        x[1] *= grow;
        if (bend_radius > 0) {
            /* The axis becomes an arc of the circle of radius bend_radius
             * centred at (bend_radius, 0, 0); arc length along it is z. */
            double th = x[2] / bend_radius, d = bend_radius - x[0];
            x[0] = bend_radius - d * cos(th);
            x[2] = d * sin(th);
        }
        for (int q = 0; q < 3; q++) x[q] *= p->size;
    }
    return m;
}

neuv_mesh *shape_capsule_family(uint64_t index)
{
    capsule_params p;
    capsule_family_params(index, &p);
    return shape_bent_capsule(&p);
}
