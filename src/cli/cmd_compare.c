/* neuv compare A_UV B_UV [--json]
 * UV consistency of two UV maps of the same surface: distance of B's UVs to
 * A's UVs at the same surface points, and the share of B's surface whose
 * chart agrees with A's. */
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/commands.h"

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
        if (st) { neuv_mesh_free(m[0]); return cli_fail(path[k], st); }
        const char *missing = neuv_mesh_face_count(m[k]) == 0 ? "the mesh has no faces"
                            : !neuv_mesh_has_uv(m[k])       ? "the mesh has no UVs to compare" : NULL;
        if (missing) { neuv_mesh_free(m[0]); neuv_mesh_free(m[1]); return cli_error(path[k], "%s", missing); }
    }
    neuv_uv_comparison r;
    neuv_status st = neuv_compare_uvs(m[0], m[1], cli_callbacks(), &r);
    neuv_mesh_free(m[0]);
    neuv_mesh_free(m[1]);
    if (st) return cli_fail(path[1], st);
    if (json) return cli_print_document(neuv_uv_comparison_json(&r, path[0], path[1]));
    printf("%s vs %s\n", path[0], path[1]);
    printf("  UV distance (atlas units) over %d corners of B, in the matched chart: mean %.6g  p95 %.6g  max %.6g"
           " (%.2f%% of corners past its seam, compared with its map extended)\n",
           r.vertices_compared, r.uv_mean, r.uv_p95, r.uv_max, 100 * r.across_seam);
    printf("  UV distance at the closest point whatever its chart: mean %.6g  p95 %.6g  max %.6g\n", r.nearest_mean,
           r.nearest_p95, r.nearest_max);
    printf("  chart agreement: %.2f%% of B's area (%.2f%% of its faces; %.2f%% of its area with each face located on "
           "A's faces facing its way)\n", 100 * r.chart_agreement, 100 * r.chart_agreement_faces,
           100 * r.chart_agreement_facing);
    printf("  faces: A %d, B %d; charts: A %d, B %d; B's farthest vertex from A's surface %.3g\n", r.faces_a, r.faces_b,
           r.charts_a, r.charts_b, r.max_surface_distance);
    printf("  B: %d flipped faces, overlap %.3g, qce_mean %.4f\n", r.b_metrics.flipped, r.b_metrics.overlap_fraction,
           r.b_metrics.qce_mean);
    return 0;
}
