/* Splitting one chart in two, for the stages that find a chart too
 * distorted once flattened (the auto-K loop, the repair stage). */
#include "charts/charts.h"

#include <stdlib.h>
#include <string.h>

#include "charts/chart_local.h"
#include "charts/chart_steps.h"
#include "core/error.h"
#include "core/mem.h"

/* Smooths the boundaries between the parts of a split (chart_id and the
 * ids from first_new on): the regions grown on the face graph meet along a
 * saw-tooth. Other charts neither give nor take faces, so their flattenings
 * stay valid. Should a part fail the disk check after all, the unsmoothed
 * parts stand. */
static neuv_status smooth_parts(const neuv_mesh *m, int *face_chart, int nc, int chart_id, int first_new)
{
    int *active = mem_calloc((size_t)nc, sizeof(int));
    int *before = mem_alloc(sizeof(int) * (size_t)m->nf);
    if (!active || !before) { mem_free(active); mem_free(before); return error_nomem("chart smoothing"); }
    active[chart_id] = 1;
    for (int c = first_new; c < nc; c++) active[c] = 1;
    memcpy(before, face_chart, sizeof(int) * (size_t)m->nf);
    int moves = 0;
    neuv_status st = charts_smooth_boundaries(m, active, face_chart, 50, &moves);
    for (int c = 0; c < nc && st == NEUV_OK && moves > 0; c++) {
        if (!active[c]) continue;
        int d = chart_is_disk(m, face_chart, c);
        if (d < 0) st = error_nomem("chart smoothing");
        if (d == 0) { memcpy(face_chart, before, sizeof(int) * (size_t)m->nf); break; }
    }
    mem_free(active); mem_free(before);
    return st;
}

neuv_status charts_split(const neuv_mesh *m, int *face_chart, int *n_charts, int chart_id)
{
    if (!m || !face_chart || !n_charts)
        return error_set(NEUV_ERR_INPUT, "charts_split: missing mesh, charts or count");
    if (chart_id < 0 || chart_id >= *n_charts)
        return error_set(NEUV_ERR_INPUT, "chart %d does not exist (%d charts)", chart_id, *n_charts);
    int n = 0;
    for (int f = 0; f < m->nf; f++) {
        if (face_chart[f] < 0 || face_chart[f] >= *n_charts)
            return error_set(NEUV_ERR_INPUT, "face %d has chart %d, outside 0..%d", f, face_chart[f],
                             *n_charts - 1);
        n += face_chart[f] == chart_id;
    }
    if (n < 2) return error_set(NEUV_ERR_INPUT, "chart %d has %d face(s); splitting needs two", chart_id, n);
    int *faces = mem_alloc(sizeof(int) * (size_t)n);
    int *part = mem_alloc(sizeof(int) * (size_t)n);
    int *comp = mem_alloc(sizeof(int) * (size_t)n);
    face_graph g = {0};
    chart_scratch s = {0};
    chart_local L = {0};
    neuv_status st = NEUV_OK;
    if (!faces || !part || !comp) { st = error_nomem("chart split"); goto done; }
    n = 0;
    for (int f = 0; f < m->nf; f++)
        if (face_chart[f] == chart_id) faces[n++] = f;
    if ((st = face_graph_build(m, &g)) != NEUV_OK) goto done;
    if ((st = chart_scratch_init(&s, m->nf, m->nv)) != NEUV_OK) goto done;
    if ((st = chart_local_build(m, &g, faces, n, &s, &L)) != NEUV_OK) goto done;
    if ((st = chart_local_grow2(&L, part)) != NEUV_OK) goto done;
    /* The two regions are each connected, but a chart that was in several
     * parts to begin with keeps them apart: every part gets its own id. */
    int parts = chart_local_components(&L, part, NULL, comp);
    if (parts < 0) { st = error_nomem("chart split"); goto done; }
    int nc = *n_charts;
    for (int i = 0; i < n; i++)
        face_chart[faces[i]] = comp[i] == 0 ? chart_id : nc + comp[i] - 1;
    int first_new = nc;
    nc += parts - 1;
    /* The parts are then made disks; only they can have changed. */
    if ((st = charts_make_disks(m, &g, face_chart, &nc, chart_id, NULL)) != NEUV_OK) goto done;
    for (int c = first_new; c < first_new + parts - 1 && st == NEUV_OK; c++)
        st = charts_make_disks(m, &g, face_chart, &nc, c, NULL);
    if (st == NEUV_OK) st = smooth_parts(m, face_chart, nc, chart_id, first_new);
    *n_charts = nc;
done:
    chart_local_free(&L);
    chart_scratch_free(&s);
    face_graph_free(&g);
    mem_free(faces); mem_free(part); mem_free(comp);
    return st;
}
