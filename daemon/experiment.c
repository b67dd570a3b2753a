/*
 * experiment.c - reading an experiment file (YAML, through libyaml's
 * document API so that every node keeps its line and column for errors).
 */
#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <dirent.h>
#include <sys/stat.h>

#include <yaml.h>

#include "experiment.h"
#include "moveit.h"
#include "mpbench/robot.h"

/* Everything the loader carries, so helpers can report errors in one way. */
typedef struct loader {
    yaml_document_t doc;
    const char *path;
    char       *dir;         /* directory of path, for relative file names */
    char       *err;
    size_t      errlen;
    int         failed;
    yaml_node_t *robot;      /* the robot: mapping, for errors about it */
    mpb_srdf   *srdf;        /* with robot.group: the SRDF, for its group
                                states; else NULL */
    int         group;       /* with robot.group: its index in srdf */
    /* Where an error with no node of this file goes while a MoveIt
     * problem file is read: that file and a place in it (moveit.h). */
    const char  *place_path;
    mpbd_mark    place;
    mpb_robot   *model;      /* the urdf robot, for link names; or NULL */
} loader;

static int fail_at(loader *L, const yaml_node_t *n, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/*
 * s as text that is safe to print on one line: control bytes, DEL and
 * bytes that are not UTF-8 become \xNN (a file's binary bytes are never
 * echoed to a terminal); well-formed UTF-8 is kept.
 */
static void escape_text(const char *s, char *out, size_t n)
{
    size_t o = 0;
    const unsigned char *p = (const unsigned char *)s;
    while (*p && o + 5 < n) {
        int len = *p < 0x80 ? 1 : (*p & 0xE0) == 0xC0 && *p >= 0xC2 ? 2
                : (*p & 0xF0) == 0xE0 ? 3 : (*p & 0xF8) == 0xF0 && *p <= 0xF4
                ? 4 : 0;
        for (int k = 1; k < len; k++)
            if ((p[k] & 0xC0) != 0x80)
                len = 0;
        if (len == 1 && *p >= 0x20 && *p != 0x7f) {
            out[o++] = (char)*p++;
        } else if (len > 1 && o + (size_t)len < n) {
            memcpy(out + o, p, (size_t)len);
            o += (size_t)len;
            p += len;
        } else {
            o += (size_t)snprintf(out + o, n - o, "\\x%02x", *p++);
        }
    }
    out[o] = '\0';
}

static int fail_at(loader *L, const yaml_node_t *n, const char *fmt, ...)
{
    char raw[512], what[2048];
    va_list ap;
    if (L->failed)
        return -1;
    va_start(ap, fmt);
    vsnprintf(raw, sizeof raw, fmt, ap);
    va_end(ap);
    escape_text(raw, what, sizeof what);
    if (n != NULL)
        snprintf(L->err, L->errlen, "%s:%lu:%lu: %s", L->path,
                 (unsigned long)n->start_mark.line + 1,
                 (unsigned long)n->start_mark.column + 1, what);
    else if (L->place_path != NULL)
        snprintf(L->err, L->errlen, "%s:%d:%d: %s", L->place_path,
                 L->place.line, L->place.column, what);
    else
        snprintf(L->err, L->errlen, "%s: %s", L->path, what);
    L->failed = 1;
    return -1;
}

static yaml_node_t *node(loader *L, int id)
{
    return yaml_document_get_node(&L->doc, id);
}

static const char *scalar(const yaml_node_t *n)
{
    return n && n->type == YAML_SCALAR_NODE ? (const char *)n->data.scalar.value
                                            : NULL;
}

/* The value under key in mapping m, or NULL. */
static yaml_node_t *get(loader *L, yaml_node_t *m, const char *key)
{
    if (m == NULL || m->type != YAML_MAPPING_NODE)
        return NULL;
    for (yaml_node_pair_t *p = m->data.mapping.pairs.start;
         p < m->data.mapping.pairs.top; p++) {
        const char *k = scalar(node(L, p->key));
        if (k && strcmp(k, key) == 0)
            return node(L, p->value);
    }
    return NULL;
}

/* Reject keys a mapping does not know: a typo must not pass silently. */
static int only_keys(loader *L, yaml_node_t *m, const char *const *known)
{
    for (yaml_node_pair_t *p = m->data.mapping.pairs.start;
         p < m->data.mapping.pairs.top; p++) {
        yaml_node_t *kn = node(L, p->key);
        const char *k = scalar(kn);
        int ok = 0;
        for (int i = 0; k && known[i]; i++)
            ok |= strcmp(k, known[i]) == 0;
        if (!ok)
            return fail_at(L, kn, "unknown key '%s'", k ? k : "?");
    }
    return 0;
}

/* The key node of pair i of mapping m, for sorting keys by name. */
typedef struct keyref {
    const char  *name;
    yaml_node_t *node;
} keyref;

static int keyref_cmp(const void *a, const void *b)
{
    const keyref *x = a, *y = b;
    int c = strcmp(x->name, y->name);
    if (c != 0)
        return c;
    return x->node < y->node ? -1 : x->node > y->node;
}

/* The first key (in file order) that repeats an earlier one in m, or
 * NULL; sorted, so that a mapping of many keys costs n log n. */
static yaml_node_t *repeated_key(loader *L, yaml_node_t *m, keyref *keys)
{
    size_t n = 0;
    yaml_node_t *first = NULL;
    for (yaml_node_pair_t *p = m->data.mapping.pairs.start;
         p < m->data.mapping.pairs.top; p++) {
        yaml_node_t *k = node(L, p->key);
        if (scalar(k) != NULL)
            keys[n++] = (keyref){scalar(k), k};
    }
    qsort(keys, n, sizeof *keys, keyref_cmp);
    for (size_t i = 1; i < n; i++)
        if (strcmp(keys[i - 1].name, keys[i].name) == 0 &&
            (first == NULL || keys[i].node->start_mark.index <
                                  first->start_mark.index))
            first = keys[i].node;
    return first;
}

/*
 * libyaml keeps every pair of a mapping, and get() would take the first:
 * refuse a key written twice anywhere, params included, as a typo.
 */
static int no_repeated_keys(loader *L)
{
    size_t most = 0;
    keyref *keys;
    for (yaml_node_t *m = L->doc.nodes.start; m < L->doc.nodes.top; m++)
        if (m->type == YAML_MAPPING_NODE) {
            size_t n = (size_t)(m->data.mapping.pairs.top -
                                m->data.mapping.pairs.start);
            most = n > most ? n : most;
        }
    if ((keys = malloc((most + 1) * sizeof *keys)) == NULL)
        return fail_at(L, NULL, "out of memory");
    for (yaml_node_t *m = L->doc.nodes.start; m < L->doc.nodes.top; m++) {
        yaml_node_t *k;
        if (m->type == YAML_MAPPING_NODE && (k = repeated_key(L, m, keys))) {
            free(keys);
            return fail_at(L, k, "key '%s' appears twice", scalar(k));
        }
    }
    free(keys);
    return 0;
}

static yaml_node_t *need(loader *L, yaml_node_t *m, const char *key,
                         yaml_node_type_t type, const char *what)
{
    yaml_node_t *n = get(L, m, key);
    if (n == NULL) {
        fail_at(L, m, "missing '%s' (%s)", key, what);
        return NULL;
    }
    if (n->type != type) {
        fail_at(L, n, "'%s' must be %s", key, what);
        return NULL;
    }
    return n;
}

static char *dup_str(loader *L, const yaml_node_t *n, const char *s)
{
    char *d = strdup(s);
    if (d == NULL)
        fail_at(L, n, "out of memory");
    return d;
}

static char *need_string(loader *L, yaml_node_t *m, const char *key)
{
    yaml_node_t *n = need(L, m, key, YAML_SCALAR_NODE, "a string");
    if (n == NULL)
        return NULL;
    if (scalar(n)[0] == '\0') {
        fail_at(L, n, "'%s' must not be empty", key);
        return NULL;
    }
    return dup_str(L, n, scalar(n));
}

/*
 * Whether s is a number as people write them in decimal: a sign, digits
 * with at most one point, an exponent. strtod() alone would also take hex
 * ("0x10"), "inf", "nan" and leading blanks.
 */
static int is_decimal(const char *s, int whole)
{
    int digits = 0;
    if (*s == '-' || *s == '+')
        s++;
    for (; isdigit((unsigned char)*s); s++)
        digits++;
    if (!whole && *s == '.')
        for (s++; isdigit((unsigned char)*s); s++)
            digits++;
    if (digits == 0)
        return 0;
    if (!whole && (*s == 'e' || *s == 'E')) {
        s++;
        if (*s == '-' || *s == '+')
            s++;
        if (!isdigit((unsigned char)*s))
            return 0;
        while (isdigit((unsigned char)*s))
            s++;
    }
    return *s == '\0';
}

int mpbd_parse_decimal(const char *s, double *out)
{
    /* Not errno: strtod() sets ERANGE for 1e-310 too, which is a number. */
    *out = is_decimal(s, 0) ? strtod(s, NULL) : NAN;
    return isfinite(*out);
}

static int parse_double(loader *L, yaml_node_t *n, const char *what, double *out)
{
    const char *s = scalar(n);
    if (s == NULL)
        return fail_at(L, n, "%s must be a number", what);
    if (!mpbd_parse_decimal(s, out))
        return fail_at(L, n, "%s must be a number, not '%s'", what, s);
    return 0;
}

/* A whole number in lo..hi: 0 if *out was set, else -1 with the error. */
static int parse_int_in(loader *L, yaml_node_t *n, const char *what,
                        long lo, long hi, int *out)
{
    const char *s = scalar(n);
    long v;
    if (s != NULL) {
        errno = 0;
        v = strtol(s, NULL, 10);
        if (is_decimal(s, 1) && errno == 0 && v >= lo && v <= hi) {
            *out = (int)v;
            return 0;
        }
    }
    if (lo == 1)
        return fail_at(L, n, "%s must be a positive integer%s%s%s", what,
                       s ? ", not '" : "", s ? s : "", s ? "'" : "");
    return fail_at(L, n, "%s must be a whole number from %ld to %ld%s%s%s",
                   what, lo, hi, s ? ", not '" : "", s ? s : "", s ? "'" : "");
}

/* Read as an integer, not through a double: 2^53 + 1 stays itself. */
static int parse_seed(loader *L, yaml_node_t *n, uint64_t *out)
{
    const char *s = scalar(n);
    long long v;
    if (s != NULL && is_decimal(s, 1)) {
        errno = 0;
        v = strtoll(s, NULL, 10);
        if (errno == 0) {
            *out = (uint64_t)v;
            return 0;
        }
    }
    return fail_at(L, n, "seed must be an integer in digits (no point or "
                   "exponent) from %lld to %lld%s%s%s",
                   LLONG_MIN, LLONG_MAX, s ? ", not '" : "", s ? s : "",
                   s ? "'" : "");
}

static int parse_positive_int(loader *L, yaml_node_t *n, const char *what,
                              int *out)
{
    return parse_int_in(L, n, what, 1, 1000000000, out);
}

/* A list of exactly n numbers. */
static double *parse_vector(loader *L, yaml_node_t *n, const char *what, int len)
{
    double *v;
    int count;
    if (n == NULL || n->type != YAML_SEQUENCE_NODE)
        return fail_at(L, n, "%s must be a list of %d numbers", what, len), NULL;
    count = (int)(n->data.sequence.items.top - n->data.sequence.items.start);
    if (count != len)
        return fail_at(L, n, "%s has %d values, the robot has %d joints", what,
                       count, len), NULL;
    v = calloc((size_t)len, sizeof *v);
    if (v == NULL)
        return fail_at(L, n, "out of memory"), NULL;
    for (int i = 0; i < len; i++)
        if (parse_double(L, node(L, n->data.sequence.items.start[i]), what,
                         &v[i]) != 0) {
            free(v);
            return NULL;
        }
    return v;
}

static size_t count_items(const yaml_node_t *n)
{
    return n && n->type == YAML_SEQUENCE_NODE
               ? (size_t)(n->data.sequence.items.top - n->data.sequence.items.start)
               : 0;
}

/* Read a file whole; NULL with errno set on failure. */
static char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    char *buf = NULL;
    size_t cap = 0, n = 0;
    struct stat st;
    if (f == NULL)
        return NULL;
    /* fopen() opens a directory; reading it would say "Input/output error". */
    if (fstat(fileno(f), &st) == 0 && S_ISDIR(st.st_mode)) {
        fclose(f);
        errno = EISDIR;
        return NULL;
    }
    for (;;) {
        if (n + 4096 + 1 > cap) {
            char *nb = realloc(buf, cap = cap * 2 + 8192);
            if (nb == NULL) {
                free(buf);
                fclose(f);
                errno = ENOMEM;
                return NULL;
            }
            buf = nb;
        }
        size_t got = fread(buf + n, 1, cap - n - 1, f);
        n += got;
        if (got == 0)
            break;
    }
    if (ferror(f)) {
        free(buf);
        fclose(f);
        errno = EIO;
        return NULL;
    }
    fclose(f);
    buf[n] = '\0';
    if (len)
        *len = n;
    return buf;
}

