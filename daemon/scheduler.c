/*
 * scheduler.c - which run goes to which planner, and what happens to a run
 * on the network: resent until the planner acknowledges it, recorded as
 * crashed if its planner goes silent or its deadline passes.
 *
 * With experiment.queue_at_planner above 0 (default 0), a busy planner also
 * holds its next request, so that it starts its next run the moment it
 * ends the last instead of idling while the daemon verifies and stores
 * that one (at the cost of that work overlapping its planning). Such a
 * request is queued: it starts, with its times and deadline, when the run
 * before it on that planner ends, or when the planner announces it is
 * working on it. One its planner never started (declined, or left at one
 * that closed or went away) is taken back: pending again, no attempt and
 * no crash counted.
 *
 * A planner that declines requests although it announces room for them
 * gets none for a while, longer each time (1 s doubling to 60 s). The
 * runs' own state (queues, flights, take-back, crashes) is runs.c's.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "daemon.h"
#include "mpbench/auth.h"
#include "mpbench/lcm_filter.h"
#include "mpb_plan_request_t.h"
#include "mpb_run_ack_t.h"

/* The request for a run of config c on query q, without what changes
 * from one send to the next (utime, attempt_id, planner_id, seed, stored).
 * It points into e. */
static void fill_request(const mpbd_experiment *e, int config, int query,
                         mpb_plan_request_t *rq)
{
    const mpbd_config *c = &e->configs[config];
    const mpbd_query *q = &e->queries[query];
    const mpbd_scene *s = &e->scenes[q->scene];
    *rq = (mpb_plan_request_t){
        .attempt_id = "",
        .planner_id = "",
        .algorithm = c->algorithm,
        .num_params = (int16_t)c->num_params,
        .params = c->params,
        .time_limit = e->time_limit,
        .memory_limit = e->memory_limit,
        .robot_format = s->robot_format,
        .robot_hash = (char *)s->robot_hash,
        .robot = s->robot,
        .scene_format = (char *)mpbd_scene_given_format(s),
        .scene_hash = (char *)mpbd_scene_given_hash(s),
        .scene = (char *)mpbd_scene_given(s),
        .num_joints = (int16_t)e->num_joints,
        .joint_names = e->joint_names,
        .start = q->start,
        .num_held = (int16_t)e->num_held,
        .held_names = e->held_names,
        .held_values = q->held,
        .goal = {
            .kind = MPB_GOAL_T_JOINTS,
            .num_joints = (int16_t)e->num_joints,
            .joints = q->goal,
            .joint_tolerance = q->tolerance,
            .link = "",
        },
    };
    if (q->goal_kind == MPB_GOAL_POSE_REGION) {
        rq->goal = (mpb_goal_t){.kind = MPB_GOAL_T_POSE_REGION,
                                .link = q->goal_link};
        memcpy(rq->goal.position, q->position, sizeof q->position);
        memcpy(rq->goal.position_tolerance, q->position_tolerance,
               sizeof q->position_tolerance);
        memcpy(rq->goal.orientation_rpy, q->rpy, sizeof q->rpy);
        memcpy(rq->goal.orientation_tolerance, q->rpy_tolerance,
               sizeof q->rpy_tolerance);
    }
}

