/* The JSON report of an unwrap (SPEC.md section 4). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/json_writer.h"
#include "core/mem.h"
#include "metrics/uv_metrics.h"
#include "metrics/uv_tiles.h"
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

unwrap_chart_figures *unwrap_chart_figures_compute(const struct neuv_unwrap_result *r)
{
    const neuv_mesh *m = r->mesh;
    unwrap_chart_figures *cf = mem_calloc((size_t)(r->n_charts > 0 ? r->n_charts : 1), sizeof *cf);
    if (!cf || !m || !m->tri_uv || !r->face_chart) return cf;
    for (int f = 0; f < m->nf; f++) {
        int c = r->face_chart[f];
        if (c < 0 || c >= r->n_charts) continue;
        double p[3][3], q[3][2], sv[2];
        for (int k = 0; k < 3; k++) {
            int v = m->tri[3 * f + k], t = m->tri_uv[3 * f + k];
            for (int d = 0; d < 3; d++) p[k][d] = m->pos[3 * v + d];
            q[k][0] = m->uv[2 * t];
            q[k][1] = m->uv[2 * t + 1];
        }
        double a = mesh_face_area(m, f);
        cf[c].faces++;
        cf[c].area += a;
        uv_jacobian_singular_values(p, q, sv);
        if (a > 0 && sv[1] > 0 && isfinite(sv[0] / sv[1])) { cf[c].qce_num += a * sv[0] / sv[1]; cf[c].qce_den += a; }
    }
    return cf;
}

void unwrap_provenance_compute(const struct neuv_unwrap_result *r, const unwrap_chart_figures *cf,
                               unwrap_provenance *out)
{
    memset(out, 0, sizeof *out);
    double nq = 0, lq = 0, qa = 0, la = 0;
    for (int c = 0; c < r->n_charts; c++) {
        int src = r->chart_source[c];
        if (src < 0 || src >= CHART_SOURCE_COUNT) continue;
        out->count[src]++;
        out->area[src] += cf[c].area;
        out->total_area += cf[c].area;
        if (chart_source_is_network((chart_source)src) && isfinite(r->chart_net_qce[c])) {
            nq += cf[c].area * r->chart_net_qce[c];
            qa += cf[c].area;
            if (isfinite(r->chart_lscm_qce[c])) { lq += cf[c].area * r->chart_lscm_qce[c]; la += cf[c].area; }
        }
    }
    double t = out->total_area;
    out->network_area_fraction =
        t > 0 ? (out->area[CHART_SOURCE_NETWORK] + out->area[CHART_SOURCE_NETWORK_REFINED]) / t : 0;
    out->network_qce_mean = qa > 0 ? nq / qa : NAN;
    out->lscm_qce_mean_same_charts = la > 0 && la >= qa * (1 - 1e-12) ? lq / la : NAN;
}

static void json_number_or_null(json_writer *w, double v)
{
    if (isfinite(v)) json_number(w, v);
    else json_null(w);
}

/* "provenance": charts and area share per source, the networks' own
 * qce_mean over the charts they mapped injectively and LSCM's on the same
 * charts; "chart_list": every chart's figures. */
static void write_provenance(json_writer *w, const struct neuv_unwrap_result *r)
{
    unwrap_chart_figures *cf = unwrap_chart_figures_compute(r);
    if (!cf) { w->failed = 1; return; } /* out of memory: no report rather than one without provenance */
    if (!r->chart_source) { mem_free(cf); return; }
    unwrap_provenance pv;
    unwrap_provenance_compute(r, cf, &pv);
    const int *count = pv.count;
    const double *area = pv.area;
    double total = pv.total_area;
    json_key(w, "provenance");
    json_begin_object(w);
    json_key(w, "sources");
    json_begin_object(w);
    for (int k = 0; k < CHART_SOURCE_COUNT; k++) {
        if (count[k] == 0 && k != CHART_SOURCE_NETWORK) continue;
        json_key(w, chart_source_name((chart_source)k));
        json_begin_object(w);
        json_key(w, "charts"); json_int(w, count[k]);
        json_key(w, "area_fraction"); json_number(w, total > 0 ? area[k] / total : 0);
        json_end_object(w);
    }
    json_end_object(w);
    json_key(w, "network_area_fraction"); json_number(w, pv.network_area_fraction);
    json_key(w, "network_qce_mean"); json_number_or_null(w, pv.network_qce_mean);
    json_key(w, "lscm_qce_mean_same_charts"); json_number_or_null(w, pv.lscm_qce_mean_same_charts);
    json_end_object(w);

    json_key(w, "chart_list");
    json_begin_array(w);
    for (int c = 0; c < r->n_charts; c++) {
        json_begin_object(w);
        json_key(w, "chart"); json_int(w, c);
        json_key(w, "faces"); json_int(w, cf[c].faces);
        json_key(w, "area"); json_number(w, cf[c].area);
        json_key(w, "source"); json_string(w, chart_source_name((chart_source)r->chart_source[c]));
        json_key(w, "network_qce"); json_number_or_null(w, r->chart_net_qce[c]);
        json_key(w, "lscm_qce"); json_number_or_null(w, r->chart_lscm_qce[c]);
        json_key(w, "qce"); json_number_or_null(w, cf[c].qce_den > 0 ? cf[c].qce_num / cf[c].qce_den : NAN);
        json_end_object(w);
    }
    json_end_array(w);
    mem_free(cf);
}

