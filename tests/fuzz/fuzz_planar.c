/* fuzz_planar.c - libFuzzer target: the planar robot and scene parsers and
 * the queries on what they build. Input: robot text, a NUL, scene text. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "mpbench/mpbench.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *buf = malloc(size + 2), err[256];
    mpb_world *w = NULL;
    if (buf == NULL)
        return 0;
    memcpy(buf, data, size);
    buf[size] = buf[size + 1] = '\0';
    const char *robot = buf, *scene = buf + strlen(buf) + 1;
    if (scene > buf + size)
        scene = buf + size;
    if (mpb_world_open("planar", robot, "planar", scene, &w, err, sizeof err)
        == MPB_OK) {
        int n = mpb_world_num_joints(w);
        double q[64] = {0};
        if (n <= 64) {
            mpb_world_in_collision(w, q);
            mpb_world_clearance(w, q);
            for (int j = 0; j < n; j++)
                q[j] = 1.0;
            mpb_world_in_collision(w, q);
        }
    }
    mpb_world_close(w);
    free(buf);
    return 0;
}
