#include "cli/unwrap_job.h"

#include <ctype.h>
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"

/* The library names the options of neuv_apply_options as the struct does;
 * its one-line message with each name as the flag the user typed. */
static const char *const apply_names[][2] = {
    {"allow_overlaps", "--allow-overlaps"}, {"check_inference", "--check-inference"},
    {"lscm_baseline", "--lscm-baseline"},   {"shared_layer", "--shared-layer"},
    {"keep_model", "--save-model"},         {"finetune", "--finetune"},
    {"refine", "--refine"},                 {"resolution", "--resolution"},
    {"padding", "--padding"},
};
/* Training's messages name few fields; only these read as flags there. */
static const char *const train_names[][2] = {
    {"texels_per_unit", "--texels-per-unit"}, {"keep_model", "--save-model"},
};

static void error_in_flags(const char *msg, const char *const (*names)[2], size_t n_names, char *out, size_t n)
{
    size_t used = 0;
    const char *p = msg;
    while (*p && used + 1 < n) {
        const char *flag = NULL;
        size_t len = 0;
        int starts = p == msg || !(isalnum((unsigned char)p[-1]) || strchr("_.-/", p[-1]));
        for (size_t k = 0; starts && !flag && k < n_names; k++) {
            len = strlen(names[k][0]);
            if (!strncmp(p, names[k][0], len) && !isalnum((unsigned char)p[len]) && p[len] != '_') flag = names[k][1];
        }
        if (flag) {
            int w = snprintf(out + used, n - used, "%s", flag);
            if (w < 0 || (size_t)w >= n - used) break;
            used += (size_t)w;
            p += len;
        } else {
            out[used++] = *p++;
        }
    }
    out[used] = '\0';
}

static int apply_model(neuv_atlas *atlas, const neuv_unwrap_options *opts, const unwrap_job *job)
{
    neuv_model *model = NULL;
    neuv_status s = neuv_model_load(job->model, &model);
    if (s != NEUV_OK) return cli_fail(job->model, s);
    /* Every option goes through; the library refuses what does not apply
     * to the model's kind (neuv_atlas_apply_model), so that the command
     * line, C and Python follow one rule. */
    neuv_apply_options ao;
    neuv_apply_options_init(&ao);
    ao.threads = opts->threads;
    ao.use_cache = opts->use_cache;
    ao.allow_overlaps = opts->allow_overlaps;
    ao.check_inference = job->check_inference;
    ao.lscm_baseline = job->lscm_baseline;
    ao.finetune = job->finetune;
    ao.shared_layer = job->shared_layer;
    ao.refine = job->refine;
    ao.resolution = job->resolution;
    ao.padding = job->padding;
    ao.keep_model = job->save_model != NULL;
    s = neuv_atlas_apply_model(atlas, model, &ao);
    neuv_model_free(model);
    if (s == NEUV_ERR_INPUT) {
        char msg[768];
        error_in_flags(neuv_last_error(), apply_names, sizeof apply_names / sizeof apply_names[0], msg, sizeof msg);
        return cli_error(job->model, "%s", msg);
    }
    if (s != NEUV_OK) return cli_fail(job->input_name, s);
    if (!job->save_model) return 0;
    /* A category model fine-tuned on this shape: a surface model of it. */
    neuv_model *tuned = NULL;
    s = neuv_atlas_take_model(atlas, &tuned);
    if (s == NEUV_OK) s = neuv_model_save(tuned, job->save_model);
    neuv_model_free(tuned);
    return s == NEUV_OK ? 0 : cli_fail(job->save_model, s);
}

static int train(neuv_atlas *atlas, const neuv_unwrap_options *opts, const unwrap_job *job)
{
    neuv_unwrap_options o = *opts;
    o.keep_model = job->save_model != NULL;
    o.train_faces = job->train_faces;
    neuv_status s = neuv_atlas_generate(atlas, &o);
    if (s == NEUV_ERR_INPUT) {
        char msg[768];
        error_in_flags(neuv_last_error(), train_names, sizeof train_names / sizeof train_names[0], msg, sizeof msg);
        return cli_error(job->input_name, "%s", msg);
    }
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

static int write_outputs(neuv_atlas *atlas, const neuv_mesh *input, const unwrap_job *job)
{
    double t = cli_now_seconds();
    neuv_mesh *written = NULL;
    neuv_status s = neuv_atlas_output_mesh(atlas, 0, input, job->uv_channel, &written);
    if (s == NEUV_OK) s = neuv_mesh_save(written, job->output);
    neuv_mesh_free(written);
    double export_seconds = cli_now_seconds() - t;
    if (s != NEUV_OK) return cli_fail(job->output, s);
    const neuv_mesh *out = neuv_atlas_mesh(atlas);

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
        /* In tiles the metric's packing_efficiency (UV area in [0,1]^2) is undefined: the mean over the tiles. */
        neuv_uv_tile *tiles = NULL;
        int ntiles = 0;
        if ((s = neuv_uv_tiles(out, &tiles, &ntiles)) != NEUV_OK) { neuv_free(json); return cli_fail(job->input_name, s); }
        double packing = mt->packing_efficiency;
        char tiled[48] = "";
        if (ntiles > 1 || (ntiles == 1 && tiles[0].udim != 1001)) {
            packing = 0;
            for (int i = 0; i < ntiles; i++) packing += tiles[i].efficiency / ntiles;
            snprintf(tiled, sizeof tiled, " over %d tiles", ntiles);
        }
        neuv_free(tiles);
        printf("%s: %d chart%s (%s)%s, qce_mean %.4f, flipped %d, overlap %.4g, packing %.3f%s, %.1f s -> %s\n",
               job->input_name, rep.charts, rep.charts == 1 ? "" : "s", sources, moved, mt->qce_mean, mt->flipped, mt->overlap_fraction,
               packing, tiled, job->load_seconds + rep.seconds_total + export_seconds, job->output);
        if (ntiles > 1 && cli_print_tiles(job->input_name, out)) { neuv_free(json); return 2; }
        if (rep.repairs > 0) printf("  %d repairs (listed in the report)\n", rep.repairs);
        if (rep.seam_edges > 0)
            printf("  %d required seam edges (the report's seams), %d crossed\n", rep.seam_edges, rep.seams_crossed);
        if (rep.polygons_split > 0)
            printf("  %d of %d polygons split between charts (written as their triangles)\n", rep.polygons_split,
                   rep.polygons);
        if (rep.hard_edges_not_kept > 0)
            printf("  %d hard edges of the file not kept: the model made the charts\n", rep.hard_edges_not_kept);
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
    if (rc == 0) rc = write_outputs(atlas, mesh, job);
    neuv_atlas_destroy(atlas);
    return rc;
}
