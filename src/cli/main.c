/* neuv command line: dispatches to one function per subcommand. */
#include <dirent.h>
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

/* Runnable tasks of this process (its own threads: OpenBLAS starts its
 * pool when it is loaded), from the state field of /proc/self/task/N/stat. */
static int own_tasks_running(void)
{
    DIR *d = opendir("/proc/self/task");
    if (!d) return 0;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        if (e->d_name[0] == '.') continue;
        char path[64], line[512];
        snprintf(path, sizeof path, "/proc/self/task/%.20s/stat", e->d_name);
        FILE *f = fopen(path, "r");
        if (!f) continue;
        size_t got = fread(line, 1, sizeof line - 1, f);
        fclose(f);
        line[got] = 0;
        const char *close = strrchr(line, ')'); /* the state follows the command name in parentheses */
        if (close && close[1] == ' ' && close[2] == 'R') n++;
    }
    closedir(d);
    return n;
}

static int other_tasks_running(void)
{
    FILE *f = fopen("/proc/loadavg", "r");
    int running = -1;
    if (f) {
        if (fscanf(f, "%*f %*f %*f %d/", &running) != 1) running = -1;
        fclose(f);
    }
    if (running < 1) return -1;
    int own = own_tasks_running();
    return running - (own > 0 ? own : 1);
}

/* How libgomp's idle threads wait after a parallel loop. It reads the
 * policy once, when it is loaded, so the CLI re-executes itself once with
 * its choice unless the user set OMP_WAIT_POLICY or GOMP_SPINCOUNT:
 *   - no other task running (Linux's count of runnable tasks, the 4th
 *     field of /proc/loadavg, less this process's own): a brief spin,
 *     GOMP_SPINCOUNT=10000. A training step is hundreds of short parallel
 *     loops; waking sleeping threads for each cost spot 17.1 s against
 *     15.1 s (300 steps, 2 threads, idle machine);
 *   - otherwise, or where that count cannot be read: PASSIVE. Spinning
 *     threads take the cores the working ones need: 28.1 s passive, 31.4 s
 *     with the brief spin, 56.6 s with libgomp's default spin beside two
 *     busy processes (bench/RESULTS.md, "OpenMP wait policy").
 * The count is of this instant, not the load average: a user's previous
 * unwrap would keep that high for a minute after it ended. If exec fails,
 * the command simply runs as is. */
static void choose_openmp_wait(char **argv)
{
    if (getenv("OMP_WAIT_POLICY") || getenv("GOMP_SPINCOUNT")) return;
    if (other_tasks_running() == 0)
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
