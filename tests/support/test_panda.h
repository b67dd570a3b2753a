/*
 * test_panda.h - the Panda of the robot data (tools/robot_data.sh: its
 * URDF, SRDF and collision meshes) opened in a MoveIt scene, for the unit
 * tests that need a robot with meshes. Include it after test_files.h and
 * <unistd.h>.
 */
#ifndef MPB_TEST_PANDA_H
#define MPB_TEST_PANDA_H

#include "mpbench/mpbench.h"

#define TEST_PANDA_DIR MPB_TEST_DATA "/../../../.cache/robots/vamp-planner-0.6.4/panda"

static const char *const test_panda_joints[7] = {
    "panda_joint1", "panda_joint2", "panda_joint3", "panda_joint4",
    "panda_joint5", "panda_joint6", "panda_joint7"};

/* The Panda's seven arm joints in the scene (MoveIt .scene text), or NULL
 * when the robot data is not fetched; the test fails if it will not open. */
static inline mpb_world *test_open_panda(const char *scene_text)
{
    char dir[4096], urdf[4200], srdf[4200];
    /* assimp reads "a/../b" as written: the folder without its ".." */
    if (access(TEST_PANDA_DIR "/panda.urdf", R_OK) != 0 ||
        !realpath(TEST_PANDA_DIR, dir))
        return NULL;
    snprintf(urdf, sizeof urdf, "%s/panda.urdf", dir);
    snprintf(srdf, sizeof srdf, "%s/panda.srdf", dir);
    strcat(dir, "/");
    char *robot = test_read_robot(urdf, srdf);
    mpb_world *w = NULL;
    char err[512];
    int rc = mpb_world_open_group_in("urdf", robot, dir, "moveit-scene",
                                     scene_text, test_panda_joints, 7, &w, err,
                                     sizeof err);
    free(robot);
    if (rc != MPB_OK)
        fail_msg("%s", err);
    assert_int_equal(mpb_world_num_joints(w), 7);
    return w;
}

#endif
