#!/bin/sh
# SRDF semantics end to end, on the Panda of tools/robot_data.sh (fetched
# if missing): `group: panda_arm` and `start: ready` check, run and are
# stored as a verified success; `mpb srdf -s -g` lists the SRDF's groups,
# states and end effector and reads back the same; the shipped PR2 arm's
# groups, given as a chain or tip first, and a state by name; bad SRDFs (truncated,
# an unknown joint, an unknown link, a group with no joints, a subgroup
# cycle) are refused in one line naming the SRDF file and line, by a run
# and by --check, an existing database left byte-identical; the Baxter
# and Fetch SRDFs, whose pairs name links their URDFs lack, load with a
# warning.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
DB=$work/test.db
daemon=$MPB_BUILD/daemon/mpbenchd
mpb=$MPB_BUILD/tools/mpb

if ! "$MPB_SOURCE/tools/robot_data.sh" --check; then
    "$MPB_SOURCE/tools/robot_data.sh" >/dev/null ||
        { echo "not ok - tools/robot_data.sh could not fetch the robots"; exit 1; }
fi
robots=$("$MPB_SOURCE/tools/robot_data.sh")
urdf=$robots/panda/panda.urdf
srdf=$robots/panda/panda.srdf

# experiment FILE SRDF GROUP START GOAL
experiment() {
    cat >"$1" <<EOT
experiment: {name: panda, runs: 1, time_limit: 5}
robot:
  format: urdf
  file: $urdf
  srdf: $2
  group: $3
scenes:
  - name: empty
    format: moveit-scene
    text: "(empty)\n.\n"
    queries:
      - {name: q, start: $4, goal: $5}
planners:
  - {planner: null, algorithms: [straight_line]}
EOT
}

experiment "$work/good.yaml" "$srdf" panda_arm ready extended
# With the meshes where planners find them: else --check warns.
out=$(MPB_MESH_PATH=$robots/panda "$daemon" --check "$work/good.yaml" 2>&1)
check "group: panda_arm with start: ready checks" test "$out" = \
    "$work/good.yaml: ok: 1 scene, 1 query, 1 planner configuration, 1 run"

# Run it: the planner opens its world with the group's joints.
mpb_spawn "$work/null.log" "$MPB_BUILD/planners/null/mpb-planner-null"
"$daemon" -d "$DB" "$work/good.yaml" >"$work/daemon.log" 2>&1 &
pid=$!
mpb_wait $pid 60
check "the run completes" eq $? 0
check "... a verified success" test "$(q "SELECT verdict || ' ' || success FROM results")" = "valid 1"
check "... stored with the group's joints" test "$(q "SELECT joint_names FROM queries")" = \
    "panda_joint1 panda_joint2 panda_joint3 panda_joint4 panda_joint5 panda_joint6 panda_joint7"
check "... and the SRDF's ready as its start" test "$(q "SELECT start FROM queries")" = \
    "0 -0.785 0 -2.356 0 1.571 0.785"
mpb_stop_all

# mpb srdf: the SRDF as mpbench reads it, for review; it reads back the same.
"$mpb" srdf -s "$srdf" -g panda_arm -o "$work/one.srdf" "$urdf"
check "mpb srdf -s -g writes" eq $? 0
check "... the group it plans, base first" grep -q "<!-- group 'panda_arm': mpbench plans 7 joints, base first: panda_joint1, panda_joint2, panda_joint3, panda_joint4, panda_joint5, panda_joint6, panda_joint7 -->" "$work/one.srdf"
check "... why it plans no hand" grep -q "<!-- not planned by mpbench: group 'hand' has no joint to plan" "$work/one.srdf"
check "... the states, as written" grep -q '<joint name="panda_joint4" value="-2.356"/>' "$work/one.srdf"
check "... the end effector" grep -q '<end_effector name="hand" group="hand" parent_link="panda_link8" parent_group="panda_arm"/>' "$work/one.srdf"
check "... the virtual joint" grep -q '<virtual_joint name="virtual_joint" type="floating" parent_frame="world" child_link="panda_link0"/>' "$work/one.srdf"
"$mpb" srdf -s "$work/one.srdf" -g panda_arm -o "$work/two.srdf" "$urdf"
check "... which read back give the same file" sh -c \
    "tail -n +6 '$work/one.srdf' >'$work/a'; tail -n +6 '$work/two.srdf' >'$work/b'; cmp -s '$work/a' '$work/b'"
out=$("$mpb" srdf -s "$srdf" -g panda_arm_han "$urdf" 2>&1)
check "mpb srdf -g with a group the SRDF lacks: refused" test "$out" = \
    "mpb srdf: $srdf has no group 'panda_arm_han'"

