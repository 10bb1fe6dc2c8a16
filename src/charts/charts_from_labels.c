/* Charts from a per-face label: pieces, fragment merging, disks, and a
 * final check of every chart with the mesh topology code. */
#include "charts/charts.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "charts/chart_steps.h"
#include "charts/face_graph.h"
#include "core/error.h"
#include "core/mem.h"
#include "core/union_find.h"
#include "mesh/topology.h"

void charts_default_options(charts_options *o)
{
    /* 0.2% of the area: see the test and report for the measurement. */
    o->min_area_share = 0.002;
    /* Smoothing usually settles in under 10 sweeps; the cap only bounds
     * the work on pathological input. */
    o->smooth_sweeps = 50;
}

/* Step (a): faces joined across manifold edges with equal labels. */
static int label_pieces(const face_graph *g, const int *face_label, int *piece)
{
    union_find u;
    if (uf_init(&u, g->nf) != 0) return -1;
    for (int f = 0; f < g->nf; f++)
        for (int k = 0; k < 3; k++) {
            int o = g->adj[3 * f + k];
            if (o > f && face_label[o] == face_label[f]) uf_union(&u, f, o);
        }
    int n = uf_labels(&u, piece);
    uf_free(&u);
    return n;
}

/* The final check, by the mesh topology code rather than the charts' own:
 * every face in a chart, and every chart one boundary loop of distinct
 * vertices around a genus-0 surface. */
static neuv_status verify_charts(const neuv_mesh *m, const int *face_chart, int n_charts)
{
    for (int f = 0; f < m->nf; f++)
        if (face_chart[f] < 0 || face_chart[f] >= n_charts)
            return error_set(NEUV_ERR_INTERNAL, "face %d has no chart", f);
    unsigned char *seen = mem_calloc((size_t)(m->nv > 0 ? m->nv : 1), 1);
    int *start = mem_calloc((size_t)n_charts + 1, sizeof(int));
    int *faces = mem_alloc(sizeof(int) * (size_t)m->nf);
    if (!seen || !start || !faces) {
        mem_free(seen); mem_free(start); mem_free(faces);
        return error_nomem("chart check");
    }
    /* Face lists per chart (counting sort), so the check stays linear. */
    for (int f = 0; f < m->nf; f++) start[face_chart[f] + 1]++;
    for (int c = 0; c < n_charts; c++) start[c + 1] += start[c];
    for (int f = 0; f < m->nf; f++) faces[start[face_chart[f]]++] = f;
    for (int c = n_charts; c > 0; c--) start[c] = start[c - 1];
    start[0] = 0;
    neuv_status st = NEUV_OK;
    for (int c = 0; c < n_charts && st == NEUV_OK; c++) {
        const int *cf = faces + start[c];
        int n = start[c + 1] - start[c];
        component_topology t;
        if (mesh_faces_topology(m, cf, n, &t) != NEUV_OK) { st = error_nomem("chart check"); break; }
        int *ls = NULL, *lv = NULL;
        int loops = mesh_faces_boundary_loops(m, cf, n, &ls, &lv);
        if (loops < 0) { st = error_nomem("chart check"); break; }
        int simple = 1;
        if (loops == 1) {
            for (int i = ls[0]; i < ls[1]; i++) {
                if (seen[lv[i]]) simple = 0;
                seen[lv[i]] = 1;
            }
            for (int i = ls[0]; i < ls[1]; i++) seen[lv[i]] = 0;
        }
        mem_free(ls); mem_free(lv);
        if (n == 0 || t.boundary_loops != 1 || loops != 1 || t.genus != 0 || t.euler != 1 || !simple)
            st = error_set(NEUV_ERR_INTERNAL,
                           "chart %d is not a disk (%d faces, %d loops, genus %d, euler %d, %s boundary)", c,
                           n, loops, t.genus, t.euler, simple ? "simple" : "pinched");
    }
    mem_free(seen); mem_free(start); mem_free(faces);
    return st;
}

neuv_status charts_from_labels(const neuv_mesh *m, const int *face_label,
                               const charts_options *opts, int *face_chart,
                               int *n_charts, charts_report *report)
{
    charts_options o;
    charts_default_options(&o);
    if (opts) o = *opts;
    if (!m || !face_label || !face_chart || !n_charts)
        return error_set(NEUV_ERR_INPUT, "charts_from_labels: missing mesh, labels or output");
    if (o.smooth_sweeps < 0)
        return error_set(NEUV_ERR_INPUT, "smoothing sweeps %d is negative", o.smooth_sweeps);
    if (!(o.min_area_share >= 0.0 && o.min_area_share < 1.0))
        return error_set(NEUV_ERR_INPUT, "minimum chart area share %g is outside [0, 1)", o.min_area_share);
    for (int f = 0; f < m->nf; f++)
        if (face_label[f] < 0)
            return error_set(NEUV_ERR_INPUT, "face %d has label %d; labels must be >= 0", f, face_label[f]);
    charts_report rep;
    memset(&rep, 0, sizeof rep);
    *n_charts = 0;
    if (m->nf == 0) {
        if (report) *report = rep;
        return NEUV_OK;
    }
    face_graph g;
    neuv_status st = face_graph_build(m, &g);
    if (st != NEUV_OK) return st;
    int n = label_pieces(&g, face_label, face_chart);
    if (n < 0) { face_graph_free(&g); return error_nomem("chart pieces"); }
    rep.pieces = n;
    double total = 0.0;
    for (int f = 0; f < m->nf; f++) total += g.area[f];
    st = charts_merge_fragments(m, &g, face_chart, &n, o.min_area_share * total, &rep.merged);
    if (st == NEUV_OK) st = charts_make_disks(m, &g, face_chart, &n, -1, &rep);
    face_graph_free(&g);
    if (st != NEUV_OK) return st;
    n = charts_renumber(m->nf, face_chart);
    if (n < 0) return error_nomem("chart ids");
    if (o.smooth_sweeps > 0) {
        /* Smoothing is checked locally; should the global check still
         * reject its result, the unsmoothed charts (already disks) stand. */
        int *before = mem_alloc(sizeof(int) * (size_t)m->nf);
        if (!before) return error_nomem("chart smoothing");
        memcpy(before, face_chart, sizeof(int) * (size_t)m->nf);
        st = charts_smooth_boundaries(m, NULL, face_chart, o.smooth_sweeps, &rep.smoothed);
        if (st == NEUV_OK && rep.smoothed > 0) {
            neuv_status v = verify_charts(m, face_chart, n);
            if (v == NEUV_ERR_NOMEM) st = v;
            else if (v != NEUV_OK) {
                memcpy(face_chart, before, sizeof(int) * (size_t)m->nf);
                rep.smoothed = 0;
            }
        }
        mem_free(before);
        if (st != NEUV_OK) return st;
    }
    st = verify_charts(m, face_chart, n);
    if (st != NEUV_OK) return st;
    rep.charts = n;
    *n_charts = n;
    if (report) *report = rep;
    return NEUV_OK;
}
