#include "cli/cli.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

cli_options cli_opts;

int cli_error(const char *what, const char *fmt, ...)
{
    cli_progress_done();
    char msg[768];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    /* Keep it to one line whatever the message holds. */
    for (char *p = msg; *p; p++) if (*p == '\n' || *p == '\r') *p = ' ';
    if (what) fprintf(stderr, "neuv: error: %s: %s\n", what, msg);
    else fprintf(stderr, "neuv: error: %s\n", msg);
    return 2;
}

int cli_fail(const char *what, neuv_status status)
{
    const char *msg = neuv_last_error();
    cli_error(what, "%s", msg && *msg ? msg : neuv_status_name(status));
    return neuv_exit_code(status);
}

double cli_now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ---- progress bar ---------------------------------------------------- */

static struct {
    int active;        /* a partial line is on the terminal */
    char stage[64];
    double stage_start;
    double last_draw;
} bar;

static int progress_cb(void *user, const char *stage, double fraction, const char *detail)
{
    (void)user;
    double now = cli_now_seconds();
    if (strncmp(bar.stage, stage, sizeof bar.stage - 1) != 0) {
        snprintf(bar.stage, sizeof bar.stage, "%s", stage);
        bar.stage_start = now;
        bar.last_draw = 0;
    }
    if (fraction < 1.0 && now - bar.last_draw < 0.1) return 1; /* at most 10 redraws a second */
    bar.last_draw = now;
    if (fraction < 0) fraction = 0;
    if (fraction > 1) fraction = 1;
    const int width = 24;
    char cells[32];
    int filled = (int)(fraction * width + 0.5);
    for (int i = 0; i < width; i++) cells[i] = i < filled ? '#' : '.';
    cells[width] = '\0';
    double elapsed = now - bar.stage_start;
    char eta[32] = "";
    if (fraction > 0.02 && fraction < 1.0) {
        double left = elapsed * (1.0 - fraction) / fraction;
        snprintf(eta, sizeof eta, " ETA %dm%02ds", (int)(left / 60), (int)fmod(left, 60));
    }
    fprintf(stderr, "\r\033[K%-10s [%s] %3d%% %s%s", stage, cells, (int)(fraction * 100 + 0.5),
            detail ? detail : "", eta);
    fflush(stderr);
    bar.active = 1;
    return 1;
}

static void log_cb(void *user, neuv_log_level level, const char *message)
{
    (void)user;
    if (level == NEUV_LOG_DEBUG && !getenv("NEUV_DEBUG")) return;
    if (cli_opts.quiet && level < NEUV_LOG_WARN) return;
    cli_progress_done();
    fprintf(stderr, "neuv: %s%s\n", level == NEUV_LOG_WARN ? "warning: " : "", message);
}

static neuv_callbacks callbacks;

void cli_install_callbacks(void)
{
    int show_bar = !cli_opts.quiet && isatty(STDERR_FILENO);
    callbacks.log = log_cb;
    callbacks.progress = show_bar ? progress_cb : NULL;
    callbacks.user = NULL;
}

const neuv_callbacks *cli_callbacks(void) { return &callbacks; }

void cli_progress_done(void)
{
    if (bar.active) { fputs("\r\033[K", stderr); fflush(stderr); bar.active = 0; }
}

/* ---- arguments ------------------------------------------------------- */

int cli_arg_str(int argc, char **argv, int *i, const char *name, const char **out, int *bad)
{
    if (strcmp(argv[*i], name) != 0) return 0;
    if (*i + 1 >= argc) { cli_error(NULL, "%s needs a value", name); *bad = 1; return 1; }
    *out = argv[++*i];
    return 1;
}

int cli_arg_int(int argc, char **argv, int *i, const char *name, int *out, int *bad)
{
    const char *s = NULL;
    if (!cli_arg_str(argc, argv, i, name, &s, bad)) return 0;
    if (*bad) return 1;
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (errno || *end || end == s || v < -2147483647L || v > 2147483647L) {
        cli_error(NULL, "%s expects an integer, got '%s'", name, s);
        *bad = 1;
        return 1;
    }
    *out = (int)v;
    return 1;
}

int cli_arg_double(int argc, char **argv, int *i, const char *name, double *out, int *bad)
{
    const char *s = NULL;
    if (!cli_arg_str(argc, argv, i, name, &s, bad)) return 0;
    if (*bad) return 1;
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (errno || *end || end == s || !isfinite(v)) {
        cli_error(NULL, "%s expects a number, got '%s'", name, s);
        *bad = 1;
        return 1;
    }
    *out = v;
    return 1;
}

