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

/* LSCM held near a given map instead of pinned: minimizes the same
 * conformal energy plus (lambda / A) sum_v a_v |uv_v - anchor_v|^2, with A
 * the chart's 3D area and a_v a third of the areas of the faces at v. Both
 * terms scale alike with the UV units, so lambda alone sets the balance:
 * an offset of d chart sides (sqrt A) costs what a conformal residual of
 * about sqrt(lambda) d over the chart does. Used to mend a map with a few
 * folded faces while keeping it where it was (the anchor's frame, scale and
 * orientation); the result is not guaranteed to be fold-free (check it).
 * Inputs: m one disk, anchor #V by 2, lambda > 0. Outputs: uv #V by 2.
 * Errors as lscm(), and NEUV_ERR_INPUT for lambda <= 0 or no area. */
neuv_status lscm_anchored(const neuv_mesh *m, const double *anchor, double lambda, double *uv);

#endif
