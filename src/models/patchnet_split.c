/* Re-seeding an emptied patch: see patchnet_split.h. */
#include "models/patchnet_split.h"

#include <math.h>
#include <stdlib.h>

#include "core/mem.h"

static int argmax_row(const float *p, int K)
{
    int best = 0;
    for (int k = 1; k < K; k++)
        if (p[k] > p[best]) best = k;
    return best;
}

static void normalize3(double *v)
{
    double n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (n > 0)
        for (int d = 0; d < 3; d++) v[d] /= n;
}

static double dot3(const double *a, const float *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* Area-weighted mean normal (normalized) of the faces with label k. */
static void mean_normal(const int *label, const float *area, const float *normal, int nf, int k, double *m)
{
    m[0] = m[1] = m[2] = 0;
    for (int f = 0; f < nf; f++)
        if (label[f] == k)
            for (int d = 0; d < 3; d++) m[d] += area[f] * normal[3 * f + d];
    normalize3(m);
}

/* 2-means on the unit normals of patch j's faces (cosine similarity, area
 * weights), started at c0 and c1; side[f] = 1 for faces nearer c1. */
static void two_means(const int *label, const float *area, const float *normal, int nf, int j, double *c0,
                      double *c1, unsigned char *side)
{
    for (int round = 0; round < 10; round++) {
        double s0[3] = {0, 0, 0}, s1[3] = {0, 0, 0};
        int changed = 0;
        for (int f = 0; f < nf; f++) {
            if (label[f] != j) continue;
            const float *n = normal + 3 * f;
            unsigned char s = dot3(c1, n) > dot3(c0, n);
            changed += s != side[f];
            side[f] = s;
            double *acc = s ? s1 : s0;
            for (int d = 0; d < 3; d++) acc[d] += area[f] * n[d];
        }
        normalize3(s0);
        normalize3(s1);
        for (int d = 0; d < 3; d++) { c0[d] = s0[d]; c1[d] = s1[d]; }
        if (round > 0 && !changed) break;
    }
}

void patchnet_split_empty(const float *P, const float *hidden, const diffusion_net_geometry *g, const float *area,
                          const float *normal, int K, int C, double empty_share, double gap, float *w, float *b,
                          patchnet_split *out)
{
    out->empty = -1;
    out->split = -1;
    out->moved_share = 0;
    int nf = g->nf;
    if (K < 2 || nf < 2) return;
    int *label = mem_alloc(sizeof(int) * (size_t)nf);
    double *won = mem_calloc((size_t)K, sizeof(double));
    double *err = mem_calloc((size_t)K, sizeof(double));
    double *half = mem_calloc(2 * (size_t)C, sizeof(double));
    unsigned char *side = mem_calloc((size_t)nf, 1);
    if (!label || !won || !err || !half || !side) goto done;
    double total = 0;
    for (int f = 0; f < nf; f++) {
        label[f] = argmax_row(P + (size_t)f * K, K);
        won[label[f]] += area[f];
        total += area[f];
    }
    int empty = -1;
    for (int k = 0; k < K; k++)
        if (won[k] < empty_share * total && (empty < 0 || won[k] < won[empty])) empty = k;
    if (empty < 0 || !(total > 0)) goto done;
    /* The worst-fitting patch, and its worst-fitting face. */
    int split = -1;
    double m[3];
    for (int k = 0; k < K; k++) {
        if (k == empty || won[k] <= 0) continue;
        mean_normal(label, area, normal, nf, k, m);
        for (int f = 0; f < nf; f++)
            if (label[f] == k) err[k] += area[f] * (1.0 - dot3(m, normal + 3 * f));
        if (split < 0 || err[k] > err[split]) split = k;
    }
    if (split < 0 || !(err[split] > 0)) goto done;
    /* The two halves start on either side of the principal axis of the
     * patch's normals about their mean (the direction they spread most). */
    double mean[3] = {0, 0, 0}, cov[9] = {0}, wsum = 0, axis[3] = {0, 0, 0}, far = -1;
    for (int f = 0; f < nf; f++)
        if (label[f] == split) {
            for (int d = 0; d < 3; d++) mean[d] += area[f] * normal[3 * f + d];
            wsum += area[f];
        }
    for (int d = 0; d < 3; d++) mean[d] /= wsum;
    for (int f = 0; f < nf; f++) {
        if (label[f] != split) continue;
        double e[3];
        for (int d = 0; d < 3; d++) e[d] = normal[3 * f + d] - mean[d];
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++) cov[3 * r + c] += area[f] * e[r] * e[c];
        double q = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
        if (q > far) { far = q; for (int d = 0; d < 3; d++) axis[d] = e[d]; }
    }
    for (int round = 0; round < 50; round++) { /* power iteration from the farthest deviation */
        double next[3];
        for (int r = 0; r < 3; r++) next[r] = cov[3 * r] * axis[0] + cov[3 * r + 1] * axis[1] + cov[3 * r + 2] * axis[2];
        normalize3(next);
        for (int d = 0; d < 3; d++) axis[d] = next[d];
    }
    double c0[3] = {0, 0, 0}, c1[3] = {0, 0, 0};
    for (int f = 0; f < nf; f++) {
        if (label[f] != split) continue;
        double t = 0;
        for (int d = 0; d < 3; d++) t += (normal[3 * f + d] - mean[d]) * axis[d];
        double *c = t > 0 ? c1 : c0;
        for (int d = 0; d < 3; d++) c[d] += area[f] * normal[3 * f + d];
    }
    normalize3(c0);
    normalize3(c1);
    two_means(label, area, normal, nf, split, c0, c1, side);
    /* Area-weighted means of the face hidden features (a face's is the mean
     * of its corners') over the two halves. */
    double wside[2] = {0, 0};
    for (int f = 0; f < nf; f++) {
        if (label[f] != split) continue;
        int s = side[f];
        wside[s] += area[f];
        for (int c = 0; c < 3; c++) {
            const float *h = hidden + (size_t)g->face_vertex[c * nf + f] * C;
            for (int i = 0; i < C; i++) half[s * C + i] += area[f] / 3.0 * h[i];
        }
    }
    if (!(wside[0] > 0) || !(wside[1] > 0)) goto done;
    double dd = 0;
    for (int i = 0; i < C; i++) {
        half[i] /= wside[0];
        half[C + i] /= wside[1];
        double d = half[C + i] - half[i];
        dd += d * d;
    }
    if (!(dd > 1e-12)) goto done;
    double alpha = gap / dd, shift = 0;
    for (int i = 0; i < C; i++) {
        double d = alpha * (half[C + i] - half[i]);
        shift += d * 0.5 * (half[C + i] + half[i]);
        w[(size_t)i * K + empty] = (float)(w[(size_t)i * K + split] + d);
        w[(size_t)i * K + split] = (float)(w[(size_t)i * K + split] - d);
    }
    b[empty] = (float)(b[split] - shift);
    b[split] = (float)(b[split] + shift);
    out->empty = empty;
    out->split = split;
    out->moved_share = wside[1] / total;
done:
    mem_free(label);
    mem_free(won);
    mem_free(err);
    mem_free(half);
    mem_free(side);
}