int mpbd_requests_fit(const mpbd_experiment *e, int authenticated, char *err,
                      size_t errlen)
{
    /* The longest a request can be: the longest planner id and a full
     * load of acknowledgements riding on it. The robot and scene text,
     * counted once per scene, stand apart from the rest. */
    static char planner_id[MPB_PLANNER_ID_MAX + 1];
    static char attempt_id[MPB_ATTEMPT_ID_SIZE];
    char *stored[MPBD_STORED_MAX];
    memset(planner_id, 'x', MPB_PLANNER_ID_MAX);
    memset(attempt_id, '0', MPB_ATTEMPT_ID_SIZE - 1);
    for (int i = 0; i < MPBD_STORED_MAX; i++)
        stored[i] = attempt_id;
    for (int q = 0; q < e->num_queries; q++) {
        const mpbd_scene *s = &e->scenes[e->queries[q].scene];
        size_t robot = strlen(s->robot), scene = strlen(mpbd_scene_given(s));
        size_t rest = 0;
        for (int c = 0; c < e->num_configs; c++) {
            mpb_plan_request_t rq;
            fill_request(e, c, q, &rq);
            rq.attempt_id = attempt_id;
            rq.planner_id = planner_id;
            rq.num_stored = MPBD_STORED_MAX;
            rq.stored = stored;
            rq.robot = rq.scene = "";
            size_t n = (size_t)mpb_plan_request_t_encoded_size(&rq);
            if (n > rest)
                rest = n;
        }
        size_t total = rest + robot + scene +
                       (authenticated ? MPB_AUTH_TRAILER_SIZE : 0);
        if (total > MPB_LCM_MESSAGE_MAX) {
            snprintf(err, errlen,
                     "%s: scene '%s' (query '%s'): its plan request would be "
                     "%zu bytes (robot %zu, scene %zu), over the %u-byte "
                     "bound of an LCM message (MPB_LCM_MESSAGE_MAX)",
                     e->file, s->name, e->queries[q].name, total, robot,
                     scene, MPB_LCM_MESSAGE_MAX);
            return MPB_EINVAL;
        }
    }
    return MPB_OK;
}

static int publish_request(mpbd *d, const mpbd_flight *f)
{
    const mpbd_experiment *e = d->exp;
    const mpbd_planner *p = &d->planners[f->planner];
    char channel[sizeof MPB_CHANNEL_REQUEST_PREFIX + MPB_PLANNER_ID_MAX];
    mpb_plan_request_t rq;
    fill_request(e, f->run.config, f->run.query, &rq);
    rq.utime = mpb_utime_now();
    rq.attempt_id = (char *)f->run.attempt_id;
    rq.planner_id = (char *)p->id;
    rq.seed = f->run.seed;
    if (mpb_request_channel(p->id, channel, sizeof channel) != MPB_OK)
        return MPB_EINVAL;
    /* The planner's stored results ride along (acks.c). If this send
     * fails, the planner re-sends those results and is answered again. */
    char stored_ids[MPBD_STORED_MAX][MPB_ATTEMPT_ID_SIZE];
    char *stored[MPBD_STORED_MAX];
    rq.num_stored = (int16_t)mpbd_owed_take(d, p->id, stored_ids, MPBD_STORED_MAX);
    for (int i = 0; i < rq.num_stored; i++)
        stored[i] = stored_ids[i];
    rq.stored = stored;
    d->requested = 1;
    /* In the layout the planner takes (an older one for a planner built
     * before attempt_id). */
    return mpb_publish_request_in(d->lcm, d->auth, p->instance, channel, &rq,
                                  p->layout);
}

/* Send the next run of config c to planner p (to wait in its queue if
 * queued); 0 if there was none. */
static int send_next(mpbd *d, int c, int p, int queued)
{
    mpbd_flight *f = mpbd_runs_send(d, c, p, queued);
    if (f == NULL)
        return 0;
    if (publish_request(d, f) != MPB_OK)
        mpbd_log("could not publish run %s (will resend)", f->run.attempt_id);
    return 1;
}

static void log_waiting(mpbd *d, double now)
{
    if (now - d->last_wait_log < 5.0)
        return;
    for (int c = 0; c < d->exp->num_configs; c++) {
        const mpbd_config *cf = &d->exp->configs[c];
        const mpbd_planner *declining = NULL;
        int offered = 0;
        if (mpbd_runs_waiting(d, c) <= 0)
            continue;
        for (int p = 0; p < d->num_planners && !offered; p++) {
            const mpbd_planner *pl = &d->planners[p];
            if (pl->gone || !mpbd_planner_offers(pl, cf->planner, cf->algorithm))
                continue;
            if (now < pl->declined_until && !pl->closing)
                declining = pl;
            else
                offered = 1;
        }
        if (!offered && declining != NULL) {
            mpbd_log("%s: waiting for a planner '%s' offering '%s' (%d runs): "
                     "%s declined its last %d request%s; next try in %.0f s",
                     cf->name, cf->planner, cf->algorithm,
                     mpbd_runs_waiting(d, c), declining->id,
                     declining->declines, declining->declines == 1 ? "" : "s",
                     declining->declined_until - now);
            d->last_wait_log = now;
        } else if (!offered) {
            mpbd_log("%s: waiting for a planner '%s' offering '%s' "
                     "(%d runs)", cf->name, cf->planner, cf->algorithm,
                     mpbd_runs_waiting(d, c));
            d->last_wait_log = now;
        }
    }
}

