/*
 * experiment_planners.c - an experiment's planner configurations: the
 * planner family, its algorithms, their parameters and runs.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "experiment_load.h"

/* "key=value;key=value" for the database; keys in file order. */
static char *params_text(const mpb_param_t *p, int n)
{
    size_t cap = 1;
    for (int i = 0; i < n; i++)
        cap += strlen(p[i].key) + strlen(p[i].value) + 2;
    char *s = malloc(cap), *w = s;
    if (s == NULL)
        return NULL;
    *w = '\0';
    for (int i = 0; i < n; i++)
        w += snprintf(w, cap - (size_t)(w - s), "%s%s=%s", i ? ";" : "",
                      p[i].key, p[i].value);
    return s;
}

static int load_params(mpbd_loader *L, mpbd_config *c, yaml_node_t *m)
{
    if (m == NULL)
        return 0;
    if (m->type != YAML_MAPPING_NODE)
        return fail_at(L, m, "params must be a mapping of name: value");
    size_t n = (size_t)(m->data.mapping.pairs.top - m->data.mapping.pairs.start);
    c->params = calloc(n + 1, sizeof *c->params);
    if (c->params == NULL)
        return fail_at(L, m, "out of memory");
    for (yaml_node_pair_t *p = m->data.mapping.pairs.start;
         p < m->data.mapping.pairs.top; p++) {
        const char *k = scalar(node(L, p->key)), *v = scalar(node(L, p->value));
        if (k == NULL || v == NULL)
            return fail_at(L, node(L, p->key),
                           "a parameter must be name: value");
        c->params[c->num_params].key = strdup(k);
        c->params[c->num_params].value = strdup(v);
        c->num_params++;
        if (!c->params[c->num_params - 1].key
            || !c->params[c->num_params - 1].value)
            return fail_at(L, m, "out of memory");
    }
    return 0;
}

/* Add one configuration's runs to *total; the cap is checked as they add
 * up, in 64 bits, so that the product cannot wrap. */
static int add_runs(mpbd_loader *L, const mpbd_experiment *e, int runs,
                    yaml_node_t *where, int64_t *total)
{
    *total += (int64_t)runs * e->num_queries;
    if (*total <= MPBD_RUNS_TOTAL_MAX)
        return 0;
    return fail_at(L, where, "runs: %d makes more than %d runs in all (runs "
                   "x planner configurations x queries)", runs,
                   MPBD_RUNS_TOTAL_MAX);
}

/* A planner announces itself as name@host:pid, an id of at most
 * MPB_PLANNER_ID_MAX characters from [A-Za-z0-9_.:@-] (docs/protocol.md):
 * a family outside that can never be offered, and its runs would wait
 * for ever. */
static int check_family(mpbd_loader *L, const yaml_node_t *n,
                        const char *family)
{
    size_t len = strlen(family);
    if (len > MPB_PLANNER_ID_MAX - 4)
        return fail_at(L, n, "planner '%.40s...' is longer than %d characters: "
                       "no planner id (name@host:pid, at most %d) can hold it",
                       family, MPB_PLANNER_ID_MAX - 4, MPB_PLANNER_ID_MAX);
    for (size_t i = 0; i < len; i++) {
        char c = family[i];
        if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
              (c >= '0' && c <= '9') || strchr("_.:@-", c) != NULL))
            return fail_at(L, n, "planner '%s' can never announce itself: a "
                           "planner id (name@host:pid) holds only letters, "
                           "digits and '_' '.' ':' '@' '-'", family);
    }
    return 0;
}

