/*
 * parse_cache.c - URDF and SRDF texts parsed once per process
 * (parse_cache.h): deep copies of the parsed structs, and the cache.
 */
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "mpbench/mpbench.h"
#include "model/parse_cache.h"

/* ---- deep copies ------------------------------------------------------- */

/* A copy of s (NULL stays NULL); *failed set when memory runs out. */
static char *dup_str(const char *s, int *failed)
{
    if (!s)
        return NULL;
    char *d = strdup(s);
    if (!d)
        *failed = 1;
    return d;
}

/* n elements of size bytes copied from p (NULL when n is 0 or p NULL). */
static void *dup_array(const void *p, int n, size_t size, int *failed)
{
    if (!p || n <= 0)
        return NULL;
    void *d = malloc((size_t)n * size);
    if (!d) {
        *failed = 1;
        return NULL;
    }
    return memcpy(d, p, (size_t)n * size);
}

int mpb__urdf_model_copy(const mpb__urdf_model *from, mpb__urdf_model *to)
{
    int failed = 0;
    memset(to, 0, sizeof *to);
    to->name = dup_str(from->name, &failed);
    to->links = dup_array(from->links, from->num_links, sizeof *from->links,
                          &failed);
    if (!to->links) {
        free(to->name);
        memset(to, 0, sizeof *to);
        return from->num_links > 0 || failed ? MPB_ENOMEM : MPB_OK;
    }
    to->num_links = from->num_links;
    /* The flat copy shares the strings and shapes: each replaced in turn,
     * and what is not yet replaced is cleared before any cleanup. */
    for (int i = 0; i < to->num_links; i++) {
        mpb__urdf_link *l = &to->links[i];
        l->name = l->joint = l->mimic = NULL;
        l->geoms = NULL;
    }
    for (int i = 0; i < to->num_links && !failed; i++) {
        const mpb__urdf_link *a = &from->links[i];
        mpb__urdf_link *l = &to->links[i];
        l->name = dup_str(a->name, &failed);
        l->joint = dup_str(a->joint, &failed);
        l->mimic = dup_str(a->mimic, &failed);
        l->geoms = dup_array(a->geoms, a->num_geoms, sizeof *a->geoms, &failed);
        if (!l->geoms) {
            l->num_geoms = 0;
            continue;
        }
        for (int k = 0; k < l->num_geoms; k++)
            l->geoms[k].mesh_uri = l->geoms[k].name = NULL;
        for (int k = 0; k < l->num_geoms; k++) {
            l->geoms[k].mesh_uri = dup_str(a->geoms[k].mesh_uri, &failed);
            l->geoms[k].name = dup_str(a->geoms[k].name, &failed);
        }
    }
    if (failed) {
        mpb__urdf_model_clear(to);
        return MPB_ENOMEM;
    }
    return MPB_OK;
}

