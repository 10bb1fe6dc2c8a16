/* neuv compare A_UV B_UV [--json]
 * UV consistency of two UV maps of the same surface: distance of B's UVs to
 * A's UVs at the same surface points, and the share of B's surface whose
 * chart agrees with A's. */
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/commands.h"
#include "compare/uv_compare.h"
#include "core/json_writer.h"
#include "metrics/uv_metrics.h"

int cmd_compare(int argc, char **argv)
{
    const char *path[2] = {NULL, NULL};
    int json = 0, bad = 0, n = 0;
    for (int i = 1; i < argc && !bad; i++) {
        if (cli_arg_global(argc, argv, &i, &bad)) continue;
        if (!strcmp(argv[i], "--json")) { json = 1; continue; }
        if (argv[i][0] == '-' && argv[i][1]) return cli_error(NULL, "compare: unknown option '%s'", argv[i]);
        if (n == 2) return cli_error(NULL, "compare: two input files expected, got a third '%s'", argv[i]);
        path[n++] = argv[i];
    }
    if (bad) return 2;
    if (n != 2) return cli_error(NULL, "usage: neuv compare A_UV B_UV [--json]");
    neuv_mesh *m[2] = {NULL, NULL};
    for (int k = 0; k < 2; k++) {
        neuv_status st = neuv_mesh_load(path[k], cli_callbacks(), &m[k]);
        if (st) { mesh_free(m[0]); return cli_fail(path[k], st); }
        if (m[k]->nf == 0) { mesh_free(m[0]); mesh_free(m[1]); return cli_error(path[k], "the mesh has no faces"); }
        if (m[k]->nuv == 0) { mesh_free(m[0]); mesh_free(m[1]); return cli_error(path[k], "the mesh has no UVs to compare"); }
    }
    uv_compare_result r;
    uv_metrics mb;
    neuv_status st = uv_compare(m[0], m[1], &r);
    if (st == NEUV_OK) st = uv_metrics_compute(m[1], &mb);
    mesh_free(m[0]); mesh_free(m[1]);
    if (st) return cli_fail(path[1], st);
    if (json) {
        json_writer w;
        json_init(&w);
        json_begin_object(&w);
        json_key(&w, "a"); json_string(&w, path[0]);
        json_key(&w, "b"); json_string(&w, path[1]);
        json_key(&w, "uv_distance");
        json_begin_object(&w);
        json_key(&w, "mean"); json_number(&w, r.uv_mean);
        json_key(&w, "p95"); json_number(&w, r.uv_p95);
        json_key(&w, "max"); json_number(&w, r.uv_max);
        json_end_object(&w);
        json_key(&w, "uv_distance_nearest");
        json_begin_object(&w);
        json_key(&w, "mean"); json_number(&w, r.nearest_mean);
        json_key(&w, "p95"); json_number(&w, r.nearest_p95);
        json_key(&w, "max"); json_number(&w, r.nearest_max);
        json_end_object(&w);
        json_key(&w, "across_seam"); json_number(&w, r.across_seam);
        json_key(&w, "chart_agreement"); json_number(&w, r.chart_agreement);
        json_key(&w, "chart_agreement_faces"); json_number(&w, r.chart_agreement_faces);
        json_key(&w, "charts_a"); json_int(&w, r.charts_a);
        json_key(&w, "charts_b"); json_int(&w, r.charts_b);
        json_key(&w, "faces_a"); json_int(&w, r.faces_a);
        json_key(&w, "faces_b"); json_int(&w, r.faces_b);
        json_key(&w, "vertices_compared"); json_int(&w, r.vertices_compared);
        json_key(&w, "max_surface_distance"); json_number(&w, r.max_surface_distance);
        json_key(&w, "worst_charts");
        json_begin_array(&w);
        for (int i = 0; i < UV_COMPARE_WORST && r.worst_chart[i] >= 0; i++) {
            json_begin_object(&w);
            json_key(&w, "b_chart"); json_int(&w, r.worst_chart[i]);
            json_key(&w, "a_chart"); json_int(&w, r.worst_match[i]);
            json_key(&w, "corners"); json_int(&w, r.worst_corners[i]);
            json_key(&w, "uv_mean"); json_number(&w, r.worst_mean[i]);
            json_end_object(&w);
        }
        json_end_array(&w);
        json_key(&w, "b_flipped"); json_int(&w, mb.flipped);
        json_key(&w, "b_overlap_fraction"); json_number(&w, mb.overlap_fraction);
        json_key(&w, "b_qce_mean"); json_number(&w, mb.qce_mean);
        json_end_object(&w);
        if (w.failed) { json_free(&w); return cli_error(NULL, "out of memory writing JSON"); }
        printf("%s\n", json_text(&w));
        json_free(&w);
        return 0;
    }
    printf("%s vs %s\n", path[0], path[1]);
    printf("  UV distance (atlas units) over %d corners of B, in the matched chart: mean %.6g  p95 %.6g  max %.6g"
           " (%.2f%% of corners past its seam, compared with its map extended)\n",
           r.vertices_compared, r.uv_mean, r.uv_p95, r.uv_max, 100 * r.across_seam);
    printf("  UV distance at the closest point whatever its chart: mean %.6g  p95 %.6g  max %.6g\n", r.nearest_mean,
           r.nearest_p95, r.nearest_max);
    printf("  chart agreement: %.2f%% of B's area (%.2f%% of its faces)\n", 100 * r.chart_agreement,
           100 * r.chart_agreement_faces);
    printf("  faces: A %d, B %d; charts: A %d, B %d; B's farthest vertex from A's surface %.3g\n", r.faces_a, r.faces_b,
           r.charts_a, r.charts_b, r.max_surface_distance);
    printf("  B: %d flipped faces, overlap %.3g, qce_mean %.4f\n", mb.flipped, mb.overlap_fraction, mb.qce_mean);
    return 0;
}
