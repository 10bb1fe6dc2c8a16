/* Splitting one chart in two, for the stages that find a chart too
 * distorted once flattened (the auto-K loop, the repair stage). */
#include "charts/charts.h"

#include <stdlib.h>

#include "charts/chart_local.h"
#include "charts/chart_steps.h"
#include "core/error.h"

neuv_status charts_split(const neuv_mesh *m, int *face_chart, int *n_charts, int chart_id)
{
    if (!m || !face_chart || !n_charts)
        return neuv_fail(NEUV_ERR_INPUT, "charts_split: missing mesh, charts or count");
    if (chart_id < 0 || chart_id >= *n_charts)
        return neuv_fail(NEUV_ERR_INPUT, "chart %d does not exist (%d charts)", chart_id, *n_charts);
    int n = 0;
    for (int f = 0; f < m->nf; f++) {
        if (face_chart[f] < 0 || face_chart[f] >= *n_charts)
            return neuv_fail(NEUV_ERR_INPUT, "face %d has chart %d, outside 0..%d", f, face_chart[f],
                             *n_charts - 1);
        n += face_chart[f] == chart_id;
    }
    if (n < 2) return neuv_fail(NEUV_ERR_INPUT, "chart %d has %d face(s); splitting needs two", chart_id, n);
    int *faces = malloc(sizeof(int) * (size_t)n);
    int *part = malloc(sizeof(int) * (size_t)n);
    int *comp = malloc(sizeof(int) * (size_t)n);
    face_graph g = {0};
    chart_scratch s = {0};
    chart_local L = {0};
    neuv_status st = NEUV_OK;
    if (!faces || !part || !comp) { st = neuv_fail_nomem("chart split"); goto done; }
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
    if (parts < 0) { st = neuv_fail_nomem("chart split"); goto done; }
    int nc = *n_charts;
    for (int i = 0; i < n; i++)
        face_chart[faces[i]] = comp[i] == 0 ? chart_id : nc + comp[i] - 1;
    int first_new = nc;
    nc += parts - 1;
    /* The parts are then made disks; only they can have changed. */
    if ((st = charts_make_disks(m, &g, face_chart, &nc, chart_id, NULL)) != NEUV_OK) goto done;
    for (int c = first_new; c < first_new + parts - 1 && st == NEUV_OK; c++)
        st = charts_make_disks(m, &g, face_chart, &nc, c, NULL);
    *n_charts = nc;
done:
    chart_local_free(&L);
    chart_scratch_free(&s);
    face_graph_free(&g);
    free(faces); free(part); free(comp);
    return st;
}