/* Runs in flight on the planners of one host. */
static int host_active(const mpbd *d, const char *host)
{
    int n = 0;
    for (int p = 0; p < d->num_planners; p++)
        if (strcmp(d->planners[p].host, host) == 0)
            n += d->planners[p].active;
    return n;
}

/* What a planner has room for now: START a run, QUEUE one behind its
 * runs in flight (experiment queue_at_planner), or NONE. An idle planner
 * held back by its host's limit gets none: a request would start. */
enum room { ROOM_NONE, ROOM_START, ROOM_QUEUE };

static enum room room(const mpbd *d, const mpbd_planner *pl, double now)
{
    if (pl->gone || pl->closing || now < pl->declined_until)
        return ROOM_NONE;
    if (mpbd_planner_busy(d, (int)(pl - d->planners)) < pl->capacity)
        return host_active(d, pl->host) < d->exp->runs_per_host
                   ? ROOM_START : ROOM_NONE;
    return pl->queued < d->exp->queue_at_planner ? ROOM_QUEUE : ROOM_NONE;
}

/* The planner to take config c's next run: one that can start it, else
 * one that can queue it; the search starts after the planner that took
 * the last run, so that planners alike share the runs. -1: none. */
static int pick_planner(const mpbd *d, int c, double now, int *queued)
{
    const mpbd_config *cf = &d->exp->configs[c];
    int np = d->num_planners, queue_at = -1;
    for (int k = 0; k < np; k++) {
        int p = (d->next_planner + k) % np;
        const mpbd_planner *pl = &d->planners[p];
        enum room r = room(d, pl, now);
        if (r == ROOM_NONE ||
            !mpbd_planner_offers(pl, cf->planner, cf->algorithm))
            continue;
        if (r == ROOM_START) {
            *queued = 0;
            return p;
        }
        if (queue_at < 0)
            queue_at = p;
    }
    *queued = 1;
    return queue_at;
}

/* One run at a time, to the configurations in turn (and to the planners
 * in turn within one), whichever planner is free: each configuration
 * advances at the same pace, even when its planners share a host's slot,
 * so that an experiment stopped part-way is balanced. */
/* Too many results wait for the verifier: no request goes out (each
 * would bring one more) until they drain below the bounds. */
static int backlog_full(mpbd *d)
{
    int n = mpbd_verifier_pending(d);
    double bytes = mpbd_verifier_bytes(d);
    int full = (d->backlog.max > 0 && n >= d->backlog.max) ||
               (d->backlog.bytes_max > 0 && bytes >= d->backlog.bytes_max);
    double t = mpb_monotonic_s();
    if (full && !d->backlog.held && t - d->backlog.logged >= 10.0 &&
        (d->backlog.logged = t) > 0)
        mpbd_log("%d results (%.0f MB) await verification, at the bound "
                 "(--backlog %ld, --backlog-mb %.0f): no request goes out "
                 "until they drain", n, bytes / 1048576.0, d->backlog.max,
                 d->backlog.bytes_max / 1048576.0);
    if (!full && d->backlog.held && d->verbose)
        mpbd_log("the verification backlog drained to %d results: "
                 "requests go out again", n);
    d->backlog.held = full;
    return full;
}

