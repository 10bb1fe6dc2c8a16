/* A second procedural family for category models, with more varied
 * geometry than the bent capsules: star-shaped blobs, a sphere whose
 * radius carries random bumps and dents of varied width, stretched along
 * three random axes, so members differ in proportions, in where they bulge
 * and in how sharply. */
#ifndef NEUV_MESH_BLOB_FAMILY_H
#define NEUV_MESH_BLOB_FAMILY_H

#include <stdint.h>

#include "mesh/mesh.h"

#define BLOB_MAX_BUMPS 8

/* The parameters of one member. */
typedef struct blob_params {
    int bumps;                       /* number of bumps and dents, 3..BLOB_MAX_BUMPS */
    double dir[BLOB_MAX_BUMPS][3];   /* unit centre of each on the sphere */
    double height[BLOB_MAX_BUMPS];   /* radial height: -0.25 (dent) .. 0.6 (bump) */
    double width[BLOB_MAX_BUMPS];    /* angular width in radians, 0.3 .. 0.9 */
    double stretch[3];               /* scale along the three axes, 0.6 .. 1.5 */
    double turn[3];                  /* rotation of those axes (Euler angles, radians) */
    int level;                       /* icosphere subdivision level, 3 or 4 */
} blob_params;

/* Member `index` of the family: parameters drawn from a generator seeded by
 * the index (uniform in the ranges above). */
void blob_family_params(uint64_t index, blob_params *p);

/* An icosphere of radius 1 (shape_icosphere), each vertex u moved to
 * r(u) u with r(u) = max(0.35, 1 + Σ_k h_k exp((u·d_k − 1) / w_k²)), then
 * stretched along the turned axes. r depends on the direction only, so the
 * surface is star-shaped and never crosses itself. NULL on bad parameters
 * or no memory. */
neuv_mesh *shape_blob(const blob_params *p);

/* shape_blob(blob_family_params(index)). */
neuv_mesh *shape_blob_family(uint64_t index);

#endif