/*
 * A robot or scene: inline `text:` or a `file:` relative to the experiment
 * file, plus its `format:`.
 */
static int load_model(loader *L, yaml_node_t *m, const char *what,
                      char **format, char **text, char **file_path)
{
    /* Each its own: a robot has no name or queries, a scene no joints. */
    static const char *const robot_keys[] = {"format", "file", "text",
                                             "joints", "group", "srdf",
                                             "joint_values", NULL};
    static const char *const scene_keys[] = {"format", "file", "text", "name",
                                             "queries", "joints", NULL};
    const char *const *keys = strcmp(what, "robot") == 0 ? robot_keys
                                                         : scene_keys;
    yaml_node_t *file, *inline_text;
    if (m == NULL || m->type != YAML_MAPPING_NODE)
        return fail_at(L, m, "%s must be a mapping with format and file or text",
                       what);
    if (only_keys(L, m, keys) != 0)
        return -1;
    if ((*format = need_string(L, m, "format")) == NULL)
        return -1;
    file = get(L, m, "file");
    inline_text = get(L, m, "text");
    if ((file == NULL) == (inline_text == NULL))
        return fail_at(L, m, "%s needs exactly one of 'file' and 'text'", what);
    if (inline_text) {
        if (scalar(inline_text) == NULL)
            return fail_at(L, inline_text, "%s text must be a string", what);
        *text = dup_str(L, inline_text, scalar(inline_text));
        return *text ? 0 : -1;
    }
    if (scalar(file) == NULL || scalar(file)[0] == '\0')
        return fail_at(L, file, "%s file must be a path", what);
    char path[4096];
    const char *f = scalar(file);
    snprintf(path, sizeof path, "%s%s", f[0] == '/' ? "" : L->dir, f);
    if ((*file_path = strdup(path)) == NULL)
        return fail_at(L, file, "out of memory");
    size_t len;
    if ((*text = slurp(path, &len)) == NULL)
        return fail_at(L, file, "cannot read %s file %s: %s", what, path,
                       strerror(errno));
    /* The parsers stop at a NUL: the rest would vanish without a word. */
    if (strlen(*text) != len)
        return fail_at(L, file, "%s: not a text file (a NUL byte at offset "
                       "%zu)", path, strlen(*text));
    return 0;
}

/*
 * A fault of the robot's, its URDF's ("urdf: ...") or its SRDF's ("srdf
 * line 3: ..."), as the library words it: at the robot's key that names
 * the file it is in, and naming that file.
 */
static int robot_fault(loader *L, const mpbd_experiment *e, const char *why)
{
    int in_srdf = strncmp(why, "srdf", 4) == 0;
    const char *file = in_srdf ? e->srdf_file : e->robot_file;
    /* "srdf line 3: ..." in the SRDF file is its "line 3: ...". */
    const char *what = in_srdf && file != NULL ? why + 5 : why;
    yaml_node_t *at = get(L, L->robot, in_srdf ? "srdf" : "file");
    if (at == NULL)
        at = get(L, L->robot, "text");
    if (file != NULL)
        return fail_at(L, at ? at : L->robot, "robot: %s: %s", file, what);
    return fail_at(L, at ? at : L->robot, "robot: %s", why);
}

/*
 * The robot's SRDF, `srdf:` a file relative to the experiment file: its
 * text goes into the robot text, on the line after the URDF (world.h),
 * for the world of every scene and every planner. It is read here too,
 * against the URDF: with `group:` for the group and its states, and for
 * the warning about pairs it names that the URDF lacks.
 */
static int load_srdf(loader *L, mpbd_experiment *e, char **robot)
{
    yaml_node_t *n = get(L, L->robot, "srdf");
    if (n == NULL)
        return 0;
    const char *f = scalar(n);
    if (f == NULL || f[0] == '\0')
        return fail_at(L, n, "srdf must be the path of a file");
    const char *format = scalar(get(L, L->robot, "format"));
    if (format == NULL || strcmp(format, "urdf") != 0)
        return fail_at(L, n, "srdf goes with a urdf robot only");
    char path[4096];
    snprintf(path, sizeof path, "%s%s", f[0] == '/' ? "" : L->dir, f);
    if ((e->srdf_file = strdup(path)) == NULL)
        return fail_at(L, n, "out of memory");
    size_t len;
    char *srdf = slurp(path, &len);
    if (srdf == NULL)
        return fail_at(L, n, "cannot read srdf file %s: %s", path,
                       strerror(errno));
    if (strlen(srdf) != len) {
        fail_at(L, n, "%s: not a text file (a NUL byte at offset %zu)", path,
                strlen(srdf));
        free(srdf);
        return -1;
    }
    /* Read against the URDF here, for the group and for the warning about
     * pairs naming links the URDF lacks (skipped, as MoveIt does). */
    char why[512];
    mpb_srdf *sem = NULL;
    if (mpb_srdf_load(*robot, srdf, &sem, why, sizeof why) != MPB_OK) {
        free(srdf);
        return robot_fault(L, e, why);
    }
    if (mpb_srdf_skipped_pairs(sem) != NULL) {
        char line[6144];
        snprintf(line, sizeof line, "robot: %s: %s", path,
                 mpb_srdf_skipped_pairs(sem));
        if ((e->srdf_warning = strdup(line)) == NULL) {
            mpb_srdf_free(sem);
            free(srdf);
            return fail_at(L, n, "out of memory");
        }
    }
    if (get(L, L->robot, "group") != NULL)
        L->srdf = sem;
    else
        mpb_srdf_free(sem);
    size_t rl = strlen(*robot);
    int nl = rl > 0 && (*robot)[rl - 1] != '\n';
    char *both = malloc(rl + (size_t)nl + len + 1);
    if (both == NULL) {
        free(srdf);
        return fail_at(L, n, "out of memory");
    }
    memcpy(both, *robot, rl);
    if (nl)
        both[rl] = '\n';
    memcpy(both + rl + nl, srdf, len + 1);
    free(srdf);
    free(*robot);
    *robot = both;
    return 0;
}

static int load_settings(loader *L, mpbd_experiment *e, yaml_node_t *root)
{
    static const char *const keys[] = {"name", "runs", "time_limit", "seed",
                                       "retries", "runs_per_host",
                                       "queue_at_planner", "memory_limit",
                                       "verification", NULL};
    yaml_node_t *m = need(L, root, "experiment", YAML_MAPPING_NODE,
                          "a mapping of name, runs, time_limit, seed");
    yaml_node_t *n;
    if (m == NULL || only_keys(L, m, keys) != 0)
        return -1;
    if ((e->name = need_string(L, m, "name")) == NULL)
        return -1;
    e->runs = 1;
    if ((n = get(L, m, "runs")) && parse_positive_int(L, n, "runs", &e->runs))
        return -1;
    if ((n = need(L, m, "time_limit", YAML_SCALAR_NODE, "seconds")) == NULL ||
        parse_double(L, n, "time_limit", &e->time_limit) != 0)
        return -1;
    if (e->time_limit <= 0)
        return fail_at(L, n, "time_limit must be positive");
    if ((n = get(L, m, "seed")) != NULL && parse_seed(L, n, &e->seed) != 0)
        return -1;
    e->runs_per_host = 1;
    if ((n = get(L, m, "runs_per_host")) &&
        parse_positive_int(L, n, "runs_per_host", &e->runs_per_host))
        return -1;
    /* 0 is allowed for these, unlike the other counts. */
    if ((n = get(L, m, "retries")) &&
        parse_int_in(L, n, "retries", 0, 1000000000, &e->retries))
        return -1;
    if ((n = get(L, m, "queue_at_planner")) &&
        parse_int_in(L, n, "queue_at_planner", 0, MPBD_QUEUE_AT_PLANNER_MAX,
                     &e->queue_at_planner))
        return -1;
    /* MB over what the planner process held when the run began
     * (docs/experiment-format.md); the planner enforces it. */
    if ((n = get(L, m, "memory_limit")) != NULL) {
        if (parse_double(L, n, "memory_limit", &e->memory_limit) != 0)
            return -1;
        if (!(e->memory_limit > 0 && e->memory_limit <= 1048576))
            return fail_at(L, n, "memory_limit must be MB above 0 and at "
                           "most 1048576 (1 TB), not '%s'", scalar(n));
    }
    /* How segments are checked (mpb_verification, docs/verification.md). */
    if ((n = get(L, m, "verification")) != NULL) {
        const char *v = scalar(n);
        if (v && strcmp(v, "sampled") == 0)
            e->verification = MPB_VERIFY_SAMPLED;
        else if (!v || strcmp(v, "certified") != 0)
            return fail_at(L, n, "verification must be certified or sampled, "
                           "not '%s'", v ? v : "");
    }
    return 0;
}

