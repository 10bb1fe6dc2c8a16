/* Public PatchNet charts of a mesh on their own (`neuv segment`), and
 * writing and drawing a label per face. */
#include <string.h>

#include "neuv/neuv.h"
#include "api/api_json.h"
#include "atlas/preview.h"
#include "core/error.h"
#include "core/log.h"
#include "core/timer.h"
#include "geometry/operator_cache.h"
#include "io/labels_write.h"
#include "models/patchnet.h"
#include "segment/patchnet_segment.h"

/* The most patches a fixed K may ask for. */
#define MAX_SEGMENT_CHARTS 100000

void neuv_segment_options_init(neuv_segment_options *o)
{
    neuv_chart_options c;
    neuv_chart_options_init(&c);
    memset(o, 0, sizeof *o);
    o->preset = c.preset;
    o->charts = c.charts;
    o->max_distortion = c.max_distortion;
    o->features = NEUV_FEATURES_HKS_NORMALS;
    o->iters = c.iters;
    o->seed = c.seed;
    o->threads = c.threads;
    o->use_cache = c.use_cache;
}

/* The network's input for the public choice; a value outside the enum gives
 * one whose name is NULL. */
static diffusion_net_features network_features(neuv_features f)
{
    switch (f) {
    case NEUV_FEATURES_HKS: return DIFFUSION_NET_HKS;
    case NEUV_FEATURES_XYZ: return DIFFUSION_NET_XYZ;
    case NEUV_FEATURES_HKS_NORMALS: return DIFFUSION_NET_HKS_NORMALS;
    }
    return (diffusion_net_features)-1;
}

static neuv_status patchnet_options_of(const neuv_segment_options *o, patchnet_options *po)
{
    if (o->preset != NEUV_PRESET_FAST && o->preset != NEUV_PRESET_PAPER)
        return error_set(NEUV_ERR_INPUT, "unknown preset %d", (int)o->preset);
    if (o->charts < 0 || o->charts > MAX_SEGMENT_CHARTS)
        return error_set(NEUV_ERR_INPUT, "charts must be 0 (automatic) or a count in 1..%d, got %d", MAX_SEGMENT_CHARTS,
                         o->charts);
    if (!diffusion_net_features_name(network_features(o->features)))
        return error_set(NEUV_ERR_INPUT, "unknown features %d", (int)o->features);
    if (!(o->max_distortion > 1)) return error_set(NEUV_ERR_INPUT, "max_distortion must be above 1, got %g", o->max_distortion);
    if (o->iters < 0) return error_set(NEUV_ERR_INPUT, "iters must be 0 (the preset's) or a step count, got %d", o->iters);
    if (o->threads < 0) return error_set(NEUV_ERR_INPUT, "threads must be 0 (the machine's) or a count, got %d", o->threads);
    patchnet_default_options(po);
    neuv_status s = patchnet_apply_preset(po, o->preset == NEUV_PRESET_PAPER ? "paper" : "fast");
    if (s != NEUV_OK) return s;
    po->charts = o->charts;
    po->features = network_features(o->features);
    po->max_distortion = o->max_distortion;
    po->seed = (uint64_t)o->seed;
    if (o->iters > 0) po->iters = o->iters;
    return NEUV_OK;
}

static neuv_status segment(const neuv_mesh *m, const neuv_segment_options *o, const patchnet_options *po,
                           int *face_chart, int *n, patchnet_report *rep, double *ops_seconds, int *hit)
{
    nn_set_threads(o->threads);
    double t0 = now_seconds();
    operators ops;
    operators_params p = operators_default_params();
    if (po->k_eig > p.k) p.k = po->k_eig;
    neuv_status s = operators_get(m, &p, o->use_cache, &ops, NULL, hit);
    if (s != NEUV_OK) return s;
    *ops_seconds = now_seconds() - t0;
    s = patchnet_segment(m, &ops, po, face_chart, n, NULL, NULL, rep);
    operators_free(&ops);
    return s;
}

