#!/bin/sh
# mpb-bench-verifydb (bench/mbmverify.sh's bench): the stored runs of a
# database read back whole (runs, stages, waypoints counted as the
# database holds them), verified again in their stored world (the same
# verdicts; an obstacle added to the stored scene changes them), and
# timed. A corrupt waypoint (NaN), a database without finished runs and
# one that is not mpbench's each give one line and exit 1, nothing timed.
# No timing is checked.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
DB=$work/test.db
daemon=$MPB_BUILD/daemon/mpbenchd
bench=$MPB_BUILD/tests/mpb-bench-verifydb
data=$MPB_SOURCE/tests/support/data

# The folding arm with its SRDF (arm1 may pass through the post): two
# queries, two runs each, of two configurations: 2-waypoint and
# 30-waypoint straight lines, one stage ("raw") a run.
cat >"$work/exp.yaml" <<EOT
experiment: {name: verifydb, runs: 2, time_limit: 5}
robot:
  format: urdf
  file: $data/folding_arm.urdf
  srdf: $data/folding_arm.srdf
  joints: [j1, j2, j3]
scenes:
  - name: empty
    format: moveit-scene
    text: "(empty)\n.\n"
    queries:
      - {name: into_post, start: [0, 0, 0], goal: [0.4636, 0, 0]}
      - {name: fold, start: [0, 0, 0], goal: [0, 0.5, -0.5]}
planners:
  - {planner: null, algorithms: [straight_line], name: two}
  - {planner: null, algorithms: [straight_line], params: {waypoints: 30}, name: thirty}
EOT
mpb_spawn "$work/null.log" "$MPB_BUILD/planners/null/mpb-planner-null"
mpb_timeout 60 "$daemon" -d "$DB" "$work/exp.yaml" >"$work/daemon.log" 2>&1
check "the experiment completes" eq $? 0
mpb_stop_all
check "... 8 runs, 8 stages, 128 waypoints stored" test \
    "$(q 'SELECT count(*) FROM runs') $(q 'SELECT count(*) || " " || sum(num_waypoints) FROM stages')" = \
    "8 8 128"
valid=$(q 'SELECT count(*) FROM stages WHERE valid = 1')

sum=$(md5sum <"$DB")
out=$("$bench" --db "$DB" --seconds 0.05 2>"$work/err")
check "the bench runs: exit 0, nothing on stderr" test "$?:$(cat "$work/err")" = "0:"
res=$(printf '%s\n' "$out" | grep '^RESULT verify_db ')
field() { printf '%s\n' "$res" | tr ' ' '\n' | sed -n "s/^$1=//p"; }
check "... it reports the 8 runs, 8 stages and 128 waypoints" test \
    "$(field runs) $(field finished) $(field stages) $(field waypoints)" = "8 8 8 128"
check "... at the experiment's resolution, in one world" test \
    "$(field resolution) $(field worlds)" = "0.01 1"
check "... every verdict as stored, as many valid" test \
    "$(field same_verdicts) $(field valid)" = "8 $valid"
check "... waypoints per second, each of the three" sh -c \
    'for k in wps verify_wps metrics_wps; do
         printf "%s\n" "$1" | grep -q " $k=[1-9][0-9]*\( \|$\)" || exit 1
     done' _ "$res"
check "... and the same in words" sh -c \
    "printf '%s\n' \"\$1\" | grep -q '^  verify + metrics .* waypoints/s'" _ "$out"
check "the database is only read" test "$(md5sum <"$DB")" = "$sum"

# Both modes in one run, interleaved: a RESULT line each, same verdicts.
out=$("$bench" --db "$DB" --seconds 0.01 --reps 2 --verification both 2>&1)
check "--verification both: a line per mode" test \
    "$(printf '%s\n' "$out" | grep -c '^RESULT verify_db_\(certified\|sampled\) ')" = 2
res=$(printf '%s\n' "$out" | grep '^RESULT verify_db_sampled ')
check "... sampled: every verdict as stored, none certified, 2 reps" test \
    "$(field same_verdicts) $(field certified) $(field reps)" = "8 0 2"
res=$(printf '%s\n' "$out" | grep '^RESULT verify_db_certified ')
check "... certified: every verdict as stored, every stage certified" test \
    "$(field same_verdicts) $(field certified)" = "8 8"
out=$("$bench" --db "$DB" --verification maybe 2>&1)
check "a mode it does not know: one line, exit 2" test "$?:$out" = \
    "2:mpb-bench-verifydb: --verification wants certified, sampled or both, not 'maybe'"

# The runs of into_post verified again in a stored scene with a block on
# their path (arm1 swept at j1 = 0.2, clear of it at the start and the
# goal, and of the runs of fold): only their verdicts change.
cp "$DB" "$work/obstacle.db"
sqlite3 "$work/obstacle.db" "UPDATE scenes SET scene = 'block
* wall
0.588 0.119 0.15
0 0 0 1
1
box
0.05 0.05 0.05
0 0 0
0 0 0 1
0 0 0 0
0
.
'"
res=$("$bench" --db "$work/obstacle.db" --seconds 0.01 | grep '^RESULT ')
check "an obstacle in the stored scene: the 4 runs through it change verdict" \
    test "$(field same_verdicts) $(field stages)" = "4 8"

# A NaN in one waypoint of the stored blob (float64, little-endian).
cp "$DB" "$work/nan.db"
sqlite3 "$work/nan.db" "UPDATE stages SET waypoints =
    substr(waypoints, 1, 24) || X'000000000000F87F' || substr(waypoints, 33)
    WHERE run_id = 3"
out=$("$bench" --db "$work/nan.db" --seconds 0.01 2>&1)
check "a NaN waypoint: exit 1 and one line naming the run, stage and waypoint" \
    test "$?:$out" = \
    "1:mpb-bench-verifydb: $work/nan.db: run 3 stage raw: waypoint 1 holds a value that is not finite (a corrupt trajectory); nothing timed"

# The same experiment without its runs.
cp "$DB" "$work/none.db"
sqlite3 "$work/none.db" "DELETE FROM metrics; DELETE FROM planner_values;
    DELETE FROM progress; DELETE FROM stages; DELETE FROM runs"
out=$("$bench" --db "$work/none.db" 2>&1)
check "no runs: exit 1, one line" test "$?:$out" = \
    "1:mpb-bench-verifydb: $work/none.db: experiment 1 has no finished runs"

# Not mpbench's database; none at all; a bad command line.
sqlite3 "$work/other.db" "CREATE TABLE t(x)"
out=$("$bench" --db "$work/other.db" 2>&1)
check "another program's database: exit 1, one line" test \
    "$?:$(printf '%s\n' "$out" | wc -l)" = "1:1"
out=$("$bench" --db "$work/missing.db" 2>&1)
check "no database: exit 1, one line" test \
    "$?:$(printf '%s\n' "$out" | wc -l)" = "1:1"
"$bench" --db "$DB" --seconds 0 >/dev/null 2>&1
check "--seconds 0: exit 2" eq $? 2

mpb_finish
