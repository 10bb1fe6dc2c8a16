/* Shared pieces of the neuv command line: errors, progress, arguments. */
#ifndef NEUV_CLI_CLI_H
#define NEUV_CLI_CLI_H

#include "neuv/neuv.h"

/* Global flags parsed before the command runs. */
typedef struct cli_options {
    int quiet;   /* --quiet: no progress, no info messages */
    int threads; /* --threads T (0 = library default) */
} cli_options;
extern cli_options cli_opts;

/* Prints `neuv: error: WHAT: message` on one line and returns 2 (usage/bad input).
 * `what` is usually the file name; NULL omits it. */
int cli_error(const char *what, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* Prints the library's last error for a failed call on `what`; returns its exit code. */
int cli_fail(const char *what, neuv_status status);

/* Seconds on a monotonic clock, for the timings the CLI reports. */
double cli_now_seconds(void);

/* Installs the progress bar (stderr, only on a terminal and without --quiet)
 * and the message logger. */
void cli_install_callbacks(void);
/* Those callbacks, for the library calls that take them. */
const neuv_callbacks *cli_callbacks(void);
/* Ends a progress line so the next output starts on a fresh line. */
void cli_progress_done(void);

/* Loads `in` and cleans it (neuv_mesh_clean_cb, warnings through the CLI's
 * callbacks). On failure prints the one-line error, frees everything, leaves
 * *out NULL and returns the exit code; returns 0 on success. A mesh whose
 * faces all were degenerate is an error. */
int cli_load_clean(const char *in, neuv_mesh **out, neuv_clean_report *report);

/* Argument helpers: return 1 when argv[*i] is `name` and consume its value
 * into *out (advancing *i); print an error and set *bad when the value is
 * missing or malformed. */
int cli_arg_str(int argc, char **argv, int *i, const char *name, const char **out, int *bad);
int cli_arg_int(int argc, char **argv, int *i, const char *name, int *out, int *bad);
int cli_arg_double(int argc, char **argv, int *i, const char *name, double *out, int *bad);
/* Consumes the global flags (--quiet, --threads T) wherever they stand. */
int cli_arg_global(int argc, char **argv, int *i, int *bad);

/* --charts auto|K (K in 1..4096; auto: 0) and --preset fast|paper: 0 on
 * success, else the one-line error is printed and 2 returned. */
int cli_parse_charts(const char *s, int *out);
int cli_parse_preset(const char *s, neuv_preset *out);

/* Prints a JSON document from the library on stdout and releases it;
 * NULL (the library ran out of memory): the error, and 1. */
int cli_print_document(char *json);

/* For UVs in several UDIM tiles (texels per unit): one line with each tile's
 * efficiency and chart count; nothing for one square. Returns 0 or, on
 * failure, the exit code after the message. */
int cli_print_tiles(const char *what, const neuv_mesh *m);

/* Writes text and a newline to path atomically; returns 0 or the exit code
 * (after printing the error). */
int cli_write_text(const char *path, const char *text);

/* Fails early (before long work) when the folder of `out` does not exist
 * or `out` is a directory; returns 0 when it looks writable. */
int cli_check_output_folder(const char *out);

/* 1 when path ends in ext (".obj"), whatever the case. */
int cli_has_extension(const char *path, const char *ext);

/* Refuses to write onto an input file; returns 0 when `out` is safe. */
int cli_check_output_not_input(const char *out, const char *in);

#endif
