#include "cli/unwrap_job.h"

#include <stdio.h>
#include <string.h>

#include "cli/cli.h"

/* Refuses the flags that do not apply to the model's kind, in the CLI's
 * words (the library refuses them too, in its own). */
static const char *model_flags_refused(const neuv_model *model, const unwrap_job *job)
{
    if (neuv_model_is_category(model)) {
        if (job->lscm_baseline) return "--lscm-baseline needs a surface model, not a category model";
        if (job->check_inference) return "--check-inference needs a surface model, not a category model";
        if (job->save_model)
            return "--save-model with a category model would write that model again, not this shape's (nor "
                   "--finetune's weights); unwrap without --model to save a model of this shape";
        return NULL;
    }
    if (job->finetune > 0 || job->refine >= 0 || job->shared_layer)
        return "a surface model is applied by inference only: --finetune, --refine and --shared-layer apply to "
               "category models (neuv train)";
    return NULL;
}

static int apply_model(neuv_atlas *atlas, const neuv_unwrap_options *opts, const unwrap_job *job)
{
    neuv_model *model = NULL;
    neuv_status s = neuv_model_load(job->model, &model);
    if (s != NEUV_OK) return cli_fail(job->model, s);
    const char *refused = model_flags_refused(model, job);
    if (refused) { neuv_model_free(model); return cli_error(job->model, "%s", refused); }
    if (neuv_model_is_category(model) && job->shared_layer && job->finetune > 0) {
        neuv_model_free(model);
        return cli_error(job->input_name, "--shared-layer is for inference; --finetune trains the networks");
    }
    neuv_apply_options ao;
    neuv_apply_options_init(&ao);
    ao.threads = opts->threads;
    ao.use_cache = opts->use_cache;
    ao.check_inference = job->check_inference;
    ao.lscm_baseline = job->lscm_baseline;
    if (neuv_model_is_category(model)) {
        ao.allow_overlaps = opts->allow_overlaps;
        ao.finetune = job->finetune;
        ao.shared_layer = job->shared_layer;
        ao.refine = job->refine;
    }
    s = neuv_atlas_apply_model(atlas, model, &ao);
    const char *what = job->input_name;
    if (s == NEUV_OK && job->save_model) {
        s = neuv_model_save(model, job->save_model);
        what = job->save_model;
    }
    neuv_model_free(model);
    return s == NEUV_OK ? 0 : cli_fail(what, s);
}

static int train(neuv_atlas *atlas, const neuv_unwrap_options *opts, const unwrap_job *job)
{
    neuv_unwrap_options o = *opts;
    o.keep_model = job->save_model != NULL;
    o.train_faces = job->train_faces;
    neuv_status s = neuv_atlas_generate(atlas, &o);
    if (s != NEUV_OK) return cli_fail(job->input_name, s);
    if (!job->save_model) return 0;
    neuv_model *model = NULL;
    s = neuv_atlas_take_model(atlas, &model);
    if (s == NEUV_OK) s = neuv_model_save(model, job->save_model);
    neuv_model_free(model);
    return s == NEUV_OK ? 0 : cli_fail(job->save_model, s);
}

/* "11 network+refined, 3 lscm_after_fold": how many charts each source made. */
static void source_summary(const neuv_report *rep, char *buf, size_t n)
{
    size_t used = 0;
    buf[0] = 0;
    for (int k = 0; k < NEUV_SOURCE_COUNT && used < n; k++) {
        if (rep->charts_by_source[k] == 0) continue;
        int w = snprintf(buf + used, n - used, "%s%d %s", used ? ", " : "", rep->charts_by_source[k],
                         neuv_chart_source_name((neuv_chart_source)k));
        if (w < 0) break;
        used += (size_t)w;
    }
}

static int write_outputs(const neuv_atlas *atlas, const unwrap_job *job)
{
    const neuv_mesh *out = neuv_atlas_mesh(atlas);
    double t = cli_now_seconds();
    neuv_status s = neuv_mesh_save(out, job->output);
    double export_seconds = cli_now_seconds() - t;
    if (s != NEUV_OK) return cli_fail(job->output, s);

    neuv_report rep;
    if ((s = neuv_atlas_get_report(atlas, &rep)) != NEUV_OK) return cli_fail(job->input_name, s);
    char *json = neuv_atlas_report_json(atlas, job->input_name, job->load_seconds, export_seconds);
    int rc = json ? 0 : cli_error(job->input_name, "out of memory writing the report");
    if (rc == 0 && job->report) rc = cli_write_text(job->report, json);
    if (rc == 0 && job->preview) {
        s = neuv_write_preview(out, job->preview, (neuv_preview_color)job->preview_color, cli_callbacks());
        if (s != NEUV_OK) rc = cli_fail(job->preview, s);
    }
    if (rc == 0 && !cli_opts.quiet) {
        const neuv_metrics *mt = &rep.metrics;
        char sources[256];
        source_summary(&rep, sources, sizeof sources);
        char moved[96] = "";
        if (rep.moved_charts > 0 && !rep.trained_on_copy) /* a copy's layout is nobody's texture */
            snprintf(moved, sizeof moved, ", %d chart%s moved from the model's layout", rep.moved_charts,
                     rep.moved_charts == 1 ? "" : "s");
        printf("%s: %d charts (%s)%s, qce_mean %.4f, flipped %d, overlap %.4g, packing %.3f, %.1f s -> %s\n",
               job->input_name, rep.charts, sources, moved, mt->qce_mean, mt->flipped, mt->overlap_fraction,
               mt->packing_efficiency, job->load_seconds + rep.seconds_total + export_seconds, job->output);
        if (rep.repairs > 0) printf("  %d repairs (listed in the report)\n", rep.repairs);
        if (rep.trained_on_copy)
            printf("  trained on a simplified copy (%d of %d faces), model applied to the full mesh\n",
                   rep.train_faces, rep.faces);
    }
    neuv_free(json);
    return rc;
}

int unwrap_job_run(const neuv_mesh *mesh, const neuv_unwrap_options *opts, const unwrap_job *job)
{
    neuv_atlas *atlas = NULL;
    neuv_status s = neuv_atlas_create(&atlas);
    if (s == NEUV_OK) {
        neuv_atlas_set_callbacks(atlas, cli_callbacks());
        s = neuv_atlas_add_loaded_mesh(atlas, mesh);
    }
    if (s != NEUV_OK) { neuv_atlas_destroy(atlas); return cli_fail(job->input_name, s); }
    int rc = job->model ? apply_model(atlas, opts, job) : train(atlas, opts, job);
    if (rc == 0) rc = write_outputs(atlas, job);
    neuv_atlas_destroy(atlas);
    return rc;
}
