/*
 * mesh_search.c - where a URDF's meshes are looked for: the folders of
 * MPB_MESH_PATH, then of ROS_PACKAGE_PATH (each colon-separated; a folder
 * holds NAME/ of package://NAME/path or is NAME itself), then the URDF's
 * folder when the caller names it; and what to say when one is not found.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpbench/mpbench.h"
#include "core/errbuf.h"
#include "model/world_urdf.h"

static const char *const mesh_vars[2] = {"MPB_MESH_PATH", "ROS_PACKAGE_PATH"};

void mpb__mesh_search_free(mpb__mesh_search *m)
{
    free(m->buf[0]);
    free(m->buf[1]);
    free(m->dirs);
}

int mpb__mesh_search_init(mpb__mesh_search *m, const char *robot_dir)
{
    memset(m, 0, sizeof *m);
    size_t cap = 2;
    for (int v = 0; v < 2; v++) {
        const char *env = getenv(mesh_vars[v]);
        if (!env)
            continue;
        if (!(m->buf[v] = strdup(env)))
            return MPB_ENOMEM;
        for (const char *c = env; *c; c++)
            cap += *c == ':';
        cap++;
    }
    if (!(m->dirs = calloc(cap, sizeof *m->dirs)))
        return MPB_ENOMEM;
    for (int v = 0; v < 2; v++) {
        char *save = NULL;
        for (char *d = m->buf[v] ? strtok_r(m->buf[v], ":", &save) : NULL; d;
             d = strtok_r(NULL, ":", &save)) {
            m->dirs[m->num_dirs++] = d;
            m->from_env[v]++;
        }
    }
    if (robot_dir && *robot_dir)
        m->dirs[m->num_dirs++] = m->robot_dir = robot_dir;
    return MPB_OK;
}

void mpb__mesh_not_found(const mpb__mesh_search *m, char *err,
                         size_t errlen)
{
    char what[1024];
    size_t n = 0;
    int first = 0;
    n += (size_t)snprintf(what + n, sizeof what - n, "; looked in");
    for (int v = 0; v < 2; v++) {
        int k = m->from_env[v];
        n += (size_t)snprintf(what + n, n < sizeof what ? sizeof what - n : 0,
                              "%s %s (", v ? " and" : "", mesh_vars[v]);
        if (k == 0)
            n += (size_t)snprintf(what + n, n < sizeof what ? sizeof what - n : 0,
                                  "%s", getenv(mesh_vars[v]) ? "empty" : "not set");
        for (int i = 0; i < k && i < 3; i++)
            n += (size_t)snprintf(what + n, n < sizeof what ? sizeof what - n : 0,
                                  "%s%s", i ? ", " : "", m->dirs[first + i]);
        if (k > 3)
            n += (size_t)snprintf(what + n, n < sizeof what ? sizeof what - n : 0,
                                  " and %d more: %d folders", k - 3, k);
        n += (size_t)snprintf(what + n, n < sizeof what ? sizeof what - n : 0, ")");
        first += k;
    }
    if (m->robot_dir)
        n += (size_t)snprintf(what + n, n < sizeof what ? sizeof what - n : 0,
                              " and the URDF's folder (%s)", m->robot_dir);
    size_t len = strlen(err);
    if (len < errlen)
        mpb__set_err(err + len, errlen - len, "%s", what);
}
