/* neuv unwrap IN [-o OUT] [--report R.json] [--preview PREFIX] [options] */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/commands.h"
#include "cli/unwrap_job.h"

static const char *usage_text =
    "usage: neuv unwrap IN [-o OUT] [--report R.json] [--preview PREFIX] [--preview-color chart|qce|area]\n"
    "                   [--method neural|lscm|harmonic] [--charts auto|K] [--max-distortion X]\n"
    "                   [--preset fast|paper] [--iters N] [--refine N] [--seed S] [--threads T]\n"
    "                   [--resolution PX] [--padding PX] [--allow-overlaps] [--no-cache] [--quiet]\n"
    "                   [--save-model M.neuv] [--model M.neuv [--finetune N] [--check-inference] [--lscm-baseline]\n"
    "                   [--shared-layer]] [--train-faces N] [--max-memory MIB] [--seam-angle DEG]\n"
    "                   [--uv-channel 0|1] [--no-hard-edges] [--texels-per-unit T]\n";

/* Above this many faces the networks train on a simplified copy and the model
 * is applied to the full mesh. Measured (bench/bench_train_faces.sh,
 * bench/RESULTS.md "The --train-faces default"): on the three shared meshes
 * over 20k faces, a 20k copy is within 4% of full-size training's qce_mean
 * at a quarter to a third of the time; 10k degrades armadillo (1.21), and
 * 40k would take the million-face run past its 120 s bar. */
#define DEFAULT_TRAIN_FACES 20000

/* Default output: the input's name without its folder and extension, plus "-uv.obj". */
static char *default_output(const char *in)
{
    const char *base = strrchr(in, '/');
    base = base ? base + 1 : in;
    const char *dot = strrchr(base, '.');
    size_t n = dot && dot != base ? (size_t)(dot - base) : strlen(base);
    char *out = malloc(n + 8);
    if (out) snprintf(out, n + 8, "%.*s-uv.obj", (int)n, base);
    return out;
}

int parse_preview_color(const char *s, int *out)
{
    if (!strcmp(s, "chart")) *out = NEUV_PREVIEW_CHART;
    else if (!strcmp(s, "qce")) *out = NEUV_PREVIEW_QCE;
    else if (!strcmp(s, "area")) *out = NEUV_PREVIEW_AREA;
    else return cli_error(NULL, "--preview-color expects chart, qce or area, got '%s'", s);
    return 0;
}

