/* util.c - helpers the `mpb` subcommands share: opening a database, ids,
 * command-line errors. */
#include <errno.h>
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "mpb.h"

mpb_store *tool_open_readonly(const char *cmd, const char *path)
{
    struct stat st;
    mpb_store *s = NULL;

    /* SQLite says only "unable to open database file"; the system says
     * why. */
    if (stat(path, &st) != 0) {
        fprintf(stderr, "mpb %s: cannot open %s: %s\n", cmd, path,
                strerror(errno));
        return NULL;
    }
    if (S_ISDIR(st.st_mode)) {
        fprintf(stderr, "mpb %s: cannot open %s: %s\n", cmd, path,
                strerror(EISDIR));
        return NULL;
    }
    if (mpb_store_open(path, 1, &s) != MPB_OK) {
        /* The store's message names the file and says what is wrong. */
        fprintf(stderr, "mpb %s: %s\n", cmd, mpb_store_errmsg(s));
        mpb_store_close(s);
        return NULL;
    }
    return s;
}

int tool_parse_id(const char *text, int64_t *out)
{
    char *end;
    errno = 0;
    long long v = strtoll(text, &end, 10);
    if (errno != 0 || end == text || *end != '\0' || v <= 0)
        return -1;
    *out = (int64_t)v;
    return 0;
}

int tool_option_error(const char *cmd, int opt, char **argv)
{
    /* getopt_long leaves optind past the word it could not use. */
    fprintf(stderr, opt == ':' ? "mpb %s: %s needs a value (try 'mpb %s --help')\n"
                               : "mpb %s: unknown option '%s' (try 'mpb %s --help')\n",
            cmd, argv[optind - 1], cmd);
    return MPB_EXIT_USAGE;
}

int tool_extra_argument(const char *cmd, const char *arg)
{
    fprintf(stderr, "mpb %s: unexpected argument '%s' (try 'mpb %s --help')\n",
            cmd, arg, cmd);
    return MPB_EXIT_USAGE;
}

static int on_experiment_row(void *ud, const mpb_experiment_row *row)
{
    (void)ud;
    (void)row;
    return 0;
}

int tool_experiment(const char *cmd, mpb_store *s, const char *db,
                    int64_t *experiment)
{
    if (*experiment == 0 &&
        mpb_store_experiment_latest(s, experiment) != MPB_OK) {
        fprintf(stderr, "mpb %s: %s holds no experiment\n", cmd, db);
        return -1;
    }
    if (mpb_store_experiment_get(s, *experiment, on_experiment_row, NULL) ==
            MPB_ENOTFOUND) {
        fprintf(stderr, "mpb %s: %s: no experiment %lld\n", cmd, db,
                (long long)*experiment);
        return -1;
    }
    return 0;
}

const char *tool_problem_set(const mpb_scene_row *scene)
{
    return scene->problem_set != NULL ? scene->problem_set : scene->name;
}

int tool_set_index(char ***sets, int *n, const mpb_scene_row *scene)
{
    const char *set = tool_problem_set(scene);
    for (int i = 0; i < *n; i++)
        if (strcmp((*sets)[i], set) == 0)
            return i;
    char **grown = realloc(*sets, (size_t)(*n + 1) * sizeof *grown);
    if (grown == NULL)
        return -1;
    *sets = grown;
    if ((grown[*n] = strdup(set)) == NULL)
        return -1;
    return (*n)++;
}

int tool_config_add(int64_t **ids, char ***names, int *n,
                    const mpb_planner_config_row *config)
{
    int64_t *grown_ids = realloc(*ids, (size_t)(*n + 1) * sizeof *grown_ids);
    if (grown_ids == NULL)
        return -1;
    *ids = grown_ids;
    char **grown_names = realloc(*names, (size_t)(*n + 1) * sizeof *grown_names);
    if (grown_names == NULL)
        return -1;
    *names = grown_names;
    if ((grown_names[*n] = strdup(config->name)) == NULL)
        return -1;
    grown_ids[(*n)++] = config->id;
    return 0;
}

int tool_scene_add(int64_t **ids, int **set_of, int *n, char ***sets,
                   int *nsets, const mpb_scene_row *scene)
{
    int set = tool_set_index(sets, nsets, scene);
    if (set < 0)
        return -1;
    int64_t *grown_ids = realloc(*ids, (size_t)(*n + 1) * sizeof *grown_ids);
    if (grown_ids == NULL)
        return -1;
    *ids = grown_ids;
    int *grown_of = realloc(*set_of, (size_t)(*n + 1) * sizeof *grown_of);
    if (grown_of == NULL)
        return -1;
    *set_of = grown_of;
    grown_ids[*n] = scene->id;
    grown_of[(*n)++] = set;
    return 0;
}

void tool_csv_text(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '"')
            fputc('"', f);
        fputc(*s, f);
    }
    fputc('"', f);
}
