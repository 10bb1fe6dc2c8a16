/* neuv convert IN -o OUT
 * Format conversion (OBJ, OFF, PLY, STL, glTF/GLB in; OBJ, PLY, GLB/glTF out)
 * keeping UVs per corner. Nothing is cleaned or welded: the output holds the
 * vertices and faces the input file holds (polygons triangulated). */
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/commands.h"

int cmd_convert(int argc, char **argv)
{
    const char *in = NULL, *out = NULL;
    int bad = 0;
    for (int i = 1; i < argc && !bad; i++) {
        if (cli_arg_global(argc, argv, &i, &bad)) continue;
        if (cli_arg_str(argc, argv, &i, "-o", &out, &bad)) continue;
        if (cli_arg_str(argc, argv, &i, "--output", &out, &bad)) continue;
        if (argv[i][0] == '-' && argv[i][1]) return cli_error(NULL, "convert: unknown option '%s'", argv[i]);
        if (in) return cli_error(NULL, "convert: one input file expected, got '%s' and '%s'", in, argv[i]);
        in = argv[i];
    }
    if (bad) return 2;
    if (!in || !out) return cli_error(NULL, "usage: neuv convert IN -o OUT");
    if (cli_check_output_not_input(out, in)) return 2;

    neuv_mesh *m = NULL;
    neuv_status st = neuv_mesh_load(in, cli_callbacks(), &m);
    if (st != NEUV_OK) return cli_fail(in, st);
    st = neuv_mesh_save(m, out);
    int rc = 0;
    if (st != NEUV_OK) rc = cli_fail(out, st);
    else if (!cli_opts.quiet)
        printf("%s: %d vertices, %d faces%s\n", out, neuv_mesh_vertex_count(m), neuv_mesh_face_count(m),
               neuv_mesh_has_uv(m) ? ", with UVs" : "");
    neuv_mesh_free(m);
    return rc;
}
