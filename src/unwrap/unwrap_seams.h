/* Required seams in the pipeline: the cleaned mesh is cut open along them
 * before the charts are made and joined again before the metrics, so every
 * chart step meets a boundary there (mesh/seam_cut.h). */
#ifndef NEUV_UNWRAP_UNWRAP_SEAMS_H
#define NEUV_UNWRAP_UNWRAP_SEAMS_H

#include "unwrap/unwrap_internal.h"

/* Cuts r->mesh (cleaned, not yet rescaled) along the edges above
 * r->opts.seam_angle, the pairs r->opts.seam_edges (vertex indices of `in`,
 * the mesh before cleaning) and, with r->opts.hard_edges, the hard and
 * material edges of `in` (mesh/hard_edges.h). Nothing to do without any.
 * With a saved model, made (keep_model) or applied (apply), seams asked for
 * are refused (NEUV_ERR_INPUT: a model does not record seams yet); the
 * file's own hard edges are refused with keep_model (the atlas would differ
 * from the one without it) and, applied, left out and counted in
 * r->hard_edges_not_kept. */
neuv_status unwrap_seams_cut(struct neuv_unwrap_result *r, const neuv_mesh *in, int keep_model, int apply);

/* Joins the copies again (r->mesh gets the cleaned mesh's vertices back; the
 * corners keep their UVs) and counts in r->seam_crossed the seam edges whose
 * two faces have the same UVs at both ends. Nothing to do when not cut. */
neuv_status unwrap_seams_join(struct neuv_unwrap_result *r);

#endif