/* The robot: formats its joints, and gives each scene its world. */
static int open_world(loader *L, mpbd_experiment *e, mpbd_scene *sc,
                      yaml_node_t *where)
{
    char why[512], dir[4096] = "";
    /* The robot file's folder: where its meshes are looked for last. */
    if (e->robot_file) {
        snprintf(dir, sizeof dir, "%s", e->robot_file);
        char *slash = strrchr(dir, '/');
        if (slash)
            slash[1] = '\0';
        else
            snprintf(dir, sizeof dir, ".");
    }
    int rc = mpb_world_open_group_in(sc->robot_format, sc->robot,
                                     dir[0] ? dir : NULL, sc->scene_format,
                                     sc->scene, (const char *const *)e->group,
                                     e->num_group, &sc->world, why, sizeof why);
    if (rc == MPB_OK)
        mpb_world_set_verification(sc->world, (mpb_verification)e->verification);
    const char *goes_with = mpb_world_scene_format(sc->robot_format);
    if (rc == MPB_EUNSUPPORTED &&
        (goes_with == NULL || strcmp(goes_with, sc->scene_format) != 0)) {
        /* A format: point at the robot's, or at this scene's if the
         * robot's is known but the scene's does not go with it. (Other
         * faults are unsupported too, a mesh URI's scheme: not these.) */
        yaml_node_t *at = goes_with == NULL ? get(L, L->robot, "format")
                                            : get(L, where, "format");
        const char *what = strncmp(why, "world: ", 7) == 0 ? why + 7 : why;
        return fail_at(L, at ? at : where, "%s", what);
    }
    if (rc != MPB_OK) {
        /* Name the file the fault is in, when it came from one, and point
         * at the key that names it: a fault of the robot's (its URDF or
         * SRDF) is at the robot's key, whichever scene it was loaded with. */
        if (strncmp(why, "scene", 5) != 0)
            return robot_fault(L, e, why);
        if (sc->scene_file != NULL)
            return fail_at(L, where, "scene '%s': %s: %s", sc->name,
                           sc->scene_file, why);
        return fail_at(L, where, "scene '%s': %s", sc->name, why);
    }
    int nj = mpb_world_num_joints(sc->world);
    if (e->joint_names == NULL) {
        e->num_joints = nj;
        e->joint_names = calloc((size_t)nj, sizeof *e->joint_names);
        e->wraps = calloc((size_t)nj + 1, 1);
        if (e->joint_names == NULL || e->wraps == NULL)
            return fail_at(L, where, "out of memory");
        for (int j = 0; j < nj; j++) {
            if ((e->joint_names[j] = strdup(mpb_world_joint_name(sc->world, j)))
                == NULL)
                return fail_at(L, where, "out of memory");
            e->wraps[j] = (unsigned char)mpb_world_joint_is_continuous(sc->world, j);
        }
    } else if (nj != e->num_joints) {
        return fail_at(L, where, "scene '%s': robot has %d joints, earlier "
                       "scenes have %d", sc->name, nj, e->num_joints);
    }
    return 0;
}

/*
 * A start or a joint goal: a list of one number per joint, or, when the
 * group is a group of the SRDF, the name of one of its group states
 * ("start: ready"), whose values it takes. n is the node, or NULL when
 * absent (the fault then at parent).
 */
static double *parse_state(loader *L, const mpbd_experiment *e, yaml_node_t *n,
                           yaml_node_t *parent, const char *what)
{
    if (n == NULL || n->type != YAML_SCALAR_NODE || L->srdf == NULL)
        return parse_vector(L, n ? n : parent, what, e->num_joints);
    char why[512];
    double *v = calloc((size_t)e->num_joints + 1, sizeof *v);
    if (v == NULL)
        return fail_at(L, n, "out of memory"), NULL;
    if (mpb_srdf_state_values(L->srdf, L->group, scalar(n), v, why,
                              sizeof why) != MPB_OK) {
        free(v);
        return fail_at(L, n, "%s: %s", what, why), NULL;
    }
    return v;
}

/* A start or goal must be a state the robot can be in: within its joint
 * limits and free of collision. Otherwise no planner can succeed. */
static int check_state(loader *L, const mpbd_experiment *e, int scene,
                       const double *q, const char *what, yaml_node_t *where)
{
    mpb_world *w = e->scenes[scene].world;
    for (int j = 0; j < e->num_joints; j++) {
        double lo, hi;
        mpb_world_joint_limits(w, j, &lo, &hi);
        if (!mpb_world_joint_is_continuous(w, j) && (q[j] < lo || q[j] > hi))
            return fail_at(L, where, "%s: joint %s = %.10g is outside its "
                           "limits [%.10g, %.10g]", what, e->joint_names[j],
                           q[j], lo, hi);
    }
    char contact[200];
    if (mpb_world_contact(w, q, contact, sizeof contact) != 0)
        return fail_at(L, where, "%s is in collision in scene '%s'%s%s", what,
                       e->scenes[scene].name, contact[0] ? ": " : "", contact);
    return 0;
}

/*
 * Three numbers: a list of 3, or, where one_for_all, a single number for
 * all three ("position_tolerance: 0.01").
 */
static int parse_triple(loader *L, yaml_node_t *m, const char *key,
                        int one_for_all, double out[3])
{
    yaml_node_t *n = get(L, m, key);
    if (n == NULL)
        return fail_at(L, m, "goal: missing '%s'", key);
    if (one_for_all && n->type == YAML_SCALAR_NODE) {
        if (parse_double(L, n, key, &out[0]) != 0)
            return -1;
        out[1] = out[2] = out[0];
        return 0;
    }
    if (n->type != YAML_SEQUENCE_NODE || count_items(n) != 3)
        return fail_at(L, n, "%s must be a list of 3 numbers%s", key,
                       one_for_all ? " (or one number for all three)" : "");
    for (int i = 0; i < 3; i++)
        if (parse_double(L, node(L, n->data.sequence.items.start[i]), key,
                         &out[i]) != 0)
            return -1;
    return 0;
}

static int parse_tolerance(loader *L, yaml_node_t *m, const char *key,
                           double out[3])
{
    if (parse_triple(L, m, key, 1, out) != 0)
        return -1;
    for (int i = 0; i < 3; i++)
        if (out[i] < 0)
            return fail_at(L, get(L, m, key), "%s must not be negative (%g)",
                           key, out[i]);
    return 0;
}

/*
 * A pose-region goal: `goal: {link, position, position_tolerance, rpy,
 * rpy_tolerance}`. Without rpy the orientation is free. The link must be
 * one of the robot's, which the world checks.
 */
static int load_region_goal(loader *L, const mpbd_experiment *e, int scene,
                            mpbd_query *q, yaml_node_t *m)
{
    static const char *const keys[] = {"link", "position",
                                       "position_tolerance", "rpy",
                                       "rpy_tolerance", NULL};
    if (only_keys(L, m, keys) != 0 ||
        (q->goal_link = need_string(L, m, "link")) == NULL ||
        parse_triple(L, m, "position", 0, q->position) != 0 ||
        parse_tolerance(L, m, "position_tolerance", q->position_tolerance) != 0)
        return -1;
    q->goal_kind = MPB_GOAL_POSE_REGION;
    if (get(L, m, "rpy") == NULL) {
        if (get(L, m, "rpy_tolerance") != NULL)
            return fail_at(L, get(L, m, "rpy_tolerance"),
                           "rpy_tolerance without rpy");
        for (int i = 0; i < 3; i++)
            q->rpy_tolerance[i] = M_PI;
    } else if (parse_triple(L, m, "rpy", 0, q->rpy) != 0 ||
               parse_tolerance(L, m, "rpy_tolerance", q->rpy_tolerance) != 0) {
        return -1;
    }
    /* Asking the world whether the start is inside checks the link and the
     * numbers, and whether this world can check regions at all. */
    char why[256];
    mpb_goal g = mpbd_query_goal(q);
    int in = mpb_world_goal_contains(e->scenes[scene].world, &g, q->start, why,
                                     sizeof why);
    if (in == MPB_EUNSUPPORTED)
        return fail_at(L, m, "%s (a region goal needs a urdf robot)", why);
    if (in < 0)
        return fail_at(L, get(L, m, "link"), "%s", why);
    return 0;
}

/* `goal:` is a configuration (a list) or a region for a link (a mapping). */
static int load_goal(loader *L, mpbd_experiment *e, int scene, mpbd_query *q,
                     yaml_node_t *query)
{
    yaml_node_t *n = get(L, query, "goal");
    if (n != NULL && n->type == YAML_MAPPING_NODE)
        return load_region_goal(L, e, scene, q, n);
    q->goal_kind = MPB_GOAL_JOINTS;
    if ((q->goal = parse_state(L, e, n, query, "goal")) == NULL)
        return -1;
    return check_state(L, e, scene, q->goal, "goal", n);
}

/* ---- joints held outside the group ---------------------------------- */

/* Give q a value for every held joint known so far: the robot's, or the
 * world's default for a joint only other queries name. */
static int held_fill(mpbd_experiment *e, mpbd_query *q)
{
    if (q->num_held_set == e->num_held)
        return 0;
    double *v = realloc(q->held, ((size_t)e->num_held + 1) * sizeof *v);
    if (v == NULL)
        return -1;
    for (int i = q->num_held_set; i < e->num_held; i++)
        v[i] = e->held_default[i];
    q->held = v;
    q->num_held_set = e->num_held;
    return 0;
}

/*
 * The index of the held joint `name` in e->held_names, added (held at the
 * world's default, 0 moved into its limits) if new; -1 with one line at
 * `at` for a joint that cannot be held.
 */
static int held_index(loader *L, mpbd_experiment *e, mpb_world *w,
                      const char *name, yaml_node_t *at)
{
    for (int i = 0; i < e->num_held; i++)
        if (strcmp(e->held_names[i], name) == 0)
            return i;
    double lo, hi;
    int rc = mpb_world_held(w, name, NULL, &lo, &hi);
    if (rc == MPB_EUNSUPPORTED)
        return fail_at(L, at, "joint '%s': a %s robot holds no joints "
                       "outside its group", name, e->scenes[0].robot_format);
    if (rc == MPB_ENOTFOUND)
        return fail_at(L, at, "joint '%s' is not a joint of the robot", name);
    for (int j = 0; rc != MPB_OK && j < e->num_joints; j++)
        if (strcmp(e->joint_names[j], name) == 0)
            return fail_at(L, at, "joint '%s' is in the planning group: its "
                           "value belongs in the start, not held", name);
    if (rc != MPB_OK)
        return fail_at(L, at, "joint '%s' cannot hold a value (a fixed, "
                       "floating or planar joint)", name);
    char **names = realloc(e->held_names,
                           ((size_t)e->num_held + 1) * sizeof *names);
    if (names != NULL)
        e->held_names = names;
    double *dflt = realloc(e->held_default,
                           ((size_t)e->num_held + 1) * sizeof *dflt);
    if (dflt != NULL)
        e->held_default = dflt;
    if (names == NULL || dflt == NULL ||
        (names[e->num_held] = strdup(name)) == NULL)
        return fail_at(L, at, "out of memory");
    dflt[e->num_held] = 0.0 < lo ? lo : 0.0 > hi ? hi : 0.0;
    return e->num_held++;
}

/*
 * Hold joint `name` at v in the world w, into *out (the query's or the
 * robot's value). With clamp, a value outside the joint's limits is moved
 * to the nearer one and counted in *clamped; without, it is refused at
 * `val`. `key` is where the name is written, for an unknown joint.
 */
static int hold_one(loader *L, mpbd_experiment *e, mpb_world *w,
                    const char *name, double v, yaml_node_t *key,
                    yaml_node_t *val, int clamp, int *clamped, int *index)
{
    char why[256];
    double lo, hi;
    int i = held_index(L, e, w, name, key);
    if (i < 0)
        return -1;
    if (clamp && mpb_world_held(w, name, NULL, &lo, &hi) == MPB_OK &&
        (v < lo || v > hi)) {
        v = v < lo ? lo : hi;
        (*clamped)++;
    }
    const char *names[1] = {name};
    if (mpb_world_hold(w, names, &v, 1, why, sizeof why) != MPB_OK)
        return fail_at(L, val, "%s", why);
    *index = i;
    return 0;
}

