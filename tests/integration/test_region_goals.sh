#!/bin/sh
# Pose-region goals in experiment files (the paper's goals): a malformed one
# is refused with file:line:col; the paper's experiment files pass --check;
# a region goal travels to the planner in the request and into the
# database, number for number.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
DB=$work/test.db
daemon=$MPB_BUILD/daemon/mpbenchd
urdf=$MPB_SOURCE/scenes/robots/pr2_right_arm.urdf
printf 'empty\n.\n' >"$work/empty.scene"

# write_experiment FILE GOAL [ROBOT_LINE]: one query whose goal is GOAL
# (YAML flow text), from the arm hanging straight down beside the robot.
write_experiment() {
    robot=${3:-"{format: urdf, file: $urdf, joints: [r_shoulder_pan_joint, r_shoulder_lift_joint, r_upper_arm_roll_joint, r_elbow_flex_joint, r_forearm_roll_joint, r_wrist_flex_joint, r_wrist_roll_joint]}"}
    cat >"$work/$1" <<EOT
experiment: {name: region, time_limit: 5}
robot: $robot
scenes:
  - name: empty
    format: moveit-scene
    file: empty.scene
    queries:
      - name: reach
        start: [-1.2, 1.1, -1.5, -1.9, 0.0, -0.6, 0.0]
        goal: $2
planners:
  - {planner: null, algorithms: [straight_line]}
EOT
}

# bad_case FILE EXPECTED: --check refuses FILE with one line matching EXPECTED.
bad_case() {
    out=$("$daemon" --check "$work/$1" 2>&1)
    rc=$?
    check "$1: refused" test "$rc" -ne 0
    check "$1: one line" eq "$(printf '%s\n' "$out" | wc -l)" 1
    check "$1: says '$2'" \
        sh -c "printf '%s' \"\$1\" | grep -q \"$work/$1:$2\"" _ "$out"
    [ "$rc" -ne 0 ] && printf '%s' "$out" | grep -q "$work/$1:$2" ||
        echo "# got: $out"
}

write_experiment unknown_link.yaml "{link: r_gripper_tool_fram, position: [0.6, -0.2, 1.0], position_tolerance: 0.01}"
bad_case unknown_link.yaml "10:22: goal link 'r_gripper_tool_fram' is not a link"

write_experiment short_position.yaml "{link: r_gripper_tool_frame, position: [0.6, -0.2], position_tolerance: 0.01}"
bad_case short_position.yaml "10:54: position must be a list of 3 numbers"

write_experiment negative_tolerance.yaml "{link: r_gripper_tool_frame, position: [0.6, -0.2, 1.0], position_tolerance: [0.01, -0.01, 0.01]}"
bad_case negative_tolerance.yaml "10:92: position_tolerance must not be negative"

write_experiment typo.yaml "{link: r_gripper_tool_frame, position: [0.6, -0.2, 1.0], position_tolerance: 0.01, rpy: [0, 0, 0], rpy_tol: 0.05}"
bad_case typo.yaml "10:114: unknown key 'rpy_tol'"

write_experiment no_rpy_tolerance.yaml "{link: r_gripper_tool_frame, position: [0.6, -0.2, 1.0], position_tolerance: 0.01, rpy: [0, 0, 0]}"
bad_case no_rpy_tolerance.yaml "10:15: goal: missing 'rpy_tolerance'"

write_experiment bad_number.yaml "{link: r_gripper_tool_frame, position: [0.6, x, 1.0], position_tolerance: 0.01}"
bad_case bad_number.yaml "10:60: position must be a number, not 'x'"

write_experiment planar.yaml "{link: tip, position: [1, 0, 0], position_tolerance: 0.01}" \
    "{format: planar, text: \"link_radius 0.05\njoint a -3 3 1\n\"}"
sed -i 's/start: \[.*\]/start: [0]/; s/moveit-scene/planar/; s/file: empty.scene/text: ""/' "$work/planar.yaml"
bad_case planar.yaml "10:15: .*a region goal needs a urdf robot"

# The paper's experiment files are valid as committed, and are what
# tools/paper_suite.sh makes of scenes/paper/suite.txt today.
for f in paper paper-quick paper-demo; do
    yaml=$MPB_SOURCE/scenes/experiments/$f.yaml
    out=$("$daemon" --check "$yaml" 2>&1)
    check "mpbenchd --check accepts $f.yaml" eq $? 0
    echo "# $out"
    out=$("$MPB_BUILD/tools/mpb-paper-suite" --variant "$f" --check "$yaml" \
          "$MPB_SOURCE/scenes/paper/suite.txt" 2>&1)
    check "$f.yaml is what mpb-paper-suite generates" eq $? 0
    [ -z "$out" ] || echo "# $out"
done

# A region goal reaches the planner: the null planner answers it with
# "needs a joint-space goal" (it would draw a straight line to a joint goal).
goal="{link: r_gripper_tool_frame, position: [0.625, -0.25, 0.875], position_tolerance: [0.01, 0.02, 0.03], rpy: [0.5, -0.25, 1.5], rpy_tolerance: 0.05}"
write_experiment region.yaml "$goal"
mpb_spawn "$work/null.log" "$MPB_BUILD/planners/null/mpb-planner-null"
mpb_timeout 60 "$daemon" -d "$DB" "$work/region.yaml" >"$work/daemon.log" 2>&1
status=$?
check "the experiment with a region goal completes" eq "$status" 0
[ "$status" -eq 0 ] || cat "$work/daemon.log"
check "the query is stored as a pose region of r_gripper_tool_frame" \
    test "$(q "SELECT goal_kind || ' ' || goal_link FROM queries")" = \
         "pose_region r_gripper_tool_frame"
check "... with its centre, half sizes, rpy and tolerances, exactly" \
    test "$(q "SELECT goal_region FROM queries")" = \
         "0.625 -0.25 0.875 0.01 0.02 0.03 0.5 -0.25 1.5 0.05 0.05 0.05"
check "... and no joint goal" eq "$(q "SELECT count(*) FROM queries WHERE goal_joints IS NULL")" 1
check "the planner was asked for a region, not a configuration" \
    eq "$(q "SELECT count(*) FROM runs WHERE state = 'done' AND success = 0 AND message LIKE '%needs a joint-space goal%'")" 1

mpb_finish
