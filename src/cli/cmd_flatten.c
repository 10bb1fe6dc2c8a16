/* neuv flatten IN --method lscm|harmonic -o OUT
 * Classic flattening of a mesh that is one topological disk; the UVs are
 * scaled into [0,1]² keeping their aspect ratio. */
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/commands.h"

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

    double t0 = cli_now_seconds();
    neuv_mesh *m = NULL;
    neuv_clean_report rep;
    int rc = cli_load_clean(in, &m, &rep);
    if (rc) return rc;
    neuv_flatten_report fr;
    neuv_status st = neuv_flatten(m, use_lscm ? NEUV_METHOD_LSCM : NEUV_METHOD_HARMONIC, cli_callbacks(), &fr);
    if (st) { neuv_mesh_free(m); return cli_fail(in, st); }
    if ((st = neuv_mesh_save(m, out))) { neuv_mesh_free(m); return cli_fail(out, st); }
    printf("%s: %d vertices, %d faces, %s in %.3f s (total %.3f s) -> %s\n", in, neuv_mesh_vertex_count(m),
           neuv_mesh_face_count(m), method, fr.seconds, cli_now_seconds() - t0, out);
    printf("  qce_mean %.6g  flipped %d\n", fr.metrics.qce_mean, fr.metrics.flipped);
    neuv_mesh_free(m);
    return 0;
}
