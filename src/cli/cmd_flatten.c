/* neuv flatten IN --method lscm|harmonic -o OUT
 * Classic flattening of a mesh that is one topological disk; the UVs are
 * scaled into [0,1]² keeping their aspect ratio. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/commands.h"
#include "core/timer.h"
#include "flatten/disk_topology.h"
#include "flatten/harmonic.h"
#include "flatten/lscm.h"
#include "mesh/clean.h"
#include "metrics/uv_metrics.h"

/* Uniform scale and shift of uv (#V by 2) into [0,1]², keeping the aspect. */
static void fit_unit_square(int nv, double *uv)
{
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (int v = 0; v < nv; v++)
        for (int c = 0; c < 2; c++) {
            lo[c] = fmin(lo[c], uv[2 * v + c]);
            hi[c] = fmax(hi[c], uv[2 * v + c]);
        }
    double size = fmax(hi[0] - lo[0], hi[1] - lo[1]);
    double s = size > 0 ? 1.0 / size : 1.0;
    for (int v = 0; v < nv; v++)
        for (int c = 0; c < 2; c++) {
            double x = (uv[2 * v + c] - lo[c]) * s;
            uv[2 * v + c] = x < 0 ? 0 : x > 1 ? 1 : x; /* clamp rounding only */
        }
}

int cmd_flatten(int argc, char **argv)
{
    const char *in = NULL, *out = NULL, *method = NULL;
    int bad = 0;
    for (int i = 1; i < argc && !bad; i++) {
        if (cli_arg_global(argc, argv, &i, &bad)) continue;
        if (cli_arg_str(argc, argv, &i, "--method", &method, &bad)) continue;
        if (cli_arg_str(argc, argv, &i, "-o", &out, &bad)) continue;
        if (argv[i][0] == '-' && argv[i][1]) return cli_error(NULL, "flatten: unknown option '%s'", argv[i]);
        if (in) return cli_error(NULL, "flatten: one input file expected, got '%s' and '%s'", in, argv[i]);
        in = argv[i];
    }
    if (bad) return 2;
    if (!in || !out || !method) return cli_error(NULL, "usage: neuv flatten IN --method lscm|harmonic -o OUT");
    int use_lscm = !strcmp(method, "lscm");
    if (!use_lscm && strcmp(method, "harmonic"))
        return cli_error(NULL, "--method expects lscm or harmonic, got '%s'", method);
    if (cli_check_output_not_input(out, in)) return 2;

    double t0 = now_seconds();
    neuv_mesh *m = NULL;
    neuv_clean_report rep;
    int rc = cli_load_clean(in, &m, &rep);
    if (rc) return rc;
    neuv_status st;
    if ((st = flatten_require_disk(m, NULL, NULL))) { mesh_free(m); return cli_fail(in, st); }
    double *uv = malloc(sizeof(double) * 2 * (size_t)m->nv);
    if (!uv) { mesh_free(m); return cli_error(in, "out of memory"); }
    double t1 = now_seconds();
    st = use_lscm ? lscm(m, uv) : harmonic(m, uv);
    double t_flat = now_seconds() - t1;
    if (st) { free(uv); mesh_free(m); return cli_fail(in, st); }
    fit_unit_square(m->nv, uv);
    st = mesh_set_uv(m, m->nv, uv, m->tri);
    free(uv);
    if (st) { mesh_free(m); return cli_fail(in, st); }
    if ((st = neuv_mesh_save(m, out))) { mesh_free(m); return cli_fail(out, st); }
    uv_metrics mt;
    st = uv_metrics_compute(m, &mt);
    if (st) { mesh_free(m); return cli_fail(out, st); }
    printf("%s: %d vertices, %d faces, %s in %.3f s (total %.3f s) -> %s\n", in, m->nv, m->nf, method, t_flat,
           now_seconds() - t0, out);
    printf("  qce_mean %.6g  flipped %d\n", mt.qce_mean, mt.flipped);
    mesh_free(m);
    return 0;
}
