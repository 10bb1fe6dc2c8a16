/* The file's polygons kept whole: every triangle of a polygon in one chart,
 * so that the written file gives each polygon back as it came (a chart
 * border through a quad would leave its two triangles with different UVs
 * at the shared corners, and the quad could only be written as triangles).
 *
 * A split polygon's triangles move, one at a time, to the chart holding
 * most of its area, each move kept only when both charts stay disks
 * (charts/face_move.h); a triangle that cannot move yet may move once its
 * neighbour in the polygon has. What cannot be joined this way (the move
 * would pinch or empty a chart) stays split and is counted. */
#include "charts/charts.h"

#include "charts/face_graph.h"
#include "charts/face_move.h"
#include "core/error.h"

/* Moves the triangles of faces [f0, f1) that are not in chart `to` there,
 * as far as the disk test allows. Returns the triangles left outside. */
static int gather(const neuv_mesh *m, const face_graph *g, const face_star *s, int *face_chart, int f0, int f1,
                  int to)
{
    int outside = 0, moved = 1;
    while (moved) {
        moved = 0;
        outside = 0;
        for (int f = f0; f < f1; f++) {
            int from = face_chart[f];
            if (from == to) continue;
            if (face_move_keeps_disk(m, g, s, face_chart, f, from, 1) &&
                face_move_keeps_disk(m, g, s, face_chart, f, to, 0)) {
                face_chart[f] = to;
                moved = 1;
            } else {
                outside++;
            }
        }
    }
    return outside;
}

/* The chart holding the most area of faces [f0, f1) among those not yet
 * tried (tried[k] for the up to 8 charts seen), or -1. */
static int largest_share(const face_graph *g, const int *face_chart, int f0, int f1, const int *tried, int n_tried)
{
    int best = -1;
    double best_area = -1;
    for (int f = f0; f < f1; f++) {
        int c = face_chart[f], seen = 0;
        for (int k = 0; k < n_tried; k++) seen |= tried[k] == c;
        if (seen) continue;
        double area = 0;
        for (int h = f0; h < f1; h++)
            if (face_chart[h] == c) area += g->area[h];
        if (area > best_area || (area == best_area && c < best)) { best = c; best_area = area; }
    }
    return best;
}

neuv_status charts_keep_polygons(const neuv_mesh *m, const int *face_polygon, const int *active, int *face_chart,
                                 int *split_left)
{
    if (split_left) *split_left = 0;
    if (!m || !face_polygon || !face_chart)
        return error_set(NEUV_ERR_INPUT, "charts_keep_polygons: missing mesh, polygons or charts");
    face_graph g;
    neuv_status st = face_graph_build(m, &g);
    if (st != NEUV_OK) return st;
    face_star s = {0};
    if ((st = face_star_build(m, &g, &s)) != NEUV_OK) { face_graph_free(&g); return st; }
    int left = 0;
    for (int f0 = 0, f1; f0 < m->nf; f0 = f1) {
        /* A polygon's triangles are consecutive faces. */
        int whole = 1, movable = 1;
        for (f1 = f0 + 1; f1 < m->nf && face_polygon[f1] == face_polygon[f0]; f1++) whole &= face_chart[f1] == face_chart[f0];
        if (whole || face_polygon[f0] < 0) continue;
        for (int f = f0; f < f1; f++) movable &= !active || active[face_chart[f]];
        int tried[8], n_tried = 0, outside = 1;
        while (movable && outside > 0 && n_tried < 8) {
            int to = largest_share(&g, face_chart, f0, f1, tried, n_tried);
            if (to < 0) break;
            tried[n_tried++] = to;
            outside = gather(m, &g, &s, face_chart, f0, f1, to);
        }
        left += !movable || outside > 0;
    }
    face_star_free(&s);
    face_graph_free(&g);
    if (split_left) *split_left = left;
    return NEUV_OK;
}

int charts_count_split_polygons(int nf, const int *face_polygon, const int *face_chart)
{
    int n = 0;
    for (int f0 = 0, f1; f0 < nf; f0 = f1) {
        int whole = 1;
        for (f1 = f0 + 1; f1 < nf && face_polygon[f1] == face_polygon[f0]; f1++) whole &= face_chart[f1] == face_chart[f0];
        n += !whole && face_polygon[f0] >= 0;
    }
    return n;
}
