/* A saved model applied to another triangulation (unwrap_apply.h). */
#include "unwrap/unwrap_apply.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "atlas/footprint.h"
#include "atlas/occupancy.h"
#include "charts/charts.h"
#include "charts/face_graph.h"
#include "core/error.h"
#include "core/log.h"
#include "core/mem.h"
#include "core/timer.h"
#include "core/union_find.h"
#include "flatten/harmonic.h"
#include "flatten/lscm.h"
#include "flatten/uv_refine.h"
#include "geometry/operator_cache.h"
#include "mesh/edge_map.h"
#include "metrics/chart_uv_check.h"
#include "metrics/uv_overlap.h"
#include "nn/nn.h"
#include "remesh/simplify.h"
#include "spatial/bvh.h"
#include "spatial/triangle_closest_point.h"
#include "unwrap/unwrap_internal.h"
#include "unwrap/uv_pull_ease.h"

/* Resolution of the atlas overlap test: the one of the overlap metric. */
#define OVERLAP_RESOLUTION 2048
#define MAX_SHRINK_ROUNDS 25
#define SHRINK_STEP 0.98
/* Then, for a chart still overlapping, larger steps down to 0.06 of its
 * size, as long as no corner ends farther than LATE_SHRINK_MAX_SHIFT (of
 * the atlas side, the p95 bound of issue 15) from where the source put it:
 * beyond that a chart shrunk in place is no nearer its texture than one
 * moved to the nearest free place. */
#define MAX_LATE_SHRINK_ROUNDS 8
#define LATE_SHRINK_STEP 0.75
#define LATE_SHRINK_MAX_SHIFT 0.01

/* ---- charts by closest point ------------------------------------------ */

/* Each face takes the chart most of four of its points lie on (closest
 * source face of the centroid and of the points (2/3, 1/6, 1/6) toward each
 * corner; ties go to the centroid's). One point is not enough on a coarse
 * mesh: a long triangle cutting a curved region has its centroid nearer
 * the chart next door.
 * Outputs: face_chart (#F, model chart ids), src_face (#F, under the centroid),
 * centroid_chart (#F, or NULL for none: the chart under the centroid when
 * the closest point facing the same way and the plain closest point agree
 * on it, else -1: where they differ the surface is thin or two sheets touch),
 * vertex_chart (#V, the model chart under each vertex), *max_dist. */
