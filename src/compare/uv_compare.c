#include "compare/uv_compare.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "atlas/uv_charts.h"
#include "charts/charts.h"
#include "core/error.h"
#include "core/mem.h"
#include "mesh/edge_map.h"
#include "spatial/bvh.h"
#include "spatial/triangle_closest_point.h"

/* Barycentric weights below this count as zero: the point is on an edge
 * or a vertex of the face, shared with its neighbours. */
#define ON_EDGE 1e-9

static int cmp_double(const void *x, const void *y)
{
    double a = *(const double *)x, b = *(const double *)y;
    return a < b ? -1 : a > b;
}

static double uv_dist_in_face(const neuv_mesh *a, int f, const double w[3], const double uv[2])
{
    double s = 0;
    for (int i = 0; i < 2; i++) {
        double x = 0;
        for (int k = 0; k < 3; k++) x += w[k] * a->uv[2 * (size_t)a->tri_uv[3 * f + k] + i];
        s += (x - uv[i]) * (x - uv[i]);
    }
    return sqrt(s);
}

/* Smallest UV distance among the A faces holding the closest point found
 * in face f with weights w (see the header on seams). */
static double uv_distance_at(const neuv_mesh *a, const int *vf_start, const int *vf, int f, const double w[3],
                             const double p[3], double d2, const double uv[2], const int *chart_a, int only)
{
    double best = only < 0 || chart_a[f] == only ? uv_dist_in_face(a, f, w, uv) : INFINITY;
    int on = 0, keep[3], nk = 0;
    for (int k = 0; k < 3; k++) {
        if (w[k] < ON_EDGE) on = 1;
        else keep[nk++] = a->tri[3 * f + k];
    }
    if (!on || nk == 0) return best;
    /* Candidates: faces around the first kept vertex that hold all kept vertices. */
    for (int j = vf_start[keep[0]]; j < vf_start[keep[0] + 1]; j++) {
        int g = vf[j];
        if (g == f || (only >= 0 && chart_a[g] != only)) continue;
        int all = 1;
        for (int i = 1; i < nk; i++) {
            int has = 0;
            for (int k = 0; k < 3; k++) has |= a->tri[3 * g + k] == keep[i];
            all &= has;
        }
        if (!all) continue;
        const int *t = a->tri + 3 * (size_t)g;
        double wg[3];
        double dg = triangle_closest_point(a->pos + 3 * (size_t)t[0], a->pos + 3 * (size_t)t[1], a->pos + 3 * (size_t)t[2], p, wg);
        if (dg > d2 + 1e-12 * (1 + d2)) continue;
        double d = uv_dist_in_face(a, g, wg, uv);
        if (d < best) best = d;
    }
    return best;
}

/* UV distance of the corners whose matched A chart does not hold their
 * closest point (they lie past that chart's seam): per chart, the closest
 * point of the chart itself, its face's UV map extended linearly there
 * (plane barycentric weights), the distance to B's UV. */
static neuv_status across_seam_distances(const neuv_mesh *a, const int *chart_a, int n_charts_a, int n,
                                         const int *chart_of, const double *pts, const double *uvb,
                                         const int *wu, double *dist)
{
    neuv_status st = NEUV_OK;
    int *idx = mem_alloc(sizeof(int) * (size_t)(n > 0 ? n : 1));
    double *q = mem_alloc(sizeof(double) * 3 * (size_t)(n > 0 ? n : 1));
    int *face = mem_alloc(sizeof(int) * (size_t)(n > 0 ? n : 1));
    if (!idx || !q || !face) { mem_free(idx); mem_free(q); mem_free(face); return error_nomem("UV comparison"); }
    for (int c = 0; c < n_charts_a && st == NEUV_OK; c++) {
        int k = 0;
        for (int w = 0; w < n; w++)
            if (chart_of[w] == c && isinf(dist[w])) {
                idx[k] = w;
                memcpy(q + 3 * (size_t)k, pts + 3 * (size_t)w, sizeof(double) * 3);
                k++;
            }
        if (k == 0) continue;
        neuv_mesh *sub = NULL;
        int *vmap = NULL, *fmap = NULL;
        bvh tree;
        memset(&tree, 0, sizeof tree);
        if ((st = chart_submesh(a, chart_a, c, &sub, &vmap, &fmap)) == NEUV_OK && (st = bvh_build(&tree, sub)) == NEUV_OK) {
            bvh_closest_points(&tree, k, q, face, NULL, NULL);
            for (int i = 0; i < k; i++) {
                const int *t = sub->tri + 3 * (size_t)face[i];
                double wt[3];
                triangle_barycentric(sub->pos + 3 * (size_t)t[0], sub->pos + 3 * (size_t)t[1], sub->pos + 3 * (size_t)t[2],
                                     q + 3 * (size_t)i, wt);
                dist[idx[i]] = uv_dist_in_face(a, fmap[face[i]], wt, uvb + 2 * (size_t)wu[idx[i]]);
            }
        }
        bvh_free(&tree);
        mesh_free(sub); mem_free(vmap); mem_free(fmap);
    }
    mem_free(idx); mem_free(q); mem_free(face);
    return st;
}

