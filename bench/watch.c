/*
 * watch.c - mpb-bench-watch: the latency of each run, end to end, seen from
 * the outside. Listens (never sends) to a running benchmark's requests,
 * results and acknowledgements and, for each run, takes the daemon's own
 * timestamps: the request's utime (first send) and the utime of the
 * message that acknowledges the result as stored, which mpbenchd sends
 * only after the commit: a RESULT_STORED alone, or a later request that
 * lists the run in `stored` (docs/protocol.md). The planner's result utime
 * splits the time into "out and back" (request to result published) and
 * "daemon" (result published to acknowledged).
 *
 * With a quick planner the acknowledgement rides on the request after the
 * next, so this is the time until the planner hears that its result is
 * stored, a run longer than until the commit; mpbenchd counts request to
 * commit itself (its log's last lines). And a listener is one more process
 * woken by every message: on a small machine it slows what it watches.
 *
 * Run it only inside a private network namespace (bench/run.sh does).
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lcm/lcm.h>

#include "mpbench/mpbench.h"
#include "mpb_plan_request_t.h"
#include "mpb_plan_result_t.h"
#include "mpb_run_ack_t.h"

#include "bench_util.h"

typedef struct entry {
    char    id[MPB_ATTEMPT_ID_SIZE];
    int64_t request;        /* daemon's utime of the first request seen */
    int64_t result;         /* planner's utime of the first result seen */
    int     done;
} entry;

typedef struct watch {
    entry  *table;
    size_t  mask;
    long    want, done, unmatched;
    long    skip, skipped;                /* acks not counted, first */
    double *total, *out_back, *daemon;   /* us, per run, in ack order */
    /* Time between the first sends of consecutive runs: with one planner,
     * the whole cost of a run as the planner sees it. */
    long    requests, ncycles;
    int64_t last_request;
    double *cycle;
} watch;

static void usage(FILE *out)
{
    fprintf(out,
"usage: mpb-bench-watch --runs N [--skip K] [--timeout S] [--url URL]\n"
"                       [--samples FILE]\n"
"\n"
"Listens to a running mpbench benchmark and prints, over its next N runs,\n"
"the median and p99 of each run's time from request (first send) to the\n"
"daemon's acknowledgement of its result (sent after the commit: alone, or\n"
"on a later request), with the daemon's own timestamps; and its two\n"
"parts, up to the planner's result\n"
"and after it; and the time from one run's request to the next one's (with\n"
"one planner, what a run costs the planner). The first K runs are not\n"
"counted (warm-up). Sends nothing. Exits after N runs or S seconds\n"
"(default 600). --samples writes total, out_back, daemon (us) per run.\n");
}

static entry *slot(watch *w, const char *id, int insert)
{
    uint64_t h = 1469598103934665603ull;
    for (const char *p = id; *p; p++)
        h = (h ^ (unsigned char)*p) * 1099511628211ull;
    for (size_t i = h & w->mask;; i = (i + 1) & w->mask) {
        entry *e = &w->table[i];
        if (e->id[0] == '\0') {
            if (!insert)
                return NULL;
            snprintf(e->id, sizeof e->id, "%s", id);
            return e;
        }
        if (strcmp(e->id, id) == 0)
            return e;
    }
}

/* The result of run id was acknowledged as stored at utime. */
static void acknowledged(watch *w, const char *id, int64_t utime)
{
    if (w->done >= w->want || !mpb_attempt_id_is_valid(id))
        return;
    entry *e = slot(w, id, 0);
    if (e == NULL || e->request == 0) {
        w->unmatched++;     /* sent before we listened */
    } else if (!e->done && w->skipped < w->skip) {
        e->done = 1;
        w->skipped++;
    } else if (!e->done) {
        e->done = 1;
        w->total[w->done] = (double)(utime - e->request);
        w->out_back[w->done] = e->result ? (double)(e->result - e->request)
                                         : NAN;
        w->daemon[w->done] = e->result ? (double)(utime - e->result) : NAN;
        w->done++;
    }
}

static void on_request(const lcm_recv_buf_t *rbuf, const char *channel,
                       void *user)
{
    watch *w = user;
    mpb_plan_request_t m;
    (void)channel;
    if (!mpb_wire_check(MPB_WIRE_PLAN_REQUEST, rbuf->data, rbuf->data_size,
                        NULL, 0) ||
        mpb_plan_request_t_decode(rbuf->data, 0, (int)rbuf->data_size, &m) < 0)
        return;
    /* Keep the table at most half full. */
    if (mpb_attempt_id_is_valid(m.attempt_id) &&
        (size_t)w->requests < w->mask / 2) {
        entry *e = slot(w, m.attempt_id, 1);
        if (e->request == 0) {
            e->request = m.utime;
            if (w->requests++ > w->skip && w->ncycles < w->want)
                w->cycle[w->ncycles++] = (double)(m.utime - w->last_request);
            w->last_request = m.utime;
        }
    }
    for (int i = 0; i < m.num_stored; i++)
        acknowledged(w, m.stored[i], m.utime);
    mpb_plan_request_t_decode_cleanup(&m);
}

static void on_result(const lcm_recv_buf_t *rbuf, const char *channel,
                      void *user)
{
    watch *w = user;
    mpb_plan_result_t m;
    (void)channel;
    if (!mpb_wire_check(MPB_WIRE_PLAN_RESULT, rbuf->data, rbuf->data_size,
                        NULL, 0) ||
        mpb_plan_result_t_decode(rbuf->data, 0, (int)rbuf->data_size, &m) < 0)
        return;
    entry *e = mpb_attempt_id_is_valid(m.attempt_id) ? slot(w, m.attempt_id, 0) : NULL;
    if (e != NULL && e->result == 0)
        e->result = m.utime;
    mpb_plan_result_t_decode_cleanup(&m);
}

