/* Per-vertex orthonormal tangent frames. See tangent_frames.h. */
#include <math.h>
#include <string.h>

#include "geometry/tangent_frames.h"

static double norm3(const double v[3]) { return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

void tangent_frames(const neuv_mesh *m, double *frames)
{
    memset(frames, 0, (size_t)m->nv * 9 * sizeof *frames);
    /* Accumulate area-weighted normals (|cross| = 2 × area) in the n slot,
     * unit normals in the e1 slot as the fallback, and the summed |cross|
     * in e2[0] to tell a cancelled normal from a small one. */
    for (int f = 0; f < m->nf; f++) {
        const int *v = m->tri + 3 * f;
        const double *a = m->pos + 3 * v[0], *b = m->pos + 3 * v[1], *c = m->pos + 3 * v[2];
        double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double x[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
        double len = norm3(x);
        for (int q = 0; q < 3; q++) {
            double *fr = frames + 9 * (size_t)v[q];
            for (int d = 0; d < 3; d++) {
                fr[6 + d] += x[d];
                if (len > 0) fr[d] += x[d] / len;
            }
            fr[3] += len;
        }
    }
    for (int i = 0; i < m->nv; i++) {
        double *fr = frames + 9 * (size_t)i;
        double n[3] = {fr[6], fr[7], fr[8]};
        double len = norm3(n);
        /* A normal that cancelled to round-off is no direction. */
        if (!(len > 1e-12 * fr[3])) {
            memcpy(n, fr, sizeof n);
            len = norm3(n);
        }
        if (!(len > 0) || !isfinite(len)) { n[0] = 0; n[1] = 0; n[2] = 1; len = 1; }
        for (int d = 0; d < 3; d++) n[d] /= len;
        /* The axis least aligned with n gives a well-conditioned projection. */
        int axis = 0;
        for (int d = 1; d < 3; d++)
            if (fabs(n[d]) < fabs(n[axis])) axis = d;
        double e1[3] = {0, 0, 0};
        e1[axis] = 1.0;
        double dot = n[axis];
        for (int d = 0; d < 3; d++) e1[d] -= dot * n[d];
        double l1 = norm3(e1);
        for (int d = 0; d < 3; d++) e1[d] /= l1;
        double e2[3] = {n[1] * e1[2] - n[2] * e1[1], n[2] * e1[0] - n[0] * e1[2], n[0] * e1[1] - n[1] * e1[0]};
        for (int d = 0; d < 3; d++) {
            fr[d] = e1[d];
            fr[3 + d] = e2[d];
            fr[6 + d] = n[d];
        }
    }
}
