#!/bin/sh
# Joints held outside the planning group reach every world of a run. The
# PR2 test arm's torso (tests/support/data/pr2_right_arm.urdf, prismatic,
# outside the group) is held at 0.3 m; a box sits where the forearm
# sweeps only at that height. The null planner's straight line, free at
# the default torso height, is refused by the daemon's verifier as a
# collision with the box; the OMPL, ARA* and Python planners, which hold
# the torso as the request says, go round it and succeed.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"
PASSES=0
FAILS=0

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
DB=$work/test.db
data=$MPB_SOURCE/tests/support/data

# The unit test's box (test_world_urdf.c), 0.3 m higher.
cat >"$work/box.scene" <<EOT
box above the arm
* box
0.6 -0.188 1.04
0 0 0 1
1
box
0.1 0.1 0.1
0 0 0
0 0 0 1
0 0 0 0
0
.
EOT
cat >"$work/held.yaml" <<EOT
experiment: {name: held, time_limit: 30, seed: 5}
robot:
  format: urdf
  file: $data/pr2_right_arm.urdf
  srdf: $data/pr2_right_arm.srdf
  joints: [r_shoulder_pan_joint, r_shoulder_lift_joint, r_upper_arm_roll_joint, r_elbow_flex_joint, r_forearm_roll_joint, r_wrist_flex_joint, r_wrist_roll_joint]
  joint_values: {torso_lift_joint: 0.3}
scenes:
  - name: box
    format: moveit-scene
    file: $work/box.scene
    queries:
      - {name: across, start: [-1.2, 0, 0, 0, 0, 0, 0], goal: [0.5, 0, 0, 0, 0, 0, 0]}
planners:
  - {planner: null, algorithms: [straight_line]}
  - {planner: ompl, algorithms: [RRTConnect]}
  - {planner: ara, algorithms: [ARAstar]}
  - {planner: python, algorithms: [RRTConnect]}
EOT

mpb_spawn "$work/null.log" "$MPB_BUILD/planners/null/mpb-planner-null"
mpb_spawn "$work/ompl.log" "$MPB_BUILD/planners/ompl/mpb-planner-ompl"
mpb_spawn "$work/ara.log" "$MPB_BUILD/planners/arastar/mpb-planner-arastar" --name ara
mpb_spawn "$work/python.log" "$MPB_BUILD/planners/python/mpb-planner-python"
mpb_timeout 200 "$MPB_BUILD/daemon/mpbenchd" -d "$DB" "$work/held.yaml" >"$work/daemon.log" 2>&1
status=$?
check "mpbenchd completes the experiment and exits 0" eq "$status" 0
[ "$status" -eq 0 ] || cat "$work/daemon.log"

check "the straight line, free with the torso at 0, collides with it at 0.3" \
    eq "$(q "SELECT count(*) FROM results WHERE planner = 'null/straight_line'
             AND claimed_success = 1 AND success = 0 AND verdict = 'collision'")" 1
# How deep the refused line goes (docs/verification.md): both bounds
# stored with the verdict, 0 < lower <= upper, in mm; the forearm's
# straight sweep plunges centimetres into the box, no graze. Valid
# stages have none.
null_depth="SELECT g.depth_lower_mm, g.depth_upper_mm FROM stages g
            JOIN runs r ON r.id = g.run_id JOIN planner_configs c
            ON c.id = r.planner_config_id WHERE c.name = 'null/straight_line'"
check "the refused stage stores a lower and an upper bound on its depth" \
    eq "$(q "SELECT count(*) FROM ($null_depth) WHERE depth_lower_mm > 1
             AND depth_upper_mm >= depth_lower_mm AND depth_upper_mm < 100")" 1
q "$null_depth" | sed 's/^/# depth lower|upper mm: /'
check "valid stages store no depth" \
    eq "$(q "SELECT count(*) FROM stages WHERE valid = 1
             AND (depth_lower_mm IS NOT NULL OR depth_upper_mm IS NOT NULL)")" 0
"$MPB_BUILD/tools/mpb" verify "$DB" >"$work/verify.out" 2>&1
check "mpb verify shows how deep the collision verdicts go" \
    grep -q "^1 collision verdicts, 1 with a depth: median" "$work/verify.out"
"$MPB_BUILD/tools/mpb" report "$DB" >"$work/report.out" 2>&1
check "mpb report gives the refused configuration's depth distribution" \
    grep -Eq "^  null/straight_line +1 +1 +[0-9.]+-[0-9.]+ +[0-9.]+-[0-9.]+ +0$" \
    "$work/report.out"
check "the query's held value is stored with it, exactly" \
    test "$(q "SELECT held FROM queries")" = "torso_lift_joint=0.29999999999999999"
for p in ompl/RRTConnect ara/ARAstar python/RRTConnect; do
    check "$p plans round the box at the held height: success, verified" \
        eq "$(q "SELECT count(*) FROM results WHERE planner = '$p' AND success = 1")" 1
    [ "$(q "SELECT success FROM results WHERE planner = '$p'")" = 1 ] ||
        q "SELECT planner, status, verdict, message FROM results WHERE planner = '$p'"
done

mpb_finish
