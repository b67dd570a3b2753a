#!/bin/sh
# Record and replay: lcm-logger records a live benchmark (the demo's scene,
# OMPL and null planners, fewer runs); mpbenchd --replay rebuilds the
# database from the log alone. Runs, statuses, verdicts, per-stage metrics
# and waypoints must match the live database. A forged result in the log is
# rejected, a truncated log gives a one-line error and keeps what came
# before, and a missing log is named.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
live=$work/live.db
replayed=$work/replayed.db
lcmlog=$work/bench.lcmlog
url="udpm://239.255.76.67:7667?ttl=0"
mpbenchd=$MPB_BUILD/daemon/mpbenchd
planar=$MPB_SOURCE/scenes/planar

# The demo experiment (scenes/experiments/demo.yaml) with 3 runs per query,
# and a null planner that takes its time, so that its runs can be seen in
# flight.
sed -e "s|runs: 10 |runs: 3 |" -e "s|\.\./planar/|$planar/|" \
    -e "s|algorithms: \[straight_line\]|&\n    params: {delay: 0.5}|" \
    "$MPB_SOURCE/scenes/experiments/demo.yaml" >"$work/demo.yaml"
check "the test's experiment has 3 runs per query and a slow null planner" \
    grep -q "runs: 3 " "$work/demo.yaml" && grep -q "delay: 0.5" "$work/demo.yaml"

mpb_spawn "$work/null.log" "$MPB_BUILD/planners/null/mpb-planner-null"
mpb_spawn "$work/ompl.log" "$MPB_BUILD/planners/ompl/mpb-planner-ompl"
lcm-logger -q --lcm-url="$url" "$lcmlog" >"$work/logger.log" 2>&1 &
logger=$!
# The logger is listening once the planners' announcements reach its file.
for i in $(seq 100); do
    [ -s "$lcmlog" ] && break
    sleep 0.1
done
check "lcm-logger records the planners' announcements" test -s "$lcmlog"

