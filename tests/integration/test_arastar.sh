#!/bin/sh
# The ARA* planner (C) with the daemon over LCM in a private network
# namespace, on the paper's PR2 arm in its KITCHEN scene: a pose-region
# goal (2 cm, 0.05 rad) and a joint goal are solved and verified by the
# daemon, tau_other (voxel grid + BFS) is stored, and two runs of the same
# query give the identical path.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
DB=$work/test.db
cat >"$work/ara.yaml" <<EOT
experiment: {name: arastar, runs: 2, time_limit: 60, seed: 7}
robot:
  format: urdf
  file: $MPB_SOURCE/scenes/robots/pr2_right_arm.urdf
  joints: [r_shoulder_pan_joint, r_shoulder_lift_joint, r_upper_arm_roll_joint, r_elbow_flex_joint, r_forearm_roll_joint, r_wrist_flex_joint, r_wrist_roll_joint]
scenes:
  - name: kitchen
    format: moveit-scene
    file: $MPB_SOURCE/scenes/paper/kitchen.scene
    queries:
      - name: counter_cup
        start: [-1.2, 1.1, -1.5, -1.9, 0.0, -0.6, 0.0]
        goal: {link: r_gripper_tool_frame, position: [0.62, -0.08, 1.0], position_tolerance: 0.01, rpy: [0, 1.5708, 0], rpy_tolerance: 0.05}
      - name: to_joints
        start: [-1.2, 1.1, -1.5, -1.9, 0.0, -0.6, 0.0]
        goal: [-0.261284, -0.420386, -1.523717, -1.031201, -1.236424, -1.761224, -2.299770]
        tolerance: 0.001
planners:
  - {planner: ara, algorithms: [ARAstar]}
EOT

# Under another name, for the 4 runs only: it must stop by itself.
"$MPB_BUILD/planners/arastar/mpb-planner-arastar" -v --name ara --max-runs 4 \
    >"$work/arastar.log" 2>&1 &
planner=$!
mpb_timeout 240 "$MPB_BUILD/daemon/mpbenchd" -d "$DB" "$work/ara.yaml" >"$work/daemon.log" 2>&1
status=$?
check "mpbenchd completes the experiment and exits 0" eq "$status" 0
[ "$status" -eq 0 ] || { cat "$work/daemon.log"; cat "$work/arastar.log"; }
mpb_wait "$planner" 20
check "the planner, named ara, exits 0 by itself after its 4 runs" eq $? 0
check "... having served as ara@" grep -q "serving as ara@" "$work/arastar.log"

check "4 runs are done" eq "$(q "SELECT count(*) FROM runs WHERE state = 'done'")" 4
check "its announced approach, search, is stored" \
    test "$(q "SELECT group_concat(DISTINCT approach) FROM planner_configs")" = search
check "the planner claims every run solved" \
    eq "$(q "SELECT count(*) FROM results WHERE status = 'solved'")" 4
check "... and the daemon's verifier accepts every path" \
    eq "$(q "SELECT count(*) FROM results WHERE success = 1 AND verdict = 'valid'")" 4
[ "$(q "SELECT count(*) FROM results WHERE success = 1")" -eq 4 ] ||
    q "SELECT query, status, verdict, message FROM results"
check "every run stores tau_other > 0 (voxel grid and BFS)" \
    eq "$(q "SELECT count(*) FROM results WHERE time_other > 0 AND time_total >= time_other")" 4
check "each path is a real search: more than start and goal" \
    eq "$(q "SELECT count(*) FROM stages WHERE name = 'raw' AND num_waypoints > 2")" 4
check "each run reports its world's setup on its own (nothing is cached)" \
    eq "$(q "SELECT count(*) FROM planner_values WHERE name = 'world_setup_time' AND value > 0")" 4
check "the search reports its expansions and generated states" \
    eq "$(q "SELECT count(*) FROM planner_values WHERE name IN ('expansions', 'states generated') AND value > 0")" 8
check "deterministic: both runs of each query return the same path" \
    eq "$(q "SELECT count(*) FROM (SELECT r.query_id FROM stages s JOIN runs r ON r.id = s.run_id
             WHERE s.name = 'raw' GROUP BY r.query_id
             HAVING count(*) = 2 AND count(DISTINCT s.waypoints) = 1)")" 2
check "the two queries' paths differ (the goal matters)" \
    eq "$(q "SELECT count(DISTINCT waypoints) FROM stages WHERE name = 'raw'")" 2

# The planner ends on SIGTERM; under ASan/UBSan its log would hold any
# leak or undefined behaviour found in the runs above.
mpb_stop_all
check "the planner logged each of the 4 runs as solved" \
    eq "$(grep -c 'status 0' "$work/arastar.log")" 4
check "... and no sanitizer report" \
    eq "$(grep -c -E 'Sanitizer|runtime error' "$work/arastar.log")" 0
grep -E 'Sanitizer|runtime error' "$work/arastar.log" | head -5

mpb_finish