/* `joint_values: {name: value, ...}`: the robot's held joints, or a
 * query's own (into q). */
static int load_joint_values(loader *L, mpbd_experiment *e, mpb_world *w,
                             yaml_node_t *m, mpbd_query *q)
{
    if (m == NULL)
        return 0;
    if (m->type != YAML_MAPPING_NODE)
        return fail_at(L, m, "joint_values must be a mapping of joint: value");
    for (yaml_node_pair_t *p = m->data.mapping.pairs.start;
         p < m->data.mapping.pairs.top; p++) {
        yaml_node_t *k = node(L, p->key), *vn = node(L, p->value);
        double v;
        int i;
        if (scalar(k) == NULL || scalar(k)[0] == '\0')
            return fail_at(L, k, "a joint must be a name");
        if (parse_double(L, vn, "a joint value", &v) != 0 ||
            hold_one(L, e, w, scalar(k), v, k, vn, 0, NULL, &i) != 0)
            return -1;
        if (q == NULL) {
            e->held_default[i] = v;
        } else {
            if (held_fill(e, q) != 0)
                return fail_at(L, m, "out of memory");
            q->held[i] = v;
        }
    }
    return 0;
}

int mpbd_query_hold(const mpbd_experiment *e, const mpbd_query *q)
{
    return mpb_world_hold(e->scenes[q->scene].world,
                          (const char *const *)e->held_names, q->held,
                          q->num_held_set < e->num_held ? q->num_held_set
                                                        : e->num_held,
                          NULL, 0);
}

static int load_queries(loader *L, mpbd_experiment *e, int scene,
                        yaml_node_t *scene_map)
{
    static const char *const keys[] = {"name", "start", "goal", "tolerance",
                                       "joint_values", NULL};
    yaml_node_t *list = get(L, scene_map, "queries");
    if (list == NULL || list->type != YAML_SEQUENCE_NODE ||
        list->data.sequence.items.top == list->data.sequence.items.start)
        return fail_at(L, list ? list : scene_map,
                       "scene '%s' needs a non-empty list 'queries'",
                       e->scenes[scene].name);
    for (yaml_node_item_t *it = list->data.sequence.items.start;
         it < list->data.sequence.items.top; it++) {
        yaml_node_t *m = node(L, *it), *n;
        mpbd_query *q = &e->queries[e->num_queries];
        if (m->type != YAML_MAPPING_NODE)
            return fail_at(L, m, "a query must be a mapping of name, start, goal");
        if (only_keys(L, m, keys) != 0)
            return -1;
        e->num_queries++;
        q->scene = scene;
        q->tolerance = 1e-3;
        if ((q->name = need_string(L, m, "name")) == NULL)
            return -1;
        for (mpbd_query *o = e->queries; o < q; o++)
            if (o->scene == scene && strcmp(o->name, q->name) == 0)
                return fail_at(L, m, "query '%s' appears twice in scene '%s'",
                               q->name, e->scenes[scene].name);
        if (held_fill(e, q) != 0)
            return fail_at(L, m, "out of memory");
        if (load_joint_values(L, e, e->scenes[scene].world,
                              get(L, m, "joint_values"), q) != 0 ||
            held_fill(e, q) != 0)
            return -1;
        if (mpbd_query_hold(e, q) != MPB_OK)
            return fail_at(L, m, "query '%s': its held joint values do not "
                           "fit the robot", q->name);
        if ((q->start = parse_state(L, e, get(L, m, "start"), m, "start")) == NULL)
            return -1;
        if (check_state(L, e, scene, q->start, "start", get(L, m, "start")) != 0 ||
            load_goal(L, e, scene, q, m) != 0)
            return -1;
        if ((n = get(L, m, "tolerance")) != NULL &&
            (parse_double(L, n, "tolerance", &q->tolerance) != 0 ||
             (q->tolerance <= 0 && fail_at(L, n, "tolerance must be positive"))))
            return -1;
    }
    return 0;
}

/*
 * `group:` names a group of the SRDF: its active joints, base first, are
 * the planning group. mpbench plans a serial chain; a group that is not
 * one is refused, saying why.
 */
static int load_srdf_group(loader *L, mpbd_experiment *e, yaml_node_t *n)
{
    const char *name = scalar(n);
    char why[512];
    if (get(L, L->robot, "joints") != NULL)
        return fail_at(L, n, "give the planning group as joints or as group, "
                       "not both");
    if (name == NULL || *name == '\0')
        return fail_at(L, n, "group must be the name of a group of the "
                       "robot's srdf");
    if (L->srdf == NULL)
        return fail_at(L, n, "group '%s' names a group of the robot's SRDF: "
                       "give it as srdf", name);
    int g = mpb_srdf_group_index(L->srdf, name);
    if (g < 0) {
        size_t used = 0;
        why[0] = '\0';
        for (int i = 0; i < mpb_srdf_num_groups(L->srdf) && used < sizeof why;
             i++)
            used += (size_t)snprintf(why + used, sizeof why - used, "%s%s",
                                     i ? ", " : "",
                                     mpb_srdf_get_group(L->srdf, i)->name);
        return fail_at(L, n, "%s has no group '%s' (%s%s)", e->srdf_file, name,
                       used ? "its groups: " : "it has none", why);
    }
    if (mpb_srdf_group_check(L->srdf, g, why, sizeof why) != MPB_OK)
        return fail_at(L, n, "%s", why);
    const mpb_srdf_group *G = mpb_srdf_get_group(L->srdf, g);
    if ((e->group_name = strdup(name)) == NULL ||
        (e->group = calloc((size_t)G->num_active + 1, sizeof *e->group)) == NULL)
        return fail_at(L, n, "out of memory");
    for (int j = 0; j < G->num_active; j++)
        if ((e->group[e->num_group++] = strdup(G->active[j])) == NULL)
            return fail_at(L, n, "out of memory");
    L->group = g;
    return 0;
}

/* The robot's planning group, as a list of joint names (optional for
 * planar robots, whose joints are all in the group), or as a group of its
 * SRDF. */
static int load_group(loader *L, mpbd_experiment *e, yaml_node_t *n)
{
    if (get(L, L->robot, "group") != NULL)
        return load_srdf_group(L, e, get(L, L->robot, "group"));
    if (n == NULL)
        return 0;
    if (n->type != YAML_SEQUENCE_NODE || count_items(n) == 0)
        return fail_at(L, n, "joints must be a list of joint names");
    e->group = calloc(count_items(n) + 1, sizeof *e->group);
    if (e->group == NULL)
        return fail_at(L, n, "out of memory");
    for (yaml_node_item_t *it = n->data.sequence.items.start;
         it < n->data.sequence.items.top; it++) {
        const char *s = scalar(node(L, *it));
        if (s == NULL || *s == '\0')
            return fail_at(L, node(L, *it), "a joint must be a name");
        if ((e->group[e->num_group++] = strdup(s)) == NULL)
            return fail_at(L, n, "out of memory");
    }
    return 0;
}

/* After the first scene's world opens: the robot's held joint values,
 * which need a world to check them against. */
static int first_world(loader *L, mpbd_experiment *e, mpbd_scene *sc)
{
    if (e->num_scenes != 1)
        return 0;
    return load_joint_values(L, e, sc->world, get(L, L->robot, "joint_values"),
                             NULL);
}

/* ---- MoveIt problems (docs/moveit-problems.md) ----------------------- */

/* Errors with no node here go to this place of a MoveIt file. */
static void at_place(loader *L, const char *path, mpbd_mark m)
{
    L->place_path = path;
    L->place = m;
}

/* The robot as robot.h reads it, for link names; NULL for planar. */
static mpb_robot *robot_model(loader *L, const mpbd_experiment *e,
                              const char *robot_format, const char *robot)
{
    if (L->model == NULL && strcmp(robot_format, "urdf") == 0 &&
        e->num_group > 0)
        mpb_robot_load_urdf_joints(robot, (const char *const *)e->group,
                                   e->num_group, &L->model, NULL, 0);
    return L->model;
}

/* Add name to the list "a, b, c" in names (cap bytes), once, as many as
 * fit, then "...". */
static void note_name(char *names, size_t cap, const char *name)
{
    char esc[128];
    size_t used = strlen(names);
    mpb_escape(name, esc, sizeof esc);
    for (const char *p = names; *p;) {
        size_t k = strcspn(p, ",");
        if (k == strlen(esc) && strncmp(p, esc, k) == 0)
            return;
        p += k + (p[k] == ',' ? 2 : 0);
    }
    if (used >= 3 && strcmp(names + used - 3, "...") == 0)
        return;
    if (used + strlen(esc) + 8 < cap)
        snprintf(names + used, cap - used, "%s%s", used ? ", " : "", esc);
    else
        snprintf(names + used, cap - used, ", ...");
}

/* Is name the id of an object of the moveit-scene text (its "* id"
 * lines)? */
static int scene_has_object(const char *text, const char *name)
{
    size_t n = strlen(name);
    for (const char *p = text; p; p = strchr(p, '\n'), p = p ? p + 1 : NULL)
        if (p[0] == '*' && p[1] == ' ' && strncmp(p + 2, name, n) == 0 &&
            (p[2 + n] == '\n' || p[2 + n] == '\0'))
            return 1;
    return 0;
}

/* A scene's allowed pair naming a link the robot lacks: skipped, counted
 * for the warning mpbd_experiment_scene_acm_note() words. */
static int skip_scene_pair(loader *L, mpbd_experiment *e,
                           const char *scene_path, const mpbd_moveit_scene *ms,
                           int i, int *counted)
{
    const char *name = ms->pairs[i];
    e->acm_skipped++;
    if (!*counted) {
        e->acm_skipped_scenes++;
        *counted = 1;
    }
    if (e->acm_skipped_at == NULL) {
        char at[4200];
        snprintf(at, sizeof at, "%s:%d:%d", scene_path, ms->pair_at[i].line,
                 ms->pair_at[i].column);
        if ((e->acm_skipped_at = strdup(at)) == NULL)
            return fail_at(L, NULL, "out of memory");
    }
    note_name(e->acm_skipped_names, sizeof e->acm_skipped_names, name);
    return 0;
}

/*
 * The robot text with a scene's allowed pairs added as SRDF
 * <disable_collisions reason="Scene"/> elements: inside the robot's SRDF
 * (before its closing tag), or as an SRDF of their own when it has none.
 * A pair naming a link the robot lacks is skipped, as MoveIt does (its
 * matrix takes any names; MotionBenchMaker's Fetch and UR5 scenes name
 * links of their own robot models), and counted; a name that is an
 * object of the scene is refused (MoveIt would allow that contact, which
 * mpbench does not read).
 */
