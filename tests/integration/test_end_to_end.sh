#!/bin/sh
# The walking skeleton, end to end: mpbenchd and two planner processes
# (null, OMPL) as separate processes over LCM UDP multicast in a private
# network namespace; a small experiment; then what the database holds.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
DB=$work/test.db
exp=$MPB_SOURCE/tests/integration/data/small.yaml

mpb_spawn "$work/null.log" "$MPB_BUILD/planners/null/mpb-planner-null"
mpb_spawn "$work/ompl.log" "$MPB_BUILD/planners/ompl/mpb-planner-ompl"

mpb_timeout 120 "$MPB_BUILD/daemon/mpbenchd" -d "$DB" "$exp" >"$work/daemon.log" 2>&1
status=$?
check "mpbenchd completes the experiment and exits 0" eq "$status" 0
[ "$status" -eq 0 ] || cat "$work/daemon.log"

# The daemon's own count of each run's latency, request to commit: every
# run, and never less than the run's wall_time (request to result
# verified and measured).
lat=$(sed -n 's/.*request sent to result committed: median \([0-9]*\) us.*(\([0-9]*\) runs)$/\1 \2/p' "$work/daemon.log")
check "the daemon reports the latency of its 14 runs" eq "${lat#* }" 14
check "... whose median is at least the runs' median wall time" \
    eq "$(q "SELECT ${lat%% *} >= CAST(wall_time * 1e6 AS INTEGER) FROM runs
             ORDER BY wall_time LIMIT 1 OFFSET 6")" 1

# 2 queries x (RRTConnect 3 + RRT 3 + straight_line 1) = 14 runs.
check "all 14 runs exist" eq "$(q 'SELECT count(*) FROM runs')" 14
check "every run is done" eq "$(q "SELECT count(*) FROM runs WHERE state = 'done'")" 14
check "each run has its own run id" \
    eq "$(q 'SELECT count(DISTINCT attempt_id) FROM runs')" 14
check "no run needed a second attempt" \
    eq "$(q 'SELECT count(*) FROM runs WHERE attempts != 1')" 0
check "the experiment is marked finished" \
    eq "$(q 'SELECT count(*) FROM experiments WHERE finished IS NOT NULL')" 1

# The OMPL planner solves both queries, with its three stages.
for algo in RRTConnect RRT; do
    check "ompl/$algo succeeds on every run" \
        eq "$(q "SELECT count(*) FROM results WHERE planner = 'ompl/$algo' AND success = 1")" 6
    check "ompl/$algo reports raw, shortcut and smoothed stages" \
        eq "$(q "SELECT count(*) FROM stages s JOIN runs r ON r.id = s.run_id
                 JOIN planner_configs c ON c.id = r.planner_config_id
                 WHERE c.name = 'ompl/$algo' AND s.name IN ('raw', 'shortcut', 'smoothed')")" 18
done

# The OMPL planner builds the one world once: its first run reports that
# on its own (world_setup_time), outside tau_t, and the report shows it.
check "the OMPL planner reports its one world's setup once" \
    eq "$(q "SELECT count(*) FROM planner_values v JOIN runs r ON r.id = v.run_id
             JOIN planner_configs c ON c.id = r.planner_config_id
             WHERE c.planner = 'ompl' AND v.name = 'world_setup_time' AND v.value >= 0")" 1
"$MPB_BUILD/tools/mpb" report "$DB" | grep -q "^world setup (Mean, s)"
check "... and mpb report shows it in a row of its own" eq $? 0

# The straight line through the pillar is rejected by mpbench's own check,
# although the null planner claims success.
check "the null planner's line through the pillar is a claimed success" \
    eq "$(q "SELECT claimed_success FROM results WHERE planner = 'null/straight_line' AND query = 'over_the_pillar'")" 1
check "... that verification rejects as a collision" \
    eq "$(q "SELECT count(*) FROM results WHERE planner = 'null/straight_line' AND query = 'over_the_pillar' AND verdict = 'collision' AND success = 0")" 1
