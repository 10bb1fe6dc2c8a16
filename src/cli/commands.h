/* One function per subcommand; each returns the process exit code. */
#ifndef NEUV_CLI_COMMANDS_H
#define NEUV_CLI_COMMANDS_H

int cmd_eval(int argc, char **argv);
int cmd_operators(int argc, char **argv);
int cmd_convert(int argc, char **argv);
int cmd_info(int argc, char **argv);
int cmd_flatten(int argc, char **argv);
int cmd_geodesics(int argc, char **argv);
int cmd_pack(int argc, char **argv);
int cmd_inspect(int argc, char **argv);
int cmd_segment(int argc, char **argv);

int cmd_unwrap(int argc, char **argv);
int cmd_demo(int argc, char **argv);
/* --preview-color chart|qce|area → preview_color; prints the error and returns 2 when unknown. */
int parse_preview_color(const char *s, int *out);
int cmd_remesh(int argc, char **argv);
int cmd_compare(int argc, char **argv);
int cmd_train(int argc, char **argv);
int cmd_shape(int argc, char **argv);

#endif
