/* Procedural shapes for the demo and the tests (no third-party data).
 * Every function returns a new mesh (caller frees with mesh_free), faces
 * counter-clockwise seen from outside, or NULL on allocation failure. */
#ifndef NEUV_MESH_SHAPES_H
#define NEUV_MESH_SHAPES_H

#include "mesh/mesh.h"

/* Unit icosphere: the icosahedron subdivided `level` times, vertices
 * projected to the sphere (level 5: 10242 vertices, 20480 faces). */
neuv_mesh *shape_icosphere(int level, double radius);
/* Latitude-longitude sphere with `slices` around and `stacks` pole to pole. */
neuv_mesh *shape_uv_sphere(int slices, int stacks, double radius);
/* Torus around z: major radius R, minor radius r, nu by nv quads split in two. */
neuv_mesh *shape_torus(double R, double r, int nu, int nv);
/* A torus whose tube radius varies smoothly, r (1 + bump sin 5u sin 3v):
 * curved everywhere, genus 1 (the demo shape). */
neuv_mesh *shape_bumpy_torus(double R, double r, double bump, int nu, int nv);
/* Flat grid in z = 0 over [0,w] by [0,h] with nx by ny cells (each split in two);
 * with_uv: per-corner UVs equal to (x, y) (identity map). */
neuv_mesh *shape_grid(int nx, int ny, double w, double h, int with_uv);
/* Open cylinder around z, radius r, z in [-h/2, h/2] (no caps): two boundary loops. */
neuv_mesh *shape_cylinder(double r, double h, int slices, int stacks);
/* Capsule around z: cylinder of radius r, z in [-h/2, h/2], closed by hemispheres
 * with `stacks` rings from pole to equator. */
neuv_mesh *shape_capsule(double r, double h, int slices, int stacks);
/* Axis-aligned cube [-1,1]^3, each side an n by n grid of quads split in two. */
neuv_mesh *shape_cube(int n);
/* A closed surface of genus 2: a thick plate [-2.5,2.5] x [-1.5,1.5] x
 * [-0.5,0.5] with two unit square holes through it, built as the boundary
 * of 5n by 3n by n voxels, so `n` is the number of cells per unit length
 * (n = 1: 100 faces; faces grow as n^2). Area 50, volume 13. */
neuv_mesh *shape_genus2(int n);

#endif