void unwrap_source_summary(const struct neuv_unwrap_result *r, char *buf, size_t n)
{
    int count[CHART_SOURCE_COUNT] = {0};
    for (int c = 0; r->chart_source && c < r->n_charts; c++)
        if (r->chart_source[c] >= 0 && r->chart_source[c] < CHART_SOURCE_COUNT) count[r->chart_source[c]]++;
    size_t used = 0;
    buf[0] = 0;
    for (int k = 0; k < CHART_SOURCE_COUNT && used < n; k++) {
        if (count[k] == 0) continue;
        int w = snprintf(buf + used, n - used, "%s%d %s", used ? ", " : "", count[k], chart_source_name((chart_source)k));
        if (w < 0) break;
        used += (size_t)w;
    }
}

/* The stages from operators to metrics (seconds: STAGE_COUNT entries). */
static void write_stage_seconds(json_writer *w, const double *seconds)
{
    static const struct { const char *key; int stage; } stages[] = {
        {"operators", STAGE_OPERATORS}, {"patches", STAGE_PATCHES}, {"param", STAGE_PARAM},
        {"repair", STAGE_REPAIR}, {"pack", STAGE_PACK}, {"metrics", STAGE_METRICS}};
    for (size_t i = 0; i < sizeof stages / sizeof stages[0]; i++) {
        json_key(w, stages[i].key);
        json_number(w, seconds[stages[i].stage]);
    }
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
    json_key(w, "fragment_charts"); json_int(w, r->model.fragment_charts);
    json_key(w, "settled_faces"); json_int(w, r->model.settled_faces);
    json_key(w, "map_from");
    json_string(w, r->model.refinement_carried
                       ? "the networks' map at the new vertices plus the source's refinement carried over"
                   : r->model.trained_on_copy
                       ? "the networks' map at the new vertices, each chart's head solved on this mesh where that "
                         "map is better"
                       : "the networks' map at the new vertices");
    if (r->model.trained_on_copy) { json_key(w, "heads_solved_on_mesh"); json_int(w, r->model.heads_solved); }
    json_key(w, "pulled_vertices"); json_int(w, r->model.pulled_vertices);
    json_key(w, "shrunk_charts"); json_int(w, r->model.shrunk_charts);
    json_key(w, "moved_charts"); json_int(w, r->model.moved_charts);
    if (r->model.trained_on_copy) { json_key(w, "repacked"); json_bool(w, r->model.repacked); }
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
    json_key(w, "output_layer");
    json_string(w, r->model.finetune > 0 ? "heads solved after fine-tuning"
                   : r->model.shared_layer ? "shared" : "a head per chart, solved on this shape");
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
    write_stage_seconds(&w, r->seconds);
    json_key(&w, "export"); json_number(&w, export_seconds);
    json_key(&w, "total"); json_number(&w, load_seconds + r->total_seconds + export_seconds);
    if (r->model.trained_on_copy) { /* the stages above are the full mesh's; the copy's training here */
        const double *c = r->model.copy_seconds;
        json_key(&w, "copy");
        json_begin_object(&w);
        json_key(&w, "simplify"); json_number(&w, r->model.copy_simplify_seconds);
        json_key(&w, "clean"); json_number(&w, c[STAGE_CLEAN]);
        write_stage_seconds(&w, c);
        json_key(&w, "total"); json_number(&w, r->model.train_seconds);
        json_end_object(&w);
    }
    json_end_object(&w);

    json_key(&w, "metrics");
    json_begin_object(&w);
    uv_metrics_write_json(&r->metrics, &w);
    json_end_object(&w);

    json_key(&w, "patches");
    json_begin_object(&w);
    json_key(&w, "k"); json_int(&w, r->patches);
    json_key(&w, "iterations"); json_int(&w, r->patch_iterations);
    json_key(&w, "reseeds"); json_int(&w, r->patch_reseeds);
    json_key(&w, "iterations_per_second"); json_number(&w, r->patch_iters_per_second);
    json_key(&w, "operators_cache_hit"); json_bool(&w, r->cache_hit);
    json_end_object(&w);

    json_key(&w, "param");
    json_begin_object(&w);
    json_key(&w, "iterations"); json_int(&w, r->param_iterations);
    json_key(&w, "face_points"); json_int(&w, r->param_face_points);
    json_key(&w, "final_loss"); json_number(&w, r->param_loss);
    json_key(&w, "network_charts"); json_int(&w, r->neural_charts);
    json_key(&w, "refine_steps"); json_int(&w, r->refine_steps);
    json_key(&w, "refine_seconds"); json_number(&w, r->refine_seconds);
    json_key(&w, "refine_stopped_charts"); json_int(&w, r->refine_stopped);
    json_end_object(&w);

    json_key(&w, "pack");
    json_begin_object(&w);
    json_key(&w, "resolution"); json_int(&w, r->opts.resolution);
    json_key(&w, "padding"); json_int(&w, r->opts.padding);
    json_key(&w, "efficiency"); json_number(&w, r->pack.efficiency);
    json_key(&w, "texels_per_unit"); json_number(&w, r->opts.texels_per_unit);
    json_key(&w, "split_charts"); json_int(&w, r->pack_splits);
    json_key(&w, "split_trials"); json_int(&w, r->pack_split_trials);
    json_key(&w, "split_seconds"); json_number(&w, r->pack_split_seconds);
    json_end_object(&w);

    /* The tiles of the written atlas (one, 1001, without texels_per_unit). */
    neuv_uv_tile *tiles = NULL;
    int ntiles = 0;
    if (uv_tiles_compute(r->mesh, &tiles, &ntiles) != NEUV_OK) w.failed = 1;
    json_key(&w, "tiles");
    uv_tiles_write_json(tiles, ntiles, &w);
    mem_free(tiles);

    json_key(&w, "seams");
    json_begin_object(&w);
    json_key(&w, "angle"); json_number(&w, r->opts.seam_angle);
    json_key(&w, "required_edges"); json_int(&w, r->seam_edges);
    json_key(&w, "above_angle"); json_int(&w, r->seam_edges_angle);
    json_key(&w, "user_pairs"); json_int(&w, r->opts.seam_edge_count);
    json_key(&w, "user_pairs_unmatched"); json_int(&w, r->seam_unmatched);
    json_key(&w, "hard_edges"); json_bool(&w, r->opts.hard_edges);
    json_key(&w, "from_normals"); json_int(&w, r->hard.from_normals);
    json_key(&w, "from_materials"); json_int(&w, r->hard.from_materials);
    json_key(&w, "flat_shaded"); json_bool(&w, r->hard.flat_shaded);
    json_key(&w, "hard_edges_not_kept"); json_int(&w, r->hard_edges_not_kept);
    json_key(&w, "crossed"); json_int(&w, r->seam_crossed);
    json_end_object(&w);

    json_key(&w, "polygons");
    json_begin_object(&w);
    json_key(&w, "input"); json_int(&w, r->polygons);
    json_key(&w, "split"); json_int(&w, r->polygons_split);
    json_end_object(&w);

    json_key(&w, "cleaning");
    write_cleaning(&w, &r->clean);

    write_provenance(&w, r);

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

    if (w.failed) { json_free(&w); error_nomem("the report"); return NULL; }
    char *text = w.buf; /* hand the buffer over */
    if (!text && !(text = mem_strdup("{}"))) error_nomem("the report");
    return text;
}
