/* fuzz_octree.c - libFuzzer target: OctoMap files and streams
 * (octree.h) and point clouds (cloud.h), as octrees; the first byte picks
 * the reader, the rest is its input. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "mpbench/mpbench.h"
#include "mpbench/cloud.h"
#include "mpbench/octree.h"

static int into(void *ctx, long i, const double p[3], char *msg, size_t msglen)
{
    (void)i;
    (void)msg;
    (void)msglen;
    int rc = mpb_octree_add_point(ctx, p);
    return rc == MPB_EINVAL ? MPB_OK : rc;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1)
        return 0;
    char err[256];
    mpb_octree *o = NULL;
    int which = data[0] % 4;
    data++;
    size--;
    if (which == 0)
        mpb_octree_create_from_bytes(data, size, "f", &o, err, sizeof err);
    else if (which == 1 || which == 2)
        mpb_octree_create_from_stream(data, size, 0.01, which == 1, "d", &o, err, sizeof err);
    else if (mpb_octree_create(0.01, &o) == MPB_OK &&
             mpb_cloud_read(data, size, "c", into, o, NULL, err, sizeof err) != MPB_OK) {
        mpb_octree_destroy(o);
        o = NULL;
    }
    if (o) {
        unsigned char *b;
        size_t n;
        if (mpb_octree_write(o, 1, &b, &n) == MPB_OK) {
            mpb_octree *back = NULL;
            /* what is written reads back as the same cells */
            if (mpb_octree_create_from_bytes(b, n, "w", &back, err, sizeof err) != MPB_OK ||
                mpb_octree_num_cells(back) != mpb_octree_num_cells(o))
                abort();
            mpb_octree_destroy(back);
            free(b);
        }
        mpb_octree_destroy(o);
    }
    return 0;
}
