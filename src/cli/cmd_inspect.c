/* neuv inspect M.neuv [--json]
 * A checkpoint's format version, JSON configuration and tensors (name, shape,
 * value range). The whole file is validated first: a malformed checkpoint is
 * one error line and exit code 2. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/commands.h"
#include "core/json_writer.h"
#include "nn/checkpoint.h"

typedef struct tensor_stats { double min, max, rms; long nonfinite; } tensor_stats;

static tensor_stats stats_of(const nn_checkpoint_tensor *t)
{
    tensor_stats s = {INFINITY, -INFINITY, 0, 0};
    double sq = 0;
    long n = (long)t->rows * t->cols, finite = 0;
    for (long i = 0; i < n; i++) {
        double v = t->data[i];
        if (!isfinite(v)) { s.nonfinite++; continue; }
        finite++;
        if (v < s.min) s.min = v;
        if (v > s.max) s.max = v;
        sq += v * v;
    }
    if (finite) s.rms = sqrt(sq / (double)finite);
    else s.min = s.max = NAN;
    return s;
}

static long parameter_count(const nn_checkpoint *c)
{
    long n = 0;
    for (int i = 0; i < c->n; i++) n += (long)c->t[i].rows * c->t[i].cols;
    return n;
}

static void print_text(const char *path, const nn_checkpoint *c)
{
    printf("%s: neuv checkpoint version %u, %d tensor%s, %ld parameters\n", path, c->version, c->n,
           c->n == 1 ? "" : "s", parameter_count(c));
    printf("  config: %s\n", c->config[0] ? c->config : "(empty)");
    if (c->n) printf("  %-32s %12s %12s %12s %12s\n", "tensor", "shape", "min", "max", "rms");
    for (int i = 0; i < c->n; i++) {
        const nn_checkpoint_tensor *t = &c->t[i];
        tensor_stats s = stats_of(t);
        char shape[32];
        snprintf(shape, sizeof shape, "%dx%d", t->rows, t->cols);
        printf("  %-32s %12s %12.5g %12.5g %12.5g", t->name, shape, s.min, s.max, s.rms);
        if (s.nonfinite) printf("  (%ld non-finite)", s.nonfinite);
        printf("\n");
    }
}

static int print_json(const char *path, const nn_checkpoint *c)
{
    json_writer w;
    json_init(&w);
    json_begin_object(&w);
    json_key(&w, "file"); json_string(&w, path);
    json_key(&w, "version"); json_int(&w, c->version);
    json_key(&w, "config"); json_string(&w, c->config);
    json_key(&w, "parameters"); json_int(&w, parameter_count(c));
    json_key(&w, "tensors");
    json_begin_array(&w);
    for (int i = 0; i < c->n; i++) {
        tensor_stats s = stats_of(&c->t[i]);
        json_begin_object(&w);
        json_key(&w, "name"); json_string(&w, c->t[i].name);
        json_key(&w, "rows"); json_int(&w, c->t[i].rows);
        json_key(&w, "cols"); json_int(&w, c->t[i].cols);
        json_key(&w, "min"); json_number(&w, s.min);
        json_key(&w, "max"); json_number(&w, s.max);
        json_key(&w, "rms"); json_number(&w, s.rms);
        json_key(&w, "nonfinite"); json_int(&w, s.nonfinite);
        json_end_object(&w);
    }
    json_end_array(&w);
    json_end_object(&w);
    if (w.failed) { json_free(&w); return cli_error(path, "out of memory writing JSON"); }
    printf("%s\n", json_text(&w));
    json_free(&w);
    return 0;
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
    nn_checkpoint c;
    neuv_status st = nn_checkpoint_load(path, &c);
    if (st != NEUV_OK) return cli_fail(path, st);
    int rc = json ? print_json(path, &c) : (print_text(path, &c), 0);
    nn_checkpoint_free(&c);
    return rc;
}
