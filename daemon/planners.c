/*
 * planners.c - the table of planner processes the daemon knows, learnt
 * from their announcements alone (announce.c hands them here); one that
 * stays silent too long is gone.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/grow.h"
#include "daemon.h"
#include "mpb_planner_announce_t.h"

static mpbd_planner *find(mpbd *d, const char *id)
{
    for (int i = 0; i < d->num_planners; i++)
        if (strcmp(d->planners[i].id, id) == 0)
            return &d->planners[i];
    return NULL;
}

static void set_offer(mpbd_planner *p, const mpb_planner_announce_t *m)
{
    for (int i = 0; i < p->num_algorithms; i++)
        free(p->algorithms[i]);
    free(p->algorithms);
    free(p->name);
    p->num_algorithms = 0;
    p->name = strdup(m->name);
    p->algorithms = calloc((size_t)m->num_algorithms + 1, sizeof *p->algorithms);
    if (p->algorithms == NULL || p->name == NULL)
        return;
    for (int i = 0; i < m->num_algorithms; i++)
        if ((p->algorithms[p->num_algorithms] = strdup(m->algorithms[i])))
            p->num_algorithms++;
}

/*
 * The approaches a planner announces for its algorithms (docs/protocol.md):
 * each configuration of its family and algorithm that the experiment file
 * gave none gets the planner's word, stored once. A word that is none of
 * proto.h's is said once and taken as none; an older planner (no
 * approaches, planner_announce_v1_t) declares none.
 */
static void learn_approaches(mpbd *d, const mpb_planner_announce_t *m)
{
    if (d->exp == NULL || d->store == NULL ||
        m->num_approaches != m->num_algorithms)
        return;
    for (int i = 0; i < m->num_algorithms; i++) {
        const char *word = m->approaches[i];
        if (word[0] == '\0')
            continue;
        if (mpb_approach_index(word) < 0) {
            char shown[4 * 32 + 4], algo[4 * 32 + 4];
            mpbd_log("planner %s announces approach '%s' for %s: none of "
                     MPB_APPROACHES_TEXT "; taken as none", m->planner_id,
                     mpb_escape(word, shown, sizeof shown),
                     mpb_escape(m->algorithms[i], algo, sizeof algo));
            continue;
        }
        for (int k = 0; k < d->exp->num_configs; k++) {
            mpbd_config *c = &d->exp->configs[k];
            if (c->approach_known || strcmp(c->planner, m->name) != 0 ||
                strcmp(c->algorithm, m->algorithms[i]) != 0)
                continue;
            if (mpb_store_planner_config_set_approach(d->store, c->db_id,
                                                      word, 1) != MPB_OK) {
                mpbd_db_error(d);
                return;
            }
            c->approach_known = 1;
        }
    }
}

/* Why an announcement cannot be taken, or NULL if it can. */
static const char *announce_fault(const mpb_planner_announce_t *m,
                                  char *why, size_t len)
{
    const char *id = m->planner_id;
    size_t n = strlen(id);
    char shown[4 * 40 + 4];
    if (n == 0)
        return "its planner id is empty";
    if (n > MPB_PLANNER_ID_MAX) {
        snprintf(why, len, "planner id '%s' is %zu characters long, more "
                 "than %d", mpb_escape(id, shown, 44), n, MPB_PLANNER_ID_MAX);
        return why;
    }
    if (!mpb_planner_id_is_valid(id)) {
        snprintf(why, len, "planner id '%s' has characters outside "
                 "[A-Za-z0-9_.:@-]", mpb_escape(id, shown, sizeof shown));
        return why;
    }
    if (m->name[0] == '\0') {
        snprintf(why, len, "planner %s announces no family name", id);
        return why;
    }
    if (m->num_algorithms < 0) {
        snprintf(why, len, "planner %s announces %d algorithms", id,
                 m->num_algorithms);
        return why;
    }
    if (m->num_approaches != 0 && m->num_approaches != m->num_algorithms) {
        snprintf(why, len, "planner %s announces %d approaches for %d "
                 "algorithms (one each, or none)", id, m->num_approaches,
                 m->num_algorithms);
        return why;
    }
    return NULL;
}

