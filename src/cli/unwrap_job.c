#include "cli/unwrap_job.h"

#include <stdio.h>
#include <stdlib.h>

#include "atlas/preview.h"
#include "cli/cli.h"
#include "core/error.h"
#include "core/timer.h"
#include "unwrap/unwrap_apply.h"
#include "unwrap/unwrap_internal.h"
#include "unwrap/unwrap_model.h"

int unwrap_job_run(const neuv_mesh *mesh, const neuv_unwrap_options *opts, const unwrap_job *job)
{
    neuv_unwrap_result *r = NULL;
    neuv_status s;
    if (job->model) {
        unwrap_model *md = NULL;
        s = unwrap_model_load(job->model, &md);
        if (s != NEUV_OK) return cli_fail(job->model, s);
        const char *what = job->input_name;
        if (md->category && job->lscm_baseline) {
            s = error_set(NEUV_ERR_INPUT, "--lscm-baseline needs a surface model, not a category model");
            what = job->model;
        } else if (md->category) {
            if (job->refine >= 0) md->refine = job->refine;
            if (job->check_inference) {
                s = error_set(NEUV_ERR_INPUT, "--check-inference needs a surface model, not a category model");
                what = job->model;
            } else if (job->save_model) {
                s = error_set(NEUV_ERR_INPUT, "--save-model with a category model would write that model again, "
                                              "not this shape's (nor --finetune's weights); unwrap without --model to "
                                              "save a model of this shape");
                what = job->model;
            } else if (job->shared_layer && job->finetune > 0) {
                s = error_set(NEUV_ERR_INPUT, "--shared-layer is for inference; --finetune trains the networks");
            } else s = unwrap_with_category(mesh, md, opts, job->finetune, job->shared_layer, &r);
        } else if (job->finetune > 0 || job->refine >= 0 || job->shared_layer) {
            s = error_set(NEUV_ERR_INPUT, "a surface model is applied by inference only: --finetune, --refine and "
                                          "--shared-layer apply to category models (neuv train)");
            what = job->model;
        } else {
            unwrap_apply_options ao = {opts->threads, opts->use_cache, job->check_inference, 0, job->lscm_baseline};
            s = unwrap_apply(mesh, md, &ao, &r);
        }
        if (s == NEUV_OK && job->save_model) {
            s = unwrap_model_save(md, job->save_model);
            what = job->save_model;
        }
        unwrap_model_free(md);
        if (s != NEUV_OK) {
            neuv_unwrap_result_free(r);
            return cli_fail(what, s);
        }
    } else {
        unwrap_model *md = NULL;
        s = unwrap_budgeted(mesh, opts, job->train_faces, job->save_model ? &md : NULL, &r);
        if (s != NEUV_OK) return cli_fail(job->input_name, s);
        if (md) {
            s = unwrap_model_save(md, job->save_model);
            unwrap_model_free(md);
            if (s != NEUV_OK) { neuv_unwrap_result_free(r); return cli_fail(job->save_model, s); }
        }
    }

    double t = now_seconds();
    s = neuv_mesh_save(neuv_unwrap_mesh(r), job->output);
    double export_seconds = now_seconds() - t;
    if (s != NEUV_OK) { neuv_unwrap_result_free(r); return cli_fail(job->output, s); }

    int rc = 0;
    char *json = neuv_unwrap_report_json(r, job->input_name, job->load_seconds, export_seconds);
    if (!json) rc = cli_error(job->input_name, "out of memory writing the report");
    if (rc == 0 && job->report) rc = cli_write_text(job->report, json);
    if (rc == 0 && job->preview) {
        s = preview_write(neuv_unwrap_mesh(r), job->preview, (preview_color)job->preview_color);
        if (s != NEUV_OK) rc = cli_fail(job->preview, s);
    }
    if (rc == 0 && !cli_opts.quiet) {
        const uv_metrics *mt = &r->metrics;
        char sources[256];
        unwrap_source_summary(r, sources, sizeof sources);
        char moved[96] = "";
        if (r->model.moved_charts > 0 && !r->model.trained_on_copy) /* a copy's layout is nobody's texture */
            snprintf(moved, sizeof moved, ", %d chart%s moved from the model's layout", r->model.moved_charts,
                     r->model.moved_charts == 1 ? "" : "s");
        printf("%s: %d charts (%s)%s, qce_mean %.4f, flipped %d, overlap %.4g, packing %.3f, %.1f s -> %s\n",
               job->input_name, r->n_charts, sources, moved, mt->qce_mean, mt->flipped, mt->overlap_fraction,
               mt->packing_efficiency, job->load_seconds + r->total_seconds + export_seconds, job->output);
        if (r->n_repairs > 0) printf("  %d repairs (listed in the report)\n", r->n_repairs);
        if (r->model.trained_on_copy)
            printf("  trained on a simplified copy (%d of %d faces), model applied to the full mesh\n",
                   r->model.train_faces, r->mesh->nf);
    }
    neuv_free(json);
    neuv_unwrap_result_free(r);
    return rc;
}
