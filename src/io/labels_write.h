/* Per-face labels (chart ids) written beside the mesh, for `neuv segment`.
 *   .ply: ASCII PLY whose face element carries an `int chart` property after
 *         vertex_indices (positions as exact decimals, %.17g)
 *   .obj: one `g chart_N` group per chart, holding that chart's faces
 * Written atomically (core/atomic_file.h). */
#ifndef NEUV_IO_LABELS_WRITE_H
#define NEUV_IO_LABELS_WRITE_H

#include "mesh/mesh.h"

/* Inputs:  path  output file, format by extension (.ply or .obj)
 *          m     mesh (#V by 3, #F by 3)
 *          label #F values >= 0
 * Errors:  NEUV_ERR_INPUT for another extension or a negative label,
 *          NEUV_ERR_IO when the file cannot be written. */
neuv_status labels_write(const char *path, const neuv_mesh *m, const int *label);

#endif