int cli_arg_global(int argc, char **argv, int *i, int *bad)
{
    if (!strcmp(argv[*i], "--quiet") || !strcmp(argv[*i], "-q")) {
        cli_opts.quiet = 1;
        cli_install_callbacks();
        return 1;
    }
    if (cli_arg_int(argc, argv, i, "--threads", &cli_opts.threads, bad)) {
        if (!*bad && cli_opts.threads < 1) {
            cli_error(NULL, "--threads must be at least 1");
            *bad = 1;
        }
        /* Every library call of the command, those whose options carry no threads too (compare, remesh). */
        if (!*bad) neuv_set_threads(cli_opts.threads);
        return 1;
    }
    return 0;
}

int cli_check_output_not_input(const char *out, const char *in)
{
    struct stat so, si;
    if (stat(out, &so) == 0 && stat(in, &si) == 0 && so.st_dev == si.st_dev && so.st_ino == si.st_ino)
        return cli_error(out, "output would overwrite the input file");
    return 0;
}

int cli_check_output_folder(const char *out)
{
    struct stat st;
    if (stat(out, &st) == 0 && S_ISDIR(st.st_mode)) return cli_error(out, "is a directory");
    const char *slash = strrchr(out, '/');
    if (!slash) return 0;
    char dir[4096];
    size_t n = slash == out ? 1 : (size_t)(slash - out);
    if (n >= sizeof dir) return cli_error(out, "path too long");
    memcpy(dir, out, n);
    dir[n] = '\0';
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) return cli_error(out, "folder %s does not exist", dir);
    if (access(dir, W_OK) != 0) return cli_error(out, "folder %s is not writable", dir);
    return 0;
}

int cli_has_extension(const char *path, const char *ext)
{
    size_t n = strlen(path), e = strlen(ext);
    return n >= e && strcasecmp(path + n - e, ext) == 0;
}

int cli_load_clean(const char *in, neuv_mesh **out, neuv_clean_report *report)
{
    *out = NULL;
    neuv_mesh *m = NULL;
    neuv_status st = neuv_mesh_load(in, cli_callbacks(), &m);
    if (st != NEUV_OK) return cli_fail(in, st);
    if ((st = neuv_mesh_clean(m, cli_callbacks(), report)) != NEUV_OK) { neuv_mesh_free(m); return cli_fail(in, st); }
    *out = m;
    return 0;
}

int cli_parse_charts(const char *s, int *out)
{
    if (!strcmp(s, "auto")) { *out = 0; return 0; }
    char *end;
    long k = strtol(s, &end, 10);
    if (end == s || *end || k < 1 || k > 4096)
        return cli_error(NULL, "--charts expects auto or a count in 1..4096, got '%s'", s);
    *out = (int)k;
    return 0;
}

int cli_parse_preset(const char *s, neuv_preset *out)
{
    if (!strcmp(s, "fast")) *out = NEUV_PRESET_FAST;
    else if (!strcmp(s, "paper")) *out = NEUV_PRESET_PAPER;
    else return cli_error(NULL, "--preset expects fast or paper, got '%s'", s);
    return 0;
}

int cli_write_text(const char *path, const char *text)
{
    neuv_status s = neuv_save_text(path, text);
    return s == NEUV_OK ? 0 : cli_fail(path, s);
}

int cli_print_document(char *json)
{
    if (!json) { cli_error(NULL, "%s", neuv_last_error()); return 1; }
    printf("%s\n", json);
    neuv_free(json);
    return 0;
}

int cli_print_tiles(const char *what, const neuv_mesh *m)
{
    neuv_uv_tile *tiles = NULL;
    int n = 0;
    neuv_status st = neuv_uv_tiles(m, &tiles, &n);
    if (st != NEUV_OK) return cli_fail(what, st);
    if (n > 1 || (n == 1 && tiles[0].udim != 1001)) {
        printf("  %d UDIM tiles:", n);
        for (int i = 0; i < n; i++)
            printf("%s %d efficiency %.3f (%d charts)", i ? "," : "", tiles[i].udim, tiles[i].efficiency,
                   tiles[i].charts);
        printf("\n");
    }
    neuv_free(tiles);
    return 0;
}