static void summarize(double *dist, int n, double *mean, double *p95, double *max)
{
    /* Summed in one order, so the mean does not depend on the threads. */
    double sum = 0;
    for (int w = 0; w < n; w++) sum += dist[w];
    qsort(dist, (size_t)n, sizeof(double), cmp_double);
    *mean = sum / n;
    *max = dist[n - 1];
    /* p95 by linear interpolation between order statistics. */
    double rank = 0.95 * (n - 1);
    int lo = (int)floor(rank);
    *p95 = lo + 1 < n ? dist[lo] + (rank - lo) * (dist[lo + 1] - dist[lo]) : dist[lo];
}

/* Chart agreement of B with A given the A chart under each B face
 * (label): each B chart is matched to the A chart holding most of its area
 * (ties: the smaller A chart id), best_a (#B charts) gets the match, and
 * *area / *faces the share of B's area / faces whose label is their
 * chart's match. Returns 0, or -1 on no memory. */
static int chart_agreement(const neuv_mesh *b, const int *chart_b, int ncbch, const int *label, int *best_a,
                           double *area_share, double *face_share)
{
    edge_map pairs;
    double *pair_area = mem_alloc(sizeof(double) * (size_t)(b->nf > 0 ? b->nf : 1));
    double *best_area = mem_alloc(sizeof(double) * (size_t)(ncbch > 0 ? ncbch : 1));
    int ok = pair_area && best_area && edge_map_init(&pairs, (size_t)b->nf / 4 + 16) == 0;
    if (!ok) { mem_free(pair_area); mem_free(best_area); return -1; }
    /* Area of B chart cb under A chart ca, one slot per pair met. */
    int npairs = 0;
    double total = 0;
    for (int f = 0; f < b->nf && ok; f++) {
        int inserted;
        int *slot = edge_map_slot(&pairs, chart_b[f], label[f], npairs, &inserted);
        if (!slot) { ok = 0; break; }
        if (inserted) pair_area[npairs++] = 0;
        double ar = mesh_face_area(b, f);
        pair_area[*slot] += ar;
        total += ar;
    }
    if (ok) {
        for (int c = 0; c < ncbch; c++) { best_a[c] = -1; best_area[c] = -1; }
        for (int f = 0; f < b->nf; f++) {
            int cb = chart_b[f], ca = label[f];
            double ar = pair_area[edge_map_get(&pairs, cb, ca)];
            if (ar > best_area[cb] || (ar == best_area[cb] && ca < best_a[cb])) { best_area[cb] = ar; best_a[cb] = ca; }
        }
        double agree_area = 0;
        int agree_faces = 0;
        for (int f = 0; f < b->nf; f++)
            if (label[f] == best_a[chart_b[f]]) { agree_area += mesh_face_area(b, f); agree_faces++; }
        *area_share = total > 0 ? agree_area / total : (double)agree_faces / b->nf;
        *face_share = (double)agree_faces / b->nf;
    }
    edge_map_free(&pairs);
    mem_free(pair_area); mem_free(best_area);
    return ok ? 0 : -1;
}

