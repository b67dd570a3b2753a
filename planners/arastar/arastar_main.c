/* arastar_main.c - mpb-planner-arastar: command line, then the kit serves. */
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "mpbench/mpbench.h"
#include "mpbench/planner.h"
#include "solve.h"

static void usage(FILE *out)
{
    fprintf(out,
"usage: mpb-planner-arastar [--lcm-url URL] [--name NAME] [--max-runs N]\n"
"                           [--secret-file FILE] [-v]\n"
"\n"
"A search-based planner process for mpbench: ARA* over joint-space motion\n"
"primitives, with a heuristic from a 3-D breadth-first search of the\n"
"end-effector over a voxel grid of the scene (as in Cohen, Sucan and\n"
"Chitta's benchmark). Algorithm \"ARAstar\"; pose-region and joint goals;\n"
"URDF robots with MoveIt scenes. It returns the first solution (epsilon\n"
"100) unless the request sets improve=1. Parameters: docs/planners.md.\n"
"\n"
"It announces itself on LCM as NAME@host:pid and serves until SIGINT or\n"
"SIGTERM (or N runs).\n"
"\n"
"options:\n"
"  --lcm-url URL   LCM URL to join (default %s;\n"
"                  the daemon must use the same one)\n"
"  --name NAME     planner name used in experiment files (default \"arastar\")\n"
"  --max-runs N    exit after answering N runs (default 0: no limit)\n"
"  --secret-file F authenticate every message with the shared secret in F\n"
"                  (the daemon must use the same file)\n"
"  -v              one line per run on stderr\n"
"  --help          show this text\n",
            MPB_DEFAULT_LCM_URL);
}

int main(int argc, char **argv)
{
    mpb_planner_options opt = {.name = "arastar"};
    ara_context ctx = {0};
    char err[256] = "";

    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int took = mpb_planner_option(argc, argv, &i, &opt, err, sizeof err);
        if (took < 0) {
            fprintf(stderr, "mpb-planner-arastar: %s (see --help)\n", err);
            return 2;
        }
        if (took)
            continue;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            usage(stdout);
            return 0;
        }
        if (strcmp(a, "-v") == 0) {
            ctx.verbose = 1;
            continue;
        }
        fprintf(stderr, "mpb-planner-arastar: unknown argument '%s' "
                "(see --help)\n", a);
        return 2;
    }

    static const char *const algorithms[] = { "ARAstar" };
    static const char *const approaches[] = { "search" };
    mpb_planner_def def = {
        .language = "c",
        .version = MPB_VERSION_STRING,
        .algorithms = algorithms,
        .num_algorithms = 1,
        .approaches = approaches,
        .solve = ara_solve,
        .user = &ctx,
    };
    return mpb_planner_main(&def, &opt, "mpb-planner-arastar");
}