neuv_status neuv_segment(const neuv_mesh *mesh, const neuv_segment_options *o, const neuv_callbacks *cb,
                         int *face_chart, int *chart_count, neuv_segment_report *report)
{
    if (!mesh || !face_chart || !chart_count)
        return error_set(NEUV_ERR_INPUT, "neuv_segment: no mesh, or no face_chart or chart_count output");
    *chart_count = 0;
    neuv_segment_options def;
    if (!o) { neuv_segment_options_init(&def); o = &def; }
    patchnet_options po;
    neuv_status s = patchnet_options_of(o, &po);
    if (s != NEUV_OK) return s;
    patchnet_report rep;
    memset(&rep, 0, sizeof rep);
    double ops_seconds = 0;
    int hit = 0, n = 0;
    log_scope scope;
    log_scope_open(&scope, cb);
    s = segment(mesh, o, &po, face_chart, &n, &rep, &ops_seconds, &hit);
    log_scope_close(&scope);
    if (s != NEUV_OK) return s;
    *chart_count = n;
    if (report) {
        memset(report, 0, sizeof *report);
        report->vertices = neuv_mesh_vertex_count(mesh);
        report->faces = neuv_mesh_face_count(mesh);
        report->seed = o->seed;
        report->features = o->features;
        report->patches = rep.k;
        report->label_charts = rep.label_charts;
        report->splits = rep.splits;
        report->charts = n;
        report->iterations = rep.iterations;
        report->iterations_per_second = rep.iters_per_second;
        report->loss = rep.loss;
        report->loss_cos = rep.loss_cos;
        report->loss_geo = rep.loss_geo;
        report->worst_lscm_qce = rep.worst_qce;
        report->lscm_flipped = rep.flipped;
        report->cache_hit = hit;
        report->seconds_operators = ops_seconds;
        report->seconds_geodesics = rep.geodesic_seconds;
        report->seconds_train = rep.train_seconds;
        report->seconds_chart_check = rep.chart_check_seconds;
        report->reseeds = rep.reseeds;
    }
    return NEUV_OK;
}

char *neuv_segment_report_json(const neuv_segment_report *r, const char *input_name, const char *output_name,
                               double load_seconds, double total_seconds)
{
    if (!r) { error_set(NEUV_ERR_INPUT, "neuv_segment_report_json: no report"); return NULL; }
    json_writer w;
    json_init(&w);
    json_begin_object(&w);
    json_key(&w, "input"); json_string(&w, input_name ? input_name : "");
    json_key(&w, "output"); json_string(&w, output_name ? output_name : "");
    json_key(&w, "vertices"); json_int(&w, r->vertices);
    json_key(&w, "faces"); json_int(&w, r->faces);
    json_key(&w, "seed"); json_int(&w, (long long)r->seed);
    const char *features = diffusion_net_features_name(network_features(r->features));
    json_key(&w, "features"); json_string(&w, features ? features : "");
    json_key(&w, "patches"); json_int(&w, r->patches);
    json_key(&w, "label_charts"); json_int(&w, r->label_charts);
    json_key(&w, "reseeds"); json_int(&w, r->reseeds);
    json_key(&w, "splits"); json_int(&w, r->splits);
    json_key(&w, "charts"); json_int(&w, r->charts);
    json_key(&w, "iterations"); json_int(&w, r->iterations);
    json_key(&w, "iterations_per_second"); json_number(&w, r->iterations_per_second);
    json_key(&w, "loss"); json_number(&w, r->loss);
    json_key(&w, "loss_cos"); json_number(&w, r->loss_cos);
    json_key(&w, "loss_geo"); json_number(&w, r->loss_geo);
    json_key(&w, "worst_lscm_qce"); json_number(&w, r->worst_lscm_qce);
    json_key(&w, "lscm_flipped"); json_int(&w, r->lscm_flipped);
    json_key(&w, "seconds");
    json_begin_object(&w);
    json_key(&w, "load"); json_number(&w, load_seconds);
    json_key(&w, "operators"); json_number(&w, r->seconds_operators);
    json_key(&w, "geodesics"); json_number(&w, r->seconds_geodesics);
    json_key(&w, "train"); json_number(&w, r->seconds_train);
    json_key(&w, "chart_check"); json_number(&w, r->seconds_chart_check);
    json_key(&w, "total"); json_number(&w, total_seconds);
    json_end_object(&w);
    json_end_object(&w);
    return api_json_finish(&w);
}

neuv_status neuv_save_face_labels(const neuv_mesh *mesh, const int *labels, const char *path)
{
    if (!mesh || !labels) return error_set(NEUV_ERR_INPUT, "neuv_save_face_labels: no mesh or no labels");
    if (!path || !*path) return error_set(NEUV_ERR_INPUT, "no file name given");
    return labels_write(path, mesh, labels);
}

neuv_status neuv_write_label_preview(const neuv_mesh *mesh, const int *labels, const char *path)
{
    if (!path || !*path) return error_set(NEUV_ERR_INPUT, "no picture file name given");
    return preview_write_labels(mesh, labels, path);
}
