#!/bin/sh
# A daemon restart spends no run's retries (issue 47): mpbenchd SIGKILLed
# three times mid-run with retries: 1, a planner killed once mid-run
# besides. The runs in flight at each kill are sent again with their ids
# by the restarted daemon: the same attempts, so runs.attempts counts only
# the planner's attempts (1 + its crashes), and the run whose planner was
# killed is retried, not stored as a crash because restarts used up its
# one retry.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; [ -n "${KEEP:-}" ] || rm -rf "$work"' EXIT
DB=$work/test.db
null=$MPB_BUILD/planners/null/mpb-planner-null
daemon=$MPB_BUILD/daemon/mpbenchd

MPB_QUERIES='{name: a, start: [0, 0, 0], goal: [0.3, -0.2, 0.1], tolerance: 0.01}
             {name: b, start: [0, 0, 0], goal: [2.6, 0, 0], tolerance: 0.01}' \
mpb_planar_experiment "$work/exp.yaml" \
    "name: restarts, runs: 15, time_limit: 2, retries: 1, runs_per_host: 2" \
    "{planner: null, algorithms: [straight_line], params: {delay: 0.3}}"
total=30
done_runs() { q "SELECT count(*) FROM runs WHERE state = 'done'"; }

"$null" >"$work/p1.log" 2>&1 & p1=$!
"$null" >"$work/p2.log" 2>&1 & p2=$!
MPB_PIDS="$p1 $p2"

kills=0
in_flight=0
while [ $kills -lt 3 ]; do
    before=$(done_runs 2>/dev/null)
    "$daemon" -d "$DB" "$work/exp.yaml" >>"$work/daemon.log" 2>&1 &
    pid=$!
    # Runs done in this life, so that others are in flight at the kill.
    mpb_wait_count "$DB" $((${before:-0} + 3)) 60 \
        "SELECT count(*) FROM runs WHERE state = 'done'"
    if [ $kills -eq 1 ]; then
        # A planner crash mid-run: its run's one retry.
        kill -KILL $p1; wait $p1 2>/dev/null
        "$null" >>"$work/p1.log" 2>&1 & p1=$!
        MPB_PIDS="$p1 $p2"
        sleep 0.5
    fi
    kill -KILL $pid 2>/dev/null && kills=$((kills + 1))
    wait $pid 2>/dev/null
    in_flight=$((in_flight + $(q "SELECT count(*) FROM runs WHERE state = 'sent'")))
done
check "the daemon was killed 3 times mid-run" eq $kills 3
mpb_timeout 120 "$daemon" -d "$DB" "$work/exp.yaml" >>"$work/daemon.log" 2>&1
rc=$?
check "the same command then completes the experiment" eq $rc 0
[ $rc -eq 0 ] || tail -20 "$work/daemon.log"
check "$total runs, each done once" eq "$(done_runs)" $total
check "runs were in flight at the kills, to be sent again" ge $in_flight 1
check "attempts count the planner's attempts only: 1 + its crashes" \
    eq "$(q 'SELECT count(*) FROM runs WHERE attempts != 1 + crashes')" 0
check "at most the one planner crash was charged to a run" \
    ge 1 "$(q 'SELECT coalesce(sum(crashes), 0) FROM runs')"
check "no run stored as a crash (one planner crash, one retry each)" \
    eq "$(q "SELECT count(*) FROM runs WHERE status = 'crash'")" 0
mpb_finish
