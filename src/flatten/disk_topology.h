/* The check both classic flattenings start with: the mesh must be one
 * topological disk (one connected component, one boundary loop, genus 0). */
#ifndef NEUV_FLATTEN_DISK_TOPOLOGY_H
#define NEUV_FLATTEN_DISK_TOPOLOGY_H

#include "mesh/mesh.h"

/* Succeeds when m is one disk; its boundary loop is returned in order.
 *
 * Inputs:  m         cleaned manifold mesh (#F by 3 faces)
 * Outputs: boundary  (may be NULL) the loop's vertices, caller frees
 *          nboundary (may be NULL) its length
 * Errors:  NEUV_ERR_INPUT "not a disk: 1 component, closed, genus 4" style,
 *          naming the topology found; NEUV_ERR_NOMEM. */
neuv_status flatten_require_disk(const neuv_mesh *m, int **boundary, int *nboundary);

#endif