static char *robot_with_pairs(loader *L, mpbd_experiment *e,
                              const char *robot_format, const char *robot,
                              const char *scene_path, const char *scene_text,
                              const mpbd_moveit_scene *ms)
{
    if (ms->num_pairs == 0)
        return strdup(robot);
    mpb_robot *model = robot_model(L, e, robot_format, robot);
    unsigned char *keep = calloc((size_t)ms->num_pairs + 1, 1);
    if (keep == NULL)
        return NULL;
    int counted = 0;
    for (int k = 0; k < ms->num_pairs; k++) {
        keep[k] = 1;
        for (int i = 2 * k; i < 2 * k + 2 && keep[k]; i++) {
            if (model != NULL && mpb_robot_link_index(model, ms->pairs[i]) >= 0)
                continue;
            char esc[256];
            at_place(L, scene_path, ms->pair_at[i]);
            if (model == NULL || scene_has_object(scene_text, ms->pairs[i])) {
                fail_at(L, NULL, "allowed_collision_matrix: '%s' is %s",
                        mpb_escape(ms->pairs[i], esc, sizeof esc),
                        model == NULL ? "not a link of the robot"
                                      : "an object of the scene; allowed "
                                        "contacts with objects are not read");
                free(keep);
                return NULL;
            }
            if (skip_scene_pair(L, e, scene_path, ms, i, &counted) != 0) {
                free(keep);
                return NULL;
            }
            keep[k] = 0;
        }
    }
    L->place_path = NULL;
    size_t extra = 64;
    for (int i = 0; i < 2 * ms->num_pairs; i++)
        extra += strlen(ms->pairs[i]) + 40;
    size_t len = strlen(robot);
    char *out = malloc(len + extra + 64);
    if (out == NULL) {
        free(keep);
        return NULL;
    }
    /* The SRDF's closing tag is the text's last "</robot" when the
     * experiment has an SRDF. */
    const char *close = NULL;
    if (e->srdf_file != NULL)
        for (const char *p = strstr(robot, "</robot"); p;
             p = strstr(p + 1, "</robot"))
            close = p;
    size_t head = close ? (size_t)(close - robot) : len;
    memcpy(out, robot, head);
    char *w = out + head;
    if (close == NULL) {
        if (head > 0 && out[head - 1] != '\n')
            *w++ = '\n';
        w += sprintf(w, "<robot name=\"scene\">\n");
    }
    for (int i = 0; i < ms->num_pairs; i++)
        if (keep[i])
            w += sprintf(w, "<disable_collisions link1=\"%s\" link2=\"%s\" "
                         "reason=\"Scene\"/>\n", ms->pairs[2 * i],
                         ms->pairs[2 * i + 1]);
    free(keep);
    if (close == NULL)
        w += sprintf(w, "</robot>\n");
    strcpy(w, robot + head);
    return out;
}

/*
 * Joint values of a MoveIt robot state: group joints into q (where set),
 * the others held by the query (clamped into their limits with clamp).
 */
static int moveit_state(loader *L, mpbd_experiment *e, mpbd_query *q,
                        const char *path, const mpbd_moveit_joints *j,
                        double *group_q, unsigned char *set, int clamp)
{
    mpb_world *w = e->scenes[q->scene].world;
    for (int i = 0; i < j->n; i++) {
        int g = -1, index;
        for (int k = 0; k < e->num_joints && g < 0; k++)
            if (strcmp(e->joint_names[k], j->names[i]) == 0)
                g = k;
        at_place(L, path, j->at[i]);
        if (g >= 0) {
            group_q[g] = j->values[i];
            set[g] = 1;
            continue;
        }
        /* A joint the URDF fixes (this Panda's fingers) has no value to
         * hold: leniently skipped, as a model without that variable
         * would. */
        int known = mpb_world_held(w, j->names[i], NULL, NULL, NULL);
        if (clamp && known == MPB_EINVAL) {
            e->held_ignored++;
            continue;
        }
        /* A joint the URDF lacks (MotionBenchMaker's Fetch states give
         * its wheels and bellows, which VAMP's Fetch leaves out): skipped
         * with clamp too, counted and named. MoveIt refuses such a state
         * for a model without the joint; without clamp, so does mpbench. */
        if (clamp && known == MPB_ENOTFOUND) {
            note_name(e->held_unknown_names, sizeof e->held_unknown_names,
                      j->names[i]);
            e->held_unknown++;
            continue;
        }
        if (hold_one(L, e, w, j->names[i], j->values[i], NULL, NULL, clamp,
                     &e->held_clamped, &index) != 0 || held_fill(e, q) != 0)
            return -1;
        double v;
        mpb_world_held(w, j->names[i], &v, NULL, NULL);
        q->held[index] = v;
    }
    return 0;
}

/* One request of a MoveIt scene: a query. */
static int moveit_query(loader *L, mpbd_experiment *e, int scene,
                        const mpbd_moveit_scene *ms, const char *scene_path,
                        const char *req_path,
                        const char *name, int clamp, double tolerance)
{
    mpbd_moveit_request r;
    mpbd_query *q = &e->queries[e->num_queries];
    if (mpbd_moveit_request_read(req_path, &r, L->err, L->errlen) != MPB_OK) {
        L->failed = 1;
        return -1;
    }
    int rc = -1, nj = e->num_joints;
    unsigned char *set = calloc((size_t)nj + 1, 1);
    e->num_queries++;
    q->scene = scene;
    q->tolerance = tolerance;
    q->planning_time = r.allowed_planning_time;
    q->name = strdup(name);
    q->start = calloc((size_t)nj + 1, sizeof *q->start);
    if (set == NULL || q->name == NULL || q->start == NULL ||
        held_fill(e, q) != 0 ||
        (r.group_name && (q->moveit_group = strdup(r.group_name)) == NULL)) {
        fail_at(L, NULL, "out of memory");
        goto done;
    }
    /* A request for another group than the one planned would be solved
     * for the wrong joints; with joints: listed there is no name to
     * compare, and the joint names are checked below. */
    if (e->group_name && r.group_name &&
        strcmp(e->group_name, r.group_name) != 0) {
        at_place(L, req_path, r.group_at);
        fail_at(L, NULL, "group_name '%s' is not the experiment's group '%s'",
                r.group_name, e->group_name);
        goto done;
    }
    /* The scene's robot state, then the request's start on top of it, as
     * MoveIt reads a start state: a difference from the scene's. */
    if (moveit_state(L, e, q, scene_path, &ms->state, q->start, set,
                     clamp) != 0 ||
        moveit_state(L, e, q, req_path, &r.start, q->start, set, clamp) != 0)
        goto done;
    for (int j = 0; j < nj; j++)
        if (!set[j]) {
            at_place(L, req_path, r.start_at);
            fail_at(L, NULL, "start_state: no value for joint '%s' of the "
                    "group (nor in the scene's robot_state)",
                    e->joint_names[j]);
            goto done;
        }
    if (mpbd_query_hold(e, q) != MPB_OK) {
        fail_at(L, NULL, "query '%s': its held joint values do not fit the "
                "robot", name);
        goto done;
    }
    /* A start just outside a limit: with clamp moved onto it, as MoveIt's
     * FixStartStateBounds adapter does within its default 0.05. */
    for (int j = 0; clamp && j < nj; j++) {
        mpb_world *sw = e->scenes[scene].world;
        double lo, hi, v = q->start[j];
        mpb_world_joint_limits(sw, j, &lo, &hi);
        if (mpb_world_joint_is_continuous(sw, j) || (v >= lo && v <= hi) ||
            v < lo - MPBD_START_BOUNDS_ERROR || v > hi + MPBD_START_BOUNDS_ERROR)
            continue;
        q->start[j] = v < lo ? lo : hi;
        e->start_clamped++;
    }
    at_place(L, req_path, r.start_at);
    if (check_state(L, e, scene, q->start, "start", NULL) != 0)
        goto done;
    q->goal_kind = r.goal_kind;
    if (r.goal_kind == MPB_GOAL_JOINTS) {
        double tol = INFINITY;
        q->goal = calloc((size_t)nj + 1, sizeof *q->goal);
        if (q->goal == NULL) {
            fail_at(L, NULL, "out of memory");
            goto done;
        }
        memset(set, 0, (size_t)nj);
        for (int i = 0; i < r.goal.n; i++) {
            int g = -1;
            for (int k = 0; k < nj && g < 0; k++)
                if (strcmp(e->joint_names[k], r.goal.names[i]) == 0)
                    g = k;
            at_place(L, req_path, r.goal.at[i]);
            if (g < 0) {
                double v;
                char esc[256];
                mpb_escape(r.goal.names[i], esc, sizeof esc);
                if (mpb_world_held(e->scenes[scene].world, r.goal.names[i],
                                   &v, NULL, NULL) == MPB_ENOTFOUND)
                    fail_at(L, NULL, "joint '%s' is not a joint of the robot",
                            esc);
                else
                    fail_at(L, NULL, "joint '%s' is outside the planning "
                            "group: a goal constrains the group's joints",
                            esc);
                goto done;
            }
            q->goal[g] = r.goal.values[i];
            set[g] = 1;
            double a = r.tolerance_above[i], b = r.tolerance_below[i];
            if (!isnan(a) && a < tol)
                tol = a;
            if (!isnan(b) && b < tol)
                tol = b;
        }
        for (int j = 0; j < nj; j++)
            if (!set[j]) {
                at_place(L, req_path, r.goal_at);
                fail_at(L, NULL, "goal_constraints: no joint constraint on "
                        "joint '%s' of the group", e->joint_names[j]);
                goto done;
            }
        /* One tolerance per query: the tightest the file gives, so that
         * every goal mpbench accepts is one MoveIt accepts too. */
        if (isfinite(tol))
            q->tolerance = tol > 0 ? tol : 1e-9;
        /* A goal just outside a joint's limits whose tolerance reaches
         * inside them (VAMP's Fetch makes wrist_roll_joint revolute at
         * +-3.14159; its problems ask for -3.1415926): MoveIt samples the
         * constraint within the limits, so with clamp the value moves
         * onto the limit and the tolerance shrinks by as much, keeping
         * the region within the file's. */
        mpb_world *gw = e->scenes[scene].world;
        double moved = 0;
        for (int j = 0; clamp && j < nj; j++) {
            double lo, hi, v = q->goal[j];
            mpb_world_joint_limits(gw, j, &lo, &hi);
            if (mpb_world_joint_is_continuous(gw, j) || (v >= lo && v <= hi))
                continue;
            double d = v < lo ? lo - v : v - hi;
            if (d >= q->tolerance)
                continue;       /* no part of the region is inside */
            q->goal[j] = v < lo ? lo : hi;
            moved = d > moved ? d : moved;
            e->goal_clamped++;
        }
        q->tolerance -= moved;
        at_place(L, req_path, r.goal_at);
        if (check_state(L, e, scene, q->goal, "goal", NULL) != 0)
            goto done;
    } else {
        char why[256];
        q->goal_link = r.link;
        r.link = NULL;
        memcpy(q->position, r.position, sizeof q->position);
        memcpy(q->position_tolerance, r.position_tolerance,
               sizeof q->position_tolerance);
        memcpy(q->rpy, r.rpy, sizeof q->rpy);
        memcpy(q->rpy_tolerance, r.rpy_tolerance, sizeof q->rpy_tolerance);
        mpb_goal g = mpbd_query_goal(q);
        int in = mpb_world_goal_contains(e->scenes[scene].world, &g, q->start,
                                         why, sizeof why);
        at_place(L, req_path, r.link_at);
        if (in < 0) {
            fail_at(L, NULL, "%s", why);
            goto done;
        }
    }
    rc = 0;
done:
    L->place_path = NULL;
    free(set);
    mpbd_moveit_request_clear(&r);
    return rc;
}

/*
 * One MoveIt scene file with its requests: a scene of the experiment and
 * one query per request. The scene's robot text carries its allowed
 * pairs, so every world of its runs has the same matrix.
 */