check "... and its stage says the verdict was proved (certified)" \
    eq "$(q "SELECT count(*) FROM stages s JOIN runs r ON r.id = s.run_id
             JOIN planner_configs c ON c.id = r.planner_config_id
             JOIN queries qu ON qu.id = r.query_id
             WHERE c.name = 'null/straight_line' AND qu.name = 'over_the_pillar'
             AND s.verdict = 'collision' AND s.verification = 'certified'")" 1
check "every valid stage of the planar arm is certified free" \
    eq "$(q "SELECT count(*) FROM stages WHERE valid = 1 AND verification IS NOT 'certified'")" 0
"$MPB_BUILD/tools/mpb" report "$DB" | grep -q "^Collision checks: [1-9][0-9]* stages certified, 0 sampled"
check "... and mpb report counts the certified and sampled stages" eq $? 0
check "the free straight line of small_move succeeds" \
    eq "$(q "SELECT success FROM results WHERE planner = 'null/straight_line' AND query = 'small_move'")" 1

# Metrics: a valid path is never shorter than the straight joint-space line
# from start to goal (2.6 rad for over_the_pillar, within the tolerance).
check "no valid path beats the straight line" \
    eq "$(q "SELECT count(*) FROM results WHERE query = 'over_the_pillar' AND success = 1 AND path_length < 2.6 - 0.02")" 0
check "the straight line's length is exactly sqrt(0.3^2+0.2^2+0.1^2)" \
    eq "$(q "SELECT abs(path_length - 0.374165738677394) < 1e-9 FROM results WHERE planner = 'null/straight_line' AND query = 'small_move'")" 1
check "every stage of every run has a path length and smoothness" \
    eq "$(q "SELECT count(*) FROM stages s WHERE NOT EXISTS (SELECT 1 FROM metrics m WHERE m.run_id = s.run_id AND m.stage = s.name AND m.name = 'path_length') OR NOT EXISTS (SELECT 1 FROM metrics m WHERE m.run_id = s.run_id AND m.stage = s.name AND m.name = 'smoothness')")" 0
check "... and a resampled smoothness, which the report shows" \
    eq "$(q "SELECT count(*) FROM stages s WHERE NOT EXISTS (SELECT 1 FROM metrics m WHERE m.run_id = s.run_id AND m.stage = s.name AND m.name = 'smoothness_resampled')")" 0
"$MPB_BUILD/tools/mpb" report "$DB" | grep -q "^kappa'_r (Mean, rad^2)"
check "... in a row of its own" eq $? 0
check "waypoints are stored whole" \
    eq "$(q "SELECT count(*) FROM stages WHERE length(waypoints) != 8 * num_waypoints * num_joints")" 0
check "times are recorded for every run" \
    eq "$(q "SELECT count(*) FROM runs WHERE time_total IS NULL OR wall_time IS NULL")" 0

# The report names both planner families.
"$MPB_BUILD/tools/mpb" report "$DB" >"$work/report.txt" 2>&1
check "mpb report exits 0" eq $? 0
check "the report has a column for each configuration" \
    sh -c "grep -q 'ompl/RRTConnect' '$work/report.txt' && grep -q 'ompl/RRT ' '$work/report.txt' && grep -q 'null/straight_line' '$work/report.txt'"

# Running again on the finished experiment with --again starts a new one;
# nothing of the first is touched.
before=$(q "SELECT count(*), sum(success) FROM runs WHERE experiment_id = 1")
mpb_timeout 120 "$MPB_BUILD/daemon/mpbenchd" --again -d "$DB" "$exp" >"$work/daemon2.log" 2>&1
check "a second run of the experiment completes" eq $? 0
check "... as a second experiment" eq "$(q 'SELECT count(*) FROM experiments')" 2
check "... leaving the first one's runs as they were" \
    test "$(q "SELECT count(*), sum(success) FROM runs WHERE experiment_id = 1")" = "$before"

mpb_finish
