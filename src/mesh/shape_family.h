/* A procedural family of shapes for category models (issue 8): bent
 * capsules of varied proportions, bulge, bend, size and tessellation, so
 * that a model trained on some members can be tried on unseen ones. */
#ifndef NEUV_MESH_SHAPE_FAMILY_H
#define NEUV_MESH_SHAPE_FAMILY_H

#include <stdint.h>

#include "mesh/mesh.h"

/* The parameters of one member. */
typedef struct capsule_params {
    double radius;   /* tube radius */
    double length;   /* cylinder length between the caps */
    double bulge;    /* relative radius change at the middle (cosine profile along the axis) */
    double bend;     /* angle in radians the axis turns over the whole length (0: straight) */
    double size;     /* uniform scale of the result */
    int slices, stacks; /* tessellation (shape_capsule) */
} capsule_params;

/* Member `index` of the family: parameters drawn from a generator seeded by
 * the index (uniform: radius 0.3-0.55, length 0.8-2.5, bulge -0.1-0.25, bend
 * 0-1.5 rad capped so the tube never folds into itself, size 0.5-2, slices
 * 20-32, stacks 6-10). */
void capsule_family_params(uint64_t index, capsule_params *p);

/* A capsule along z (shape_capsule), its radius scaled by
 * 1 + bulge·cos(π z / total length), then bent in the x-z plane around a
 * circle of radius total length / bend, then scaled by size. Faces stay
 * counter-clockwise seen from outside. NULL on bad parameters or no memory. */
neuv_mesh *shape_bent_capsule(const capsule_params *p);

/* shape_bent_capsule(capsule_family_params(index)). */
neuv_mesh *shape_capsule_family(uint64_t index);

#endif