static int moveit_scene(loader *L, mpbd_experiment *e, yaml_node_t *entry,
                        const char *robot_format, const char *robot,
                        const char *name, const char *scene_path,
                        char *const *req_paths, char *const *qnames, int nreq,
                        int clamp, double tolerance)
{
    mpbd_moveit_scene ms;
    mpbd_scene *sc = &e->scenes[e->num_scenes];
    if (mpbd_moveit_scene_read(scene_path, name, &ms, L->err, L->errlen)
        != MPB_OK) {
        L->failed = 1;
        return -1;
    }
    e->num_scenes++;
    int rc = -1;
    for (mpbd_scene *o = e->scenes; o < sc; o++)
        if (strcmp(o->name, name) == 0) {
            fail_at(L, entry, "scene '%s' appears twice", name);
            goto done;
        }
    sc->name = strdup(name);
    sc->scene_format = strdup("moveit-scene");
    sc->scene_file = strdup(scene_path);
    sc->robot_format = strdup(robot_format);
    sc->scene = ms.text;
    ms.text = NULL;
    if (!sc->name || !sc->scene_format || !sc->scene_file ||
        !sc->robot_format) {
        fail_at(L, entry, "out of memory");
        goto done;
    }
    if ((sc->robot = robot_with_pairs(L, e, robot_format, robot, scene_path,
                                      sc->scene, &ms)) == NULL) {
        if (!L->failed)
            fail_at(L, entry, "out of memory");
        goto done;
    }
    mpb_hash_hex(sc->robot, strlen(sc->robot), sc->robot_hash);
    mpb_hash_hex(sc->scene, strlen(sc->scene), sc->scene_hash);
    if (open_world(L, e, sc, entry) != 0 || first_world(L, e, sc) != 0)
        goto done;
    for (int i = 0; i < nreq; i++) {
        if (moveit_query(L, e, e->num_scenes - 1, &ms, scene_path,
                         req_paths[i], qnames[i], clamp, tolerance) != 0)
            goto done;
    }
    rc = 0;
done:
    L->place_path = NULL;
    mpbd_moveit_scene_clear(&ms);
    return rc;
}

/* A problem set: the NNNN of every sceneNNNN.yaml with a requestNNNN.yaml
 * beside it, sorted (as numbers: same-width digits sort as text). */
typedef struct problem_set {
    char  **ids;
    int     n;
} problem_set;

static int id_cmp(const void *a, const void *b)
{
    const char *x = *(char *const *)a, *y = *(char *const *)b;
    size_t lx = strlen(x), ly = strlen(y);
    return lx != ly ? (lx < ly ? -1 : 1) : strcmp(x, y);
}

static void problem_set_free(problem_set *ps)
{
    for (int i = 0; i < ps->n; i++)
        free(ps->ids[i]);
    free(ps->ids);
    memset(ps, 0, sizeof *ps);
}

static int problem_set_read(loader *L, yaml_node_t *at, const char *dir,
                            problem_set *ps)
{
    DIR *d = opendir(dir);
    struct dirent *ent;
    int cap = 0;
    memset(ps, 0, sizeof *ps);
    if (d == NULL)
        return fail_at(L, at, "cannot read problem set %s: %s", dir,
                       strerror(errno));
    while ((ent = readdir(d)) != NULL) {
        const char *nm = ent->d_name;
        size_t len = strlen(nm), digits = 0;
        if (len < 11 || strncmp(nm, "scene", 5) != 0 ||
            strcmp(nm + len - 5, ".yaml") != 0)
            continue;
        for (size_t k = 5; k < len - 5; k++)
            digits += isdigit((unsigned char)nm[k]) != 0;
        if (digits != len - 10 || digits > 9)
            continue;
        char req[4096];
        struct stat st;
        snprintf(req, sizeof req, "%s/request%.*s.yaml", dir, (int)digits,
                 nm + 5);
        if (stat(req, &st) != 0)
            continue;
        if (ps->n == cap) {
            char **ids = realloc(ps->ids, (size_t)(cap = cap * 2 + 64) *
                                              sizeof *ids);
            if (ids == NULL)
                break;
            ps->ids = ids;
        }
        if ((ps->ids[ps->n] = strndup(nm + 5, digits)) == NULL)
            break;
        ps->n++;
    }
    int broke = ent != NULL;
    closedir(d);
    if (broke)
        return fail_at(L, at, "out of memory");
    if (ps->n == 0)
        return fail_at(L, at, "problem set %s holds no sceneNNNN.yaml with "
                       "a requestNNNN.yaml beside it", dir);
    qsort(ps->ids, (size_t)ps->n, sizeof *ps->ids, id_cmp);
    return 0;
}

/* A path from the experiment file's folder. */
static void path_from(const loader *L, const char *f, char *out, size_t n)
{
    snprintf(out, n, "%s%s", f[0] == '/' ? "" : L->dir, f);
}

/* The keys of a MoveIt entry: `problems: DIR` (with first, count) or
 * `moveit_scene: FILE` with `requests`. */
static const char *const moveit_keys[] = {"problems", "first", "count",
                                          "moveit_scene", "requests", "name",
                                          "tolerance", "clamp_joint_values",
                                          NULL};

static int is_moveit_entry(loader *L, yaml_node_t *m)
{
    return get(L, m, "problems") != NULL || get(L, m, "moveit_scene") != NULL;
}

/* How many scenes and queries a MoveIt entry makes (0 on error). */
static int moveit_entry_size(loader *L, yaml_node_t *m, int *scenes,
                             int *queries)
{
    if (get(L, m, "moveit_scene") != NULL) {
        *scenes = 1;
        *queries = (int)count_items(get(L, m, "requests"));
        return 0;
    }
    char dir[4096];
    problem_set ps;
    const char *p = scalar(get(L, m, "problems"));
    if (p == NULL || p[0] == '\0')
        return fail_at(L, get(L, m, "problems"), "problems must be the path "
                       "of a folder");
    path_from(L, p, dir, sizeof dir);
    if (problem_set_read(L, get(L, m, "problems"), dir, &ps) != 0)
        return -1;
    *scenes = *queries = ps.n;
    problem_set_free(&ps);
    return 0;
}

static int load_moveit_entry(loader *L, mpbd_experiment *e, yaml_node_t *m,
                             const char *robot_format, const char *robot)
{
    yaml_node_t *n;
    int first = 1, num = INT_MAX, clamp = 0, rc = -1;
    double tolerance = 1e-3;
    if (only_keys(L, m, moveit_keys) != 0)
        return -1;
    if ((get(L, m, "problems") != NULL) == (get(L, m, "moveit_scene") != NULL))
        return fail_at(L, m, "a MoveIt entry names 'problems' (a folder) or "
                       "'moveit_scene' (a file), not both");
    if ((n = get(L, m, "tolerance")) != NULL &&
        (parse_double(L, n, "tolerance", &tolerance) != 0 ||
         (tolerance <= 0 && fail_at(L, n, "tolerance must be positive"))))
        return -1;
    if ((n = get(L, m, "clamp_joint_values")) != NULL) {
        const char *b = scalar(n);
        if (b == NULL || (strcmp(b, "true") != 0 && strcmp(b, "false") != 0))
            return fail_at(L, n, "clamp_joint_values must be true or false");
        clamp = strcmp(b, "true") == 0;
    }
    if (get(L, m, "moveit_scene") != NULL) {
        yaml_node_t *reqs = get(L, m, "requests"), *sn = get(L, m,
                                                             "moveit_scene");
        char *name = need_string(L, m, "name");
        if (name == NULL)
            return -1;
        if (get(L, m, "first") || get(L, m, "count")) {
            free(name);
            return fail_at(L, get(L, m, "first") ? get(L, m, "first")
                                                 : get(L, m, "count"),
                           "first and count slice a problem set");
        }
        int k = (int)count_items(reqs);
        char **paths = calloc((size_t)k + 1, sizeof *paths);
        char **qnames = calloc((size_t)k + 1, sizeof *qnames);
        char spath[4096];
        if (scalar(sn) == NULL || scalar(sn)[0] == '\0' || k == 0) {
            fail_at(L, k == 0 ? (reqs ? reqs : m) : sn, k == 0 ?
                    "requests must be a non-empty list of MoveIt request "
                    "files" : "moveit_scene must be the path of a file");
            goto one_done;
        }
        path_from(L, scalar(sn), spath, sizeof spath);
        for (int i = 0; paths && qnames && i < k; i++) {
            yaml_node_t *it = node(L, reqs->data.sequence.items.start[i]);
            const char *f = scalar(it);
            char p[4096];
            if (f == NULL || f[0] == '\0') {
                fail_at(L, it, "a request must be the path of a file");
                goto one_done;
            }
            path_from(L, f, p, sizeof p);
            const char *base = strrchr(f, '/') ? strrchr(f, '/') + 1 : f;
            size_t bl = strlen(base);
            if (bl > 5 && strcmp(base + bl - 5, ".yaml") == 0)
                bl -= 5;
            paths[i] = strdup(p);
            qnames[i] = strndup(base, bl);
            for (int o = 0; o < i && qnames[i]; o++)
                if (strcmp(qnames[o], qnames[i]) == 0) {
                    fail_at(L, it, "query '%s' appears twice in scene '%s'",
                            qnames[i], name);
                    goto one_done;
                }
        }
        rc = moveit_scene(L, e, m, robot_format, robot, name, spath, paths,
                          qnames, k, clamp, tolerance);
one_done:
        for (int i = 0; i < k; i++) {
            free(paths ? paths[i] : NULL);
            free(qnames ? qnames[i] : NULL);
        }
        free(paths);
        free(qnames);
        free(name);
        return rc;
    }

    char dir[4096];
    problem_set ps;
    if (get(L, m, "name") != NULL)
        return fail_at(L, get(L, m, "name"), "a problem set's scenes are "
                       "named after its folder and files");
    if ((n = get(L, m, "first")) &&
        parse_int_in(L, n, "first", 1, INT_MAX, &first) != 0)
        return -1;
    if ((n = get(L, m, "count")) && parse_positive_int(L, n, "count", &num))
        return -1;
    path_from(L, scalar(get(L, m, "problems")), dir, sizeof dir);
    if (problem_set_read(L, get(L, m, "problems"), dir, &ps) != 0)
        return -1;
    if (first > ps.n) {
        fail_at(L, get(L, m, "first"), "first: %d is past the %d problems "
                "of %s", first, ps.n, dir);
        problem_set_free(&ps);
        return -1;
    }
    /* The set's name: its folder's ("box_panda"). */
    char set[256];
    size_t dl = strlen(dir);
    while (dl > 1 && dir[dl - 1] == '/')
        dl--;
    const char *b = dir + dl;
    while (b > dir && b[-1] != '/')
        b--;
    snprintf(set, sizeof set, "%.*s", (int)(dir + dl - b), b);
    rc = 0;
    for (int i = first - 1; rc == 0 && i < ps.n && i - (first - 1) < num;
         i++) {
        char name[512], spath[4200], rpath[4200];
        char *rp = rpath, *qn = name;
        snprintf(name, sizeof name, "%s/%s", set, ps.ids[i]);
        snprintf(spath, sizeof spath, "%s/scene%s.yaml", dir, ps.ids[i]);
        snprintf(rpath, sizeof rpath, "%s/request%s.yaml", dir, ps.ids[i]);
        rc = moveit_scene(L, e, m, robot_format, robot, name, spath, &rp, &qn,
                          1, clamp, tolerance);
    }
    problem_set_free(&ps);
    return rc;
}

