/* The JSON report of an unwrap (SPEC.md section 4). */
#include <stdlib.h>
#include <string.h>

#include "core/json_writer.h"
#include "unwrap/unwrap_internal.h"

static const char *method_name(neuv_method m)
{
    switch (m) {
    case NEUV_METHOD_LSCM: return "lscm";
    case NEUV_METHOD_HARMONIC: return "harmonic";
    default: return "neural";
    }
}

static void write_cleaning(json_writer *w, const mesh_clean_report *c)
{
    json_begin_object(w);
    json_key(w, "welded_vertices"); json_int(w, c->welded_vertices);
    json_key(w, "degenerate_faces"); json_int(w, c->degenerate_faces);
    json_key(w, "duplicate_faces"); json_int(w, c->duplicate_faces);
    json_key(w, "unreferenced_vertices"); json_int(w, c->unreferenced_vertices);
    json_key(w, "flipped_faces"); json_int(w, c->flipped_faces);
    json_key(w, "nonmanifold_edges"); json_int(w, c->nonmanifold_edges);
    json_key(w, "nonmanifold_vertices"); json_int(w, c->nonmanifold_vertices);
    json_key(w, "split_vertices"); json_int(w, c->split_vertices);
    json_key(w, "nonorientable_components"); json_int(w, c->nonorientable_components);
    json_end_object(w);
}

/* The "model" section of an atlas from a saved surface model (unwrap_apply.h). */
static void write_surface_model(json_writer *w, const struct neuv_unwrap_result *r)
{
    json_key(w, "trained_on_simplified_copy"); json_bool(w, r->model.trained_on_copy);
    if (r->model.trained_on_copy) {
        json_key(w, "train_faces"); json_int(w, r->model.train_faces);
        json_key(w, "train_seconds"); json_number(w, r->model.train_seconds);
    }
    json_key(w, "charts_from"); json_string(w, "closest point on the source surface");
    json_key(w, "network_charts"); json_int(w, r->model.network_charts);
    json_key(w, "transferred_charts"); json_int(w, r->model.transferred_charts);
    json_key(w, "empty_source_charts"); json_int(w, r->model.empty_charts);
    json_key(w, "merged_fragments"); json_int(w, r->model.merged_fragments);
    json_key(w, "shrunk_charts"); json_int(w, r->model.shrunk_charts);
    json_key(w, "repacked"); json_bool(w, r->model.repacked);
    json_key(w, "surface_distance"); json_number(w, r->model.surface_distance);
    json_key(w, "inference_seconds"); json_number(w, r->model.inference_seconds);
    json_key(w, "patchnet_label_agreement");
    if (r->model.label_agreement >= 0) json_number(w, r->model.label_agreement);
    else json_null(w);
}

/* The "model" section of an unseen shape unwrapped with a category model. */
static void write_category_model(json_writer *w, const struct neuv_unwrap_result *r)
{
    json_key(w, "charts_from"); json_string(w, "PatchNet inference on this shape");
    json_key(w, "network_charts"); json_int(w, r->model.network_charts);
    json_key(w, "finetune_steps"); json_int(w, r->model.finetune);
    json_key(w, "inference_seconds"); json_number(w, r->model.inference_seconds);
}

