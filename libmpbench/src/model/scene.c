/*
 * scene.c - MoveIt's plain-text .scene format: parsing (both variants),
 * mpbench's "attach" extension for carried objects, the content hash, and
 * placing a scene's world objects in a collision world.
 */
#include "mpbench/mpbench.h"
#include "mpbench/scene.h"

#include "mpbench/octree.h"

#include "core/base64.h"
#include "core/grow.h"
#include "core/number.h"
#include "core/readfile.h"
#include "core/words.h"
#include "geometry/mesh.h"
#include "geometry/collision_internal.h"

#include <errno.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SHOWN 40                /* characters of a token quoted in errors */

typedef struct sobj {
    mpb_scene_object    pub;    /* the public view; arrays point below */
    char               *id;
    mpb_scene_shape    *shapes;
    int                 num_shapes, cap_shapes;
    mpb_scene_subframe *subframes;
    int                 num_subframes, cap_subframes;
    char               *link;
    char              **touch;
    int                 num_touch;
} sobj;

struct mpb_scene {
    char             *name;
    char              hash[MPB_HASH_SIZE];
    mpb_scene_variant variant;
    sobj             *objects;
    int               num_objects, cap_objects;
};

/* ---- text: whitespace-separated tokens with their line numbers ---------- */

typedef struct tok {
    const char *p;
    int         len;
    int         line;
} tok;

typedef struct parser {
    const char *p;              /* next unread character */
    int         line;           /* of p */
    int         last_line;      /* of the last token read */
    size_t      left;           /* bytes from p to the end */
    char       *err;
    size_t      errlen;
} parser;