static int load_scenes(loader *L, mpbd_experiment *e, yaml_node_t *root)
{
    char *robot_format = NULL, *robot = NULL;
    yaml_node_t *list = need(L, root, "scenes", YAML_SEQUENCE_NODE,
                             "a list of scenes");
    int rc = -1;
    size_t total_queries = 0;

    if (list == NULL)
        return -1;
    if ((L->robot = need(L, root, "robot", YAML_MAPPING_NODE,
                         "a mapping of format and file or text")) == NULL ||
        load_model(L, L->robot, "robot", &robot_format, &robot,
                   &e->robot_file) != 0 ||
        load_srdf(L, e, &robot) != 0 ||
        load_group(L, e, get(L, L->robot, "joints")) != 0)
        goto done;
    e->num_scenes = 0;
    size_t total_scenes = 0;
    for (yaml_node_item_t *it = list->data.sequence.items.start;
         it < list->data.sequence.items.top; it++) {
        yaml_node_t *m = node(L, *it);
        int ns = 1, nq = (int)count_items(get(L, m, "queries"));
        if (is_moveit_entry(L, m) && moveit_entry_size(L, m, &ns, &nq) != 0)
            goto done;
        total_scenes += (size_t)ns;
        total_queries += (size_t)nq;
    }
    e->scenes = calloc(total_scenes + 1, sizeof *e->scenes);
    e->queries = calloc(total_queries + 1, sizeof *e->queries);
    if (e->scenes == NULL || e->queries == NULL) {
        fail_at(L, list, "out of memory");
        goto done;
    }
    if (count_items(list) == 0) {
        fail_at(L, list, "'scenes' must not be empty");
        goto done;
    }
    for (yaml_node_item_t *it = list->data.sequence.items.start;
         it < list->data.sequence.items.top; it++) {
        yaml_node_t *m = node(L, *it);
        mpbd_scene *sc = &e->scenes[e->num_scenes];
        if (m->type != YAML_MAPPING_NODE) {
            fail_at(L, m, "a scene must be a mapping of name, format, file "
                          "or text, queries");
            goto done;
        }
        if (is_moveit_entry(L, m)) {
            if (load_moveit_entry(L, e, m, robot_format, robot) != 0)
                goto done;
            continue;
        }
        e->num_scenes++;
        if (get(L, m, "joints") != NULL) {
            fail_at(L, get(L, m, "joints"), "joints belong to the robot, not "
                    "to a scene");
            goto done;
        }
        if ((sc->name = need_string(L, m, "name")) == NULL ||
            load_model(L, m, "scene", &sc->scene_format, &sc->scene,
                       &sc->scene_file) != 0)
            goto done;
        for (mpbd_scene *o = e->scenes; o < sc; o++)
            if (strcmp(o->name, sc->name) == 0) {
                fail_at(L, m, "scene '%s' appears twice", sc->name);
                goto done;
            }
        if ((sc->robot_format = strdup(robot_format)) == NULL ||
            (sc->robot = strdup(robot)) == NULL) {
            fail_at(L, m, "out of memory");
            goto done;
        }
        mpb_hash_hex(sc->robot, strlen(sc->robot), sc->robot_hash);
        mpb_hash_hex(sc->scene, strlen(sc->scene), sc->scene_hash);
        if (open_world(L, e, sc, m) != 0 || first_world(L, e, sc) != 0 ||
            load_queries(L, e, e->num_scenes - 1, m) != 0)
            goto done;
    }
    /* Every query holds every joint some query names. */
    for (int i = 0; i < e->num_queries; i++)
        if (held_fill(e, &e->queries[i]) != 0) {
            fail_at(L, list, "out of memory");
            goto done;
        }
    rc = 0;
done:
    mpb_robot_free(L->model);
    L->model = NULL;
    free(robot_format);
    free(robot);
    return rc;
}

/* "key=value;key=value" for the database; keys in file order. */
static char *params_text(const mpb_param_t *p, int n)
{
    size_t cap = 1;
    for (int i = 0; i < n; i++)
        cap += strlen(p[i].key) + strlen(p[i].value) + 2;
    char *s = malloc(cap), *w = s;
    if (s == NULL)
        return NULL;
    *w = '\0';
    for (int i = 0; i < n; i++)
        w += snprintf(w, cap - (size_t)(w - s), "%s%s=%s", i ? ";" : "",
                      p[i].key, p[i].value);
    return s;
}

static int load_params(loader *L, mpbd_config *c, yaml_node_t *m)
{
    if (m == NULL)
        return 0;
    if (m->type != YAML_MAPPING_NODE)
        return fail_at(L, m, "params must be a mapping of name: value");
    size_t n = (size_t)(m->data.mapping.pairs.top - m->data.mapping.pairs.start);
    c->params = calloc(n + 1, sizeof *c->params);
    if (c->params == NULL)
        return fail_at(L, m, "out of memory");
    for (yaml_node_pair_t *p = m->data.mapping.pairs.start;
         p < m->data.mapping.pairs.top; p++) {
        const char *k = scalar(node(L, p->key)), *v = scalar(node(L, p->value));
        if (k == NULL || v == NULL)
            return fail_at(L, node(L, p->key), "a parameter must be name: value");
        c->params[c->num_params].key = strdup(k);
        c->params[c->num_params].value = strdup(v);
        c->num_params++;
        if (!c->params[c->num_params - 1].key || !c->params[c->num_params - 1].value)
            return fail_at(L, m, "out of memory");
    }
    return 0;
}

/* Add one configuration's runs to *total; the cap is checked as they add
 * up, in 64 bits, so that the product cannot wrap. */
static int add_runs(loader *L, const mpbd_experiment *e, int runs,
                    yaml_node_t *where, int64_t *total)
{
    *total += (int64_t)runs * e->num_queries;
    if (*total <= MPBD_RUNS_TOTAL_MAX)
        return 0;
    return fail_at(L, where, "runs: %d makes more than %d runs in all (runs "
                   "x planner configurations x queries)", runs,
                   MPBD_RUNS_TOTAL_MAX);
}

/* A planner announces itself as name@host:pid, an id of at most
 * MPB_PLANNER_ID_MAX characters from [A-Za-z0-9_.:@-] (docs/protocol.md):
 * a family outside that can never be offered, and its runs would wait
 * for ever. */
static int check_family(loader *L, const yaml_node_t *n, const char *family)
{
    size_t len = strlen(family);
    if (len > MPB_PLANNER_ID_MAX - 4)
        return fail_at(L, n, "planner '%.40s...' is longer than %d characters: "
                       "no planner id (name@host:pid, at most %d) can hold it",
                       family, MPB_PLANNER_ID_MAX - 4, MPB_PLANNER_ID_MAX);
    for (size_t i = 0; i < len; i++) {
        char c = family[i];
        if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
              (c >= '0' && c <= '9') || strchr("_.:@-", c) != NULL))
            return fail_at(L, n, "planner '%s' can never announce itself: a "
                           "planner id (name@host:pid) holds only letters, "
                           "digits and '_' '.' ':' '@' '-'", family);
    }
    return 0;
}

static int load_planners(loader *L, mpbd_experiment *e, yaml_node_t *root)
{
    static const char *const keys[] = {"planner", "algorithms", "params",
                                       "runs", "name", NULL};
    yaml_node_t *list = need(L, root, "planners", YAML_SEQUENCE_NODE,
                             "a list of planners");
    size_t total = 0;
    int64_t total_runs = 0;
    /* Where the default runs come from, for the message. */
    yaml_node_t *default_runs = get(L, get(L, root, "experiment"), "runs");
    if (list == NULL)
        return -1;
    for (yaml_node_item_t *it = list->data.sequence.items.start;
         it < list->data.sequence.items.top; it++)
        total += count_items(get(L, node(L, *it), "algorithms"));
    if ((e->configs = calloc(total + 1, sizeof *e->configs)) == NULL)
        return fail_at(L, list, "out of memory");
    if (count_items(list) == 0)
        return fail_at(L, list, "'planners' must not be empty");
    for (yaml_node_item_t *it = list->data.sequence.items.start;
         it < list->data.sequence.items.top; it++) {
        yaml_node_t *m = node(L, *it), *algos, *n;
        char *planner;
        const char *suffix = NULL;
        int runs = e->runs;
        if (m->type != YAML_MAPPING_NODE)
            return fail_at(L, m, "a planner must be a mapping of planner, "
                                 "algorithms");
        if (only_keys(L, m, keys) != 0 ||
            (algos = need(L, m, "algorithms", YAML_SEQUENCE_NODE,
                          "a list of algorithm names")) == NULL)
            return -1;
        if (count_items(algos) == 0)
            return fail_at(L, algos, "'algorithms' must not be empty");
        yaml_node_t *runs_node = get(L, m, "runs");
        if (runs_node && parse_positive_int(L, runs_node, "runs", &runs))
            return -1;
        if (runs_node == NULL)
            runs_node = default_runs ? default_runs : m;
        if ((n = get(L, m, "name")) != NULL && (suffix = scalar(n)) == NULL)
            return fail_at(L, n, "name must be a string");
        if ((planner = need_string(L, m, "planner")) == NULL)
            return -1;
        if (check_family(L, get(L, m, "planner"), planner) != 0) {
            free(planner);
            return -1;
        }
        for (yaml_node_item_t *a = algos->data.sequence.items.start;
             a < algos->data.sequence.items.top; a++) {
            yaml_node_t *an = node(L, *a);
            mpbd_config *c = &e->configs[e->num_configs++];
            char name[512];
            if (scalar(an) == NULL || scalar(an)[0] == '\0') {
                free(planner);
                return fail_at(L, an, "an algorithm must be a name");
            }
            c->planner = strdup(planner);
            c->algorithm = strdup(scalar(an));
            c->runs = runs;
            snprintf(name, sizeof name, "%s/%s%s%s", planner, scalar(an),
                     suffix ? "#" : "", suffix ? suffix : "");
            c->name = strdup(name);
            if (!c->planner || !c->algorithm || !c->name ||
                load_params(L, c, get(L, m, "params")) != 0 ||
                (c->params_text = params_text(c->params, c->num_params)) == NULL) {
                free(planner);
                return fail_at(L, an, "out of memory");
            }
            for (mpbd_config *o = e->configs; o < c; o++)
                if (strcmp(o->name, c->name) == 0) {
                    free(planner);
                    return fail_at(L, an, "planner configuration '%s' appears "
                                   "twice (give one a 'name')", c->name);
                }
            if (add_runs(L, e, runs, runs_node, &total_runs) != 0) {
                free(planner);
                return -1;
            }
        }
        free(planner);
    }
    return 0;
}

static char *dir_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    size_t n = slash ? (size_t)(slash - path + 1) : 0;
    char *d = malloc(n + 1);
    if (d) {
        memcpy(d, path, n);
        d[n] = '\0';
    }
    return d;
}

/* libyaml's complaint, at the place it names. */
static int fail_yaml(loader *L, const yaml_parser_t *parser)
{
    snprintf(L->err, L->errlen, "%s:%lu:%lu: YAML: %s", L->path,
             (unsigned long)parser->problem_mark.line + 1,
             (unsigned long)parser->problem_mark.column + 1,
             parser->problem ? parser->problem : "syntax error");
    L->failed = 1;
    return -1;
}

/* The loader reads one document: a second one (after `---`) would be
 * ignored without a word, so it is an error, as is bad YAML in it. */
