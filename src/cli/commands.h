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

#endif
