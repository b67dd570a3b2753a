/*
 * scene_resolve.c - a scene file's lines that name octree and cloud files
 * (after the '.'), made into the octree and spheres lines that hold the
 * data (scene.h): the text that travels is then whole.
 */
#include "mpbench/mpbench.h"
#include "mpbench/cloud.h"
#include "mpbench/octree.h"
#include "mpbench/scene.h"

#include "core/base64.h"
#include "core/errbuf.h"
#include "core/number.h"
#include "core/words.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct buf {
    char  *s;
    size_t len, cap;
    int    oom;
} buf;

static void put(buf *b, const char *p, size_t n)
{
    if (b->oom)
        return;
    if (b->len + n + 1 > b->cap) {
        size_t cap = b->cap ? b->cap : 1024;
        while (cap < b->len + n + 1)
            cap *= 2;
        char *q = realloc(b->s, cap);
        if (!q) {
            b->oom = 1;
            return;
        }
        b->s = q;
        b->cap = cap;
    }
    memcpy(b->s + b->len, p, n);
    b->len += n;
    b->s[b->len] = '\0';
}

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static void putf(buf *b, const char *fmt, ...)
{
    char tmp[512];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(tmp, sizeof tmp, fmt, ap);
    va_end(ap);
    if (n > 0)
        put(b, tmp, (size_t)n < sizeof tmp ? (size_t)n : sizeof tmp - 1);
}

#define MAX_WORDS 16

static int is(const mpb__word *w, const char *s)
{
    return (size_t)w->len == strlen(s) && memcmp(w->p, s, strlen(s)) == 0;
}

/* The pose words (none: identity) as 7 numbers x y z qx qy qz qw. */
static int pose_vals(const mpb__word *w, int n, double v[7])
{
    static const double id[7] = {0, 0, 0, 0, 0, 0, 1};
    if (n == 0) {
        memcpy(v, id, sizeof id);
        return 0;
    }
    if (n != 7)
        return -1;
    for (int i = 0; i < 7; i++)
        if (!mpb__number(w[i].p, w[i].len, &v[i]))
            return -1;
    return 0;
}

static void pose_text(const double v[7], char *out, size_t len)
{
    snprintf(out, len, "%.17g %.17g %.17g %.17g %.17g %.17g %.17g", v[0], v[1], v[2],
             v[3], v[4], v[5], v[6]);
}

static void path_of(const mpb__word *w, const char *dir, char *out, size_t len)
{
    if (w->p[0] == '/' || !dir || !*dir)
        snprintf(out, len, "%.*s", w->len, w->p);
    else
        snprintf(out, len, "%s%s%.*s", dir, dir[strlen(dir) - 1] == '/' ? "" : "/",
                 w->len, w->p);
}

int mpb_scene_octree_text(mpb_octree *o, const char *id, const double pose[7],
                          char **out)
{
    static const double identity[7] = {0, 0, 0, 0, 0, 0, 1};
    if (!o || !id || !*id || strpbrk(id, " \t\r\n") || !out)
        return MPB_EINVAL;
    *out = NULL;
    unsigned char *data;
    size_t n;
    int rc = mpb_octree_write(o, 0, &data, &n);
    if (rc != MPB_OK)
        return rc;
    char *text = NULL;
    rc = mpb__base64_encode(data, n, &text, NULL);
    free(data);
    if (rc != MPB_OK)
        return rc;
    char p[256];
    pose_text(pose ? pose : identity, p, sizeof p);
    buf b = {0};
    putf(&b, "octree %s binary %.17g %zu %s\n", id, mpb_octree_resolution(o), n, p);
    put(&b, text, strlen(text));
    free(text);
    if (b.oom) {
        free(b.s);
        return MPB_ENOMEM;
    }
    *out = b.s;
    return MPB_OK;
}

static int octree_lines(buf *b, const mpb__word *id, mpb_octree *o, const double pose[7])
{
    char name[256], *text;
    snprintf(name, sizeof name, "%.*s", id->len, id->p);
    int rc = mpb_scene_octree_text(o, name, pose, &text);
    if (rc != MPB_OK)
        return rc;
    put(b, text, strlen(text));
    free(text);
    return MPB_OK;
}