neuv_status uv_compare(const neuv_mesh *a, const neuv_mesh *b, uv_compare_result *res)
{
    memset(res, 0, sizeof *res);
    if (a->nf <= 0 || b->nf <= 0) return error_set(NEUV_ERR_INPUT, "both meshes need faces to compare UVs");
    if (a->nuv <= 0 || !a->tri_uv) return error_set(NEUV_ERR_INPUT, "the first mesh has no UVs");
    if (b->nuv <= 0 || !b->tri_uv) return error_set(NEUV_ERR_INPUT, "the second mesh has no UVs");
    size_t ncb = (size_t)b->nf * 3;
    neuv_status st = NEUV_OK;
    bvh tree;
    memset(&tree, 0, sizeof tree);
    edge_map wedges;
    int wedges_ok = edge_map_init(&wedges, ncb) == 0;
    int *wv = mem_alloc(sizeof(int) * ncb), *wu = mem_alloc(sizeof(int) * ncb), *wchart = mem_alloc(sizeof(int) * ncb);
    int *vf_start = mem_calloc((size_t)a->nv + 1, sizeof(int)), *vf = mem_alloc(sizeof(int) * 3 * (size_t)a->nf);
    int *chart_a = mem_alloc(sizeof(int) * (size_t)a->nf), *chart_b = mem_alloc(sizeof(int) * (size_t)b->nf);
    double *pts = mem_alloc(sizeof(double) * 3 * (ncb > (size_t)b->nf ? ncb : (size_t)b->nf));
    double *bary = mem_alloc(sizeof(double) * 3 * ncb), *d2 = mem_alloc(sizeof(double) * ncb), *dist = NULL, *dist_any = NULL;
    int *face = mem_alloc(sizeof(int) * ncb);
    int *best_a = NULL;
    if (!wedges_ok || !wv || !wu || !wchart || !vf_start || !vf || !chart_a || !chart_b || !pts || !bary ||
        !d2 || !face)
        goto nomem;
    if ((st = bvh_build(&tree, a))) goto done;
    for (size_t c = 0; c < (size_t)a->nf * 3; c++) vf_start[a->tri[c] + 1]++;
    for (int v = 0; v < a->nv; v++) vf_start[v + 1] += vf_start[v];
    for (size_t c = 0; c < (size_t)a->nf * 3; c++) vf[vf_start[a->tri[c]]++] = (int)(c / 3);
    for (int v = a->nv; v > 0; v--) vf_start[v] = vf_start[v - 1];
    vf_start[0] = 0;

    /* Chart agreement. */
    int nca = uv_charts(a, chart_a), ncbch = uv_charts(b, chart_b);
    if (nca < 0 || ncbch < 0) goto nomem;
    res->charts_a = nca; res->charts_b = ncbch;
    for (int f = 0; f < b->nf; f++) {
        const int *t = b->tri + 3 * (size_t)f;
        for (int i = 0; i < 3; i++)
            pts[3 * (size_t)f + i] = (b->pos[3 * (size_t)t[0] + i] + b->pos[3 * (size_t)t[1] + i] + b->pos[3 * (size_t)t[2] + i]) / 3;
    }
    bvh_closest_points(&tree, b->nf, pts, face, NULL, NULL);
    best_a = mem_alloc(sizeof(int) * (size_t)ncbch);
    int *label = mem_alloc(sizeof(int) * (size_t)b->nf), *best_facing = mem_alloc(sizeof(int) * (size_t)ncbch);
    if (!best_a || !label || !best_facing) { mem_free(label); mem_free(best_facing); goto nomem; }
    for (int f = 0; f < b->nf; f++) label[f] = chart_a[face[f]];
    int ag = chart_agreement(b, chart_b, ncbch, label, best_a, &res->chart_agreement, &res->chart_agreement_faces);
    /* Again with the closest point facing the same way as the B face. */
#pragma omp parallel for schedule(dynamic, 256)
    for (int f = 0; f < b->nf; f++) {
        double n[3];
        mesh_face_normal(b, f, n);
        int af;
        bvh_closest_point_facing(&tree, pts + 3 * (size_t)f, n, &af, NULL, NULL);
        label[f] = chart_a[af];
    }
    double facing_faces;
    if (ag == 0) ag = chart_agreement(b, chart_b, ncbch, label, best_facing, &res->chart_agreement_facing, &facing_faces);
    mem_free(label); mem_free(best_facing);
    if (ag != 0) goto nomem;
    res->faces_a = a->nf;
    res->faces_b = b->nf;

    /* UV distance at every distinct (vertex, UV) corner of B, in the A chart
     * matched to the corner's B chart. */
    int nw = 0;
    for (size_t c = 0; c < ncb; c++) {
        int inserted;
        if (!edge_map_slot(&wedges, b->tri[c], b->tri_uv[c], nw, &inserted)) goto nomem;
        if (inserted) { wv[nw] = b->tri[c]; wu[nw] = b->tri_uv[c]; wchart[nw] = best_a[chart_b[c / 3]]; nw++; }
    }
    for (int w = 0; w < nw; w++) memcpy(pts + 3 * (size_t)w, b->pos + 3 * (size_t)wv[w], sizeof(double) * 3);
    bvh_closest_points(&tree, nw, pts, face, bary, d2);
    dist = mem_alloc(sizeof(double) * (size_t)(nw > 0 ? nw : 1));
    dist_any = mem_alloc(sizeof(double) * (size_t)(nw > 0 ? nw : 1));
    if (!dist || !dist_any) goto nomem;
#pragma omp parallel for schedule(dynamic, 256)
    for (int w = 0; w < nw; w++) {
        const double *wt = bary + 3 * (size_t)w, *p = pts + 3 * (size_t)w, *uv = b->uv + 2 * (size_t)wu[w];
        dist_any[w] = uv_distance_at(a, vf_start, vf, face[w], wt, p, d2[w], uv, chart_a, -1);
        dist[w] = uv_distance_at(a, vf_start, vf, face[w], wt, p, d2[w], uv, chart_a, wchart[w]);
    }
    int across = 0;
    for (int w = 0; w < nw; w++) across += isinf(dist[w]) != 0;
    if (across && (st = across_seam_distances(a, chart_a, nca, nw, wchart, pts, b->uv, wu, dist))) goto done;
    for (int w = 0; w < nw; w++) res->max_surface_distance = fmax(res->max_surface_distance, sqrt(d2[w]));
    /* Per B chart: which parts of the map are off. Each corner counts once,
     * for the chart of the first face using it (wv is not needed any more
     * and marks the corners counted). */
    {
        double *sum = mem_calloc((size_t)ncbch, sizeof(double));
        int *cnt = mem_calloc((size_t)ncbch, sizeof(int));
        if (!sum || !cnt) { mem_free(sum); mem_free(cnt); goto nomem; }
        for (int f = 0; f < b->nf; f++)
            for (int k = 0; k < 3; k++) {
                int w = edge_map_get(&wedges, b->tri[3 * f + k], b->tri_uv[3 * f + k]);
                if (w < 0 || wv[w] < 0) continue;
                sum[chart_b[f]] += dist[w];
                cnt[chart_b[f]]++;
                wv[w] = -1; /* counted once */
            }
        for (int i = 0; i < UV_COMPARE_WORST; i++) { res->worst_chart[i] = res->worst_match[i] = -1; }
        for (int c = 0; c < ncbch; c++) {
            if (!cnt[c]) continue;
            double mean = sum[c] / cnt[c];
            for (int i = 0; i < UV_COMPARE_WORST; i++)
                if (res->worst_chart[i] < 0 || mean > res->worst_mean[i]) {
                    for (int j = UV_COMPARE_WORST - 1; j > i; j--) {
                        res->worst_chart[j] = res->worst_chart[j - 1]; res->worst_match[j] = res->worst_match[j - 1];
                        res->worst_corners[j] = res->worst_corners[j - 1]; res->worst_mean[j] = res->worst_mean[j - 1];
                    }
                    res->worst_chart[i] = c; res->worst_match[i] = best_a[c];
                    res->worst_corners[i] = cnt[c]; res->worst_mean[i] = mean;
                    break;
                }
        }
        mem_free(sum); mem_free(cnt);
    }
    res->vertices_compared = nw;
    res->across_seam = (double)across / nw;
    summarize(dist, nw, &res->uv_mean, &res->uv_p95, &res->uv_max);
    summarize(dist_any, nw, &res->nearest_mean, &res->nearest_p95, &res->nearest_max);
    goto done;
nomem:
    st = error_set(NEUV_ERR_NOMEM, "out of memory comparing UV maps");
done:
    if (wedges_ok) edge_map_free(&wedges);
    mem_free(wv); mem_free(wu); mem_free(wchart); mem_free(vf_start); mem_free(vf); mem_free(chart_a); mem_free(chart_b); mem_free(pts);
    mem_free(bary); mem_free(d2); mem_free(dist); mem_free(dist_any); mem_free(face); mem_free(best_a);
    bvh_free(&tree);
    return st;
}
