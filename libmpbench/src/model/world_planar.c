/*
 * world_planar.c - the "planar" world provider: a chain of revolute joints
 * in the plane, capsule links, circle and axis-aligned box obstacles. Exact
 * distances, no self-collision.
 */
#include "mpbench/mpbench.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/errbuf.h"
#include "core/grow.h"
#include "core/number.h"
#include "model/world_provider.h"
#include "core/mathconst.h"

/* ---- text: lines of whitespace-separated tokens, '#' to end of line ---- */

#define MAX_TOKENS 8
#define NAME_SHOWN 40           /* characters of a token quoted in errors */

typedef struct token {
    const char *p;
    int         len;
} token;

typedef struct lines {
    const char *cur;
    int         lineno;
} lines;

static int is_space(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/*
 * Read the next line with at least one token. Returns the number of tokens
 * on it (only the first MAX_TOKENS are stored), 0 at the end of the text.
 */
static int next_line(lines *ls, token *t)
{
    while (*ls->cur) {
        ls->lineno++;
        int n = 0;
        const char *s = ls->cur;
        while (*s && *s != '\n' && *s != '#') {
            while (is_space(*s))
                s++;
            if (!*s || *s == '\n' || *s == '#')
                break;
            const char *b = s;
            while (*s && *s != '\n' && *s != '#' && !is_space(*s))
                s++;
            if (n < MAX_TOKENS) {
                t[n].p = b;
                t[n].len = (int)(s - b);
            }
            n++;
        }
        while (*s && *s != '\n')
            s++;
        ls->cur = *s ? s + 1 : s;
        if (n > 0)
            return n;
    }
    return 0;
}

static int tok_is(const token *t, const char *word)
{
    size_t n = strlen(word);
    return (size_t)t->len == n && memcmp(t->p, word, n) == 0;
}

static int shown(const token *t)
{
    return t->len < NAME_SHOWN ? t->len : NAME_SHOWN;
}

/*
 * Parse tokens t[first..first+count) as numbers into v; 0 and a message if
 * not. Each is a length (m) or an angle (rad), bounded as the collision
 * world bounds coordinates: near 1e308 the distances overflow to NaN.
 */
static int numbers(const token *t, int first, int count, double *v,
                   const char *what, int lineno, char *err, size_t errlen)
{
    for (int i = 0; i < count; i++) {
        const token *k = &t[first + i];
        if (!mpb__number(k->p, k->len, &v[i])) {
            mpb__set_err(err, errlen, "%s line %d: '%.*s' is not a number",
                         what, lineno, shown(k), k->p);
            return 0;
        }
        if (fabs(v[i]) > MPB_COLLISION_MAX_COORD) {
            /* A scene holds lengths only; a robot, angles too. */
            mpb__set_err(err, errlen, "%s line %d: %.*s is beyond %g %s", what,
                         lineno, shown(k), k->p, MPB_COLLISION_MAX_COORD,
                         strcmp(what, "scene") == 0 ? "m" : "(m or rad)");
            return 0;
        }
    }
    return 1;
}

/* ---- the planar world --------------------------------------------------- */

typedef struct circle {
    double cx, cy, r;
} circle;

typedef struct box {
    double xmin, ymin, xmax, ymax;
} box;

typedef struct planar {
    int     n;                  /* joints = links */
    double  bx, by;             /* base */
    double  radius;             /* link_radius */
    double *length;             /* n */
    double *xy;                 /* 2 (n + 1): scratch for forward kinematics */
    circle *circles;
    int     num_circles, cap_circles;
    box    *boxes;
    int     num_boxes, cap_boxes;
} planar;

static void planar_close(void *impl)
{
    planar *p = impl;
    if (!p)
        return;
    free(p->length);
    free(p->xy);
    free(p->circles);
    free(p->boxes);
    free(p);
}

static int parse_robot(mpb_world *w, planar *p, const char *text,
                       char *err, size_t errlen)
{
    lines ls = { text, 0 };
    token t[MAX_TOKENS];
    int nt, have_base = 0, have_radius = 0, cap_length = 0;
    double v[3];

    while ((nt = next_line(&ls, t)) > 0) {
        int ln = ls.lineno;
        if (tok_is(&t[0], "base")) {
            if (nt != 3) {
                mpb__set_err(err, errlen, "robot line %d: base needs <x> <y>", ln);
                return MPB_EPARSE;
            }
            if (have_base) {
                mpb__set_err(err, errlen, "robot line %d: a second base", ln);
                return MPB_EPARSE;
            }
            if (!numbers(t, 1, 2, v, "robot", ln, err, errlen))
                return MPB_EPARSE;
            p->bx = v[0];
            p->by = v[1];
            have_base = 1;
        } else if (tok_is(&t[0], "link_radius")) {
            if (nt != 2) {
                mpb__set_err(err, errlen, "robot line %d: link_radius needs <r>", ln);
                return MPB_EPARSE;
            }
            if (have_radius) {
                mpb__set_err(err, errlen, "robot line %d: a second link_radius", ln);
                return MPB_EPARSE;
            }
            if (!numbers(t, 1, 1, v, "robot", ln, err, errlen))
                return MPB_EPARSE;
            if (v[0] < 0) {
                mpb__set_err(err, errlen, "robot line %d: link_radius must be >= 0", ln);
                return MPB_EPARSE;
            }
            p->radius = v[0];
            have_radius = 1;
        } else if (tok_is(&t[0], "joint")) {
            int continuous = nt == 4 && tok_is(&t[2], "continuous");
            if (!continuous && nt != 5) {
                mpb__set_err(err, errlen, "robot line %d: joint needs <name> "
                             "<lo> <hi> <length> (or <name> continuous "
                             "<length>)", ln);
                return MPB_EPARSE;
            }
            const token *name = &t[1];
            for (int j = 0; j < w->num_joints; j++)
                if (tok_is(name, w->joint_names[j])) {
                    mpb__set_err(err, errlen, "robot line %d: joint '%.*s' "
                                 "declared twice", ln, shown(name), name->p);
                    return MPB_EPARSE;
                }
            if (continuous) {
                if (!numbers(t, 3, 1, &v[2], "robot", ln, err, errlen))
                    return MPB_EPARSE;
                v[0] = -M_PI;
                v[1] = M_PI;
            } else {
                if (!numbers(t, 2, 3, v, "robot", ln, err, errlen))
                    return MPB_EPARSE;
                if (v[0] > v[1]) {
                    mpb__set_err(err, errlen, "robot line %d: joint '%.*s' "
                                 "has lo > hi", ln, shown(name), name->p);
                    return MPB_EPARSE;
                }
            }
            if (!(v[2] > 0)) {
                mpb__set_err(err, errlen, "robot line %d: joint '%.*s' "
                             "length must be > 0", ln, shown(name), name->p);
                return MPB_EPARSE;
            }
            if (mpb__grow((void **)&p->length, &cap_length, p->n + 1,
                          sizeof *p->length) != MPB_OK)
                return MPB_ENOMEM;
            int rc = mpb__world_add_joint(w, name->p, (size_t)name->len,
                                          v[0], v[1], continuous, 0.0);
            if (rc != MPB_OK)
                return rc;
            p->length[p->n++] = v[2];
        } else {
            mpb__set_err(err, errlen, "robot line %d: unknown item '%.*s' "
                         "(expected base, link_radius or joint)", ln,
                         shown(&t[0]), t[0].p);
            return MPB_EPARSE;
        }
    }
    if (!have_radius) {
        mpb__set_err(err, errlen, "robot: no link_radius line");
        return MPB_EPARSE;
    }
    if (p->n == 0) {
        mpb__set_err(err, errlen, "robot: no joints");
        return MPB_EPARSE;
    }
    return MPB_OK;
}

static int parse_scene(planar *p, const char *text, char *err, size_t errlen)
{
    lines ls = { text, 0 };
    token t[MAX_TOKENS];
    int nt;
    double v[4];

    while ((nt = next_line(&ls, t)) > 0) {
        int ln = ls.lineno;
        if (tok_is(&t[0], "circle")) {
            if (nt != 4) {
                mpb__set_err(err, errlen, "scene line %d: circle needs <cx> <cy> <r>", ln);
                return MPB_EPARSE;
            }
            if (!numbers(t, 1, 3, v, "scene", ln, err, errlen))
                return MPB_EPARSE;
            if (v[2] < 0) {
                mpb__set_err(err, errlen, "scene line %d: circle radius must be >= 0", ln);
                return MPB_EPARSE;
            }
            if (mpb__grow((void **)&p->circles, &p->cap_circles, p->num_circles + 1,
                          sizeof *p->circles) != MPB_OK)
                return MPB_ENOMEM;
            p->circles[p->num_circles++] = (circle){ .cx = v[0], .cy = v[1], .r = v[2] };
        } else if (tok_is(&t[0], "box")) {
            if (nt != 5) {
                mpb__set_err(err, errlen, "scene line %d: box needs <cx> <cy> "
                             "<half_x> <half_y>", ln);
                return MPB_EPARSE;
            }
            if (!numbers(t, 1, 4, v, "scene", ln, err, errlen))
                return MPB_EPARSE;
            if (v[2] < 0 || v[3] < 0) {
                mpb__set_err(err, errlen, "scene line %d: box half sizes must be >= 0", ln);
                return MPB_EPARSE;
            }
            if (mpb__grow((void **)&p->boxes, &p->cap_boxes, p->num_boxes + 1,
                          sizeof *p->boxes) != MPB_OK)
                return MPB_ENOMEM;
            p->boxes[p->num_boxes++] = (box){ .xmin = v[0] - v[2], .ymin = v[1] - v[3],
                                              .xmax = v[0] + v[2], .ymax = v[1] + v[3] };
        } else {
            mpb__set_err(err, errlen, "scene line %d: unknown item '%.*s' "
                         "(expected circle or box)", ln, shown(&t[0]), t[0].p);
            return MPB_EPARSE;
        }
    }
    return MPB_OK;
}

static int planar_open(mpb_world *w, const char *robot_text,
                       const char *scene_text, const char *const *joints,
                       int num_joints, char *err, size_t errlen)
{
    planar *p = calloc(1, sizeof *p);
    if (!p)
        return MPB_ENOMEM;
    w->impl = p;
    int rc = parse_robot(w, p, robot_text, err, errlen);
    if (rc != MPB_OK)
        return rc;
    rc = parse_scene(p, scene_text, err, errlen);
    if (rc != MPB_OK)
        return rc;
    /* A group, if named, must be the arm's joints in order. */
    int same = joints == NULL || num_joints == w->num_joints;
    for (int j = 0; same && joints && j < num_joints; j++)
        same = joints[j] && strcmp(joints[j], w->joint_names[j]) == 0;
    if (!same) {
        mpb__set_err(err, errlen, "robot: the group's joints must be the "
                     "planar arm's %d joints in order", w->num_joints);
        return MPB_EPARSE;
    }
    p->xy = malloc(2 * ((size_t)p->n + 1) * sizeof *p->xy);
    return p->xy ? MPB_OK : MPB_ENOMEM;
}

/* ---- kinematics and geometry ------------------------------------------- */

/* Joint i at xy[2i], link i from joint i to i + 1; the tip is xy[2n]. */
static void forward(const planar *p, const double *q, double *xy)
{
    double x = p->bx, y = p->by, theta = 0.0;
    xy[0] = x;
    xy[1] = y;
    for (int i = 0; i < p->n; i++) {
        theta += q[i];
        x += p->length[i] * cos(theta);
        y += p->length[i] * sin(theta);
        xy[2 * i + 2] = x;
        xy[2 * i + 3] = y;
    }
}

/* Squared distance from point (px, py) to the segment a-b. */
static double seg_point2(double ax, double ay, double bx, double by,
                         double px, double py)
{
    double dx = bx - ax, dy = by - ay;
    double dd = dx * dx + dy * dy;
    double t = dd > 0 ? ((px - ax) * dx + (py - ay) * dy) / dd : 0.0;
    if (t < 0)
        t = 0;
    else if (t > 1)
        t = 1;
    double ex = ax + t * dx - px, ey = ay + t * dy - py;
    return ex * ex + ey * ey;
}

/* Distance from point (px, py) to the segment a-b. sqrt, not hypot:
 * planar distances are far from overflow, and hypot's care costs a third
 * of verification (bench/verify.c, callgrind). */
static double seg_point(double ax, double ay, double bx, double by,
                        double px, double py)
{
    return sqrt(seg_point2(ax, ay, bx, by, px, py));
}

/* The larger of a, b and 0; a plain comparison, not fmax(): the values are
 * finite, and fmax is a call into libm for its NaN rules. */
static double pos_max(double a, double b)
{
    double m = a > b ? a : b;
    return m > 0.0 ? m : 0.0;
}

/* Squared distance from a point to a box; 0 inside. */
static double box_point2(const box *b, double px, double py)
{
    double dx = pos_max(b->xmin - px, px - b->xmax);
    double dy = pos_max(b->ymin - py, py - b->ymax);
    return dx * dx + dy * dy;
}

/* Distance from a point to a box; 0 inside. */
static double box_point(const box *b, double px, double py)
{
    return sqrt(box_point2(b, px, py));
}

/* Does the segment a-b meet the box? (Liang-Barsky clipping.) */
static int seg_meets_box(double ax, double ay, double bx, double by,
                         const box *b)
{
    double t0 = 0.0, t1 = 1.0;
    double pq[4][2] = {
        { -(bx - ax), ax - b->xmin },
        {   bx - ax,  b->xmax - ax },
        { -(by - ay), ay - b->ymin },
        {   by - ay,  b->ymax - ay },
    };
    for (int k = 0; k < 4; k++) {
        double pk = pq[k][0], qk = pq[k][1];
        if (pk == 0) {
            if (qk < 0)
                return 0;       /* parallel to this side and outside it */
        } else {
            double r = qk / pk;
            if (pk < 0)
                t0 = r > t0 ? r : t0;
            else
                t1 = r < t1 ? r : t1;
            if (t0 > t1)
                return 0;
        }
    }
    return 1;
}

/*
 * Distance from the segment a-b to a box; 0 if they meet. Two disjoint
 * convex sets are nearest at a vertex of one: an end of the segment against
 * the box, or a corner of the box against the segment.
 */
static double seg_box(double ax, double ay, double bx, double by,
                      const box *b)
{
    if (seg_meets_box(ax, ay, bx, by, b))
        return 0.0;
    double d = fmin(box_point(b, ax, ay), box_point(b, bx, by));
    d = fmin(d, seg_point(ax, ay, bx, by, b->xmin, b->ymin));
    d = fmin(d, seg_point(ax, ay, bx, by, b->xmin, b->ymax));
    d = fmin(d, seg_point(ax, ay, bx, by, b->xmax, b->ymin));
    d = fmin(d, seg_point(ax, ay, bx, by, b->xmax, b->ymax));
    return d;
}

/*
 * Smallest signed distance from the capsule links to the obstacles; stops
 * early, at the first value <= stop_at.
 */
static double min_distance(planar *p, const double *q, double stop_at)
{
    double best = INFINITY;
    forward(p, q, p->xy);
    for (int i = 0; i < p->n; i++) {
        double ax = p->xy[2 * i], ay = p->xy[2 * i + 1];
        double bx = p->xy[2 * i + 2], by = p->xy[2 * i + 3];
        for (int k = 0; k < p->num_circles; k++) {
            const circle *c = &p->circles[k];
            double d = seg_point(ax, ay, bx, by, c->cx, c->cy) - c->r - p->radius;
            if (d < best)
                best = d;
            if (best <= stop_at)
                return best;
        }
        for (int k = 0; k < p->num_boxes; k++) {
            double d = seg_box(ax, ay, bx, by, &p->boxes[k]) - p->radius;
            if (d < best)
                best = d;
            if (best <= stop_at)
                return best;
        }
    }
    return best;
}

/*
 * Does a capsule link (segment a-b, radius r) touch the box? The same
 * answer as seg_box() - r <= 0, in squared distances: no square roots.
 */
static int capsule_box(double ax, double ay, double bx, double by, double r,
                       const box *b)
{
    double r2 = r * r;
    return seg_meets_box(ax, ay, bx, by, b) ||
           box_point2(b, ax, ay) <= r2 || box_point2(b, bx, by) <= r2 ||
           seg_point2(ax, ay, bx, by, b->xmin, b->ymin) <= r2 ||
           seg_point2(ax, ay, bx, by, b->xmin, b->ymax) <= r2 ||
           seg_point2(ax, ay, bx, by, b->xmax, b->ymin) <= r2 ||
           seg_point2(ax, ay, bx, by, b->xmax, b->ymax) <= r2;
}

/* min_distance(q) <= 0, decided without distances: verification asks
 * this at every step of every path, and needs no more. */
static int planar_in_collision(void *impl, const double *q)
{
    planar *p = impl;
    forward(p, q, p->xy);
    for (int i = 0; i < p->n; i++) {
        double ax = p->xy[2 * i], ay = p->xy[2 * i + 1];
        double bx = p->xy[2 * i + 2], by = p->xy[2 * i + 3];
        for (int k = 0; k < p->num_circles; k++) {
            const circle *c = &p->circles[k];
            double reach = c->r + p->radius;
            if (seg_point2(ax, ay, bx, by, c->cx, c->cy) <= reach * reach)
                return 1;
        }
        for (int k = 0; k < p->num_boxes; k++)
            if (capsule_box(ax, ay, bx, by, p->radius, &p->boxes[k]))
                return 1;
    }
    return 0;
}

static double planar_clearance(void *impl, const double *q)
{
    return min_distance(impl, q, -INFINITY);
}

static void planar_ee_position(void *impl, const double *q, double xyz[3])
{
    planar *p = impl;
    forward(p, q, p->xy);
    xyz[0] = p->xy[2 * p->n];
    xyz[1] = p->xy[2 * p->n + 1];
    xyz[2] = 0.0;
}

/*
 * Certified verification's step (world_provider.h): the distance now over
 * the fastest any point of the arm can move per unit s. A point of link i
 * lies within sum_{k=j..i} length[k] + radius of joint j, so it moves at
 * most sum_{j<=i} |d_j| (sum_{k=j..i} length[k] + radius) per unit s; the
 * last link's bound holds for every link.
 */
static int planar_safe_step(void *impl, const double *q, const double *d,
                            double margin, double want, double moved,
                            double *step)
{
    (void)moved;                /* distances are measured every time */
    planar *p = impl;
    double rate = 0.0, lever = p->radius;
    for (int j = p->n - 1; j >= 0; j--) {
        lever += p->length[j];
        rate += fabs(d[j]) * lever;
    }
    double gap = min_distance(p, q, -INFINITY) - margin;
    if (!(gap > 0))
        *step = 0.0;
    else
        *step = rate > 0 ? fmin(want, gap / rate) : want;
    return isfinite(*step) ? MPB_OK : MPB_EINVAL;
}

const mpb__world_provider mpb__world_planar = {
    .robot_format = "planar",
    .scene_format = "planar",
    .open         = planar_open,
    .close        = planar_close,
    .in_collision = planar_in_collision,
    .clearance    = planar_clearance,
    .ee_position  = planar_ee_position,
    .safe_step    = planar_safe_step,
};

int mpb__planar_points(const mpb_world *w, const double *q, double *xy)
{
    if (!w || !q || !xy || w->provider != &mpb__world_planar)
        return MPB_EINVAL;
    forward(w->impl, q, xy);
    return MPB_OK;
}

int mpb__planar_get_model(const mpb_world *w, mpb__planar_model *out)
{
    if (!w || !out || w->provider != &mpb__world_planar)
        return MPB_EINVAL;
    const planar *p = w->impl;
    *out = (mpb__planar_model){p->n, {p->bx, p->by}, p->radius, p->length,
                               p->num_circles, p->num_boxes};
    return MPB_OK;
}

int mpb__planar_obstacle(const mpb_world *w, int k, double v[4])
{
    if (!w || !v || w->provider != &mpb__world_planar)
        return MPB_EINVAL;
    const planar *p = w->impl;
    if (k >= 0 && k < p->num_circles) {
        const circle *c = &p->circles[k];
        v[0] = c->cx, v[1] = c->cy, v[2] = c->r, v[3] = 0.0;
        return MPB_OK;
    }
    k -= p->num_circles;
    if (k < 0 || k >= p->num_boxes)
        return MPB_EINVAL;
    const box *b = &p->boxes[k];
    v[0] = b->xmin, v[1] = b->ymin, v[2] = b->xmax, v[3] = b->ymax;
    return MPB_OK;
}

int mpb__planar_contact(mpb_world *w, const double *q, int *link,
                        int *obstacle)
{
    if (!w || !q || w->provider != &mpb__world_planar)
        return MPB_EINVAL;
    planar *p = w->impl;
    forward(p, q, p->xy);
    for (int i = 0; i < p->n; i++) {
        double ax = p->xy[2 * i], ay = p->xy[2 * i + 1];
        double bx = p->xy[2 * i + 2], by = p->xy[2 * i + 3];
        for (int k = 0; k < p->num_circles; k++) {
            const circle *c = &p->circles[k];
            double reach = c->r + p->radius;
            if (seg_point2(ax, ay, bx, by, c->cx, c->cy) <= reach * reach) {
                *link = i, *obstacle = k;
                return 1;
            }
        }
        for (int k = 0; k < p->num_boxes; k++)
            if (capsule_box(ax, ay, bx, by, p->radius, &p->boxes[k])) {
                *link = i, *obstacle = p->num_circles + k;
                return 1;
            }
    }
    return 0;
}
