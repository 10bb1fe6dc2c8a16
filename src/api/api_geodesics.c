/* Public geodesic distances from one vertex (`neuv geodesics`): the heat
 * method on a cleaned copy, read back in the caller's vertex numbering. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "neuv/neuv.h"
#include "api/api_json.h"
#include "core/error.h"
#include "core/log.h"
#include "core/mem.h"
#include "geometry/heat_geodesics.h"
#include "mesh/clean.h"

static _Thread_local const double *sort_pos; /* qsort has no user pointer */

static int cmp_pos(const void *a, const void *b)
{
    const double *p = sort_pos + 3 * *(const int *)a, *q = sort_pos + 3 * *(const int *)b;
    for (int k = 0; k < 3; k++)
        if (p[k] != q[k]) return p[k] < q[k] ? -1 : 1;
    return 0;
}

/* For each vertex of `orig`, a vertex of `clean` at exactly the same
 * position, or -1 (the vertex was dropped: used by no face). */
static int *match_vertices(const neuv_mesh *orig, const neuv_mesh *clean)
{
    int *order = mem_alloc(sizeof(int) * (size_t)(clean->nv > 0 ? clean->nv : 1));
    int *map = mem_alloc(sizeof(int) * (size_t)(orig->nv > 0 ? orig->nv : 1));
    if (!order || !map) { mem_free(order); mem_free(map); return NULL; }
    for (int v = 0; v < clean->nv; v++) order[v] = v;
    sort_pos = clean->pos;
    qsort(order, (size_t)clean->nv, sizeof *order, cmp_pos);
    for (int v = 0; v < orig->nv; v++) {
        const double *p = orig->pos + 3 * v;
        int lo = 0, hi = clean->nv - 1;
        map[v] = -1;
        while (lo <= hi) {
            int mid = (lo + hi) / 2, c = 0;
            const double *q = clean->pos + 3 * order[mid];
            for (int k = 0; k < 3 && !c; k++) c = p[k] < q[k] ? -1 : p[k] > q[k] ? 1 : 0;
            if (c == 0) { map[v] = order[mid]; break; }
            if (c < 0) hi = mid - 1; else lo = mid + 1;
        }
    }
    mem_free(order);
    return map;
}

static neuv_status distances_on(const neuv_mesh *orig, int source, double *distances, double *time)
{
    neuv_mesh *m = mesh_clone(orig);
    if (!m) return error_set(NEUV_ERR_NOMEM, "out of memory");
    mesh_clean_report rep;
    neuv_status s = mesh_clean(m, NULL, &rep);
    int *map = NULL;
    if (s == NEUV_OK && !(map = match_vertices(orig, m))) s = error_set(NEUV_ERR_NOMEM, "out of memory");
    if (s == NEUV_OK && map[source] < 0)
        s = error_set(NEUV_ERR_INPUT, "vertex %d is used by no face, so it has no geodesic distances", source);
    double *d = NULL;
    heat_geodesics *g = NULL;
    if (s == NEUV_OK && !(d = mem_alloc(sizeof(double) * (size_t)(m->nv > 0 ? m->nv : 1))))
        s = error_set(NEUV_ERR_NOMEM, "out of memory");
    if (s == NEUV_OK) s = heat_geodesics_create(m, 1.0, &g);
    if (s == NEUV_OK) s = heat_geodesics_from_vertex(g, map[source], d);
    if (s == NEUV_OK) {
        for (int v = 0; v < orig->nv; v++) distances[v] = map[v] >= 0 ? d[map[v]] : INFINITY;
        if (time) *time = heat_geodesics_time(g);
    }
    heat_geodesics_free(g);
    mem_free(d);
    mem_free(map);
    mesh_free(m);
    return s;
}

neuv_status neuv_geodesic_distances(const neuv_mesh *mesh, int source, const neuv_callbacks *cb, double *distances,
                                    double *time)
{
    if (!mesh || !distances) return error_set(NEUV_ERR_INPUT, "neuv_geodesic_distances: no mesh or no output");
    if (source < 0 || source >= mesh->nv)
        return error_set(NEUV_ERR_INPUT, "source vertex %d is out of range: the mesh has %d vertices", source, mesh->nv);
    log_scope scope;
    log_scope_open(&scope, cb);
    neuv_status s = distances_on(mesh, source, distances, time);
    log_scope_close(&scope);
    return s;
}

char *neuv_geodesics_json(const char *input_name, int source, const double *distances, int count, double seconds)
{
    if (!distances && count > 0) { error_set(NEUV_ERR_INPUT, "neuv_geodesics_json: no distances"); return NULL; }
    json_writer w;
    json_init(&w);
    json_begin_object(&w);
    json_key(&w, "input"); json_string(&w, input_name ? input_name : "");
    json_key(&w, "source"); json_int(&w, source);
    json_key(&w, "distances");
    json_begin_array(&w);
    for (int v = 0; v < count; v++) json_number(&w, distances[v]); /* not reached: null */
    json_end_array(&w);
    json_key(&w, "seconds"); json_number(&w, seconds);
    json_end_object(&w);
    return api_json_finish(&w);
}