mpbd_planner *mpbd_planner_learn(mpbd *d, const mpb_planner_announce_t *m,
                                 double now)
{
    mpbd_planner *p;
    char why[256];
    const char *fault = announce_fault(m, why, sizeof why);

    if (fault != NULL) {
        d->count.rejected++;
        /* Such a planner goes on announcing: one line in 5 s says why no
         * run goes to it, not one a heartbeat. */
        if (now - d->last_bad_announce_log >= 5.0) {
            mpbd_log("rejected an announcement: %s (%ld messages rejected "
                     "so far)", fault, d->count.rejected);
            d->last_bad_announce_log = now;
        }
        return NULL;
    }
    if ((p = find(d, m->planner_id)) == NULL) {
        if (mpb__grow((void **)&d->planners, &d->cap_planners,
                      d->num_planners + 1, sizeof *d->planners) != MPB_OK)
            return NULL;
        p = &d->planners[d->num_planners++];
        memset(p, 0, sizeof *p);
        strcpy(p->id, m->planner_id);
        snprintf(p->host, sizeof p->host, "%s", m->host);
        set_offer(p, m);
        learn_approaches(d, m);
        char language[4 * 32 + 4];
        mpbd_log("planner %s joined (%s, %d algorithm%s)", p->id,
                 mpb_escape(m->language, language, sizeof language),
                 m->num_algorithms, m->num_algorithms == 1 ? "" : "s");
    } else if (p->gone) {
        set_offer(p, m);
        learn_approaches(d, m);
        p->gone = 0;
        mpbd_log("planner %s is back", p->id);
    }
    /* Capacity 0 after more: closing (max runs reached). From the start,
     * it is read as 1: a planner that never set it. */
    if (m->capacity > 0) {
        p->capacity = m->capacity;
        p->capacity_seen = 1;
        p->closing = 0;
    } else if (p->capacity_seen) {
        if (!p->closing)
            mpbd_log("planner %s is closing: it takes no more runs", p->id);
        p->closing = 1;
    } else {
        p->capacity = 1;
    }
    p->heartbeat_s = m->heartbeat_ms > 0 ? m->heartbeat_ms / 1000.0 : 0.5;
    p->last_seen = now;
    p->instance = d->msg_from;
    int layout = d->msg_layout > 0 ? MPB_WIRE_BEFORE_ATTEMPT_ID : 0;
    if (layout != p->layout)
        mpbd_log("planner %s %s", p->id, layout != 0
                     ? "was built before attempt_id: it is sent requests "
                       "and acks in their older layouts"
                     : "speaks today's layouts");
    p->layout = layout;
    return p;
}

int mpbd_planners_expire(mpbd *d, double now)
{
    int went = 0;
    if (mpbd_hub_unproven(d, now))
        return 0;
    for (int i = 0; i < d->num_planners; i++) {
        mpbd_planner *p = &d->planners[i];
        double silence = now - p->last_seen;
        double limit = MPBD_PLANNER_MISSED * p->heartbeat_s + 0.5;
        /* Through a hub, silent only if the daemon's own status came back
         * after the planner should have been heard: a stalling hub blocks
         * its clients one after another, the planner's before the
         * daemon's maybe. */
        if (!mpbd_hub_heard_since(d, p->last_seen + limit))
            continue;
        if (!p->gone && silence > limit) {
            p->gone = 1;
            went++;
            mpbd_log("planner %s is gone (silent for %.1f s)", p->id, silence);
        }
    }
    return went;
}

int mpbd_planner_offers(const mpbd_planner *p, const char *name,
                        const char *algorithm)
{
    if (p->name == NULL || strcmp(p->name, name) != 0)
        return 0;
    for (int i = 0; i < p->num_algorithms; i++)
        if (strcmp(p->algorithms[i], algorithm) == 0)
            return 1;
    return 0;
}

uint64_t mpbd_planner_instance(const mpbd *d, const char *id)
{
    for (int i = 0; i < d->num_planners; i++)
        if (strcmp(d->planners[i].id, id) == 0)
            return d->planners[i].instance;
    return 0;
}

int mpbd_planner_layout(const mpbd *d, const char *id)
{
    for (int i = 0; i < d->num_planners; i++)
        if (strcmp(d->planners[i].id, id) == 0)
            return d->planners[i].layout;
    return 0;
}

void mpbd_planners_free(mpbd *d)
{
    for (int i = 0; i < d->num_planners; i++) {
        for (int a = 0; a < d->planners[i].num_algorithms; a++)
            free(d->planners[i].algorithms[a]);
        free(d->planners[i].algorithms);
        free(d->planners[i].name);
    }
    free(d->planners);
    d->planners = NULL;
    d->num_planners = d->cap_planners = 0;
}
