/* cmd_scene.c - `sol plan` and `sol render`: placeholders until the scene layer lands (issue 9). */
#include <stdio.h>

#include "cli.h"

int cli_plan_main(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    fprintf(stderr, "sol plan: not implemented yet\n");
    return CLI_EXIT_USAGE;
}

int cli_render_main(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    fprintf(stderr, "sol render: not implemented yet\n");
    return CLI_EXIT_USAGE;
}
