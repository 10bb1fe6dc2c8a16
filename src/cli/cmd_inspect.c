/* neuv inspect M.neuv [--json]
 * A checkpoint's format version, JSON configuration and tensors (name, shape,
 * value range). The whole file is validated first: a malformed checkpoint is
 * one error line and exit code 2. */
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/commands.h"

static void print_text(const char *path, const neuv_checkpoint *c)
{
    int n = neuv_checkpoint_tensor_count(c);
    const char *config = neuv_checkpoint_config(c);
    printf("%s: neuv checkpoint version %u, %d tensor%s, %lld parameters\n", path, neuv_checkpoint_version(c), n,
           n == 1 ? "" : "s", neuv_checkpoint_parameter_count(c));
    printf("  config: %s\n", config[0] ? config : "(empty)");
    if (n) printf("  %-32s %12s %12s %12s %12s\n", "tensor", "shape", "min", "max", "rms");
    for (int i = 0; i < n; i++) {
        neuv_tensor_info t;
        if (neuv_checkpoint_get_tensor(c, i, &t) != NEUV_OK) continue;
        char shape[32];
        snprintf(shape, sizeof shape, "%dx%d", t.rows, t.cols);
        printf("  %-32s %12s %12.5g %12.5g %12.5g", t.name, shape, t.min, t.max, t.rms);
        if (t.nonfinite) printf("  (%lld non-finite)", t.nonfinite);
        printf("\n");
    }
}

int cmd_inspect(int argc, char **argv)
{
    const char *path = NULL;
    int json = 0, bad = 0;
    for (int i = 1; i < argc; i++) {
        if (cli_arg_global(argc, argv, &i, &bad)) { if (bad) return 2; continue; }
        if (!strcmp(argv[i], "--json")) { json = 1; continue; }
        if (argv[i][0] == '-' && argv[i][1]) return cli_error(NULL, "inspect: unknown option '%s'", argv[i]);
        if (path) return cli_error(NULL, "inspect: one checkpoint at a time ('%s' and '%s')", path, argv[i]);
        path = argv[i];
    }
    if (!path) return cli_error(NULL, "usage: neuv inspect M.neuv [--json]");
    neuv_checkpoint *c = NULL;
    neuv_status st = neuv_checkpoint_load(path, &c);
    if (st != NEUV_OK) return cli_fail(path, st);
    int rc = json ? cli_print_document(neuv_checkpoint_json(c, path)) : (print_text(path, c), 0);
    neuv_checkpoint_free(c);
    return rc;
}