static int is_ws(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

static void advance(parser *ps)
{
    if (*ps->p == '\n')
        ps->line++;
    ps->p++;
    ps->left--;
}

/* The next token, or 0 at the end of the text. */
static int next_tok(parser *ps, tok *t)
{
    while (*ps->p && is_ws(*ps->p))
        advance(ps);
    t->p = ps->p;
    t->line = ps->line;
    t->len = 0;
    if (!*ps->p)
        return 0;
    while (*ps->p && !is_ws(*ps->p))
        advance(ps);
    t->len = (int)(ps->p - t->p);
    ps->last_line = t->line;
    return 1;
}

/* The rest of the current line, trimmed; moves past its newline. */
static void rest_of_line(parser *ps, const char **b, int *len)
{
    while (*ps->p && *ps->p != '\n' && is_ws(*ps->p))
        advance(ps);
    const char *s = ps->p;
    while (*ps->p && *ps->p != '\n')
        advance(ps);
    const char *e = ps->p;
    while (e > s && is_ws(e[-1]))
        e--;
    if (*ps->p == '\n')
        advance(ps);
    *b = s;
    *len = (int)(e - s);
}

static int tok_is(const tok *t, const char *word)
{
    size_t n = strlen(word);
    return (size_t)t->len == n && memcmp(t->p, word, n) == 0;
}

static int shown(const tok *t)
{
    return t->len < SHOWN ? t->len : SHOWN;
}

#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
static int fail(parser *ps, int line, const char *fmt, ...)
{
    if (ps->err && ps->errlen) {
        int n = snprintf(ps->err, ps->errlen, "scene line %d: ", line);
        if (n >= 0 && (size_t)n < ps->errlen) {
            va_list ap;
            va_start(ap, fmt);
            vsnprintf(ps->err + n, ps->errlen - (size_t)n, fmt, ap);
            va_end(ap);
        }
        for (char *c = ps->err; *c; c++)
            if (*c == '\n' || *c == '\r')
                *c = ' ';
    }
    return MPB_EPARSE;
}

/* "found 'x'" or "found the end of the text", for messages. */
static int found(parser *ps, const tok *t, int have, const char *expected)
{
    if (!have)
        return fail(ps, ps->last_line, "%s, found the end of the text", expected);
    return fail(ps, t->line, "%s, found '%.*s'", expected, shown(t), t->p);
}

/* A non-negative decimal integer up to INT_MAX filling the whole token. */
static int tok_count(const tok *t, long *v)
{
    if (t->len <= 0 || t->len > 10)
        return 0;
    long x = 0;
    for (int i = 0; i < t->len; i++) {
        if (t->p[i] < '0' || t->p[i] > '9')
            return 0;
        x = 10 * x + (t->p[i] - '0');
    }
    if (x > INT_MAX)
        return 0;
    *v = x;
    return 1;
}

/* n numbers into v; "expected" says what was wanted, for the message. */
static int read_nums(parser *ps, double *v, int n, const char *expected)
{
    for (int i = 0; i < n; i++) {
        tok t;
        int have = next_tok(ps, &t);
        if (!have || !mpb__number(t.p, t.len, &v[i]))
            return found(ps, &t, have, expected);
    }
    return MPB_OK;
}

/* A count (see tok_count); *line (if not NULL) gets its line. */
static int read_count(parser *ps, long *n, int *line, const char *expected)
{
    tok t;
    int have = next_tok(ps, &t);
    if (!have || !tok_count(&t, n))
        return found(ps, &t, have, expected);
    if (line)
        *line = t.line;
    return MPB_OK;
}

/* Position then quaternion (x y z w) into *pose. */
static int read_pose(parser *ps, mpb_pose *pose, const char *what)
{
    double v[7];
    char expected[96];
    snprintf(expected, sizeof expected, "%s position needs <x> <y> <z>", what);
    int rc = read_nums(ps, v, 3, expected);
    if (rc != MPB_OK)
        return rc;
    for (int i = 0; i < 3; i++)
        if (fabs(v[i]) > MPB_COLLISION_MAX_COORD)
            return fail(ps, ps->last_line, "%s position: %g is beyond %g m", what,
                        v[i], MPB_COLLISION_MAX_COORD);
    snprintf(expected, sizeof expected, "%s orientation needs <qx> <qy> <qz> <qw>", what);
    rc = read_nums(ps, v + 3, 4, expected);
    if (rc != MPB_OK)
        return rc;
    pose->t[0] = v[0];
    pose->t[1] = v[1];
    pose->t[2] = v[2];
    if (mpb_pose_set_quat(pose, v[3], v[4], v[5], v[6]) != 0)
        return fail(ps, ps->last_line, "%s orientation: the quaternion is zero", what);
    return MPB_OK;
}

static char *dup_n(const char *s, size_t n)
{
    char *c = malloc(n + 1);
    if (c) {
        memcpy(c, s, n);
        c[n] = '\0';
    }
    return c;
}

/* ---- the scene ---------------------------------------------------------- */

static void sync_pub(sobj *o)
{
    o->pub.id = o->id;
    o->pub.shapes = o->shapes;
    o->pub.num_shapes = o->num_shapes;
    o->pub.subframes = o->subframes;
    o->pub.num_subframes = o->num_subframes;
    o->pub.attached_link = o->link;
    o->pub.touch_links = (const char *const *)o->touch;
    o->pub.num_touch_links = o->num_touch;
}

static void free_touch(sobj *o)
{
    for (int i = 0; i < o->num_touch; i++)
        free(o->touch[i]);
    free(o->touch);
    o->touch = NULL;
    o->num_touch = 0;
}

static void free_obj(sobj *o)
{
    free(o->id);
    for (int i = 0; i < o->num_shapes; i++)
        mpb__mesh_destroy((mpb_mesh *)o->shapes[i].geometry.mesh);
    free(o->shapes);
    for (int i = 0; i < o->num_subframes; i++)
        free((char *)o->subframes[i].name);
    free(o->subframes);
    free(o->link);
    free_touch(o);
}

void mpb_scene_close(mpb_scene *s)
{
    if (!s)
        return;
    for (int i = 0; i < s->num_objects; i++)
        free_obj(&s->objects[i]);
    free(s->objects);
    free(s->name);
    free(s);
}

static int find_n(const mpb_scene *s, const char *id, size_t n)
{
    for (int i = 0; i < s->num_objects; i++)
        if (strlen(s->objects[i].id) == n && memcmp(s->objects[i].id, id, n) == 0)
            return i;
    return MPB_ENOTFOUND;
}

/* Set the attachment of o (strings copied). */
static int attach(sobj *o, const char *link, size_t link_len,
                  const char *const *touch, const size_t *touch_len, int num_touch)
{
    char *l = dup_n(link, link_len);
    char **tl = num_touch > 0 ? calloc((size_t)num_touch, sizeof *tl) : NULL;
    if (!l || (num_touch > 0 && !tl)) {
        free(l);
        free(tl);
        return MPB_ENOMEM;
    }
    for (int i = 0; i < num_touch; i++) {
        tl[i] = dup_n(touch[i], touch_len[i]);
        if (!tl[i]) {
            for (int k = 0; k < i; k++)
                free(tl[k]);
            free(tl);
            free(l);
            return MPB_ENOMEM;
        }
    }
    free(o->link);
    free_touch(o);
    o->link = l;
    o->touch = tl;
    o->num_touch = num_touch;
    sync_pub(o);
    return MPB_OK;
}

/* ---- parsing ------------------------------------------------------------ */

static int parse_mesh(parser *ps, mpb_scene_shape *sh)
{
    long nv, nt;
    int line;
    int rc = read_count(ps, &nv, &line, "mesh needs <vertex count> <triangle count>");
    if (rc != MPB_OK)
        return rc;
    rc = read_count(ps, &nt, NULL, "mesh needs <vertex count> <triangle count>");
    if (rc != MPB_OK)
        return rc;
    if (nv < 3 || nt < 1)
        return fail(ps, line, "mesh needs at least 3 vertices and 1 "
                    "triangle (has %ld and %ld)", nv, nt);
    /* each vertex or triangle takes 5 bytes or more ("0 0 0"): a wrong
       count fails here, not in a huge allocation */
    if ((size_t)(nv + nt) > ps->left / 4)
        return fail(ps, line, "mesh of %ld vertices and %ld triangles: more "
                    "than the rest of the text holds", nv, nt);
    mpb_mesh *m = mpb__mesh_create((int)nv, (int)nt);
    if (!m)
        return MPB_ENOMEM;
    sh->geometry.mesh = m;      /* owned by the shape from here on */
    for (long i = 0; i < nv; i++) {
        char expected[80];
        snprintf(expected, sizeof expected, "mesh vertex %ld needs <x> <y> <z>", i);
        rc = read_nums(ps, &m->vertices[3 * i], 3, expected);
        if (rc != MPB_OK)
            return rc;
    }
    for (long i = 0; i < nt; i++)
        for (int k = 0; k < 3; k++) {
            tok t;
            long v;
            int have = next_tok(ps, &t);
            if (!have || !tok_count(&t, &v)) {
                char expected[80];
                snprintf(expected, sizeof expected, "mesh triangle %ld needs 3 "
                         "vertex indices", i);
                return found(ps, &t, have, expected);
            }
            if (v >= nv)
                return fail(ps, t.line, "mesh triangle %ld: vertex index %ld is "
                            "out of range 0..%ld", i, v, nv - 1);
            m->triangles[3 * i + k] = (int32_t)v;
        }
    return MPB_OK;
}

static int parse_shape(parser *ps, mpb_scene_shape *sh)
{
    static const char types[] = "expected a shape type (box, sphere, cylinder, "
                                "cone, plane or mesh)";
    tok t;
    int have = next_tok(ps, &t);
    if (!have)
        return found(ps, &t, have, types);
    sh->line = t.line;
    mpb_geometry *g = &sh->geometry;
    double *d = g->dims;
    int rc;
    if (tok_is(&t, "box")) {
        g->type = MPB_SHAPE_BOX;
        rc = read_nums(ps, d, 3, "box needs <x> <y> <z> (side lengths)");
    } else if (tok_is(&t, "sphere")) {
        g->type = MPB_SHAPE_SPHERE;
        rc = read_nums(ps, d, 1, "sphere needs <radius>");
    } else if (tok_is(&t, "cylinder")) {
        g->type = MPB_SHAPE_CYLINDER;
        rc = read_nums(ps, d, 2, "cylinder needs <radius> <length>");
    } else if (tok_is(&t, "cone")) {
        g->type = MPB_SHAPE_CONE;
        rc = read_nums(ps, d, 2, "cone needs <radius> <length>");
    } else if (tok_is(&t, "plane")) {
        g->type = MPB_SHAPE_PLANE;
        rc = read_nums(ps, d, 4, "plane needs <a> <b> <c> <d>");
        if (rc == MPB_OK && d[0] == 0 && d[1] == 0 && d[2] == 0)
            return fail(ps, ps->last_line, "plane: the normal (a, b, c) is "
                        "zero");
    } else if (tok_is(&t, "mesh")) {
        g->type = MPB_SHAPE_MESH;
        rc = parse_mesh(ps, sh);
    } else {
        return found(ps, &t, have, types);
    }
    if (rc != MPB_OK)
        return rc;
    /* the collision world's rules (collision.h), checked here with a line:
     * the dimensions' own (MoveIt writes them below the shape's name), a
     * mesh's at its name */
    char why[160];
    if (mpb__geometry_check(g, why, sizeof why) != MPB_OK)
        return fail(ps, g->type == MPB_SHAPE_MESH ? sh->line : ps->last_line,
                    "%s", why);
    rc = read_pose(ps, &sh->pose, "shape");
    if (rc != MPB_OK)
        return rc;
    double c[4];
    rc = read_nums(ps, c, 4, "shape color needs <r> <g> <b> <a>");
    if (rc != MPB_OK)
        return rc;
    for (int i = 0; i < 4; i++) {
        if (fabs(c[i]) > FLT_MAX)
            return fail(ps, ps->last_line, "shape color: %g does not fit a float", c[i]);
        sh->color[i] = (float)c[i];
    }
    return MPB_OK;
}

static int parse_object(parser *ps, mpb_scene *s, int star_line)
{
    const char *id;
    int idlen;
    rest_of_line(ps, &id, &idlen);
    if (idlen == 0)
        return fail(ps, star_line, "'*' needs an object id after it");
    int prev = find_n(s, id, (size_t)idlen);
    if (prev >= 0)
        return fail(ps, star_line, "object '%.*s' is defined twice (first on "
                    "line %d)", idlen < SHOWN ? idlen : SHOWN, id,
                    s->objects[prev].pub.line);

    if (s->num_objects == 0) {
        /* The variant, decided as MoveIt does: does the next line hold
           several numbers (a position) or one (a shape count)? */
        const char *b = ps->p, *e = ps->p;
        while (*e && *e != '\n')
            e++;
        while (b < e && is_ws(*b))
            b++;
        while (e > b && is_ws(e[-1]))
            e--;
        s->variant = MPB_SCENE_OLD;
        for (const char *c = b; c < e; c++)
            if (is_ws(*c))
                s->variant = MPB_SCENE_NEW;
    }

    if (mpb__grow((void **)&s->objects, &s->cap_objects, s->num_objects + 1,
                  sizeof *s->objects) != MPB_OK)
        return MPB_ENOMEM;
    sobj *o = &s->objects[s->num_objects];
    memset(o, 0, sizeof *o);
    o->id = dup_n(id, (size_t)idlen);
    if (!o->id)
        return MPB_ENOMEM;
    s->num_objects++;           /* from here on freed with the scene */
    o->pub.line = star_line;
    mpb_pose_identity(&o->pub.pose);

    int rc;
    if (s->variant == MPB_SCENE_NEW) {
        rc = read_pose(ps, &o->pub.pose, "object");
        if (rc != MPB_OK)
            return rc;
    }
    long count;
    rc = read_count(ps, &count, NULL, "expected the number of shapes");
    if (rc != MPB_OK)
        return rc;
    for (long i = 0; i < count; i++) {
        if (mpb__grow((void **)&o->shapes, &o->cap_shapes, o->num_shapes + 1,
                      sizeof *o->shapes) != MPB_OK)
            return MPB_ENOMEM;
        mpb_scene_shape *sh = &o->shapes[o->num_shapes++];
        memset(sh, 0, sizeof *sh);
        mpb_pose_identity(&sh->pose);
        rc = parse_shape(ps, sh);
        if (rc != MPB_OK)
            return rc;
    }
    if (s->variant == MPB_SCENE_NEW) {
        rc = read_count(ps, &count, NULL, "expected the number of subframes");
        if (rc != MPB_OK)
            return rc;
        for (long i = 0; i < count; i++) {
            tok t;
            int have = next_tok(ps, &t);
            if (!have)
                return found(ps, &t, have, "expected a subframe name");
            if (mpb__grow((void **)&o->subframes, &o->cap_subframes,
                          o->num_subframes + 1, sizeof *o->subframes) != MPB_OK)
                return MPB_ENOMEM;
            mpb_scene_subframe *sf = &o->subframes[o->num_subframes];
            sf->name = dup_n(t.p, (size_t)t.len);
            if (!sf->name)
                return MPB_ENOMEM;
            o->num_subframes++;
            rc = read_pose(ps, &sf->pose, "subframe");
            if (rc != MPB_OK)
                return rc;
        }
    }
    sync_pub(o);
    return MPB_OK;
}

#define MAX_ATTACH_TOKENS 64

/* Split the line [b, e) into tokens (words.h), the first
 * MAX_ATTACH_TOKENS into t, each at `line`; returns how many there are. */
static int line_tokens(const char *b, const char *e, tok *t, int line)
{
    mpb__word w[MAX_ATTACH_TOKENS];
    int n = mpb__split_words(b, e, w, MAX_ATTACH_TOKENS);
    for (int k = 0; k < n && k < MAX_ATTACH_TOKENS; k++)
        t[k] = (tok){w[k].p, w[k].len, line};
    return n;
}

/* A new object of id t (not yet in s) at `line`, identity pose; *out. */
static int new_object(parser *ps, mpb_scene *s, const tok *t, int line, sobj **out)
{
    int prev = find_n(s, t->p, (size_t)t->len);
    if (prev >= 0)
        return fail(ps, line, "object '%.*s' is defined twice (first on line %d)",
                    shown(t), t->p, s->objects[prev].pub.line);
    if (mpb__grow((void **)&s->objects, &s->cap_objects, s->num_objects + 1,
                  sizeof *s->objects) != MPB_OK)
        return MPB_ENOMEM;
    sobj *o = &s->objects[s->num_objects];
    memset(o, 0, sizeof *o);
    o->id = dup_n(t->p, (size_t)t->len);
    if (!o->id)
        return MPB_ENOMEM;
    s->num_objects++;
    o->pub.line = line;
    mpb_pose_identity(&o->pub.pose);
    sync_pub(o);
    *out = o;
    return MPB_OK;
}

/* Seven tokens, position and quaternion, into *pose. */
static int tokens_pose(parser *ps, const tok *t, int line, const char *what,
                       mpb_pose *pose)
{
    double v[7];
    for (int i = 0; i < 7; i++)
        if (!mpb__number(t[i].p, t[i].len, &v[i]))
            return fail(ps, line, "%s pose needs <x y z> <qx qy qz qw>, found '%.*s'",
                        what, shown(&t[i]), t[i].p);
    for (int i = 0; i < 3; i++)
        if (fabs(v[i]) > MPB_COLLISION_MAX_COORD)
            return fail(ps, line, "%s position: %g is beyond %g m", what, v[i],
                        MPB_COLLISION_MAX_COORD);
    pose->t[0] = v[0];
    pose->t[1] = v[1];
    pose->t[2] = v[2];
    if (mpb_pose_set_quat(pose, v[3], v[4], v[5], v[6]) != 0)
        return fail(ps, line, "%s orientation: the quaternion is zero", what);
    return MPB_OK;
}

static int add_shape(sobj *o, const mpb_geometry *g, const double at[3], int line)
{
    if (mpb__grow((void **)&o->shapes, &o->cap_shapes, o->num_shapes + 1,
                  sizeof *o->shapes) != MPB_OK)
        return MPB_ENOMEM;
    mpb_scene_shape *sh = &o->shapes[o->num_shapes++];
    memset(sh, 0, sizeof *sh);
    sh->geometry = *g;
    mpb_pose_identity(&sh->pose);
    memcpy(sh->pose.t, at, sizeof sh->pose.t);
    sh->line = line;
    return MPB_OK;
}

/* "octree <id> <binary|full> <resolution> <bytes> <pose>" (n tokens t at
 * line), then its data in base64 from ps on. */
static int parse_octree(parser *ps, mpb_scene *s, const tok *t, int n, int line)
{
    if (n >= 3 && tok_is(&t[2], "file"))
        return fail(ps, line, "octree '%.*s' names a file: a scene file's "
                    "octree is read by mpb_scene_open() or mpb_scene_resolve()",
                    shown(&t[1]), t[1].p);
    if (n != 12)
        return fail(ps, line, "octree needs <id> <binary|full> <resolution> <bytes> "
                    "<x y z> <qx qy qz qw>, then its data in base64");
    int binary = tok_is(&t[2], "binary");
    if (!binary && !tok_is(&t[2], "full"))
        return fail(ps, line, "octree data is 'binary' or 'full', found '%.*s'",
                    shown(&t[2]), t[2].p);
    double res;
    long bytes;
    if (!mpb__number(t[3].p, t[3].len, &res))
        return fail(ps, line, "octree resolution: '%.*s' is not a number",
                    shown(&t[3]), t[3].p);
    if (!(res >= MPB_OCTREE_MIN_RESOLUTION && res <= MPB_OCTREE_MAX_RESOLUTION))
        return fail(ps, line, "octree resolution %g is outside %g .. %g m", res,
                    MPB_OCTREE_MIN_RESOLUTION, MPB_OCTREE_MAX_RESOLUTION);
    if (!tok_count(&t[4], &bytes))
        return fail(ps, line, "octree needs its data's size in bytes, found '%.*s'",
                    shown(&t[4]), t[4].p);
    mpb_pose pose;
    int rc = tokens_pose(ps, t + 5, line, "octree", &pose);
    if (rc != MPB_OK)
        return rc;
    size_t chars = ((size_t)bytes + 2) / 3 * 4;
    if (chars > ps->left)
        return fail(ps, line, "octree of %ld bytes: more than the rest of the text "
                    "holds", bytes);
    char *b64 = malloc(chars + 1);
    unsigned char *data = malloc(chars / 4 * 3 + 1);
    if (!b64 || !data) {
        free(b64);
        free(data);
        return MPB_ENOMEM;
    }
    size_t have = 0;
    while (have < chars) {
        tok d;
        if (!next_tok(ps, &d)) {
            rc = fail(ps, ps->last_line, "octree '%.*s': the text ends after %zu of its "
                      "%zu base64 characters", shown(&t[1]), t[1].p, have, chars);
            break;
        }
        if ((size_t)d.len > chars - have) {
            rc = fail(ps, d.line, "octree '%.*s': more base64 than %ld bytes",
                      shown(&t[1]), t[1].p, bytes);
            break;
        }
        memcpy(b64 + have, d.p, (size_t)d.len);
        have += (size_t)d.len;
    }
    size_t got = 0;
    if (rc == MPB_OK) {
        long bad = mpb__base64_decode(b64, chars, data, &got);
        if (bad < 0 || got != (size_t)bytes)
            rc = fail(ps, ps->last_line, "octree '%.*s': bad base64 at character %ld "
                      "of its data", shown(&t[1]), t[1].p, bad < 0 ? -1 - bad : (long)got);
    }
    free(b64);
    mpb_octree *oc = NULL;
    if (rc == MPB_OK) {
        char name[80], why[200];
        snprintf(name, sizeof name, "octree '%.*s'", shown(&t[1]), t[1].p);
        rc = mpb_octree_create_from_stream(data, (size_t)bytes, res, binary, name, &oc, why,
                                           sizeof why);
        if (rc != MPB_OK && rc != MPB_ENOMEM)
            rc = fail(ps, line, "%s", why);
    }
    free(data);
    sobj *o = NULL;
    if (rc == MPB_OK)
        rc = new_object(ps, s, &t[1], line, &o);
    double *boxes = NULL;
    int nb = 0;
    if (rc == MPB_OK)
        rc = mpb_octree_boxes(oc, &boxes, &nb);
    for (int i = 0; rc == MPB_OK && i < nb; i++) {
        const double *b = boxes + 6 * i;
        double c[3] = {(b[0] + b[3]) / 2, (b[1] + b[4]) / 2, (b[2] + b[5]) / 2};
        mpb_geometry g = {.type = MPB_SHAPE_BOX,
                          .dims = {b[3] - b[0], b[4] - b[1], b[5] - b[2], 0}};
        rc = add_shape(o, &g, c, line);
    }
    free(boxes);
    mpb_octree_destroy(oc);
    if (o) {
        o->pub.pose = pose;
        o->pub.kind = MPB_SCENE_OCTREE;
        o->pub.resolution = res;
        sync_pub(o);
    }
    return rc;
}

/* "spheres <id> <radius> <count> <pose>", then count points. */
static int parse_spheres(parser *ps, mpb_scene *s, const tok *t, int n, int line)
{
    if (n != 11)
        return fail(ps, line, "spheres needs <id> <radius> <count> <x y z> "
                    "<qx qy qz qw>, then count points <x y z>");
    double r;
    long count;
    if (!mpb__number(t[2].p, t[2].len, &r) || !(r >= MPB_COLLISION_MIN_SIZE &&
                                                 r <= MPB_COLLISION_MAX_COORD))
        return fail(ps, line, "spheres radius '%.*s' is not a number from %g to %g m",
                    shown(&t[2]), t[2].p, MPB_COLLISION_MIN_SIZE, MPB_COLLISION_MAX_COORD);
    if (!tok_count(&t[3], &count))
        return fail(ps, line, "spheres needs a count, found '%.*s'", shown(&t[3]), t[3].p);
    if (count > MPB_SCENE_MAX_SPHERES)
        return fail(ps, line, "spheres: %ld points, more than %d (give the cloud a "
                    "voxel size instead)", count, MPB_SCENE_MAX_SPHERES);
    if ((size_t)count > ps->left / 6)
        return fail(ps, line, "spheres: %ld points, more than the rest of the text "
                    "holds", count);
    mpb_pose pose;
    int rc = tokens_pose(ps, t + 4, line, "spheres", &pose);
    if (rc != MPB_OK)
        return rc;
    sobj *o;
    if ((rc = new_object(ps, s, &t[1], line, &o)) != MPB_OK)
        return rc;
    o->pub.pose = pose;
    o->pub.kind = MPB_SCENE_SPHERES;
    o->pub.resolution = r;
    mpb_geometry g = {.type = MPB_SHAPE_SPHERE, .dims = {r, 0, 0, 0}};
    for (long i = 0; i < count && rc == MPB_OK; i++) {
        double p[3];
        char expected[64];
        snprintf(expected, sizeof expected, "spheres point %ld needs <x> <y> <z>", i);
        if ((rc = read_nums(ps, p, 3, expected)) != MPB_OK)
            break;
        for (int k = 0; k < 3; k++)
            if (fabs(p[k]) > MPB_COLLISION_MAX_COORD)
                rc = fail(ps, ps->last_line, "spheres point %ld: %g is beyond %g m", i,
                          p[k], MPB_COLLISION_MAX_COORD);
        if (rc == MPB_OK)
            rc = add_shape(o, &g, p, ps->last_line);
    }
    sync_pub(o);
    return rc;
}

/* mpbench's lines after the '.': blanks, '#' comments and attach lines. */
static int parse_extension(parser *ps, mpb_scene *s)
{
    while (*ps->p) {
        int line = ps->line;
        const char *b = ps->p;
        while (*ps->p && *ps->p != '\n')
            advance(ps);
        const char *e = ps->p;
        if (*ps->p == '\n')
            advance(ps);
        tok t[MAX_ATTACH_TOKENS];
        int n = line_tokens(b, e, t, line);
        if (n == 0 || t[0].p[0] == '#')
            continue;
        if (tok_is(&t[0], "octree") || tok_is(&t[0], "spheres")) {
            if (n < 2)
                return fail(ps, line, "%.*s needs an object id", shown(&t[0]), t[0].p);
            int rc = tok_is(&t[0], "octree") ? parse_octree(ps, s, t, n, line)
                                             : parse_spheres(ps, s, t, n, line);
            if (rc != MPB_OK)
                return rc;
            continue;
        }
        if (tok_is(&t[0], "cloud"))
            return fail(ps, line, "cloud '%.*s' names a file: a scene file's "
                        "cloud is read by mpb_scene_open() or mpb_scene_resolve()",
                        n > 1 ? shown(&t[1]) : 0, n > 1 ? t[1].p : "");
        if (!tok_is(&t[0], "attach"))
            return fail(ps, line, "after the '.' end marker only attach, octree, "
                        "spheres and cloud lines and '#' comments may follow, "
                        "found '%.*s'", shown(&t[0]), t[0].p);
        if (n < 3)
            return fail(ps, line, "attach needs <object id> <link> [<touch link> ...]");
        if (n > MAX_ATTACH_TOKENS)
            return fail(ps, line, "attach: more than %d touch links",
                        MAX_ATTACH_TOKENS - 3);
        int i = find_n(s, t[1].p, (size_t)t[1].len);
        if (i < 0)
            return fail(ps, line, "attach: no object '%.*s' in the scene",
                        shown(&t[1]), t[1].p);
        if (s->objects[i].link)
            return fail(ps, line, "attach: object '%.*s' is already attached",
                        shown(&t[1]), t[1].p);
        const char *touch[MAX_ATTACH_TOKENS];
        size_t touch_len[MAX_ATTACH_TOKENS];
        for (int k = 3; k < n; k++) {
            touch[k - 3] = t[k].p;
            touch_len[k - 3] = (size_t)t[k].len;
        }
        int rc = attach(&s->objects[i], t[2].p, (size_t)t[2].len, touch,
                        touch_len, n - 3);
        if (rc != MPB_OK)
            return rc;
        s->objects[i].pub.attach_line = line;
    }
    return MPB_OK;
}

static int parse(parser *ps, mpb_scene *s)
{
    const char *name;
    int namelen;
    const char *q = ps->p;
    while (*q && is_ws(*q))
        q++;
    if (!*q) {                  /* empty text: an empty scene */
        s->name = dup_n("", 0);
        return s->name ? MPB_OK : MPB_ENOMEM;
    }
    rest_of_line(ps, &name, &namelen);
    s->name = dup_n(name, (size_t)namelen);
    if (!s->name)
        return MPB_ENOMEM;
    ps->last_line = 1;
    for (;;) {
        tok t;
        int have = next_tok(ps, &t);
        if (!have)
            return fail(ps, ps->last_line, "missing the '.' line that ends "
                        "the scene");
        if (tok_is(&t, "*")) {
            int rc = parse_object(ps, s, t.line);
            if (rc != MPB_OK)
                return rc;
        } else if (tok_is(&t, ".")) {
            return parse_extension(ps, s);
        } else {
            return fail(ps, t.line, "expected '*' (an object) or '.' (the "
                        "end), found '%.*s'", shown(&t), t.p);
        }
    }
}

int mpb_scene_open_text(const char *text, mpb_scene **out, char *err, size_t errlen)
{
    if (err && errlen)
        err[0] = '\0';
    if (!out)
        return MPB_EINVAL;
    *out = NULL;
    if (!text) {
        if (err && errlen)
            snprintf(err, errlen, "scene: no text");
        return MPB_EINVAL;
    }
    mpb_scene *s = calloc(1, sizeof *s);
    if (!s) {
        if (err && errlen)
            snprintf(err, errlen, "scene: out of memory");
        return MPB_ENOMEM;
    }
    s->variant = MPB_SCENE_NEW;
    size_t len = strlen(text);
    mpb_hash_hex(text, len, s->hash);
    parser ps = { .p = text, .line = 1, .last_line = 1, .left = len,
                  .err = err, .errlen = errlen };
    int rc = parse(&ps, s);
    if (rc != MPB_OK) {
        if (rc == MPB_ENOMEM && err && errlen)
            snprintf(err, errlen, "scene: out of memory");
        mpb_scene_close(s);
        return rc;
    }
    *out = s;
    return MPB_OK;
}

int mpb_scene_open(const char *path, mpb_scene **out, char *err, size_t errlen)
{
    if (err && errlen)
        err[0] = '\0';
    if (!out)
        return MPB_EINVAL;
    *out = NULL;
    if (!path) {
        if (err && errlen)
            snprintf(err, errlen, "scene: no file name");
        return MPB_EINVAL;
    }
    char *buf;
    size_t len;
    int rc = mpb__read_file(path, 0, &buf, &len, err, errlen);
    if (rc != MPB_OK)
        return rc;
    if (memchr(buf, '\0', len)) {
        if (err && errlen)
            snprintf(err, errlen, "%s: not a text file (holds a NUL byte)",
                     path);
        free(buf);
        return MPB_EPARSE;
    }
    char msg[512], dir[4096];
    const char *slash = strrchr(path, '/');
    snprintf(dir, sizeof dir, "%.*s", slash ? (int)(slash - path + 1) : 0, path);
    char *whole;
    rc = mpb_scene_resolve(buf, dir, &whole, msg, sizeof msg);
    free(buf);
    if (rc != MPB_OK) {
        if (err && errlen)
            snprintf(err, errlen, "%s: %s", path, msg);
        return rc;
    }
    rc = mpb_scene_open_text(whole, out, msg, sizeof msg);
    free(whole);
    if (rc != MPB_OK && err && errlen)
        snprintf(err, errlen, "%s: %s", path, msg);
    return rc;
}

const char *mpb_scene_name(const mpb_scene *s)
{
    return s ? s->name : NULL;
}

const char *mpb_scene_hash(const mpb_scene *s)
{
    return s ? s->hash : NULL;
}

mpb_scene_variant mpb_scene_variant_of(const mpb_scene *s)
{
    return s ? s->variant : MPB_SCENE_NEW;
}

int mpb_scene_num_objects(const mpb_scene *s)
{
    return s ? s->num_objects : 0;
}

const mpb_scene_object *mpb_scene_object_at(const mpb_scene *s, int i)
{
    if (!s || i < 0 || i >= s->num_objects)
        return NULL;
    return &s->objects[i].pub;
}

int mpb_scene_find(const mpb_scene *s, const char *id)
{
    if (!s || !id)
        return MPB_ENOTFOUND;
    return find_n(s, id, strlen(id));
}

int mpb_scene_attach(mpb_scene *s, const char *id, const char *link,
                     const mpb_pose *link_T_object,
                     const char *const *touch, int num_touch)
{
    if (!s || !id || !link || !*link || num_touch < 0 || (num_touch > 0 && !touch))
        return MPB_EINVAL;
    if (link_T_object && !mpb_pose_is_rigid(link_T_object))
        return MPB_EINVAL;
    for (int i = 0; i < num_touch; i++)
        if (!touch[i] || !*touch[i])
            return MPB_EINVAL;
    int i = mpb_scene_find(s, id);
    if (i < 0)
        return MPB_ENOTFOUND;
    size_t *lens = num_touch > 0 ? malloc((size_t)num_touch * sizeof *lens) : NULL;
    if (num_touch > 0 && !lens)
        return MPB_ENOMEM;
    for (int k = 0; k < num_touch; k++)
        lens[k] = strlen(touch[k]);
    int rc = attach(&s->objects[i], link, strlen(link), touch, lens, num_touch);
    free(lens);
    if (rc == MPB_OK)
        s->objects[i].pub.attach_line = 0;
    if (rc == MPB_OK && link_T_object)
        s->objects[i].pub.pose = *link_T_object;
    return rc;
}

int mpb_scene_add_statics(const mpb_scene *s, mpb_collision *c)
{
    if (!s || !c)
        return MPB_EINVAL;
    for (int i = 0; i < s->num_objects; i++) {
        const mpb_scene_object *o = &s->objects[i].pub;
        if (o->attached_link)
            continue;
        for (int k = 0; k < o->num_shapes; k++) {
            mpb_pose p;
            mpb_pose_mul(&o->pose, &o->shapes[k].pose, &p);
            int rc = mpb_collision_add_static(c, i, &o->shapes[k].geometry, &p);
            if (rc != MPB_OK)
                return rc;
        }
    }
    return MPB_OK;
}
