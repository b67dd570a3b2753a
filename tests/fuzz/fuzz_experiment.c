/* fuzz_experiment.c - libFuzzer target: the experiment file loader
 * (YAML, schema checks, planar robot and scene, start and goal checks). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "experiment.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static char path[64];
    char err[1024];
    if (path[0] == '\0')
        snprintf(path, sizeof path, "/tmp/mpb_fuzz_exp_%ld.yaml", (long)getpid());
    FILE *f = fopen(path, "wb");
    if (f == NULL)
        return 0;
    fwrite(data, 1, size, f);
    fclose(f);
    mpbd_experiment *e = mpbd_experiment_load(path, err, sizeof err);
    mpbd_experiment_free(e);
    return 0;
}
