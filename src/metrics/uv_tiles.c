#include "metrics/uv_tiles.h"

#include <math.h>

#include "atlas/uv_charts.h"
#include "core/error.h"
#include "core/mem.h"
#include "metrics/uv_metrics.h"

enum { tiles_side = 10, tiles_max = tiles_side * tiles_side };

static double uv_area(const double *a, const double *b, const double *c)
{
    return 0.5 * fabs((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
}

/* The tile (u0 + 10 v0) that holds every corner of face f, or -1. */
static int face_tile(const neuv_mesh *m, int f)
{
    const double *q[3];
    for (int k = 0; k < 3; k++) q[k] = m->uv + 2 * (size_t)m->tri_uv[3 * f + k];
    int t[2];
    for (int d = 0; d < 2; d++) {
        double c = (q[0][d] + q[1][d] + q[2][d]) / 3;
        if (!(c >= 0 && c < tiles_side)) return -1;
        t[d] = (int)floor(c);
        for (int k = 0; k < 3; k++)
            if (!(q[k][d] >= t[d] - UV_METRICS_UNIT_TOL && q[k][d] <= t[d] + 1 + UV_METRICS_UNIT_TOL)) return -1;
    }
    return t[0] + tiles_side * t[1];
}

neuv_status uv_tiles_compute(const neuv_mesh *m, neuv_uv_tile **tiles, int *count)
{
    *tiles = NULL;
    *count = 0;
    if (!m || m->nuv <= 0 || !m->uv || !m->tri_uv)
        return error_set(NEUV_ERR_INPUT, "the mesh carries no texture coordinates");
    if (m->nf == 0) return NEUV_OK;
    int *chart = mem_alloc(sizeof *chart * (size_t)m->nf);
    int *tile = mem_alloc(sizeof *tile * (size_t)m->nf);
    /* Per tile: faces, area, charts (a bit per chart and tile marks one counted). */
    neuv_uv_tile *all = mem_calloc(tiles_max, sizeof *all);
    unsigned char *bits = NULL;
    neuv_status st = NEUV_OK;
    int nchart = chart ? uv_charts(m, chart) : -1;
    if (!chart || !tile || !all || nchart < 0) { st = error_nomem("UV tiles"); goto done; }
    bits = mem_calloc((size_t)nchart * tiles_max / 8 + 1, 1);
    if (!bits) { st = error_nomem("UV tiles"); goto done; }
    double mean3 = 0;
    for (int f = 0; f < m->nf; f++) mean3 += mesh_face_area(m, f);
    mean3 /= m->nf;
    for (int f = 0; f < m->nf; f++) {
        tile[f] = face_tile(m, f);
        if (tile[f] < 0) goto done; /* not a tile layout: no tiles */
    }
    for (int f = 0; f < m->nf; f++) {
        neuv_uv_tile *t = &all[tile[f]];
        t->faces++;
        if (mesh_face_area(m, f) >= UV_METRICS_AREA_EPS * mean3) {
            const int *c = m->tri_uv + 3 * (size_t)f;
            t->efficiency += uv_area(m->uv + 2 * (size_t)c[0], m->uv + 2 * (size_t)c[1], m->uv + 2 * (size_t)c[2]);
        }
        size_t bit = (size_t)chart[f] * tiles_max + (size_t)tile[f];
        if (!(bits[bit / 8] & (1u << (bit % 8)))) { bits[bit / 8] |= (unsigned char)(1u << (bit % 8)); t->charts++; }
    }
    int n = 0;
    for (int k = 0; k < tiles_max; k++) n += all[k].faces > 0;
    *tiles = mem_alloc(sizeof **tiles * (size_t)n);
    if (!*tiles) { st = error_nomem("UV tiles"); goto done; }
    for (int k = 0, i = 0; k < tiles_max; k++) {
        if (all[k].faces == 0) continue;
        all[k].udim = 1001 + k;
        (*tiles)[i++] = all[k];
    }
    *count = n;
done:
    mem_free(chart); mem_free(tile); mem_free(all); mem_free(bits);
    return st;
}

void uv_tiles_write_json(const neuv_uv_tile *tiles, int count, json_writer *w)
{
    json_begin_array(w);
    for (int i = 0; i < count; i++) {
        json_begin_object(w);
        json_key(w, "udim"); json_int(w, tiles[i].udim);
        json_key(w, "charts"); json_int(w, tiles[i].charts);
        json_key(w, "faces"); json_int(w, tiles[i].faces);
        json_key(w, "efficiency"); json_number(w, tiles[i].efficiency);
        json_end_object(w);
    }
    json_end_array(w);
}
