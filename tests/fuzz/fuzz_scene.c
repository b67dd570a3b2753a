/* fuzz_scene.c - libFuzzer target: the MoveIt .scene parser, and adding
 * what it parsed to a collision world. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "mpbench/mpbench.h"
#include "mpbench/collision.h"
#include "mpbench/scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1), err[256];
    mpb_scene *s = NULL;
    if (text == NULL)
        return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    if (mpb_scene_open_text(text, &s, err, sizeof err) == MPB_OK) {
        mpb_collision *c = NULL;
        if (mpb_collision_create(&c) == MPB_OK) {
            mpb_scene_add_statics(s, c);
            mpb_collision_check(c, NULL, NULL);
            mpb_collision_destroy(c);
        }
        mpb_scene_close(s);
    }
    free(text);
    return 0;
}
