#!/bin/sh
# The success rule exists once (outcome.h): mpbenchd decides each run with
# it, and mpb verify, checking every stage again, decides each stored run
# with the same function. On a database of the paper's quick suite (the
# PR2 in its four environments, every query, one run of two OMPL
# planners at a 1 s limit, so that some answer APPROXIMATE or TIMEOUT
# with a path, and of the null planner, which cannot take a pose goal),
# mpb verify agrees with the daemon on every run, and its counts of each
# outcome are the stored ones.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
DB=$work/paper-quick.db
mpb=$MPB_BUILD/tools/mpb

mpb_paper_quick_experiment "$work/exp.yaml"
cat >>"$work/exp.yaml" <<EOT
  - planner: ompl
    algorithms: [RRTConnect, KPIECE1]
  - planner: null
    algorithms: [straight_line]
EOT

mpb_spawn "$work/null.log" "$MPB_BUILD/planners/null/mpb-planner-null"
mpb_spawn "$work/ompl.log" "$MPB_BUILD/planners/ompl/mpb-planner-ompl"
"$MPB_BUILD/daemon/mpbenchd" -d "$DB" "$work/exp.yaml" >"$work/daemon.log" 2>&1 &
mpb_wait $! 240
status=$?
check "the paper's quick suite completes" eq "$status" 0
[ "$status" -eq 0 ] || tail -20 "$work/daemon.log"
check "... every query, three configurations" eq \
    "$(q "SELECT count(*) FROM runs WHERE state = 'done'")" \
    "$(q "SELECT 3 * count(*) FROM queries")"

out=$("$mpb" verify "$DB")
status=$?
check "mpb verify agrees with the daemon on every run: exit 0" eq "$status" 0
[ "$status" -eq 0 ] || printf '%s\n' "$out" | tail -20
# The stored outcomes, counted as mpb verify prints them (runs with
# stages; the null planner's answers to pose goals have none).
stored=$(q "SELECT group_concat(o || ' ' || n, ', ') FROM (
    SELECT w.o, (SELECT count(*) FROM runs r WHERE r.outcome = w.o
                 AND EXISTS (SELECT 1 FROM stages s WHERE s.run_id = r.id)) n, w.k
      FROM (SELECT 'unclaimed' o, 0 k UNION SELECT 'verified', 1
            UNION SELECT 'refused', 2 UNION SELECT 'late', 3
            UNION SELECT 'unclaimed_valid', 4) w ORDER BY w.k)")
check "... its counts of each outcome are the stored ones" test \
    "$(printf '%s\n' "$out" | tail -1)" = \
    "outcomes by the success rule: $stored; 0 runs decided otherwise than stored"
check "... and some runs were verified" test \
    "$(q "SELECT count(*) > 0 FROM runs WHERE outcome = 'verified'")" = 1
check "... every success verified, and only those" eq \
    "$(q "SELECT count(*) FROM runs WHERE (success = 1) != (outcome = 'verified')")" 0

mpb_finish
