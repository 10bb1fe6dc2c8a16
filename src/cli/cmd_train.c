/* neuv train -o M.neuv IN... [options]: a category model (unwrap_category.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/commands.h"

static const char *usage_text =
    "usage: neuv train -o M.neuv IN... [--charts auto|K] [--max-distortion X] [--preset fast|paper]\n"
    "                  [--iters N] [--patch-iters N] [--refine N] [--seed S] [--threads T]\n"
    "                  [--resolution PX] [--padding PX] [--report R.json] [--no-cache] [--quiet]\n"
    "                  [--max-memory MIB]\n"
    "  trains PatchNet and the parameterization networks on all inputs at once (a category\n"
    "  model); `neuv unwrap --model M.neuv NEW` then unwraps an unseen shape by inference\n";

int cmd_train(int argc, char **argv)
{
    neuv_unwrap_options o;
    neuv_unwrap_options_init(&o);
    const char *out = NULL, *charts = NULL, *preset = NULL, *report = NULL;
    int seed = -1, refine = -1, patch_iters = 0, bad = 0, n = 0, max_distortion_given = 0, max_memory_given = 0;
    const char **inputs = calloc((size_t)argc, sizeof *inputs);
    if (!inputs) return cli_error(NULL, "out of memory");
    for (int i = 1; i < argc && !bad; i++) {
        if (cli_arg_global(argc, argv, &i, &bad)) continue;
        if (cli_arg_str(argc, argv, &i, "-o", &out, &bad)) continue;
        if (cli_arg_str(argc, argv, &i, "--charts", &charts, &bad)) continue;
        if (cli_arg_str(argc, argv, &i, "--preset", &preset, &bad)) continue;
        if (cli_arg_str(argc, argv, &i, "--report", &report, &bad)) continue;
        if (cli_arg_double(argc, argv, &i, "--max-distortion", &o.max_distortion, &bad)) { max_distortion_given = 1; continue; }
        if (cli_arg_int(argc, argv, &i, "--iters", &o.iters, &bad)) continue;
        if (cli_arg_int(argc, argv, &i, "--patch-iters", &patch_iters, &bad)) continue;
        if (cli_arg_int(argc, argv, &i, "--refine", &refine, &bad)) continue;
        if (cli_arg_int(argc, argv, &i, "--seed", &seed, &bad)) continue;
        if (cli_arg_int(argc, argv, &i, "--resolution", &o.resolution, &bad)) continue;
        if (cli_arg_int(argc, argv, &i, "--padding", &o.padding, &bad)) continue;
        if (cli_arg_int(argc, argv, &i, "--max-memory", &o.max_memory_mb, &bad)) { max_memory_given = 1; continue; }
        if (!strcmp(argv[i], "--no-cache")) { o.use_cache = 0; continue; }
        if (!strcmp(argv[i], "-h") || !strcmp(argv[i], "--help")) { fputs(usage_text, stdout); free(inputs); return 0; }
        if (argv[i][0] == '-' && argv[i][1]) { free(inputs); return cli_error(NULL, "train: unknown option '%s'", argv[i]); }
        inputs[n++] = argv[i];
    }
    int rc = bad ? 2 : 0;
    if (!rc && (!out || n == 0)) rc = cli_error(NULL, "train needs -o M.neuv and at least one input mesh (neuv train --help)");
    if (!rc && preset) rc = cli_parse_preset(preset, &o.preset);
    if (!rc && charts) rc = cli_parse_charts(charts, &o.charts);
    if (!rc && o.max_distortion < 1.0) rc = cli_error(NULL, "--max-distortion must be at least 1");
    if (!rc && max_distortion_given && o.charts > 0)
        rc = cli_error(NULL, "--max-distortion applies to --charts auto: --charts K fixes the chart count");
    if (!rc && o.iters < 0) rc = cli_error(NULL, "--iters must be positive");
    if (!rc && (patch_iters < 0 || patch_iters > 10000000)) rc = cli_error(NULL, "--patch-iters must be positive");
    if (!rc && (refine < -1 || refine > 1000000))
        rc = cli_error(NULL, "--refine must be 0 (off) or a step count up to 1000000");
    if (!rc && seed < -1) rc = cli_error(NULL, "--seed must be non-negative");
    if (!rc && (o.resolution < 64 || o.resolution > 16384)) rc = cli_error(NULL, "--resolution must be in 64..16384");
    if (!rc && (o.padding < 0 || o.padding > o.resolution / 8)) rc = cli_error(NULL, "--padding must be in 0..resolution/8");
    if (!rc && (o.max_memory_mb < 0 || (max_memory_given && o.max_memory_mb == 0)))
        rc = cli_error(NULL, "--max-memory must be a size in MiB (without it: half of this machine's memory)");
    for (int i = 0; !rc && i < n; i++) {
        rc = cli_check_output_not_input(out, inputs[i]);
        if (!rc && report) rc = cli_check_output_not_input(report, inputs[i]);
    }
    if (!rc) rc = cli_check_output_folder(out);
    if (!rc && report) rc = cli_check_output_folder(report);
    if (rc) { free(inputs); return rc; }
    if (refine >= 0) o.refine = refine;
    if (seed >= 0) o.seed = (unsigned long long)seed;
    o.threads = cli_opts.threads;

    neuv_mesh **meshes = calloc((size_t)n, sizeof *meshes);
    if (!meshes) { free(inputs); return cli_error(NULL, "out of memory"); }
    for (int i = 0; !rc && i < n; i++) {
        neuv_status s = neuv_mesh_load(inputs[i], cli_callbacks(), &meshes[i]);
        if (s != NEUV_OK) rc = cli_fail(inputs[i], s);
    }
    neuv_model *md = NULL;
    neuv_train_report rep;
    if (!rc) {
        neuv_status s = neuv_train_category((const neuv_mesh *const *)meshes, n, &o, patch_iters, cli_callbacks(),
                                            &md, &rep);
        if (s != NEUV_OK) rc = cli_fail(n == 1 ? inputs[0] : "train", s);
    }
    char *json = NULL;
    if (!rc && report) {
        json = neuv_train_report_json(&rep, out);
        if (!json) rc = cli_error(NULL, "out of memory writing the report");
    }
    if (!rc) {
        neuv_status s = neuv_model_save(md, out);
        if (s != NEUV_OK) rc = cli_fail(out, s);
    }
    if (!rc && json) rc = cli_write_text(report, json);
    if (!rc && !cli_opts.quiet)
        printf("trained on %d shapes (%d faces, %d charts): PatchNet K %d, %d steps; networks %d steps, "
               "%.1f s -> %s\n", rep.shapes, rep.faces, rep.charts, rep.patch_k, rep.patch_iterations,
               rep.param_iterations, rep.seconds, out);
    neuv_free(json);
    neuv_model_free(md);
    for (int i = 0; i < n; i++) neuv_mesh_free(meshes[i]);
    free(meshes);
    free(inputs);
    return rc;
}
