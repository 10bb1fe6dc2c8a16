/* UDIM tiles of a UV layout (docs/metrics.md, "tiles"): which unit squares
 * [u0, u0+1] x [v0, v0+1] (UDIM 1001 + u0 + 10 v0) hold faces, and how full
 * each one is, measured as packing_efficiency measures the one square. */
#ifndef NEUV_METRICS_UV_TILES_H
#define NEUV_METRICS_UV_TILES_H

#include "core/json_writer.h"
#include "mesh/mesh.h"

/* Inputs:  m with UVs (nuv > 0, tri_uv #F by 3); positions welded as for
 *          uv_metrics_compute (charts are UV-connected components).
 * Outputs: *tiles (*count, sorted by udim; caller frees with mem_free) when
 *          every face lies within one tile with u0 in 0..9 and v0 in 0..9,
 *          to UV_METRICS_UNIT_TOL; otherwise *tiles = NULL, *count = 0.
 *          Faces of (nearly) zero 3D area count as in uv_metrics_compute:
 *          not at all.
 * Returns NEUV_OK, NEUV_ERR_INPUT (no UVs) or NEUV_ERR_NOMEM. */
neuv_status uv_tiles_compute(const neuv_mesh *m, neuv_uv_tile **tiles, int *count);

/* Writes the tiles as a JSON array of {udim, charts, faces, efficiency}. */
void uv_tiles_write_json(const neuv_uv_tile *tiles, int count, json_writer *w);

#endif
