/* Lumped (barycentric) vertex mass. */
#include <string.h>

#include "geometry/lumped_mass.h"

void lumped_mass(const neuv_mesh *m, double *mass)
{
    memset(mass, 0, (size_t)m->nv * sizeof *mass);
    for (int f = 0; f < m->nf; f++) {
        double a = mesh_face_area(m, f) / 3.0;
        for (int c = 0; c < 3; c++) mass[m->tri[3 * f + c]] += a;
    }
}
