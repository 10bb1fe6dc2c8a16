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

static void print_text(const char *in, int from, const double *d, int nv, double t, double seconds)
{
    int reached = 0;
    double dmax = 0;
    for (int v = 0; v < nv; v++)
        if (isfinite(d[v])) { reached++; if (d[v] > dmax) dmax = d[v]; }
    printf("%s: %d vertices, heat-method geodesics from vertex %d (t = %.6g)\n", in, nv, from, t);
    printf("  reached %d of %d vertices, farthest at distance %.6g, %.3f s\n", reached, nv, dmax, seconds);
    int show = nv < 10 ? nv : 10;
    printf("  vertex  distance\n");
    for (int v = 0; v < show; v++) {
        if (isfinite(d[v])) printf("  %6d  %.6g\n", v, d[v]);
        else printf("  %6d  -\n", v);
    }
    if (nv > show) printf("  ... %d more (all of them with --json)\n", nv - show);
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

    double t0 = cli_now_seconds();
    neuv_mesh *m = NULL;
    neuv_status st = neuv_mesh_load(in, cli_callbacks(), &m);
    if (st) return cli_fail(in, st);
    int nv = neuv_mesh_vertex_count(m);
    if (from < 0 || from >= nv) {
        neuv_mesh_free(m);
        return cli_error(in, "--from %d is out of range: the mesh has %d vertices (0 to %d)", from, nv, nv - 1);
    }
    double *d = malloc(sizeof(double) * (size_t)nv), t = 0;
    if (!d) { neuv_mesh_free(m); return cli_error(in, "out of memory"); }
    st = neuv_geodesic_distances(m, from, cli_callbacks(), d, &t);
    neuv_mesh_free(m);
    double seconds = cli_now_seconds() - t0;
    int rc = 0;
    if (st) rc = cli_fail(in, st);
    else if (json) rc = cli_print_document(neuv_geodesics_json(in, from, d, nv, seconds));
    else print_text(in, from, d, nv, t, seconds);
    free(d);
    return rc;
}
