/* neuv geodesics IN --from V [--json]
 * Heat-method geodesic distance from one vertex to every vertex. V and the
 * output follow the input file's vertex numbering: the distances are computed
 * on the cleaned mesh and read back through equal positions. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/commands.h"
#include "core/json_writer.h"
#include "core/timer.h"
#include "geometry/heat_geodesics.h"
#include "mesh/clean.h"

static const double *sort_pos; /* qsort has no user pointer */

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
    int *order = malloc(sizeof(int) * (size_t)(clean->nv > 0 ? clean->nv : 1));
    int *map = malloc(sizeof(int) * (size_t)(orig->nv > 0 ? orig->nv : 1));
    if (!order || !map) { free(order); free(map); return NULL; }
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
    free(order);
    return map;
}

int cmd_geodesics(int argc, char **argv)
{
    const char *in = NULL;
    int from = -1, have_from = 0, json = 0, bad = 0;
    for (int i = 1; i < argc && !bad; i++) {
        if (cli_arg_global(argc, argv, &i, &bad)) continue;
        if (cli_arg_int(argc, argv, &i, "--from", &from, &bad)) { have_from = 1; continue; }
        if (!strcmp(argv[i], "--json")) { json = 1; continue; }
        if (argv[i][0] == '-' && argv[i][1]) return cli_error(NULL, "geodesics: unknown option '%s'", argv[i]);
        if (in) return cli_error(NULL, "geodesics: one input file expected, got '%s' and '%s'", in, argv[i]);
        in = argv[i];
    }
    if (bad) return 2;
    if (!in || !have_from) return cli_error(NULL, "usage: neuv geodesics IN --from V [--json]");

    double t0 = now_seconds();
    neuv_mesh *orig = NULL;
    neuv_status st = neuv_mesh_load(in, cli_callbacks(), &orig);
    if (st) return cli_fail(in, st);
    if (from < 0 || from >= orig->nv) {
        int nv = orig->nv;
        mesh_free(orig);
        return cli_error(in, "--from %d is out of range: the mesh has %d vertices (0 to %d)", from, nv, nv - 1);
    }
    neuv_mesh *m = mesh_clone(orig);
    if (!m) { mesh_free(orig); return cli_error(in, "out of memory"); }
    mesh_clean_report rep;
    st = mesh_clean(m, NULL, &rep);
    int *map = st ? NULL : match_vertices(orig, m);
    if (st || !map) {
        mesh_free(orig); mesh_free(m);
        return st ? cli_fail(in, st) : cli_error(in, "out of memory");
    }
    if (map[from] < 0) {
        mesh_free(orig); mesh_free(m); free(map);
        return cli_error(in, "vertex %d is used by no face, so it has no geodesic distances", from);
    }
    heat_geodesics *g = NULL;
    double *d = malloc(sizeof(double) * (size_t)m->nv);
    if (!d) st = NEUV_ERR_NOMEM;
    if (!st) st = heat_geodesics_create(m, 1.0, &g);
    if (!st) st = heat_geodesics_from_vertex(g, map[from], d);
    double seconds = now_seconds() - t0;
    int rc = 0;
    if (st) {
        rc = cli_fail(in, st);
    } else {
        int nv = orig->nv, reached = 0;
        double dmax = 0;
        for (int v = 0; v < nv; v++) {
            double x = map[v] >= 0 ? d[map[v]] : INFINITY;
            if (isfinite(x)) { reached++; if (x > dmax) dmax = x; }
        }
        if (json) {
            json_writer w;
            json_init(&w);
            json_begin_object(&w);
            json_key(&w, "input"); json_string(&w, in);
            json_key(&w, "source"); json_int(&w, from);
            json_key(&w, "distances");
            json_begin_array(&w);
            for (int v = 0; v < nv; v++) json_number(&w, map[v] >= 0 ? d[map[v]] : INFINITY); /* unreachable: null */
            json_end_array(&w);
            json_key(&w, "seconds"); json_number(&w, seconds);
            json_end_object(&w);
            if (w.failed) rc = cli_error(NULL, "out of memory writing the JSON output");
            else printf("%s\n", json_text(&w));
            json_free(&w);
        } else {
            printf("%s: %d vertices, heat-method geodesics from vertex %d (t = %.6g)\n", in, nv, from,
                   heat_geodesics_time(g));
            printf("  reached %d of %d vertices, farthest at distance %.6g, %.3f s\n", reached, nv, dmax, seconds);
            int show = nv < 10 ? nv : 10;
            printf("  vertex  distance\n");
            for (int v = 0; v < show; v++) {
                double x = map[v] >= 0 ? d[map[v]] : INFINITY;
                if (isfinite(x)) printf("  %6d  %.6g\n", v, x);
                else printf("  %6d  -\n", v);
            }
            if (nv > show) printf("  ... %d more (all of them with --json)\n", nv - show);
        }
    }
    heat_geodesics_free(g);
    free(d); free(map);
    mesh_free(m); mesh_free(orig);
    return rc;
}
