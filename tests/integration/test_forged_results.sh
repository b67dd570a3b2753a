#!/bin/sh
# Forged results: one for a run id that was never sent, one for a real run
# in flight but from a planner the run did not go to. Both are rejected and
# counted; neither reaches the database.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
DB=$work/test.db
forge=$MPB_BUILD/tests/mpb-test-forge-result
planar=$MPB_SOURCE/scenes/planar

cat >"$work/exp.yaml" <<EOT
experiment: {name: forged, runs: 6, time_limit: 5}
robot: {format: planar, file: $planar/arm3.robot}
scenes:
  - name: pillars
    format: planar
    file: $planar/pillars.scene
    queries:
      - {name: a, start: [0, 0, 0], goal: [0.3, -0.2, 0.1], tolerance: 0.01}
planners:
  - {planner: null, algorithms: [straight_line], params: {delay: 0.5}}
EOT
mpb_spawn "$work/null.log" "$MPB_BUILD/planners/null/mpb-planner-null"
"$MPB_BUILD/daemon/mpbenchd" -d "$DB" "$work/exp.yaml" >"$work/daemon.log" 2>&1 &
daemon=$!

# Wait for a run in flight, then forge.
uid=""
for i in $(seq 50); do
    uid=$(q "SELECT run_uid FROM runs WHERE state = 'sent' LIMIT 1" 2>/dev/null)
    [ -n "$uid" ] && break
    sleep 0.1
done
check "a run is in flight" test -n "$uid"

out=$("$forge" 0123456789abcdef0123456789abcdef "null@elsewhere:1")
check "a result for an unknown run id is refused" test "$out" = "acked rejected"
# (Its acknowledgement cannot be told from the one the real planner's result
# may get meanwhile; the log and the database tell what happened.)
"$forge" "$uid" "null@elsewhere:1" >/dev/null
out=$("$forge" "not-a-run-id" "null@elsewhere:1")
check "a malformed run id is refused too" test "$out" = "acked rejected"

mpb_wait $daemon 30
check "the experiment completes" eq $? 0
check "the daemon counted three rejected messages" \
    grep -q "(3 rejected messages)" "$work/daemon.log"
check "it logged each with its reason" \
    eq "$(grep -c 'rejected result' "$work/daemon.log")" 3
check "... the wrong planner's as such" \
    grep -q "rejected result $uid from null@elsewhere:1: sent by a planner the run did not go to" "$work/daemon.log"
check "no forged stage reached the database" \
    eq "$(q "SELECT count(*) FROM stages WHERE name = 'forged'")" 0
check "the attacked run holds the real planner's answer" \
    test "$(q "SELECT planner_id LIKE 'null@%' AND planner_id != 'null@elsewhere:1' AND message != 'forged' FROM runs WHERE run_uid = '$uid'")" = 1
check "all six runs are solved" eq "$(q "SELECT count(*) FROM runs WHERE status = 'solved'")" 6
check "a median latency over the histogram's cap is written as such" \
    grep -q "median over 65536 us" "$work/daemon.log"

mpb_finish
