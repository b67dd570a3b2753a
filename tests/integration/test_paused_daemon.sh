#!/bin/sh
# A daemon that does not run for a while (SIGSTOP, a suspended machine)
# does not count that time against its planners:
#   1. stopped for longer than its planners' heartbeat window (2 s) and
#      past the deadline of the runs in flight, it finds its planners still
#      there when it continues, and those runs, which ended meanwhile,
#      solved;
#   2. a planner that really died meanwhile is still found gone, and its
#      run goes to the other planner.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
daemon_pid=0
trap 'kill -CONT $daemon_pid 2>/dev/null; mpb_stop_all; rm -rf "$work"' EXIT
daemon=$MPB_BUILD/daemon/mpbenchd
null=$MPB_BUILD/planners/null/mpb-planner-null

# experiment NAME: 4 runs of 2 s each, a time limit of 3 s (a deadline
# 8 s after a request), one retry.
experiment() {
    mpb_planar_experiment "$work/$1.yaml" \
        "name: $1, runs: 4, time_limit: 3, retries: 1, runs_per_host: 2" \
        "{planner: null, algorithms: [straight_line], params: {delay: 2}}"
}

# start NAME: two planners and a daemon; stopped once both plan a run.
start() {
    experiment "$1"
    DB=$work/$1.db
    mpb_spawn "$work/$1-p1.log" "$null"
    first=$MPB_SPAWNED
    mpb_spawn "$work/$1-p2.log" "$null"
    second=$MPB_SPAWNED
    "$daemon" -d "$DB" "$work/$1.yaml" >"$work/$1.log" 2>&1 &
    daemon_pid=$!
    mpb_wait_count "$DB" 2 5 "SELECT count(*) FROM runs WHERE state = 'sent'"
    kill -STOP $daemon_pid
}

# 1. Stopped for 9 s, while both planners plan a run: they answer
# meanwhile, and their runs' deadlines pass.
start stop
sleep 9
kill -CONT $daemon_pid
mpb_wait $daemon_pid 60
check "stop: the experiment completes" eq $? 0
check "stop: every run solved at its first attempt" \
    eq "$(q "SELECT count(*) FROM runs WHERE status = 'solved' AND attempts = 1")" 4
check "stop: no planner was counted gone" \
    test "$(grep -c "is gone" "$work/stop.log")" -eq 0
check "stop: the daemon says it read nothing for that time" \
    grep -q "read no message for 9\.[0-9] s" "$work/stop.log"
mpb_stop_all

# 2. The same, but the first planner is killed, in the middle of its run,
# while the daemon is stopped.
start death
kill -KILL "$first"
sleep 9
kill -CONT $daemon_pid
mpb_wait $daemon_pid 60
check "death: the experiment completes" eq $? 0
check "death: the killed planner is found gone" \
    grep -q "planner null@[^ ]*:$first is gone" "$work/death.log"
check "death: the run it was planning is solved by the other, at its second attempt" \
    eq "$(q "SELECT count(*) FROM runs WHERE status = 'solved' AND attempts = 2
             AND crashes = 1 AND planner_id LIKE 'null@%:$second'")" 1
check "death: the other planner is never counted gone" \
    test "$(grep -c ":$second is gone" "$work/death.log")" -eq 0
check "death: every run solved" \
    eq "$(q "SELECT count(*) FROM runs WHERE status = 'solved'")" 4
mpb_finish