int cmd_unwrap(int argc, char **argv)
{
    neuv_unwrap_options o;
    neuv_unwrap_options_init(&o);
    unwrap_job job = {0};
    const char *in = NULL, *method = NULL, *charts = NULL, *preset = NULL, *color = NULL;
    int seed = -1, bad = 0, finetune = 0, refine = -1;
    /* The options a model cannot take, when given (their values may be the defaults). */
    int max_distortion_given = 0, iters_given = 0, resolution_given = 0, padding_given = 0, train_faces_given = 0;
    int max_memory_given = 0, seam_angle_given = 0, hard_edges_given = 0, texels_given = 0;
    job.train_faces = DEFAULT_TRAIN_FACES;
    for (int i = 1; i < argc && !bad; i++) {
        if (cli_arg_global(argc, argv, &i, &bad)) continue;
        if (cli_arg_str(argc, argv, &i, "-o", &job.output, &bad)) continue;
        if (cli_arg_str(argc, argv, &i, "--report", &job.report, &bad)) continue;
        if (cli_arg_str(argc, argv, &i, "--preview", &job.preview, &bad)) continue;
        if (cli_arg_str(argc, argv, &i, "--preview-color", &color, &bad)) continue;
        if (cli_arg_str(argc, argv, &i, "--method", &method, &bad)) continue;
        if (cli_arg_str(argc, argv, &i, "--charts", &charts, &bad)) continue;
        if (cli_arg_str(argc, argv, &i, "--preset", &preset, &bad)) continue;
        if (cli_arg_double(argc, argv, &i, "--max-distortion", &o.max_distortion, &bad)) { max_distortion_given = 1; continue; }
        if (cli_arg_int(argc, argv, &i, "--iters", &o.iters, &bad)) { iters_given = 1; continue; }
        if (cli_arg_int(argc, argv, &i, "--refine", &refine, &bad)) continue;
        if (cli_arg_int(argc, argv, &i, "--seed", &seed, &bad)) continue;
        if (cli_arg_int(argc, argv, &i, "--resolution", &o.resolution, &bad)) { resolution_given = 1; continue; }
        if (cli_arg_int(argc, argv, &i, "--padding", &o.padding, &bad)) { padding_given = 1; continue; }
        if (cli_arg_str(argc, argv, &i, "--save-model", &job.save_model, &bad)) continue;
        if (cli_arg_str(argc, argv, &i, "--model", &job.model, &bad)) continue;
        if (cli_arg_int(argc, argv, &i, "--finetune", &finetune, &bad)) continue;
        if (cli_arg_int(argc, argv, &i, "--train-faces", &job.train_faces, &bad)) { train_faces_given = 1; continue; }
        if (cli_arg_int(argc, argv, &i, "--max-memory", &o.max_memory_mb, &bad)) { max_memory_given = 1; continue; }
        if (cli_arg_double(argc, argv, &i, "--seam-angle", &o.seam_angle, &bad)) { seam_angle_given = 1; continue; }
        if (cli_arg_int(argc, argv, &i, "--uv-channel", &job.uv_channel, &bad)) continue;
        if (cli_arg_double(argc, argv, &i, "--texels-per-unit", &o.texels_per_unit, &bad)) { texels_given = 1; continue; }
        if (!strcmp(argv[i], "--check-inference")) { job.check_inference = 1; continue; }
        if (!strcmp(argv[i], "--lscm-baseline")) { job.lscm_baseline = 1; continue; }
        if (!strcmp(argv[i], "--shared-layer")) { job.shared_layer = 1; continue; }
        if (!strcmp(argv[i], "--allow-overlaps")) { o.allow_overlaps = 1; continue; }
        if (!strcmp(argv[i], "--no-cache")) { o.use_cache = 0; continue; }
        if (!strcmp(argv[i], "--no-hard-edges")) { o.hard_edges = 0; hard_edges_given = 1; continue; }
        if (!strcmp(argv[i], "-h") || !strcmp(argv[i], "--help")) { fputs(usage_text, stdout); return 0; }
        if (argv[i][0] == '-' && argv[i][1]) return cli_error(NULL, "unwrap: unknown option '%s'", argv[i]);
        if (in) return cli_error(NULL, "unwrap takes one input file (got '%s' and '%s')", in, argv[i]);
        in = argv[i];
    }
    if (bad) return 2;
    if (!in) { fputs(usage_text, stderr); return 2; }
    if (method) {
        if (!strcmp(method, "neural")) o.method = NEUV_METHOD_NEURAL;
        else if (!strcmp(method, "lscm")) o.method = NEUV_METHOD_LSCM;
        else if (!strcmp(method, "harmonic")) o.method = NEUV_METHOD_HARMONIC;
        else return cli_error(NULL, "--method expects neural, lscm or harmonic, got '%s'", method);
    }
    if (preset && cli_parse_preset(preset, &o.preset)) return 2;
    if (charts && cli_parse_charts(charts, &o.charts)) return 2;
    if (o.max_distortion < 1.0) return cli_error(NULL, "--max-distortion must be at least 1");
    if (o.iters < 0) return cli_error(NULL, "--iters must be positive");
    if (refine < -1 || refine > 1000000) return cli_error(NULL, "--refine must be 0 (off) or a step count up to 1000000");
    if (o.resolution < 64 || o.resolution > 16384) return cli_error(NULL, "--resolution must be in 64..16384");
    if (o.padding < 0 || (!job.model && o.padding > o.resolution / 8))
        return cli_error(NULL, "--padding must be in 0..resolution/8 (%d)", o.resolution / 8);
    /* A saved model records the refinement and carries it over when it is
     * applied (docs/transfer.md), so --save-model leaves it on: the atlas is
     * the same with and without --save-model. */
    if (refine >= 0) o.refine = refine;
    if (seed >= 0) o.seed = (unsigned long long)seed;
    else if (seed != -1) return cli_error(NULL, "--seed must be non-negative");
    o.threads = cli_opts.threads;
    if (job.train_faces < 0) return cli_error(NULL, "--train-faces must be 0 (never simplify) or a face count");
    if (job.train_faces > 0 && job.train_faces < 500)
        return cli_error(NULL, "--train-faces must be at least 500 (or 0 to train on the full mesh)");
    if (o.max_memory_mb < 0 || (max_memory_given && o.max_memory_mb == 0))
        return cli_error(NULL, "--max-memory must be a size in MiB (without it: half of this machine's memory)");
    if (seam_angle_given && !(o.seam_angle > 0 && o.seam_angle < 180))
        return cli_error(NULL, "--seam-angle must be an angle in degrees between 0 and 180 (exclusive)");
    if (job.uv_channel != 0 && job.uv_channel != 1)
        return cli_error(NULL, "--uv-channel must be 0 (the atlas replaces the UVs) or 1 (the atlas as a second UV set)");
    if (texels_given && !(o.texels_per_unit > 0))
        return cli_error(NULL, "--texels-per-unit must be a number of pixels per unit of surface length above 0, got %g",
                         o.texels_per_unit);
    if (texels_given && job.save_model)
        return cli_error(NULL, "--texels-per-unit cannot be used with --save-model: a model records its layout in one "
                               "square, not in tiles");
    if (finetune < 0 || finetune > 1000000) return cli_error(NULL, "--finetune must be a step count in 0..1000000");
    if (finetune > 0 && !job.model) return cli_error(NULL, "--finetune needs --model");
    job.finetune = finetune;
    if (!job.model && job.check_inference) return cli_error(NULL, "--check-inference needs --model");
    if (!job.model && job.lscm_baseline) return cli_error(NULL, "--lscm-baseline needs --model");
    if (!job.model && job.shared_layer) return cli_error(NULL, "--shared-layer needs --model");
    if (color && !job.preview) return cli_error(NULL, "--preview-color needs --preview (it colours the pictures)");
    /* Options that would change nothing are refused, never ignored. */
    if (!job.model && max_distortion_given && o.charts > 0)
        return cli_error(NULL, "--max-distortion applies to --charts auto: --charts K fixes the chart count");
    if (!job.model && refine >= 0 && o.method != NEUV_METHOD_NEURAL)
        return cli_error(NULL, "--refine applies to the networks' map (--method neural): %s has nothing to refine",
                         method);
    if (job.model) {
        /* The library takes none of these with a model (neuv_apply_options
         * has no field for them); the rest go through and the library
         * refuses what does not apply to the model's kind. */
        const char *refused = method ? "--method cannot be used with --model: the model's method is applied"
            : preset ? "--preset cannot be used with --model: the model's networks are applied"
            : charts ? "--charts cannot be used with --model: the charts come from the model"
            : max_distortion_given ? "--max-distortion cannot be used with --model: the charts come from the model "
                                     "(a category model's threshold is neuv train --max-distortion)"
            : iters_given ? "--iters cannot be used with --model: the model is applied, not trained (a category "
                            "model trains --finetune N steps)"
            : seed >= 0 ? "--seed cannot be used with --model: the model's seed is used"
            : train_faces_given ? "--train-faces cannot be used with --model: nothing trains on a simplified copy "
                                  "(--finetune trains on the mesh itself)"
            : max_memory_given ? "--max-memory cannot be used with --model: it bounds training on the whole mesh, "
                                 "and a model is applied"
            : seam_angle_given ? "--seam-angle cannot be used with --model: the charts come from the model, "
                                 "which does not record seams yet"
            : hard_edges_given ? "--no-hard-edges cannot be used with --model: the charts come from the model, "
                                 "and the file's hard edges are left out anyway (counted in the report)"
            : texels_given ? "--texels-per-unit cannot be used with --model: the charts go where the model's "
                             "layout, one square, has them"
            : NULL;
        if (refused) return cli_error(job.model, "%s", refused);
        job.refine = refine;
        job.resolution = resolution_given ? o.resolution : 0;
        job.padding = padding_given ? o.padding : -1;
    } else {
        job.refine = -1;
    }
    if (color && parse_preview_color(color, &job.preview_color)) return 2;

    char *owned_output = NULL;
    if (!job.output) job.output = owned_output = default_output(in);
    if (!job.output) return cli_error(in, "out of memory");
    int rc = cli_check_output_not_input(job.output, in);
    if (rc == 0) rc = cli_check_output_folder(job.output);
    if (rc == 0 && job.report) rc = cli_check_output_not_input(job.report, in);
    if (rc == 0 && job.report) rc = cli_check_output_folder(job.report);
    if (rc == 0 && job.preview) rc = cli_check_output_folder(job.preview);
    if (rc == 0 && job.save_model) rc = cli_check_output_not_input(job.save_model, in);
    if (rc == 0 && job.save_model && job.model) rc = cli_check_output_not_input(job.save_model, job.model);
    if (rc == 0 && job.save_model) rc = cli_check_output_folder(job.save_model);
    if (rc == 0 && job.uv_channel == 1 && cli_has_extension(job.output, ".obj"))
        rc = cli_error(job.output, "--uv-channel 1 writes a second UV set, which OBJ cannot hold: write .ply, .glb or .gltf");
    if (rc) { free(owned_output); return rc; }

    double t = cli_now_seconds();
    neuv_mesh *mesh = NULL;
    neuv_status s = neuv_mesh_load(in, cli_callbacks(), &mesh);
    if (s != NEUV_OK) { free(owned_output); return cli_fail(in, s); }
    if (job.uv_channel == 1 && !neuv_mesh_has_uv(mesh)) {
        neuv_mesh_free(mesh);
        free(owned_output);
        return cli_error(in, "--uv-channel 1 keeps the file's UVs as the first set, but it has none");
    }
    job.input_name = in;
    job.load_seconds = cli_now_seconds() - t;
    rc = unwrap_job_run(mesh, &o, &job);
    neuv_mesh_free(mesh);
    free(owned_output);
    return rc;
}
