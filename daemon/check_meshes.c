/*
 * check_meshes.c - whether planners will find the robot's meshes. A
 * planner looks for them in the folders of MPB_MESH_PATH and
 * ROS_PACKAGE_PATH; mpbenchd also beside the robot's URDF (docs/scenes.md).
 * --check warns when only that folder holds them; --mesh-path prints it,
 * for tools/run_benchmark.sh to give the planners it starts.
 */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "experiment.h"
#include "mpbench/mesh.h"
#include "mpbench/robot.h"
#include "yamldoc.h"

/* The folder of file (an absolute path when it exists), into out. */
static void folder_of(const char *file, char *out, size_t n)
{
    char dir[PATH_MAX], real[PATH_MAX];
    snprintf(dir, sizeof dir, "%s", file);
    char *slash = strrchr(dir, '/');
    if (slash != NULL)
        slash[slash == dir ? 1 : 0] = '\0';
    else
        snprintf(dir, sizeof dir, ".");
    snprintf(out, n, "%s", realpath(dir, real) ? real : dir);
}

/* The folders a planner searches, from the environment, as the library
 * splits them; *buf holds them (free it). */
static int env_dirs(const char **dirs, int cap, char **buf)
{
    const char *a = getenv("MPB_MESH_PATH"), *b = getenv("ROS_PACKAGE_PATH");
    size_t len = (a ? strlen(a) : 0) + (b ? strlen(b) : 0) + 2;
    int n = 0;
    if ((*buf = malloc(len + 1)) == NULL)
        return -1;
    snprintf(*buf, len + 1, "%s:%s", a ? a : "", b ? b : "");
    char *save = NULL;
    for (char *d = strtok_r(*buf, ":", &save); d && n < cap - 1;
         d = strtok_r(NULL, ":", &save))
        dirs[n++] = d;
    return n;
}

int mpbd_mesh_note(const mpbd_experiment *e, char *buf, size_t len)
{
    enum { MAX_DIRS = 256 };
    if (e->robot_file == NULL || e->num_scenes < 1 || e->num_group < 1 ||
        strcmp(e->scenes[0].robot_format, "urdf") != 0)
        return 0;
    mpb_robot *r = NULL;
    if (mpb_robot_open_urdf_joints(e->scenes[0].robot,
                                   (const char *const *)e->group, e->num_group,
                                   &r, NULL, 0) != MPB_OK)
        return 0;
    const char *dirs[MAX_DIRS];
    char *env = NULL, robot_dir[PATH_MAX], path[PATH_MAX];
    int n = env_dirs(dirs, MAX_DIRS, &env), beside = 0;
    const char *first = NULL;
    folder_of(e->robot_file, robot_dir, sizeof robot_dir);
    for (int i = 0; n >= 0 && i < mpb_robot_num_collisions(r); i++) {
        const mpb_robot_collision *c = mpb_robot_get_collision(r, i);
        if (c->mesh_uri == NULL ||
            mpb_mesh_resolve(c->mesh_uri, dirs, n, path, sizeof path, NULL,
                             0) != MPB_ENOTFOUND)
            continue;
        dirs[n] = robot_dir;
        if (mpb_mesh_resolve(c->mesh_uri, dirs, n + 1, path, sizeof path,
                             NULL, 0) == MPB_OK && beside++ == 0)
            first = c->mesh_uri;
    }
    if (beside > 0)
        snprintf(buf, len, "robot: %d mesh%s (the first '%s') %s found "
                 "only beside its URDF, in %s, where planners do not look: "
                 "start planners of your own with MPB_MESH_PATH=%s "
                 "(tools/run_benchmark.sh does so for its own)", beside,
                 beside == 1 ? "" : "es", first, beside == 1 ? "is" : "are",
                 robot_dir, robot_dir);
    mpb_robot_close(r);
    free(env);
    return beside > 0;
}

int mpbd_mesh_path(const char *path, char *out, size_t n, char *err,
                   size_t errlen)
{
    mpbd_yaml Y = {.path = path, .err = err, .errlen = errlen};
    char *text;
    out[0] = '\0';
    if (mpbd_yaml_load_file(&Y, &text, "an experiment file holds one") != 0)
        return -1;
    yaml_node_t *robot = mpbd_yaml_get(&Y, yaml_document_get_root_node(&Y.doc),
                                       "robot");
    const char *format = mpbd_yaml_scalar(mpbd_yaml_get(&Y, robot, "format"));
    const char *file = mpbd_yaml_scalar(mpbd_yaml_get(&Y, robot, "file"));
    if (format != NULL && strcmp(format, "urdf") == 0 && file != NULL &&
        file[0] != '\0') {
        /* As the loader reads it: relative to the experiment's folder. */
        char full[2 * PATH_MAX + 2], here[PATH_MAX];
        folder_of(path, here, sizeof here);
        snprintf(full, sizeof full, "%s%s%s", file[0] == '/' ? "" : here,
                 file[0] == '/' ? "" : "/", file);
        folder_of(full, out, n);
    }
    yaml_document_delete(&Y.doc);
    free(text);
    return 0;
}
