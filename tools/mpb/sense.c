/*
 * sense.c - `mpb sense SCENE -o SENSED`: what depth cameras would see of a
 * scene. Each camera casts a ray per pixel against the scene's world
 * objects (boxes, spheres, cylinders, cones, planes, meshes), adds
 * Gaussian noise along the ray (a seeded generator of its own, so that a
 * seed gives the same bytes), and the hits within range are fused into an
 * occupancy octree, written as a scene of one octree object.
 */
#include <getopt.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpbench/mpbench.h"
#include "mpbench/octree.h"
#include "mpbench/scene.h"

#include "mpb.h"

#define CMD "sense"
#define MAX_CAMERAS 16

typedef struct camera {
    double eye[3], at[3];
} camera;

typedef struct settings {
    camera cams[MAX_CAMERAS];
    int    ncams;
    int    width, height;
    double fov;                  /* horizontal, degrees */
    double near, far;            /* m */
    double noise;                /* m, standard deviation along the ray */
    double resolution;           /* m */
    uint64_t seed;
} settings;

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

/* Cast camera c's rays; hits in range into o. The number of hits, or a
 * negative code. */
static long cast(const settings *st, const camera *c, const mpb_scene *s, mpb_octree *o,
                 uint64_t *rng)
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
    double tx = tan(st->fov * M_PI / 360.0), ty = tx * st->height / st->width;
    long hits = 0;
    for (int y = 0; y < st->height; y++)
        for (int x = 0; x < st->width; x++) {
            double a = (2.0 * (x + 0.5) / st->width - 1.0) * tx;
            double b = (1.0 - 2.0 * (y + 0.5) / st->height) * ty;
            double d[3];
            for (int k = 0; k < 3; k++)
                d[k] = f[k] + a * r[k] + b * u[k];
            normalise(d);
            double t = scene_hit(s, c->eye, d);
            double n = st->noise > 0 ? st->noise * gaussian(rng) : 0.0;
            if (!(t >= st->near && t <= st->far))
                continue;
            t += n;
            double p[3];
            for (int k = 0; k < 3; k++)
                p[k] = c->eye[k] + t * d[k];
            int rc = mpb_octree_add_point(o, p);
            if (rc == MPB_EINVAL)
                continue;            /* beyond the octree's reach */
            if (rc != MPB_OK)
                return rc;
            hits++;
        }
    return hits;
}

/* Two cameras over the scene's world objects, as a robot's head and a
 * second view would see it: 1.5 m back along -x, 1 m to either side,
 * 1 m up, looking at the centre of the objects' positions. */
static void default_cameras(const mpb_scene *s, settings *st)
{
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
    st->ncams = 2;
    for (int i = 0; i < 2; i++) {
        camera *cam = &st->cams[i];
        memcpy(cam->at, c, sizeof c);
        cam->eye[0] = c[0] - 1.5;
        cam->eye[1] = c[1] + (i ? -1.0 : 1.0);
        cam->eye[2] = c[2] + 1.0;
    }
}

static int parse_numbers(const char *s, double *v, int n)
{
    char *e;
    for (int i = 0; i < n; i++) {
        v[i] = strtod(s, &e);
        if (e == s || !isfinite(v[i]))
            return -1;
        s = e;
        while (*s == ' ' || *s == ',')
            s++;
    }
    return *s ? -1 : 0;
}

static void usage(FILE *f)
{
    fprintf(f,
            "usage: mpb sense SCENE -o SENSED [options]\n"
            "  --camera 'EX EY EZ AX AY AZ'  a camera at E looking at A (repeat; default:\n"
            "                                two, 1.5 m back and 1 m up, either side)\n"
            "  --width N --height N    pixels (default 160 x 120)\n"
            "  --fov DEG               horizontal field of view (default 60)\n"
            "  --range NEAR FAR        m (default 0.3 4)\n"
            "  --noise SIGMA           m along each ray, Gaussian (default 0.002)\n"
            "  --resolution R          the octree's cells, m (default 0.01)\n"
            "  --seed N                the noise's seed (default 1)\n");
}

