#include "mesh/signed_volume.h"

double mesh_signed_volume(const neuv_mesh *m, const int *faces, int nfaces)
{
    if (!faces) nfaces = m->nf;
    if (nfaces <= 0) return 0.0;
    const double *o = m->pos + 3 * m->tri[3 * (faces ? faces[0] : 0)];
    double vol = 0.0;
    for (int i = 0; i < nfaces; i++) {
        int f = faces ? faces[i] : i;
        const double *pa = m->pos + 3 * m->tri[3 * f], *pb = m->pos + 3 * m->tri[3 * f + 1],
                     *pc = m->pos + 3 * m->tri[3 * f + 2];
        double a[3] = {pa[0] - o[0], pa[1] - o[1], pa[2] - o[2]};
        double b[3] = {pb[0] - o[0], pb[1] - o[1], pb[2] - o[2]};
        double c[3] = {pc[0] - o[0], pc[1] - o[1], pc[2] - o[2]};
        vol += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
               a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    return vol / 6.0;
}
