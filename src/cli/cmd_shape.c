/* neuv shape NAME -o OUT [--member I]: writes a built-in procedural shape
 * (to try neuv without data, and to make category-model families). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/commands.h"

static const char *usage_text =
    "usage: neuv shape NAME -o OUT [--member I]\n"
    "  NAME: bumpy-torus (the demo shape), sphere, capsule, cube, genus2,\n"
    "        bent-capsule (member I >= 0 of a family of bent capsules of varied proportions),\n"
    "        blob (member I >= 0 of a family of stretched spheres with random bumps and dents)\n";

int cmd_shape(int argc, char **argv)
{
    const char *name = NULL, *out = NULL;
    int member = -1, bad = 0;
    for (int i = 1; i < argc && !bad; i++) {
        if (cli_arg_global(argc, argv, &i, &bad)) continue;
        if (cli_arg_str(argc, argv, &i, "-o", &out, &bad)) continue;
        if (cli_arg_int(argc, argv, &i, "--member", &member, &bad)) continue;
        if (!strcmp(argv[i], "-h") || !strcmp(argv[i], "--help")) { fputs(usage_text, stdout); return 0; }
        if (argv[i][0] == '-' && argv[i][1]) return cli_error(NULL, "shape: unknown option '%s'", argv[i]);
        if (name) return cli_error(NULL, "shape takes one name (got '%s' and '%s')", name, argv[i]);
        name = argv[i];
    }
    if (bad) return 2;
    if (!name || !out) return cli_error(NULL, "shape needs a name and -o OUT (neuv shape --help)");
    neuv_mesh *m = NULL;
    neuv_status st = neuv_shape(name, member, &m);
    if (st != NEUV_OK) return cli_fail(NULL, st);
    int rc = cli_check_output_folder(out);
    if (rc == 0) {
        neuv_status s = neuv_mesh_save(m, out);
        if (s != NEUV_OK) rc = cli_fail(out, s);
    }
    if (rc == 0 && !cli_opts.quiet)
        printf("%s: %d vertices, %d faces -> %s\n", name, neuv_mesh_vertex_count(m), neuv_mesh_face_count(m), out);
    neuv_mesh_free(m);
    return rc;
}