# Bad SRDFs, each against the Panda: one line naming the SRDF file and the
# line; the database left as it was, by a run and by --check.
sum_before=$(md5sum <"$DB")
bad_srdf() {
    experiment "$work/$1.yaml" "$work/$1.srdf" panda_arm ready extended
    for how in run check; do
        if [ $how = run ]; then
            out=$("$daemon" -d "$DB" "$work/$1.yaml" 2>&1)
        else
            out=$("$daemon" --check -d "$DB" "$work/$1.yaml" 2>&1)
        fi
        rc=$?
        check "$1 ($how): exits non-zero" test "$rc" -ne 0
        check "$1 ($how): one line" eq "$(printf '%s\n' "$out" | wc -l)" 1
        check "$1 ($how): names the file and the line: '$2'" \
            sh -c "printf '%s' \"\$1\" | grep -q \"^mpbenchd: $work/$1.yaml:5:9: robot: $work/$1.srdf: $2\$\"" _ "$out"
        check "$1 ($how): database untouched" test "$(md5sum <"$DB")" = "$sum_before"
    done
}
{ head -n 20 "$srdf"; printf '    <joint name="panda_joint3" val'; } >"$work/truncated.srdf"
bad_srdf truncated "line 21, column [0-9]*: not well-formed XML: .*"
sed 's/<joint name="panda_joint4" value/<joint name="panda_joint44" value/' "$srdf" >"$work/unknown_joint.srdf"
line=$(grep -n panda_joint44 "$work/unknown_joint.srdf" | head -1 | cut -d: -f1)
bad_srdf unknown_joint "line $line: group_state 'ready' gives joint 'panda_joint44', which is not a joint of the URDF"
sed 's/<link name="panda_leftfinger"\/>/<link name="panda_leftfingr"\/>/' "$srdf" >"$work/unknown_link.srdf"
line=$(grep -n panda_leftfingr "$work/unknown_link.srdf" | head -1 | cut -d: -f1)
bad_srdf unknown_link "line $line: group 'hand' names link 'panda_leftfingr', which is not a link of the URDF"
sed 's|</robot>|  <group name="nothing">\n  </group>\n</robot>|' "$srdf" >"$work/no_joints.srdf"
line=$(grep -n '<group name="nothing">' "$work/no_joints.srdf" | cut -d: -f1)
bad_srdf no_joints "line $line: group 'nothing' has no joints"
sed 's|<group name="panda_arm"/>|<group name="panda_arm_hand"/>|' "$srdf" >"$work/cycle.srdf"
line=$(grep -n '<group name="panda_arm_hand"/>' "$work/cycle.srdf" | cut -d: -f1)
bad_srdf cycle "line $line: group 'panda_arm_hand' contains itself through its subgroups (panda_arm_hand -> panda_arm_hand)"

# The shipped PR2 arm, with the matrix mpb srdf generates for it and
# groups and states added: a chain from the base to the tool frame is the
# arm's seven joints (the fixed torso and wrist joints left out); joints
# named tip first are planned base first; a state by name is its values.
pr2=$MPB_SOURCE/scenes/robots/pr2_right_arm.urdf
"$mpb" srdf -o "$work/pr2.srdf" "$pr2"
sed 's|^</robot>|  <group name="right_arm"><chain base_link="base_link" tip_link="r_gripper_tool_frame"/></group>\
  <group name="wrist"><joint name="r_wrist_roll_joint"/><joint name="r_wrist_flex_joint"/></group>\
  <group name="torso"><joint name="torso_lift_joint"/></group>\
  <group_state name="side_a" group="right_arm">\
    <joint name="r_shoulder_pan_joint" value="-2.0"/><joint name="r_shoulder_lift_joint" value="1.0"/>\
    <joint name="r_upper_arm_roll_joint" value="-2.9"/><joint name="r_elbow_flex_joint" value="-1.6"/>\
    <joint name="r_forearm_roll_joint" value="-0.5"/><joint name="r_wrist_flex_joint" value="0.0"/>\
    <joint name="r_wrist_roll_joint" value="-2.4"/>\
  </group_state>\
</robot>|' "$work/pr2.srdf" >"$work/pr2_groups.srdf"
cat >"$work/pr2.yaml" <<EOT
experiment: {name: pr2, runs: 1, time_limit: 5}
robot: {format: urdf, file: $pr2, srdf: $work/pr2_groups.srdf, group: right_arm}
scenes:
  - {name: empty, format: moveit-scene, text: "(empty)\n.\n", queries: [{name: q, start: side_a, goal: [-1.0, 1.0, -3.5, -1.8, -0.3, -0.4, -1.8]}]}
planners: [{planner: null, algorithms: [straight_line]}]
EOT
out=$("$daemon" --check "$work/pr2.yaml" 2>&1)
check "the PR2 with group: right_arm and start: side_a checks" test "$out" = \
    "$work/pr2.yaml: ok: 1 scene, 1 query, 1 planner configuration, 1 run"
