/* neuv segment IN -o OUT [--charts auto|K] [--max-distortion X] [--features hks|xyz|hks+normals]
 *                 [--preset fast|paper] [--seed S] [--iters N] [--preview PREFIX]
 *                 [--no-cache] [--json]
 * PatchNet charts of a mesh: chart id per face, written as a PLY face
 * property `chart` or as OBJ groups (by extension). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/commands.h"

#define SEGMENT_USAGE "segment IN -o OUT [--charts auto|K] [--max-distortion X] [--features hks|xyz|hks+normals] " \
                      "[--preset fast|paper] [--seed S] [--iters N] [--preview PREFIX] [--no-cache] [--json]"

int cmd_segment(int argc, char **argv)
{
    const char *in = NULL, *out = NULL, *charts = "auto", *features = "hks+normals", *preview = NULL, *preset = "fast";
    int json = 0, no_cache = 0, bad = 0, seed = 1, iters = 0, seed_set = 0;
    double max_distortion = 1.15;
    for (int i = 1; i < argc && !bad; i++) {
        if (cli_arg_global(argc, argv, &i, &bad)) continue;
        if (cli_arg_str(argc, argv, &i, "-o", &out, &bad)) continue;
        if (cli_arg_str(argc, argv, &i, "--charts", &charts, &bad)) continue;
        if (cli_arg_str(argc, argv, &i, "--features", &features, &bad)) continue;
        if (cli_arg_str(argc, argv, &i, "--preset", &preset, &bad)) continue;
        if (cli_arg_str(argc, argv, &i, "--preview", &preview, &bad)) continue;
        if (cli_arg_double(argc, argv, &i, "--max-distortion", &max_distortion, &bad)) continue;
        if (cli_arg_int(argc, argv, &i, "--seed", &seed, &bad)) { seed_set = 1; continue; }
        if (cli_arg_int(argc, argv, &i, "--iters", &iters, &bad)) continue;
        if (!strcmp(argv[i], "--json")) { json = 1; continue; }
        if (!strcmp(argv[i], "--no-cache")) { no_cache = 1; continue; }
        if (argv[i][0] == '-' && argv[i][1]) return cli_error(NULL, "segment: unknown option '%s'", argv[i]);
        if (in) return cli_error(NULL, "segment: one input file expected, got '%s' and '%s'", in, argv[i]);
        in = argv[i];
    }
    (void)seed_set;
    if (bad) return 2;
    if (!in || !out) return cli_error(NULL, "usage: neuv " SEGMENT_USAGE);
    neuv_segment_options o;
    neuv_segment_options_init(&o);
    if (!strcmp(preset, "fast")) o.preset = NEUV_PRESET_FAST;
    else if (!strcmp(preset, "paper")) o.preset = NEUV_PRESET_PAPER;
    else return cli_error(NULL, "--preset expects fast or paper, got '%s'", preset);
    if (!strcmp(charts, "auto")) o.charts = 0;
    else {
        char *end;
        long k = strtol(charts, &end, 10);
        if (*end || k < 1 || k > 100000) return cli_error(NULL, "--charts expects auto or a count >= 1, got '%s'", charts);
        o.charts = (int)k;
    }
    if (!strcmp(features, "hks")) o.features = NEUV_FEATURES_HKS;
    else if (!strcmp(features, "xyz")) o.features = NEUV_FEATURES_XYZ;
    else if (!strcmp(features, "hks+normals")) o.features = NEUV_FEATURES_HKS_NORMALS;
    else return cli_error(NULL, "--features expects hks, xyz or hks+normals, got '%s'", features);
    if (!(max_distortion > 1)) return cli_error(NULL, "--max-distortion must be above 1, got %g", max_distortion);
    if (iters < 0) return cli_error(NULL, "--iters must be >= 1, got %d", iters);
    if (seed < 0) return cli_error(NULL, "--seed must be >= 0, got %d", seed);
    o.max_distortion = max_distortion;
    o.seed = (unsigned long long)seed;
    o.iters = iters;
    o.threads = cli_opts.threads;
    o.use_cache = !no_cache;
    const char *dot = strrchr(out, '.');
    if (!dot || (strcmp(dot, ".ply") && strcmp(dot, ".obj") && strcmp(dot, ".PLY") && strcmp(dot, ".OBJ")))
        return cli_error(out, "segment writes .ply (face property chart) or .obj (groups)");
    if (cli_check_output_not_input(out, in)) return 2;

    double t0 = cli_now_seconds();
    neuv_mesh *m = NULL;
    neuv_clean_report crep;
    int rc = cli_load_clean(in, &m, &crep);
    if (rc) return rc;
    neuv_status st;
    double t_load = cli_now_seconds() - t0;
    int *chart = malloc(sizeof(int) * (size_t)neuv_mesh_face_count(m));
    if (!chart) { neuv_mesh_free(m); return cli_error(in, "out of memory"); }
    int n = 0;
    neuv_segment_report rep;
    st = neuv_segment(m, &o, cli_callbacks(), chart, &n, &rep);
    if (st) { free(chart); neuv_mesh_free(m); return cli_fail(in, st); }
    if ((st = neuv_save_face_labels(m, chart, out))) { free(chart); neuv_mesh_free(m); return cli_fail(out, st); }
    if (preview) {
        char path[4096];
        snprintf(path, sizeof path, "%s-charts.png", preview);
        if ((st = neuv_write_label_preview(m, chart, path))) { free(chart); neuv_mesh_free(m); return cli_fail(path, st); }
    }
    double total = cli_now_seconds() - t0;
    cli_progress_done();
    if (json) {
        rc = cli_print_document(neuv_segment_report_json(&rep, in, out, t_load, total));
    } else {
        printf("%s: %d faces -> %d charts (%d patches, %d from labels, %d splits) in %.2f s -> %s\n", in, rep.faces, n,
               rep.patches, rep.label_charts, rep.splits, total, out);
        printf("  worst chart LSCM qce_mean %.4f  flipped %d  iterations %d (%.1f it/s)  loss %.4f (cos %.4f, geo %.4f)\n",
               rep.worst_lscm_qce, rep.lscm_flipped, rep.iterations, rep.iterations_per_second, rep.loss, rep.loss_cos,
               rep.loss_geo);
        printf("  seconds: load %.2f  operators %.2f%s  geodesics %.2f  train %.2f  chart check %.2f\n", t_load,
               rep.seconds_operators, rep.cache_hit ? " (cache)" : "", rep.seconds_geodesics, rep.seconds_train,
               rep.seconds_chart_check);
    }
    free(chart);
    neuv_mesh_free(m);
    return rc;
}
