#!/bin/sh
# mpbenchd killed with SIGKILL at 10 random moments and restarted on the
# same database: the final set of runs equals that of an uninterrupted
# experiment, each run exactly once.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; [ "$FAILS" -eq 0 ] && rm -rf "$work"' EXIT
daemon=$MPB_BUILD/daemon/mpbenchd
planar=$MPB_SOURCE/scenes/planar
# A scene of its own, to edit between two starts.
cp "$planar/pillars.scene" "$work/pillars.scene"

cat >"$work/exp.yaml" <<EOT
experiment: {name: restarts, runs: 50, time_limit: 2, seed: 3}
robot: {format: planar, file: $planar/arm3.robot}
scenes:
  - name: pillars
    format: planar
    file: $work/pillars.scene
    queries:
      - {name: free, start: [0, 0, 0], goal: [0.3, -0.2, 0.1], tolerance: 0.01}
      - {name: blocked, start: [0, 0, 0], goal: [2.6, 0, 0], tolerance: 0.01}
planners:
  - {planner: null, algorithms: [straight_line], params: {delay: 0.05}}
  - {planner: null, algorithms: [straight_line], params: {delay: 0.03}, name: fast}
EOT

mpb_spawn "$work/p1.log" "$MPB_BUILD/planners/null/mpb-planner-null"
mpb_spawn "$work/p2.log" "$MPB_BUILD/planners/null/mpb-planner-null"

# The reference: the same experiment, never interrupted.
mpb_timeout 120 "$daemon" -d "$work/ref.db" "$work/exp.yaml" >"$work/ref.log" 2>&1
check "the uninterrupted experiment completes" eq $? 0

DB=$work/test.db
kills=0
finished=0
while [ $kills -lt 10 ]; do
    "$daemon" -d "$DB" "$work/exp.yaml" >>"$work/daemon.log" 2>&1 &
    pid=$!
    sleep "0.$(shuf -i 10-70 -n 1)"
    if kill -KILL $pid 2>/dev/null; then
        kills=$((kills + 1))
    else
        finished=1
    fi
    wait $pid 2>/dev/null
    [ $finished -eq 1 ] && break
done
check "the daemon was killed 10 times before it could finish" eq $kills 10
check "the experiment keeps the step it is verified at" \
    test "$(q 'SELECT resolution FROM experiments')" = 0.01
# Resumed at another step, its runs would be verified two ways.
done_before=$(q "SELECT count(*) FROM runs WHERE state = 'done'")
mpb_timeout 30 "$daemon" -d "$DB" -r 0.02 "$work/exp.yaml" >"$work/other_r.log" 2>&1
check "a restart at another --resolution is refused" eq $? 1
check "... saying why, in one line" test "$(cat "$work/other_r.log")" = \
    "mpbenchd: $DB: experiment 'restarts' (id 1) is verified at --resolution 0.01, not 0.02: resume it with that, or start a new one with --new"
check "... and runs nothing" \
    eq "$(q "SELECT count(*) FROM runs WHERE state = 'done'")" "$done_before"
# Resumed against an edited scene, its runs would be verified two ways.
cp "$work/pillars.scene" "$work/pillars.kept"
echo "circle 0.5 0.5 0.1" >>"$work/pillars.scene"
mpb_timeout 30 "$daemon" -d "$DB" "$work/exp.yaml" >"$work/edited.log" 2>&1
check "a restart with the scene file edited is refused" eq $? 1
check "... naming the file, in one line" test "$(cat "$work/edited.log")" = \
    "mpbenchd: $DB: experiment 'restarts' (id 1) began with another scene for scene 'pillars' ($work/pillars.scene has changed since): restore it to resume, or start a new experiment with --new"
check "... and runs nothing" \
    eq "$(q "SELECT count(*) FROM runs WHERE state = 'done'")" "$done_before"
mv "$work/pillars.kept" "$work/pillars.scene"
# An edited experiment file is a new experiment; the old one is named.
sed 's/seed: 3}/seed: 3}  # edited/' "$work/exp.yaml" >"$work/exp2.yaml"
"$daemon" -d "$work/edit.db" "$work/exp.yaml" >/dev/null 2>&1 &
pid=$!
mpb_wait_count "$work/edit.db" 200 10 'SELECT count(*) FROM runs'   # begun
kill -KILL $pid 2>/dev/null
wait $pid 2>/dev/null
mpb_timeout 120 "$daemon" -d "$work/edit.db" "$work/exp2.yaml" >"$work/exp2.log" 2>&1
check "an edited experiment file runs as a new experiment" \
    eq "$(sqlite3 "$work/edit.db" 'SELECT count(*) FROM experiments')" 2
check "... saying that the unfinished one with its name is left" \
    grep -q "experiment 'restarts' (id 1) is unfinished, but its file has changed since: a new one begins" "$work/exp2.log"
"$daemon" -d "$DB" -r 0.5 "$work/exp.yaml" >"$work/coarse.log" 2>&1
check "a step coarser than 0.1 rad is refused" eq $? 2
check "... naming the bound" grep -q "<= 0.1, not '0.5'" "$work/coarse.log"
mpb_timeout 120 "$daemon" -d "$DB" "$work/exp.yaml" >"$work/final.log" 2>&1
check "restarted once more, it completes the experiment" eq $? 0
check "it resumed rather than starting afresh" \
    eq "$(q 'SELECT count(*) FROM experiments')" 1
# (Only the last start is sure to live long enough to say so: a kill
# may come before a slow start, under a sanitizer, has said anything.)
check "it said it was resuming" \
    grep -q "resuming experiment 'restarts' (id 1)" "$work/final.log"

runs="SELECT c.name, q.name, r.repetition, r.seed, r.status, r.success,
             r.verdict, m.value
        FROM runs r JOIN planner_configs c ON c.id = r.planner_config_id
        JOIN queries q ON q.id = r.query_id
        LEFT JOIN metrics m ON m.run_id = r.id AND m.stage = 'raw'
                           AND m.name = 'path_length'
       ORDER BY 1, 2, 3"
sqlite3 "$work/ref.db" "$runs" >"$work/ref.txt"
sqlite3 "$DB" "$runs" >"$work/test.txt"
check "200 runs in each" eq "$(wc -l <"$work/test.txt")" 200
check "the runs equal those of the uninterrupted experiment" \
    cmp -s "$work/ref.txt" "$work/test.txt"
check "each run done once, with one stage" \
    eq "$(q "SELECT count(*) FROM runs r WHERE state != 'done' OR (SELECT count(*) FROM stages s WHERE s.run_id = r.id) != 1")" 0
check "no run crashed" eq "$(q "SELECT count(*) FROM runs WHERE status = 'crash'")" 0

mpb_finish
