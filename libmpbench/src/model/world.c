/* world.c - the mpb_world handle: picks a provider by format, forwards to it. */
#include "mpbench/mpbench.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/errbuf.h"
#include "core/grow.h"
#include "model/world_provider.h"
#include "core/mathconst.h"

static const mpb__world_provider *const providers[] = {
    &mpb__world_planar,
    &mpb__world_urdf,
};
#define NUM_PROVIDERS ((int)(sizeof providers / sizeof providers[0]))

int mpb__world_add_joint(mpb_world *w, const char *name, size_t namelen,
                         double lo, double hi, int continuous,
                         double max_velocity)
{
    if (w->num_joints == w->cap) {
        /* Five arrays of one capacity, each grown from the same one. */
        int need = w->num_joints + 1,
            cap[5] = {w->cap, w->cap, w->cap, w->cap, w->cap};
        if (mpb__grow((void **)&w->joint_names, &cap[0], need,
                      sizeof *w->joint_names) != MPB_OK ||
            mpb__grow((void **)&w->lo, &cap[1], need, sizeof *w->lo) != MPB_OK ||
            mpb__grow((void **)&w->hi, &cap[2], need, sizeof *w->hi) != MPB_OK ||
            mpb__grow((void **)&w->wraps, &cap[3], need, sizeof *w->wraps) !=
                MPB_OK ||
            mpb__grow((void **)&w->max_velocity, &cap[4], need,
                      sizeof *w->max_velocity) != MPB_OK)
            return MPB_ENOMEM;
        w->cap = cap[0];
    }
    char *copy = malloc(namelen + 1);
    if (!copy)
        return MPB_ENOMEM;
    memcpy(copy, name, namelen);
    copy[namelen] = '\0';
    int i = w->num_joints++;
    w->joint_names[i] = copy;
    w->wraps[i] = continuous ? 1 : 0;
    w->lo[i] = continuous ? -M_PI : lo;
    w->hi[i] = continuous ? M_PI : hi;
    w->max_velocity[i] = isfinite(max_velocity) && max_velocity > 0
                             ? max_velocity : 0.0;
    return MPB_OK;
}

static const mpb__world_provider *find_provider(const char *robot_format)
{
    for (int i = 0; i < NUM_PROVIDERS; i++)
        if (strcmp(providers[i]->robot_format, robot_format) == 0)
            return providers[i];
    return NULL;
}

const char *mpb_world_scene_format(const char *robot_format)
{
    const mpb__world_provider *p = robot_format ? find_provider(robot_format)
                                                : NULL;
    return p ? p->scene_format : NULL;
}

int mpb_world_open(const char *robot_format, const char *robot_text,
                   const char *scene_format, const char *scene_text,
                   mpb_world **out, char *err, size_t errlen)
{
    return mpb_world_open_group(robot_format, robot_text, scene_format,
                                scene_text, NULL, 0, out, err, errlen);
}

int mpb_world_open_group(const char *robot_format, const char *robot_text,
                         const char *scene_format, const char *scene_text,
                         const char *const *joints, int num_joints,
                         mpb_world **out, char *err, size_t errlen)
{
    return mpb_world_open_group_in(robot_format, robot_text, NULL,
                                   scene_format, scene_text, joints,
                                   num_joints, out, err, errlen);
}

int mpb_world_open_group_in(const char *robot_format, const char *robot_text,
                            const char *robot_dir, const char *scene_format,
                            const char *scene_text, const char *const *joints,
                            int num_joints, mpb_world **out, char *err,
                            size_t errlen)
{
    mpb__set_err(err, errlen, "%s", "");
    if (!out)
        return MPB_EINVAL;
    *out = NULL;
    if (!robot_format || !robot_text || !scene_format) {
        mpb__set_err(err, errlen, "world: robot format, robot text and "
                     "scene format are required");
        return MPB_EINVAL;
    }
    const mpb__world_provider *p = find_provider(robot_format);
    if (!p) {
        char known[128] = "";
        for (int i = 0; i < NUM_PROVIDERS; i++)
            snprintf(known + strlen(known), sizeof known - strlen(known),
                     "%s'%s'", i ? ", " : "", providers[i]->robot_format);
        mpb__set_err(err, errlen, "world: robot format '%.40s' is not "
                     "supported (known: %s)", robot_format, known);
        return MPB_EUNSUPPORTED;
    }
    if (strcmp(p->scene_format, scene_format) != 0) {
        mpb__set_err(err, errlen, "world: scene format '%.40s' does not go "
                     "with robot format '%s' (expected '%s')", scene_format,
                     p->robot_format, p->scene_format);
        return MPB_EUNSUPPORTED;
    }

    mpb_world *w = calloc(1, sizeof *w);
    if (!w) {
        mpb__set_err(err, errlen, "world: out of memory");
        return MPB_ENOMEM;
    }
    w->provider = p;
    w->robot_dir = robot_dir;
    if (num_joints < 0 || (num_joints > 0 && joints == NULL)) {
        free(w);
        mpb__set_err(err, errlen, "world: bad joint list");
        return MPB_EINVAL;
    }
    int rc = p->open(w, robot_text, scene_text ? scene_text : "", joints,
                     num_joints, err, errlen);
    if (rc == MPB_OK && w->num_joints < 1) {
        mpb__set_err(err, errlen, "robot: no joints");
        rc = MPB_EPARSE;
    }
    w->robot_dir = NULL;        /* the caller's: only for open */
    if (rc != MPB_OK) {
        if (rc == MPB_ENOMEM)
            mpb__set_err(err, errlen, "world: out of memory");
        mpb_world_close(w);
        return rc;
    }
    *out = w;
    return MPB_OK;
}

