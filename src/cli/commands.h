/* One function per subcommand; each returns the process exit code. */
#ifndef NEUV_CLI_COMMANDS_H
#define NEUV_CLI_COMMANDS_H


#endif