int mpbd_scheduler_dispatch(mpbd *d, double now)
{
    int sent = 0, nc = d->exp->num_configs;
    if (d->runs.total_pending > 0 && backlog_full(d))
        return 0;
    while (d->runs.total_pending > 0) {
        int got = 0;
        for (int k = 0; k < nc && !got; k++) {
            int c = (d->next_config + k) % nc, p, queued;
            if (mpbd_runs_waiting(d, c) <= 0 ||
                (p = pick_planner(d, c, now, &queued)) < 0)
                continue;
            if ((got = send_next(d, c, p, queued))) {
                d->next_config = (c + 1) % nc;
                d->next_planner = (p + 1) % d->num_planners;
            }
        }
        if (!got)
            break;
        sent++;
    }
    if (d->runs.total_pending > 0)
        log_waiting(d, now);
    return sent;
}

static void resend(mpbd *d, mpbd_flight *f, double now);

void mpbd_scheduler_tick(mpbd *d, double now)
{
    for (int i = 0; i < d->runs.num_flights;) {
        mpbd_flight *f = &d->runs.flights[i];
        const mpbd_planner *p = &d->planners[f->planner];
        if (p->gone) {
            if (f->queued)
                mpbd_take_back(d, f, "its planner went silent before "
                                     "starting it");
            else
                mpbd_record_crash(d, f, "planner went silent during the run");
            continue; /* f now holds another flight */
        }
        if (f->queued) {
            i++;
            continue;
        }
        /* A planner that holds other requests may be planning one of them
         * before it re-sends a lost result of this run. */
        double deadline = f->deadline;
        if (p->queued > 0 || mpbd_planner_busy(d, f->planner) > p->capacity)
            deadline += d->exp->time_limit;
        if (now > deadline && !mpbd_hub_unproven(d, now)) {
            char why[sizeof MPB_CHANNEL_REQUEST_PREFIX + MPB_PLANNER_ID_MAX + 128];
            if (f->acked)
                snprintf(why, sizeof why,
                         "no result within the time limit and grace");
            else
                snprintf(why, sizeof why, "request never acknowledged (%d "
                         "sends): is the planner subscribed to %s%s?",
                         f->sends, MPB_CHANNEL_REQUEST_PREFIX, p->id);
            mpbd_runs_abandon(d, f);
            mpbd_record_crash(d, f, why);
            continue;
        }
        /* Not while the hub is away: such a send is lost, and the first
         * after it comes back goes at once (mpbd_scheduler_relink). */
        if (!f->acked && !mpbd_hub_down(d) && now >= f->next_send)
            resend(d, f, now);
        i++;
    }
}

/* Re-send a request not acknowledged: the planner may start on this copy,
 * so its time starts again here; the next waits twice as long. */
static void resend(mpbd *d, mpbd_flight *f, double now)
{
    double wait = MPBD_REQUEST_RESEND_S * (double)(1 << (f->sends < 5 ? f->sends : 5));
    f->last_send = now;
    f->away = 0;
    f->sends++;
    f->next_send = now + fmin(wait, MPBD_REQUEST_RESEND_MAX_S);
    publish_request(d, f);
}

static void hold_clocks(mpbd *d, double secs)
{
    for (int i = 0; i < d->num_planners; i++)
        d->planners[i].last_seen += secs;
    for (int i = 0; i < d->runs.num_flights; i++)
        d->runs.flights[i].deadline += secs;   /* INFINITY stays so */
}

void mpbd_scheduler_pause(mpbd *d, double secs)
{
    hold_clocks(d, secs);
    for (int i = 0; i < d->runs.num_flights; i++)
        if (!d->runs.flights[i].queued)
            d->runs.flights[i].away += secs;
}

void mpbd_scheduler_relink(mpbd *d, double now)
{
    for (int i = 0; i < d->num_planners; i++)
        if (!d->planners[i].gone)
            d->planners[i].relinked = now;
    for (int i = 0; i < d->runs.num_flights; i++)
        if (!d->runs.flights[i].acked && !d->runs.flights[i].queued)
            d->runs.flights[i].next_send = now;
}

