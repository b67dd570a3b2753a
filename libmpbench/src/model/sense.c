/*
 * sense.c - what depth cameras would see of a scene (sense.h): a ray per
 * pixel against the scene's world objects, each shape hit in its own
 * frame, Gaussian noise along the ray from a seeded generator of the
 * call's own, the hits within range fused into an octree; and that octree
 * written as a scene text, as `mpb sense` writes it.
 */
#include "mpbench/mpbench.h"
#include "mpbench/sense.h"
#include "core/errbuf.h"
#include "core/mathconst.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- the generator: splitmix64, then Box-Muller ----------------------- */

static uint64_t next64(uint64_t *s)
{
    uint64_t z = (*s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

static double uniform(uint64_t *s)     /* in (0, 1] */
{
    return ((double)(next64(s) >> 11) + 1.0) / 9007199254740992.0;
}

static double gaussian(uint64_t *s)
{
    double u = uniform(s), v = uniform(s);
    return sqrt(-2.0 * log(u)) * cos(2.0 * M_PI * v);
}

/* ---- rays against shapes, in each shape's own frame -------------------- */

static double dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* The least root > eps of a t^2 + b t + c within [lo_z, hi_z] of o + t d's
 * z, or INFINITY. */
static double quad_hit(double a, double b, double c, const double o[3], const double d[3],
                       double lo_z, double hi_z, double eps)
{
    if (fabs(a) < 1e-300)
        return INFINITY;
    double disc = b * b - 4 * a * c;
    if (disc < 0)
        return INFINITY;
    double r = sqrt(disc), t[2] = {(-b - r) / (2 * a), (-b + r) / (2 * a)};
    if (t[0] > t[1]) {
        double x = t[0];
        t[0] = t[1];
        t[1] = x;
    }
    for (int i = 0; i < 2; i++) {
        double z = o[2] + t[i] * d[2];
        if (t[i] > eps && z >= lo_z && z <= hi_z)
            return t[i];
    }
    return INFINITY;
}

/* A disc of radius r at height z, normal z. */
static double disc_hit(const double o[3], const double d[3], double z, double r, double eps)
{
    if (fabs(d[2]) < 1e-300)
        return INFINITY;
    double t = (z - o[2]) / d[2];
    double x = o[0] + t * d[0], y = o[1] + t * d[1];
    return t > eps && x * x + y * y <= r * r ? t : INFINITY;
}

/* The least t > 0 at which o + t d (the shape's frame) meets shape g, or
 * INFINITY. */
static double shape_hit(const mpb_geometry *g, const double o[3], const double d[3])
{
    const double eps = 1e-9, *h = g->dims;
    switch (g->type) {
    case MPB_SHAPE_BOX: {
        double t0 = -INFINITY, t1 = INFINITY;
        for (int k = 0; k < 3; k++) {
            double e = h[k] / 2;
            if (fabs(d[k]) < 1e-300) {
                if (o[k] < -e || o[k] > e)
                    return INFINITY;
                continue;
            }
            double a = (-e - o[k]) / d[k], b = (e - o[k]) / d[k];
            if (a > b) {
                double x = a;
                a = b;
                b = x;
            }
            t0 = a > t0 ? a : t0;
            t1 = b < t1 ? b : t1;
        }
        if (t0 > t1)
            return INFINITY;
        return t0 > eps ? t0 : t1 > eps ? t1 : INFINITY;
    }
    case MPB_SHAPE_SPHERE: {
        double z = INFINITY;
        return quad_hit(dot(d, d), 2 * dot(o, d), dot(o, o) - h[0] * h[0], o, d, -z, z, eps);
    }
    case MPB_SHAPE_CYLINDER: {
        double r = h[0], l = h[1] / 2;
        double t = quad_hit(d[0] * d[0] + d[1] * d[1], 2 * (o[0] * d[0] + o[1] * d[1]),
                            o[0] * o[0] + o[1] * o[1] - r * r, o, d, -l, l, eps);
        double a = disc_hit(o, d, l, r, eps), b = disc_hit(o, d, -l, r, eps);
        return fmin(t, fmin(a, b));
    }
    case MPB_SHAPE_CONE: {
        /* x^2 + y^2 = (k (l - z))^2, k = r / (2 l), apex at z = l */
        double r = h[0], l = h[1] / 2, k = r / (2 * l);
        double w = l - o[2], k2 = k * k;
        double a = d[0] * d[0] + d[1] * d[1] - k2 * d[2] * d[2];
        double b = 2 * (o[0] * d[0] + o[1] * d[1] + k2 * w * d[2]);
        double c = o[0] * o[0] + o[1] * o[1] - k2 * w * w;
        double t = quad_hit(a, b, c, o, d, -l, l, eps);
        return fmin(t, disc_hit(o, d, -l, r, eps));
    }
    case MPB_SHAPE_PLANE: {
        double nd = h[0] * d[0] + h[1] * d[1] + h[2] * d[2];
        if (fabs(nd) < 1e-300)
            return INFINITY;
        double t = (h[3] - (h[0] * o[0] + h[1] * o[1] + h[2] * o[2])) / nd;
        return t > eps ? t : INFINITY;
    }
    case MPB_SHAPE_MESH: {
        const mpb_mesh *m = g->mesh;
        double best = INFINITY;
        for (int i = 0; m && i < m->num_triangles; i++) {
            const double *a = &m->vertices[3 * m->triangles[3 * i]],
                         *b = &m->vertices[3 * m->triangles[3 * i + 1]],
                         *c = &m->vertices[3 * m->triangles[3 * i + 2]];
            double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
            double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
            double p[3] = {d[1] * e2[2] - d[2] * e2[1], d[2] * e2[0] - d[0] * e2[2],
                           d[0] * e2[1] - d[1] * e2[0]};
            double det = dot(e1, p);
            if (fabs(det) < 1e-300)
                continue;
            double s[3] = {o[0] - a[0], o[1] - a[1], o[2] - a[2]};
            double u = dot(s, p) / det;
            if (u < 0 || u > 1)
                continue;
            double q[3] = {s[1] * e1[2] - s[2] * e1[1], s[2] * e1[0] - s[0] * e1[2],
                           s[0] * e1[1] - s[1] * e1[0]};
            double v = dot(d, q) / det;
            if (v < 0 || u + v > 1)
                continue;
            double t = dot(e2, q) / det;
            if (t > eps && t < best)
                best = t;
        }
        return best;
    }
    default:
        return INFINITY;
    }
}

/* The nearest hit of the ray o + t d (|d| = 1, world) on the scene's
 * world objects, or INFINITY. */
static double scene_hit(const mpb_scene *s, const double o[3], const double d[3])
{
    double best = INFINITY;
    for (int i = 0; i < mpb_scene_num_objects(s); i++) {
        const mpb_scene_object *ob = mpb_scene_object_at(s, i);
        if (ob->attached_link)
            continue;
        for (int k = 0; k < ob->num_shapes; k++) {
            mpb_pose p;
            mpb_pose_mul(&ob->pose, &ob->shapes[k].pose, &p);
            double lo[3], ld[3];     /* the ray in the shape's frame */
            for (int j = 0; j < 3; j++) {
                lo[j] = p.R[j] * (o[0] - p.t[0]) + p.R[3 + j] * (o[1] - p.t[1]) +
                        p.R[6 + j] * (o[2] - p.t[2]);
                ld[j] = p.R[j] * d[0] + p.R[3 + j] * d[1] + p.R[6 + j] * d[2];
            }
            double t = shape_hit(&ob->shapes[k].geometry, lo, ld);
            if (t < best)
                best = t;
        }
    }
    return best;
}

/* ---- cameras -------------------------------------------------------------- */

static void normalise(double v[3])
{
    double n = sqrt(dot(v, v));
    for (int k = 0; k < 3; k++)
        v[k] /= n;
}

/* Cast camera c's rays (options o); the hits in range into tree t. The
 * number of hits, or a negative code of mpb_octree_add_point(). */
static long cast(const mpb_sense_options *o, const mpb_camera *c, const mpb_scene *s,
                 mpb_octree *t, uint64_t *rng)
{
    double f[3] = {c->at[0] - c->eye[0], c->at[1] - c->eye[1], c->at[2] - c->eye[2]};
    normalise(f);
    double up[3] = {0, 0, 1};
    if (fabs(f[2]) > 0.999)
        up[0] = 1, up[2] = 0;
    double r[3] = {f[1] * up[2] - f[2] * up[1], f[2] * up[0] - f[0] * up[2],
                   f[0] * up[1] - f[1] * up[0]};
    normalise(r);
    double u[3] = {r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2],
                   r[0] * f[1] - r[1] * f[0]};
    double tx = tan(o->fov * M_PI / 360.0), ty = tx * o->height / o->width;
    long hits = 0;
    for (int y = 0; y < o->height; y++)
        for (int x = 0; x < o->width; x++) {
            double a = (2.0 * (x + 0.5) / o->width - 1.0) * tx;
            double b = (1.0 - 2.0 * (y + 0.5) / o->height) * ty;
            double d[3];
            for (int k = 0; k < 3; k++)
                d[k] = f[k] + a * r[k] + b * u[k];
            normalise(d);
            double h = scene_hit(s, c->eye, d);
            double n = o->noise > 0 ? o->noise * gaussian(rng) : 0.0;
            if (!(h >= o->near && h <= o->far))
                continue;
            h += n;
            double p[3];
            for (int k = 0; k < 3; k++)
                p[k] = c->eye[k] + h * d[k];
            int rc = mpb_octree_add_point(t, p);
            if (rc == MPB_EINVAL)
                continue;            /* beyond the octree's reach */
            if (rc != MPB_OK)
                return rc;
            hits++;
        }
    return hits;
}

/* ---- the options ---------------------------------------------------------- */

void mpb_sense_options_init(mpb_sense_options *o)
{
    if (!o)
        return;
    memset(o, 0, sizeof *o);
    o->width = 160;
    o->height = 120;
    o->fov = 60;
    o->near = 0.3;
    o->far = 4;
    o->noise = 0.002;
    o->resolution = 0.01;
    o->seed = 1;
}

static int finite3(const double v[3])
{
    return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

int mpb_sense_options_check(const mpb_sense_options *o, char *why, size_t len)
{
    if (!o) {
        mpb__set_err(why, len, "no options given");
        return MPB_EINVAL;
    }
    if (o->num_cameras < 0 || o->num_cameras > MPB_SENSE_MAX_CAMERAS) {
        mpb__set_err(why, len, "num_cameras %d is outside 0 .. %d", o->num_cameras,
                     MPB_SENSE_MAX_CAMERAS);
        return MPB_EINVAL;
    }
    for (int i = 0; i < o->num_cameras; i++) {
        const mpb_camera *c = &o->cameras[i];
        if (!finite3(c->eye) || !finite3(c->at)) {
            mpb__set_err(why, len, "camera %d: a coordinate is not finite", i + 1);
            return MPB_EINVAL;
        }
        if (c->eye[0] == c->at[0] && c->eye[1] == c->at[1] && c->eye[2] == c->at[2]) {
            mpb__set_err(why, len, "camera %d: eye and at are the same point", i + 1);
            return MPB_EINVAL;
        }
    }
    if (o->width < 1 || o->width > MPB_SENSE_MAX_SIDE) {
        mpb__set_err(why, len, "width %d is outside 1 .. %d pixels", o->width,
                     MPB_SENSE_MAX_SIDE);
        return MPB_EINVAL;
    }
    if (o->height < 1 || o->height > MPB_SENSE_MAX_SIDE) {
        mpb__set_err(why, len, "height %d is outside 1 .. %d pixels", o->height,
                     MPB_SENSE_MAX_SIDE);
        return MPB_EINVAL;
    }
    if (!(o->fov > 0 && o->fov < MPB_SENSE_MAX_FOV)) {
        mpb__set_err(why, len, "fov %g is outside (0, %g) degrees", o->fov,
                     MPB_SENSE_MAX_FOV);
        return MPB_EINVAL;
    }
    if (!(o->near >= 0 && o->far > o->near && isfinite(o->far))) {
        mpb__set_err(why, len, "near %g and far %g need 0 <= near < far (m)", o->near,
                     o->far);
        return MPB_EINVAL;
    }
    if (!(o->noise >= 0 && isfinite(o->noise))) {
        mpb__set_err(why, len, "noise %g is not a standard deviation >= 0 m", o->noise);
        return MPB_EINVAL;
    }
    if (!(o->resolution >= MPB_OCTREE_MIN_RESOLUTION &&
          o->resolution <= MPB_OCTREE_MAX_RESOLUTION)) {
        mpb__set_err(why, len, "resolution %g is outside %g .. %g m", o->resolution,
                     MPB_OCTREE_MIN_RESOLUTION, MPB_OCTREE_MAX_RESOLUTION);
        return MPB_EINVAL;
    }
    return MPB_OK;
}

void mpb_sense_default_cameras(const mpb_scene *s, mpb_sense_options *o)
{
    if (!s || !o)
        return;
    double c[3] = {0, 0, 0};
    int n = 0;
    for (int i = 0; i < mpb_scene_num_objects(s); i++) {
        const mpb_scene_object *ob = mpb_scene_object_at(s, i);
        if (ob->attached_link)
            continue;
        for (int k = 0; k < ob->num_shapes; k++) {
            if (ob->shapes[k].geometry.type == MPB_SHAPE_PLANE)
                continue;
            double w[3];
            mpb_pose_apply(&ob->pose, ob->shapes[k].pose.t, w);
            for (int j = 0; j < 3; j++)
                c[j] += w[j];
            n++;
        }
    }
    for (int j = 0; n > 0 && j < 3; j++)
        c[j] /= n;
    o->num_cameras = 2;
    for (int i = 0; i < 2; i++) {
        mpb_camera *cam = &o->cameras[i];
        memcpy(cam->at, c, sizeof c);
        cam->eye[0] = c[0] - 1.5;
        cam->eye[1] = c[1] + (i ? -1.0 : 1.0);
        cam->eye[2] = c[2] + 1.0;
    }
}

/* ---- sensing -------------------------------------------------------------- */

/* Check o and copy it into *use, with the default cameras when it names
 * none. */
static int prepare(const mpb_scene *s, const mpb_sense_options *o, mpb_sense_options *use,
                   char *why, size_t len)
{
    if (!s || !o) {
        mpb__set_err(why, len, "no scene or no options given");
        return MPB_EINVAL;
    }
    int rc = mpb_sense_options_check(o, why, len);
    if (rc != MPB_OK)
        return rc;
    *use = *o;
    if (use->num_cameras == 0)
        mpb_sense_default_cameras(s, use);
    return MPB_OK;
}

/* mpb_scene_sense() with o checked and its cameras filled in. */
static int sense(const mpb_scene *s, const mpb_sense_options *o, mpb_octree **out,
                 long *hits, char *why, size_t len)
{
    mpb_octree *t = NULL;
    if (mpb_octree_create(o->resolution, &t) != MPB_OK) {
        mpb__set_err(why, len, "out of memory");
        return MPB_ENOMEM;
    }
    uint64_t rng = o->seed;
    long total = 0;
    for (int i = 0; i < o->num_cameras; i++) {
        long h = cast(o, &o->cameras[i], s, t, &rng);
        /* the pending points merged, so that an overflow is this camera's */
        int rc = h < 0 ? (int)h : mpb_octree_num_cells(t);
        if (rc < 0) {
            mpb__set_err(why, len, "camera %d: %s", i + 1,
                         rc == MPB_EPARSE ? "more occupied cells than an octree may hold"
                                          : mpb_strerror(rc));
            mpb_octree_destroy(t);
            return rc;
        }
        total += h;
    }
    *out = t;
    if (hits)
        *hits = total;
    return MPB_OK;
}

int mpb_scene_sense(const mpb_scene *s, const mpb_sense_options *o, mpb_octree **out,
                    long *hits, char *why, size_t len)
{
    if (!out) {
        mpb__set_err(why, len, "nowhere to put the octree");
        return MPB_EINVAL;
    }
    *out = NULL;
    mpb_sense_options use;
    int rc = prepare(s, o, &use, why, len);
    return rc != MPB_OK ? rc : sense(s, &use, out, hits, why, len);
}

int mpb_scene_sense_text(const mpb_scene *s, const mpb_sense_options *o, char **text,
                         long *hits, int *cells, char *why, size_t len)
{
    if (!text) {
        mpb__set_err(why, len, "nowhere to put the text");
        return MPB_EINVAL;
    }
    *text = NULL;
    mpb_sense_options use;
    int rc = prepare(s, o, &use, why, len);
    mpb_octree *t = NULL;
    long h = 0;
    if (rc == MPB_OK)
        rc = sense(s, &use, &t, &h, why, len);
    if (rc != MPB_OK)
        return rc;
    char *tree = NULL, *all = NULL;
    size_t n = 0;
    rc = mpb_scene_octree_text(t, "sensed", NULL, &tree);
    if (rc != MPB_OK) {
        mpb__set_err(why, len, "the octree's text: %s", mpb_strerror(rc));
        mpb_octree_destroy(t);
        return rc;
    }
    int k = mpb_octree_num_cells(t);
    FILE *f = open_memstream(&all, &n);
    if (f) {
        fprintf(f, "%s (sensed)\n.\n# mpb sense: %d camera(s) %dx%d, fov %g, range %g .. %g m, "
                "noise %g m, seed %llu, resolution %g m: %ld hits, %d cells\n",
                mpb_scene_name(s), use.num_cameras, use.width, use.height, use.fov, use.near,
                use.far, use.noise, (unsigned long long)use.seed, use.resolution, h, k);
        for (int i = 0; i < use.num_cameras; i++) {
            const mpb_camera *c = &use.cameras[i];
            fprintf(f, "# camera %d at %g %g %g looking at %g %g %g\n", i + 1, c->eye[0],
                    c->eye[1], c->eye[2], c->at[0], c->at[1], c->at[2]);
        }
        fputs(tree, f);
        int bad = ferror(f);
        if ((fclose(f) != 0) | bad) {
            free(all);
            all = NULL;
        }
    }
    free(tree);
    mpb_octree_destroy(t);
    if (!all) {
        mpb__set_err(why, len, "out of memory");
        return MPB_ENOMEM;
    }
    *text = all;
    if (hits)
        *hits = h;
    if (cells)
        *cells = k;
    return MPB_OK;
}
