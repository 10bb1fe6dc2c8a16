/* neuv pack IN_WITH_UV -o OUT [--resolution PX] [--padding PX] [--keep-scale | --texels-per-unit T]
 *           [--preview PREFIX] [--preview-color chart|qce|area]
 * Repacks the charts of any UV map (charts = UV-connected components, as
 * `neuv eval` counts them) into one square atlas, or at T pixels per unit of
 * surface length into as many UDIM tiles as that takes. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/commands.h"

static const char *pack_usage =
    "usage: neuv pack IN_WITH_UV -o OUT [--resolution PX] [--padding PX] [--keep-scale | --texels-per-unit T] "
    "[--preview PREFIX] [--preview-color chart|qce|area]";

static void print_efficiency(const char *when, double e)
{
    if (isfinite(e) && e >= 0) printf("  packing efficiency %-6s %.4f\n", when, e);
    else printf("  packing efficiency %-6s -        (UVs leave [0,1]^2)\n", when);
}

int cmd_pack(int argc, char **argv)
{
    const char *in = NULL, *out = NULL, *preview = NULL, *color_name = "chart";
    neuv_pack_options opt;
    neuv_pack_options_init(&opt);
    int bad = 0, texels_given = 0;
    for (int i = 1; i < argc && !bad; i++) {
        if (cli_arg_global(argc, argv, &i, &bad)) continue;
        if (cli_arg_str(argc, argv, &i, "-o", &out, &bad)) continue;
        if (cli_arg_int(argc, argv, &i, "--resolution", &opt.resolution, &bad)) continue;
        if (cli_arg_int(argc, argv, &i, "--padding", &opt.padding, &bad)) continue;
        if (cli_arg_double(argc, argv, &i, "--texels-per-unit", &opt.texels_per_unit, &bad)) { texels_given = 1; continue; }
        if (cli_arg_str(argc, argv, &i, "--preview", &preview, &bad)) continue;
        if (cli_arg_str(argc, argv, &i, "--preview-color", &color_name, &bad)) continue;
        if (!strcmp(argv[i], "--keep-scale")) { opt.keep_scale = 1; continue; }
        if (argv[i][0] == '-' && argv[i][1]) return cli_error(NULL, "pack: unknown option '%s'", argv[i]);
        if (in) return cli_error(NULL, "pack: one input file expected, got '%s' and '%s'", in, argv[i]);
        in = argv[i];
    }
    if (bad) return 2;
    opt.threads = cli_opts.threads;
    if (!in || !out) return cli_error(NULL, "%s", pack_usage);
    if (opt.resolution < 8 || opt.resolution > 32768)
        return cli_error(NULL, "--resolution must be between 8 and 32768 px, got %d", opt.resolution);
    if (opt.padding < 0 || 2 * opt.padding + 1 > opt.resolution)
        return cli_error(NULL, "--padding must be between 0 and %d px for a %d px atlas, got %d",
                         (opt.resolution - 1) / 2, opt.resolution, opt.padding);
    if (texels_given && !(opt.texels_per_unit > 0))
        return cli_error(NULL, "--texels-per-unit must be a number of pixels per unit of surface length above 0, got %g",
                         opt.texels_per_unit);
    if (texels_given && opt.keep_scale)
        return cli_error(NULL, "--texels-per-unit sets every chart's scale: it cannot be used with --keep-scale");
    neuv_preview_color color = NEUV_PREVIEW_CHART;
    if (!strcmp(color_name, "qce")) color = NEUV_PREVIEW_QCE;
    else if (!strcmp(color_name, "area")) color = NEUV_PREVIEW_AREA;
    else if (strcmp(color_name, "chart")) return cli_error(NULL, "--preview-color expects chart, qce or area, got '%s'", color_name);
    if (cli_check_output_not_input(out, in)) return 2;

    double t0 = cli_now_seconds();
    neuv_mesh *m = NULL;
    neuv_status st = neuv_mesh_load(in, cli_callbacks(), &m);
    if (st != NEUV_OK) return cli_fail(in, st);
    if (!neuv_mesh_has_uv(m)) {
        neuv_mesh_free(m);
        return cli_error(in, "no UVs: neuv pack repacks the charts of a mesh that carries texture coordinates");
    }
    /* Charts are found across shared edges, which needs shared vertex indices;
     * welding only merges identical positions, so positions are written back
     * exactly as read. */
    neuv_metrics before, after;
    st = neuv_mesh_weld(m, NULL);
    if (st == NEUV_OK) st = neuv_evaluate(m, cli_callbacks(), &before);
    if (st != NEUV_OK) { neuv_mesh_free(m); return cli_fail(in, st); }
    double t1 = cli_now_seconds();
    neuv_pack_report res;
    st = neuv_pack_uvs(m, &opt, cli_callbacks(), &res);
    double t2 = cli_now_seconds();
    if (st == NEUV_OK) st = neuv_evaluate(m, cli_callbacks(), &after);
    if (st != NEUV_OK) { neuv_mesh_free(m); return cli_fail(in, st); }
    st = neuv_mesh_save(m, out);
    if (st != NEUV_OK) { neuv_mesh_free(m); return cli_fail(out, st); }

    if (!cli_opts.quiet) {
        if (texels_given)
            printf("%s: %d charts packed at %g px per unit into %d tile%s of %d px with %d px padding in %.2f s (%d tries)\n",
                   in, res.charts, opt.texels_per_unit, res.tiles, res.tiles == 1 ? "" : "s", opt.resolution,
                   opt.padding, t2 - t1, res.attempts);
        else
            printf("%s: %d charts packed into %d px with %d px padding%s in %.2f s (%d tries)\n", in, res.charts,
                   opt.resolution, opt.padding, opt.keep_scale ? ", relative scales kept" : "", t2 - t1, res.attempts);
        print_efficiency("before", before.packing_efficiency);
        print_efficiency("after", after.packing_efficiency);
        if (cli_print_tiles(in, m)) { neuv_mesh_free(m); return 2; }
        printf("  qce_mean before %.6f after %.6f\n", before.qce_mean, after.qce_mean);
        printf("  texel density %.2f px per unit length; wrote %s (%.2f s total)\n", res.texel_scale, out,
               cli_now_seconds() - t0);
    }
    int rc = 0;
    if (preview) {
        st = neuv_write_preview(m, preview, color, cli_callbacks());
        if (st != NEUV_OK) rc = cli_fail(preview, st);
        else if (!cli_opts.quiet) printf("  wrote %s-uv.png and %s-checker.png\n", preview, preview);
    }
    neuv_mesh_free(m);
    return rc;
}
