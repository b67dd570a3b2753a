#!/bin/sh
# `mpb import -p` against OMPL 1.5.2's own ompl_benchmark_statistics.py:
# on the same logs they must write the same database, every table and
# view, every column (name, declared type, order) and every cell with its
# SQLite type (tests/tools/same_database.py). The logs: one written by
# OMPL's Benchmark (experiment parameters, three planners, progress, the
# status enum), and one written here with what OMPL's writer seldom
# shows (parameters of every type and with '-' in their names, integers
# past 2^53 up to INT64's limits, nan, inf and empty values, a run and a
# progress property no run measured, two planners with settings, and a
# third with an approximate run, a timed-out one and an incorrect one,
# the cells OMPL leaves empty left empty), and a held-out one written by
# hand (tests/integration/data/heldout.log). Both
# tools also add to each other's databases (-a): a configuration added
# again is one plannerConfigs row, an enum one set of rows.
#
# The script is not part of mpbench: bench/ompl_peer.sh takes it from
# Debian's source package of the installed OMPL into .cache/ompl-peer
# (make deps does too). Without it this test fails: it does not skip.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mpb=$MPB_BUILD/tools/mpb
same="$MPB_SOURCE/tests/tools/same_database.py"

stats=$(sh "$MPB_SOURCE/bench/ompl_peer.sh" "$MPB_SOURCE/.cache/ompl-peer")
check "OMPL's ompl_benchmark_statistics.py is at hand (bench/ompl_peer.sh)" \
    test -n "$stats" -a -s "${stats:-/nonexistent}"
# Debian's python3, which OMPL's package would run it with; it needs no
# module outside Python's own (matplotlib only for its plots).
py=/usr/bin/python3
check "Debian's python3 is installed" test -x "$py"
[ $FAILS -eq 0 ] || { mpb_finish; exit 1; }

"$MPB_BUILD/tests/mpb-test-ompl-log" "$work/wall.log" 5 0.05
check "OMPL's Benchmark wrote a log with experiment parameters" \
    grep -q '^3 experiment properties$' "$work/wall.log"

cat >"$work/edge.log" <<'EOT'
OMPL version 1.5.2
Experiment edge
5 experiment properties
big INTEGER = 9007199254740993
max-speed REAL = 2.5
narrow BOOLEAN = 1
passage width REAL = 1e-3
wall_width REAL = 0.25
Running on host-a
Starting at 2026-01-02 03:04:05
<<<|
a setup
  with blanks 
|>>>
<<<|
CPU: a test
|>>>
18446744073709551615 is the random seed
2.5 seconds per run
512 MB per run
3 runs per planner
12.75 seconds spent to collect the data
1 enum type
status|Unknown status|Invalid start|Invalid goal|Unrecognized goal type|Timeout|Approximate solution|Exact solution|Crash|Abort|Infeasible
3 planners
geometric_RRT
2 common properties
goal_bias = 0.05
range = 0
7 properties for each run
graph states INTEGER
solution length REAL
solved BOOLEAN
status ENUM
time REAL
unmeasured INTEGER
valid segment count INTEGER
3 runs
9007199254740993; 1.5; 1; 6; 0.125; ; -9223372036854775807; 
-9223372036854775808; nan; 0; 4; 2.5; ; 9223372036854775807; 
; inf; 0; 9; 1e-7; ; 10000000000000000; 
4 progress properties for each run
best cost REAL
iterations INTEGER
never REAL
time REAL
3 runs
1.5,10,,0.05,;inf,20,nan,0.1,;
,3,,0.05,;

.
geometric_PRM
1 common properties
max_nearest_neighbors = 8
4 properties for each run
memory REAL
solved BOOLEAN
status ENUM
time REAL
3 runs
0.5; 1; 6; 0.25; 
; 0; 4; 2.5; 
3; 1; 5; 1.0; 
.
geometric_KPIECE1
0 common properties
9 properties for each run
approximate solution BOOLEAN
correct solution BOOLEAN
simplification time REAL
simplified solution length REAL
solution length REAL
solution segments INTEGER
solved BOOLEAN
status ENUM
time REAL
3 runs
1; 1; 0.01; 1.25; 1.5; 4; 0; 5; 2.5; 
; ; ; ; ; ; 0; 4; 2.5; 
0; 0; 0.02; 2.25; 3.5; 7; 1; 6; 0.5; 
.
EOT

# Each case: the script's database and mpb import -p's, from the same
# logs, then compared. $1 names the case, the rest are the logs.
compare() {
    what=$1; shift
    rm -f "$work/ompl.db" "$work/mpb.db"
    "$py" "$stats" -d "$work/ompl.db" "$@" >"$work/ompl.out" 2>&1
    check "$what: OMPL's script reads the logs" test -s "$work/ompl.db"
    "$mpb" import -p "$work/mpb.db" "$@" >/dev/null
    check "$what: mpb import -p reads them" test $? -eq 0
    "$py" "$same" "$work/ompl.db" "$work/mpb.db" >"$work/diff.out"
    check "$what: the same database, every table and every cell" test $? -eq 0
    sed 's/^/# /' "$work/diff.out" | head -n 24
}
compare "OMPL's log" "$work/wall.log"
# A held-out log, written by hand with planners and properties the others
# lack, and REAL texts that SQLite reads otherwise than strtod does
# ("0.814637" is 0.8146370000000001 in the script's cells).
compare "the held-out log" "$MPB_SOURCE/tests/integration/data/heldout.log"
check "... its smoothness as the script stores it, not as strtod reads it" \
    test "$(sqlite3 "$work/mpb.db" "SELECT printf('%!.17g', simplified_solution_smoothness) FROM runs WHERE id = 1")" = 0.81463700000000006
