/* neuv eval IN_WITH_UV [--json] [--preview PREFIX] [--preview-color chart|qce|area]
 * The metrics of SPEC.md section 5 for any mesh that carries UVs. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/commands.h"

static void print_number(const char *name, double x, const char *note)
{
    if (isnan(x)) printf("  %-20s %-14s %s\n", name, "-", note);
    else printf("  %-20s %-14.6g %s\n", name, x, note);
}

/* UVs laid out in several UDIM tiles: each tile's efficiency (packing_efficiency covers [0,1]^2 only). */
static int print_tiles(const char *path, const neuv_mesh *m)
{
    neuv_uv_tile *tiles = NULL;
    int n = 0;
    neuv_status st = neuv_uv_tiles(m, &tiles, &n);
    if (st != NEUV_OK) return cli_fail(path, st);
    if (n > 1 || (n == 1 && tiles[0].udim != 1001)) {
        double area = 0;
        for (int i = 0; i < n; i++) area += tiles[i].efficiency;
        printf("  %-20s %-14d UDIM tiles, mean efficiency %.6g\n", "tiles", n, area / n);
        for (int i = 0; i < n; i++)
            printf("    %-18d %-14.6g efficiency, %d charts, %d faces\n", tiles[i].udim, tiles[i].efficiency,
                   tiles[i].charts, tiles[i].faces);
    }
    neuv_free(tiles);
    return 0;
}

static void print_table(const char *path, const neuv_mesh *m, const neuv_metrics *mt)
{
    printf("%s: %d vertices, %d faces\n", path, neuv_mesh_vertex_count(m), neuv_mesh_face_count(m));
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

static int print_json(const char *path, const neuv_mesh *m, const neuv_metrics *mt)
{
    return cli_print_document(neuv_metrics_json(mt, m, path));
}

static int parse_color(const char *s, neuv_preview_color *out)
{
    if (!strcmp(s, "chart")) *out = NEUV_PREVIEW_CHART;
    else if (!strcmp(s, "qce")) *out = NEUV_PREVIEW_QCE;
    else if (!strcmp(s, "area")) *out = NEUV_PREVIEW_AREA;
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
    neuv_preview_color color = NEUV_PREVIEW_CHART;
    if (parse_color(color_name, &color)) return 2;

    neuv_mesh *m = NULL;
    neuv_status st = neuv_mesh_load(in, cli_callbacks(), &m);
    if (st != NEUV_OK) return cli_fail(in, st);
    if (!neuv_mesh_has_uv(m)) {
        neuv_mesh_free(m);
        return cli_error(in, "no UVs: neuv eval needs a mesh that carries texture coordinates");
    }
    /* Seams are edges whose two sides disagree on UVs; that needs the two
     * sides to share vertex indices, which loaders that split vertices per
     * corner do not give. Nothing else is repaired: a metric must describe
     * the map as the file has it. */
    neuv_metrics mt;
    st = neuv_mesh_weld(m, NULL);
    if (st == NEUV_OK) st = neuv_evaluate(m, cli_callbacks(), &mt);
    if (st != NEUV_OK) { neuv_mesh_free(m); return cli_fail(in, st); }
    int rc = json ? print_json(in, m, &mt) : (print_table(in, m, &mt), print_tiles(in, m));
    if (rc == 0 && preview) {
        st = neuv_write_preview(m, preview, color, cli_callbacks());
        if (st != NEUV_OK) rc = cli_fail(preview, st);
    }
    neuv_mesh_free(m);
    return rc;
}
