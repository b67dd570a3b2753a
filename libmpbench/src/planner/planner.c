/* planner.c - a planner process's side of the protocol: announce, answer,
 * re-send until acked; through a hub, tell a stalled link and hold. */
#include <errno.h>
#include <limits.h>
#include <pthread.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/select.h>
#include <time.h>
#include <unistd.h>

#include <lcm/lcm.h>

#include "mpbench/mpbench.h"
#include "mpbench/planner.h"
#include "mpbench/link.h"
#include "mpbench/robot.h"
#include "mpbench/world.h"
#include "mpb_daemon_status_t.h"
#include "mpb_planner_announce_t.h"
#include "mpb_run_ack_t.h"
#include "planner/planner_memory.h"

/* How many finished runs are remembered, to answer a repeated request. */
#define MPB__RESULTS_KEPT 64
/* A result is re-sent until acknowledged, for as long as it is kept:
 * after MPB__RESEND_S, the wait doubling to MPB__RESEND_MAX_S, and at once
 * when a hub link connects again. A planner closing (--max-runs) waits at
 * most MPB__CLOSING_WAIT_S for its last results' acknowledgements. */
#define MPB__RESEND_S 0.2
#define MPB__RESEND_MAX_S 2.0
#define MPB__CLOSING_WAIT_S 10.0
/* Longest wait in select(), so that *stop and re-sends are seen promptly. */
#define MPB__POLL_S 0.05
/* LCM queue lengths: acks are small and may come many at once (a commit
 * of several results); requests are large and few. */
#define MPB__ACK_QUEUE 1000
#define MPB__REQUEST_QUEUE 8
/* Closest two announces may be (ms). */
#define MPB__ANNOUNCE_GAP_MS 50
/* A request is acknowledged (REQUEST_RECEIVED) only if its solve is still
 * running this long after it began; a quicker result acknowledges its own
 * request. Well below the daemon's re-send interval (250 ms). */
#define MPB__ACK_AFTER_S 0.05
/* Through a hub, every heartbeat also goes to the planner itself, on its
 * own acknowledgement channel: the hub relays it back. None back for this
 * long (or three heartbeats, if longer) while connected: the hub is
 * stalled (a client that never reads blocks it), as the daemon judges by
 * its own statuses (MPBD_HUB_ECHO_MAX_S). */
#define MPB__ECHO_MAX_S 5.0
/* A closing planner (max_runs reached) waits through a stall for its last
 * results' acknowledgements as long as the daemon waits for a hub away or
 * stalled before it stops (MPBD_HUB_AWAY_MAX_S), then stops too. */
#define MPB__STALL_CLOSING_MAX_S 60.0

typedef struct mpb__kept {
    int used;
    int acked;
    int sends;                 /* since it was last acknowledged */
    double first_send_s;
    double next_send_s;
    mpb_plan_result_t res;     /* owned; res.attempt_id names the run */
} mpb__kept;

typedef struct mpb__server {
    const mpb_planner_def *def;
    lcm_t *lcm;
    mpb_auth *auth;             /* NULL: messages are not authenticated */
    char id[MPB_PLANNER_ID_MAX + 1];
    char host[256];
    char request_channel[sizeof MPB_CHANNEL_REQUEST_PREFIX + MPB_PLANNER_ID_MAX];
    char ack_channel[sizeof MPB_CHANNEL_ACK_PREFIX + MPB_PLANNER_ID_MAX];
    int heartbeat_ms;

    long solved;                /* runs answered (solve() called) */
    long max_runs;
    int run_error;              /* an MPB_E... code that ends the loop */

    mpb__kept kept[MPB__RESULTS_KEPT];
    int kept_next;              /* ring position of the next result */
    long hub_connects;          /* the hub link's connections, last seen */

    /* Through a hub: the link's echo, watched by the serving thread. */
    int is_hub;
    double stall_s;             /* no echo this long: stalled */
    double echo_back_s;         /* monotonic s: an echo came back, or a
                                   connection began whose echo is to come */
    long echo_connects;         /* the connection that echo_back_s is of */
    double stalled_since;       /* the last echo before the stall */
    int relays_again;           /* the stall ended: every result goes now */
    int link_said;              /* the link's state last told the user:
                                   0 none yet, 1 up, 2 away */
    double link_lost_s;         /* monotonic s: the link went away */

    /* Shared with the heartbeat thread, under mu. */
    pthread_mutex_t mu;
    pthread_cond_t cond;
    char active[MPB_ATTEMPT_ID_SIZE];   /* run being solved, "" if idle */
    double active_since;            /* monotonic s, when its solve began */
    int active_acked;               /* REQUEST_RECEIVED sent for it */
    int closed;                     /* capacity 0: max_runs reached */
    int quit;
    int announce_now;
    double waiting_until;           /* the thread sleeps until; 0: awake */
    int stalled;                    /* the hub relays nothing: send only
                                       the echo (written by the serving
                                       thread alone) */
    /* With a secret: the instance of the daemon last heard (auth.h),
     * which every message echoes; 0 before any, when the planner does
     * not announce (no daemon would believe it). */
    uint64_t daemon;
    volatile sig_atomic_t *stop;    /* mpb_planner_serve()'s, for solve() */
} mpb__server;

/* ---- results ----------------------------------------------------------- */

static char *mpb__strdup(const char *s)
{
    size_t n = strlen(s) + 1;
    char *p = malloc(n);
    if (p != NULL)
        memcpy(p, s, n);
    return p;
}