void mpb_world_close(mpb_world *w)
{
    if (!w)
        return;
    if (w->provider && w->provider->close)
        w->provider->close(w->impl);
    for (int i = 0; i < w->num_joints; i++)
        free(w->joint_names[i]);
    free(w->joint_names);
    free(w->lo);
    free(w->hi);
    free(w->wraps);
    free(w->max_velocity);
    free(w);
}

int mpb_world_num_joints(const mpb_world *w)
{
    return w ? w->num_joints : 0;
}

const char *mpb_world_joint_name(const mpb_world *w, int joint)
{
    if (!w || joint < 0 || joint >= w->num_joints)
        return NULL;
    return w->joint_names[joint];
}

void mpb_world_joint_limits(const mpb_world *w, int joint,
                            double *lo, double *hi)
{
    int ok = w && joint >= 0 && joint < w->num_joints;
    if (lo)
        *lo = ok ? w->lo[joint] : NAN;
    if (hi)
        *hi = ok ? w->hi[joint] : NAN;
}

double mpb_world_joint_max_velocity(const mpb_world *w, int joint)
{
    return w && joint >= 0 && joint < w->num_joints ? w->max_velocity[joint]
                                                    : 0.0;
}

int mpb_world_joint_is_continuous(const mpb_world *w, int joint)
{
    if (!w || joint < 0 || joint >= w->num_joints)
        return 0;
    return w->wraps[joint] != 0;
}

const unsigned char *mpb_world_joint_wraps(const mpb_world *w)
{
    return w ? w->wraps : NULL;
}

static int all_finite(const mpb_world *w, const double *q)
{
    for (int j = 0; j < w->num_joints; j++)
        if (!isfinite(q[j]))
            return 0;
    return 1;
}

int mpb_world_in_collision(mpb_world *w, const double *q)
{
    if (!w || !q)
        return MPB_EINVAL;
    if (!all_finite(w, q))
        return 1;
    return w->provider->in_collision(w->impl, q) ? 1 : 0;
}

double mpb_world_clearance(mpb_world *w, const double *q)
{
    if (!w || !q || !all_finite(w, q))
        return NAN;
    return w->provider->clearance(w->impl, q);
}

int mpb_world_ee_position(mpb_world *w, const double *q, double xyz[3])
{
    if (!w || !q || !xyz)
        return MPB_EINVAL;
    if (!all_finite(w, q))
        return MPB_EINVAL;
    w->provider->ee_position(w->impl, q, xyz);
    return MPB_OK;
}

int mpb_world_goal_contains(mpb_world *w, const mpb_goal *g, const double *q,
                            char *detail, size_t len)
{
    mpb__set_err(detail, len, "%s", "");
    if (!w || !g || !q)
        return MPB_EINVAL;
    if (g->kind != MPB_GOAL_POSE_REGION || !w->provider->goal_region) {
        mpb__set_err(detail, len, "pose-region goals cannot be checked in "
                     "a '%s' world", w->provider->robot_format);
        return MPB_EUNSUPPORTED;
    }
    if (!all_finite(w, q))
        return 0;
    return w->provider->goal_region(w->impl, g, q, detail, len);
}

int mpb_world_contact(mpb_world *w, const double *q, char *what, size_t len)
{
    mpb__set_err(what, len, "%s", "");
    if (!w || !q || !all_finite(w, q))
        return MPB_EINVAL;
    if (!w->provider->contact)
        return w->provider->in_collision(w->impl, q) ? 1 : 0;
    return w->provider->contact(w->impl, q, what, len);
}

int mpb__world_depth_above(mpb_world *w, const double *q, double floor,
                           double *lower, double *upper)
{
    if (!w || !q || !lower || !upper || !all_finite(w, q) || !(floor >= 0))
        return MPB_EINVAL;
    *lower = *upper = NAN;
    if (!w->provider->depth)
        return MPB_EUNSUPPORTED;
    return w->provider->depth(w->impl, q, floor, lower, upper);
}

int mpb_world_depth(mpb_world *w, const double *q, double *lower,
                    double *upper)
{
    return mpb__world_depth_above(w, q, 0.0, lower, upper);
}

int mpb_world_hold(mpb_world *w, const char *const *joints,
                   const double *values, int n, char *err, size_t errlen)
{
    mpb__set_err(err, errlen, "%s", "");
    if (!w || n < 0 || (n > 0 && (!joints || !values)))
        return MPB_EINVAL;
    if (n == 0)
        return MPB_OK;
    if (!w->provider->hold) {
        mpb__set_err(err, errlen, "joint '%s': a '%s' robot has no joints "
                     "outside its group", joints[0], w->provider->robot_format);
        return MPB_EUNSUPPORTED;
    }
    return w->provider->hold(w->impl, joints, values, n, err, errlen);
}

int mpb_world_held(const mpb_world *w, const char *joint, double *value,
                   double *lo, double *hi)
{
    if (!w || !joint)
        return MPB_EINVAL;
    if (!w->provider->held)
        return MPB_EUNSUPPORTED;
    return w->provider->held(w->impl, joint, value, lo, hi);
}

int mpb_world_num_allowed_pairs(const mpb_world *w)
{
    if (!w || !w->provider->num_allowed)
        return 0;
    return w->provider->num_allowed(w->impl);
}

int mpb_world_allowed_pair(const mpb_world *w, int i,
                           mpb_world_acm_pair *out)
{
    if (!w || !out || !w->provider->allowed_pair)
        return MPB_EINVAL;
    return w->provider->allowed_pair(w->impl, i, out);
}
