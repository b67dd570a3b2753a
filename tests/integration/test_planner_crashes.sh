#!/bin/sh
# Planners killed with SIGKILL 20 times in the middle of runs: every run of
# the experiment is still accounted for exactly once (succeeded or crashed),
# none lost, none duplicated, and the experiment completes.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
DB=$work/test.db
null=$MPB_BUILD/planners/null/mpb-planner-null

# 60 runs of 0.15 s each; a run whose planner dies is retried up to 3 times.
MPB_QUERIES='{name: a, start: [0, 0, 0], goal: [0.3, -0.2, 0.1], tolerance: 0.01}
             {name: b, start: [0, 0, 0], goal: [-0.2, 0.3, 0.2], tolerance: 0.01}' \
mpb_planar_experiment "$work/exp.yaml" \
    "name: crashes, runs: 30, time_limit: 2, retries: 3, runs_per_host: 2" \
    "{planner: null, algorithms: [straight_line], params: {delay: 0.15}}"

"$MPB_BUILD/daemon/mpbenchd" -d "$DB" "$work/exp.yaml" >"$work/daemon.log" 2>&1 &
daemon=$!

# Two planners at a time; every 0.4 s one of them is killed mid-run and a
# new one takes its place, 20 times in all.
"$null" >"$work/p.log" 2>&1 & p1=$!
"$null" >>"$work/p.log" 2>&1 & p2=$!
kills=0
while [ $kills -lt 20 ] && kill -0 $daemon 2>/dev/null; do
    sleep 0.4
    if [ $((kills % 2)) -eq 0 ]; then
        kill -KILL $p1 2>/dev/null; wait $p1 2>/dev/null
        "$null" >>"$work/p.log" 2>&1 & p1=$!
    else
        kill -KILL $p2 2>/dev/null; wait $p2 2>/dev/null
        "$null" >>"$work/p.log" 2>&1 & p2=$!
    fi
    kills=$((kills + 1))
done
MPB_PIDS="$p1 $p2"

# The daemon must finish by itself, within a bound.
mpb_wait $daemon 90
status=$?
check "planners were killed 20 times" eq $kills 20
check "mpbenchd completes the experiment" eq $status 0
[ $status -eq 0 ] || tail -20 "$work/daemon.log"

check "60 runs, each done" eq "$(q "SELECT count(*) FROM runs WHERE state = 'done'")" 60
check "no run is missing" eq "$(q 'SELECT count(*) FROM runs')" 60
check "each run is solved or crashed, nothing else" \
    eq "$(q "SELECT count(*) FROM runs WHERE status NOT IN ('solved', 'crash')")" 0
check "crashed attempts were seen and retried" \
    ge "$(q 'SELECT sum(crashes) FROM runs')" 1
check "each finished run has exactly one stored answer" \
    eq "$(q "SELECT count(*) FROM runs r WHERE status = 'solved' AND (SELECT count(*) FROM stages s WHERE s.run_id = r.id) != 1")" 0
check "a crashed run has no stages" \
    eq "$(q "SELECT count(*) FROM stages s JOIN runs r ON r.id = s.run_id WHERE r.status = 'crash'")" 0
check "every run's result came from the planner it was last sent to" \
    eq "$(q "SELECT count(*) FROM runs WHERE planner_id IS NULL")" 0

mpb_finish
