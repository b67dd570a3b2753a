#!/bin/sh
# Whole-body self-collision of the shipped PR2 (scenes/robots/): a goal
# with the gripper inside the torso is refused by --check, naming both
# links; a returned straight line through the torso is stored as a
# failure naming them; without an SRDF the daemon says how it generated
# the allowed-collision matrix, and `mpb srdf` writes the same matrix
# every time, one that reads back unchanged and that the daemon takes as
# the robot's srdf:; bad SRDFs are refused in one line naming the file
# and the line, the database left byte-identical; pairs naming links the
# URDF lacks are skipped with one warning, as MoveIt does.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
DB=$work/test.db
daemon=$MPB_BUILD/daemon/mpbenchd
mpb=$MPB_BUILD/tools/mpb
urdf=$MPB_SOURCE/scenes/robots/pr2_right_arm.urdf
joints=r_shoulder_pan_joint,r_shoulder_lift_joint,r_upper_arm_roll_joint,r_elbow_flex_joint,r_forearm_roll_joint,r_wrist_flex_joint,r_wrist_roll_joint

# Free states on either side of the torso; the straight line between them
# passes the tool frame through the torso column (its middle is the state
# of tests/unit/model/test_self_collision.c).
side_a="[-2.0, 1.0, -2.9, -1.6, -0.5, 0.0, -2.4]"
side_b="[-1.0, 1.0, -3.5, -1.8, -0.3, -0.4, -1.8]"
in_torso="[-1.5, 1.0, -3.2, -1.7, -0.4, -0.2, -2.1]"

# experiment FILE NAME START GOAL [SRDF]
experiment() {
    cat >"$1" <<EOT
experiment: {name: $2, runs: 1, time_limit: 5}
robot:
  format: urdf
  file: $urdf
  joints: [$joints]
${5:+  srdf: $5}
scenes:
  - name: empty
    format: moveit-scene
    text: "(empty)\n.\n"
    queries:
      - {name: q, start: $3, goal: $4}
planners:
  - {planner: null, algorithms: [straight_line]}
EOT
}

# A goal inside the torso: refused, both links named.
experiment "$work/goal.yaml" goal "$side_a" "$in_torso"
out=$("$daemon" --check "$work/goal.yaml" 2>&1)
check "--check refuses a goal with the gripper in the torso" test $? -ne 0
check "... in one line naming both links" sh -c "printf '%s\n' \"\$1\" | grep -qx \"mpbenchd: $work/goal.yaml:12:[0-9]*: goal is in collision in scene 'empty': self-collision between torso_lift_link and r_gripper_palm_link\"" _ "$out"

# A straight line through the torso: stored as a failure naming them.
experiment "$work/line.yaml" line "$side_a" "$side_b"
mpb_spawn "$work/null.log" "$MPB_BUILD/planners/null/mpb-planner-null"
"$daemon" -d "$DB" "$work/line.yaml" >"$work/daemon.log" 2>&1 &
pid=$!
mpb_wait $pid 60
check "the run through the torso completes" eq $? 0
check "... stored as a collision, no success" test \
    "$(q "SELECT verdict || ' ' || success FROM results")" = "collision 0"
check "... the verdict naming the two links" sh -c \
    "sqlite3 '$DB' 'SELECT verdict_detail FROM stages' | grep -q 'self-collision between torso_lift_link and r_gripper_palm_link'"
check "the daemon says how it made the matrix, in one line" eq \
    "$(grep -c "robot has no srdf: self-collision matrix generated as MoveIt's setup assistant does, 27 pairs allowed (9 adjacent, 2 in collision at the default state, 0 nearly always, 16 never in 10000 random states); review it with 'mpb srdf $urdf -j $joints -o robot.srdf'" "$work/daemon.log")" 1

# mpb srdf: the same file twice; read back, the same pairs.
"$mpb" srdf "$urdf" >"$work/one.srdf"
check "mpb srdf writes the matrix" test $? -eq 0
"$mpb" srdf -j "$joints" -o "$work/two.srdf" "$urdf"
check "... the same with the group named and -o" cmp -s "$work/one.srdf" "$work/two.srdf"
check "... 27 pairs" eq "$(grep -c '<disable_collisions ' "$work/one.srdf")" 27
"$mpb" srdf -s "$work/one.srdf" "$urdf" >"$work/back.srdf"
check "... which read back give the same pairs and reasons" sh -c \
    "grep '<disable_collisions' '$work/one.srdf' >'$work/a'; grep '<disable_collisions' '$work/back.srdf' >'$work/b'; cmp -s '$work/a' '$work/b'"

# The file as the robot's srdf: the daemon takes it and generates nothing.
experiment "$work/with.yaml" with "$side_a" "$side_b" one.srdf
out=$("$daemon" --check "$work/with.yaml" 2>&1)
check "the written SRDF is a robot's srdf" test "$out" = \
    "$work/with.yaml: ok: 1 scene, 1 query, 1 planner configuration, 1 run"
