#!/bin/sh
# 20 % of UDP packets dropped (iptables' statistic match, inside the test's
# own network namespace): acknowledgements and resends still bring every
# run of the experiment to the database exactly once.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
if [ "$(id -u)" -ne 0 ] || ! command -v iptables >/dev/null; then
    echo "skipped: needs root and iptables"
    echo "0 passed, 0 failed, 1 skipped"
    exit 0
fi
mpb_enter_netns "$0" "$@"
iptables -A INPUT -p udp -m statistic --mode random --probability 0.2 -j DROP

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
DB=$work/test.db

MPB_QUERIES='{name: a, start: [0, 0, 0], goal: [0.3, -0.2, 0.1], tolerance: 0.01}
             {name: b, start: [0, 0, 0], goal: [2.6, 0, 0], tolerance: 0.01}' \
mpb_planar_experiment "$work/exp.yaml" "name: lossy, runs: 100, time_limit: 5, retries: 5" \
    "{planner: null, algorithms: [straight_line]}"
mpb_spawn "$work/null.log" "$MPB_BUILD/planners/null/mpb-planner-null"
mpb_timeout 200 "$MPB_BUILD/daemon/mpbenchd" -d "$DB" "$work/exp.yaml" >"$work/daemon.log" 2>&1
check "the experiment completes despite the losses" eq $? 0
drops=$(iptables -L INPUT -v -x -n | awk '/DROP/ {print $1}')
check "packets were really dropped" ge "${drops:-0}" 20
check "200 runs, each done" eq "$(q "SELECT count(*) FROM runs WHERE state = 'done'")" 200
check "each with exactly one stored answer" \
    eq "$(q "SELECT count(*) FROM runs r WHERE (SELECT count(*) FROM stages s WHERE s.run_id = r.id) != 1")" 0
check "no run was lost to a crash" \
    eq "$(q "SELECT count(*) FROM runs WHERE status = 'crash'")" 0
check "verdicts are as without losses" \
    eq "$(q "SELECT count(*) FROM results WHERE (query = 'a' AND success = 1) OR (query = 'b' AND verdict = 'collision')")" 200

mpb_finish