int mpb_result_add_stage(mpb_plan_result_t *res, const char *name,
                         double time, const double *waypoints,
                         int num_waypoints, int num_joints)
{
    if (res == NULL || name == NULL || num_waypoints < 0 || num_joints < 0 ||
        num_joints > INT16_MAX || res->num_stages >= INT16_MAX ||
        (num_waypoints > 0 && num_joints > 0 && waypoints == NULL) ||
        (num_joints > 0 && num_waypoints > INT32_MAX / num_joints))
        return MPB_EINVAL;
    size_t nv = (size_t)num_waypoints * (size_t)num_joints;
    mpb_stage_t *stages = realloc(res->stages,
                                  ((size_t)res->num_stages + 1) * sizeof *stages);
    if (stages == NULL)
        return MPB_ENOMEM;
    res->stages = stages;
    mpb_stage_t *st = &stages[res->num_stages];
    memset(st, 0, sizeof *st);
    st->name = mpb__strdup(name);
    st->waypoints = nv > 0 ? malloc(nv * sizeof(double)) : NULL;
    if (st->name == NULL || (nv > 0 && st->waypoints == NULL)) {
        free(st->name);
        free(st->waypoints);
        return MPB_ENOMEM;
    }
    if (nv > 0)
        memcpy(st->waypoints, waypoints, nv * sizeof(double));
    st->time = time;
    st->num_waypoints = num_waypoints;
    st->num_joints = (int16_t)num_joints;
    st->num_values = (int32_t)nv;
    res->num_stages++;
    return MPB_OK;
}

int mpb_result_set_times(mpb_plan_result_t *res, int stage,
                         const double *times, int num_times)
{
    if (res == NULL || stage < 0 || stage >= res->num_stages ||
        num_times < 0 || (num_times > 0 && times == NULL))
        return MPB_EINVAL;
    mpb_stage_t *st = &res->stages[stage];
    double *copy = NULL;
    if (num_times > 0) {
        if ((copy = malloc((size_t)num_times * sizeof *copy)) == NULL)
            return MPB_ENOMEM;
        memcpy(copy, times, (size_t)num_times * sizeof *copy);
    }
    free(st->times);
    st->times = copy;
    st->num_times = num_times;
    return MPB_OK;
}

int mpb_result_add_value(mpb_plan_result_t *res, const char *name,
                         double value)
{
    if (res == NULL || name == NULL || res->num_values >= INT16_MAX)
        return MPB_EINVAL;
    mpb_named_value_t *v = realloc(res->values,
                                   ((size_t)res->num_values + 1) * sizeof *v);
    if (v == NULL)
        return MPB_ENOMEM;
    res->values = v;
    v[res->num_values].name = mpb__strdup(name);
    if (v[res->num_values].name == NULL)
        return MPB_ENOMEM;
    v[res->num_values].value = value;
    res->num_values++;
    return MPB_OK;
}

int mpb_result_set_message(mpb_plan_result_t *res, const char *fmt, ...)
{
    if (res == NULL || fmt == NULL)
        return MPB_EINVAL;
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    if (n < 0)
        return MPB_EINVAL;
    char *m = malloc((size_t)n + 1);
    if (m == NULL)
        return MPB_ENOMEM;
    va_start(ap, fmt);
    vsnprintf(m, (size_t)n + 1, fmt, ap);
    va_end(ap);
    free(res->message);
    res->message = m;
    return MPB_OK;
}

/* Free the stages, values and progress of res, leaving none. */
static void mpb__result_clear_lists(mpb_plan_result_t *res)
{
    for (int i = 0; i < res->num_stages; i++) {
        free(res->stages[i].name);
        free(res->stages[i].waypoints);
        free(res->stages[i].times);
    }
    free(res->stages);
    for (int i = 0; i < res->num_values; i++)
        free(res->values[i].name);
    free(res->values);
    for (int i = 0; i < res->num_progress; i++) {
        for (int j = 0; j < res->progress[i].num_values; j++)
            free(res->progress[i].values[j].name);
        free(res->progress[i].values);
    }
    free(res->progress);
    res->stages = NULL;
    res->values = NULL;
    res->progress = NULL;
    res->num_stages = 0;
    res->num_values = 0;
    res->num_progress = 0;
}

void mpb_result_clear(mpb_plan_result_t *res)
{
    if (res == NULL)
        return;
    free(res->attempt_id);
    free(res->planner_id);
    free(res->message);
    mpb__result_clear_lists(res);
    memset(res, 0, sizeof *res);
}

const char *mpb_request_param(const mpb_plan_request_t *req, const char *key)
{
    if (req == NULL || key == NULL)
        return NULL;
    for (int i = 0; i < req->num_params; i++)
        if (req->params[i].key != NULL && strcmp(req->params[i].key, key) == 0)
            return req->params[i].value != NULL ? req->params[i].value : "";
    return NULL;
}

/* LCM cannot encode a NULL string: give every string of res a value. */
static int mpb__result_fill_strings(mpb_plan_result_t *res)
{
    if (res->message == NULL && (res->message = mpb__strdup("")) == NULL)
        return MPB_ENOMEM;
    for (int i = 0; i < res->num_stages; i++)
        if (res->stages[i].name == NULL &&
            (res->stages[i].name = mpb__strdup("")) == NULL)
            return MPB_ENOMEM;
    for (int i = 0; i < res->num_values; i++)
        if (res->values[i].name == NULL &&
            (res->values[i].name = mpb__strdup("")) == NULL)
            return MPB_ENOMEM;
    for (int i = 0; i < res->num_progress; i++)
        for (int j = 0; j < res->progress[i].num_values; j++)
            if (res->progress[i].values[j].name == NULL &&
                (res->progress[i].values[j].name = mpb__strdup("")) == NULL)
                return MPB_ENOMEM;
    return MPB_OK;
}

/* ---- the planner id ---------------------------------------------------- */

