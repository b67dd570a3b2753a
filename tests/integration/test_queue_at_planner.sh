#!/bin/sh
# With experiment.queue_at_planner: 1, a request waits at each busy
# planner, so the planner starts its next run as it ends the last, not a
# round trip and a commit later. lcm-logger records the traffic:
#   1. with the queue, each run's request is on the network before the
#      previous run's result; without (the default), never; the replay
#      of the log times each run from its start, as the live daemon did;
#   2. a request a closing planner (--max-runs) will not take is declined
#      and given to another planner: no crash, no extra attempt;
#   3. a request left waiting at a planner that is killed is taken back
#      without a crash; only the run it was planning crashes.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
url="udpm://239.255.76.67:7667?ttl=0"
null=$MPB_BUILD/planners/null/mpb-planner-null
python=$MPB_SOURCE/.venv/bin/python3

# experiment NAME RUNS DELAY [SETTINGS]: an experiment file of null runs
# that each last DELAY seconds.
experiment() {
    mpb_planar_experiment "$work/$1.yaml" \
        "name: $1, runs: $2, time_limit: 5, retries: 0${4:+, $4}" \
        "{planner: null, algorithms: [straight_line], params: {delay: $3}}"
}

# For each run but a planner's first: was its request (first send) on the
# network before the result of the planner's run before it? Prints how
# many runs were, and how many were not.
cat >"$work/order.py" <<'EOT'
import sys
import lcm
from mpb import plan_request_t, plan_result_t

requested, answered, last_result, early, late = {}, set(), {}, 0, 0
for n, ev in enumerate(lcm.EventLog(sys.argv[1], "r")):
    if ev.channel.startswith("MPB_REQUEST_"):
        rq = plan_request_t.decode(ev.data)
        requested.setdefault(rq.attempt_id, (n, rq.planner_id))
    elif ev.channel == "MPB_RESULT":
        res = plan_result_t.decode(ev.data)
        if res.attempt_id not in requested or res.attempt_id in answered:
            continue
        answered.add(res.attempt_id)
        sent, planner = requested[res.attempt_id]
        before = last_result.get(planner)
        if before is not None:
            if sent < before:
                early += 1
            else:
                late += 1
        last_result[planner] = n
print(early, late)
EOT

# Record the traffic of one experiment; the daemon's exit status.
record() {
    lcm-logger -q --lcm-url="$url" "$work/$1.lcmlog" >/dev/null 2>&1 &
    logger=$!
    for i in $(seq 100); do
        [ -s "$work/$1.lcmlog" ] && break
        sleep 0.1
    done
    mpb_timeout 120 "$MPB_BUILD/daemon/mpbenchd" -d "$work/$1.db" \
        "$work/$1.yaml" >"$work/$1.log" 2>&1
    status=$?
    sleep 0.3
    kill "$logger"; wait "$logger" 2>/dev/null
    return $status
}

order() {
    PYTHONPATH="$MPB_BUILD/lcmtypes/python" "$python" "$work/order.py" \
        "$work/$1.lcmlog"
}

# 1. 20 runs of 50 ms on one planner: with the queue, and without.
mpb_spawn "$work/null.log" "$null"
experiment queued 20 0.05 "queue_at_planner: 1"
record queued
check "the experiment with a queue completes" eq $? 0
set -- $(order queued)
check "a run's request goes out before the previous result (at least 17 of 19)" \
    ge "${1:-0}" 17
DB=$work/queued.db
check "every run succeeds, each in one attempt" \
    eq "$(q "SELECT count(*) FROM runs WHERE status = 'solved' AND attempts = 1")" 20

# The replay counts a run's wall time from its start too: within a few ms
# of the live one (from its request, it would be a whole run more).
"$MPB_BUILD/daemon/mpbenchd" --replay "$work/queued.lcmlog" -d "$work/replayed.db" \
    "$work/queued.yaml" >"$work/replay.log" 2>&1
check "the replay of the queued experiment completes" eq $? 0
DB=$work/replayed.db
check "... every run solved in one attempt, as live" \
    eq "$(q "SELECT count(*) FROM runs WHERE status = 'solved' AND attempts = 1")" 20
check "... each run's wall time within 25 ms of the live one (at least 18)" \
    ge "$(q "ATTACH '$work/queued.db' AS live;
             SELECT count(*) FROM runs r JOIN live.runs l USING (attempt_id)
             WHERE abs(r.wall_time - l.wall_time) < 0.025")" 18

experiment unqueued 20 0.05
record unqueued
check "the experiment without a queue completes" eq $? 0
set -- $(order unqueued)
check "without, no request goes out before the previous result" eq "${1:-1}" 0
check "... for all 19 runs after the first" eq "${2:-0}" 19
mpb_stop_all

# 2. A planner that closes after 3 runs, and one that stays: without the
# queue (the next request may reach it before it says it is closing) and
# with it (one waits at it while it plans its last run).
for queue in 0 1; do
    experiment closing$queue 30 0.01 "queue_at_planner: $queue"
    "$MPB_BUILD/daemon/mpbenchd" -d "$work/closing$queue.db" \
        "$work/closing$queue.yaml" >"$work/closing$queue.log" 2>&1 &
    daemon=$!
    "$null" --max-runs 3 >"$work/closing_planner$queue.log" 2>&1 &
    closer=$!
    mpb_wait $closer 30
    check "queue $queue: the planner with --max-runs 3 exits by itself" eq $? 0
    mpb_spawn "$work/stays$queue.log" "$null"
    mpb_wait $daemon 60
    check "queue $queue: the experiment completes with the other planner" eq $? 0
    DB=$work/closing$queue.db
    check "queue $queue: the closing planner did 3 runs" \
        eq "$(q "SELECT count(*) FROM runs WHERE planner_id LIKE '%:$closer'")" 3
    check "queue $queue: all 30 succeed, none crashed" \
        eq "$(q "SELECT count(*) FROM runs WHERE status = 'solved' AND crashes = 0")" 30
    check "queue $queue: ... each in one attempt" \
        eq "$(q "SELECT count(*) FROM runs WHERE attempts = 1")" 30
    # It says it by capacity 0, or (its last request on the way as it
    # closed) by declining that request.
    check "queue $queue: the daemon says the planner is closing or declined" \
        grep -Eq "is closing|declined run" "$work/closing$queue.log"
    mpb_stop_all
done

# 3. A planner killed during a run of 1 s, while a request waits at it.
experiment killed 6 1.0 "queue_at_planner: 1"
"$MPB_BUILD/daemon/mpbenchd" -d "$work/killed.db" "$work/killed.yaml" \
    >"$work/killed.log" 2>&1 &
daemon=$!
"$null" >"$work/victim.log" 2>&1 &
victim=$!
DB=$work/killed.db
for i in $(seq 300); do
    [ "$(q "SELECT count(*) FROM runs WHERE state = 'done'" 2>/dev/null)" = 1 ] && break
    sleep 0.05
done
sleep 0.5       # half-way through its second run, the third waiting
kill -KILL $victim; wait $victim 2>/dev/null
mpb_spawn "$work/after.log" "$null"
mpb_wait $daemon 60
check "the experiment completes after the kill" eq $? 0
check "exactly one run crashed: the one being planned" \
    eq "$(q "SELECT count(*) FROM runs WHERE status = 'crash'")" 1
check "the other 5 succeed, none after a crash" \
    eq "$(q "SELECT count(*) FROM runs WHERE status = 'solved' AND crashes = 0")" 5
check "the request that waited was not counted as an attempt" \
    eq "$(q "SELECT sum(attempts) FROM runs")" 6
mpb_finish