int mpb__srdf_copy(const mpb__srdf *from, mpb__srdf *to)
{
    int failed = 0;
    memset(to, 0, sizeof *to);
    to->robot_name = dup_str(from->robot_name, &failed);
    /* Each list: the flat copy, then its strings cleared and copied, so
     * that a failure midway leaves only what mpb__srdf_clear() frees. */
    if ((to->pairs = dup_array(from->pairs, from->num_pairs,
                               sizeof *from->pairs, &failed))) {
        to->num_pairs = from->num_pairs;
        for (int i = 0; i < to->num_pairs; i++) {
            mpb__srdf_pair *p = &to->pairs[i];
            p->link1 = p->link2 = p->reason = NULL;
        }
        for (int i = 0; i < to->num_pairs; i++) {
            mpb__srdf_pair *p = &to->pairs[i];
            p->link1 = dup_str(from->pairs[i].link1, &failed);
            p->link2 = dup_str(from->pairs[i].link2, &failed);
            p->reason = dup_str(from->pairs[i].reason, &failed);
        }
    }
    if ((to->groups = dup_array(from->groups, from->num_groups,
                                sizeof *from->groups, &failed))) {
        to->num_groups = from->num_groups;
        for (int i = 0; i < to->num_groups; i++) {
            to->groups[i].name = NULL;
            to->groups[i].elems = NULL;
            to->groups[i].num_elems = 0;
        }
        for (int i = 0; i < to->num_groups; i++) {
            const mpb__srdf_group *a = &from->groups[i];
            mpb__srdf_group *g = &to->groups[i];
            g->name = dup_str(a->name, &failed);
            if (!(g->elems = dup_array(a->elems, a->num_elems,
                                       sizeof *a->elems, &failed)))
                continue;
            g->num_elems = a->num_elems;
            for (int k = 0; k < g->num_elems; k++)
                g->elems[k].name = g->elems[k].tip = NULL;
            for (int k = 0; k < g->num_elems; k++) {
                g->elems[k].name = dup_str(a->elems[k].name, &failed);
                g->elems[k].tip = dup_str(a->elems[k].tip, &failed);
            }
        }
    }
    if ((to->states = dup_array(from->states, from->num_states,
                                sizeof *from->states, &failed))) {
        to->num_states = from->num_states;
        for (int i = 0; i < to->num_states; i++) {
            to->states[i].name = to->states[i].group = NULL;
            to->states[i].values = NULL;
            to->states[i].num_values = 0;
        }
        for (int i = 0; i < to->num_states; i++) {
            const mpb__srdf_state *a = &from->states[i];
            mpb__srdf_state *s = &to->states[i];
            s->name = dup_str(a->name, &failed);
            s->group = dup_str(a->group, &failed);
            if (!(s->values = dup_array(a->values, a->num_values,
                                        sizeof *a->values, &failed)))
                continue;
            s->num_values = a->num_values;
            for (int k = 0; k < s->num_values; k++)
                s->values[k].joint = NULL;
            for (int k = 0; k < s->num_values; k++)
                s->values[k].joint = dup_str(a->values[k].joint, &failed);
        }
    }
    if ((to->vjoints = dup_array(from->vjoints, from->num_vjoints,
                                 sizeof *from->vjoints, &failed))) {
        to->num_vjoints = from->num_vjoints;
        for (int i = 0; i < to->num_vjoints; i++) {
            mpb__srdf_vjoint *v = &to->vjoints[i];
            v->name = v->type = v->parent_frame = v->child_link = NULL;
        }
        for (int i = 0; i < to->num_vjoints; i++) {
            const mpb__srdf_vjoint *a = &from->vjoints[i];
            mpb__srdf_vjoint *v = &to->vjoints[i];
            v->name = dup_str(a->name, &failed);
            v->type = dup_str(a->type, &failed);
            v->parent_frame = dup_str(a->parent_frame, &failed);
            v->child_link = dup_str(a->child_link, &failed);
        }
    }
    if ((to->passive = dup_array(from->passive, from->num_passive,
                                 sizeof *from->passive, &failed))) {
        to->num_passive = from->num_passive;
        for (int i = 0; i < to->num_passive; i++)
            to->passive[i].name = NULL;
        for (int i = 0; i < to->num_passive; i++)
            to->passive[i].name = dup_str(from->passive[i].name, &failed);
    }
    if ((to->eefs = dup_array(from->eefs, from->num_eefs, sizeof *from->eefs,
                              &failed))) {
        to->num_eefs = from->num_eefs;
        for (int i = 0; i < to->num_eefs; i++) {
            mpb__srdf_eef *e = &to->eefs[i];
            e->name = e->group = e->parent_link = e->parent_group = NULL;
        }
        for (int i = 0; i < to->num_eefs; i++) {
            const mpb__srdf_eef *a = &from->eefs[i];
            mpb__srdf_eef *e = &to->eefs[i];
            e->name = dup_str(a->name, &failed);
            e->group = dup_str(a->group, &failed);
            e->parent_link = dup_str(a->parent_link, &failed);
            e->parent_group = dup_str(a->parent_group, &failed);
        }
    }
    if (failed) {
        mpb__srdf_clear(to);
        return MPB_ENOMEM;
    }
    return MPB_OK;
}