static int mpb__make_id(mpb__server *s, char *err, size_t errlen)
{
    const char *name = s->def->name;
    char host[256];
    if (gethostname(host, sizeof host) != 0)
        host[0] = '\0';
    host[sizeof host - 1] = '\0';
    if (mpb_planner_id_make(name, host, (long)getpid(), s->id,
                            sizeof s->id) != MPB_OK) {
        if (name == NULL || strlen(name) == 0 || strlen(name) > 32)
            snprintf(err, errlen, "planner name must be 1 to 32 characters");
        else
            snprintf(err, errlen, "planner name '%s' may hold only "
                     "letters, digits and '_' '.' '-'", name);
        return MPB_EINVAL;
    }
    /* The host as announced: whole, in the id's characters. */
    for (char *p = host; *p != '\0'; p++)
        if (!((*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') ||
              (*p >= '0' && *p <= '9') || strchr("_.-", *p) != NULL))
            *p = '-';
    snprintf(s->host, sizeof s->host, "%s", host[0] ? host : "localhost");
    if (mpb_request_channel(s->id, s->request_channel,
                            sizeof s->request_channel) != MPB_OK ||
        mpb_ack_channel(s->id, s->ack_channel, sizeof s->ack_channel) != MPB_OK) {
        snprintf(err, errlen, "cannot make a planner id from '%s'", s->id);
        return MPB_EINVAL;
    }
    return MPB_OK;
}

/* What every announcement of this planner says of it; the caller sets
 * capacity and the active runs. Allocates nothing (the last words of
 * planner_memory.h are built with it). */
static void announce_fill(mpb__server *s, mpb_planner_announce_t *a)
{
    const mpb_planner_def *d = s->def;
    memset(a, 0, sizeof *a);
    a->utime = mpb_utime_now();
    a->planner_id = s->id;
    a->name = (char *)d->name;
    a->host = s->host;
    a->pid = (int32_t)getpid();
    a->language = (char *)(d->language != NULL ? d->language : "");
    a->version = (char *)(d->version != NULL ? d->version : "");
    a->heartbeat_ms = s->heartbeat_ms;
    a->num_algorithms = (int16_t)d->num_algorithms;
    a->algorithms = (char **)d->algorithms;
    if (d->approaches != NULL) {
        a->num_approaches = (int16_t)d->num_algorithms;
        a->approaches = (char **)d->approaches;
    }
}

/* ---- heartbeat --------------------------------------------------------- */

static void mpb__announce(mpb__server *s)
{
    char active[MPB_ATTEMPT_ID_SIZE];
    char *active_list[1] = { active };
    int closed;

    pthread_mutex_lock(&s->mu);
    memcpy(active, s->active, sizeof active);
    closed = s->closed;
    uint64_t daemon = s->daemon;
    pthread_mutex_unlock(&s->mu);
    if (s->auth != NULL && daemon == 0)
        return;

    mpb_planner_announce_t a;
    announce_fill(s, &a);
    a.capacity = closed ? 0 : 1;
    a.num_active = active[0] != '\0' ? 1 : 0;
    a.active_attempts = active_list;
    mpb_publish_announce(s->lcm, s->auth, daemon, MPB_CHANNEL_ANNOUNCE, &a);
}

/*
 * The announcement a process dying under its memory limit sends as its
 * last words (planner_memory.h): closing (capacity 0), still working on
 * attempt_id. Encoded now, with room for a trailer, since the dying cannot
 * allocate; caller frees. NULL when out of memory.
 */
static unsigned char *mpb__closing_announce(mpb__server *s,
                                            const char *attempt_id, int *len)
{
    char *active_list[1] = { (char *)attempt_id };
    mpb_planner_announce_t a;
    announce_fill(s, &a);
    a.capacity = 0;
    a.num_active = 1;
    a.active_attempts = active_list;
    int n = mpb_planner_announce_t_encoded_size(&a);
    unsigned char *buf = n > 0 ? malloc((size_t)n + MPB_AUTH_TRAILER_SIZE)
                               : NULL;
    if (buf != NULL && mpb_planner_announce_t_encode(buf, 0, n, &a) != n) {
        free(buf);
        buf = NULL;
    }
    *len = n;
    return buf;
}

static void mpb__ack(mpb__server *s, const char *attempt_id, int kind);
static void mpb__echo(mpb__server *s);

/*
 * The heartbeat thread: announce at once, then every heartbeat_ms; a change
 * of the active run (announce_now) brings the next announce forward, but
 * never closer than MPB__ANNOUNCE_GAP_MS to the last, so a fast planner
 * does not announce once per run. It also acknowledges the request being
 * solved once the solve has lasted MPB__ACK_AFTER_S: a planner that answers
 * sooner sends one message per run instead of two. Through a hub each
 * heartbeat is echoed (mpb__echo); while the hub is stalled the echo is
 * all it sends, the rest would only wait in the blocked connection.
 */
static void *mpb__heartbeat_main(void *arg)
{
    mpb__server *s = arg;
    const double gap = MPB__ANNOUNCE_GAP_MS / 1000.0;
    double last_announce = -1e9, next_announce = 0;

    pthread_mutex_lock(&s->mu);
    while (!s->quit) {
        double now = mpb_monotonic_s();
        double ack_due = s->active[0] != '\0' && !s->active_acked
                             ? s->active_since + MPB__ACK_AFTER_S : 1e300;
        double announce_due = next_announce;
        if (s->announce_now && last_announce + gap < announce_due)
            announce_due = last_announce + gap;

        int stalled = s->stalled;
        if (now >= ack_due) {
            char run[MPB_ATTEMPT_ID_SIZE];
            memcpy(run, s->active, sizeof run);
            s->active_acked = 1;
            pthread_mutex_unlock(&s->mu);
            if (!stalled)   /* else the daemon's re-sent request asks again */
                mpb__ack(s, run, MPB_RUN_ACK_T_REQUEST_RECEIVED);
            pthread_mutex_lock(&s->mu);
        } else if (now >= announce_due) {
            s->announce_now = 0;    /* changes from here on: announce again */
            pthread_mutex_unlock(&s->mu);
            if (!stalled)
                mpb__announce(s);
            if (s->is_hub)
                mpb__echo(s);
            pthread_mutex_lock(&s->mu);
            last_announce = now;
            next_announce = now + s->heartbeat_ms / 1000.0;
        } else {
            double due = ack_due < announce_due ? ack_due : announce_due;
            struct timespec ts;
            ts.tv_sec = (time_t)due;
            ts.tv_nsec = (long)((due - (double)ts.tv_sec) * 1e9);
            if (ts.tv_nsec >= 1000000000L)
                ts.tv_nsec = 999999999L;
            s->waiting_until = due;
            pthread_cond_timedwait(&s->cond, &s->mu, &ts);
            s->waiting_until = 0;
        }
    }
    pthread_mutex_unlock(&s->mu);
    return NULL;
}

/* Set the run being solved ("" for none) and have it announced soon (and
 * acknowledged, if its solve lasts). The heartbeat thread is woken only if
 * it would otherwise sleep past that: a planner answering thousands of
 * runs a second wakes it about every MPB__ANNOUNCE_GAP_MS, not twice a run. */
static void mpb__set_active(mpb__server *s, const char *attempt_id, int closed)
{
    double now = mpb_monotonic_s();
    pthread_mutex_lock(&s->mu);
    snprintf(s->active, sizeof s->active, "%s", attempt_id);
    s->active_since = now;
    s->active_acked = 0;
    s->closed = closed;
    s->announce_now = 1;
    if (s->waiting_until > now + MPB__ACK_AFTER_S ||
        s->waiting_until > now + MPB__ANNOUNCE_GAP_MS / 1000.0)
        pthread_cond_signal(&s->cond);
    pthread_mutex_unlock(&s->mu);
}

/* ---- messages ---------------------------------------------------------- */

static uint64_t mpb__daemon(mpb__server *s)
{
    pthread_mutex_lock(&s->mu);
    uint64_t d = s->daemon;
    pthread_mutex_unlock(&s->mu);
    return d;
}

/* With a secret: messages echo daemon from now on; a daemon not echoed
 * before hears an announcement at once. */
static void mpb__set_daemon(mpb__server *s, uint64_t daemon)
{
    pthread_mutex_lock(&s->mu);
    if (s->daemon != daemon) {
        s->daemon = daemon;
        s->announce_now = 1;
        pthread_cond_signal(&s->cond);
    }
    pthread_mutex_unlock(&s->mu);
}

static void mpb__ack(mpb__server *s, const char *attempt_id, int kind)
{
    mpb_run_ack_t a;
    memset(&a, 0, sizeof a);
    a.utime = mpb_utime_now();
    a.attempt_id = (char *)attempt_id;
    a.sender_id = s->id;
    a.kind = (int8_t)kind;
    mpb_publish_ack(s->lcm, s->auth, mpb__daemon(s), MPB_CHANNEL_ACK, &a);
}

/* The heartbeat's echo, to this planner itself on its acknowledgement
 * channel (no run, sender_id its own id, and with a secret echoing its
 * own instance, so that its gate believes it): the hub relays it back
 * only while it relays at all. */
static void mpb__echo(mpb__server *s)
{
    mpb_run_ack_t a;
    memset(&a, 0, sizeof a);
    a.utime = mpb_utime_now();
    a.attempt_id = "";
    a.sender_id = s->id;
    a.kind = MPB_RUN_ACK_T_REQUEST_RECEIVED;
    mpb_publish_ack(s->lcm, s->auth, mpb_auth_instance(s->auth),
                    s->ack_channel, &a);
}

/* The kept result of attempt_id, or NULL. Newest first: the run asked about is
 * nearly always the last one answered. */
static mpb__kept *mpb__find_kept(mpb__server *s, const char *attempt_id)
{
    for (int n = 1; n <= MPB__RESULTS_KEPT; n++) {
        mpb__kept *k = &s->kept[(s->kept_next + MPB__RESULTS_KEPT - n) %
                                MPB__RESULTS_KEPT];
        if (k->used && strcmp(k->res.attempt_id, attempt_id) == 0)
            return k;
    }
    return NULL;
}

/* Publish a kept result. A failed send (the socket's buffer full, say) is
 * not an error: it counts as a lost message, which the re-sends cover.
 * With the hub stalled it is held instead: it goes when the hub relays
 * again (mpb__resend_due). */
static void mpb__send(mpb__server *s, mpb__kept *k)
{
    if (!s->stalled)
        mpb_publish_result(s->lcm, s->auth, mpb__daemon(s),
                           MPB_CHANNEL_RESULT, &k->res);
    double now = mpb_monotonic_s(), wait = MPB__RESEND_S;
    for (int i = 0; i < k->sends && wait < MPB__RESEND_MAX_S; i++)
        wait *= 2;
    k->sends++;
    k->next_send_s = now + (wait < MPB__RESEND_MAX_S ? wait : MPB__RESEND_MAX_S);
}

/* ---- solving ----------------------------------------------------------- */

/* Checks of a request that do not need the planner; NULL if it passes. */
static const char *mpb__check_request(const mpb__server *s,
                                      const mpb_plan_request_t *req)
{
    int offered = 0;
    for (int i = 0; i < s->def->num_algorithms; i++)
        if (strcmp(s->def->algorithms[i], req->algorithm) == 0)
            offered = 1;
    if (!offered)
        return "algorithm not offered by this planner";
    if (req->num_joints <= 0)
        return "no joints";
    if (req->goal.kind == MPB_GOAL_T_JOINTS &&
        req->goal.num_joints != req->num_joints)
        return "goal has a different number of joints than start";
    if (req->goal.kind != MPB_GOAL_T_JOINTS &&
        req->goal.kind != MPB_GOAL_T_POSE_REGION)
        return "unknown goal kind";
    return NULL;
}

/* Solve req into a new ring slot, publish the result. */
static int mpb__run(mpb__server *s, const mpb_plan_request_t *req)
{
    mpb__kept *k = &s->kept[s->kept_next];
    s->kept_next = (s->kept_next + 1) % MPB__RESULTS_KEPT;
    if (k->used)
        mpb_result_clear(&k->res);
    memset(k, 0, sizeof *k);

    mpb_plan_result_t *res = &k->res;
    res->utime = mpb_utime_now();
    res->attempt_id = mpb__strdup(req->attempt_id);
    res->planner_id = mpb__strdup(s->id);
    if (res->attempt_id == NULL || res->planner_id == NULL) {
        mpb_result_clear(res);
        return MPB_ENOMEM;
    }

    const char *bad = mpb__check_request(s, req);
    if (bad != NULL) {
        res->status = MPB_PLAN_RESULT_T_INVALID_REQUEST;
        mpb_result_set_message(res, "%s", bad);
    } else {
        /* The planning's peak memory and its limit (docs/protocol.md,
         * "Memory"): measured and enforced around solve() alone. */
        mpb__memwatch mw;
        char unlimited[160] = "";
        int ann_len = 0;
        unsigned char *ann = req->memory_limit > 0
            ? mpb__closing_announce(s, req->attempt_id, &ann_len) : NULL;
        mpb__mem_begin(&mw, req->memory_limit, unlimited, sizeof unlimited);
        mpb__last_words_arm(&mw, s->lcm, s->auth, mpb__daemon(s),
                            req->attempt_id, s->id, ann, ann_len);
        mpb_solve_limits lim = {.start = mpb_monotonic_s(), .stop = s->stop};
        lim.deadline = lim.start + req->time_limit;
        int rc = s->def->solve(s->def->user, req, &lim, res);
        mpb__last_words_disarm();
        double peak = mpb__mem_end(&mw);
        free(ann);
        if (!(res->memory > 0))
            res->memory = peak;
        /* The attempt id and planner id are ours, whatever solve() did. */
        if (res->attempt_id == NULL || strcmp(res->attempt_id, req->attempt_id) != 0) {
            free(res->attempt_id);
            res->attempt_id = mpb__strdup(req->attempt_id);
        }
        if (res->planner_id == NULL || strcmp(res->planner_id, s->id) != 0) {
            free(res->planner_id);
            res->planner_id = mpb__strdup(s->id);
        }
        if (rc == MPB_ENOMEM) {
            /* An allocation failed: under a limit, the limit's doing. */
            res->status = MPB_PLAN_RESULT_T_MEMORY;
            if (res->message == NULL || res->message[0] == '\0') {
                if (mw.limit_mb > 0)
                    mpb_result_set_message(res, "out of memory under the "
                                           "memory_limit of %g MB",
                                           mw.limit_mb);
                else
                    mpb_result_set_message(res, "out of memory");
            }
        } else if (rc < 0) {
            res->status = MPB_PLAN_RESULT_T_INVALID_REQUEST;
            if (res->message == NULL || res->message[0] == '\0')
                mpb_result_set_message(res, "planner refused the request (%s)",
                                       mpb_err_name(rc));
        } else if (!mpb_status_is_planners(res->status)) {
            mpb_result_set_message(res, "planner set status %d; %s",
                                   (int)res->status,
                                   res->message != NULL ? res->message : "");
            res->status = MPB_PLAN_RESULT_T_FAILED;
        }
        /* A limit asked for and not set: the run says so. */
        if (unlimited[0] != '\0')
            mpb_result_set_message(res, "%s%s%s", unlimited,
                                   res->message && res->message[0] ? "; " : "",
                                   res->message ? res->message : "");
    }
    if (res->attempt_id == NULL || res->planner_id == NULL ||
        mpb__result_fill_strings(res) != MPB_OK) {
        mpb_result_clear(res);
        return MPB_ENOMEM;
    }
    /* Every receiver drops a message over the bound (lcm_filter.h): send
     * a failure saying why instead, which the daemon stores. */
    size_t size = (size_t)mpb_plan_result_t_encoded_size(res) +
                  (s->auth != NULL ? MPB_AUTH_TRAILER_SIZE : 0);
    if (size > MPB_LCM_MESSAGE_MAX) {
        mpb__result_clear_lists(res);
        res->status = MPB_PLAN_RESULT_T_FAILED;
        if (mpb_result_set_message(res, "result too large: %zu bytes, over "
                                   "the %u-byte (16 MiB) bound of an LCM "
                                   "message", size, MPB_LCM_MESSAGE_MAX) !=
            MPB_OK) {
            mpb_result_clear(res);
            return MPB_ENOMEM;
        }
    }
    res->utime = mpb_utime_now();
    k->used = 1;
    k->first_send_s = mpb_monotonic_s();
    mpb__send(s, k);
    return MPB_OK;
}

/* ---- LCM handlers ------------------------------------------------------ */

/*
 * A request for us: answer it from memory (acknowledging it), or solve it
 * here and now (acknowledged by its result, or by the heartbeat thread if
 * the solve lasts). Solving inside the handler needs no copy of the request;
 * meanwhile LCM queues what arrives.
 */
static void mpb__on_request(const lcm_recv_buf_t *rbuf, const char *channel,
                       const mpb_plan_request_t *msg, void *user)
{
    (void)rbuf;
    (void)channel;
    mpb__server *s = user;
    if (!mpb_attempt_id_is_valid(msg->attempt_id) || msg->planner_id == NULL ||
        strcmp(msg->planner_id, s->id) != 0)
        return;                 /* not a request for us: nothing to say */

    /* Earlier results the daemon has stored: each as a RESULT_STORED. */
    for (int i = 0; i < msg->num_stored; i++) {
        mpb__kept *done = mpb__find_kept(s, msg->stored[i]);
        if (done != NULL)
            done->acked = 1;
    }
    mpb__kept *k = mpb__find_kept(s, msg->attempt_id);
    if (k != NULL) {
        /* Solved already: send the result now, and re-send it until it is
         * acknowledged (again, if it was acknowledged before). */
        mpb__ack(s, msg->attempt_id, MPB_RUN_ACK_T_REQUEST_RECEIVED);
        if (k->acked) {
            k->acked = 0;
            k->sends = 0;
            k->first_send_s = mpb_monotonic_s();
        }
        mpb__send(s, k);
        return;
    }
    if (s->run_error != MPB_OK ||
        (s->max_runs > 0 && s->solved >= s->max_runs)) {
        /* Closing: take no new runs, and say so, so that the daemon gives
         * this one to another planner instead of waiting for it. */
        mpb__ack(s, msg->attempt_id, MPB_RUN_ACK_T_REQUEST_DECLINED);
        return;
    }
    /* No REQUEST_RECEIVED yet: the result acknowledges the request, unless
     * the solve lasts MPB__ACK_AFTER_S, when the heartbeat thread sends it. */

    int closing = s->max_runs > 0 && s->solved + 1 >= s->max_runs;
    mpb__set_active(s, msg->attempt_id, closing);
    int rc = mpb__run(s, msg);
    s->solved++;
    mpb__set_active(s, "", closing);
    if (rc != MPB_OK)
        s->run_error = rc;
}

/* Raw handlers: every message passes the receive gate (link.h) before
 * anything acts on it; one that fails is dropped. */
static void mpb__on_request_raw(const lcm_recv_buf_t *rbuf,
                                const char *channel, void *user)
{
    mpb__server *s = user;
    mpb_plan_request_t m;
    mpb_received r;
    /* With a secret, only a request from a daemon heard lately that
     * echoes this process, not had before: a replay is dropped. */
    if (mpb_receive(s->auth, MPB_RECEIVE_FRESH, MPB_WIRE_PLAN_REQUEST,
                    channel, rbuf->data, rbuf->data_size, &m, &r) != MPB_OK)
        return;
    if (s->auth != NULL)
        mpb__set_daemon(s, r.info.instance);
    mpb__on_request(rbuf, channel, &m, user);
    mpb_receive_done(MPB_WIRE_PLAN_REQUEST, &m);
}

static void mpb__on_ack(const lcm_recv_buf_t *rbuf, const char *channel,
                   const mpb_run_ack_t *msg, void *user)
{
    (void)rbuf;
    (void)channel;
    mpb__server *s = user;
    if (msg->kind != MPB_RUN_ACK_T_RESULT_STORED &&
        msg->kind != MPB_RUN_ACK_T_RESULT_REJECTED)
        return;
    mpb__kept *k = mpb__find_kept(s, msg->attempt_id);
    if (k != NULL)
        k->acked = 1;
}

static void mpb__echo_back(mpb__server *s);

/* The daemon's acknowledgement, or this planner's own echo: from its id,
 * and with a secret from its own instance. */
static void mpb__on_ack_raw(const lcm_recv_buf_t *rbuf, const char *channel,
                            void *user)
{
    mpb__server *s = user;
    mpb_run_ack_t m;
    mpb_received r;
    if (mpb_receive(s->auth, MPB_RECEIVE_FRESH, MPB_WIRE_RUN_ACK, channel,
                    rbuf->data, rbuf->data_size, &m, &r) != MPB_OK)
        return;
    if (strcmp(m.sender_id, s->id) == 0 &&
        (s->auth == NULL || r.info.instance == mpb_auth_instance(s->auth)))
        mpb__echo_back(s);
    else
        mpb__on_ack(rbuf, channel, &m, user);
    mpb_receive_done(MPB_WIRE_RUN_ACK, &m);
}

/* With a secret: a daemon's status names the instance to echo. Its
 * freshness cannot be shown (a status echoes no planner), but a replayed
 * one costs at most a planner unknown to the daemon a few announcements
 * it does not believe, until the daemon's next status. */
static void mpb__on_status_raw(const lcm_recv_buf_t *rbuf,
                               const char *channel, void *user)
{
    mpb__server *s = user;
    mpb_daemon_status_t m;
    mpb_received r;
    if (mpb_receive(s->auth, MPB_RECEIVE_FRESH | MPB_RECEIVE_UNPROVEN,
                    MPB_WIRE_DAEMON_STATUS, channel, rbuf->data,
                    rbuf->data_size, &m, &r) != MPB_OK)
        return;
    if (strcmp(m.state, "waiting") == 0 || strcmp(m.state, "running") == 0)
        mpb__set_daemon(s, r.info.instance);
    mpb_receive_done(MPB_WIRE_DAEMON_STATUS, &m);
}

/* ---- a stalled hub ----------------------------------------------------- */

static void mpb__warn(mpb__server *s, const char *fmt, ...)
{
    if (s->def->on_warning == NULL)
        return;
    char line[320];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    s->def->on_warning(s->def->user, line);
}

static void mpb__set_stalled(mpb__server *s, int stalled)
{
    pthread_mutex_lock(&s->mu);
    s->stalled = stalled;
    if (!stalled) {                 /* the daemon hears of it at once */
        s->announce_now = 1;
        pthread_cond_signal(&s->cond);
    }
    pthread_mutex_unlock(&s->mu);
}

/* An echo came back: the hub relays; if it was stalled, say so once and
 * have every result not yet stored sent at once. */
static void mpb__echo_back(mpb__server *s)
{
    double now = mpb_monotonic_s();
    s->echo_back_s = now;
    if (!s->stalled)
        return;
    mpb__set_stalled(s, 0);
    s->relays_again = 1;
    mpb__warn(s, "the hub relays again after %.1f s: the results it has "
              "not stored go again now", now - s->stalled_since);
}

/* A hub away (killed, restarted, out of reach) is an outage: say so in
 * one line when the link goes and one when it is back, as the daemon
 * does; the results not stored go again then (mpb__resend_due). */
static void mpb__tell_outage(mpb__server *s, const mpb_hub_stats *st,
                             double now)
{
    if (st->connected && s->link_said == 2)
        mpb__warn(s, "the hub is back after %.1f s (connection %ld): the "
                  "results it has not stored go again now",
                  now - s->link_lost_s, st->connects);
    else if (!st->connected && s->link_said != 2) {
        s->link_lost_s = now;
        mpb__warn(s, "%s; trying again every %.1f s, its results wait "
                  "meanwhile", s->link_said == 1 ? "lost the hub"
                  : "cannot reach the hub yet", MPB_HUB_RETRY_S);
    }
    s->link_said = st->connected ? 1 : 2;
}

/* With nothing waiting to be handled (so that an echo received is one
 * handled, however long a solve kept this thread): connected, and none of
 * the heartbeats' echoes back for stall_s, the hub is stalled. The link
 * away is an outage instead (it reconnects, and the results go again), and
 * a new connection's echo is yet to come. Once stalled, only an echo ends
 * it, whatever the link does meanwhile. */
static void mpb__watch_link(mpb__server *s)
{
    if (!s->is_hub || s->stalled)
        return;
    double now = mpb_monotonic_s();
    mpb_hub_stats st;
    mpb_lcm_hub_stats(s->lcm, &st);
    mpb__tell_outage(s, &st, now);
    if (!st.connected || st.connects != s->echo_connects) {
        s->echo_connects = st.connects;
        s->echo_back_s = now;
        return;
    }
    if (now - s->echo_back_s <= s->stall_s)
        return;
    s->stalled_since = s->echo_back_s;
    mpb__set_stalled(s, 1);
    mpb__warn(s, "the hub is stalled: connected, but none of this "
              "planner's heartbeats has come back for %.1f s (a client "
              "that never reads blocks it, docs/topology.md); its results "
              "wait until it relays again", now - s->echo_back_s);
}

/* ---- the loop ---------------------------------------------------------- */

/* Re-send due results; return the seconds until the next one is due.
 * *pending: results not acknowledged that a closing planner waits for.
 * While the hub is stalled nothing is sent and every such result is
 * pending: that time is not the planner's, nor the closing wait's, which
 * begins again when the hub relays again. */
static double mpb__resend_due(mpb__server *s, int *pending)
{
    double now = mpb_monotonic_s(), wait = MPB__POLL_S;
    mpb_hub_stats st;
    /* A hub link connected again: what it sent meanwhile was lost. */
    mpb_lcm_hub_stats(s->lcm, &st);
    int relinked = st.connects != s->hub_connects;
    s->hub_connects = st.connects;
    int again = s->relays_again;
    s->relays_again = 0;
    *pending = 0;
    for (int i = 0; i < MPB__RESULTS_KEPT; i++) {
        mpb__kept *k = &s->kept[i];
        if (!k->used || k->acked)
            continue;
        if (s->stalled) {
            if (now - s->stalled_since < MPB__STALL_CLOSING_MAX_S)
                (*pending)++;
            continue;
        }
        if (relinked || again) {
            k->sends = 0;
            k->next_send_s = now;
        }
        if (again)
            k->first_send_s = now;
        if (k->next_send_s <= now)
            mpb__send(s, k);
        if (now - k->first_send_s < MPB__CLOSING_WAIT_S)
            (*pending)++;
        double w = k->next_send_s - now;
        if (w < wait)
            wait = w;
    }
    return wait < 0 ? 0 : wait;
}

static int mpb__loop(mpb__server *s, volatile sig_atomic_t *stop,
                     char *err, size_t errlen)
{
    int fd = lcm_get_fileno(s->lcm);
    for (;;) {
        if (stop != NULL && *stop)
            return MPB_OK;

        if (s->run_error != MPB_OK) {
            snprintf(err, errlen, "out of memory while answering a run");
            return s->run_error;
        }

        int pending;
        double wait = mpb__resend_due(s, &pending);
        if (s->max_runs > 0 && s->solved >= s->max_runs && pending == 0) {
            int held = 0;
            for (int i = 0; s->stalled && i < MPB__RESULTS_KEPT; i++)
                held += s->kept[i].used && !s->kept[i].acked;
            if (held > 0)
                mpb__warn(s, "the hub has been stalled for %.0f s: stopping "
                          "with %d results not acknowledged, as the daemon "
                          "stops", mpb_monotonic_s() - s->stalled_since, held);
            return MPB_OK;
        }

        fd_set fds;
        FD_ZERO(&fds);
        FD_SET(fd, &fds);
        struct timeval tv;
        tv.tv_sec = 0;
        tv.tv_usec = (suseconds_t)(wait * 1e6);
        int n = select(fd + 1, &fds, NULL, NULL, &tv);
        if (n < 0) {
            if (errno == EINTR)
                continue;
            snprintf(err, errlen, "select on the LCM socket: %s", strerror(errno));
            return MPB_ELCM;
        }
        if (n == 0)
            mpb__watch_link(s);
        if (n > 0 && lcm_handle(s->lcm) != 0) {
            snprintf(err, errlen, "lcm_handle failed");
            return MPB_ELCM;
        }
    }
}

int mpb_planner_serve(const mpb_planner_def *def, const char *lcm_url,
                      volatile sig_atomic_t *stop, long max_runs,
                      char *err, size_t errlen)
{
    char dummy[1];
    if (err == NULL || errlen == 0) {
        err = dummy;
        errlen = sizeof dummy;
    }
    err[0] = '\0';
    if (def == NULL || def->solve == NULL || def->num_algorithms < 0 ||
        def->num_algorithms > INT16_MAX ||
        (def->num_algorithms > 0 && def->algorithms == NULL)) {
        snprintf(err, errlen, "planner definition lacks a solve function "
                 "or its algorithms");
        return MPB_EINVAL;
    }
    for (int i = 0; i < def->num_algorithms; i++)
        if (def->algorithms[i] == NULL) {
            snprintf(err, errlen, "algorithm %d is NULL", i);
            return MPB_EINVAL;
        }

    mpb__server *s = calloc(1, sizeof *s);
    if (s == NULL) {
        snprintf(err, errlen, "out of memory");
        return MPB_ENOMEM;
    }
    s->def = def;
    s->max_runs = max_runs;
    s->heartbeat_ms = def->heartbeat_ms > 0 ? def->heartbeat_ms : 500;
    if (s->heartbeat_ms < MPB__ANNOUNCE_GAP_MS)
        s->heartbeat_ms = MPB__ANNOUNCE_GAP_MS;
    int rc = mpb__make_id(s, err, errlen);
    if (rc == MPB_OK && def->secret_file != NULL)
        rc = mpb_auth_open(def->secret_file, &s->auth, err, errlen);
    if (rc != MPB_OK) {
        free(s);
        return rc;
    }

    const char *url = lcm_url != NULL ? lcm_url : MPB_DEFAULT_LCM_URL;
    /* The other planners' requests and acknowledgements, every result,
     * announcement and (without a secret) status, and every malformed
     * datagram: dropped by the kernel, not after a wake-up of LCM's thread
     * in this process (lcm_filter.h). Without the filter the same messages
     * arrive and are ignored, but a malformed datagram can crash LCM's
     * thread. With a secret the daemon's status passes, for the instance
     * to echo (auth.h). */
    const char *mine[] = {s->request_channel, s->ack_channel,
                          MPB_CHANNEL_STATUS};
    int filtered = 0;
    s->lcm = mpb_lcm_create(url, mine, s->auth != NULL ? 3 : 2,
                                    &filtered);
    if (s->lcm == NULL) {
        snprintf(err, errlen, "cannot join LCM at %s (%s)", url,
                 mpb_lcm_url_is_hub(url)
                     ? "a hub's URL is tcpq://HOST:PORT"
                     : "udpm needs a multicast route, e.g. 'ip route add "
                       "224.0.0.0/4 dev lo'");
        mpb_auth_close(s->auth);
        free(s);
        return MPB_ELCM;
    }

    lcm_subscription_t *rsub =
        lcm_subscribe(s->lcm, s->request_channel, mpb__on_request_raw, s);
    lcm_subscription_t *asub =
        lcm_subscribe(s->lcm, s->ack_channel, mpb__on_ack_raw, s);
    /* With a secret, the daemons' status: the instance to echo. */
    lcm_subscription_t *ssub = s->auth == NULL ? NULL :
        lcm_subscribe(s->lcm, MPB_CHANNEL_STATUS, mpb__on_status_raw, s);
    if (rsub == NULL || asub == NULL || (s->auth != NULL && ssub == NULL)) {
        snprintf(err, errlen, "cannot subscribe to LCM channels");
        if (rsub != NULL)
            lcm_unsubscribe(s->lcm, rsub);
        if (asub != NULL)
            lcm_unsubscribe(s->lcm, asub);
        if (ssub != NULL)
            lcm_unsubscribe(s->lcm, ssub);
        mpb_lcm_destroy(s->lcm);
        mpb_auth_close(s->auth);
        free(s);
        return MPB_ELCM;
    }
    if (!filtered && def->on_warning != NULL)
        def->on_warning(def->user, MPB_LCM_UNFILTERED);
    /* Through a hub, the link connects in the background: a moment for
     * it, so that the first announcement is not lost. */
    mpb_lcm_hub_wait(s->lcm, 2.0);
    mpb_hub_stats st;
    mpb_lcm_hub_stats(s->lcm, &st);
    s->is_hub = st.is_hub;
    s->stall_s = 3.0 * s->heartbeat_ms / 1000.0;
    if (s->stall_s < MPB__ECHO_MAX_S)
        s->stall_s = MPB__ECHO_MAX_S;
    s->echo_back_s = mpb_monotonic_s();
    s->echo_connects = st.connects;
    lcm_subscription_set_queue_capacity(rsub, MPB__REQUEST_QUEUE);
    lcm_subscription_set_queue_capacity(asub, MPB__ACK_QUEUE);

    pthread_condattr_t ca;
    pthread_condattr_init(&ca);
    pthread_condattr_setclock(&ca, CLOCK_MONOTONIC);
    pthread_mutex_init(&s->mu, NULL);
    pthread_cond_init(&s->cond, &ca);
    pthread_condattr_destroy(&ca);

    /* The heartbeat thread takes no signals: they belong to the caller's
     * thread, where they interrupt select(). */
    sigset_t all, old;
    sigfillset(&all);
    pthread_sigmask(SIG_SETMASK, &all, &old);
    pthread_t hb;
    int trc = pthread_create(&hb, NULL, mpb__heartbeat_main, s);
    pthread_sigmask(SIG_SETMASK, &old, NULL);
    if (trc != 0) {
        snprintf(err, errlen, "cannot start the heartbeat thread: %s",
                 strerror(trc));
        rc = MPB_EERROR;
    } else {
        if (def->on_ready != NULL)
            def->on_ready(def->user, s->id);
        s->stop = stop;
        rc = mpb__loop(s, stop, err, errlen);

        pthread_mutex_lock(&s->mu);
        s->quit = 1;
        pthread_cond_signal(&s->cond);
        pthread_mutex_unlock(&s->mu);
        pthread_join(hb, NULL);
    }

    for (int i = 0; i < MPB__RESULTS_KEPT; i++)
        if (s->kept[i].used)
            mpb_result_clear(&s->kept[i].res);
    lcm_unsubscribe(s->lcm, rsub);
    lcm_unsubscribe(s->lcm, asub);
    if (ssub != NULL)
        lcm_unsubscribe(s->lcm, ssub);
    mpb_lcm_destroy(s->lcm);
    pthread_cond_destroy(&s->cond);
    pthread_mutex_destroy(&s->mu);
    mpb_auth_close(s->auth);
    free(s);
    return rc;
}

int mpb_request_hold(const mpb_plan_request_t *req, struct mpb_world *w,
                     struct mpb_robot *r, char *err, size_t errlen)
{
    if (err && errlen)
        err[0] = '\0';
    if (req == NULL || req->num_held < 0)
        return MPB_EINVAL;
    if (req->num_held == 0)
        return MPB_OK;
    if (req->held_names == NULL || req->held_values == NULL)
        return MPB_EINVAL;
    if (w != NULL) {
        int rc = mpb_world_hold(w, (const char *const *)req->held_names,
                                req->held_values, req->num_held, err, errlen);
        if (rc != MPB_OK)
            return rc;
    }
    for (int i = 0; r != NULL && i < req->num_held; i++) {
        int rc = mpb_robot_set_passive(r, req->held_names[i],
                                       req->held_values[i]);
        if (rc != MPB_OK) {
            if (err && errlen)
                snprintf(err, errlen, "joint '%s' cannot be held at %g",
                         req->held_names[i], req->held_values[i]);
            return rc;
        }
    }
    return MPB_OK;
}