char *neuv_unwrap_report_json(const neuv_unwrap_result *r, const char *input_name, double load_seconds,
                              double export_seconds)
{
    json_writer w;
    json_init(&w);
    json_begin_object(&w);
    json_key(&w, "version"); json_string(&w, neuv_version());
    json_key(&w, "input"); json_string(&w, input_name ? input_name : "");
    json_key(&w, "vertices"); json_int(&w, r->mesh->nv);
    json_key(&w, "faces"); json_int(&w, r->mesh->nf);
    json_key(&w, "input_vertices"); json_int(&w, r->input_vertices);
    json_key(&w, "input_faces"); json_int(&w, r->input_faces);
    json_key(&w, "method"); json_string(&w, method_name(r->opts.method));
    json_key(&w, "preset"); json_string(&w, r->opts.preset == NEUV_PRESET_PAPER ? "paper" : "fast");
    json_key(&w, "seed"); json_int(&w, (long long)r->opts.seed);
    json_key(&w, "threads"); json_int(&w, r->opts.threads);
    json_key(&w, "charts"); json_int(&w, r->n_charts);

    json_key(&w, "seconds");
    json_begin_object(&w);
    json_key(&w, "load"); json_number(&w, load_seconds + r->seconds[STAGE_CLEAN]);
    json_key(&w, "operators"); json_number(&w, r->seconds[STAGE_OPERATORS]);
    json_key(&w, "patches"); json_number(&w, r->seconds[STAGE_PATCHES]);
    json_key(&w, "param"); json_number(&w, r->seconds[STAGE_PARAM]);
    json_key(&w, "repair"); json_number(&w, r->seconds[STAGE_REPAIR]);
    json_key(&w, "pack"); json_number(&w, r->seconds[STAGE_PACK]);
    json_key(&w, "metrics"); json_number(&w, r->seconds[STAGE_METRICS]);
    json_key(&w, "export"); json_number(&w, export_seconds);
    json_key(&w, "total"); json_number(&w, load_seconds + r->total_seconds + export_seconds);
    json_end_object(&w);

    json_key(&w, "metrics");
    json_begin_object(&w);
    uv_metrics_write_json(&r->metrics, &w);
    json_end_object(&w);

    json_key(&w, "patches");
    json_begin_object(&w);
    json_key(&w, "k"); json_int(&w, r->patches);
    json_key(&w, "iterations"); json_int(&w, r->patch_iterations);
    json_key(&w, "iterations_per_second"); json_number(&w, r->patch_iters_per_second);
    json_key(&w, "operators_cache_hit"); json_bool(&w, r->cache_hit);
    json_end_object(&w);

    json_key(&w, "param");
    json_begin_object(&w);
    json_key(&w, "iterations"); json_int(&w, r->param_iterations);
    json_key(&w, "final_loss"); json_number(&w, r->param_loss);
    json_key(&w, "neural_charts"); json_int(&w, r->neural_charts);
    json_key(&w, "refine_steps"); json_int(&w, r->refine_steps);
    json_key(&w, "refine_seconds"); json_number(&w, r->refine_seconds);
    json_key(&w, "refine_stopped_charts"); json_int(&w, r->refine_stopped);
    json_end_object(&w);

    json_key(&w, "pack");
    json_begin_object(&w);
    json_key(&w, "resolution"); json_int(&w, r->opts.resolution);
    json_key(&w, "padding"); json_int(&w, r->opts.padding);
    json_key(&w, "efficiency"); json_number(&w, r->pack.efficiency);
    json_key(&w, "split_charts"); json_int(&w, r->pack_splits);
    json_key(&w, "split_trials"); json_int(&w, r->pack_split_trials);
    json_end_object(&w);

    json_key(&w, "cleaning");
    write_cleaning(&w, &r->clean);

    if (r->model.used) {
        json_key(&w, "model");
        json_begin_object(&w);
        json_key(&w, "kind"); json_string(&w, r->model.category ? "category" : "surface");
        if (r->model.category) write_category_model(&w, r);
        else write_surface_model(&w, r);
        json_end_object(&w);
    }

    json_key(&w, "repairs");
    json_begin_array(&w);
    for (int i = 0; i < r->n_repairs; i++) {
        json_begin_object(&w);
        json_key(&w, "chart"); json_int(&w, r->repairs[i].chart);
        json_key(&w, "what"); json_string(&w, r->repairs[i].what);
        json_end_object(&w);
    }
    json_end_array(&w);
    json_end_object(&w);

    if (w.failed) { json_free(&w); return NULL; }
    char *text = w.buf; /* hand the buffer over */
    return text ? text : strdup("{}");
}