/* ---- the cache --------------------------------------------------------- */

/* Enough for a planner that alternates between a few robots. */
#define KEEP 4

typedef enum kind { URDF = 0, SRDF = 1 } kind;

typedef struct entry {
    char *text;                 /* NULL: an empty slot */
    union {
        mpb__urdf_model urdf;
        mpb__srdf       srdf;
    } u;
    unsigned long used;         /* when last found or stored */
} entry;

static pthread_mutex_t mu = PTHREAD_MUTEX_INITIALIZER;
static entry slots[2][KEEP];
static unsigned long clock_;
static long parses;

static void clear_entry(kind k, entry *e)
{
    if (!e->text)
        return;
    if (k == URDF)
        mpb__urdf_model_clear(&e->u.urdf);
    else
        mpb__srdf_clear(&e->u.srdf);
    free(e->text);
    memset(e, 0, sizeof *e);
}

static int copy_out(kind k, const entry *e, void *out)
{
    return k == URDF ? mpb__urdf_model_copy(&e->u.urdf, out)
                     : mpb__srdf_copy(&e->u.srdf, out);
}

/* The parse of text for kind k into out, from the cache when it holds
 * that very text. */
static int parse_cached(kind k, const char *text, void *out, char *err,
                        size_t errlen)
{
    if (!text || !out)
        return k == URDF ? mpb__urdf_parse(text, out, err, errlen)
                         : mpb__srdf_parse(text, out, err, errlen);
    int rc = MPB_ENOTFOUND;
    pthread_mutex_lock(&mu);
    for (int i = 0; i < KEEP; i++) {
        entry *e = &slots[k][i];
        if (e->text && strcmp(e->text, text) == 0) {
            e->used = ++clock_;
            rc = copy_out(k, e, out);
            break;
        }
    }
    parses += rc != MPB_OK;
    pthread_mutex_unlock(&mu);
    if (rc == MPB_OK) {
        if (err && errlen)
            err[0] = '\0';
        return rc;
    }
    /* Parsed outside the lock; two threads may both parse one text, and
     * both copies are kept until one slot is reused. */
    rc = k == URDF ? mpb__urdf_parse(text, out, err, errlen)
                   : mpb__srdf_parse(text, out, err, errlen);
    if (rc != MPB_OK)
        return rc;
    entry fresh = {0};
    if (!(fresh.text = strdup(text)) ||
        (k == URDF ? mpb__urdf_model_copy(out, &fresh.u.urdf)
                   : mpb__srdf_copy(out, &fresh.u.srdf)) != MPB_OK) {
        free(fresh.text);
        return MPB_OK;          /* not kept: the next open parses again */
    }
    pthread_mutex_lock(&mu);
    entry *victim = &slots[k][0];
    for (int i = 1; i < KEEP; i++)
        if (slots[k][i].used < victim->used)
            victim = &slots[k][i];
    entry old = *victim;
    fresh.used = ++clock_;
    *victim = fresh;
    pthread_mutex_unlock(&mu);
    clear_entry(k, &old);
    return MPB_OK;
}

int mpb__urdf_parse_cached(const char *text, mpb__urdf_model *m, char *err,
                           size_t errlen)
{
    return parse_cached(URDF, text, m, err, errlen);
}

int mpb__srdf_parse_cached(const char *text, mpb__srdf *s, char *err,
                           size_t errlen)
{
    return parse_cached(SRDF, text, s, err, errlen);
}

long mpb__parse_cache_parses(void)
{
    pthread_mutex_lock(&mu);
    long n = parses;
    pthread_mutex_unlock(&mu);
    return n;
}

void mpb__parse_cache_forget(void)
{
    pthread_mutex_lock(&mu);
    for (int k = 0; k < 2; k++)
        for (int i = 0; i < KEEP; i++)
            clear_entry((kind)k, &slots[k][i]);
    pthread_mutex_unlock(&mu);
}
