/* neuv info IN [--json]
 * What a mesh is made of after the standard cleaning: counts, components
 * with their topology (boundary loops, genus, Euler characteristic), and
 * every repair the cleaning had to make. */
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/commands.h"

/* Components listed one per line in the text output; the rest are summed. */
#define INFO_TEXT_COMPONENTS 12

static void print_text(const char *path, const neuv_topology *t)
{
    int ncomp = t->component_count;
    const neuv_component *ct = t->components;
    printf("%s: %d vertices, %d faces, %d component%s, %s\n", path, t->vertices, t->faces, ncomp,
           ncomp == 1 ? "" : "s", t->has_uv ? "with UVs" : "no UVs");
    if (t->input_vertices != t->vertices || t->input_faces != t->faces)
        printf("  as read: %d vertices, %d faces\n", t->input_vertices, t->input_faces);
    if (ncomp > 0) {
        printf("  %9s %9s %9s %6s %6s %6s\n", "component", "faces", "vertices", "loops", "genus", "euler");
        for (int c = 0; c < ncomp && c < INFO_TEXT_COMPONENTS; c++)
            printf("  %9d %9d %9d %6d %6d %6d  %s\n", c, ct[c].faces, ct[c].vertices, ct[c].boundary_loops,
                   ct[c].genus, ct[c].euler, ct[c].closed ? "closed" : "open");
        if (ncomp > INFO_TEXT_COMPONENTS) {
            int faces = 0, closed = 0;
            for (int c = INFO_TEXT_COMPONENTS; c < ncomp; c++) { faces += ct[c].faces; closed += ct[c].closed; }
            printf("  %9s %9d  in %d more components (%d closed; --json lists them all)\n", "...", faces,
                   ncomp - INFO_TEXT_COMPONENTS, closed);
        }
    }
    const neuv_clean_report *r = &t->repairs;
    const struct { int value; const char *what; } f[] = {
        {r->welded_vertices, "duplicate vertices welded"},
        {r->degenerate_faces, "degenerate faces dropped"},
        {r->duplicate_faces, "duplicate faces dropped"},
        {r->unreferenced_vertices, "unreferenced vertices dropped"},
        {r->flipped_faces, "faces flipped to a consistent orientation"},
        {r->nonmanifold_edges, "non-manifold edges split"},
        {r->nonmanifold_vertices, "non-manifold vertices split"},
        {r->split_vertices, "vertices added by the splits"},
        {r->nonorientable_components, "non-orientable components (left as they are)"},
    };
    int any = 0;
    for (size_t i = 0; i < sizeof f / sizeof f[0]; i++)
        if (f[i].value) {
            if (!any) printf("  repairs:\n");
            any = 1;
            printf("  %9d %s\n", f[i].value, f[i].what);
        }
    if (!any) printf("  repairs: none (clean, manifold, consistently oriented)\n");
}

int cmd_info(int argc, char **argv)
{
    const char *in = NULL;
    int json = 0, bad = 0;
    for (int i = 1; i < argc && !bad; i++) {
        if (cli_arg_global(argc, argv, &i, &bad)) continue;
        if (!strcmp(argv[i], "--json")) { json = 1; continue; }
        if (argv[i][0] == '-' && argv[i][1]) return cli_error(NULL, "info: unknown option '%s'", argv[i]);
        if (in) return cli_error(NULL, "info: one input file expected, got '%s' and '%s'", in, argv[i]);
        in = argv[i];
    }
    if (bad) return 2;
    if (!in) return cli_error(NULL, "usage: neuv info IN [--json]");

    neuv_mesh *m = NULL;
    neuv_status st = neuv_mesh_load(in, cli_callbacks(), &m);
    if (st != NEUV_OK) return cli_fail(in, st);
    neuv_topology t;
    st = neuv_mesh_topology(m, cli_callbacks(), &t);
    neuv_mesh_free(m);
    if (st != NEUV_OK) return cli_fail(in, st);
    int rc = 0;
    if (json) rc = cli_print_document(neuv_topology_json(&t, in));
    else print_text(in, &t);
    neuv_free(t.components);
    return rc;
}