"$mpb" srdf -s "$work/pr2_groups.srdf" "$pr2" >"$work/pr2_review.srdf"
check "... right_arm is the arm's seven joints, base first" grep -q "<!-- group 'right_arm': mpbench plans 7 joints, base first: r_shoulder_pan_joint, r_shoulder_lift_joint, r_upper_arm_roll_joint, r_elbow_flex_joint, r_forearm_roll_joint, r_wrist_flex_joint, r_wrist_roll_joint -->" "$work/pr2_review.srdf"
check "... wrist, named tip first, is planned base first" grep -q "<!-- group 'wrist': mpbench plans 2 joints, base first: r_wrist_flex_joint, r_wrist_roll_joint -->" "$work/pr2_review.srdf"
sed 's/group: right_arm/group: torso/' "$work/pr2.yaml" >"$work/pr2_torso.yaml"
out=$("$daemon" --check "$work/pr2_torso.yaml" 2>&1)
check "... torso, whose joint is fixed here, is refused at group:" sh -c \
    "printf '%s\n' \"\$1\" | grep -qx \"mpbenchd: $work/pr2_torso.yaml:2:[0-9]*: group 'torso' has no joint to plan: its joints are fixed, mimic, passive or virtual\"" _ "$out"

# Names the experiment gives that the SRDF lacks: at the experiment's key.
experiment "$work/redy.yaml" "$srdf" panda_arm redy extended
out=$("$daemon" --check -d "$DB" "$work/redy.yaml" 2>&1)
check "start: redy is refused at its place" test "$out" = \
    "mpbenchd: $work/redy.yaml:12:26: start: group 'panda_arm' has no group_state 'redy' (it has ready, extended, transport)"
experiment "$work/open.yaml" "$srdf" panda_arm ready open
out=$("$daemon" --check -d "$DB" "$work/open.yaml" 2>&1)
check "goal: open, a state of the hand, is refused at its place" test "$out" = \
    "mpbenchd: $work/open.yaml:12:39: goal: group_state 'open' is for group 'hand', not 'panda_arm'"
check "database still untouched" test "$(md5sum <"$DB")" = "$sum_before"


# The field's other robots: VAMP's Baxter and Fetch SRDFs name links their
# URDFs leave out (Baxter's collision_head_link, Fetch's bellows, estop
# and wheels); those pairs are skipped with one warning naming the file,
# as MoveIt does, and the rest loads. The Panda's and UR5's name none.
# robot_srdf ROBOT GROUP: mpb srdf -s of its SRDF, stderr in $work/ROBOT.err
robot_srdf() {
    "$mpb" srdf -s "$robots/$1/$1.srdf" -g "$2" "$robots/$1/$1.urdf" \
        >"$work/$1_review.srdf" 2>"$work/$1.err"
}
robot_srdf baxter right_arm
check "Baxter's SRDF loads" test $? -eq 0
check "... with one warning: 112 of its 450 pairs skipped, the first at line 163" \
    grep -qx "mpb srdf: warning: $robots/baxter/baxter.srdf: 112 of 450 disable_collisions pairs name links the URDF lacks and are skipped, as MoveIt does: line 163 (collision_head_link, display: no link 'collision_head_link'), line 164 (collision_head_link, head: no link 'collision_head_link'), line 165 (collision_head_link, left_lower_shoulder: no link 'collision_head_link') and 109 more; the names: collision_head_link, sonar_ring, left_hand_range, right_hand_camera, right_hand_range, left_hand_camera, left_hand_accelerometer, right_hand_accelerometer" "$work/baxter.err"
check "... and nothing else on stderr" eq "$(wc -l <"$work/baxter.err")" 1
check "... its right arm planned, base first" grep -q "<!-- group 'right_arm': mpbench plans 7 joints, base first: right_s0, right_s1, right_e0, right_e1, right_w0, right_w1, right_w2 -->" "$work/baxter_review.srdf"
robot_srdf fetch arm
check "Fetch's SRDF loads" test $? -eq 0
check "... with one warning: 87 of its 162 pairs skipped, the first at line 49" \
    grep -q "^mpb srdf: warning: $robots/fetch/fetch.srdf: 87 of 162 disable_collisions pairs name links the URDF lacks and are skipped, as MoveIt does: line 49 (base_link, bellows_link2: no link 'bellows_link2')" "$work/fetch.err"
check "... naming each link it lacks once, VAMP's typo torso_link_link_collision_2 too" \
    grep -q "; the names: bellows_link2, estop_link, l_wheel_link, laser_link, r_wheel_link, torso_lift_link_collision_3, torso_link_link_collision_2\$" "$work/fetch.err"
check "... and nothing else on stderr" eq "$(wc -l <"$work/fetch.err")" 1
robot_srdf ur5 manipulator
check "UR5's SRDF loads without a warning" sh -c "test $? -eq 0 && test ! -s '$work/ur5.err'"
robot_srdf panda panda_arm
check "the Panda's too" sh -c "test $? -eq 0 && test ! -s '$work/panda.err'"

mpb_finish
