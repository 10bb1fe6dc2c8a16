/* neuv shape NAME -o OUT [--member I]: writes a built-in procedural shape
 * (to try neuv without data, and to make category-model families). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/commands.h"
#include "mesh/blob_family.h"
#include "mesh/shape_family.h"
#include "mesh/shapes.h"

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
    int family = !strcmp(name, "bent-capsule") || !strcmp(name, "blob");
    if (member != -1 && !family) return cli_error(NULL, "--member applies to bent-capsule and blob only");
    if (family && member < 0) return cli_error(NULL, "%s needs --member I (I >= 0)", name);
    neuv_mesh *m = NULL;
    if (family && name[0] == 'b' && name[1] == 'e') m = shape_capsule_family((uint64_t)member);
    else if (family) m = shape_blob_family((uint64_t)member);
    else if (!strcmp(name, "bumpy-torus")) m = shape_bumpy_torus(1.0, 0.4, 0.25, 96, 40);
    else if (!strcmp(name, "sphere")) m = shape_icosphere(4, 1.0);
    else if (!strcmp(name, "capsule")) m = shape_capsule(0.5, 1.5, 32, 8);
    else if (!strcmp(name, "cube")) m = shape_cube(16);
    else if (!strcmp(name, "genus2")) m = shape_genus2(4);
    else return cli_error(NULL, "unknown shape '%s' (expected bumpy-torus, sphere, capsule, cube, genus2, bent-capsule or blob)", name);
    if (!m) return cli_error(NULL, "out of memory");
    int rc = cli_check_output_folder(out);
    if (rc == 0) {
        neuv_status s = neuv_mesh_save(m, out);
        if (s != NEUV_OK) rc = cli_fail(out, s);
    }
    if (rc == 0 && !cli_opts.quiet)
        printf("%s: %d vertices, %d faces -> %s\n", name, m->nv, m->nf, out);
    mesh_free(m);
    return rc;
}
