/* Re-seeding an emptied PatchNet patch by splitting the patch that fits its
 * faces' normals worst (issue 20, item 5).
 *
 * A softmax output that loses all its faces gets almost no gradient back
 * (∂P_fk/∂z ∝ P_fk), so training ends with fewer patches than K: on a cube
 * two sides share one patch while another is empty. The move is k-means'
 * rule for an empty cluster, on the network's last layer:
 *
 *   - a patch is empty when the faces it wins (argmax) hold less than
 *     `empty_share` of the area;
 *   - the patch j with the largest area-weighted normal error
 *     Σ a_f (1 − n_f·m_j) over its faces is split in two by 2-means on
 *     their unit normals (started at m_j and the worst-fitting normal);
 *   - with h± the area-weighted means of the last hidden features over the
 *     two halves, d = h₊ − h₋ and mid = (h₊ + h₋)/2, the empty patch k gets
 *     j's output column plus α d and j's minus α d (biases ∓ α d·mid), with
 *     α = gap / |d|²: logit_k − logit_j = 2α d·(h − mid), +gap at h₊ and
 *     −gap at h₋, so the two halves start on two patches.
 *
 * The caller decides whether to keep the move (patchnet.c keeps it when the
 * loss does not rise) and resets the optimizer's moments of both columns. */
#ifndef NEUV_MODELS_PATCHNET_SPLIT_H
#define NEUV_MODELS_PATCHNET_SPLIT_H

#include "models/diffusion_net.h"

typedef struct patchnet_split {
    int empty;  /* the emptied patch re-seeded, -1 when none */
    int split;  /* the patch split into it */
    double moved_share; /* area share of the split patch's faces that start on `empty` */
} patchnet_split;

/* Proposes and applies the move to the last layer (w C by K, b 1 by K) in place.
 * Inputs:  P #F by K soft assignment, hidden #V by C last hidden features,
 *          g (face corners), area #F, normal #F by 3 (unit), empty_share,
 *          gap (logit difference at the halves' means)
 * Outputs: w, b changed when a move is made; *out says which (empty -1: none,
 *          nothing changed: no empty patch, or the worst patch cannot be
 *          separated by the hidden features). */
void patchnet_split_empty(const float *P, const float *hidden, const diffusion_net_geometry *g, const float *area,
                          const float *normal, int K, int C, double empty_share, double gap, float *w, float *b,
                          patchnet_split *out);

#endif
