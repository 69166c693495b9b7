/* cmd_check.c - `sol check`: placeholder until the check subcommands land (issue 10). */
#include <stdio.h>

#include "cli.h"

int cli_check_main(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    fprintf(stderr, "sol check: not implemented yet\n");
    return CLI_EXIT_USAGE;
}
