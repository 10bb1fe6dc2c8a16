/* Least squares conformal maps (Lévy, Petitjean, Ray, Maillot 2002) with a
 * free boundary: two boundary vertices pinned, everything else chosen to make
 * the map as conformal as possible in the least-squares sense.
 *
 * Pins: the boundary pair farthest apart in 3D (exact search up to 4096
 * boundary vertices, a deterministic double sweep beyond), placed at (0,0)
 * and (d,0) with d their 3D distance, so the result has roughly the mesh's
 * scale. The result is oriented counter-clockwise (positive total UV area).
 *
 * Inputs:  m   one disk (see flatten_require_disk), #V by 3, #F by 3
 * Outputs: uv  #V by 2 (caller allocates); vertices used by no face get (0,0)
 * Errors:  NEUV_ERR_INPUT when m is not one disk (the message names its
 *          topology), NEUV_ERR_NOMEM, NEUV_ERR_INTERNAL if the solve fails. */
#ifndef NEUV_FLATTEN_LSCM_H
#define NEUV_FLATTEN_LSCM_H

#include "mesh/mesh.h"

neuv_status lscm(const neuv_mesh *m, double *uv);

#endif