static void on_ack(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    mpb_run_ack_t m;
    (void)channel;
    if (!mpb_wire_check(MPB_WIRE_RUN_ACK, rbuf->data, rbuf->data_size, NULL, 0)
        || mpb_run_ack_t_decode(rbuf->data, 0, (int)rbuf->data_size, &m) < 0)
        return;
    if (m.kind == MPB_RUN_ACK_T_RESULT_STORED)
        acknowledged(user, m.attempt_id, m.utime);
    mpb_run_ack_t_decode_cleanup(&m);
}

static void summary(const char *key, const char *what, double *v, long n)
{
    long k = 0;
    for (long i = 0; i < n; i++)
        if (!isnan(v[i]))
            v[k++] = v[i];
    mpbb_sort(v, (size_t)k);
    printf("  %-34s median %8.1f us  p90 %8.1f us  p99 %8.1f us  max %9.1f us\n",
           what, mpbb_quantile(v, k, 0.5), mpbb_quantile(v, k, 0.9),
           mpbb_quantile(v, k, 0.99), k ? v[k - 1] : NAN);
    mpbb_result("%s n=%ld median_us=%.2f p90_us=%.2f p99_us=%.2f max_us=%.2f "
                "mean_us=%.2f", key, k, mpbb_quantile(v, k, 0.5),
                mpbb_quantile(v, k, 0.9), mpbb_quantile(v, k, 0.99),
                k ? v[k - 1] : NAN, mpbb_mean(v, k));
}

int main(int argc, char **argv)
{
    const char *url = MPB_DEFAULT_LCM_URL, *samples = NULL;
    long runs = 0, skip = 0;
    double timeout = 600;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--help") == 0) {
            usage(stdout);
            return 0;
        }
        if (v == NULL) {
            usage(stderr);
            return 2;
        }
        i++;
        if (strcmp(a, "--runs") == 0) runs = atol(v);
        else if (strcmp(a, "--timeout") == 0) timeout = atof(v);
        else if (strcmp(a, "--skip") == 0) skip = atol(v);
        else if (strcmp(a, "--url") == 0) url = v;
        else if (strcmp(a, "--samples") == 0) samples = v;
        else {
            usage(stderr);
            return 2;
        }
    }
    if (runs <= 0 || skip < 0 || !(timeout > 0)) {
        usage(stderr);
        return 2;
    }

    watch w = {.want = runs, .skip = skip};
    size_t cap = 1024;
    while (cap < 4 * (size_t)(runs + skip))
        cap *= 2;
    w.table = calloc(cap, sizeof *w.table);
    w.mask = cap - 1;
    w.total = calloc((size_t)runs, sizeof(double));
    w.out_back = calloc((size_t)runs, sizeof(double));
    w.daemon = calloc((size_t)runs, sizeof(double));
    w.cycle = calloc((size_t)runs, sizeof(double));
    if (!w.table || !w.total || !w.out_back || !w.daemon || !w.cycle) {
        fprintf(stderr, "mpb-bench-watch: out of memory\n");
        return 1;
    }
    lcm_t *lcm = lcm_create(url);
    if (lcm == NULL) {
        fprintf(stderr, "mpb-bench-watch: cannot start LCM on %s\n", url);
        return 1;
    }
    lcm_subscription_t *s1 = lcm_subscribe(lcm, MPB_CHANNEL_REQUEST_PREFIX ".*",
                                           on_request, &w);
    lcm_subscription_t *s2 = lcm_subscribe(lcm, MPB_CHANNEL_RESULT, on_result, &w);
    /* The daemon's acknowledgements, on MPB_ACK_<planner> (and on MPB_ACK
     * from mpbench before they moved there, to compare versions). */
    lcm_subscription_t *s3 = lcm_subscribe(lcm, MPB_CHANNEL_ACK ".*", on_ack, &w);
    /* A listener must not lose messages to a short queue. */
    lcm_subscription_set_queue_capacity(s1, 10000);
    lcm_subscription_set_queue_capacity(s2, 10000);
    lcm_subscription_set_queue_capacity(s3, 10000);
    printf("mpb-bench-watch: listening\n");
    fflush(stdout);

    double deadline = mpbb_now() + timeout;
    while (w.done < w.want && mpbb_now() < deadline)
        lcm_handle_timeout(lcm, 100);

    if (samples != NULL) {
        FILE *f = fopen(samples, "w");
        for (long i = 0; f && i < w.done; i++)
            fprintf(f, "%.0f %.0f %.0f\n", w.total[i], w.out_back[i],
                    w.daemon[i]);
        if (f)
            fclose(f);
    }
    printf("per-run latency over %ld runs (%ld acks unmatched)%s:\n", w.done,
           w.unmatched, w.done < w.want ? " (TIMED OUT)" : "");
    summary("run_latency", "request -> stored and acked", w.total, w.done);
    summary("run_out_back", "  request -> result published", w.out_back, w.done);
    summary("run_daemon", "  result published -> acked", w.daemon, w.done);
    summary("run_cycle", "request -> next run's request", w.cycle, w.ncycles);
    lcm_unsubscribe(lcm, s1);
    lcm_unsubscribe(lcm, s2);
    lcm_unsubscribe(lcm, s3);
    lcm_destroy(lcm);
    return w.done == w.want ? 0 : 1;
}