static neuv_status transfer_charts(const neuv_mesh *m, const unwrap_model *md, int *face_chart, int *src_face,
                                   int *centroid_chart, int *vertex_chart, double *max_dist)
{
    bvh b;
    neuv_status s = bvh_build(&b, md->source);
    if (s) return s;
    size_t np = 4 * (size_t)m->nf > (size_t)m->nv ? 4 * (size_t)m->nf : (size_t)m->nv;
    double *pt = mem_alloc(sizeof(double) * 3 * np);
    double *d2 = mem_alloc(sizeof(double) * np);
    int *sf = mem_alloc(sizeof(int) * np);
    double *fn = mem_alloc(sizeof(double) * 3 * (size_t)(m->nf > 0 ? m->nf : 1));
    double *vn = mem_calloc(3 * (size_t)(m->nv > 0 ? m->nv : 1), sizeof(double));
    if (!pt || !d2 || !sf || !fn || !vn) {
        mem_free(pt); mem_free(d2); mem_free(sf); mem_free(fn); mem_free(vn); bvh_free(&b);
        return error_nomem("chart transfer");
    }
    /* Face normals (area-weighted) and vertex normals: each point looks for
     * the closest source face on its own side of the surface. */
    for (int f = 0; f < m->nf; f++) {
        const double *a = m->pos + 3 * m->tri[3 * f], *bq = m->pos + 3 * m->tri[3 * f + 1], *c = m->pos + 3 * m->tri[3 * f + 2];
        double e0[3] = {bq[0] - a[0], bq[1] - a[1], bq[2] - a[2]}, e1[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double *n = fn + 3 * (size_t)f;
        n[0] = e0[1] * e1[2] - e0[2] * e1[1];
        n[1] = e0[2] * e1[0] - e0[0] * e1[2];
        n[2] = e0[0] * e1[1] - e0[1] * e1[0];
        for (int k = 0; k < 3; k++)
            for (int q = 0; q < 3; q++) vn[3 * (size_t)m->tri[3 * f + k] + q] += n[q];
    }
    static const double w[4][3] = {{1.0 / 3, 1.0 / 3, 1.0 / 3}, {2.0 / 3, 1.0 / 6, 1.0 / 6},
                                   {1.0 / 6, 2.0 / 3, 1.0 / 6}, {1.0 / 6, 1.0 / 6, 2.0 / 3}};
    for (int f = 0; f < m->nf; f++) {
        const int *t = m->tri + 3 * f;
        for (int j = 0; j < 4; j++)
            for (int q = 0; q < 3; q++)
                pt[3 * (4 * (size_t)f + j) + q] =
                    w[j][0] * m->pos[3 * t[0] + q] + w[j][1] * m->pos[3 * t[1] + q] + w[j][2] * m->pos[3 * t[2] + q];
    }
#pragma omp parallel for schedule(dynamic, 256)
    for (int i = 0; i < 4 * m->nf; i++)
        bvh_closest_point_facing(&b, pt + 3 * (size_t)i, fn + 3 * (size_t)(i / 4), sf + i, NULL, d2 + i);
    double worst = 0;
    for (int f = 0; f < m->nf; f++) {
        int lab[4], best = md->face_chart[sf[4 * (size_t)f]], best_n = 0;
        for (int j = 0; j < 4; j++) lab[j] = md->face_chart[sf[4 * (size_t)f + j]];
        for (int j = 0; j < 4; j++) {
            int n = 0;
            for (int k = 0; k < 4; k++) n += lab[k] == lab[j];
            if (n > best_n) { best_n = n; best = lab[j]; }
        }
        if (best_n <= 2 && lab[0] != best) { /* a 2-2 tie: the centroid's */
            int n0 = 0;
            for (int k = 0; k < 4; k++) n0 += lab[k] == lab[0];
            if (n0 == best_n) best = lab[0];
        }
        face_chart[f] = best;
        src_face[f] = sf[4 * (size_t)f];
        if (d2[4 * (size_t)f] > worst) worst = d2[4 * (size_t)f];
    }
    *max_dist = sqrt(worst);
    if (centroid_chart) {
        for (int f = 0; f < m->nf; f++) memmove(pt + 3 * (size_t)f, pt + 3 * (4 * (size_t)f), sizeof(double) * 3);
        bvh_closest_points(&b, m->nf, pt, sf, NULL, NULL);
        for (int f = 0; f < m->nf; f++) {
            int c = md->face_chart[src_face[f]];
            centroid_chart[f] = md->face_chart[sf[f]] == c ? c : -1;
        }
    }
#pragma omp parallel for schedule(dynamic, 256)
    for (int v = 0; v < m->nv; v++) bvh_closest_point_facing(&b, m->pos + 3 * (size_t)v, vn + 3 * (size_t)v, sf + v, NULL, NULL);
    for (int v = 0; v < m->nv; v++) vertex_chart[v] = md->face_chart[sf[v]];
    mem_free(pt); mem_free(d2); mem_free(sf); mem_free(fn); mem_free(vn);
    bvh_free(&b);
    return NEUV_OK;
}

/* Edge-connected pieces of equal label: piece (#F) gets a dense id per
 * piece, numbered in order of each piece's first face. The border zigzag
 * of a coarser or finer triangulation can cut a few faces of a chart off
 * from the rest; they keep their chart's map as a chart of their own
 * (merged into a neighbour, their texture would come from the neighbour's
 * map). Returns the number of pieces, or -1 on no memory. */
static int label_pieces(const face_graph *g, const int *label, int *piece)
{
    union_find u;
    if (uf_init(&u, g->nf)) return -1;
    for (int f = 0; f < g->nf; f++)
        for (int k = 0; k < 3; k++) {
            int h = g->adj[3 * f + k];
            if (h >= 0 && label[h] == label[f]) uf_union(&u, f, h);
        }
    int n = uf_labels(&u, piece);
    uf_free(&u);
    return n;
}

/* Pieces of a chart cut off from its largest piece (the border zigzag of a
 * coarser or finer triangulation can isolate a few faces) are merged into
 * the neighbouring chart they share the longest border with, smallest
 * first, until every such piece is merged (or has no other chart around
 * it). With centroid_chart (NULL where the atlas is packed afresh, as for
 * a simplified copy's model), a piece is kept instead, as a chart of its
 * own, when no face of it lies surely over another chart and over half its
 * area lies surely over its own (centroid_chart: -1 where the facing and
 * the plain closest point disagree), and it borders more than one other
 * chart or the mesh's border (inside a single chart it would make a hole in
 * it): its chart's map takes it inside the chart's island, where merged,
 * its texture would come from the neighbour's map. A piece once kept stays
 * kept when a merged face joins it. Returns the number merged, or -1 on no
 * memory. */
static int merge_fragments(const face_graph *g, const int *centroid_chart, int *face_chart, int n_labels)
{
    int nf = g->nf, merged = 0;
    int *comp = mem_alloc(sizeof(int) * (size_t)nf);
    double *carea = mem_alloc(sizeof(double) * (size_t)nf), *sure = mem_alloc(sizeof(double) * (size_t)nf);
    int *best = mem_alloc(sizeof(int) * (size_t)n_labels);
    double *share = mem_calloc((size_t)n_labels, sizeof(double));
    int *order = mem_alloc(sizeof(int) * (size_t)nf);
    /* keep: per piece, kept as a chart of its own; kept: per face, in a piece kept in an earlier round. */
    unsigned char *keep = mem_alloc((size_t)(nf > 0 ? nf : 1)), *multi = mem_alloc((size_t)(nf > 0 ? nf : 1));
    int *nb = mem_alloc(sizeof(int) * (size_t)(nf > 0 ? nf : 1));
    unsigned char *kept = mem_calloc((size_t)(nf > 0 ? nf : 1), 1);
    if (!kept || !comp || !carea || !sure || !best || !share || !order || !keep || !multi || !nb) {
        mem_free(comp); mem_free(carea); mem_free(sure); mem_free(best); mem_free(share); mem_free(order);
        mem_free(keep); mem_free(multi); mem_free(nb); mem_free(kept);
        return -1;
    }
    for (int round = 0; round < 8; round++) {
        int nc = label_pieces(g, face_chart, comp);
        if (nc < 0) { merged = -1; break; }
        for (int c = 0; c < nc; c++) { carea[c] = 0; sure[c] = 0; keep[c] = centroid_chart != NULL; }
        /* nb: the one other label around each piece so far (-1: none yet), multi: more than one, or a mesh border. */
        for (int c = 0; c < nc; c++) { nb[c] = -1; multi[c] = 0; }
        for (int f = 0; f < nf; f++) {
            int c = comp[f];
            carea[c] += g->area[f];
            if (!centroid_chart) continue;
            if (centroid_chart[f] == face_chart[f]) sure[c] += g->area[f];
            else if (centroid_chart[f] >= 0) keep[c] = 0; /* surely over another chart */
            for (int k = 0; k < 3; k++) {
                int h = g->adj[3 * f + k], l = h >= 0 ? face_chart[h] : -1;
                if (h >= 0 && l == face_chart[f]) continue;
                if (h < 0 || (nb[c] >= 0 && nb[c] != l)) multi[c] = 1;
                else nb[c] = l;
            }
        }
        for (int c = 0; c < nc; c++) keep[c] = keep[c] && multi[c] && sure[c] > 0.5 * carea[c];
        /* Once kept, kept: a face merged next to a kept piece does not undo it. */
        for (int f = 0; f < nf; f++)
            if (kept[f]) keep[comp[f]] = 1;
        for (int f = 0; f < nf; f++) kept[f] = keep[comp[f]];
        for (int l = 0; l < n_labels; l++) best[l] = -1;
        for (int c = 0; c < nc; c++) order[c] = -1;
        for (int f = 0; f < nf; f++) { /* largest piece of each label */
            int l = face_chart[f], c = comp[f];
            if (best[l] < 0 || carea[c] > carea[best[l]] || (carea[c] == carea[best[l]] && c < best[l])) best[l] = c;
        }
        /* Fragments, smallest first (by area; ties by id): a selection by repeated scans is enough,
         * there are few. */
        int n_frag = 0;
        for (int f = 0; f < nf; f++) {
            int c = comp[f];
            if (c != best[face_chart[f]] && !keep[c] && order[c] < 0) order[c] = n_frag++;
        }
        if (n_frag == 0) break;
        int changed = 0;
        for (int pass = 0; pass < n_frag; pass++) {
            int pick = -1;
            for (int c = 0; c < nc; c++)
                if (order[c] >= 0 && (pick < 0 || carea[c] < carea[pick])) pick = c;
            order[pick] = -1;
            /* Longest border to another label (labels as they are now). */
            int from = -1;
            for (int f = 0; f < nf && from < 0; f++) if (comp[f] == pick) from = face_chart[f];
            for (int l = 0; l < n_labels; l++) share[l] = 0;
            for (int f = 0; f < nf; f++) {
                if (comp[f] != pick) continue;
                for (int k = 0; k < 3; k++) {
                    int h = g->adj[3 * f + k];
                    if (h >= 0 && face_chart[h] != from) share[face_chart[h]] += g->elen[3 * f + k];
                }
            }
            int to = -1;
            for (int l = 0; l < n_labels; l++) if (share[l] > 0 && (to < 0 || share[l] > share[to])) to = l;
            if (to < 0) continue; /* a whole mesh component: nothing to merge into */
            for (int f = 0; f < nf; f++) if (comp[f] == pick) face_chart[f] = to;
            merged++;
            changed = 1;
        }
        if (!changed) break;
    }
    mem_free(comp); mem_free(carea); mem_free(sure); mem_free(best); mem_free(share); mem_free(order);
    mem_free(keep); mem_free(multi); mem_free(nb); mem_free(kept);
    return merged;
}


/* ---- per-chart UVs ------------------------------------------------------ */

/* The least-squares similarity (rotation, uniform scale, translation; no
 * reflection) taking uv to target, applied to uv in place: in complex
 * numbers w = a (z − z̄) + w̄ with a = Σ conj(z − z̄)(w − w̄) / Σ |z − z̄|². */
static void align_similarity(double *uv, const double *target, int n)
{
    double zc[2] = {0, 0}, wc[2] = {0, 0};
    for (int i = 0; i < n; i++)
        for (int q = 0; q < 2; q++) { zc[q] += uv[2 * i + q] / n; wc[q] += target[2 * i + q] / n; }
    double re = 0, im = 0, den = 0;
    for (int i = 0; i < n; i++) {
        double zx = uv[2 * i] - zc[0], zy = uv[2 * i + 1] - zc[1];
        double wx = target[2 * i] - wc[0], wy = target[2 * i + 1] - wc[1];
        re += zx * wx + zy * wy;
        im += zx * wy - zy * wx;
        den += zx * zx + zy * zy;
    }
    if (!(den > 0)) return;
    re /= den;
    im /= den;
    for (int i = 0; i < n; i++) {
        double zx = uv[2 * i] - zc[0], zy = uv[2 * i + 1] - zc[1];
        uv[2 * i] = re * zx - im * zy + wc[0];
        uv[2 * i + 1] = im * zx + re * zy + wc[1];
    }
}

/* One source chart, ready for closest-point queries of its atlas UVs. */
typedef struct source_island {
    neuv_mesh *sub;
    int *vmap, *fmap;
    double *uv; /* #CV by 2: the source atlas at the chart's vertices */
    bvh tree;
    int ready;
} source_island;

static neuv_status source_island_open(const unwrap_model *md, int mc, source_island *is)
{
    memset(is, 0, sizeof *is);
    neuv_status s = chart_submesh(md->source, md->face_chart, mc, &is->sub, &is->vmap, &is->fmap);
    if (s) return s;
    is->uv = mem_alloc(sizeof(double) * 2 * (size_t)is->sub->nv);
    if (!is->uv) return error_nomem("UV transfer");
    /* A chart is one island: one UV per vertex. */
    for (int f = 0; f < is->sub->nf; f++)
        for (int k = 0; k < 3; k++)
            memcpy(is->uv + 2 * (size_t)is->sub->tri[3 * f + k],
                   md->source->uv + 2 * (size_t)md->source->tri_uv[3 * (size_t)is->fmap[f] + k], sizeof(double) * 2);
    if ((s = bvh_build(&is->tree, is->sub))) return s;
    is->ready = 1;
    return NEUV_OK;
}

static void source_island_close(source_island *is)
{
    if (is->ready) bvh_free(&is->tree);
    mesh_free(is->sub);
    mem_free(is->vmap); mem_free(is->fmap); mem_free(is->uv);
    memset(is, 0, sizeof *is);
}

/* The source atlas seen from one chart of the new mesh.
 * For every piece vertex, the closest point of source chart mc:
 *   ext    (#CV by 2) the source UV there with the closest face's affine map
 *          extended past it (plane barycentric weights), so a vertex past the
 *          source chart's border continues its map. Clamping instead (plain
 *          barycentric of the closest point) would pile every such vertex
 *          onto the border and fold the faces there: a new triangulation's
 *          chart border zigzags across the source's.
 *   anchor (#CV by 2) the source UV at the closest point itself (on the
 *          chart: inside its island of the atlas).
 *   delta  (#CV by 2, may be NULL; only for a network chart) the source
 *          atlas minus the networks' map placed by the chart's transform,
 *          interpolated at the closest point: what the source's refinement
 *          added to the networks' map.
 *   closest (#CV by 3) the closest point itself. */
static neuv_status source_chart_uvs(const unwrap_model *md, int mc, const chart_piece *p, double *ext, double *anchor,
                                    double *delta, double *closest)
{
    source_island is;
    neuv_status s = source_island_open(md, mc, &is);
    int n = p->sub->nv;
    int *face = mem_alloc(sizeof(int) * (size_t)n);
    double *bary = mem_alloc(sizeof(double) * 3 * (size_t)n), *sd = NULL;
    if (s == NEUV_OK && (!face || !bary)) s = error_nomem("UV transfer");
    const neuv_mesh *ssub = is.sub;
    const double *suv = is.uv;
    if (s == NEUV_OK && delta) {
        sd = mem_alloc(sizeof(double) * 2 * (size_t)ssub->nv);
        if (!sd) s = error_nomem("UV transfer");
        else s = param_net_apply(md->param, md->chart_net[mc], ssub->pos, ssub->nv, sd);
        for (int v = 0; s == NEUV_OK && v < ssub->nv; v++) {
            double q[2] = {md->chart_mirrored[mc] ? -sd[2 * v] : sd[2 * v], sd[2 * v + 1]}, o[2];
            atlas_chart_transform_apply(&md->xf[mc], q, o);
            sd[2 * v] = suv[2 * v] - o[0];
            sd[2 * v + 1] = suv[2 * v + 1] - o[1];
        }
    }
    if (s == NEUV_OK) {
        bvh_closest_points(&is.tree, n, p->sub->pos, face, bary, NULL);
        for (int v = 0; v < n; v++) {
            const int *t = ssub->tri + 3 * face[v];
            const double *wc = bary + 3 * (size_t)v;
            double wp[3];
            triangle_barycentric(ssub->pos + 3 * t[0], ssub->pos + 3 * t[1], ssub->pos + 3 * t[2], p->sub->pos + 3 * v, wp);
            for (int q = 0; q < 3; q++)
                closest[3 * v + q] = wc[0] * ssub->pos[3 * t[0] + q] + wc[1] * ssub->pos[3 * t[1] + q] + wc[2] * ssub->pos[3 * t[2] + q];
            for (int q = 0; q < 2; q++) {
                double e = 0, a = 0, d = 0;
                for (int k = 0; k < 3; k++) {
                    e += wp[k] * suv[2 * t[k] + q];
                    a += wc[k] * suv[2 * t[k] + q];
                    if (sd) d += wc[k] * sd[2 * t[k] + q];
                }
                ext[2 * v + q] = e;
                anchor[2 * v + q] = a;
                if (delta) delta[2 * v + q] = d;
            }
        }
    }
    source_island_close(&is);
    mem_free(face); mem_free(bary); mem_free(sd);
    return s;
}

/* The source atlas of the island at point p, the closest face's affine map extended. */
static void source_island_ext(const source_island *is, const double p[3], double uv[2])
{
    int f;
    bvh_closest_point(&is->tree, p, &f, NULL, NULL);
    const int *t = is->sub->tri + 3 * f;
    double w[3];
    triangle_barycentric(is->sub->pos + 3 * t[0], is->sub->pos + 3 * t[1], is->sub->pos + 3 * t[2], p, w);
    for (int q = 0; q < 2; q++)
        uv[q] = w[0] * is->uv[2 * t[0] + q] + w[1] * is->uv[2 * t[1] + q] + w[2] * is->uv[2 * t[2] + q];
}

static double face_ext_area2(const neuv_mesh *m, const source_island *is, int f)
{
    double u[3][2];
    for (int k = 0; k < 3; k++) source_island_ext(is, m->pos + 3 * (size_t)m->tri[3 * (size_t)f + k], u[k]);
    return (u[1][0] - u[0][0]) * (u[2][1] - u[0][1]) - (u[1][1] - u[0][1]) * (u[2][0] - u[0][0]);
}

/* Faces along a chart border that the source atlas of their chart maps
 * flipped or flat (a closest-point border cuts a source seam where this
 * mesh's edges cannot follow it, and a face across the seam may land
 * backwards in its chart's map) go to a neighbouring chart whose map takes
 * them the right way round: the border moves by a face toward where the
 * source's seam runs. A few rounds; faces away from every border are not
 * examined. label holds model chart ids.
 * Returns the number of faces moved, or -1 on no memory. */
static int settle_border_faces(const neuv_mesh *m, const unwrap_model *md, const face_graph *g, int *label,
                               neuv_status *st)
{
    int nf = m->nf, moved = 0;
    *st = NEUV_OK;
    source_island *is = mem_calloc((size_t)md->n_charts, sizeof *is);
    unsigned char *border = mem_alloc((size_t)(nf > 0 ? nf : 1));
    if (!is || !border) { mem_free(is); mem_free(border); *st = error_nomem("charts"); return -1; }
    for (int round = 0; round < 3 && *st == NEUV_OK; round++) {
        int changed = 0;
        for (int f = 0; f < nf; f++) {
            border[f] = 0;
            for (int k = 0; k < 3; k++) {
                int h = g->adj[3 * f + k];
                if (h >= 0 && label[h] != label[f]) border[f] = 1;
            }
        }
        for (int f = 0; f < nf && *st == NEUV_OK; f++) {
            if (!border[f]) continue;
            int c = label[f];
            if (!is[c].ready && (*st = source_island_open(md, c, &is[c]))) break;
            if (face_ext_area2(m, &is[c], f) > 0) continue;
            for (int k = 0; k < 3; k++) {
                int h = g->adj[3 * f + k];
                if (h < 0 || label[h] == c) continue;
                int d = label[h];
                if (!is[d].ready && (*st = source_island_open(md, d, &is[d]))) break;
                if (face_ext_area2(m, &is[d], f) > 0) { label[f] = d; changed++; break; }
            }
        }
        moved += changed;
        if (!changed) break;
    }
    for (int c = 0; c < md->n_charts; c++) source_island_close(&is[c]);
    mem_free(is); mem_free(border);
    return *st == NEUV_OK ? moved : -1;
}

/* 1: the UVs pass the injectivity check as they are (no mirroring needed). */
static int uv_usable(const chart_piece *p, const double *uv, double *scratch, chart_uv_check *chk)
{
    memcpy(scratch, uv, sizeof(double) * 2 * (size_t)p->sub->nv);
    int ok = chart_uv_check_run(p->sub, scratch, chk);
    if (ok < 0) return -1;
    return ok && !chk->mirrored;
}

static void transform_uvs(double *uv, int n, const atlas_chart_transform *xf)
{
    for (int i = 0; i < n; i++) {
        double o[2];
        atlas_chart_transform_apply(xf, uv + 2 * i, o);
        uv[2 * i] = o[0];
        uv[2 * i + 1] = o[1];
    }
}

/* Local repair of a few folded faces: the inner vertices of non-positive
 * faces move to the mean of their chart neighbours (one Tutte step), a few
 * rounds, so the rest of the chart keeps the model's UVs exactly. Returns 1
 * when the chart then passes the check, 0 when not (uv is then unchanged), -1 on no memory. */
static int relax_folds(chart_piece *p, double *scratch)
{
    const neuv_mesh *c = p->sub;
    int nv = c->nv, nf = c->nf;
    double *uv0 = mem_alloc(sizeof(double) * 2 * (size_t)nv);
    int *deg = mem_calloc((size_t)nv + 1, sizeof(int)), *bnd = mem_calloc((size_t)nv, sizeof(int));
    unsigned char *hot = mem_alloc((size_t)nv);
    if (!uv0 || !deg || !bnd || !hot) { mem_free(uv0); mem_free(deg); mem_free(bnd); mem_free(hot); return -1; }
    memcpy(uv0, p->uv, sizeof(double) * 2 * (size_t)nv);
    /* Boundary vertices (a directed edge whose twin is missing) stay. */
    edge_map e;
    if (edge_map_init(&e, (size_t)nf * 3)) { mem_free(uv0); mem_free(deg); mem_free(bnd); mem_free(hot); return -1; }
    int bad = 0;
    for (int f = 0; f < nf && !bad; f++)
        for (int k = 0; k < 3; k++)
            if (!edge_map_slot(&e, c->tri[3 * f + k], c->tri[3 * f + (k + 1) % 3], f, NULL)) bad = 1;
    for (int f = 0; f < nf && !bad; f++)
        for (int k = 0; k < 3; k++) {
            int a = c->tri[3 * f + k], b = c->tri[3 * f + (k + 1) % 3];
            if (edge_map_get(&e, b, a) < 0) bnd[a] = bnd[b] = 1;
        }
    edge_map_free(&e);
    if (bad) { mem_free(uv0); mem_free(deg); mem_free(bnd); mem_free(hot); return -1; }
    chart_uv_check chk;
    int ok = 0;
    for (int round = 0; round < 30 && !ok; round++) {
        memset(hot, 0, (size_t)nv);
        int any = 0;
        for (int f = 0; f < nf; f++)
            if (uv_face_area2(p->uv, c->tri + 3 * f) <= 0)
                for (int k = 0; k < 3; k++) { hot[c->tri[3 * f + k]] = 1; any = 1; }
        if (!any) { ok = uv_usable(p, p->uv, scratch, &chk); break; }
        /* Grow by one ring so the neighbours can make room. */
        if (round > 10)
            for (int f = 0; f < nf; f++)
                if (hot[c->tri[3 * f]] == 1 || hot[c->tri[3 * f + 1]] == 1 || hot[c->tri[3 * f + 2]] == 1)
                    for (int k = 0; k < 3; k++) if (!hot[c->tri[3 * f + k]]) hot[c->tri[3 * f + k]] = 2;
        memset(scratch, 0, sizeof(double) * 2 * (size_t)nv);
        memset(deg, 0, sizeof(int) * (size_t)nv);
        for (int f = 0; f < nf; f++)
            for (int k = 0; k < 3; k++) {
                int a = c->tri[3 * f + k];
                if (!hot[a] || bnd[a]) continue;
                for (int j = 1; j < 3; j++) {
                    int b = c->tri[3 * f + (k + j) % 3];
                    scratch[2 * a] += p->uv[2 * b];
                    scratch[2 * a + 1] += p->uv[2 * b + 1];
                    deg[a]++;
                }
            }
        for (int v = 0; v < nv; v++)
            if (hot[v] && !bnd[v] && deg[v]) {
                p->uv[2 * v] = scratch[2 * v] / deg[v];
                p->uv[2 * v + 1] = scratch[2 * v + 1] / deg[v];
            }
    }
    if (ok <= 0) memcpy(p->uv, uv0, sizeof(double) * 2 * (size_t)nv);
    mem_free(uv0); mem_free(deg); mem_free(bnd); mem_free(hot);
    return ok;
}

/* Anchor weights of the anchored LSCM tried first (flatten/lscm.h): the
 * conformal energy unfolds the map while the anchor keeps it where the
 * model put it; a smaller weight unfolds harder folds. */
static const double reflatten_anchor_lambda[] = {10.0, 1.0, 0.1};

/* Flattens a piece again: LSCM anchored to target (aligned 0), or plain
 * LSCM and harmonic placed onto target by a similarity (aligned 1). Returns
 * 1 when the result is usable, 0 when not, -1 on no memory; a flattening
 * error (not a disk) counts as unusable. */
static int reflatten(chart_piece *p, const double *target, double *scratch, int aligned, const char **how)
{
    chart_uv_check chk;
    const int anchored = (int)(sizeof reflatten_anchor_lambda / sizeof reflatten_anchor_lambda[0]);
    for (int attempt = aligned ? anchored : 0; attempt < (aligned ? anchored + 2 : anchored); attempt++) {
        neuv_status s;
        if (attempt < anchored) {
            s = lscm_anchored(p->sub, target, reflatten_anchor_lambda[attempt], p->uv);
            *how = "LSCM anchored to the model's map";
        } else {
            s = attempt == anchored ? lscm(p->sub, p->uv) : harmonic(p->sub, p->uv);
            *how = attempt == anchored ? "LSCM, aligned to it" : "harmonic, aligned to it";
        }
        if (s == NEUV_ERR_NOMEM) return -1;
        if (s != NEUV_OK) continue;
        if (attempt >= anchored) {
            int ok = chart_uv_check_run(p->sub, p->uv, &chk); /* orients it counter-clockwise */
            if (ok < 0) return -1;
            if (!ok) continue;
            align_similarity(p->uv, target, p->sub->nv);
        }
        int ok = uv_usable(p, p->uv, scratch, &chk);
        if (ok) return ok;
    }
    return 0;
}

/* ---- the atlas ---------------------------------------------------------- */

typedef struct chart_span {
    int first, count;   /* range of the chart's UVs in m->uv */
    int repaired;
    int moved;          /* 1: no longer where the source atlas put it */
    double lo[2], hi[2];
} chart_span;

static void span_bounds(const neuv_mesh *m, chart_span *sp)
{
    sp->lo[0] = sp->lo[1] = INFINITY;
    sp->hi[0] = sp->hi[1] = -INFINITY;
    for (int i = sp->first; i < sp->first + sp->count; i++)
        for (int q = 0; q < 2; q++) {
            sp->lo[q] = fmin(sp->lo[q], m->uv[2 * i + q]);
            sp->hi[q] = fmax(sp->hi[q], m->uv[2 * i + q]);
        }
}

/* Faces listed by chart: order (#F), first (n_charts + 1). */
static neuv_status faces_by_chart(const struct neuv_unwrap_result *r, int **order_out, int **first_out)
{
    int nf = r->mesh->nf;
    int *order = mem_alloc(sizeof(int) * (size_t)(nf > 0 ? nf : 1));
    int *first = mem_calloc((size_t)r->n_charts + 1, sizeof(int));
    int *fill = mem_calloc((size_t)r->n_charts + 1, sizeof(int));
    if (!order || !first || !fill) { mem_free(order); mem_free(first); mem_free(fill); return error_nomem("overlap test"); }
    for (int f = 0; f < nf; f++) first[r->face_chart[f] + 1]++;
    for (int c = 0; c < r->n_charts; c++) first[c + 1] += first[c];
    for (int f = 0; f < nf; f++) order[first[r->face_chart[f]] + fill[r->face_chart[f]]++] = f;
    mem_free(fill);
    *order_out = order;
    *first_out = first;
    return NEUV_OK;
}

/* The pairs of charts that overlap, at the overlap metric's raster. */
static neuv_status overlapping_pairs(const struct neuv_unwrap_result *r, int **pairs, int *n)
{
    const neuv_mesh *m = r->mesh;
    return uv_overlap_chart_pairs(m->uv, m->nf, m->tri_uv, r->face_chart, OVERLAP_RESOLUTION, pairs, n);
}

static double span_area(const chart_span *sp)
{
    return (sp->hi[0] - sp->lo[0]) * (sp->hi[1] - sp->lo[1]);
}

/* Each chart's range of UVs (its corners' UV indices: the charts' UVs lie
 * one after the other, unwrap_assemble_uvs) and whether a fold repair
 * re-flattened it. */
static neuv_status chart_spans(const struct neuv_unwrap_result *r, chart_span **out)
{
    *out = NULL;
    const neuv_mesh *m = r->mesh;
    chart_span *span = mem_calloc((size_t)(r->n_charts > 0 ? r->n_charts : 1), sizeof *span);
    if (!span) return error_nomem("charts");
    for (int c = 0; c < r->n_charts; c++) span[c].first = -1;
    for (int f = 0; f < m->nf; f++) {
        chart_span *sp = &span[r->face_chart[f]];
        for (int k = 0; k < 3; k++) {
            int i = m->tri_uv[3 * (size_t)f + k];
            if (sp->first < 0) { sp->first = i; sp->count = 1; continue; }
            if (i < sp->first) { sp->count += sp->first - i; sp->first = i; }
            if (i >= sp->first + sp->count) sp->count = i - sp->first + 1;
        }
    }
    for (int c = 0; c < r->n_charts; c++) {
        if (span[c].first < 0) span[c].first = 0;
        span[c].repaired = r->chart_source && r->chart_source[c] == CHART_SOURCE_LSCM_AFTER_FOLD;
    }
    *out = span;
    return NEUV_OK;
}

/* Overlaps made by the new triangulation itself, mended without moving a
 * chart: a face across the source's seam belongs to one side, and its
 * corner past the seam continues its chart's map beyond the island's
 * border, into the gutter and at worst onto the next island. Those corners
 * (the ones whose closest source point lies in another chart) of a chart
 * that overlaps another or leaves [0,1]^2, on a face that covers an
 * overlapped pixel or outside [0,1]^2 themselves, are pulled toward the source UV
 * at their closest point ON their chart, which lies inside the island:
 * first to half the packing's gap from it, then onto it. Faces a pull
 * collapses or folds have it eased (uv_pull_ease); a pull that would still
 * fold the chart is relaxed locally, else undone (the chart is then left to
 * resolve_overlaps). pieces[c].uv and anchor[c] are per piece vertex, in
 * the atlas frame. */
static neuv_status pull_past_borders(struct neuv_unwrap_result *r, chart_span *span, chart_piece *pieces,
                                     double *const *anchor, const int *model_chart, const int *vertex_chart)
{
    neuv_mesh *m = r->mesh;
    int nc = r->n_charts;
    neuv_status s = NEUV_OK;
    unsigned char *hot = mem_alloc((size_t)(nc > 0 ? nc : 1)), *out = mem_alloc((size_t)(nc > 0 ? nc : 1));
    int maxv = 1;
    for (int c = 0; c < nc; c++) if (pieces[c].sub->nv > maxv) maxv = pieces[c].sub->nv;
    double *keep = mem_alloc(sizeof(double) * 2 * (size_t)maxv), *scratch = mem_alloc(sizeof(double) * 2 * (size_t)maxv);
    int *pulled = mem_calloc((size_t)(nc > 0 ? nc : 1), sizeof(int));
    unsigned char *hit = mem_alloc((size_t)(m->nf > 0 ? m->nf : 1)), *near = mem_alloc((size_t)maxv);
    if (!hot || !out || !keep || !scratch || !pulled || !hit || !near) s = error_nomem("overlap test");
    /* How far past its island a corner may stay, per round: half the gap the
     * packing left between islands, then none. */
    const double reach[2] = {0.5 * r->opts.padding / (r->opts.resolution > 0 ? r->opts.resolution : 1), 0.0};
    for (int round = 0; s == NEUV_OK && round < 2; round++) {
        int any = 0;
        for (int c = 0; c < nc; c++) {
            span_bounds(m, &span[c]);
            chart_span *A = &span[c];
            hot[c] = out[c] = A->lo[0] < 0 || A->lo[1] < 0 || A->hi[0] > 1 || A->hi[1] > 1;
            any |= hot[c];
        }
        /* The faces on an overlap (only their corners past the seam are
         * pulled; elsewhere they stay): their charts are the ones that
         * overlap another (uv_overlap_chart_pairs' charts, same raster). */
        if ((s = uv_overlap_faces(m->uv, m->nf, m->tri_uv, r->face_chart, OVERLAP_RESOLUTION, hit))) break;
        for (int f = 0; f < m->nf; f++)
            if (hit[f]) { hot[r->face_chart[f]] = 1; any = 1; }
        if (!any) break;
        for (int c = 0; c < nc && s == NEUV_OK; c++) {
            if (!hot[c]) continue;
            chart_piece *p = &pieces[c];
            int n = p->sub->nv, moved = 0;
            double *uv = m->uv + 2 * (size_t)span[c].first;
            memcpy(keep, uv, sizeof(double) * 2 * (size_t)n);
            /* near: corners of its faces on an overlap, and corners outside [0,1]^2. */
            for (int v = 0; v < n; v++)
                near[v] = out[c] && (uv[2 * v] < 0 || uv[2 * v] > 1 || uv[2 * v + 1] < 0 || uv[2 * v + 1] > 1);
            for (int lf = 0; lf < p->sub->nf; lf++)
                if (hit[p->fmap[lf]])
                    for (int k = 0; k < 3; k++) near[p->sub->tri[3 * lf + k]] = 1;
            for (int v = 0; v < n; v++) {
                if (vertex_chart[p->vmap[v]] == model_chart[c] || !near[v]) continue;
                double dx = uv[2 * v] - anchor[c][2 * v], dy = uv[2 * v + 1] - anchor[c][2 * v + 1];
                double d = sqrt(dx * dx + dy * dy);
                if (d <= reach[round]) continue;
                uv[2 * v] = anchor[c][2 * v] + dx * reach[round] / d;
                uv[2 * v + 1] = anchor[c][2 * v + 1] + dy * reach[round] / d;
                moved++;
            }
            if (moved == 0) continue;
            uv_pull_ease(p->sub, keep, uv);
            memcpy(p->uv, uv, sizeof(double) * 2 * (size_t)n);
            chart_uv_check chk;
            int ok = uv_usable(p, p->uv, scratch, &chk);
            if (ok == 0) ok = relax_folds(p, scratch);
            if (ok < 0) { s = error_nomem("chart check"); break; }
            if (ok) {
                memcpy(uv, p->uv, sizeof(double) * 2 * (size_t)n);
                pulled[c] += moved;
            } else {
                memcpy(uv, keep, sizeof(double) * 2 * (size_t)n);
                memcpy(p->uv, keep, sizeof(double) * 2 * (size_t)n);
            }
        }
    }
    for (int c = 0; s == NEUV_OK && c < nc; c++)
        if (pulled[c]) {
            r->model.pulled_vertices += pulled[c];
            unwrap_add_repair(r, c, "%d corners past the source chart's seam overlapped or left the atlas; pulled toward "
                              "the source chart's border (the chart stays in place)", pulled[c]);
        }
    mem_free(hot); mem_free(out); mem_free(keep); mem_free(scratch); mem_free(pulled); mem_free(hit); mem_free(near);
    return s;
}

/* Shrinks charts that overlap a neighbour until the whole atlas has no
 * overlapped pixel centre (at the metric's resolution): of each
 * overlapping pair, the chart already off the model's layout (re-flattened
 * by a fold repair, or moved), else the smaller one, shrinks to SHRINK_STEP
 * of its size about its centroid, once per round: small steps, so that a
 * chart moves no farther than the overlap needs; then larger ones
 * (LATE_SHRINK_STEP), since a chart shrunk in place keeps its texture's
 * place where a chart moved elsewhere does not. */
static neuv_status resolve_overlaps(struct neuv_unwrap_result *r, chart_span *span)
{
    neuv_mesh *m = r->mesh;
    int *shrunk = mem_calloc((size_t)r->n_charts + 1, sizeof(int));
    unsigned char *now = mem_alloc((size_t)r->n_charts + 1);
    if (!shrunk || !now) { mem_free(shrunk); mem_free(now); return error_nomem("overlap test"); }
    neuv_status s = NEUV_OK;
    double *scale = mem_alloc(sizeof(double) * ((size_t)r->n_charts + 1));
    if (!scale) { mem_free(shrunk); mem_free(now); return error_nomem("overlap test"); }
    for (int c = 0; c < r->n_charts; c++) scale[c] = 1;
    for (int round = 0; round < MAX_SHRINK_ROUNDS + MAX_LATE_SHRINK_ROUNDS; round++) {
        double step = round < MAX_SHRINK_ROUNDS ? SHRINK_STEP : LATE_SHRINK_STEP;
        int *pairs = NULL, np = 0;
        if ((s = overlapping_pairs(r, &pairs, &np))) break;
        if (np == 0) { mem_free(pairs); break; }
        memset(now, 0, (size_t)r->n_charts + 1);
        for (int c = 0; c < r->n_charts; c++) span_bounds(m, &span[c]);
        for (int k = 0; k < np; k++) {
            int a = pairs[2 * k], b = pairs[2 * k + 1];
            chart_span *A = &span[a], *B = &span[b];
            /* A chart already off the model's layout (re-flattened or moved) gives way; else the smaller one. */
            int wa = A->repaired || A->moved, wb = B->repaired || B->moved;
            int pick = wa != wb ? (wa ? a : b) : (span_area(A) <= span_area(B) ? a : b);
            if (now[a] || now[b]) continue; /* one of them shrank this round already */
            chart_span *P = &span[pick];
            double cx = 0, cy = 0;
            for (int i = P->first; i < P->first + P->count; i++) { cx += m->uv[2 * i]; cy += m->uv[2 * i + 1]; }
            cx /= P->count;
            cy /= P->count;
            if (round >= MAX_SHRINK_ROUNDS) {
                double r2 = 0; /* the farthest corner from the centroid, at the chart's size now */
                for (int i = P->first; i < P->first + P->count; i++)
                    r2 = fmax(r2, (m->uv[2 * i] - cx) * (m->uv[2 * i] - cx) + (m->uv[2 * i + 1] - cy) * (m->uv[2 * i + 1] - cy));
                if ((1 - scale[pick] * step) * sqrt(r2) / scale[pick] > LATE_SHRINK_MAX_SHIFT) continue;
            }
            for (int i = P->first; i < P->first + P->count; i++) {
                m->uv[2 * i] = cx + step * (m->uv[2 * i] - cx);
                m->uv[2 * i + 1] = cy + step * (m->uv[2 * i + 1] - cy);
            }
            scale[pick] *= step;
            if (!shrunk[pick]) r->model.shrunk_charts++;
            shrunk[pick]++;
            P->moved = 1;
            now[pick] = 1;
        }
        mem_free(pairs);
    }
    for (int c = 0; c < r->n_charts && s == NEUV_OK; c++)
        if (shrunk[c])
            unwrap_add_repair(r, c, "overlapped a neighbour in the atlas; shrunk to %.3f of its size about its centroid",
                              scale[c]);
    mem_free(shrunk); mem_free(now); mem_free(scale);
    return s;
}

/* Footprint of chart c at the packing's pixel size, and its pixel origin. */
static int chart_footprint(const neuv_mesh *m, const chart_span *sp, const int *order, const int *first, int c, int R,
                           double *q, int *lt, footprint *fp, int *x0, int *y0)
{
    *x0 = (int)floor(sp->lo[0] * R);
    *y0 = (int)floor(sp->lo[1] * R);
    int w = (int)ceil(sp->hi[0] * R) - *x0 + 2, h = (int)ceil(sp->hi[1] * R) - *y0 + 2;
    for (int i = 0; i < sp->count; i++) {
        q[2 * i] = m->uv[2 * (size_t)(sp->first + i)] * R - *x0;
        q[2 * i + 1] = m->uv[2 * (size_t)(sp->first + i) + 1] * R - *y0;
    }
    int n = 0;
    for (int k = first[c]; k < first[c + 1]; k++, n++)
        for (int j = 0; j < 3; j++) lt[3 * n + j] = m->tri_uv[3 * (size_t)order[k] + j] - sp->first;
    return footprint_rasterize(q, lt, n, w, h, fp);
}

/* Last resort for the no-overlap guarantee, after the shrinking: the
 * smaller chart of each pair that still overlaps moves, at its size, to the
 * free place of the atlas nearest to where it was (the packing's pixel grid
 * and padding) with every other chart kept where it is: the nearer, the
 * less of a painted texture it leaves behind. The rest of the layout
 * stays the source's; each move is reported. */
static neuv_status place_in_free_space(struct neuv_unwrap_result *r, chart_span *span)
{
    neuv_mesh *m = r->mesh;
    int nc = r->n_charts, R = r->opts.resolution > 0 ? r->opts.resolution : 1024, pad = r->opts.padding;
    int *pairs = NULL, np = 0;
    neuv_status s = overlapping_pairs(r, &pairs, &np);
    if (s || np == 0) { mem_free(pairs); return s; }
    int *order = NULL, *first = NULL;
    if ((s = faces_by_chart(r, &order, &first))) { mem_free(pairs); return s; }
    int maxv = 1, maxf = 1;
    for (int c = 0; c < nc; c++) {
        span_bounds(m, &span[c]);
        if (span[c].count > maxv) maxv = span[c].count;
        if (first[c + 1] - first[c] > maxf) maxf = first[c + 1] - first[c];
    }
    unsigned char *move = mem_calloc((size_t)nc + 1, 1);
    double *q = mem_alloc(sizeof(double) * 2 * (size_t)maxv);
    int *lt = mem_alloc(sizeof(int) * 3 * (size_t)maxf);
    occupancy occ;
    int occ_ok = occupancy_init(&occ, R, pad) == 0;
    if (!move || !q || !lt || !occ_ok) s = error_nomem("chart placement");
    for (int k = 0; s == NEUV_OK && k < np; k++) {
        int a = pairs[2 * k], b = pairs[2 * k + 1];
        if (!move[a] && !move[b]) move[span_area(&span[a]) <= span_area(&span[b]) ? a : b] = 1;
    }
    mem_free(pairs);
    for (int pass = 0; pass < 2 && s == NEUV_OK; pass++) /* the charts that stay, then the ones that move */
        for (int c = 0; c < nc && s == NEUV_OK; c++) {
            if (move[c] != pass || span[c].count == 0) continue;
            footprint fp;
            footprint_spans fs;
            memset(&fs, 0, sizeof fs);
            int x0, y0;
            if (chart_footprint(m, &span[c], order, first, c, R, q, lt, &fp, &x0, &y0)) { s = error_nomem("chart placement"); break; }
            int x = x0, y = y0, found = 1;
            double scale = 1;
            for (int tries = 0; pass == 1 && tries < 8; tries++) {
                footprint_spans_free(&fs);
                if (footprint_to_spans(&fp, &fs)) { s = error_nomem("chart placement"); break; }
                found = occupancy_find_nearest(&occ, &fs, x0, y0, &x, &y);
                if (found) break;
                /* No room at this size: 0.8 of it about its centroid, and look again. */
                double cx = 0, cy = 0;
                for (int i = span[c].first; i < span[c].first + span[c].count; i++) { cx += m->uv[2 * i]; cy += m->uv[2 * i + 1]; }
                cx /= span[c].count;
                cy /= span[c].count;
                for (int i = span[c].first; i < span[c].first + span[c].count; i++) {
                    m->uv[2 * i] = cx + 0.8 * (m->uv[2 * i] - cx);
                    m->uv[2 * i + 1] = cy + 0.8 * (m->uv[2 * i + 1] - cy);
                }
                scale *= 0.8;
                span_bounds(m, &span[c]);
                footprint_free(&fp);
                if (chart_footprint(m, &span[c], order, first, c, R, q, lt, &fp, &x0, &y0)) {
                    s = error_nomem("chart placement");
                    memset(&fp, 0, sizeof fp);
                    break;
                }
            }
            if (s == NEUV_OK && found && pass == 0 && footprint_to_spans(&fp, &fs)) s = error_nomem("chart placement");
            if (s) { footprint_free(&fp); footprint_spans_free(&fs); break; }
            if (found) occupancy_mark(&occ, &fs, x, y, pad);
            footprint_free(&fp);
            footprint_spans_free(&fs);
            if (pass == 1 && found) {
                double dx = (double)(x - x0) / R, dy = (double)(y - y0) / R;
                for (int i = span[c].first; i < span[c].first + span[c].count; i++) {
                    m->uv[2 * (size_t)i] += dx;
                    m->uv[2 * (size_t)i + 1] += dy;
                }
                span_bounds(m, &span[c]);
                span[c].moved = 1;
                unwrap_add_repair(r, c, "still overlapped a neighbour after shrinking; moved by (%.4f, %.4f) to free space "
                                  "in the atlas, at %.3f of that size", dx, dy, scale);
            } else if (pass == 1) {
                unwrap_add_repair(r, c, "still overlapped a neighbour after shrinking and found no free space (down to %.3f of "
                                  "that size)", scale);
            }
        }
    if (occ_ok) occupancy_free(&occ);
    mem_free(order); mem_free(first); mem_free(move); mem_free(q); mem_free(lt);
    return s;
}

/* A chart whose UVs reach past [0,1]^2 (network UVs near a chart's border
 * may reach a little past the source's) moves back inside, to the padding
 * margin, by a translation of that chart alone: the rest of the atlas keeps
 * the model's layout. Overlaps this makes are resolve_overlaps' to mend. */
static void pull_charts_inside(struct neuv_unwrap_result *r, chart_span *span)
{
    neuv_mesh *m = r->mesh;
    double margin = (double)r->opts.padding / r->opts.resolution;
    for (int c = 0; c < r->n_charts; c++) {
        chart_span *sp = &span[c];
        if (sp->count == 0) continue;
        span_bounds(m, sp);
        double d[2] = {0, 0};
        for (int q = 0; q < 2; q++) {
            if (sp->hi[q] - sp->lo[q] > 1 - 2 * margin) continue; /* wider than the square: fit_unit_square's */
            if (sp->lo[q] < 0) d[q] = margin - sp->lo[q];
            else if (sp->hi[q] > 1) d[q] = 1 - margin - sp->hi[q];
        }
        if (d[0] == 0 && d[1] == 0) continue;
        for (int i = sp->first; i < sp->first + sp->count; i++) {
            m->uv[2 * i] += d[0];
            m->uv[2 * i + 1] += d[1];
        }
        span_bounds(m, sp);
        sp->moved = 1;
        unwrap_add_repair(r, c, "reached past [0,1]^2; moved inside by (%.4f, %.4f)", d[0], d[1]);
    }
}

/* Moves the atlas into [0,1]^2 by one uniform scale and translation when a
 * chart crossed the border (network UVs near a chart's border may reach a
 * little past the source's). */
static void fit_unit_square(struct neuv_unwrap_result *r, chart_span *span)
{
    neuv_mesh *m = r->mesh;
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (int i = 0; i < m->nuv; i++)
        for (int q = 0; q < 2; q++) { lo[q] = fmin(lo[q], m->uv[2 * i + q]); hi[q] = fmax(hi[q], m->uv[2 * i + q]); }
    if (lo[0] >= 0 && lo[1] >= 0 && hi[0] <= 1 && hi[1] <= 1) return;
    double margin = (double)r->opts.padding / r->opts.resolution;
    double side = fmax(hi[0] - lo[0], hi[1] - lo[1]);
    double sc = fmin(1.0, (1 - 2 * margin) / side);
    double ox = 0.5 - sc * 0.5 * (lo[0] + hi[0]), oy = 0.5 - sc * 0.5 * (lo[1] + hi[1]);
    for (int i = 0; i < m->nuv; i++) {
        m->uv[2 * i] = fmin(1, fmax(0, sc * m->uv[2 * i] + ox));
        m->uv[2 * i + 1] = fmin(1, fmax(0, sc * m->uv[2 * i + 1] + oy));
    }
    for (int c = 0; c < r->n_charts; c++) span[c].moved = 1;
    unwrap_add_repair(r, -1, "atlas reached past [0,1]^2 (box %.4f..%.4f, %.4f..%.4f); scaled by %.4f and centred",
                      lo[0], hi[0], lo[1], hi[1], sc);
}

/* PatchNet on this mesh against the source's labels at the closest source face (by area). */
static neuv_status check_inference(struct neuv_unwrap_result *r, const unwrap_model *md, const int *src_face,
                                   int use_cache)
{
    if (!md->patchnet || !md->face_label) return NEUV_OK;
    operators ops;
    memset(&ops, 0, sizeof ops);
    operators_params op = operators_default_params();
    neuv_status s = operators_get(r->mesh, &op, use_cache, &ops, NULL, &r->cache_hit);
    if (s) return s;
    int *label = mem_alloc(sizeof(int) * (size_t)r->mesh->nf);
    if (!label) { operators_free(&ops); return error_nomem("labels"); }
    s = patchnet_infer(md->patchnet, r->mesh, &ops, label);
    operators_free(&ops);
    if (s == NEUV_OK) {
        double agree = 0, total = 0;
        for (int f = 0; f < r->mesh->nf; f++) {
            double a = mesh_face_area(r->mesh, f);
            total += a;
            if (label[f] == md->face_label[src_face[f]]) agree += a;
        }
        r->model.label_agreement = total > 0 ? agree / total : 0;
    }
    mem_free(label);
    return s;
}

#define REFINE_MAX_FACES 250000

neuv_status unwrap_apply_charts(struct neuv_unwrap_result *r, const unwrap_model *md, const unwrap_apply_options *o)
{
    neuv_mesh *m = r->mesh;
    neuv_status s;
    double t = now_seconds();
    log_progress("patches", 0, "charts from the model's source surface");
    int *label = mem_alloc(sizeof(int) * (size_t)m->nf);
    int *src_face = mem_alloc(sizeof(int) * (size_t)m->nf);
    int *vertex_chart = r->model.vertex_source_chart = mem_alloc(sizeof(int) * (size_t)m->nv);
    r->face_chart = mem_alloc(sizeof(int) * (size_t)m->nf);
    if (!label || !src_face || !vertex_chart || !r->face_chart) {
        mem_free(label); mem_free(src_face);
        return error_nomem("charts");
    }
    /* The chart under each face's centroid: a cut-off piece is kept where it
     * agrees (not for a simplified copy's model, whose atlas is packed afresh). */
    int *centroid_chart = o->refine_on_mesh ? NULL : mem_alloc(sizeof(int) * (size_t)(m->nf > 0 ? m->nf : 1));
    double dist = 0;
    if (!o->refine_on_mesh && !centroid_chart) s = error_nomem("charts");
    else s = transfer_charts(m, md, label, src_face, centroid_chart, vertex_chart, &dist);
    r->model.surface_distance = md->norm[3] > 0 ? dist / md->norm[3] : 0;
    face_graph g;
    if (s == NEUV_OK) s = face_graph_build(m, &g);
    int *piece = NULL;
    int n_pieces = 0;
    if (s == NEUV_OK) {
        int merged = merge_fragments(&g, centroid_chart, label, md->n_charts);
        if (merged < 0) s = error_nomem("charts");
        int settled = s == NEUV_OK && !o->refine_on_mesh ? settle_border_faces(m, md, &g, label, &s) : 0;
        if (s == NEUV_OK && settled > 0) {
            int again = merge_fragments(&g, centroid_chart, label, md->n_charts);
            if (again < 0) s = error_nomem("charts");
            else merged += again;
        }
        r->model.merged_fragments = merged > 0 ? merged : 0;
        r->model.settled_faces = settled > 0 ? settled : 0;
        piece = mem_alloc(sizeof(int) * (size_t)(m->nf > 0 ? m->nf : 1));
        if (s == NEUV_OK && !piece) s = error_nomem("charts");
        if (s == NEUV_OK && !o->refine_on_mesh && (n_pieces = label_pieces(&g, label, piece)) < 0)
            s = error_nomem("charts");
        if (s == NEUV_OK && o->refine_on_mesh) { /* one chart per source chart, as packed afresh */
            memcpy(piece, label, sizeof(int) * (size_t)m->nf);
            n_pieces = md->n_charts;
        }
        face_graph_free(&g);
    }
    /* One chart per connected piece of a source chart's faces (per source
     * chart for a simplified copy's model), in the source's chart order
     * (pieces of one chart in order of their first face); source charts
     * that got no face are dropped. */
    int *model_chart = r->model.source_chart = mem_alloc(sizeof(int) * (size_t)(n_pieces > 0 ? n_pieces : 1));
    int *new_id = mem_alloc(sizeof(int) * (size_t)(n_pieces > 0 ? n_pieces : 1));
    int *first = mem_calloc((size_t)md->n_charts + 1, sizeof(int));
    if (s == NEUV_OK && (!model_chart || !new_id || !first)) s = error_nomem("charts");
    if (s == NEUV_OK) {
        /* new_id first holds each piece's label; first[] counts the pieces per label. */
        for (int p = 0; p < n_pieces; p++) new_id[p] = -1;
        for (int f = 0; f < m->nf; f++)
            if (new_id[piece[f]] < 0) { new_id[piece[f]] = label[f]; first[label[f] + 1]++; }
        int used = 0;
        for (int c = 0; c < md->n_charts; c++) used += first[c + 1] > 0;
        for (int c = 0; c < md->n_charts; c++) first[c + 1] += first[c];
        int charts = 0;
        for (int p = 0; p < n_pieces; p++) { /* pieces are numbered by first face: stable per label */
            int l = new_id[p];
            if (l < 0) continue; /* a source chart without faces */
            model_chart[first[l]] = l;
            new_id[p] = first[l]++;
            charts++;
        }
        r->n_charts = charts;
        r->model.empty_charts = md->n_charts - used;
        r->model.fragment_charts = charts - used;
        for (int f = 0; f < m->nf; f++) r->face_chart[f] = new_id[piece[f]];
    }
    mem_free(piece);
    mem_free(first);
    mem_free(centroid_chart);
    mem_free(label);
    mem_free(new_id);
    unwrap_stage_time(r, STAGE_PATCHES, t);
    if (s == NEUV_OK && o->check_inference) { /* a diagnostic, timed with the operators it computes */
        t = now_seconds();
        s = check_inference(r, md, src_face, o->use_cache);
        unwrap_stage_time(r, STAGE_OPERATORS, t);
    }
    mem_free(src_face);
    return s;
}


/* 1 when map a of the chart is at most `factor` times worse than map b in
 * angles (qce_mean) and in area (L2 stretch); factor 1: no worse. */
static int within_map(const neuv_mesh *sub, const double *a, const double *b, double factor)
{
    return chart_qce_mean(sub, a, NULL) <= factor * chart_qce_mean(sub, b, NULL) &&
           chart_l2_stretch(sub, a) <= factor * chart_l2_stretch(sub, b);
}

static int no_worse_map(const neuv_mesh *sub, const double *a, const double *b)
{
    return within_map(sub, a, b, 1.0);
}

/* A chart's head solved on this mesh ahead of the charts' loop
 * (presolve_heads): param_net_apply_solved's outputs for the chart as the
 * model carried it, taken by the loop when it reaches the chart unsplit. */
typedef struct presolved {
    int head_id;  /* the model chart whose head was solved (-1: none) */
    int visited;  /* the loop has reached the chart (a second visit follows a split) */
    neuv_status s;
    double *uv;   /* 2 nv of the chart's piece */
    float *head;  /* param_head_size */
    double gain;
} presolved;

static void presolved_drop(presolved *ps)
{
    mem_free(ps->uv);
    mem_free(ps->head);
    ps->uv = NULL;
    ps->head = NULL;
    ps->head_id = -1;
}

/* param_net_apply_solved for head `id` on piece p, from *ps when it holds
 * that solve (then dropped: a chart takes it once). */
static neuv_status apply_solved(presolved *ps, const param_net_model *param, int id, const chart_piece *p, double *uv,
                                float *head, double *gain)
{
    if (!ps || ps->head_id != id || !ps->uv) return param_net_apply_solved(param, id, p->sub, uv, head, gain, NULL);
    neuv_status s = ps->s;
    if (s == NEUV_OK) {
        memcpy(uv, ps->uv, sizeof(double) * 2 * (size_t)p->sub->nv);
        if (head) memcpy(head, ps->head, sizeof(float) * (size_t)param_head_size(&param->f));
        if (gain) *gain = ps->gain;
    }
    presolved_drop(ps);
    return s;
}

/* The model chart whose head the loop of unwrap_apply_param solves on
 * chart c's piece, as the chart was carried: its network chart, or for a
 * chart the networks folded on the copy the head they had for it; -1 when
 * none is solved. */
static int head_to_solve(const unwrap_model *md, const unwrap_apply_options *o, int mc)
{
    if (!o->refine_on_mesh || !md->param || !md->param->heads) return -1;
    if (md->chart_net[mc] >= 0) return md->chart_net[mc];
    return md->chart_tried && md->chart_tried[mc] >= 0 ? md->chart_tried[mc] : -1;
}

/* Every chart's head solved on its piece side by side (each solve's
 * products cut as on the run's threads: the same bits as in the loop),
 * before the loop takes the charts one by one; a chart the loop splits
 * solves its pieces there. Allocation failures leave a chart unsolved (the
 * loop solves it). Progress is reported from the calling thread; after a
 * cancel the charts not started are left. */
static presolved *presolve_heads(const struct neuv_unwrap_result *r, const unwrap_model *md,
                                 const unwrap_apply_options *o, const int *model_chart)
{
    int n = r->n_charts;
    presolved *pre = mem_calloc((size_t)(n > 0 ? n : 1), sizeof *pre);
    if (!pre) return NULL;
    int hs = md->param ? param_head_size(&md->param->f) : 0, finished = 0, cancelled = 0;
    for (int c = 0; c < n; c++) pre[c].head_id = -1;
#pragma omp parallel for schedule(dynamic, 1)
    for (int c = 0; c < n; c++) {
        presolved *ps = &pre[c];
        int id = head_to_solve(md, o, model_chart[c]), stop;
#pragma omp atomic read
        stop = cancelled;
        if (id < 0 || stop) continue;
        chart_piece p;
        memset(&p, 0, sizeof p);
        unwrap_piece_clear(&p);
        if (unwrap_piece_build(r->mesh, r->face_chart, c, &p) == NEUV_OK) {
            ps->uv = mem_alloc(sizeof(double) * 2 * (size_t)p.sub->nv);
            ps->head = mem_alloc(sizeof(float) * (size_t)(hs > 0 ? hs : 1));
            if (ps->uv && ps->head) {
                ps->s = param_net_apply_solved(md->param, id, p.sub, ps->uv, ps->head, &ps->gain, NULL);
                ps->head_id = id;
            }
            if (ps->head_id < 0 || ps->s == NEUV_ERR_NOMEM) presolved_drop(ps); /* the loop tries again */
        }
        unwrap_piece_clear(&p);
        int done;
#pragma omp atomic capture
        done = ++finished;
        if (omp_get_thread_num() == 0 &&
            log_progress("param", 0.5 * done / n, "heads solved on this mesh: %d of %d charts", done, n)) {
#pragma omp atomic write
            cancelled = 1;
        }
    }
    return pre;
}

/* On the mesh a simplified copy's model is applied to (--train-faces), a
 * chart's head (MLP_f's output layer for it) is solved again on the
 * chart's own triangles (param_net_apply_solved): the learnt head fits the
 * copy's triangles, and between the copy's vertices its map can fold or be
 * far less conformal than the features allow (camelhead: a chart of 5086
 * faces at qce 1.128 where LSCM gives 1.016). The solved map (the same
 * networks' map, with an output layer fitted here) replaces the learnt
 * head's map `uv` when the learnt one folds or crosses its own boundary,
 * or when it does neither and is no worse than the learnt one in angles
 * (qce_mean) and in area (L2 stretch): the solve minimizes angle
 * distortion only, and can squeeze a region the learnt map, trained with
 * L_iso, keeps (face.obj: a chart whose L∞ stretch doubled, and whose
 * refinement then stalled at qce 1.037 where the learnt map refined to
 * 1.017). head, gain: the solved head and its gain (NULL: not wanted).
 * Returns 1 when replaced, 0 when not, -1 on an error (*s set). */
static int solve_head_on_mesh(chart_piece *p, const param_net_model *param, int net, presolved *ps, double *uv,
                              double *scratch, float *head, double *gain, neuv_status *s)
{
    int n = p->sub->nv;
    double *solved = mem_alloc(sizeof(double) * 2 * (size_t)n);
    if (!solved) { *s = error_nomem("chart head"); return -1; }
    *s = apply_solved(ps, param, net, p, solved, head, gain);
    int take = 0;
    if (*s == NEUV_OK) {
        chart_uv_check chk;
        memcpy(scratch, solved, sizeof(double) * 2 * (size_t)n);
        int ok_solved = chart_uv_check_run(p->sub, scratch, &chk);
        memcpy(scratch, uv, sizeof(double) * 2 * (size_t)n);
        int ok_learnt = chart_uv_check_run(p->sub, scratch, &chk);
        if (ok_solved < 0 || ok_learnt < 0) *s = error_nomem("chart check");
        else if (ok_learnt == 0) take = 1;
        else take = ok_solved > 0 && no_worse_map(p->sub, solved, uv);
    }
    if (take) memcpy(uv, solved, sizeof(double) * 2 * (size_t)n);
    mem_free(solved);
    return *s == NEUV_OK ? take : -1;
}

/* Whether chart c, a network chart being mapped on this mesh, may be split
 * once more for its pieces to be mapped again: fewer than NET_SPLIT_DEPTH
 * splits deep, two faces at least, and the run's splits below its faces. */
static int can_split_again(const int *depth, int c, const chart_piece *p, int splits, const neuv_mesh *m)
{
    return depth[c] < NET_SPLIT_DEPTH && p->sub->nf >= 2 && splits < m->nf;
}

/* Chart c of r split in two (charts_split) for its pieces to be mapped
 * again by the networks: the new charts come from the same model chart,
 * one split deeper. *model_chart and *depth (cap entries) grow when the
 * chart count passes cap. Returns NEUV_OK or NEUV_ERR_NOMEM. */
static neuv_status split_network_chart(struct neuv_unwrap_result *r, int c, int cap, int **model_chart, int **depth)
{
    int before = r->n_charts;
    neuv_status s = charts_split(r->mesh, r->face_chart, &r->n_charts, c);
    if (s == NEUV_OK && r->n_charts > cap) {
        int *nm = mem_realloc(*model_chart, sizeof(int) * (size_t)r->n_charts);
        if (nm) *model_chart = r->model.source_chart = nm;
        int *nd = mem_realloc(*depth, sizeof(int) * (size_t)r->n_charts);
        if (nd) *depth = nd;
        if (!nm || !nd) return error_nomem("charts");
    }
    for (int k = before; s == NEUV_OK && k < r->n_charts; k++) {
        (*model_chart)[k] = (*model_chart)[c];
        (*depth)[k] = (*depth)[c] + 1;
    }
    (*depth)[c]++;
    return s;
}

/* For a chart the networks folded on the copy (flattened by LSCM there,
 * so no network map of it is kept): the head they had for it, solved on
 * this mesh's triangles, into p->uv. Returns 1 when that map is usable
 * (*mirror: whether it must be mirrored to run counter-clockwise), 0 when
 * not, -1 on an error (*s set). w, gain: the solved head and its gain
 * (NULL: not wanted); ps: the solve made ahead (NULL: none). */
static int solve_folded_head(chart_piece *p, const param_net_model *param, int head, presolved *ps, double *scratch,
                             int *mirror, float *w, double *gain, neuv_status *s)
{
    *s = apply_solved(ps, param, head, p, p->uv, w, gain);
    if (*s != NEUV_OK) return -1;
    chart_uv_check chk;
    memcpy(scratch, p->uv, sizeof(double) * 2 * (size_t)p->sub->nv);
    int ok = chart_uv_check_run(p->sub, scratch, &chk);
    if (ok < 0) { *s = error_nomem("chart check"); return -1; }
    *mirror = chk.mirrored;
    return ok;
}

/* The result keeps, per chart, the network chart that maps it (-1: none)
 * and its mirror flag (n_charts entries of net and mirror), as a training
 * result does, so that a model can be made of it. */
static neuv_status keep_chart_nets(struct neuv_unwrap_result *r, const int *net, const int *mirror)
{
    size_t n = (size_t)(r->n_charts > 0 ? r->n_charts : 1);
    r->chart_net = mem_alloc(sizeof(int) * n);
    r->chart_mirrored = mem_alloc(sizeof(int) * n);
    r->chart_tried = mem_alloc(sizeof(int) * n);
    if (!r->chart_net || !r->chart_mirrored || !r->chart_tried) return error_nomem("the model");
    memcpy(r->chart_net, net, sizeof(int) * (size_t)r->n_charts);
    memcpy(r->chart_mirrored, mirror, sizeof(int) * (size_t)r->n_charts);
    memcpy(r->chart_tried, net, sizeof(int) * (size_t)r->n_charts);
    return NEUV_OK;
}

neuv_status unwrap_apply_param(struct neuv_unwrap_result *r, const unwrap_model *md, const unwrap_apply_options *o)
{
    neuv_mesh *m = r->mesh;
    neuv_status s = NEUV_OK;
    double t = now_seconds();
    int *model_chart = r->model.source_chart, *vertex_chart = r->model.vertex_source_chart;
    if (!model_chart || !vertex_chart) return error_set(NEUV_ERR_INTERNAL, "the model's charts were not carried first");
    /* Vertex refinement costs ~0.5 µs per face and step (spot: 400 steps in
     * 1.1 s) and moves a vertex a share of an edge per step, so on a very fine
     * mesh it is slow and does little: such meshes keep the networks' map. */
    int refine = md->refine;
    if (refine > 0 && m->nf > REFINE_MAX_FACES) {
        log_message(NEUV_LOG_INFO, "vertex refinement skipped: %d faces (more than %d)", m->nf, REFINE_MAX_FACES);
        refine = 0;
    }
    /* UVs of every chart in the source's atlas frame, checked; folded ones repaired. */
    int cap = r->n_charts + 16;
    chart_piece *pieces = mem_calloc((size_t)cap, sizeof *pieces);
    int *repaired = mem_calloc((size_t)cap, sizeof(int));
    int *depth = mem_calloc((size_t)cap, sizeof(int)); /* splits of a network chart whose map crossed its boundary */
    int *mc_grown = mem_realloc(model_chart, sizeof(int) * (size_t)cap);
    double **anchor = mem_calloc((size_t)cap, sizeof *anchor);
    /* With keep_model: the network chart that maps each chart (-1: none)
     * and its mirror flag, and the head solved on it. */
    param_net_model *keep = o->keep_model ? o->keep_heads : NULL;
    int *kept_net = mem_alloc(sizeof(int) * (size_t)cap), *kept_mirror = mem_calloc((size_t)cap, sizeof(int));
    float *solved_w = keep ? mem_alloc(sizeof(float) * (size_t)param_head_size(&keep->f)) : NULL;
    double solved_gain = 1;
    if (mc_grown) model_chart = r->model.source_chart = mc_grown;
    if (!pieces || !repaired || !depth || !mc_grown || !anchor || !kept_net || !kept_mirror || (keep && !solved_w)) {
        mem_free(pieces); mem_free(repaired); mem_free(depth); mem_free(anchor);
        mem_free(kept_net); mem_free(kept_mirror); mem_free(solved_w);
        return error_nomem("charts");
    }
    /* The source's refinement is carried over (its difference to the networks'
     * map, interpolated) unless the options ask to refine on this mesh. */
    int carry_refinement = md->refine > 0 && !o->refine_on_mesh;
    int splits = 0, n0 = r->n_charts;
    presolved *pre = o->refine_on_mesh ? presolve_heads(r, md, o, model_chart) : NULL;
    if (log_cancelled()) s = error_cancelled();
    for (int c = 0; c < r->n_charts && s == NEUV_OK; c++) {
        presolved *ps = pre && c < n0 ? &pre[c] : NULL;
        if (ps && ps->visited) presolved_drop(ps); /* split since: its piece is another */
        if (ps) ps->visited = 1;
        if (r->n_charts >= cap) { /* charts added by splits */
            int nc = 2 * r->n_charts;
            chart_piece *np = mem_realloc(pieces, sizeof *np * (size_t)nc);
            if (np) { memset(np + cap, 0, sizeof *np * (size_t)(nc - cap)); pieces = np; }
            int *nr = mem_realloc(repaired, sizeof(int) * (size_t)nc);
            if (nr) { memset(nr + cap, 0, sizeof(int) * (size_t)(nc - cap)); repaired = nr; }
            int *nd = mem_realloc(depth, sizeof(int) * (size_t)nc);
            if (nd) { memset(nd + cap, 0, sizeof(int) * (size_t)(nc - cap)); depth = nd; }
            int *nm = mem_realloc(model_chart, sizeof(int) * (size_t)nc);
            if (nm) model_chart = r->model.source_chart = nm;
            double **na = mem_realloc(anchor, sizeof *na * (size_t)nc);
            if (na) { memset(na + cap, 0, sizeof *na * (size_t)(nc - cap)); anchor = na; }
            int *kn = mem_realloc(kept_net, sizeof(int) * (size_t)nc);
            if (kn) kept_net = kn;
            int *km = mem_realloc(kept_mirror, sizeof(int) * (size_t)nc);
            if (km) kept_mirror = km;
            if (!np || !nr || !nd || !nm || !na || !kn || !km) { s = error_nomem("charts"); break; }
            cap = nc;
        }
        chart_piece *p = &pieces[c];
        unwrap_piece_clear(p); /* a chart split below is built again */
        mem_free(anchor[c]);
        anchor[c] = NULL;
        if ((s = unwrap_piece_build(m, r->face_chart, c, p))) break;
        log_progress("param", (pre ? 0.5 : 0) + (pre ? 0.5 : 1) * c / r->n_charts, "chart %d of %d", c + 1, r->n_charts);
        int mc = model_chart[c], net = md->chart_net[mc], n = p->sub->nv, relaxed = 0, head_solved = 0;
        double *target = mem_alloc(sizeof(double) * 2 * (size_t)n), *scratch = mem_alloc(sizeof(double) * 2 * (size_t)n);
        double *ext = mem_alloc(sizeof(double) * 2 * (size_t)n), *delta = mem_alloc(sizeof(double) * 2 * (size_t)n);
        double *closest = mem_alloc(sizeof(double) * 3 * (size_t)n);
        anchor[c] = mem_alloc(sizeof(double) * 2 * (size_t)n);
        if (!target || !scratch || !ext || !delta || !closest || !anchor[c]) {
            mem_free(target); mem_free(scratch); mem_free(ext); mem_free(delta); mem_free(closest);
            s = error_nomem("chart UVs");
            break;
        }
        s = source_chart_uvs(md, mc, p, ext, anchor[c], net >= 0 && carry_refinement ? delta : NULL, closest);
        int mirror = net >= 0 && md->chart_mirrored[mc], mapped = 0;
        if (s == NEUV_OK && net < 0 && o->refine_on_mesh && md->chart_tried && md->chart_tried[mc] >= 0 &&
            md->param && md->param->heads) {
            /* The networks' map folded on the copy, where LSCM flattened the
             * chart: their head solved on this mesh may not fold. It takes
             * the chart when it is at most 1.10 times worse than the copy's
             * map carried here (`ext`, LSCM's there) in angles (qce_mean) and
             * in area (L2 stretch), the bound that training's pieces of a
             * folded chart meet: an injective map can still squeeze a region
             * (face.obj: a chart at L2 stretch 26.6 against 1.29). */
            int got = solve_folded_head(p, md->param, md->chart_tried[mc], ps, scratch, &mirror, solved_w, &solved_gain,
                                        &s);
            mapped = got > 0 && within_map(p->sub, p->uv, ext, SOLVED_HEAD_MAX_QCE_RATIO);
            if (mapped) net = md->chart_tried[mc];
            head_solved = mapped;
            if (s == NEUV_OK && got >= 0 && !mapped && can_split_again(depth, c, p, splits, m)) {
                int before = r->n_charts;
                s = split_network_chart(r, c, cap, &model_chart, &depth);
                splits++;
                if (got)
                    unwrap_add_repair(r, c, "the networks' head solved on this mesh was injective but not within %.2f "
                                      "times the copy's map in qce_mean and L2 stretch; split into %d charts, each "
                                      "solved again", SOLVED_HEAD_MAX_QCE_RATIO, r->n_charts - before + 1);
                else
                    unwrap_add_repair(r, c, "the networks' head solved on this mesh folded; split into %d charts, each "
                                      "solved again", r->n_charts - before + 1);
                mem_free(target); mem_free(scratch); mem_free(ext); mem_free(delta); mem_free(closest);
                if (s != NEUV_OK) break;
                c--;
                continue;
            }
        }
        if (s == NEUV_OK && net >= 0) {
            /* The networks learnt the chart, not what lies past its seam: a
             * vertex there takes their map at its closest point of the chart,
             * continued by the source atlas's linear extension (ext - anchor). */
            for (int v = 0; v < n; v++)
                if (vertex_chart[p->vmap[v]] == mc || o->refine_on_mesh)
                    memcpy(closest + 3 * (size_t)v, p->sub->pos + 3 * (size_t)v, sizeof(double) * 3);
            double *at = p->uv;
            if (!mapped) s = param_net_apply(md->param, net, closest, n, at);
            if (s == NEUV_OK && !mapped && o->refine_on_mesh && md->param->heads)
                head_solved = solve_head_on_mesh(p, md->param, net, ps, at, scratch, solved_w, &solved_gain, &s) > 0;
            for (int v = 0; s == NEUV_OK && v < n; v++) {
                if (vertex_chart[p->vmap[v]] == mc || o->refine_on_mesh) continue;
                /* the extension, in the networks' own frame (before mirroring and placing) */
                double e[2] = {ext[2 * v] - anchor[c][2 * v], ext[2 * v + 1] - anchor[c][2 * v + 1]};
                const atlas_chart_transform *xf = &md->xf[mc];
                double cs = cos(xf->angle), sn = sin(xf->angle);
                double lx = (cs * e[0] + sn * e[1]) / xf->scale, ly = (-sn * e[0] + cs * e[1]) / xf->scale;
                at[2 * v] += mirror ? -lx : lx;
                at[2 * v + 1] += ly;
            }
            if (mirror) /* as the source's check did before packing (or this mesh's, for a head solved here) */
                for (int v = 0; v < n; v++) p->uv[2 * v] = -p->uv[2 * v];
            if (s == NEUV_OK) p->net_qce = chart_qce_mean(p->sub, p->uv, NULL);
            if (s == NEUV_OK && refine > 0 && !carry_refinement) { /* refined on this mesh, where usable */
                chart_uv_check chk0;
                int ok0 = uv_usable(p, p->uv, scratch, &chk0);
                if (ok0 < 0) s = error_nomem("chart check");
                else if (ok0) {
                    uv_refine_report rr;
                    s = unwrap_refine_piece(p, refine, &rr);
                    r->refine_seconds += rr.seconds;
                    if (rr.iters > r->refine_steps) r->refine_steps = rr.iters;
                    r->refine_stopped += rr.charts_stopped;
                }
            }
            if (s == NEUV_OK) transform_uvs(p->uv, n, &md->xf[mc]);
            if (s == NEUV_OK && carry_refinement)
                for (int i = 0; i < 2 * n; i++) p->uv[i] += delta[i];
        } else if (s == NEUV_OK) {
            memcpy(p->uv, ext, sizeof(double) * 2 * (size_t)n);
        }
        mem_free(delta); mem_free(closest);
        int baseline = 0, from_source = 0, deviates = 0;
        if (s == NEUV_OK && net >= 0 && !o->lscm_baseline && !o->refine_on_mesh) {
            /* The networks' map at these vertices against the source atlas, which
             * is the same map at the source's vertices (plus any refinement
             * carried), over the chart's own vertices: farther apart on average
             * than the packing's gutter, the networks' map varies between the
             * source's vertices more than the atlas can absorb, and the source
             * atlas is taken instead. */
            double dev = 0;
            int nin = 0;
            for (int v = 0; v < n; v++)
                if (vertex_chart[p->vmap[v]] == mc) {
                    dev += hypot(p->uv[2 * v] - ext[2 * v], p->uv[2 * v + 1] - ext[2 * v + 1]);
                    nin++;
                }
            dev = nin ? dev / nin : 0;
            double gutter = (double)r->opts.padding / (r->opts.resolution > 0 ? r->opts.resolution : 1024);
            if (dev > gutter) {
                memcpy(p->uv, ext, sizeof(double) * 2 * (size_t)n);
                deviates = 1;
                unwrap_add_repair(r, c, "network map %.2g (mean) from the source atlas on this mesh, more than the "
                                  "%.2g gutter; the source atlas taken at the closest point instead", dev, gutter);
            }
        }
        if (s == NEUV_OK && o->lscm_baseline) { /* LSCM here, placed where the model's map is */
            memcpy(target, p->uv, sizeof(double) * 2 * (size_t)n);
            neuv_status ls = lscm(p->sub, p->uv);
            chart_uv_check chk0;
            int ok0 = ls == NEUV_OK ? chart_uv_check_run(p->sub, p->uv, &chk0) : 0;
            if (ls == NEUV_ERR_NOMEM || ok0 < 0) s = error_nomem("LSCM baseline");
            else if (ok0) { align_similarity(p->uv, target, n); baseline = 1; }
            else memcpy(p->uv, target, sizeof(double) * 2 * (size_t)n);
        }
        if (s) { mem_free(target); mem_free(scratch); mem_free(ext); break; }
        memcpy(target, p->uv, sizeof(double) * 2 * (size_t)n);
        chart_uv_check chk;
        int ok = uv_usable(p, p->uv, scratch, &chk);
        if (ok == 0) {
            char why[160];
            snprintf(why, sizeof why, "%d flipped, %d degenerate faces, %d boundary crossings%s", chk.flipped,
                     chk.degenerate, chk.boundary_crossings, chk.mirrored ? ", reversed orientation" : "");
            const char *how = "LSCM";
            if (o->refine_on_mesh && net >= 0 && chk.flipped == 0 && chk.degenerate == 0 && !chk.mirrored &&
                can_split_again(depth, c, p, splits, m)) {
                /* As training does on its own mesh: a network map that folds
                 * nowhere but crosses the chart's own boundary may be injective
                 * on each half; the halves are mapped again (their heads solved
                 * on them) instead of handing the chart to LSCM. */
                int before = r->n_charts;
                s = split_network_chart(r, c, cap, &model_chart, &depth);
                splits++;
                unwrap_add_repair(r, c, "the networks' map crossed the chart's own boundary on this mesh (%d crossings); "
                                  "split into %d charts, each mapped again", chk.boundary_crossings, r->n_charts - before + 1);
                mem_free(target); mem_free(scratch); mem_free(ext);
                c--;
                continue;
            }
            /* Local repairs first, each relaxed if it still folds: the map as
             * it is; its corners past the seam pulled onto the source island
             * (a zigzag border extended past the seam can cross itself); then
             * for a network chart the source atlas (the networks' map at the
             * source's vertices, linear between them: injective on the source),
             * as it is and pulled. */
            int pulled = 0;
            ok = relax_folds(p, scratch);
            for (int attempt = 1; ok == 0 && attempt < 4 && !o->refine_on_mesh; attempt++) {
                if (attempt >= 2 && (net < 0 || baseline || deviates || o->refine_on_mesh)) break;
                memcpy(p->uv, attempt == 1 ? target : ext, sizeof(double) * 2 * (size_t)n);
                if (attempt != 2)
                    for (int v = 0; v < n; v++)
                        if (vertex_chart[p->vmap[v]] != mc) memcpy(p->uv + 2 * v, anchor[c] + 2 * v, sizeof(double) * 2);
                chart_uv_check chk1;
                ok = uv_usable(p, p->uv, scratch, &chk1);
                if (ok == 0) ok = relax_folds(p, scratch);
                if (ok > 0) { pulled = attempt != 2; from_source = attempt >= 2; }
            }
            if (ok == 0) memcpy(p->uv, target, sizeof(double) * 2 * (size_t)n);
            relaxed = ok > 0 && !from_source;
            if (from_source) {
                unwrap_add_repair(r, c, "network map folded on this mesh (%s); the source atlas taken at the closest "
                                  "point instead%s", why, pulled ? ", corners past the seam pulled onto its island" : "");
            } else if (ok > 0 && pulled) {
                unwrap_add_repair(r, c, "%s map folded on this mesh (%s); corners past the seam pulled onto the source "
                                  "island", net >= 0 && !deviates ? "network" : "transferred", why);
            } else if (ok > 0) {
                unwrap_add_repair(r, c, "%s map folded on this mesh (%s); folded faces relaxed locally",
                                  net >= 0 && !deviates ? "network" : "transferred", why);
            } else if (ok == 0 && (ok = reflatten(p, target, scratch, 0, &how)) > 0) {
                repaired[c] = 1;
                unwrap_add_repair(r, c, "%s map folded on this mesh (%s); re-flattened with %s",
                                  net >= 0 && !deviates ? "network" : "transferred", why, how);
            } else if (ok == 0 && !o->refine_on_mesh && can_split_again(depth, c, p, splits, m)) {
                /* Before a flattening that only a similarity places (its
                 * shape is not the island's, so it overlaps the neighbours
                 * and moves): the chart split, each piece mapped again as a
                 * chart of its own, where most keep the map in place. */
                int before = r->n_charts;
                s = split_network_chart(r, c, cap, &model_chart, &depth);
                splits++;
                unwrap_add_repair(r, c, "%s map folded here (%s), anchored LSCM too; split in %d charts mapped "
                                  "again", net >= 0 && !deviates ? "network" : "transferred", why,
                                  r->n_charts - before + 1);
                mem_free(target); mem_free(scratch); mem_free(ext);
                c--;
                continue;
            } else if (ok == 0 && (ok = reflatten(p, target, scratch, 1, &how)) > 0) {
                repaired[c] = 1;
                unwrap_add_repair(r, c, "%s map folded on this mesh (%s); re-flattened with %s",
                                  net >= 0 && !deviates ? "network" : "transferred", why, how);
            } else if (ok == 0) {
                if (p->sub->nf < 2 || splits >= m->nf) {
                    s = error_set(NEUV_ERR_INTERNAL, "chart %d cannot be flattened without folds", c);
                } else {
                    int before = r->n_charts;
                    s = charts_split(m, r->face_chart, &r->n_charts, c);
                    if (s == NEUV_OK && r->n_charts > cap) {
                        int *nm = mem_realloc(model_chart, sizeof(int) * (size_t)r->n_charts);
                        if (nm) model_chart = r->model.source_chart = nm;
                        else s = error_nomem("charts");
                    }
                    for (int k = before; s == NEUV_OK && k < r->n_charts; k++) model_chart[k] = mc;
                    splits++;
                    unwrap_add_repair(r, c, "folded on this mesh (%s) and could not be re-flattened; split into %d charts",
                                      why, r->n_charts - before + 1);
                    c--;
                }
                mem_free(target); mem_free(scratch); mem_free(ext);
                continue;
            }
        }
        mem_free(ext);
        if (ok < 0) s = error_nomem("chart check");
        if (baseline && !relaxed && !repaired[c]) p->source = CHART_SOURCE_LSCM;
        else if (repaired[c]) p->source = CHART_SOURCE_LSCM_AFTER_FOLD;
        else if (net < 0 || from_source || deviates) p->source = CHART_SOURCE_TRANSFERRED;
        else if (repaired[c]) p->source = CHART_SOURCE_LSCM_AFTER_FOLD;
        else p->source = md->refine > 0 || relaxed ? CHART_SOURCE_NETWORK_REFINED : CHART_SOURCE_NETWORK;
        if (s == NEUV_OK && chart_source_is_network(p->source)) s = unwrap_piece_lscm_qce(p);
        if (net >= 0 && !repaired[c] && !baseline && !from_source && !deviates) {
            r->model.network_charts++;
            r->model.heads_solved += head_solved;
        }
        if ((net < 0 || from_source || deviates) && !repaired[c]) r->model.transferred_charts++;
        kept_net[c] = chart_source_is_network(p->source) ? net : -1;
        kept_mirror[c] = kept_net[c] >= 0 && mirror;
        /* A head solved here is the chart's map: kept as a network chart of its own. */
        if (s == NEUV_OK && keep && kept_net[c] >= 0 && head_solved)
            s = param_net_add_chart(keep, net, solved_w, solved_gain, &kept_net[c]);
        mem_free(target); mem_free(scratch);
    }
    r->model.refinement_carried = carry_refinement;
    for (int c = 0; pre && c < n0; c++) presolved_drop(&pre[c]);
    mem_free(pre);
    if (s == NEUV_OK) s = unwrap_assemble_uvs(m, pieces, r->n_charts);
    if (s == NEUV_OK) s = unwrap_keep_provenance(r, pieces);
    mem_free(repaired);
    mem_free(depth);
    mem_free(solved_w);
    if (s == NEUV_OK && o->keep_model) s = keep_chart_nets(r, kept_net, kept_mirror);
    mem_free(kept_net);
    mem_free(kept_mirror);
    r->neural_charts = r->model.network_charts;
    unwrap_stage_time(r, STAGE_PARAM, t);

    /* Corners past a source seam pulled back onto their island where the
     * chart overlaps another or leaves the square. */
    t = now_seconds();
    chart_span *span = NULL;
    if (s == NEUV_OK) s = chart_spans(r, &span);
    r->transforms = mem_calloc((size_t)(r->n_charts > 0 ? r->n_charts : 1), sizeof *r->transforms);
    if (s == NEUV_OK && !r->transforms) s = error_nomem("chart transforms");
    for (int c = 0; s == NEUV_OK && c < r->n_charts; c++) r->transforms[c] = md->xf[model_chart[c]];
    if (s == NEUV_OK && o->keep_model) { /* the packing starts from the source atlas's frame: its transforms come first */
        r->frame_xf = mem_alloc(sizeof *r->frame_xf * (size_t)(r->n_charts > 0 ? r->n_charts : 1));
        if (!r->frame_xf) s = error_nomem("chart transforms");
        else memcpy(r->frame_xf, r->transforms, sizeof *r->frame_xf * (size_t)r->n_charts);
    }
    /* On a simplified copy's model the copy's layout does not matter, and
     * pulling corners flattens border faces (camelhead: qce_mean 1.020 ->
     * 1.027): the shrinking alone resolves overlaps there. */
    if (s == NEUV_OK && !o->refine_on_mesh) s = pull_past_borders(r, span, pieces, anchor, model_chart, vertex_chart);
    mem_free(span);
    for (int c = 0; c < cap; c++) { unwrap_piece_clear(&pieces[c]); mem_free(anchor[c]); }
    mem_free(pieces);
    mem_free(anchor);
    /* What carried the source's charts here is not needed past this stage. */
    mem_free(r->model.source_chart);
    mem_free(r->model.vertex_source_chart);
    r->model.source_chart = r->model.vertex_source_chart = NULL;
    unwrap_stage_time(r, STAGE_REPAIR, t);
    return s;
}


neuv_status unwrap_apply_place(struct neuv_unwrap_result *r, const unwrap_apply_options *o)
{
    neuv_mesh *m = r->mesh;
    double t = now_seconds();
    /* The whole atlas: no chart on another, inside the unit square, each
     * chart where the source put it. */
    log_progress("pack", 0, "%d charts where the model's atlas has them", r->n_charts);
    chart_span *span = NULL;
    neuv_status s = chart_spans(r, &span);
    if (s == NEUV_OK) pull_charts_inside(r, span);
    if (s == NEUV_OK) s = resolve_overlaps(r, span);
    if (s == NEUV_OK) fit_unit_square(r, span);
    if (s == NEUV_OK && !o->refine_on_mesh) s = place_in_free_space(r, span);
    if (s == NEUV_OK && o->refine_on_mesh) { /* a copy's layout is nobody's texture: a fresh packing when needed */
        uv_coverage cov;
        s = uv_coverage_count(m->uv, m->nf, m->tri_uv, NULL, OVERLAP_RESOLUTION, &cov);
        if (s == NEUV_OK && cov.overlapped > 0) {
            atlas_pack_options pk;
            atlas_pack_options_default(&pk);
            pk.resolution = r->opts.resolution;
            pk.padding = r->opts.padding;
            pk.keep_scale = 1;
            s = atlas_pack(m, r->face_chart, r->n_charts, &pk, r->transforms, &r->pack);
            r->model.repacked = 1;
            unwrap_add_repair(r, -1, "charts still overlapped after shrinking; atlas packed afresh (the simplified "
                              "copy's layout is not kept)");
        }
    }
    for (int c = 0; s == NEUV_OK && c < r->n_charts; c++) r->model.moved_charts += span[c].moved;
    mem_free(span);
    if (s == NEUV_OK) {
        uv_coverage cov;
        s = uv_coverage_count(m->uv, m->nf, m->tri_uv, NULL, OVERLAP_RESOLUTION, &cov);
        if (s == NEUV_OK && cov.overlapped > 0)
            unwrap_add_repair(r, -1, "%lld overlapped pixel centres remain (at %d px) after the charts were shrunk",
                              cov.overlapped, OVERLAP_RESOLUTION);
    }
    unwrap_stage_time(r, STAGE_PACK, t);
    return s;
}


static void opts_from_model(neuv_unwrap_options *opts, const unwrap_model *md)
{
    neuv_unwrap_options_init(opts);
    opts->method = md->method;
    opts->preset = md->preset;
    opts->seed = md->seed;
    opts->refine = md->refine;
    opts->resolution = md->resolution;
    opts->padding = md->padding;
}

neuv_status unwrap_apply(const neuv_mesh *mesh, const unwrap_model *md, const unwrap_apply_options *o,
                         neuv_unwrap_result **out)
{
    *out = NULL;
    if (!mesh || mesh->nf == 0) return error_set(NEUV_ERR_INPUT, "no faces: neuv needs a triangle mesh");
    unwrap_apply_options def = {0, 1, 0, 0, 0, 0, 0, NULL};
    if (!o) o = &def;
    neuv_unwrap_options opts;
    opts_from_model(&opts, md);
    opts.threads = o->threads;
    opts.use_cache = o->use_cache;
    if (o->refine_on_mesh) opts.texels_per_unit = o->texels_per_unit;
    struct neuv_unwrap_result *r = NULL;
    neuv_status s = unwrap_result_new(&opts, &r);
    if (s != NEUV_OK) return s;
    r->model.used = 1;
    unwrap_plan plan = {md, 0, 0, o};
    s = unwrap_run_stages(r, mesh, &plan);
    if (s != NEUV_OK) { neuv_unwrap_result_free(r); return s; }
    *out = r;
    return NEUV_OK;
}

neuv_status unwrap_budgeted(const neuv_mesh *mesh, const neuv_unwrap_options *opts, int train_faces,
                            unwrap_model **model_out, neuv_unwrap_result **out)
{
    *out = NULL;
    if (model_out) *model_out = NULL;
    if (!mesh || train_faces <= 0 || mesh->nf <= train_faces) {
        neuv_status s = unwrap_train(mesh, opts, model_out != NULL, out);
        if (s || !model_out) return s;
        s = unwrap_model_from_result(*out, model_out);
        if (s) { neuv_unwrap_result_free(*out); *out = NULL; }
        return s;
    }
    if (model_out && opts && opts->texels_per_unit > 0)
        return error_set(NEUV_ERR_INPUT, "texels_per_unit cannot be used with keep_model: a model records a layout "
                                         "in one square, not in tiles");
    if (opts && (opts->seam_angle != 0 || opts->seam_edge_count != 0))
        return error_set(NEUV_ERR_INPUT, "required seams (--seam-angle) need the networks trained on this mesh, "
                                         "not on a simplified copy: it has %d faces, over train_faces %d "
                                         "(--train-faces 0 trains on it)", mesh->nf, train_faces);
    double t = now_seconds();
    log_progress("simplify", 0, "%d faces to about %d", mesh->nf, train_faces);
    neuv_mesh *copy = mesh_clone(mesh);
    if (!copy) return error_nomem("the mesh");
    mesh_set_uv(copy, 0, NULL, NULL);
    neuv_mesh *small = NULL;
    neuv_status s = mesh_simplify(copy, (double)train_faces / mesh->nf, &small);
    mesh_free(copy);
    if (s) return s;
    double simplify_seconds = now_seconds() - t;
    log_message(NEUV_LOG_INFO, "training on a simplified copy: %d of %d faces", small->nf, mesh->nf);
    neuv_unwrap_result *tr = NULL;
    /* The copy's layout is nobody's texture, and its model carries one square:
     * the texel density is the full mesh's packing's. */
    neuv_unwrap_options copy_opts;
    if (opts) copy_opts = *opts;
    else neuv_unwrap_options_init(&copy_opts);
    copy_opts.texels_per_unit = 0;
    s = unwrap_train(small, &copy_opts, 1, &tr);
    int small_faces = small->nf;
    mesh_free(small);
    if (s) return s;
    unwrap_model *md = NULL;
    s = unwrap_model_from_result(tr, &md);
    double train_seconds = now_seconds() - t;
    if (s == NEUV_OK) {
        /* A model kept of this run is the full mesh's (below): the heads
         * solved here join the copy's networks as charts of their own. */
        unwrap_apply_options ao = {opts ? opts->threads : 0, opts ? opts->use_cache : 1, 0, 1, 0,
                                   opts ? opts->texels_per_unit : 0, model_out != NULL, model_out ? md->param : NULL};
        s = unwrap_apply(mesh, md, &ao, out);
    }
    if (s == NEUV_OK) {
        struct neuv_unwrap_result *r = *out;
        r->opts = tr->opts;
        r->opts.texels_per_unit = opts ? opts->texels_per_unit : 0;
        r->model.trained_on_copy = 1;
        r->model.train_faces = small_faces;
        r->model.train_seconds = train_seconds;
        r->model.copy_simplify_seconds = simplify_seconds;
        memcpy(r->model.copy_seconds, tr->seconds, sizeof r->model.copy_seconds);
        r->patches = tr->patches;
        r->patch_iterations = tr->patch_iterations;
        r->patch_iters_per_second = tr->patch_iters_per_second;
        r->param_iterations = tr->param_iterations;
        r->param_face_points = tr->param_face_points;
        r->param_loss = tr->param_loss;
        r->total_seconds += train_seconds;
        for (int i = 0; i < tr->n_repairs; i++)
            unwrap_add_repair(r, -1, "while training on the copy: chart %d: %.120s", tr->repairs[i].chart,
                              tr->repairs[i].what);
        if (r->repairs_lost) {
            s = error_nomem("a repair note");
            neuv_unwrap_result_free(r);
            *out = NULL;
        }
    }
    neuv_unwrap_result_free(tr);
    if (s == NEUV_OK && model_out) {
        /* The model saved is the full mesh's atlas, not the copy's layout
         * (nobody's texture): its charts, the packing's transforms composed
         * with the copy's, and the networks trained on the copy with the
         * heads solved here, so that applied to another triangulation it
         * gives back this atlas. */
        struct neuv_unwrap_result *r = *out;
        r->param = md->param;
        md->param = NULL;
        r->patchnet = md->patchnet;
        md->patchnet = NULL;
        s = unwrap_model_from_result(r, model_out);
        if (s) { neuv_unwrap_result_free(r); *out = NULL; }
    }
    unwrap_model_free(md);
    return s;
}
