#!/bin/sh
# A malformed experiment file: one line naming the file and what is wrong,
# a non-zero exit, and a database left exactly as it was.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
DB=$work/test.db
daemon=$MPB_BUILD/daemon/mpbenchd

# A database with something in it already.
sqlite3 "$DB" "CREATE TABLE keep(x); INSERT INTO keep VALUES (42);"
sum_before=$(md5sum <"$DB")

# bad_case FILE EXPECTED_MESSAGE_PART: the file must be refused like this.
bad_case() {
    file=$work/$1
    out=$("$daemon" -d "$DB" "$file" 2>&1)
    rc=$?
    check "$1: exits non-zero" test "$rc" -ne 0
    check "$1: one line" eq "$(printf '%s\n' "$out" | wc -l)" 1
    check "$1: names the file and says '$2'" \
        sh -c "printf '%s' \"\$1\" | grep -q \"^mpbenchd: $file.*$2\"" _ "$out"
    check "$1: database untouched" test "$(md5sum <"$DB")" = "$sum_before"
}

base=$MPB_SOURCE/scenes/planar
cat >"$work/yaml_syntax.yaml" <<EOT
experiment: {name: x, time_limit: 1
EOT
bad_case yaml_syntax.yaml "YAML"

cat >"$work/wrong_size.yaml" <<EOT
experiment: {name: x, time_limit: 1}
robot: {format: planar, file: $base/arm3.robot}
scenes:
  - name: s
    format: planar
    file: $base/pillars.scene
    queries:
      - {name: q, start: [0, 0], goal: [1, 0, 0]}
planners:
  - {planner: null, algorithms: [straight_line]}
EOT
bad_case wrong_size.yaml ":8:.*start has 2 values, the robot has 3 joints"

cat >"$work/typo.yaml" <<EOT
experiment: {name: x, time_limt: 1}
EOT
bad_case typo.yaml "unknown key 'time_limt'"

cat >"$work/bad_runs.yaml" <<EOT
experiment: {name: x, runs: -3, time_limit: 1}
EOT
bad_case bad_runs.yaml "runs must be a positive integer"

cat >"$work/bad_queue.yaml" <<EOT
experiment: {name: x, time_limit: 1, queue_at_planner: 9}
EOT
bad_case bad_queue.yaml ":1:.*queue_at_planner must be a whole number from 0 to 4, not '9'"

cat >"$work/bad_retries.yaml" <<EOT
experiment: {name: x, time_limit: 1, retries: -1}
EOT
bad_case bad_retries.yaml ":1:.*retries must be a whole number from 0 to 1000000000, not '-1'"

cat >"$work/bad_verification.yaml" <<EOT
experiment: {name: x, time_limit: 1, verification: often}
EOT
bad_case bad_verification.yaml ":1:.*verification must be certified or sampled, not 'often'"

# 150 million runs: more than an experiment may have (the count wrapped
# in an int before, and the runs filled the disk in one transaction).
cat >"$work/too_many_runs.yaml" <<EOT
experiment: {name: x, time_limit: 1, runs: 50000000}
robot: {format: planar, text: "link_radius 0.01\\njoint a -1 1 0.5\\n"}
scenes: [{name: s, format: planar, text: "", queries: [{name: q, start: [0], goal: [0.5]}]}]
planners: [{planner: ompl, algorithms: [RRT, EST, PRM]}]
EOT
bad_case too_many_runs.yaml ":1:44: runs: 50000000 makes more than 100000000 runs in all"

# A key twice: libyaml keeps both and the first would win unseen.
cat >"$work/dup_runs.yaml" <<EOT
experiment:
  name: x
  runs: 10
  time_limit: 1
  runs: 1
EOT
bad_case dup_runs.yaml ":5:3: key 'runs' appears twice"

cat >"$work/dup_params.yaml" <<EOT
experiment: {name: x, time_limit: 1}
robot: {format: planar, text: "link_radius 0.01\\njoint a -1 1 0.5\\n"}
scenes: [{name: s, format: planar, text: "", queries: [{name: q, start: [0], goal: [0.5]}]}]
planners: [{planner: ompl, algorithms: [RRT], params: {range: 0.3, range: 5}}]
EOT
bad_case dup_params.yaml ":4:[0-9]*: key 'range' appears twice"

# A second document after --- would be ignored.
cat >"$work/two_docs.yaml" <<EOT
experiment: {name: x, time_limit: 1}
robot: {format: planar, text: "link_radius 0.01\\njoint a -1 1 0.5\\n"}
scenes: [{name: s, format: planar, text: "", queries: [{name: q, start: [0], goal: [0.5]}]}]
planners: [{planner: ompl, algorithms: [RRT]}]
---
experiment: {name: y, time_limit: 1}
EOT
bad_case two_docs.yaml ":5:1: a second YAML document"

# Lists nested 5000 deep: libyaml's time grows with the square of the
# depth, so the loader stops at 100 levels.
{ printf 'experiment:\n  name: x\n  runs: '
  awk 'BEGIN { for (i = 0; i < 5000; i++) printf "["; for (i = 0; i < 5000; i++) printf "]"; print "" }'
} >"$work/deep.yaml"
bad_case deep.yaml ":3:107: nested too deeply (more than 100 levels)"

# A NUL byte in a robot file: the parser would stop there.
printf 'link_radius 0.01\njoint a -1 1 0.5\n\000joint b -1 1 0.5\n' >"$work/nul.robot"
cat >"$work/nul_robot.yaml" <<EOT
experiment: {name: x, time_limit: 1}
robot: {format: planar, file: nul.robot}
scenes: [{name: s, format: planar, text: "", queries: [{name: q, start: [0], goal: [0.5]}]}]
planners: [{planner: null, algorithms: [a]}]
EOT
bad_case nul_robot.yaml ":2:.*nul.robot: not a text file (a NUL byte at offset 34)"

cat >"$work/robot_name.yaml" <<EOT
experiment: {name: x, time_limit: 1}
robot: {format: planar, name: arm, text: "link_radius 0.01\\njoint a -1 1 0.5\\n"}
scenes: [{name: s, format: planar, text: "", queries: [{name: q, start: [0], goal: [0.5]}]}]
planners: [{planner: null, algorithms: [a]}]
EOT
bad_case robot_name.yaml ":2:25: unknown key 'name'"

cat >"$work/missing_file.yaml" <<EOT
experiment: {name: x, time_limit: 1}
robot: {format: planar, file: nosuch.robot}
scenes: [{name: s, format: planar, text: "", queries: [{name: q, start: [0], goal: [0]}]}]
planners: [{planner: null, algorithms: [a]}]
EOT
bad_case missing_file.yaml "cannot read robot file"

cat >"$work/bad_robot.yaml" <<EOT
experiment: {name: x, time_limit: 1}
robot: {format: planar, text: "joint a 0 1\n"}
scenes: [{name: s, format: planar, text: "", queries: [{name: q, start: [0], goal: [0]}]}]
planners: [{planner: null, algorithms: [a]}]
EOT
bad_case bad_robot.yaml "robot line 1"

cat >"$work/goal_in_collision.yaml" <<EOT
experiment: {name: x, time_limit: 1}
robot: {format: planar, file: $base/arm3.robot}
scenes:
  - name: s
    format: planar
    file: $base/pillars.scene
    queries:
      - {name: up, start: [0, 0, 0], goal: [1.5708, 0, 0]}
planners:
  - {planner: null, algorithms: [straight_line]}
EOT
bad_case goal_in_collision.yaml ":8:.*goal is in collision in scene 's'"

printf '<robot name="r">\n  <link name="a">\n</robot>\n' >"$work/broken.urdf"
printf 'empty\n.\n' >"$work/empty.scene"
cat >"$work/bad_urdf.yaml" <<EOT
experiment: {name: x, time_limit: 1}
robot: {format: urdf, file: broken.urdf, joints: [j]}
scenes: [{name: s, format: moveit-scene, file: empty.scene, queries: [{name: q, start: [0], goal: [0]}]}]
planners: [{planner: null, algorithms: [a]}]
EOT
bad_case bad_urdf.yaml "broken.urdf: urdf: line 3, column .*not well-formed XML"

printf 'bad\n* box\n0 0 0\n0 0 0 1\n1\nbox\n1 x 1\n' >"$work/broken.scene"
cat >"$work/bad_scene.yaml" <<EOT
experiment: {name: x, time_limit: 1}
robot: {format: urdf, file: $MPB_SOURCE/tests/support/data/pr2_right_arm.urdf, joints: [r_shoulder_pan_joint]}
scenes: [{name: s, format: moveit-scene, file: broken.scene, queries: [{name: q, start: [0], goal: [0]}]}]
planners: [{planner: null, algorithms: [a]}]
EOT
bad_case bad_scene.yaml "broken.scene: scene line 7"

# ---- obstacles thinner than the verification step ---------------------------
# At 0.01 rad the planar arm's tip moves up to 1.42 m/rad x 0.01 rad; a
# 2 mm box and an 8 mm circle can be passed through between two samples,
# the 0.3 m pillar cannot. A warning each, at --check and at load; the
# experiment is still good (exit 0).
printf 'circle 0.0 0.8 0.15\nbox 0.0 -0.9 0.3 0.001\ncircle 0.5 0.5 0.004\n' >"$work/thin.scene"
MPB_QUERIES='{name: q, start: [0, 0, 0], goal: [0.1, 0, 0], tolerance: 0.01}'
cat >"$work/thin.yaml" <<EOT
experiment: {name: thin, runs: 1, time_limit: 1}
robot: {format: planar, file: $MPB_SOURCE/scenes/planar/arm3.robot}
scenes: [{name: thin, format: planar, file: thin.scene, queries: [$MPB_QUERIES]}]
planners: [{planner: null, algorithms: [straight_line]}]
EOT
"$daemon" --check "$work/thin.yaml" >"$work/thin.out" 2>"$work/thin.err"
check "--check of a scene with thin obstacles exits 0" eq $? 0
check "... warning of each thin one, by its line, with the numbers" \
    sh -c "grep -q \"warning: scene 'thin': the box of line 2 is 0.002 m thick, less than the 0.0142 m the end effector may move between two verification samples (0.01 rad x 1.42 m/rad)\" '$work/thin.err' &&
           grep -q \"the circle of line 3 is 0.008 m thick\" '$work/thin.err'"
check "... and of no other" eq "$(grep -c warning "$work/thin.err")" 2
"$daemon" --check -r 0.005 "$work/thin.yaml" >/dev/null 2>"$work/thin-fine.err"
check "at half the step the circle is thick enough: one warning" \
    eq "$(grep -c warning "$work/thin-fine.err")" 1
# A planar arm of 2 mm links: those are thin too, said once.
sed 's/^link_radius .*/link_radius 0.001/' "$MPB_SOURCE/scenes/planar/arm3.robot" >"$work/thin.robot"
sed "s|file: $MPB_SOURCE/scenes/planar/arm3.robot|file: thin.robot|" "$work/thin.yaml" >"$work/thin-arm.yaml"
"$daemon" --check "$work/thin-arm.yaml" >/dev/null 2>"$work/thin-arm.err"
check "a planar arm with 2 mm links is warned of once" \
    eq "$(grep -c "warning: the robot's links are 0.002 m thick (link_radius 0.001), less than the 0.0142 m" "$work/thin-arm.err")" 1
"$daemon" --check "$MPB_SOURCE/scenes/experiments/paper-demo.yaml" >/dev/null 2>"$work/paper.err"
# (It may say how the robot's self-collision matrix was made: no warning.)
check "the paper's scenes have no part too thin" \
    eq "$(grep -c 'warning' "$work/paper.err")" 0
# A MoveIt scene with a 2 mm plate, for the PR2's arm.
printf 'thin\n* plate\n0 0 0\n0 0 0 1\n1\nbox\n0.5 0.5 0.002\n1.5 -1.5 0.2\n0 0 0 1\n0 0 0 0\n0\n.\n' >"$work/plate.scene"
cat >"$work/plate.yaml" <<EOT
experiment: {name: plate, runs: 1, time_limit: 1}
robot: {format: urdf, file: $MPB_SOURCE/scenes/robots/pr2_right_arm.urdf, joints: [r_shoulder_pan_joint, r_shoulder_lift_joint, r_upper_arm_roll_joint, r_elbow_flex_joint, r_forearm_roll_joint, r_wrist_flex_joint, r_wrist_roll_joint]}
scenes: [{name: plated, format: moveit-scene, file: plate.scene, queries: [{name: q, start: [-1.2, 1.1, -1.5, -1.9, 0, -0.6, 0], goal: [-1.2, 1.1, -1.5, -1.9, 0, -0.6, 0.1]}]}]
planners: [{planner: null, algorithms: [straight_line]}]
EOT
"$daemon" --check "$work/plate.yaml" >/dev/null 2>"$work/plate.err"
check "a MoveIt scene's thin box is named by its object and line" \
    grep -q "warning: scene 'plated': object 'plate' (shape of line 6) is 0.002 m thick" "$work/plate.err"

# ---- a scene too large for one LCM message ---------------------------------
# Every receive socket drops a message over MPB_LCM_MESSAGE_MAX (16 MiB),
# so the plan requests carrying this scene would vanish: refused at load
# and at --check, with the sizes. A 65-byte comment line doubled 18 times
# is 17,039,360 bytes.
printf '# padding to make a scene too large for one LCM message: 0123456\n' >"$work/huge.scene"
i=0
while [ "$i" -lt 18 ]; do
    cat "$work/huge.scene" "$work/huge.scene" >"$work/huge.tmp"
    mv "$work/huge.tmp" "$work/huge.scene"
    i=$((i + 1))
done
cat >"$work/huge_scene.yaml" <<EOT
experiment: {name: huge, runs: 1, time_limit: 1}
robot: {format: planar, file: $base/arm3.robot}
scenes: [{name: huge, format: planar, file: huge.scene, queries: [{name: q, start: [0, 0, 0], goal: [0.1, 0, 0]}]}]
planners: [{planner: null, algorithms: [straight_line]}]
EOT
bad_case huge_scene.yaml ": scene 'huge' (query 'q'): its plan request would be [0-9]* bytes (robot 228, scene 17039360), over the 16777216-byte bound of an LCM message"
out=$("$daemon" --check "$work/huge_scene.yaml" 2>&1)
check "--check refuses it too" test $? -ne 0
check "... in one line with the sizes" \
    sh -c "printf '%s\n' \"\$1\" | grep -c 'scene 17039360), over the 16777216-byte bound' | grep -qx 1" _ "$out"
plain=$(printf '%s' "$out" | sed -n 's/.*would be \([0-9]*\) bytes.*/\1/p')
head -c 32 /dev/urandom >"$work/secret"
out=$("$daemon" --check --secret-file "$work/secret" "$work/huge_scene.yaml" 2>&1)
check "with a secret the request is 56 bytes longer (the trailer)" \
    sh -c "printf '%s' \"\$1\" | grep -q 'would be $((plain + 56)) bytes'" _ "$out"
# Cut to exactly the bound without a trailer: good without a secret, one
# byte per trailer byte too long with one.
head -c $((17039360 - (plain - 16777216))) "$work/huge.scene" >"$work/huge.tmp"
mv "$work/huge.tmp" "$work/huge.scene"
"$daemon" --check "$work/huge_scene.yaml" >/dev/null 2>&1
check "a request of exactly 16 MiB is accepted" eq $? 0
out=$("$daemon" --check --secret-file "$work/secret" "$work/huge_scene.yaml" 2>&1)
check "... but not with the 56-byte trailer of a secret" \
    sh -c "printf '%s' \"\$1\" | grep -q 'would be 16777272 bytes'" _ "$out"
rm -f "$work/huge.scene"
check "database still untouched" test "$(md5sum <"$DB")" = "$sum_before"

out=$("$daemon" -d "$DB" "$work/nosuch.yaml" 2>&1)
check "a missing experiment file is refused" test $? -ne 0
check "... with a message naming it" \
    sh -c "printf '%s' \"\$1\" | grep -q 'nosuch.yaml: cannot read'" _ "$out"
check "database still untouched" test "$(md5sum <"$DB")" = "$sum_before"

mpb_finish
