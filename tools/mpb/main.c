/*
 * main.c - `mpb`, the mpbench command line: finds the subcommand and hands
 * it the rest of the arguments. The subcommands are listed in mpb.h, one
 * file each.
 */
#include <stdio.h>
#include <string.h>

#include "mpb.h"

typedef struct command {
    const char *name;
    const char *summary;
    int (*run)(int argc, char **argv);
} command;

static const command commands[] = {
#define MPB__TOOL_ENTRY(name, summary) {#name, summary, cmd_##name},
    MPB_TOOL_COMMANDS(MPB__TOOL_ENTRY)
#undef MPB__TOOL_ENTRY
};

#define NUM_COMMANDS ((int)(sizeof commands / sizeof commands[0]))

static void usage(FILE *out)
{
    fprintf(out,
        "usage: mpb COMMAND [OPTIONS] [ARGS]\n"
        "       mpb help [COMMAND]\n"
        "       mpb --version\n"
        "\n"
        "The mpbench command line: reads the SQLite database that mpbenchd\n"
        "writes.\n"
        "\n"
        "Commands:\n");
    for (int i = 0; i < NUM_COMMANDS; i++)
        fprintf(out, "  %-10s %s\n", commands[i].name, commands[i].summary);
    fprintf(out,
        "\n"
        "'mpb COMMAND --help' describes a command. Exit status: 0 on\n"
        "success, 1 on an error, 2 on a bad command line.\n");
}

static const command *find(const char *name)
{
    for (int i = 0; i < NUM_COMMANDS; i++)
        if (strcmp(commands[i].name, name) == 0)
            return &commands[i];
    return NULL;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return MPB_EXIT_USAGE;
    }
    const char *name = argv[1];
    if (strcmp(name, "-h") == 0 || strcmp(name, "--help") == 0) {
        usage(stdout);
        return MPB_EXIT_OK;
    }
    if (strcmp(name, "--version") == 0) {
        printf("mpb (mpbench) %s\n", MPB_VERSION_STRING);
        return MPB_EXIT_OK;
    }
    if (strcmp(name, "help") == 0) {
        if (argc < 3) {
            usage(stdout);
            return MPB_EXIT_OK;
        }
        const command *c = find(argv[2]);
        if (c == NULL) {
            fprintf(stderr, "mpb: unknown command '%s' (try 'mpb --help')\n",
                    argv[2]);
            return MPB_EXIT_USAGE;
        }
        char help[] = "--help";
        char *help_argv[] = {argv[2], help, NULL};
        return c->run(2, help_argv);
    }
    const command *c = find(name);
    if (c == NULL) {
        fprintf(stderr, "mpb: unknown command '%s' (try 'mpb --help')\n",
                name);
        return MPB_EXIT_USAGE;
    }
    return c->run(argc - 1, argv + 1);
}
