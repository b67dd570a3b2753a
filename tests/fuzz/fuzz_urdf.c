/* fuzz_urdf.c - libFuzzer target: URDF loading (urdfdom through the C
 * bridge), then forward kinematics of what loaded. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "mpbench/mpbench.h"
#include "mpbench/robot.h"

static void exercise(mpb_robot *r)
{
    int nj = mpb_robot_num_joints(r), nl = mpb_robot_num_links(r);
    double *q = calloc((size_t)nj + 1, sizeof *q);
    mpb_pose *poses = calloc((size_t)nl + 1, sizeof *poses);
    if (q && poses)
        mpb_robot_fk(r, q, poses);
    free(q);
    free(poses);
    mpb_robot_close(r);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const char *const joints[] = {"j1", "r_shoulder_pan_joint"};
    char *text = malloc(size + 1), err[256];
    mpb_robot *r = NULL;
    if (text == NULL)
        return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    if (mpb_robot_open_urdf(text, NULL, "tool", &r, err, sizeof err) == MPB_OK)
        exercise(r);
    if (mpb_robot_open_urdf_joints(text, joints, 1, &r, err, sizeof err) == MPB_OK)
        exercise(r);
    free(text);
    return 0;
}
