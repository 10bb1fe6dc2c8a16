#include "spatial/bvh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/mem.h"
#include "spatial/triangle_closest_point.h"

/* Faces per leaf: small leaves keep the triangle tests few per query. */
#define BVH_LEAF 4
/* A traversal stack holds at most one pending sibling per level plus the
 * node in hand; the build caps the depth below this. */
#define BVH_STACK 128
#define BVH_SAH_DEPTH 64

void bvh_free(bvh *b)
{
    mem_free(b->nodes); mem_free(b->face); mem_free(b->corner);
    memset(b, 0, sizeof *b);
}

/* Orders faces by centroid along `axis`, ties by face id, so the split is
 * the same on every machine whatever the quickselect path. */
static int face_less(const double *cen, int axis, int f, int g)
{
    double x = cen[3 * f + axis], y = cen[3 * g + axis];
    return x < y || (x == y && f < g);
}

/* Partially orders ids[0..n) so ids[k] is the k-th smallest and everything
 * before it is not larger (Hoare quickselect, median-of-three pivots). */
static void select_kth(int *ids, int n, int k, const double *cen, int axis)
{
    int lo = 0, hi = n - 1;
    while (hi > lo) {
        int mid = lo + (hi - lo) / 2;
        int a = ids[lo], b = ids[mid], c = ids[hi], piv;
        if (face_less(cen, axis, a, b)) piv = face_less(cen, axis, b, c) ? b : (face_less(cen, axis, a, c) ? c : a);
        else piv = face_less(cen, axis, a, c) ? a : (face_less(cen, axis, b, c) ? c : b);
        int i = lo, j = hi;
        while (i <= j) {
            while (face_less(cen, axis, ids[i], piv)) i++;
            while (face_less(cen, axis, piv, ids[j])) j--;
            if (i <= j) { int t = ids[i]; ids[i] = ids[j]; ids[j] = t; i++; j--; }
        }
        if (k <= j) hi = j;
        else if (k >= i) lo = i;
        else return;
    }
}

/* Binned surface-area heuristic (Wald, "On fast construction of SAH-based
 * bounding volume hierarchies", 2007): the plane between centroid bins
 * that minimizes area(left) * #left + area(right) * #right. Reorders ids
 * so the left side comes first and returns its size (0: no plane found). */
#define BVH_BINS 16
static double box_area(const double lo[3], const double hi[3])
{
    double d[3] = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
    return 2 * (d[0] * d[1] + d[1] * d[2] + d[2] * d[0]);
}

static int bin_of(double x, double lo, double ext)
{
    int k = (int)((x - lo) / ext * BVH_BINS);
    return k < 0 ? 0 : k >= BVH_BINS ? BVH_BINS - 1 : k;
}

static int sah_split(int *ids, int n, const double *cen, const double *flo, const double *fhi, const double clo[3],
                     const double chi[3])
{
    double best = INFINITY;
    int best_axis = -1, best_bin = 0;
    for (int axis = 0; axis < 3; axis++) {
        double ext = chi[axis] - clo[axis];
        if (!(ext > 0)) continue;
        int cnt[BVH_BINS] = {0};
        double blo[BVH_BINS][3], bhi[BVH_BINS][3];
        for (int k = 0; k < BVH_BINS; k++)
            for (int i = 0; i < 3; i++) { blo[k][i] = INFINITY; bhi[k][i] = -INFINITY; }
        for (int j = 0; j < n; j++) {
            int f = ids[j], k = bin_of(cen[3 * f + axis], clo[axis], ext);
            cnt[k]++;
            for (int i = 0; i < 3; i++) {
                blo[k][i] = fmin(blo[k][i], flo[3 * f + i]);
                bhi[k][i] = fmax(bhi[k][i], fhi[3 * f + i]);
            }
        }
        /* Right-side areas and counts by suffix, then sweep from the left. */
        double rarea[BVH_BINS], rl[3] = {INFINITY, INFINITY, INFINITY}, rh[3] = {-INFINITY, -INFINITY, -INFINITY};
        int rcnt[BVH_BINS], rc = 0;
        for (int k = BVH_BINS - 1; k > 0; k--) {
            rc += cnt[k];
            for (int i = 0; i < 3; i++) { rl[i] = fmin(rl[i], blo[k][i]); rh[i] = fmax(rh[i], bhi[k][i]); }
            rcnt[k] = rc;
            rarea[k] = rc ? box_area(rl, rh) : 0;
        }
        double ll[3] = {INFINITY, INFINITY, INFINITY}, lh[3] = {-INFINITY, -INFINITY, -INFINITY};
        int lc = 0;
        for (int k = 1; k < BVH_BINS; k++) {
            lc += cnt[k - 1];
            for (int i = 0; i < 3; i++) { ll[i] = fmin(ll[i], blo[k - 1][i]); lh[i] = fmax(lh[i], bhi[k - 1][i]); }
            if (lc == 0 || rcnt[k] == 0) continue;
            double cost = box_area(ll, lh) * lc + rarea[k] * rcnt[k];
            if (cost < best) { best = cost; best_axis = axis; best_bin = k; }
        }
    }
    if (best_axis < 0) return 0;
    double ext = chi[best_axis] - clo[best_axis];
    int i = 0, j = n - 1;
    while (i <= j) {
        if (bin_of(cen[3 * ids[i] + best_axis], clo[best_axis], ext) < best_bin) i++;
        else { int t = ids[i]; ids[i] = ids[j]; ids[j] = t; j--; }
    }
    return i;
}

