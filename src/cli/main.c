/* neuv command line: dispatches to one function per subcommand. */
/* getloadavg is a BSD/GNU function, outside POSIX */
#define _DEFAULT_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/commands.h"

typedef struct command {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *usage;
} command;

static const command commands[] = {
    /* Each command adds one line here, in the order of SPEC.md section 3. */
    {"unwrap", cmd_unwrap, "unwrap IN [-o OUT] [--report R.json] [--preview PREFIX] [--method neural|lscm|harmonic] [--charts auto|K] [--preset fast|paper] [--iters N] [--refine N] [--seed S] [--threads T] [--resolution PX] [--padding PX] [--allow-overlaps] [--save-model M] [--model M [--finetune N] [--check-inference] [--lscm-baseline]] [--train-faces N] [--max-memory MIB] [--seam-angle DEG] [--no-hard-edges] [--quiet]"},
    {"eval", cmd_eval, "eval IN_WITH_UV [--json] [--preview PREFIX] [--preview-color chart|qce|area]"},
    {"pack", cmd_pack, "pack IN_WITH_UV -o OUT [--resolution PX] [--padding PX] [--keep-scale] [--preview PREFIX]   repack the charts of any UV map"},
    {"info", cmd_info, "info IN [--json]   vertices, faces, components, boundaries, genus, repairs"},
    {"flatten", cmd_flatten, "flatten IN --method lscm|harmonic -o OUT   classic flattening of a single disk"},
    {"operators", cmd_operators, "operators IN [--k K] [--hks N] [--json] [--no-cache]"},
    {"geodesics", cmd_geodesics, "geodesics IN --from V [--json]   heat-method distances from one vertex"},
    {"convert", cmd_convert, "convert IN -o OUT   (format by extension: .obj .ply .glb .gltf; UVs kept)"},
    {"inspect", cmd_inspect, "inspect M.neuv [--json]   a checkpoint's configuration and tensors"},
    {"segment", cmd_segment, "segment IN -o OUT [--charts auto|K] [--max-distortion X] [--features hks|xyz] [--preset fast|paper] [--seed S] [--iters N] [--preview PREFIX] [--no-cache] [--json]   PatchNet chart id per face"},
    {"demo", cmd_demo, "demo [-o DIR]   the whole pipeline on a built-in procedural shape"},
    {"remesh", cmd_remesh, "remesh IN -o OUT (--simplify R | --subdivide N [--loop] | --isotropic L | --faces N) [--jitter] [--seed S]   another discretization of the same surface"},
    {"train", cmd_train, "train -o M.neuv IN... [--charts auto|K] [--preset fast|paper] [--iters N] [--patch-iters N] [--seed S] [--report R.json]   a category model: unwrap unseen shapes by inference"},
    {"shape", cmd_shape, "shape NAME -o OUT [--member I]   a built-in procedural shape (bent-capsule: a family for category models)"},
    {"compare", cmd_compare, "compare A_UV B_UV [--json]   UV consistency of two UV maps of the same surface"},
    {NULL, NULL, NULL},
};

static void usage(FILE *out)
{
    fprintf(out, "neuv %s — neural UV unwrapping\n\nusage: neuv COMMAND [options]\n\ncommands:\n",
            neuv_version());
    for (size_t i = 0; commands[i].name; i++)
        fprintf(out, "  neuv %s\n", commands[i].usage);
    fprintf(out, "\nglobal options: --quiet, --threads T\n"
                 "exit codes: 0 success, 2 bad input or usage, 1 internal error\n");
}

/* How libgomp's idle threads wait after a parallel loop. It reads the
 * policy once, when it is loaded, so the CLI re-executes itself once with
 * its choice unless the user set OMP_WAIT_POLICY or GOMP_SPINCOUNT:
 *   - cores free (1-minute load average below the cores less one half): a
 *     brief spin, GOMP_SPINCOUNT=10000. A training step is hundreds of short
 *     parallel loops; waking sleeping threads for each cost spot 16.6 s
 *     against 14.1 s (300 steps, 2 threads, idle machine);
 *   - cores busy: PASSIVE. Spinning threads take the cores the working ones
 *     need: 26.4 s passive, 29.1 s with the brief spin, 33.5 s with libgomp's
 *     default spin beside two busy processes (bench/RESULTS.md, "OpenMP wait
 *     policy"). If exec fails, it simply runs as is. */
static void choose_openmp_wait(char **argv)
{
    if (getenv("OMP_WAIT_POLICY") || getenv("GOMP_SPINCOUNT")) return;
    double load[1];
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    if (getloadavg(load, 1) == 1 && cores > 1 && load[0] < (double)cores - 0.5)
        setenv("GOMP_SPINCOUNT", "10000", 1);
    else
        setenv("OMP_WAIT_POLICY", "PASSIVE", 1);
    execv("/proc/self/exe", argv);
}

int main(int argc, char **argv)
{
    choose_openmp_wait(argv);
    if (argc < 2) { usage(stderr); return 2; }
    const char *name = argv[1];
    if (!strcmp(name, "-h") || !strcmp(name, "--help") || !strcmp(name, "help")) { usage(stdout); return 0; }
    if (!strcmp(name, "--version") || !strcmp(name, "version")) { printf("neuv %s\n", neuv_version()); return 0; }
    for (size_t i = 0; commands[i].name; i++)
        if (!strcmp(name, commands[i].name)) {
            cli_install_callbacks();
            int rc = commands[i].run(argc - 1, argv + 1);
            cli_progress_done();
            return rc;
        }
    return cli_error(NULL, "unknown command '%s' (try neuv --help)", name);
}