static int no_second_document(loader *L, yaml_parser_t *parser)
{
    yaml_document_t next;
    if (!yaml_parser_load(parser, &next))
        return fail_yaml(L, parser);
    int more = yaml_document_get_root_node(&next) != NULL;
    yaml_mark_t at = next.start_mark;
    yaml_document_delete(&next);
    if (!more)
        return 0;
    snprintf(L->err, L->errlen, "%s:%lu:%lu: a second YAML document (an "
             "experiment file holds one)", L->path,
             (unsigned long)at.line + 1, (unsigned long)at.column + 1);
    L->failed = 1;
    return -1;
}

/* Far deeper than an experiment needs (six levels); libyaml's scanner
 * spends time in proportion to the depth on every token, so a hundred
 * thousand '[' took minutes. */
#define YAML_DEPTH_MAX 100

/* A pass over libyaml's events before it builds the document, stopping
 * at the first collection nested deeper than YAML_DEPTH_MAX. */
static int not_too_deep(loader *L, const char *text, size_t len)
{
    yaml_parser_t parser;
    yaml_event_t ev;
    int depth = 0, rc = 0;
    yaml_parser_initialize(&parser);
    yaml_parser_set_input_string(&parser, (const unsigned char *)text, len);
    for (;;) {
        if (!yaml_parser_parse(&parser, &ev)) {
            rc = fail_yaml(L, &parser);
            break;
        }
        yaml_event_type_t type = ev.type;
        yaml_mark_t at = ev.start_mark;
        yaml_event_delete(&ev);
        if (type == YAML_STREAM_END_EVENT)
            break;
        if (type == YAML_SEQUENCE_END_EVENT || type == YAML_MAPPING_END_EVENT)
            depth--;
        else if ((type == YAML_SEQUENCE_START_EVENT ||
                  type == YAML_MAPPING_START_EVENT) && ++depth > YAML_DEPTH_MAX) {
            snprintf(L->err, L->errlen, "%s:%lu:%lu: nested too deeply (more "
                     "than %d levels)", L->path, (unsigned long)at.line + 1,
                     (unsigned long)at.column + 1, YAML_DEPTH_MAX);
            L->failed = 1;
            rc = -1;
            break;
        }
    }
    yaml_parser_delete(&parser);
    return rc;
}

mpbd_experiment *mpbd_experiment_load(const char *path, char *err, size_t errlen)
{
    static const char *const top_keys[] = {"experiment", "robot", "scenes",
                                           "planners", NULL};
    loader L = {.path = path, .err = err, .errlen = errlen};
    yaml_parser_t parser;
    mpbd_experiment *e = calloc(1, sizeof *e);
    size_t len = 0;
    int have_doc = 0;

    if (e == NULL) {
        snprintf(err, errlen, "%s: out of memory", path);
        return NULL;
    }
    if ((e->text = slurp(path, &len)) == NULL) {
        snprintf(err, errlen, "%s: cannot read: %s", path, strerror(errno));
        goto fail;
    }
    if (strlen(e->text) != len) {
        snprintf(err, errlen, "%s: not a text file (contains a NUL byte)", path);
        goto fail;
    }
    e->file = strdup(path);
    L.dir = dir_of(path);
    if (e->file == NULL || L.dir == NULL) {
        snprintf(err, errlen, "%s: out of memory", path);
        goto fail;
    }
    mpb_hash_hex(e->text, len, e->hash);

    if (not_too_deep(&L, e->text, len) != 0)
        goto fail;
    yaml_parser_initialize(&parser);
    yaml_parser_set_input_string(&parser, (const unsigned char *)e->text, len);
    if (!yaml_parser_load(&parser, &L.doc)) {
        fail_yaml(&L, &parser);
        yaml_parser_delete(&parser);
        goto fail;
    }
    have_doc = 1;
    if (no_second_document(&L, &parser) != 0) {
        yaml_parser_delete(&parser);
        goto fail;
    }
    yaml_parser_delete(&parser);

    yaml_node_t *root = yaml_document_get_root_node(&L.doc);
    if (root == NULL || root->type != YAML_MAPPING_NODE) {
        fail_at(&L, root, "expected a mapping with experiment, robot, scenes "
                          "and planners");
        goto fail;
    }
    if (no_repeated_keys(&L) != 0 ||
        only_keys(&L, root, top_keys) != 0 || load_settings(&L, e, root) != 0 ||
        load_scenes(&L, e, root) != 0 || load_planners(&L, e, root) != 0)
        goto fail;

    yaml_document_delete(&L.doc);
    mpb_srdf_free(L.srdf);
    free(L.dir);
    return e;
fail:
    if (have_doc)
        yaml_document_delete(&L.doc);
    mpb_srdf_free(L.srdf);
    free(L.dir);
    mpbd_experiment_free(e);
    return NULL;
}

void mpbd_experiment_free(mpbd_experiment *e)
{
    if (e == NULL)
        return;
    for (int i = 0; i < e->num_scenes; i++) {
        mpbd_scene *s = &e->scenes[i];
        free(s->name);
        free(s->robot_format);
        free(s->robot);
        free(s->scene_format);
        free(s->scene);
        free(s->scene_file);
        mpb_world_close(s->world);
    }
    for (int i = 0; i < e->num_queries; i++) {
        free(e->queries[i].name);
        free(e->queries[i].start);
        free(e->queries[i].goal);
        free(e->queries[i].goal_link);
        free(e->queries[i].held);
        free(e->queries[i].moveit_group);
    }
    for (int i = 0; i < e->num_configs; i++) {
        mpbd_config *c = &e->configs[i];
        free(c->name);
        free(c->planner);
        free(c->algorithm);
        for (int p = 0; p < c->num_params; p++) {
            free(c->params[p].key);
            free(c->params[p].value);
        }
        free(c->params);
        free(c->params_text);
    }
    for (int j = 0; j < e->num_joints && e->joint_names; j++)
        free(e->joint_names[j]);
    free(e->joint_names);
    for (int j = 0; j < e->num_held; j++)
        free(e->held_names[j]);
    free(e->held_names);
    free(e->held_default);
    for (int j = 0; j < e->num_group; j++)
        free(e->group[j]);
    free(e->group);
    free(e->wraps);
    free(e->robot_file);
    free(e->srdf_file);
    free(e->srdf_warning);
    free(e->acm_skipped_at);
    free(e->group_name);
    free(e->scenes);
    free(e->queries);
    free(e->configs);
    free(e->name);
    free(e->file);
    free(e->text);
    free(e);
}

mpb_goal mpbd_query_goal(const mpbd_query *q)
{
    mpb_goal g = {.kind = q->goal_kind, .joints = q->goal,
                  .joint_tolerance = q->tolerance, .link = q->goal_link};
    for (int i = 0; i < 3; i++) {
        g.position[i] = q->position[i];
        g.position_tolerance[i] = q->position_tolerance[i];
        g.orientation_rpy[i] = q->rpy[i];
        g.orientation_tolerance[i] = q->rpy_tolerance[i];
    }
    return g;
}

/* splitmix64: a well-mixed 64-bit function of the run's place. */
static uint64_t mix(uint64_t x)
{
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

int64_t mpbd_run_seed(const mpbd_experiment *e, int config, int query,
                      int repetition)
{
    uint64_t h = mix(e->seed);
    h = mix(h ^ (uint64_t)config);
    h = mix(h ^ (uint64_t)query);
    h = mix(h ^ (uint64_t)repetition);
    /* Keep it positive and within 31 bits: every planner's RNG takes it. */
    return (int64_t)(h & 0x7fffffff);
}

int mpbd_experiment_acm_note(const mpbd_experiment *e, char *buf, size_t len)
{
    if (e->num_scenes < 1 || e->srdf_file != NULL ||
        strcmp(e->scenes[0].robot_format, "urdf") != 0)
        return 0;
    mpb_world *w = e->scenes[0].world;
    int n = mpb_world_num_allowed_pairs(w), adjacent = 0, dflt = 0, always = 0;
    int never = 0;
    for (int i = 0; i < n; i++) {
        mpb_world_acm_pair p;
        if (mpb_world_allowed_pair(w, i, &p) != MPB_OK)
            continue;
        adjacent += strcmp(p.reason, "Adjacent") == 0;
        dflt += strcmp(p.reason, "Default") == 0;
        always += strcmp(p.reason, "Always") == 0;
        never += strcmp(p.reason, "Never") == 0;
    }
    char joints[1024] = "";
    size_t used = 0;
    for (int j = 0; j < e->num_joints && used < sizeof joints; j++)
        used += (size_t)snprintf(joints + used, sizeof joints - used, "%s%s",
                                 j ? "," : "", e->joint_names[j]);
    snprintf(buf, len, "robot has no srdf: self-collision matrix generated "
             "as MoveIt's setup assistant does, %d pairs allowed (%d adjacent, "
             "%d in collision at the default state, %d nearly always, %d "
             "never in %d random states); review it with 'mpb srdf %s -j %s "
             "-o robot.srdf' and give the file as the robot's srdf", n,
             adjacent, dflt, always, never, MPB_WORLD_ACM_SAMPLES,
             e->robot_file ? e->robot_file : "ROBOT.urdf", joints);
    return 1;
}

int mpbd_experiment_scene_acm_note(const mpbd_experiment *e, char *buf,
                                   size_t len)
{
    if (e->acm_skipped == 0)
        return 0;
    snprintf(buf, len, "%d allowed_collision_matrix pairs in %d MoveIt "
             "scene%s name links the robot lacks (%s) and are skipped, as "
             "MoveIt does; the first at %s", e->acm_skipped,
             e->acm_skipped_scenes, e->acm_skipped_scenes == 1 ? "" : "s",
             e->acm_skipped_names, e->acm_skipped_at ? e->acm_skipped_at : "?");
    return 1;
}

int mpbd_experiment_moveit_note(const mpbd_experiment *e, char *buf,
                                size_t len)
{
    int moveit = 0, other_time = 0;
    double most = 0;
    for (int i = 0; i < e->num_queries; i++) {
        const mpbd_query *q = &e->queries[i];
        if (q->moveit_group == NULL && q->planning_time == 0)
            continue;
        moveit++;
        if (q->planning_time > 0 && q->planning_time != e->time_limit) {
            other_time++;
            most = q->planning_time > most ? q->planning_time : most;
        }
    }
    if (moveit == 0 || (e->held_clamped == 0 && e->held_ignored == 0 &&
                        e->held_unknown == 0 && e->goal_clamped == 0 &&
                        e->start_clamped == 0 &&
                        other_time == 0))
        return 0;
    char unknown[400] = "", goals[160] = "";
    if (e->goal_clamped > 0 || e->start_clamped > 0)
        snprintf(goals, sizeof goals, ", %d start values within %g of a "
                 "limit and %d goal values within their tolerance of one "
                 "moved onto it", e->start_clamped, MPBD_START_BOUNDS_ERROR,
                 e->goal_clamped);
    if (e->held_unknown > 0)
        snprintf(unknown, sizeof unknown, ", %d of joints the robot lacks "
                 "ignored (%s)", e->held_unknown, e->held_unknown_names);
    snprintf(buf, len, "%d MoveIt queries: %d joint values moved into their "
             "limits and %d of fixed joints ignored%s%s (clamp_joint_values); "
             "%d ask for an allowed_planning_time other than the time_limit "
             "(up to %g s), which rules (%g s)", moveit, e->held_clamped,
             e->held_ignored, unknown, goals, other_time, most,
             e->time_limit);
    return 1;
}
