/* sol_main.c - `sol SUBCOMMAND ...`: dispatch to the subcommands declared in cli.h. */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "sol_core.h"

typedef struct subcommand {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *summary;
} subcommand;

static int version_main(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    printf("sol %s\n", sol_version());
    return CLI_EXIT_OK;
}

static const subcommand subcommands[] = {
    {"plan", cli_plan_main, "list the effects a scene calls for, and those skipped and why"},
    {"render", cli_render_main, "render a scene's reference and engine paths, attribute the error per effect"},
    {"check", cli_check_main, "compare an engine's own output with sol's reference (sol check help)"},
    {"version", version_main, "print the library's version"},
};

static void usage(FILE *to)
{
    fprintf(to, "usage: sol SUBCOMMAND [ARGS...]\n\nsubcommands:\n");
    for (size_t i = 0; i < sizeof subcommands / sizeof subcommands[0]; ++i)
        fprintf(to, "  %-8s %s\n", subcommands[i].name, subcommands[i].summary);
    fprintf(to, "\nexit status: 0 success, 1 check failed, 2 bad input or usage\n");
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return CLI_EXIT_USAGE;
    }
    if (!strcmp(argv[1], "help") || !strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) {
        usage(stdout);
        return CLI_EXIT_OK;
    }
    for (size_t i = 0; i < sizeof subcommands / sizeof subcommands[0]; ++i)
        if (!strcmp(argv[1], subcommands[i].name))
            return subcommands[i].run(argc - 1, argv + 1);
    fprintf(stderr, "sol: unknown subcommand '%s'\n\n", argv[1]);
    usage(stderr);
    return CLI_EXIT_USAGE;
}