neuv_status bvh_build(bvh *b, const neuv_mesh *m)
{
    memset(b, 0, sizeof *b);
    if (m->nf <= 0) return error_set(NEUV_ERR_INPUT, "cannot build a BVH over a mesh without faces");
    int nf = m->nf;
    double *cen = mem_alloc(sizeof(double) * 3 * (size_t)nf);
    double *lo = mem_alloc(sizeof(double) * 3 * (size_t)nf), *hi = mem_alloc(sizeof(double) * 3 * (size_t)nf);
    int *stack = mem_alloc(sizeof(int) * 4 * (size_t)(2 * nf));
    b->nodes = mem_alloc(sizeof(bvh_node) * (size_t)(2 * nf));
    b->face = mem_alloc(sizeof(int) * (size_t)nf);
    b->corner = mem_alloc(sizeof(double) * 9 * (size_t)nf);
    if (!cen || !lo || !hi || !stack || !b->nodes || !b->face || !b->corner) {
        mem_free(cen); mem_free(lo); mem_free(hi); mem_free(stack); bvh_free(b);
        return error_set(NEUV_ERR_NOMEM, "out of memory building a BVH over %d faces", nf);
    }
    b->nf = nf;
    for (int f = 0; f < nf; f++) {
        b->face[f] = f;
        for (int i = 0; i < 3; i++) {
            double x0 = m->pos[3 * m->tri[3 * f] + i], x1 = m->pos[3 * m->tri[3 * f + 1] + i],
                   x2 = m->pos[3 * m->tri[3 * f + 2] + i];
            cen[3 * f + i] = (x0 + x1 + x2) / 3.0;
            lo[3 * f + i] = fmin(x0, fmin(x1, x2));
            hi[3 * f + i] = fmax(x0, fmax(x1, x2));
        }
    }
    /* Work list of (node, start, count); children are allocated in pairs. */
    int top = 0;
    b->nnodes = 1;
    stack[0] = 0; stack[1] = 0; stack[2] = nf; stack[3] = 0; top = 1;
    while (top > 0) {
        top--;
        int node = stack[4 * top], start = stack[4 * top + 1], count = stack[4 * top + 2], depth = stack[4 * top + 3];
        bvh_node *nd = &b->nodes[node];
        double clo[3] = {INFINITY, INFINITY, INFINITY}, chi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (int i = 0; i < 3; i++) { nd->lo[i] = INFINITY; nd->hi[i] = -INFINITY; }
        for (int j = start; j < start + count; j++) {
            int f = b->face[j];
            for (int i = 0; i < 3; i++) {
                nd->lo[i] = fmin(nd->lo[i], lo[3 * f + i]);
                nd->hi[i] = fmax(nd->hi[i], hi[3 * f + i]);
                clo[i] = fmin(clo[i], cen[3 * f + i]);
                chi[i] = fmax(chi[i], cen[3 * f + i]);
            }
        }
        nd->start = start; nd->count = count; nd->child = -1;
        if (count <= BVH_LEAF) continue;
        /* Past BVH_SAH_DEPTH only halving splits, so the depth (and the
         * query stack) stays below BVH_SAH_DEPTH + log2(F) + 1. */
        int half = depth < BVH_SAH_DEPTH ? sah_split(b->face + start, count, cen, lo, hi, clo, chi) : 0;
        if (half <= 0 || half >= count) {
            /* No useful SAH plane (coincident centroids): halve by count. */
            int axis = 0;
            for (int i = 1; i < 3; i++)
                if (chi[i] - clo[i] > chi[axis] - clo[axis]) axis = i;
            half = count / 2;
            select_kth(b->face + start, count, half, cen, axis);
        }
        int c = b->nnodes;
        b->nnodes += 2;
        nd->child = c;
        stack[4 * top] = c; stack[4 * top + 1] = start; stack[4 * top + 2] = half; stack[4 * top + 3] = depth + 1; top++;
        stack[4 * top] = c + 1; stack[4 * top + 1] = start + half; stack[4 * top + 2] = count - half;
        stack[4 * top + 3] = depth + 1; top++;
    }
    for (int j = 0; j < nf; j++) {
        int f = b->face[j];
        for (int k = 0; k < 3; k++)
            memcpy(b->corner + 9 * (size_t)j + 3 * k, m->pos + 3 * (size_t)m->tri[3 * f + k], sizeof(double) * 3);
    }
    mem_free(cen); mem_free(lo); mem_free(hi); mem_free(stack);
    return NEUV_OK;
}

