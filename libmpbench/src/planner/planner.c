/* planner.c - a planner process's side of the protocol: announce, answer,
 * re-send until acked (results: result.c; the hub's echo and outages:
 * planner_link.c). */
#include <errno.h>
#include <limits.h>
#include <pthread.h>
#include <signal.h>
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
#include "planner/planner_internal.h"
#include "planner/planner_memory.h"


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
    s->active_told = 0;
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

/* mpb_solve_setting_up(), mpb_solve_planning(): kind, once per run. */
void mpb__tell_phase(void *kit, int kind)
{
    mpb__server *s = kit;
    char run[MPB_ATTEMPT_ID_SIZE];
    pthread_mutex_lock(&s->mu);
    int fresh = s->active[0] != '\0' && !(s->active_told & (1 << kind));
    s->active_told |= 1 << kind;
    s->active_acked = 1;        /* it acknowledges the request too */
    int stalled = s->stalled;
    memcpy(run, s->active, sizeof run);
    pthread_mutex_unlock(&s->mu);
    if (fresh && !stalled)
        mpb__ack(s, run, kind);
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
    res->attempt_id = strdup(req->attempt_id);
    res->planner_id = strdup(s->id);
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
        mpb_solve_limits lim = {.start = mpb_monotonic_s(), .stop = s->stop,
                                .kit = s};
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
            res->attempt_id = strdup(req->attempt_id);
        }
        if (res->planner_id == NULL || strcmp(res->planner_id, s->id) != 0) {
            free(res->planner_id);
            res->planner_id = strdup(s->id);
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
