#!/bin/sh
# A hub outage changes no stored result (issue 47): the hub (lcm-java's
# TCPService) killed for 2 s and for 15 s mid-run, with retries: 0 and a
# 1 s time limit, so that a run charged with the outage would be late
# (success 0) or a crash. Every run's outcome (status, verdict, success,
# attempts, crashes) equals that of the same experiment run without an
# outage. Runs in flight meanwhile lose their results (the planners
# publish into a link that is away) and have them re-sent once the hub is
# back, past the old limits of 20 request sends and 50 result sends.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_need_hub
mpb_enter_netns "$0" "$@"
mpb_no_multicast

work=$(mktemp -d)
trap 'mpb_stop_all; [ -n "${KEEP:-}" ] || rm -rf "$work"' EXIT
B=$MPB_BUILD
url=tcpq://127.0.0.1:7700
py=$B/planners/python/mpb-planner-python
[ -x "$MPB_SOURCE/.venv/bin/python3" ] || py=""

mpb_spawn_hub "$work/hub.log"
hub=$MPB_HUB_PID
mpb_spawn "$work/null1.log" "$B/planners/null/mpb-planner-null" --lcm-url "$url"
mpb_spawn "$work/null2.log" "$B/planners/null/mpb-planner-null" --lcm-url "$url"
[ -z "$py" ] || mpb_spawn "$work/python.log" "$py" --lcm-url "$url"
# Solved and valid, and failed as asked: two outcomes to keep apart.
mpb_planar_experiment "$work/exp.yaml" "name: outage, runs: 16, time_limit: 1, retries: 0" \
    "{planner: null, algorithms: [straight_line], params: {delay: 0.3}}" \
    "{planner: null, algorithms: [straight_line], name: failing, params: {delay: 0.3, status: failed}}" \
    ${py:+"{planner: python, algorithms: [RRTConnect], runs: 4}"}
total=32
[ -z "$py" ] || total=36

# Each run's outcome, in run order (the same file makes the same ids).
outcomes() {
    sqlite3 "$1" "SELECT planner_config_id, query_id, repetition, state,
        status, verdict, success, attempts, crashes FROM runs
        ORDER BY planner_config_id, query_id, repetition"
}

mpb_timeout 120 "$B/daemon/mpbenchd" --lcm-url "$url" -d "$work/ref.db" \
    "$work/exp.yaml" >"$work/ref.log" 2>&1
check "the experiment completes without an outage" eq $? 0
outcomes "$work/ref.db" >"$work/ref.txt"
check "... $total runs" eq "$(wc -l <"$work/ref.txt")" $total
check "... none crashed, each at its first attempt" \
    eq "$(sqlite3 "$work/ref.db" "SELECT count(*) FROM runs WHERE
        status = 'crash' OR attempts != 1 OR crashes != 0")" 0

for away in 2 15; do
    DB=$work/out$away.db
    mpb_spawn "$work/out$away.log" \
        "$B/daemon/mpbenchd" --lcm-url "$url" -d "$DB" "$work/exp.yaml"
    daemon=$MPB_SPAWNED
    mpb_wait_count "$DB" 6 60 "SELECT count(*) FROM runs WHERE state = 'done'"
    kill -KILL $hub
    wait $hub 2>/dev/null
    sleep $away
    mpb_spawn_hub "$work/hub.log"
    hub=$MPB_HUB_PID
    mpb_wait $daemon 150
    rc=$?
    check "hub away $away s: the experiment completes" eq $rc 0
    [ $rc -eq 0 ] || tail -20 "$work/out$away.log"
    check "... the daemon saw the hub go and come back" \
        grep -q "the hub is back after" "$work/out$away.log"
    check "... a run was in flight across the outage" \
        ge "$(q "SELECT count(*) FROM runs WHERE wall_time > $away")" 1
    outcomes "$DB" >"$work/out$away.txt"
    check "... every run's outcome as without the outage" \
        cmp -s "$work/ref.txt" "$work/out$away.txt"
    cmp -s "$work/ref.txt" "$work/out$away.txt" ||
        diff "$work/ref.txt" "$work/out$away.txt" | head -10
    check "... no planner counted gone" \
        eq "$(grep -c 'is gone' "$work/out$away.log")" 0
done
# The planners, C and Python, say so too: one line as the hub goes, one
# as it is back, for each of the two outages.
for p in null1 null2 ${py:+python}; do
    check "the $p planner says it lost the hub, once an outage" \
        eq "$(grep -c 'lost the hub; trying again every 0\.5 s' "$work/$p.log")" 2
    check "... and that it is back, once an outage" \
        eq "$(grep -c 'the hub is back after' "$work/$p.log")" 2
    check "... and never that it could not reach it at first" \
        eq "$(grep -c 'cannot reach the hub yet' "$work/$p.log")" 0
done
mpb_finish
