/* cli.h - the `sol` program's subcommands. The program is a thin front end over library calls:
 * it parses arguments, calls sol_* functions, prints their results and maps them to exit codes.
 *
 * Exit status of every subcommand: 0 success (or check passed), 1 check failed,
 * 2 bad input or usage. Messages go to stderr; machine-readable output (--json) to stdout. */
#ifndef SOL_CLI_H
#define SOL_CLI_H

enum { CLI_EXIT_OK = 0, CLI_EXIT_FAILED = 1, CLI_EXIT_USAGE = 2 };

/* Each subcommand receives argv starting at its own name (argv[0] = "check", ...). */
int cli_check_main(int argc, char **argv);  /* cmd_check.c: sol check <technique> ... */
int cli_plan_main(int argc, char **argv);   /* cmd_scene.c: sol plan SCENE */
int cli_render_main(int argc, char **argv); /* cmd_scene.c: sol render SCENE */

#endif
