#!/bin/sh
# runs.verify_time (issue 27): the time mpbenchd spends verifying and
# measuring each run's stages is stored, is part of the run's wall_time
# (request to result verified and measured, docs/schema.md), and shows
# in mpb report, text and JSON. A fine --resolution makes verification
# the larger part of a run of the null planner, whose straight line
# takes no time to plan. No check is of speed.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
DB=$work/test.db
mpb=$MPB_BUILD/tools/mpb

mpb_planar_experiment "$work/exp.yaml" "name: verify, runs: 3, time_limit: 5" \
    "{planner: null, algorithms: [straight_line]}"
mpb_spawn "$work/null.log" "$MPB_BUILD/planners/null/mpb-planner-null"
mpb_timeout 120 "$MPB_BUILD/daemon/mpbenchd" --resolution 0.000002 -d "$DB" \
    "$work/exp.yaml" >"$work/daemon.log" 2>&1
status=$?
check "mpbenchd completes the experiment" eq "$status" 0
[ "$status" -eq 0 ] || cat "$work/daemon.log"

check "all 3 runs are done, with a stage each" \
    eq "$(q "SELECT count(*) FROM runs r WHERE state = 'done'
             AND EXISTS (SELECT 1 FROM stages s WHERE s.run_id = r.id)")" 3
check "every finished run has a verify_time > 0" \
    eq "$(q "SELECT count(*) FROM runs WHERE state = 'done' AND verify_time > 0")" 3
check "... inside its wall_time, which ends after verification" \
    eq "$(q "SELECT count(*) FROM runs WHERE wall_time >= verify_time")" 3

"$mpb" report "$DB" >"$work/report.txt" 2>&1
check "mpb report succeeds" eq $? 0
check "... with a row 'verify (Mean, s)' holding a number" \
    grep -Eq '^verify \(Mean, s\) +[0-9]' "$work/report.txt"

"$mpb" report --format json "$DB" >"$work/report.json"
check "mpb report --format json succeeds" eq $? 0
check "... giving verify_time in s, its mean > 0 over the 3 runs" \
    test "$(python3 -c '
import json, sys
r = json.load(open(sys.argv[1]))
m = r["scenes"][0]["planners"][0]["metrics"]["verify_time"]
print(r["units"]["verify_time"], m["n"], m["mean"] > 0)' "$work/report.json")" = "s 3 True"

mpb_finish