void mpbd_planner_heard(mpbd *d, int planner, double now)
{
    mpbd_planner *p = &d->planners[planner];
    if (p->relinked <= 0)
        return;
    for (int i = 0; i < d->runs.num_flights; i++) {
        mpbd_flight *f = &d->runs.flights[i];
        if (f->planner != planner || f->queued)
            continue;
        double since = fmax(p->relinked, f->last_send);
        if (now > since) {
            f->away += now - since;
            f->deadline += now - since;
        }
        /* What it finished while away it answers from its kept results;
         * what it still plans it acknowledges again. An acknowledged
         * request's time does not start again. */
        if (f->acked)
            publish_request(d, f);
        else
            resend(d, f, now);
    }
    p->relinked = 0;
}

void mpbd_scheduler_stalled(mpbd *d, double secs)
{
    /* The hub away or stalled (its publishing blocks the loop): network
     * time, logged once by hub.c. */
    if (mpbd_hub_down(d)) {
        mpbd_scheduler_pause(d, secs);
        return;
    }
    /* Not network time: what planners sent meanwhile carries the
     * kernel's receive time, so runs are timed as they ran. */
    hold_clocks(d, secs);
    mpbd_log("read no message for %.1f s (stopped, its machine "
             "suspended, or busy): planners' silence and runs' deadlines "
             "are counted without that time", secs);
}

/* A planner declined a request: it goes to another. A planner declines
 * only when closing, and then announces capacity 0; one that has not (or
 * not yet) gets no request for a while, 1 s doubling to 60 s, so that one
 * that declines everything does not have the daemon send it a request and
 * take it back, with two log lines, every heartbeat for ever. */
static void declined(mpbd *d, mpbd_flight *f)
{
    mpbd_planner *p = &d->planners[f->planner];
    long long run = (long long)f->run.id;
    if (!p->closing) {
        double pause = p->declines < 6 ? (double)(1 << p->declines) : 60.0;
        p->declines++;
        p->declined_until = mpb_monotonic_s() + pause;
        if (p->declines == 1)
            mpbd_log("planner %s declined run %lld: no request goes to it "
                     "for %.0f s", p->id, run, pause);
        else
            mpbd_log("planner %s declined run %lld, %d in a row, while it "
                     "announces capacity %d (a planner declines only when "
                     "closing, at capacity 0): no request goes to it for "
                     "%.0f s", p->id, run, p->declines, p->capacity, pause);
    }
    mpbd_take_back(d, f, "its planner declined it");
}

/* A planner acknowledged a request: stop re-sending it. Or it declined
 * it: it goes to another. */
static void on_ack(mpbd *d, const mpb_run_ack_t *m)
{
    mpbd_flight *f;
    if (!mpb_attempt_id_is_valid(m->attempt_id) ||
        (f = mpbd_flight_find(d, m->attempt_id)) == NULL ||
        strcmp(d->planners[f->planner].id, m->sender_id) != 0)
        return;
    mpbd_planner_heard(d, f->planner, mpb_monotonic_s());
    if (m->kind == MPB_RUN_ACK_T_REQUEST_RECEIVED) {
        f->acked = 1;
        d->planners[f->planner].declines = 0;
    } else if (m->kind == MPB_RUN_ACK_T_REQUEST_DECLINED) {
        declined(d, f);
    } else if (m->kind == MPB_RUN_ACK_T_SETTING_UP) {
        mpbd_flight_setting_up(d, f, mpbd_clock(d));
    } else if (m->kind == MPB_RUN_ACK_T_PLANNING) {
        mpbd_flight_planning(d, f, mpbd_clock(d));
    }
}

static void on_ack_raw(const lcm_recv_buf_t *rbuf, const char *channel,
                       void *user)
{
    mpb_run_ack_t m;
    if (!mpbd_receive(user, MPB_WIRE_RUN_ACK, rbuf, channel, &m))
        return;
    on_ack(user, &m);
    mpb_receive_done(MPB_WIRE_RUN_ACK, &m);
}

void mpbd_scheduler_subscribe(mpbd *d)
{
    d->sub_ack = lcm_subscribe(d->lcm, MPB_CHANNEL_ACK, on_ack_raw, d);
}
