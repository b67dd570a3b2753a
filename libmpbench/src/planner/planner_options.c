/* planner_options.c - the command-line options all planner processes share. */
#include "mpbench/mpbench.h"
#include "mpbench/planner.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "core/errbuf.h"

int mpb_planner_option(int argc, char **argv, int *i, mpb_planner_options *o,
                       char *err, size_t errlen)
{
    static const char *const names[] = {"--lcm-url", "--name", "--max-runs",
                                        "--secret-file", NULL};
    const char *a = argv[*i];
    int k = 0;
    while (names[k] && strcmp(a, names[k]) != 0)
        k++;
    if (names[k] == NULL)
        return 0;
    if (*i + 1 >= argc) {
        mpb__set_err(err, errlen, "%s needs a value", a);
        return -1;
    }
    const char *v = argv[++*i];
    switch (k) {
    case 0: o->lcm_url = v; break;
    case 1: o->name = v; break;
    case 3: o->secret_file = v; break;
    default: {
        char *end;
        errno = 0;
        long n = strtol(v, &end, 10);
        if (errno != 0 || end == v || *end != '\0' || n < 0) {
            mpb__set_err(err, errlen, "--max-runs wants a number >= 0, not "
                         "'%.60s'", v);
            return -1;
        }
        o->max_runs = n;
    }
    }
    return 1;
}