/* One octree-file or cloud-file line (words w, n of them) into b. */
static int resolve_line(buf *b, const mpb__word *w, int n, const char *dir, int line,
                        char *err, size_t errlen)
{
    char path[4096], why[400];
    double pose[7];
    int cloud = is(&w[0], "cloud");
    int fixed = cloud ? 6 : 4;      /* words before the pose */
    if (n < fixed || (n != fixed && n != fixed + 7) ||
        (cloud && !is(&w[4], "voxel") && !is(&w[4], "radius"))) {
        mpb__set_err(err, errlen, cloud
                     ? "scene line %d: cloud needs <id> file <path> voxel|radius <size> "
                       "[<x y z> <qx qy qz qw>]"
                     : "scene line %d: octree needs <id> file <path> "
                       "[<x y z> <qx qy qz qw>]", line);
        return MPB_EPARSE;
    }
    if (pose_vals(w + fixed, n - fixed, pose) != 0) {
        mpb__set_err(err, errlen, "scene line %d: %.*s pose needs <x y z> <qx qy qz qw>",
                     line, w[0].len, w[0].p);
        return MPB_EPARSE;
    }
    path_of(&w[3], dir, path, sizeof path);
    mpb_octree *o = NULL;
    int rc;
    if (!cloud) {
        rc = mpb_octree_create_from_file(path, &o, why, sizeof why);
    } else {
        double size;
        if (!mpb__number(w[5].p, w[5].len, &size)) {
            mpb__set_err(err, errlen, "scene line %d: cloud %.*s: '%.*s' is not a number",
                         line, w[4].len, w[4].p, w[5].len, w[5].p);
            return MPB_EPARSE;
        }
        if (is(&w[4], "voxel")) {
            rc = mpb_cloud_load_octree(path, size, &o, why, sizeof why);
            if (rc == MPB_EINVAL)
                rc = MPB_EPARSE;
        } else {
            double *xyz;
            long np;
            if (!(size >= MPB_COLLISION_MIN_SIZE && size <= MPB_COLLISION_MAX_COORD)) {
                mpb__set_err(err, errlen, "scene line %d: cloud radius %g is not from "
                             "%g to %g m", line, size, MPB_COLLISION_MIN_SIZE,
                             MPB_COLLISION_MAX_COORD);
                return MPB_EPARSE;
            }
            rc = mpb_cloud_load_points(path, MPB_SCENE_MAX_SPHERES, &xyz, &np, why,
                                       sizeof why);
            if (rc == MPB_OK) {
                char pt[256];
                pose_text(pose, pt, sizeof pt);
                putf(b, "spheres %.*s %.17g %ld %s\n", w[1].len, w[1].p, size, np, pt);
                for (long i = 0; i < np; i++)
                    putf(b, "%.9g %.9g %.9g\n", xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
                free(xyz);
                return MPB_OK;
            }
        }
    }
    if (rc != MPB_OK) {
        mpb__set_err(err, errlen, "scene line %d: %s", line, why);
        return rc;
    }
    rc = octree_lines(b, &w[1], o, pose);
    mpb_octree_destroy(o);
    return rc;
}

int mpb_scene_resolve(const char *text, const char *dir, char **out, char *err,
                      size_t errlen)
{
    if (err && errlen)
        err[0] = '\0';
    if (!text || !out)
        return MPB_EINVAL;
    *out = NULL;
    buf b = {0};
    const char *p = text;
    int line = 0, after = 0, rc = MPB_OK;
    while (*p && rc == MPB_OK) {
        line++;
        const char *e = strchr(p, '\n');
        const char *next = e ? e + 1 : p + strlen(p);
        if (!e)
            e = next;
        mpb__word w[MAX_WORDS];
        int n = mpb__split_words(p, e, w, MAX_WORDS);
        if (!after) {
            after = line > 1 && n == 1 && is(&w[0], ".");
        } else if (n >= 3 && n <= MAX_WORDS &&
                   ((is(&w[0], "octree") && is(&w[2], "file")) ||
                    (is(&w[0], "cloud") && is(&w[2], "file")))) {
            rc = resolve_line(&b, w, n, dir, line, err, errlen);
            p = next;
            continue;
        }
        put(&b, p, (size_t)(next - p));
        p = next;
    }
    if (rc == MPB_OK && b.oom)
        rc = MPB_ENOMEM;
    if (rc != MPB_OK) {
        if (rc == MPB_ENOMEM)
            mpb__set_err(err, errlen, "scene: out of memory");
        free(b.s);
        return rc;
    }
    if (!b.s) {
        b.s = calloc(1, 1);
        if (!b.s)
            return MPB_ENOMEM;
    }
    *out = b.s;
    return MPB_OK;
}
