/* neuv eval IN_WITH_UV [--json] [--preview PREFIX] [--preview-color chart|qce|area]
 * The metrics of SPEC.md section 5 for any mesh that carries UVs. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "atlas/preview.h"
#include "cli/cli.h"
#include "cli/commands.h"
#include "core/json_writer.h"
#include "mesh/clean.h"
#include "metrics/uv_metrics.h"

static void print_number(const char *name, double x, const char *note)
{
    if (isnan(x)) printf("  %-20s %-14s %s\n", name, "-", note);
    else printf("  %-20s %-14.6g %s\n", name, x, note);
}

static void print_table(const char *path, const neuv_mesh *m, const uv_metrics *mt)
{
    printf("%s: %d vertices, %d faces\n", path, m->nv, m->nf);
    printf("  %-20s %-14d\n", "charts", mt->charts);
    print_number("qce_mean", mt->qce_mean, "ideal 1 (angle distortion s1/s2)");
    print_number("qce_p95", mt->qce_p95, "");
    print_number("qce_max", mt->qce_max, "");
    print_number("ase_mean", mt->ase_mean, "ideal 0 (log area ratio, signed)");
    print_number("ase_abs_mean", mt->ase_abs_mean, "ideal 0");
    print_number("ase_abs_mean_chart", mt->ase_abs_mean_chart, "ideal 0 (per chart scale)");
    print_number("l2_stretch", mt->l2_stretch, "ideal 1");
    print_number("linf_stretch", mt->linf_stretch, "ideal 1");
    print_number("sym_dirichlet_mean", mt->sym_dirichlet_mean, "ideal 4");
    printf("  %-20s %-14d\n", "flipped", mt->flipped);
    printf("  %-20s %-14d\n", "degenerate_uv", mt->degenerate_uv);
    print_number("overlap_fraction", mt->overlap_fraction, "ideal 0");
    print_number("packing_efficiency", mt->packing_efficiency,
                 isnan(mt->packing_efficiency) ? "(UVs leave [0,1]^2)" : "UV area in [0,1]^2");
    print_number("seam_length", mt->seam_length, "cut length / sqrt(3D area)");
    if (mt->excluded_faces)
        printf("  %-20s %-14d faces of (near) zero 3D area left out\n", "excluded_faces", mt->excluded_faces);
}

static int print_json(const char *path, const neuv_mesh *m, const uv_metrics *mt)
{
    json_writer w;
    json_init(&w);
    json_begin_object(&w);
    json_key(&w, "version"); json_string(&w, neuv_version());
    json_key(&w, "input"); json_string(&w, path);
    json_key(&w, "vertices"); json_int(&w, m->nv);
    json_key(&w, "faces"); json_int(&w, m->nf);
    json_key(&w, "metrics");
    json_begin_object(&w);
    uv_metrics_write_json(mt, &w);
    json_end_object(&w);
    json_end_object(&w);
    return cli_print_json(&w);
}

static int parse_color(const char *s, preview_color *out)
{
    if (!strcmp(s, "chart")) *out = PREVIEW_COLOR_CHART;
    else if (!strcmp(s, "qce")) *out = PREVIEW_COLOR_QCE;
    else if (!strcmp(s, "area")) *out = PREVIEW_COLOR_AREA;
    else return cli_error(NULL, "--preview-color expects chart, qce or area, got '%s'", s);
    return 0;
}

int cmd_eval(int argc, char **argv)
{
    const char *in = NULL, *preview = NULL, *color_name = "chart";
    int json = 0, bad = 0;
    for (int i = 1; i < argc && !bad; i++) {
        if (cli_arg_global(argc, argv, &i, &bad)) continue;
        if (cli_arg_str(argc, argv, &i, "--preview", &preview, &bad)) continue;
        if (cli_arg_str(argc, argv, &i, "--preview-color", &color_name, &bad)) continue;
        if (!strcmp(argv[i], "--json")) { json = 1; continue; }
        if (argv[i][0] == '-' && argv[i][1]) return cli_error(NULL, "eval: unknown option '%s'", argv[i]);
        if (in) return cli_error(NULL, "eval: one input file expected, got '%s' and '%s'", in, argv[i]);
        in = argv[i];
    }
    if (bad) return 2;
    if (!in) return cli_error(NULL, "usage: neuv eval IN_WITH_UV [--json] [--preview PREFIX] [--preview-color chart|qce|area]");
    preview_color color = PREVIEW_COLOR_CHART;
    if (parse_color(color_name, &color)) return 2;

    neuv_mesh *m = NULL;
    neuv_status st = neuv_mesh_load(in, &m);
    if (st != NEUV_OK) return cli_fail(in, st);
    if (m->nuv == 0) {
        mesh_free(m);
        return cli_error(in, "no UVs: neuv eval needs a mesh that carries texture coordinates");
    }
    /* Seams are edges whose two sides disagree on UVs; that needs the two
     * sides to share vertex indices, which loaders that split vertices per
     * corner do not give. Nothing else is repaired: a metric must describe
     * the map as the file has it. */
    if (mesh_weld_positions(m) < 0) {
        mesh_free(m);
        return cli_error(in, "out of memory welding vertices");
    }
    uv_metrics mt;
    st = uv_metrics_compute(m, &mt);
    if (st != NEUV_OK) { mesh_free(m); return cli_fail(in, st); }
    int rc = json ? print_json(in, m, &mt) : (print_table(in, m, &mt), 0);
    if (rc == 0 && preview) {
        st = preview_write(m, preview, color);
        if (st != NEUV_OK) rc = cli_fail(preview, st);
    }
    mesh_free(m);
    return rc;
}