int mpbd_load_planners(mpbd_loader *L, mpbd_experiment *e, yaml_node_t *root)
{
    static const char *const keys[] = {"planner", "algorithms", "params",
                                       "runs", "name", "approach", NULL};
    yaml_node_t *list = need(L, root, "planners", YAML_SEQUENCE_NODE,
                             "a list of planners");
    size_t total = 0;
    int64_t total_runs = 0;
    /* Where the default runs come from, for the message. */
    yaml_node_t *default_runs = get(L, get(L, root, "experiment"), "runs");
    if (list == NULL)
        return -1;
    for (yaml_node_item_t *it = list->data.sequence.items.start;
         it < list->data.sequence.items.top; it++)
        total += count_items(get(L, node(L, *it), "algorithms"));
    if ((e->configs = calloc(total + 1, sizeof *e->configs)) == NULL)
        return fail_at(L, list, "out of memory");
    if (count_items(list) == 0)
        return fail_at(L, list, "'planners' must not be empty");
    for (yaml_node_item_t *it = list->data.sequence.items.start;
         it < list->data.sequence.items.top; it++) {
        yaml_node_t *m = node(L, *it), *algos, *n;
        char *planner;
        const char *suffix = NULL;
        int runs = e->runs;
        if (m->type != YAML_MAPPING_NODE)
            return fail_at(L, m, "a planner must be a mapping of planner, "
                           "algorithms");
        if (only_keys(L, m, keys) != 0 ||
            (algos = need(L, m, "algorithms", YAML_SEQUENCE_NODE,
                          "a list of algorithm names")) == NULL)
            return -1;
        if (count_items(algos) == 0)
            return fail_at(L, algos, "'algorithms' must not be empty");
        yaml_node_t *runs_node = get(L, m, "runs");
        if (runs_node && parse_positive_int(L, runs_node, "runs", &runs))
            return -1;
        if (runs_node == NULL)
            runs_node = default_runs ? default_runs : m;
        if ((n = get(L, m, "name")) != NULL && (suffix = scalar(n)) == NULL)
            return fail_at(L, n, "name must be a string");
        /* The approach, the paper's word for the kind of planner, for
         * each of these algorithms: over what the planner announces. */
        const char *approach = NULL;
        if ((n = get(L, m, "approach")) != NULL &&
            (approach = scalar(n)) == NULL)
            return fail_at(L, n, "approach must be one word: "
                           MPB_APPROACHES_TEXT);
        if (n != NULL && mpb_approach_index(approach) < 0)
            return fail_at(L, n, "approach '%s' is none of "
                           MPB_APPROACHES_TEXT, approach);
        if ((planner = need_string(L, m, "planner")) == NULL)
            return -1;
        if (check_family(L, get(L, m, "planner"), planner) != 0) {
            free(planner);
            return -1;
        }
        for (yaml_node_item_t *a = algos->data.sequence.items.start;
             a < algos->data.sequence.items.top; a++) {
            yaml_node_t *an = node(L, *a);
            mpbd_config *c = &e->configs[e->num_configs++];
            char name[512];
            if (scalar(an) == NULL || scalar(an)[0] == '\0') {
                free(planner);
                return fail_at(L, an, "an algorithm must be a name");
            }
            c->planner = strdup(planner);
            c->algorithm = strdup(scalar(an));
            c->runs = runs;
            snprintf(name, sizeof name, "%s/%s%s%s", planner, scalar(an),
                     suffix ? "#" : "", suffix ? suffix : "");
            c->name = strdup(name);
            c->approach = approach ? strdup(approach) : NULL;
            if (!c->planner || !c->algorithm || !c->name ||
                (approach && !c->approach) ||
                load_params(L, c, get(L, m, "params")) != 0 ||
                (c->params_text = params_text(c->params,
                                              c->num_params)) == NULL) {
                free(planner);
                return fail_at(L, an, "out of memory");
            }
            for (mpbd_config *o = e->configs; o < c; o++)
                if (strcmp(o->name, c->name) == 0) {
                    free(planner);
                    return fail_at(L, an, "planner configuration '%s' appears "
                                   "twice (give one a 'name')", c->name);
                }
            if (add_runs(L, e, runs, runs_node, &total_runs) != 0) {
                free(planner);
                return -1;
            }
        }
        free(planner);
    }
    return 0;
}
