/*
 * experiment_families.c - which planner families an experiment file names,
 * for --list-planners: tools/run_benchmark.sh starts those planner
 * processes and no others (a peer's process takes seconds and hundreds of
 * megabytes to start). Reads only the file's YAML, as --mesh-path does;
 * mpbenchd checks the whole file when it runs it.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "experiment.h"
#include "yamldoc.h"

int mpbd_planner_families(const char *path, FILE *out, char *err,
                          size_t errlen)
{
    mpbd_yaml Y = {.path = path, .err = err, .errlen = errlen};
    char *text;
    if (mpbd_yaml_load_file(&Y, &text, "an experiment file holds one") != 0)
        return -1;
    yaml_node_t *list = mpbd_yaml_get(&Y, yaml_document_get_root_node(&Y.doc),
                                      "planners");
    int n = mpbd_yaml_count(list), rc = 0;
    if (n == 0)
        rc = mpbd_yaml_fail(&Y, list, "planners: expected a list of "
                                      "planner configurations");
    for (int i = 0; i < n && rc == 0; i++) {
        yaml_node_t *item = mpbd_yaml_item(&Y, list, i);
        const char *family = mpbd_yaml_scalar(mpbd_yaml_get(&Y, item,
                                                            "planner"));
        if (family == NULL || family[0] == '\0') {
            rc = mpbd_yaml_fail(&Y, item, "planner: missing");
            break;
        }
        int seen = 0;   /* each family once, in the file's order */
        for (int j = 0; j < i && !seen; j++) {
            const char *f = mpbd_yaml_scalar(
                mpbd_yaml_get(&Y, mpbd_yaml_item(&Y, list, j), "planner"));
            seen = f != NULL && strcmp(f, family) == 0;
        }
        if (!seen)
            fprintf(out, "%s\n", family);
    }
    yaml_document_delete(&Y.doc);
    free(text);
    return rc;
}