"$mpbenchd" -d "$live" "$work/demo.yaml" >"$work/live.log" 2>&1 &
daemon=$!
# Two forged results go on the record too: one for a run id never sent, one
# for a real run in flight from a planner it did not go to.
forge=$MPB_BUILD/tests/mpb-test-forge-result
uid=""
for i in $(seq 100); do
    uid=$(sqlite3 "$live" "SELECT attempt_id FROM runs r JOIN planner_configs c
        ON c.id = r.planner_config_id WHERE c.planner = 'null'
        AND r.state = 'sent' LIMIT 1" 2>/dev/null)
    [ -n "$uid" ] && break
    sleep 0.1
done
check "a run is in flight" test -n "$uid"
check "the live daemon refuses a result for a run id never sent" \
    test "$("$forge" 0123456789abcdef0123456789abcdef null@elsewhere:1)" = "acked rejected"
"$forge" "$uid" null@elsewhere:1 >/dev/null
mpb_wait $daemon 120
check "the live benchmark completes" eq $? 0
check "... having rejected the two forged results" \
    grep -q "(2 rejected messages)" "$work/live.log"
# The daemon's last status ("done") follows every result it stored: once it
# is in the log, so is everything else.
for i in $(seq 100); do
    grep -aq done "$lcmlog" && break
    sleep 0.1
done
kill -INT $logger
wait $logger
mpb_stop_all

"$mpbenchd" --replay "$lcmlog" -d "$replayed" "$work/demo.yaml" >"$work/replay.log" 2>&1
check "the replay succeeds" eq $? 0
[ "$FAILS" -eq 0 ] || cat "$work/replay.log"
check "... rejecting the two forged results in the log, as the live run did" \
    grep -q "14 of 14 runs stored .*, 0 without a result in the log, 2 rejected messages" "$work/replay.log"
check "... the one for a run id no request carried as such" \
    grep -q "rejected result 0123456789abcdef0123456789abcdef from null@elsewhere:1: no such run in flight" "$work/replay.log"
check "... and the other as from the wrong planner" \
    grep -q "rejected result $uid from null@elsewhere:1: sent by a planner the run did not go to" "$work/replay.log"
check "no forged stage reached the replayed database" \
    eq "$(sqlite3 "$replayed" "SELECT count(*) FROM runs WHERE planner_id = 'null@elsewhere:1' OR message = 'forged'")" 0

# Every run as (configuration, query, repetition) with what verification and
# measurement made of it; wall time is left out (it is the log's clock).
runs_of() {
    sqlite3 "$1" "SELECT c.name, q.name, r.repetition, r.seed, r.state,
        r.status, r.claimed_success, r.valid, r.verdict, r.success,
        r.time_total, r.time_other, r.final_stage, r.attempts, r.planner_id
      FROM runs r JOIN planner_configs c ON c.id = r.planner_config_id
      JOIN queries q ON q.id = r.query_id ORDER BY 1, 2, 3"
}
stages_of() {
    sqlite3 "$1" "SELECT c.name, q.name, r.repetition, s.idx, s.name, s.time,
        s.num_waypoints, hex(s.waypoints), s.valid, s.verdict,
        s.verdict_segment
      FROM stages s JOIN runs r ON r.id = s.run_id
      JOIN planner_configs c ON c.id = r.planner_config_id
      JOIN queries q ON q.id = r.query_id ORDER BY 1, 2, 3, 4"
}
metrics_of() {
    sqlite3 "$1" "SELECT c.name, q.name, r.repetition, m.stage, m.name,
        printf('%.17g', m.value)
      FROM metrics m JOIN runs r ON r.id = m.run_id
      JOIN planner_configs c ON c.id = r.planner_config_id
      JOIN queries q ON q.id = r.query_id ORDER BY 1, 2, 3, 4, 5"
}
values_of() {
    sqlite3 "$1" "SELECT c.name, q.name, r.repetition, v.name, v.value
      FROM planner_values v JOIN runs r ON r.id = v.run_id
      JOIN planner_configs c ON c.id = r.planner_config_id
      JOIN queries q ON q.id = r.query_id ORDER BY 1, 2, 3, 4"
}
for what in runs stages metrics values; do
    ${what}_of "$live" >"$work/live.$what"
    ${what}_of "$replayed" >"$work/replayed.$what"
done

# 2 queries x (RRTConnect 3 + RRT 3 + straight_line 1) = 14 runs.
check "the live database holds 14 done runs" \
    eq "$(sqlite3 "$live" "SELECT count(*) FROM runs WHERE state = 'done'")" 14
check "... with stages and metrics to compare" \
    test "$(wc -l <"$work/live.metrics")" -gt 100
check "the replayed database holds the same runs, statuses and verdicts" \
    cmp -s "$work/live.runs" "$work/replayed.runs"
check "... the same stages and waypoints, bit for bit" \
    cmp -s "$work/live.stages" "$work/replayed.stages"
check "... the same metrics per stage" \
    cmp -s "$work/live.metrics" "$work/replayed.metrics"
check "... the same planner values" \
    cmp -s "$work/live.values" "$work/replayed.values"
check "the replayed experiment is finished" \
    eq "$(sqlite3 "$replayed" "SELECT count(*) FROM experiments WHERE finished IS NOT NULL")" 1
check "... under the experiment's own name" \
    test "$(sqlite3 "$replayed" "SELECT name FROM experiments")" = demo
check "wall times come from the log's clock (request to result)" \
    eq "$(sqlite3 "$replayed" "SELECT count(*) FROM runs WHERE NOT (wall_time >= time_total * 0.5 AND wall_time < 60)")" 0
diff "$work/live.runs" "$work/replayed.runs" | head -5

# ---- a run whose planner dies: crashed live, and so in the replay --------
# The log holds no result for it, but the daemon's "done" status: every run
# had ended, so the run without a result had crashed.
mpb_planar_experiment "$work/crash.yaml" \
    "name: crashing, runs: 3, time_limit: 5, retries: 0, seed: 3" \
    "{planner: null, algorithms: [straight_line], params: {delay: 1.0}}"
"$MPB_BUILD/planners/null/mpb-planner-null" >"$work/victim.log" 2>&1 &
victim=$!
lcm-logger -q --lcm-url="$url" "$work/crash.lcmlog" >/dev/null 2>&1 &
logger=$!
for i in $(seq 100); do
    [ -s "$work/crash.lcmlog" ] && break
    sleep 0.1
done
"$mpbenchd" -d "$work/crash-live.db" "$work/crash.yaml" >"$work/crash-live.log" 2>&1 &
daemon=$!
for i in $(seq 100); do
    [ -n "$(sqlite3 "$work/crash-live.db" "SELECT 1 FROM runs WHERE state = 'sent'" 2>/dev/null)" ] && break
    sleep 0.1
done
kill -KILL $victim
wait $victim 2>/dev/null
mpb_spawn "$work/rescuer.log" "$MPB_BUILD/planners/null/mpb-planner-null"
mpb_wait $daemon 60
check "the live experiment with a killed planner completes" eq $? 0
for i in $(seq 100); do
    grep -aq done "$work/crash.lcmlog" && break
    sleep 0.1
done
kill -INT $logger
wait $logger
mpb_stop_all
check "... with one run crashed" \
    eq "$(sqlite3 "$work/crash-live.db" "SELECT count(*) FROM runs WHERE status = 'crash'")" 1
"$mpbenchd" --replay "$work/crash.lcmlog" -d "$work/crash-replayed.db" \
    "$work/crash.yaml" >"$work/crash-replay.log" 2>&1
check "its replay succeeds" eq $? 0
runs_of "$work/crash-live.db" >"$work/crash-live.runs"
runs_of "$work/crash-replayed.db" >"$work/crash-replayed.runs"
check "... with the same runs, the crashed one crashed" \
    cmp -s "$work/crash-live.runs" "$work/crash-replayed.runs"
check "... and says so" \
    grep -q "3 of 3 runs stored (2 succeeded, 1 crashed), 0 without a result" "$work/crash-replay.log"

# A log cut in the middle of an event: one line naming the log and where it
# ends, and the runs before it stored.
size=$(stat -c %s "$lcmlog")
head -c $((size * 2 / 3)) "$lcmlog" >"$work/cut.lcmlog"
"$mpbenchd" --replay "$work/cut.lcmlog" -d "$work/cut.db" "$work/demo.yaml" \
    >"$work/cut.out" 2>"$work/cut.err"
check "a truncated log fails the replay" eq $? 1
check "... with one line naming the log and the byte it breaks at" \
    grep -q "^mpbenchd: $work/cut.lcmlog: truncated or corrupt event at byte [0-9]* (after [0-9]* good events); the runs before it are stored$" "$work/cut.err"
cut_done=$(sqlite3 "$work/cut.db" "SELECT count(*) FROM runs WHERE state = 'done'")
check "... keeping the runs stored before the damage" ge "$cut_done" 1
check "... and not the later ones" test "$cut_done" -lt 14
runs_of "$work/cut.db" | grep '|done|' | sort >"$work/cut.runs"
sort "$work/live.runs" >"$work/live.sorted"
check "... each exactly as in the live database" \
    test -z "$(comm -23 "$work/cut.runs" "$work/live.sorted")"

# A missing log is named.
"$mpbenchd" --replay "$work/nothing.lcmlog" -d "$work/none.db" "$work/demo.yaml" \
    >/dev/null 2>"$work/missing.err"
check "a missing log fails the replay" eq $? 1
check "... naming it" \
    grep -q "^mpbenchd: cannot read log $work/nothing.lcmlog: No such file or directory$" "$work/missing.err"
check "... and creates no database" test ! -e "$work/none.db"

mpb_finish
