/* app/commands.h: the subcommands of the `cumulo` program; each returns the process exit status. */
#ifndef CU_CLI_COMMANDS_H
#define CU_CLI_COMMANDS_H
int cmd_render(int argc, char **argv);
int cmd_bench(int argc, char **argv);
int cmd_run(int argc, char **argv);
int cmd_expand(int argc, char **argv);
int cmd_sun(int argc, char **argv);
int cmd_ig(int argc, char **argv);
#endif