int cmd_sense(int argc, char **argv)
{
    settings st = {.width = 160, .height = 120, .fov = 60, .near = 0.3, .far = 4,
                   .noise = 0.002, .resolution = 0.01, .seed = 1};
    const char *outpath = NULL;
    static const struct option opts[] = {
        {"output", required_argument, NULL, 'o'}, {"camera", required_argument, NULL, 'c'},
        {"width", required_argument, NULL, 'W'},  {"height", required_argument, NULL, 'H'},
        {"fov", required_argument, NULL, 'f'},    {"range", required_argument, NULL, 'r'},
        {"noise", required_argument, NULL, 'n'},  {"resolution", required_argument, NULL, 'R'},
        {"seed", required_argument, NULL, 's'},   {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0}};
    opterr = 0;
    optind = 1;
    int opt;
    while ((opt = getopt_long(argc, argv, ":o:h", opts, NULL)) != -1) {
        double v[6];
        switch (opt) {
        case 'o':
            outpath = optarg;
            break;
        case 'c':
            if (st.ncams == MAX_CAMERAS || parse_numbers(optarg, v, 6) != 0) {
                fprintf(stderr, "mpb sense: --camera needs 'EX EY EZ AX AY AZ' (at most "
                        "%d cameras), not '%s'\n", MAX_CAMERAS, optarg);
                return MPB_EXIT_USAGE;
            }
            memcpy(st.cams[st.ncams].eye, v, 3 * sizeof *v);
            memcpy(st.cams[st.ncams].at, v + 3, 3 * sizeof *v);
            st.ncams++;
            break;
        case 'W':
        case 'H':
            if (parse_numbers(optarg, v, 1) != 0 || v[0] < 1 || v[0] > 4096 ||
                v[0] != floor(v[0])) {
                fprintf(stderr, "mpb sense: --%s needs a whole number of pixels from 1 "
                        "to 4096, not '%s'\n", opt == 'W' ? "width" : "height", optarg);
                return MPB_EXIT_USAGE;
            }
            *(opt == 'W' ? &st.width : &st.height) = (int)v[0];
            break;
        case 'f':
            if (parse_numbers(optarg, v, 1) != 0 || !(v[0] > 0 && v[0] < 170)) {
                fprintf(stderr, "mpb sense: --fov needs degrees in (0, 170), not '%s'\n",
                        optarg);
                return MPB_EXIT_USAGE;
            }
            st.fov = v[0];
            break;
        case 'r':
            if (optind >= argc || parse_numbers(optarg, v, 1) != 0 ||
                parse_numbers(argv[optind], v + 1, 1) != 0 || !(v[0] >= 0 && v[1] > v[0])) {
                fprintf(stderr, "mpb sense: --range needs NEAR FAR, 0 <= NEAR < FAR\n");
                return MPB_EXIT_USAGE;
            }
            optind++;
            st.near = v[0];
            st.far = v[1];
            break;
        case 'n':
            if (parse_numbers(optarg, v, 1) != 0 || v[0] < 0) {
                fprintf(stderr, "mpb sense: --noise needs a standard deviation >= 0 m, "
                        "not '%s'\n", optarg);
                return MPB_EXIT_USAGE;
            }
            st.noise = v[0];
            break;
        case 'R':
            if (parse_numbers(optarg, v, 1) != 0 || !(v[0] >= MPB_OCTREE_MIN_RESOLUTION &&
                                                      v[0] <= MPB_OCTREE_MAX_RESOLUTION)) {
                fprintf(stderr, "mpb sense: --resolution needs %g .. %g m, not '%s'\n",
                        MPB_OCTREE_MIN_RESOLUTION, MPB_OCTREE_MAX_RESOLUTION, optarg);
                return MPB_EXIT_USAGE;
            }
            st.resolution = v[0];
            break;
        case 's': {
            char *e;
            unsigned long long x = strtoull(optarg, &e, 10);
            if (e == optarg || *e || optarg[0] == '-') {
                fprintf(stderr, "mpb sense: --seed needs a whole number >= 0, not '%s'\n",
                        optarg);
                return MPB_EXIT_USAGE;
            }
            st.seed = x;
            break;
        }
        case 'h':
            usage(stdout);
            return MPB_EXIT_OK;
        default:
            return tool_option_error(CMD, opt, argv);
        }
    }
    if (optind >= argc || !outpath) {
        usage(stderr);
        return MPB_EXIT_USAGE;
    }
    if (optind + 1 < argc)
        return tool_extra_argument(CMD, argv[optind + 1]);
    const char *inpath = argv[optind];
    char err[600];
    mpb_scene *s = NULL;
    if (mpb_scene_load(inpath, &s, err, sizeof err) != MPB_OK) {
        fprintf(stderr, "mpb sense: %s\n", err);
        return MPB_EXIT_ERROR;
    }
    if (st.ncams == 0)
        default_cameras(s, &st);
    mpb_octree *o = NULL;
    if (mpb_octree_create(st.resolution, &o) != MPB_OK) {
        mpb_scene_free(s);
        fprintf(stderr, "mpb sense: out of memory\n");
        return MPB_EXIT_ERROR;
    }
    uint64_t rng = st.seed;
    long hits = 0;
    for (int i = 0; i < st.ncams; i++) {
        long h = cast(&st, &st.cams[i], s, o, &rng);
        if (h < 0) {
            fprintf(stderr, "mpb sense: %s: camera %d: %s\n", inpath, i + 1,
                    h == MPB_EPARSE ? "more occupied cells than an octree may hold"
                                    : mpb_strerror((int)h));
            mpb_octree_free(o);
            mpb_scene_free(s);
            return MPB_EXIT_ERROR;
        }
        hits += h;
    }
    char *text = NULL;
    int rc = mpb_scene_octree_text(o, "sensed", NULL, &text);
    int cells = mpb_octree_num_cells(o);
    FILE *f = rc == MPB_OK ? fopen(outpath, "w") : NULL;
    if (!f) {
        fprintf(stderr, "mpb sense: cannot write %s\n", outpath);
        free(text);
        mpb_octree_free(o);
        mpb_scene_free(s);
        return MPB_EXIT_ERROR;
    }
    fprintf(f, "%s (sensed)\n.\n# mpb sense: %d camera(s) %dx%d, fov %g, range %g .. %g m, "
            "noise %g m, seed %llu, resolution %g m: %ld hits, %d cells\n",
            mpb_scene_name(s), st.ncams, st.width, st.height, st.fov, st.near, st.far,
            st.noise, (unsigned long long)st.seed, st.resolution, hits, cells);
    for (int i = 0; i < st.ncams; i++)
        fprintf(f, "# camera %d at %g %g %g looking at %g %g %g\n", i + 1,
                st.cams[i].eye[0], st.cams[i].eye[1], st.cams[i].eye[2],
                st.cams[i].at[0], st.cams[i].at[1], st.cams[i].at[2]);
    fputs(text, f);
    int bad = ferror(f) | (fclose(f) != 0);
    free(text);
    mpb_octree_free(o);
    mpb_scene_free(s);
    if (bad) {
        fprintf(stderr, "mpb sense: write error on %s\n", outpath);
        return MPB_EXIT_ERROR;
    }
    printf("%s: %ld hits, %d cells at %g m\n", outpath, hits, cells, st.resolution);
    return MPB_EXIT_OK;
}
