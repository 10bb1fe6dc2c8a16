/* Lumped (barycentric) mass: one third of the area of each incident face.
 *
 * Inputs:  m    mesh
 * Outputs: mass #V vertex areas (caller allocates) */
#ifndef NEUV_GEOMETRY_LUMPED_MASS_H
#define NEUV_GEOMETRY_LUMPED_MASS_H

#include "mesh/mesh.h"

void lumped_mass(const neuv_mesh *m, double *mass);

#endif
