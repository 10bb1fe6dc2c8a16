/* Easing back the pulls that collapse faces, for the apply path's overlap
 * mend (unwrap_apply.c, pull_past_borders). */
#ifndef NEUV_UNWRAP_UV_PULL_EASE_H
#define NEUV_UNWRAP_UV_PULL_EASE_H

#include "mesh/mesh.h"

/* Share of its UV area before a pull under which a face counts as
 * collapsed by it, and the most halvings of a collapsing pull. */
#define UV_PULL_KEEP_AREA 0.1
#define UV_PULL_EASE_ROUNDS 10

/* A pull of a chart's corners toward its island's border can lay a corner
 * on the line through its face's other two (their closest source points lie
 * on one stretch of the border): the face is not folded, so no fold check
 * refuses it, but its texture is a streak (homer's model on a jittered
 * remesh at half its faces: one face at qce 1.5e6; bench/RESULTS.md,
 * "Faces collapsed by the pull"). Each face of sub left with less than
 * UV_PULL_KEEP_AREA of its area in uv0, folded ones included, has the pull
 * of its moved corners halved, round after round, until no face is (at most
 * UV_PULL_EASE_ROUNDS rounds: a corner is then within 1/1024 of its pull
 * from where it was). A pull that folded a face was undone whole before, for
 * the whole chart; eased, the rest of it stays (measured against easing the
 * collapsed faces only: same bench). Faces not positive in uv0 are left to
 * the fold checks. uv0: sub's UVs before the pull; uv: after it, eased in
 * place. Returns the corners eased. */
int uv_pull_ease(const neuv_mesh *sub, const double *uv0, double *uv);

/* Twice the signed area of triangle t (three indices) in uv (two per index). */
double uv_face_area2(const double *uv, const int *t);

#endif