compare "the edge log" "$work/edge.log"
compare "three logs, one twice" "$work/wall.log" "$work/edge.log" "$work/wall.log"

# Adding to the other's database (-a): each tool finds the configurations
# and enums the other wrote.
rm -f "$work/ompl.db" "$work/a.db" "$work/b.db"
"$py" "$stats" -d "$work/ompl.db" "$work/wall.log" "$work/edge.log" \
    "$work/wall.log" >/dev/null 2>&1
"$py" "$stats" -d "$work/a.db" "$work/wall.log" >/dev/null 2>&1
"$mpb" import -p "$work/a.db" -a "$work/edge.log" "$work/wall.log" >/dev/null
check "mpb import -p -a adds to the script's database" test $? -eq 0
"$py" "$same" "$work/ompl.db" "$work/a.db" >"$work/diff.out"
check "... as the script would have" test $? -eq 0
sed 's/^/# /' "$work/diff.out" | head -n 24
"$mpb" import -p "$work/b.db" "$work/wall.log" "$work/edge.log" >/dev/null
"$py" "$stats" -a -d "$work/b.db" "$work/wall.log" >/dev/null 2>&1
"$py" "$same" "$work/ompl.db" "$work/b.db" >"$work/diff.out"
check "the script adds to mpb import -p's database as to its own" test $? -eq 0
sed 's/^/# /' "$work/diff.out" | head -n 24
check "a configuration added again is one row" \
    eq "$(sqlite3 "$work/b.db" "SELECT count(*) FROM plannerConfigs")" 6

# The round trip through an mpbench database: mpb import -d, then mpb
# export --planner-arena gives back the very database the script makes
# of the log, every table and every cell (the log's planner names and
# settings, its columns in its order, its enums, nothing of mpbench's);
# mpb export --ompl-log read by the script keeps every property each log
# had, with its value and SQLite type, as the script stores it from the
# log itself: the experiment's header (date, version, total time, seed,
# memory limit, CPU block, setup, host) and parameters, and every run and
# progress property (its planners are named mpbench's way, and mpbench
# adds properties of its own), the edge log's integers past 2^53
# (INT64_MIN and INT64_MAX among them) exactly, and the properties that
# no run measured (the wall log's progress, the edge log's "unmeasured"
# and "never") as the script's columns of NULLs. The held-out log too
# (first: the edge log's database stays for the checks after).
cp "$MPB_SOURCE/tests/integration/data/heldout.log" "$work/heldout.log"
for log in heldout wall edge; do
    rm -rf "$work/rt.db" "$work/rt-pa.db" "$work/rt-logs" "$work/rt-ompl.db" \
        "$work/ompl.db"
    "$py" "$stats" -d "$work/ompl.db" "$work/$log.log" >/dev/null 2>&1
    "$mpb" import -d "$work/rt.db" "$work/$log.log" >/dev/null &&
        "$mpb" export --planner-arena "$work/rt.db" "$work/rt-pa.db" >/dev/null
    check "$log: import -d, export --planner-arena" test $? -eq 0
    "$py" "$same" "$work/ompl.db" "$work/rt-pa.db" >"$work/diff.out"
    check "$log: ... the script's database of the log, every table and cell" \
        test $? -eq 0
    sed 's/^/# /' "$work/diff.out" | head -n 24
    cp "$work/rt-pa.db" "$work/$log-pa.db"
    "$mpb" export --ompl-log "$work/rt.db" "$work/rt-logs" >/dev/null &&
        "$py" "$stats" -d "$work/rt-ompl.db" "$work/rt-logs"/*.log >/dev/null 2>&1
    check "$log: export --ompl-log, read by OMPL's script" test $? -eq 0
    "$py" "$same" --properties "$work/ompl.db" "$work/rt-ompl.db" \
        >"$work/diff.out"
    check "$log: ... keeps every property of the log, value and type" test $? -eq 0
    sed 's/^/# /' "$work/diff.out" | head -n 24
done
# The edge log's planner and its common properties come back as the log
# wrote them: not "ompl/RRT", nor "algorithm = RRT" in front.
check "a planner's name and settings are the log's lines" test "$(sqlite3 "$work/edge-pa.db" \
    "SELECT name || '|' || settings FROM plannerConfigs WHERE name LIKE '%RRT'")" = "geometric_RRT|goal_bias = 0.05
;range = 0
;"
# A log mpbench wrote (17 significant digits, its own properties and
# enum) reads the same with both tools too.
compare "mpb export --ompl-log's log" "$work"/rt-logs/*.log
check "the header is mpbench's own columns" test "$(sqlite3 "$work/rt.db" \
    "SELECT started, total_time, seed, memory_limit, cpuinfo, host, version
       FROM experiments")" = "2026-01-02 03:04:05|12.75|18446744073709551615|512.0|CPU: a test
|host-a|OMPL 1.5.2"
check "the parameters are kept as written" test "$(sqlite3 "$work/rt.db" \
    "SELECT group_concat(name || ' ' || type || ' = ' || value, ',')
       FROM (SELECT * FROM experiment_params ORDER BY idx)")" = \
    "big INTEGER = 9007199254740993,max-speed REAL = 2.5,narrow BOOLEAN = 1,passage width REAL = 1e-3,wall_width REAL = 0.25"

mpb_finish
