/* neuv info IN [--json]
 * What a mesh is made of after the standard cleaning: counts, components
 * with their topology (boundary loops, genus, Euler characteristic), and
 * every repair the cleaning had to make. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/commands.h"
#include "core/json_writer.h"
#include "mesh/clean.h"
#include "mesh/topology.h"

/* Components listed one per line in the text output; the rest are summed. */
#define INFO_TEXT_COMPONENTS 12

typedef struct repair_field { const char *key; int value; const char *what; } repair_field;

static int repair_fields(const mesh_clean_report *r, repair_field out[9])
{
    const repair_field f[9] = {
        {"welded_vertices", r->welded_vertices, "duplicate vertices welded"},
        {"degenerate_faces", r->degenerate_faces, "degenerate faces dropped"},
        {"duplicate_faces", r->duplicate_faces, "duplicate faces dropped"},
        {"unreferenced_vertices", r->unreferenced_vertices, "unreferenced vertices dropped"},
        {"flipped_faces", r->flipped_faces, "faces flipped to a consistent orientation"},
        {"nonmanifold_edges", r->nonmanifold_edges, "non-manifold edges split"},
        {"nonmanifold_vertices", r->nonmanifold_vertices, "non-manifold vertices split"},
        {"split_vertices", r->split_vertices, "vertices added by the splits"},
        {"nonorientable_components", r->nonorientable_components, "non-orientable components (left as they are)"},
    };
    memcpy(out, f, sizeof f);
    return 9;
}

static void print_text(const char *path, int in_nv, int in_nf, const neuv_mesh *m, int ncomp,
                       const component_topology *ct, const mesh_clean_report *r)
{
    printf("%s: %d vertices, %d faces, %d component%s, %s\n", path, m->nv, m->nf, ncomp,
           ncomp == 1 ? "" : "s", m->nuv > 0 ? "with UVs" : "no UVs");
    if (in_nv != m->nv || in_nf != m->nf)
        printf("  as read: %d vertices, %d faces\n", in_nv, in_nf);
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
    repair_field f[9];
    int n = repair_fields(r, f), any = 0;
    for (int i = 0; i < n; i++)
        if (f[i].value) {
            if (!any) printf("  repairs:\n");
            any = 1;
            printf("  %9d %s\n", f[i].value, f[i].what);
        }
    if (!any) printf("  repairs: none (clean, manifold, consistently oriented)\n");
}

static int print_json(const char *path, int in_nv, int in_nf, const neuv_mesh *m, int ncomp,
                      const component_topology *ct, const mesh_clean_report *r)
{
    json_writer w;
    json_init(&w);
    json_begin_object(&w);
    json_key(&w, "version"); json_string(&w, neuv_version());
    json_key(&w, "input"); json_string(&w, path);
    json_key(&w, "input_vertices"); json_int(&w, in_nv);
    json_key(&w, "input_faces"); json_int(&w, in_nf);
    json_key(&w, "vertices"); json_int(&w, m->nv);
    json_key(&w, "faces"); json_int(&w, m->nf);
    json_key(&w, "has_uv"); json_bool(&w, m->nuv > 0);
    json_key(&w, "components");
    json_begin_array(&w);
    for (int c = 0; c < ncomp; c++) {
        json_begin_object(&w);
        json_key(&w, "faces"); json_int(&w, ct[c].faces);
        json_key(&w, "vertices"); json_int(&w, ct[c].vertices);
        json_key(&w, "edges"); json_int(&w, ct[c].edges);
        json_key(&w, "boundary_loops"); json_int(&w, ct[c].boundary_loops);
        json_key(&w, "genus"); json_int(&w, ct[c].genus);
        json_key(&w, "euler"); json_int(&w, ct[c].euler);
        json_key(&w, "closed"); json_bool(&w, ct[c].closed);
        json_end_object(&w);
    }
    json_end_array(&w);
    json_key(&w, "repairs");
    json_begin_object(&w);
    repair_field f[9];
    int n = repair_fields(r, f);
    for (int i = 0; i < n; i++) { json_key(&w, f[i].key); json_int(&w, f[i].value); }
    json_end_object(&w);
    json_end_object(&w);
    return cli_print_json(&w);
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
    int in_nv = m->nv, in_nf = m->nf;
    mesh_clean_report rep;
    st = mesh_clean(m, NULL, &rep);
    if (st != NEUV_OK) { mesh_free(m); return cli_fail(in, st); }

    int *label = malloc(sizeof(int) * (size_t)(m->nf > 0 ? m->nf : 1));
    int ncomp = label ? mesh_face_components(m, label) : -1;
    /* Faces grouped by component (counting sort) so each component's
     * topology costs time linear in its size. */
    int *start = ncomp >= 0 ? calloc((size_t)ncomp + 2, sizeof(int)) : NULL;
    int *faces = malloc(sizeof(int) * (size_t)(m->nf > 0 ? m->nf : 1));
    component_topology *ct = ncomp >= 0 ? calloc((size_t)ncomp + 1, sizeof *ct) : NULL;
    int rc = 0;
    if (!label || ncomp < 0 || !start || !faces || !ct) {
        rc = cli_error(in, "out of memory computing components");
    } else {
        for (int f = 0; f < m->nf; f++) start[label[f] + 2]++;
        for (int c = 0; c < ncomp; c++) start[c + 2] += start[c + 1];
        for (int f = 0; f < m->nf; f++) faces[start[label[f] + 1]++] = f;
        for (int c = 0; c < ncomp && rc == 0; c++) {
            st = mesh_faces_topology(m, faces + start[c], start[c + 1] - start[c], &ct[c]);
            if (st != NEUV_OK) rc = cli_fail(in, st);
        }
    }
    if (rc == 0) {
        if (json) rc = print_json(in, in_nv, in_nf, m, ncomp, ct, &rep);
        else print_text(in, in_nv, in_nf, m, ncomp, ct, &rep);
    }
    free(label); free(start); free(faces); free(ct);
    mesh_free(m);
    return rc;
}
