/* neuv demo [-o DIR]: the whole pipeline on a built-in procedural shape
 * (a bumpy torus: closed, curved everywhere, with a handle, so charts must be cut). */
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "cli/cli.h"
#include "cli/commands.h"
#include "cli/unwrap_job.h"

int cmd_demo(int argc, char **argv)
{
    const char *dir = "demo-out";
    int bad = 0;
    for (int i = 1; i < argc && !bad; i++) {
        if (cli_arg_global(argc, argv, &i, &bad)) continue;
        if (cli_arg_str(argc, argv, &i, "-o", &dir, &bad)) continue;
        return cli_error(NULL, "demo: unknown argument '%s' (usage: neuv demo [-o DIR])", argv[i]);
    }
    if (bad) return 2;
    if (mkdir(dir, 0755) != 0 && errno != EEXIST) return cli_error(dir, "cannot create folder: %s", strerror(errno));

    neuv_mesh *mesh = NULL;
    neuv_status st = neuv_shape("bumpy-torus", -1, &mesh);
    if (st != NEUV_OK) return cli_fail(NULL, st);
    char input[4096], output[4096], report[4096], preview[4096];
    snprintf(input, sizeof input, "%s/demo-input.obj", dir);
    snprintf(output, sizeof output, "%s/demo.obj", dir);
    snprintf(report, sizeof report, "%s/report.json", dir);
    snprintf(preview, sizeof preview, "%s/demo", dir);
    neuv_status s = neuv_mesh_save(mesh, input);
    if (s != NEUV_OK) { neuv_mesh_free(mesh); return cli_fail(input, s); }
    if (!cli_opts.quiet)
        printf("neuv demo: bumpy torus, %d vertices, %d faces (written to %s)\n", neuv_mesh_vertex_count(mesh),
               neuv_mesh_face_count(mesh), input);

    neuv_unwrap_options o;
    neuv_unwrap_options_init(&o);
    o.threads = cli_opts.threads;
    unwrap_job job = {.input_name = input, .output = output, .report = report, .preview = preview,
                      .preview_color = NEUV_PREVIEW_CHART};
    int rc = unwrap_job_run(mesh, &o, &job);
    neuv_mesh_free(mesh);
    if (rc == 0 && !cli_opts.quiet)
        printf("wrote %s, %s, %s-uv.png, %s-checker.png\n", output, report, preview, preview);
    return rc;
}