experiment "$work/with_goal.yaml" with_goal "$side_a" "$in_torso" one.srdf
out=$("$daemon" --check "$work/with_goal.yaml" 2>&1)
check "... and with it the gripper in the torso is still refused" sh -c \
    "printf '%s' '$out' | grep -q 'self-collision between torso_lift_link and r_gripper_palm_link'"

# Bad SRDFs: one line naming the file and the line; database untouched.
sum_before=$(md5sum <"$DB")
bad_srdf() {
    experiment "$work/$1.yaml" bad "$side_a" "$side_b" "$1.srdf"
    out=$("$daemon" -d "$DB" "$work/$1.yaml" 2>&1)
    rc=$?
    check "$1: exits non-zero" test "$rc" -ne 0
    check "$1: one line" eq "$(printf '%s\n' "$out" | wc -l)" 1
    check "$1: names the file and the line: '$2'" \
        sh -c "printf '%s' \"\$1\" | grep -q \"^mpbenchd: $work/$1.yaml:.*$work/$1.srdf: $2\"" _ "$out"
    check "$1: database untouched" test "$(md5sum <"$DB")" = "$sum_before"
}
{ head -n 11 "$work/one.srdf"; printf '  <disable_collisions link1="base_li'; } >"$work/truncated.srdf"
bad_srdf truncated "line 12, column [0-9]*: not well-formed XML"
# A group naming a link the URDF lacks: refused, at its line.
sed 's|^</robot>|  <group name="g">\n    <link name="r_forarm_link"/>\n  </group>\n</robot>|' "$work/one.srdf" >"$work/group.srdf"
line=$(grep -n '<link name="r_forarm_link"' "$work/group.srdf" | cut -d: -f1)
bad_srdf group "line $line: group 'g' names link 'r_forarm_link', which is not a link of the URDF"

# Pairs naming a link the URDF lacks: skipped as MoveIt does, with one
# warning naming the file, the count and the pairs at their lines; the
# rest of the SRDF holds.
sed 's/link2="r_forearm_link"/link2="r_forarm_link"/' "$work/one.srdf" >"$work/unknown.srdf"
l1=$(grep -n 'r_forarm_link' "$work/unknown.srdf" | sed -n 1p | cut -d: -f1)
l2=$(grep -n 'r_forarm_link' "$work/unknown.srdf" | sed -n 2p | cut -d: -f1)
warning="2 of 27 disable_collisions pairs name links the URDF lacks and are skipped, as MoveIt does: line $l1 (r_shoulder_lift_link, r_forarm_link: no link 'r_forarm_link'), line $l2 (r_elbow_flex_link, r_forarm_link: no link 'r_forarm_link'); the names: r_forarm_link"
experiment "$work/unknown.yaml" unknown "$side_a" "$side_b" unknown.srdf
out=$("$daemon" --check "$work/unknown.yaml" 2>&1)
check "an SRDF with pairs naming unknown links loads" test $? -eq 0
check "... with one warning naming the file, the count and the lines" eq \
    "$(printf '%s\n' "$out" | grep -cF "warning: robot: $work/unknown.srdf: $warning")" 1
check "... and no other warning" eq "$(printf '%s\n' "$out" | grep -c warning)" 1
out=$("$mpb" srdf -s "$work/unknown.srdf" "$urdf" 2>&1 >"$work/unknown_back.srdf")
check "mpb srdf -s says the same and writes the matrix" test \
    "$out" = "mpb srdf: warning: $work/unknown.srdf: $warning"
check "... the other pairs, the adjacent one again, not the skipped one" \
    sh -c "grep '<disable_collisions' '$work/one.srdf' | grep -v 'r_shoulder_lift_link\" link2=\"r_forearm_link' >'$work/a'; grep '<disable_collisions' '$work/unknown_back.srdf' >'$work/b'; cmp -s '$work/a' '$work/b'"

# An unfinished experiment whose SRDF changed since: not resumed, and the
# message names the SRDF, not the URDF (their texts travel as one).
RDB=$work/resume.db
cp "$work/one.srdf" "$work/kept.srdf"
experiment "$work/resume.yaml" resume "$side_a" "$side_b" kept.srdf
sed -i 's/planner: null,/planner: nobody,/' "$work/resume.yaml"
"$daemon" -d "$RDB" "$work/resume.yaml" >"$work/resume.log" 2>&1 &
pid=$!
mpb_wait_count "$RDB" 1 20 'SELECT count(*) FROM runs'
check "an experiment with no planner begins" eq $? 0
kill -TERM $pid 2>/dev/null
wait $pid 2>/dev/null
echo "<!-- reviewed -->" >>"$work/kept.srdf"
out=$(mpb_timeout 30 "$daemon" -d "$RDB" "$work/resume.yaml" 2>&1)
check "resuming it with its SRDF edited is refused" test $? -ne 0
check "... naming the SRDF" test "$out" = \
    "mpbenchd: $RDB: experiment 'resume' (id 1) began with another robot SRDF for scene 'empty' ($work/kept.srdf has changed since): restore it to resume, or start a new experiment with --new"

mpb_finish
