/* neuv segment IN -o OUT [--charts auto|K] [--max-distortion X] [--features hks|xyz]
 *                 [--preset fast|paper] [--seed S] [--iters N] [--preview PREFIX]
 *                 [--no-cache] [--json]
 * PatchNet charts of a mesh: chart id per face, written as a PLY face
 * property `chart` or as OBJ groups (by extension). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "atlas/preview.h"
#include "cli/cli.h"
#include "cli/commands.h"
#include "core/json_writer.h"
#include "core/timer.h"
#include "geometry/operator_cache.h"
#include "io/labels_write.h"
#include "mesh/clean.h"
#include "models/patchnet.h"
#include "segment/patchnet_segment.h"

#define SEGMENT_USAGE "segment IN -o OUT [--charts auto|K] [--max-distortion X] [--features hks|xyz] " \
                      "[--preset fast|paper] [--seed S] [--iters N] [--preview PREFIX] [--no-cache] [--json]"

int cmd_segment(int argc, char **argv)
{
    const char *in = NULL, *out = NULL, *charts = "auto", *features = "hks", *preview = NULL, *preset = "fast";
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
    patchnet_options o;
    patchnet_default_options(&o);
    if (patchnet_apply_preset(&o, preset)) return cli_error(NULL, "--preset expects fast or paper, got '%s'", preset);
    if (!strcmp(charts, "auto")) o.charts = 0;
    else {
        char *end;
        long k = strtol(charts, &end, 10);
        if (*end || k < 1 || k > 100000) return cli_error(NULL, "--charts expects auto or a count >= 1, got '%s'", charts);
        o.charts = (int)k;
    }
    if (!strcmp(features, "hks")) o.features = DIFFUSION_NET_HKS;
    else if (!strcmp(features, "xyz")) o.features = DIFFUSION_NET_XYZ;
    else return cli_error(NULL, "--features expects hks or xyz, got '%s'", features);
    if (!(max_distortion > 1)) return cli_error(NULL, "--max-distortion must be above 1, got %g", max_distortion);
    if (iters < 0) return cli_error(NULL, "--iters must be >= 1, got %d", iters);
    if (seed < 0) return cli_error(NULL, "--seed must be >= 0, got %d", seed);
    o.max_distortion = max_distortion;
    o.seed = (uint64_t)seed;
    if (iters > 0) o.iters = iters;
    const char *dot = strrchr(out, '.');
    if (!dot || (strcmp(dot, ".ply") && strcmp(dot, ".obj") && strcmp(dot, ".PLY") && strcmp(dot, ".OBJ")))
        return cli_error(out, "segment writes .ply (face property chart) or .obj (groups)");
    if (cli_check_output_not_input(out, in)) return 2;
    if (cli_opts.threads > 0) nn_set_threads(cli_opts.threads);

    double t0 = now_seconds();
    neuv_mesh *m = NULL;
    neuv_clean_report crep;
    int rc = cli_load_clean(in, &m, &crep);
    if (rc) return rc;
    neuv_status st;
    double t_load = now_seconds() - t0;
    double t1 = now_seconds();
    operators ops;
    operators_params p = operators_default_params();
    if (o.k_eig > p.k) p.k = o.k_eig;
    int hit = 0;
    if ((st = operators_get(m, &p, !no_cache, &ops, NULL, &hit))) { mesh_free(m); return cli_fail(in, st); }
    double t_ops = now_seconds() - t1;
    int *chart = malloc(sizeof(int) * (size_t)m->nf);
    if (!chart) { operators_free(&ops); mesh_free(m); return cli_error(in, "out of memory"); }
    int n = 0;
    patchnet_report rep;
    st = patchnet_segment(m, &ops, &o, chart, &n, NULL, NULL, &rep);
    operators_free(&ops);
    if (st) { free(chart); mesh_free(m); return cli_fail(in, st); }
    if ((st = labels_write(out, m, chart))) { free(chart); mesh_free(m); return cli_fail(out, st); }
    if (preview) {
        char path[4096];
        snprintf(path, sizeof path, "%s-charts.png", preview);
        if ((st = preview_write_labels(m, chart, path))) { free(chart); mesh_free(m); return cli_fail(path, st); }
    }
    double total = now_seconds() - t0;
    cli_progress_done();
    if (json) {
        json_writer w;
        json_init(&w);
        json_begin_object(&w);
        json_key(&w, "input"); json_string(&w, in);
        json_key(&w, "output"); json_string(&w, out);
        json_key(&w, "vertices"); json_int(&w, m->nv);
        json_key(&w, "faces"); json_int(&w, m->nf);
        json_key(&w, "seed"); json_int(&w, seed);
        json_key(&w, "features"); json_string(&w, features);
        json_key(&w, "patches"); json_int(&w, rep.k);
        json_key(&w, "label_charts"); json_int(&w, rep.label_charts);
        json_key(&w, "splits"); json_int(&w, rep.splits);
        json_key(&w, "charts"); json_int(&w, n);
        json_key(&w, "iterations"); json_int(&w, rep.iterations);
        json_key(&w, "iterations_per_second"); json_number(&w, rep.iters_per_second);
        json_key(&w, "loss"); json_number(&w, rep.loss);
        json_key(&w, "loss_cos"); json_number(&w, rep.loss_cos);
        json_key(&w, "loss_geo"); json_number(&w, rep.loss_geo);
        json_key(&w, "worst_lscm_qce"); json_number(&w, rep.worst_qce);
        json_key(&w, "lscm_flipped"); json_int(&w, rep.flipped);
        json_key(&w, "seconds");
        json_begin_object(&w);
        json_key(&w, "load"); json_number(&w, t_load);
        json_key(&w, "operators"); json_number(&w, t_ops);
        json_key(&w, "geodesics"); json_number(&w, rep.geodesic_seconds);
        json_key(&w, "train"); json_number(&w, rep.train_seconds);
        json_key(&w, "chart_check"); json_number(&w, rep.chart_check_seconds);
        json_key(&w, "total"); json_number(&w, total);
        json_end_object(&w);
        json_end_object(&w);
        printf("%s\n", json_text(&w));
        json_free(&w);
    } else {
        printf("%s: %d faces -> %d charts (%d patches, %d from labels, %d splits) in %.2f s -> %s\n", in, m->nf, n,
               rep.k, rep.label_charts, rep.splits, total, out);
        printf("  worst chart LSCM qce_mean %.4f  flipped %d  iterations %d (%.1f it/s)  loss %.4f (cos %.4f, geo %.4f)\n",
               rep.worst_qce, rep.flipped, rep.iterations, rep.iters_per_second, rep.loss, rep.loss_cos, rep.loss_geo);
        printf("  seconds: load %.2f  operators %.2f%s  geodesics %.2f  train %.2f  chart check %.2f\n", t_load, t_ops,
               hit ? " (cache)" : "", rep.geodesic_seconds, rep.train_seconds, rep.chart_check_seconds);
    }
    free(chart);
    mesh_free(m);
    return 0;
}
