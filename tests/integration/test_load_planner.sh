#!/bin/sh
# mpb-planner-load (planners/load/): the paths of an earlier database are
# answered again, at once, for the same problems, and mpbenchd stores and
# verifies them as any planner's. A first experiment of the null planner
# (seven waypoints on each straight line) makes the database: query a,
# whose line is free, and over_the_pillar, whose line collides. A second
# experiment, on another database, runs the load planner reading the
# first: each of its runs must hold the first's waypoints exactly, and
# mpbenchd's verdicts and metrics on them must equal the first's; a
# query the first database lacks (c) is answered with the straight line
# of two waypoints, verified too. Real daemon, LCM and SQLite.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
SRC=$work/source.db
DB=$work/load.db

two='{name: a, start: [0, 0, 0], goal: [0.3, -0.2, 0.1], tolerance: 0.01}
{name: over_the_pillar, start: [0, 0, 0], goal: [2.6, 0, 0], tolerance: 0.01}'
MPB_QUERIES=$two mpb_planar_experiment "$work/source.yaml" \
    "name: source, runs: 2, time_limit: 5" \
    "{planner: null, algorithms: [straight_line], params: {waypoints: 7}}"
mpb_spawn "$work/null.log" "$MPB_BUILD/planners/null/mpb-planner-null"
mpb_timeout 120 "$MPB_BUILD/daemon/mpbenchd" -d "$SRC" "$work/source.yaml" \
    >"$work/source.log" 2>&1
check "the source experiment completes" eq $? 0
mpb_stop_all
check "... its 4 runs with a stage of 7 waypoints each" \
    eq "$(sqlite3 "$SRC" "SELECT count(*) FROM stages WHERE num_waypoints = 7")" 4
check "... over_the_pillar's line collides there" \
    eq "$(sqlite3 "$SRC" "SELECT count(*) FROM stages s JOIN runs r ON r.id = s.run_id
             JOIN queries q ON q.id = r.query_id
             WHERE q.name = 'over_the_pillar' AND s.verdict = 'collision'")" 2

MPB_QUERIES="$two
{name: c, start: [0, 0, 0], goal: [-0.2, 0.3, 0.1], tolerance: 0.01}" \
    mpb_planar_experiment "$work/load.yaml" "name: load, runs: 3, time_limit: 5" \
    "{planner: load, algorithms: [replay]}"
mpb_spawn "$work/load.log" "$MPB_BUILD/planners/load/mpb-planner-load" \
    --from "$SRC"
mpb_timeout 120 "$MPB_BUILD/daemon/mpbenchd" -d "$DB" "$work/load.yaml" \
    >"$work/daemon.log" 2>&1
status=$?
check "the load experiment completes" eq "$status" 0
[ "$status" -eq 0 ] || { cat "$work/daemon.log" "$work/load.log"; }
check "the load planner read 2 problems with a path" \
    grep -q '2 problems, 2 with a path' "$work/load.log"
check "all 9 runs are done, each with a stored, verified stage" \
    eq "$(q "SELECT count(*) FROM runs r WHERE state = 'done' AND EXISTS
             (SELECT 1 FROM stages s WHERE s.run_id = r.id
              AND s.verdict <> '' AND s.verification IS NOT NULL)")" 9

# One statement each, the source attached (the views above do not last).
both() {
    sqlite3 "$DB" "ATTACH '$SRC' AS src;
        WITH old AS (SELECT q.name AS query, s.* FROM src.stages s
                 JOIN src.runs r ON r.id = s.run_id
                 JOIN src.queries q ON q.id = r.query_id),
             new AS (SELECT q.name AS query, r.id AS run, s.* FROM stages s
                 JOIN runs r ON r.id = s.run_id
                 JOIN queries q ON q.id = r.query_id)
        $1"
}
check "the 6 runs of a and over_the_pillar hold the source's waypoints, bit for bit" \
    eq "$(both "SELECT count(DISTINCT n.run) FROM new n JOIN old o
                ON o.query = n.query AND o.name = n.name
                AND o.waypoints = n.waypoints AND o.num_waypoints = 7")" 6
check "... with the source's verdicts (3 valid, 3 collisions)" \
    test "$(both "SELECT group_concat(v) FROM (SELECT DISTINCT n.run,
                n.verdict || '=' || o.verdict AS v FROM new n JOIN old o
                ON o.query = n.query AND o.name = n.name ORDER BY v)")" = \
    "collision=collision,collision=collision,collision=collision,valid=valid,valid=valid,valid=valid"
check "... and the source's metrics, each to 1e-12" \
    eq "$(sqlite3 "$DB" "ATTACH '$SRC' AS src;
        SELECT count(*) FROM metrics m JOIN runs r ON r.id = m.run_id
            JOIN queries q ON q.id = r.query_id
        WHERE q.name <> 'c' AND NOT EXISTS (SELECT 1 FROM src.metrics sm
            JOIN src.runs sr ON sr.id = sm.run_id
            JOIN src.queries sq ON sq.id = sr.query_id
            WHERE sq.name = q.name AND sm.stage = m.stage AND sm.name = m.name
            AND (sm.value = m.value OR abs(sm.value - m.value) <= 1e-12)
            AND sm.name <> 'time')
            AND m.name <> 'time'")" 0
check "... some metrics compared at all" \
    ge "$(q "SELECT count(*) FROM metrics WHERE name = 'path_length'")" 9
check "query c, not in the source, gets the straight line of 2 waypoints, valid" \
    eq "$(both "SELECT count(*) FROM new WHERE query = 'c' AND num_waypoints = 2
                AND verdict = 'valid'")" 3
check "the load planner's runs are successes where their paths are valid" \
    eq "$(q "SELECT count(*) FROM runs WHERE success = 1")" 6

mpb_finish
