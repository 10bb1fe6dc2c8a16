/* Public comparison of two UV maps of one surface (`neuv compare`). */
#include <string.h>

#include "neuv/neuv.h"
#include "api/api_json.h"
#include "compare/uv_compare.h"
#include "core/error.h"
#include "core/log.h"
#include "mesh/clean.h"
#include "mesh/mesh.h"
#include "metrics/uv_metrics.h"

_Static_assert(NEUV_WORST_CHARTS == UV_COMPARE_WORST, "public and internal worst-chart counts differ");

neuv_status neuv_compare_uvs(const neuv_mesh *a, const neuv_mesh *b, const neuv_callbacks *cb, neuv_uv_comparison *out)
{
    if (!a || !b || !out) return error_set(NEUV_ERR_INPUT, "neuv_compare_uvs: no mesh or no output");
    uv_compare_result r;
    uv_metrics mb;
    /* Charts are found across shared edges, as neuv_evaluate finds them: a
     * file that repeats a vertex at each of its patches' borders (the Utah
     * teapot's) would otherwise count every patch as a chart of its own, and
     * the matched-chart distance and the chart agreement would compare
     * patches, not charts. Welding merges only identical positions. */
    neuv_mesh *wa = mesh_clone(a), *wb = mesh_clone(b);
    neuv_status s = !wa || !wb || mesh_weld_positions(wa) < 0 || mesh_weld_positions(wb) < 0
                        ? error_nomem("welding vertices") : NEUV_OK;
    log_scope scope;
    log_scope_open(&scope, cb);
    if (s == NEUV_OK) s = uv_compare(wa, wb, &r);
    if (s == NEUV_OK) s = uv_metrics_compute(wb, &mb);
    log_scope_close(&scope);
    mesh_free(wa);
    mesh_free(wb);
    if (s != NEUV_OK) return s;
    memset(out, 0, sizeof *out);
    out->uv_mean = r.uv_mean;
    out->uv_p95 = r.uv_p95;
    out->uv_max = r.uv_max;
    out->nearest_mean = r.nearest_mean;
    out->nearest_p95 = r.nearest_p95;
    out->nearest_max = r.nearest_max;
    out->across_seam = r.across_seam;
    out->chart_agreement = r.chart_agreement;
    out->chart_agreement_faces = r.chart_agreement_faces;
    out->chart_agreement_facing = r.chart_agreement_facing;
    out->faces_a = r.faces_a;
    out->faces_b = r.faces_b;
    out->charts_a = r.charts_a;
    out->charts_b = r.charts_b;
    out->vertices_compared = r.vertices_compared;
    out->max_surface_distance = r.max_surface_distance;
    for (int i = 0; i < UV_COMPARE_WORST && r.worst_chart[i] >= 0; i++) {
        out->worst[i].b_chart = r.worst_chart[i];
        out->worst[i].a_chart = r.worst_match[i];
        out->worst[i].corners = r.worst_corners[i];
        out->worst[i].uv_mean = r.worst_mean[i];
        out->worst_count = i + 1;
    }
    memcpy(&out->b_metrics, &mb, sizeof out->b_metrics);
    return NEUV_OK;
}

char *neuv_uv_comparison_json(const neuv_uv_comparison *c, const char *a_name, const char *b_name)
{
    if (!c) { error_set(NEUV_ERR_INPUT, "neuv_uv_comparison_json: no comparison"); return NULL; }
    json_writer w;
    json_init(&w);
    json_begin_object(&w);
    json_key(&w, "a"); json_string(&w, a_name ? a_name : "");
    json_key(&w, "b"); json_string(&w, b_name ? b_name : "");
    json_key(&w, "uv_distance");
    json_begin_object(&w);
    json_key(&w, "mean"); json_number(&w, c->uv_mean);
    json_key(&w, "p95"); json_number(&w, c->uv_p95);
    json_key(&w, "max"); json_number(&w, c->uv_max);
    json_end_object(&w);
    json_key(&w, "uv_distance_nearest");
    json_begin_object(&w);
    json_key(&w, "mean"); json_number(&w, c->nearest_mean);
    json_key(&w, "p95"); json_number(&w, c->nearest_p95);
    json_key(&w, "max"); json_number(&w, c->nearest_max);
    json_end_object(&w);
    json_key(&w, "across_seam"); json_number(&w, c->across_seam);
    json_key(&w, "chart_agreement"); json_number(&w, c->chart_agreement);
    json_key(&w, "chart_agreement_faces"); json_number(&w, c->chart_agreement_faces);
    json_key(&w, "chart_agreement_facing"); json_number(&w, c->chart_agreement_facing);
    json_key(&w, "charts_a"); json_int(&w, c->charts_a);
    json_key(&w, "charts_b"); json_int(&w, c->charts_b);
    json_key(&w, "faces_a"); json_int(&w, c->faces_a);
    json_key(&w, "faces_b"); json_int(&w, c->faces_b);
    json_key(&w, "vertices_compared"); json_int(&w, c->vertices_compared);
    json_key(&w, "max_surface_distance"); json_number(&w, c->max_surface_distance);
    json_key(&w, "worst_charts");
    json_begin_array(&w);
    for (int i = 0; i < c->worst_count && i < NEUV_WORST_CHARTS; i++) {
        json_begin_object(&w);
        json_key(&w, "b_chart"); json_int(&w, c->worst[i].b_chart);
        json_key(&w, "a_chart"); json_int(&w, c->worst[i].a_chart);
        json_key(&w, "corners"); json_int(&w, c->worst[i].corners);
        json_key(&w, "uv_mean"); json_number(&w, c->worst[i].uv_mean);
        json_end_object(&w);
    }
    json_end_array(&w);
    json_key(&w, "b_flipped"); json_int(&w, c->b_metrics.flipped);
    json_key(&w, "b_overlap_fraction"); json_number(&w, c->b_metrics.overlap_fraction);
    json_key(&w, "b_qce_mean"); json_number(&w, c->b_metrics.qce_mean);
    json_end_object(&w);
    return api_json_finish(&w);
}
