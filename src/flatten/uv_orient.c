#include "flatten/uv_orient.h"

void flatten_orient_ccw(const neuv_mesh *m, double *uv)
{
    double area = 0;
    for (int f = 0; f < m->nf; f++) {
        const double *a = uv + 2 * m->tri[3 * f], *b = uv + 2 * m->tri[3 * f + 1], *c = uv + 2 * m->tri[3 * f + 2];
        area += (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    }
    if (area < 0)
        for (int v = 0; v < m->nv; v++) uv[2 * v] = -uv[2 * v];
}
