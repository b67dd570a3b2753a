#!/bin/sh
# The same seed gives the same raw trajectory: one OMPL planner process
# serves the same experiment (the PR2 arm over the paper's table, a joint
# goal and an end-effector region goal, RRTConnect, two seeds per query)
# to two daemons in turn, into two databases. Every run's raw waypoints
# must match byte for byte; the two seeds of a query must not.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
exp=$MPB_SOURCE/tests/integration/data/ompl_repeatable.yaml

mpb_spawn "$work/ompl.log" "$MPB_BUILD/planners/ompl/mpb-planner-ompl"

for n in 1 2; do
    mpb_timeout 300 "$MPB_BUILD/daemon/mpbenchd" -d "$work/run$n.db" "$exp" \
        >"$work/daemon$n.log" 2>&1
    status=$?
    check "experiment $n completes" eq "$status" 0
    [ "$status" -eq 0 ] || cat "$work/daemon$n.log"
    DB=$work/run$n.db
    check "experiment $n: all 4 runs solved and verified" \
        eq "$(q "SELECT count(*) FROM runs WHERE success = 1")" 4
    [ "$(q "SELECT count(*) FROM runs WHERE success = 1")" -eq 4 ] ||
        q "SELECT query_id, repetition, status, verdict, message FROM runs" | sed 's/^/# /'
done

# One line per run: query, repetition, seed, raw waypoints in hex.
raw() {
    sqlite3 "$1" "SELECT q.name, r.repetition, r.seed, s.num_waypoints, hex(s.waypoints)
                  FROM runs r JOIN queries q ON q.id = r.query_id
                  JOIN stages s ON s.run_id = r.id AND s.name = 'raw'
                  ORDER BY q.name, r.repetition"
}
raw "$work/run1.db" >"$work/raw1.txt"
raw "$work/run2.db" >"$work/raw2.txt"
check "each database has the raw stage of all 4 runs" \
    test "$(wc -l <"$work/raw1.txt")" -eq 4 -a "$(wc -l <"$work/raw2.txt")" -eq 4
check "the same seed gives the same raw waypoints, run for run" \
    cmp -s "$work/raw1.txt" "$work/raw2.txt"
cmp -s "$work/raw1.txt" "$work/raw2.txt" || diff "$work/raw1.txt" "$work/raw2.txt" | cut -c1-120 | sed 's/^/# /'

# Different seeds, different paths: otherwise the check above proves nothing.
DB=$work/run1.db
for query in below_the_table_joints above_centre_region; do
    check "$query: its two runs had different seeds" \
        eq "$(q "SELECT count(DISTINCT r.seed) FROM runs r JOIN queries q ON q.id = r.query_id WHERE q.name = '$query'")" 2
    check "$query: ... and found different raw paths" \
        eq "$(q "SELECT count(DISTINCT hex(s.waypoints)) FROM runs r JOIN queries q ON q.id = r.query_id
                 JOIN stages s ON s.run_id = r.id AND s.name = 'raw' WHERE q.name = '$query'")" 2
done

# The region goal was reached through IK samples, and every stage the
# planner returned passes the daemon's own verification.
check "the region goal's runs sampled at least one goal state" \
    eq "$(q "SELECT count(*) FROM planner_values v JOIN runs r ON r.id = v.run_id
             JOIN queries q ON q.id = r.query_id
             WHERE q.name = 'above_centre_region' AND v.name = 'goal states' AND v.value >= 1")" 2
check "every run returned raw, shortcut and smoothed stages, all valid" \
    eq "$(q "SELECT count(*) FROM stages WHERE valid = 1 AND name IN ('raw', 'shortcut', 'smoothed')")" 12

mpb_finish
