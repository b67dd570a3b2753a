#!/bin/sh
# A verification backlog is bounded (issue 47): with the verifier slowed
# (MPBD_TEST_SLOW_VERIFY, test-only) and --backlog 20, planners answer
# faster than results are verified; the daemon stops sending requests at
# the bound, says so once, sends again as the backlog drains, and stores
# every run once. The memory this bounds is measured by bench/backlog.sh.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; [ -n "${KEEP:-}" ] || rm -rf "$work"' EXIT
DB=$work/test.db
null=$MPB_BUILD/planners/null/mpb-planner-null

mpb_planar_experiment "$work/exp.yaml" "name: backlog, runs: 300, time_limit: 2, runs_per_host: 4" \
    "{planner: null, algorithms: [straight_line], params: {waypoints: 2000}}"
for i in 1 2 3 4; do mpb_spawn "$work/p$i.log" "$null"; done
MPBD_TEST_SLOW_VERIFY=20 mpb_timeout 240 "$MPB_BUILD/daemon/mpbenchd" \
    --backlog 20 -d "$DB" "$work/exp.yaml" >"$work/daemon.log" 2>&1
rc=$?
check "the experiment completes" eq $rc 0
[ $rc -eq 0 ] || tail -5 "$work/daemon.log"
check "the daemon held its requests at the bound, and said so" \
    ge "$(grep -c "await verification, at the bound (--backlog 20" "$work/daemon.log")" 1
check "300 runs, each done once, at its first attempt" \
    eq "$(q "SELECT count(*) FROM runs WHERE state = 'done' AND attempts = 1
             AND status = 'solved'")" 300
check "none crashed while held" eq "$(q 'SELECT coalesce(sum(crashes), 0) FROM runs')" 0
mpb_finish