/* Squared distance from p to the box (0 inside). */
static double box_dist2(const bvh_node *nd, const double p[3])
{
    double s = 0;
    for (int i = 0; i < 3; i++) {
        double d = p[i] < nd->lo[i] ? nd->lo[i] - p[i] : p[i] > nd->hi[i] ? p[i] - nd->hi[i] : 0;
        s += d * d;
    }
    return s;
}

/* 1 when triangle c (9 doubles) faces the same side as n (n NULL: always). */
static int facing(const double *c, const double *n)
{
    if (!n) return 1;
    double e0[3], e1[3];
    for (int q = 0; q < 3; q++) { e0[q] = c[3 + q] - c[q]; e1[q] = c[6 + q] - c[q]; }
    double x = e0[1] * e1[2] - e0[2] * e1[1], y = e0[2] * e1[0] - e0[0] * e1[2], z = e0[0] * e1[1] - e0[1] * e1[0];
    return x * n[0] + y * n[1] + z * n[2] > 0;
}

static int closest_point_filtered(const bvh *b, const double point[3], const double *normal, int *face, double bary[3],
                                  double *dist2);

void bvh_closest_point(const bvh *b, const double point[3], int *face, double bary[3], double *dist2)
{
    closest_point_filtered(b, point, NULL, face, bary, dist2);
}

void bvh_closest_point_facing(const bvh *b, const double point[3], const double normal[3], int *face, double bary[3],
                              double *dist2)
{
    if (!closest_point_filtered(b, point, normal, face, bary, dist2)) /* nothing faces that way */
        closest_point_filtered(b, point, NULL, face, bary, dist2);
}

/* Returns 0 when no triangle passed the filter (outputs then untouched). */
static int closest_point_filtered(const bvh *b, const double point[3], const double *normal, int *face, double bary[3],
                                  double *dist2)
{
    double best = INFINITY, best_bary[3] = {1, 0, 0};
    int best_j = 0;
    int stack[BVH_STACK], top = 0;
    double sdist[BVH_STACK];
    stack[top] = 0; sdist[top] = box_dist2(&b->nodes[0], point); top++;
    while (top > 0) {
        top--;
        if (sdist[top] > best) continue;
        const bvh_node *nd = &b->nodes[stack[top]];
        if (nd->child < 0) {
            for (int j = nd->start; j < nd->start + nd->count; j++) {
                const double *c = b->corner + 9 * (size_t)j;
                if (!facing(c, normal)) continue;
                double w[3];
                double d = triangle_closest_point(c, c + 3, c + 6, point, w);
                if (d < best) {
                    best = d; best_j = j;
                    best_bary[0] = w[0]; best_bary[1] = w[1]; best_bary[2] = w[2];
                }
            }
            continue;
        }
        /* Visit the nearer child first so `best` shrinks early. */
        int c0 = nd->child, c1 = nd->child + 1;
        double d0 = box_dist2(&b->nodes[c0], point), d1 = box_dist2(&b->nodes[c1], point);
        if (d0 > d1) { int t = c0; c0 = c1; c1 = t; double td = d0; d0 = d1; d1 = td; }
        if (d1 <= best) { stack[top] = c1; sdist[top] = d1; top++; }
        if (d0 <= best) { stack[top] = c0; sdist[top] = d0; top++; }
    }
    if (best == INFINITY && normal) return 0;
    if (face) *face = b->face[best_j];
    if (bary) { bary[0] = best_bary[0]; bary[1] = best_bary[1]; bary[2] = best_bary[2]; }
    if (dist2) *dist2 = best;
    return 1;
}

void bvh_closest_points(const bvh *b, int n, const double *points, int *face, double *bary, double *dist2)
{
#pragma omp parallel for schedule(dynamic, 256)
    for (int i = 0; i < n; i++)
        bvh_closest_point(b, points + 3 * (size_t)i, face ? face + i : NULL, bary ? bary + 3 * (size_t)i : NULL,
                          dist2 ? dist2 + i : NULL);
}
