#!/bin/sh
# mpb verify: the stored runs of an experiment checked again with this
# mpbench's world model. A database verified under the same model holds
# no change (exit 0); once the stored world differs from what the runs
# were verified in (an obstacle on the path, the SRDF's pair dropped so
# the arm's path goes through the robot's own post), each changed stage
# is listed with its new verdict, the totals count the lost successes and
# those through the robot's body, and the database is left byte-identical.
# A run verified with joints held outside the group is verified again
# holding the same values.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
DB=$work/test.db
daemon=$MPB_BUILD/daemon/mpbenchd
mpb=$MPB_BUILD/tools/mpb
data=$MPB_SOURCE/tests/support/data

# The folding arm: its SRDF lets arm1 pass through the post. The straight
# line from the origin to "through the post" is free with it.
cat >"$work/exp.yaml" <<EOT
experiment: {name: again, runs: 2, time_limit: 5}
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
planners:
  - {planner: null, algorithms: [straight_line]}
EOT
mpb_spawn "$work/null.log" "$MPB_BUILD/planners/null/mpb-planner-null"
mpb_timeout 60 "$daemon" -d "$DB" "$work/exp.yaml" >"$work/daemon.log" 2>&1
check "the experiment completes" eq $? 0
check "... both runs succeed" eq "$(q 'SELECT count(*) FROM results WHERE success = 1')" 2

# totals OUT: the line of the verdicts' totals; outcomes OUT: that of the
# runs decided again by the success rule.
totals() { printf '%s\n' "$1" | grep '^experiment '; }
outcomes() { printf '%s\n' "$1" | grep '^outcomes '; }
out=$("$mpb" verify "$DB")
check "verified again under the same model: exit 0" eq $? 0
check "... and the totals say nothing changed" test "$(totals "$out")" = \
    "experiment 1: 2 runs with stages, 2 stages verified again; 0 stages of 0 runs changed verdict; 0 of 2 successes no longer hold (0 through the robot's own body)"
check "... every run decided as the daemon did" test "$(outcomes "$out")" = \
    "outcomes by the success rule: unclaimed 0, verified 2, refused 0, late 0, unclaimed_valid 0; 0 runs decided otherwise than stored"
check "... in two lines, nothing else" eq "$(printf '%s\n' "$out" | wc -l)" 2

# The stored robot without its SRDF: the matrix is generated, arm1 and the
# post are checked, and the same paths go through the robot's own body.
sum=$(md5sum <"$DB")
cp "$DB" "$work/edited.db"
sqlite3 "$work/edited.db" "UPDATE scenes SET robot = substr(robot, 1, instr(robot, '</robot>') + 7)"
out=$("$mpb" verify "$work/edited.db")
check "with the SRDF gone the verdicts change: exit 1" eq $? 1
check "... one line per changed stage, naming the new verdict and the links" eq \
    "$(printf '%s\n' "$out" | grep -c "^run [0-9]* empty/into_post null/straight_line stage raw: stored valid, now collision: segment 0 collides at s=.*self-collision between arm1 and post (depth [0-9.e+-]*-[0-9.e+-]* mm)$")" 2
check "... the runs once verified now refused claims, one line each" eq \
    "$(printf '%s\n' "$out" | grep -c "^run [0-9]* empty/into_post null/straight_line: stored verified, now refused$")" 2
check "... counted so by the success rule" test "$(outcomes "$out")" = \
    "outcomes by the success rule: unclaimed 0, verified 0, refused 2, late 0, unclaimed_valid 0; 2 runs decided otherwise than stored"
check "... and the totals count them as through the robot's body" test \
    "$(totals "$out")" = \
    "experiment 1: 2 runs with stages, 2 stages verified again; 2 stages of 2 runs changed verdict; 2 of 2 successes no longer hold (2 through the robot's own body)"

# An obstacle on the path in the stored scene: a collision with it.
cp "$DB" "$work/obstacle.db"
sqlite3 "$work/obstacle.db" "UPDATE scenes SET scene = 'block
* wall
0.5 0 0.15
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
out=$("$mpb" verify "$work/obstacle.db")
check "an obstacle on the path: exit 1" eq $? 1
check "... the stage names the scene object" sh -c \
    "printf '%s\n' \"\$1\" | grep -q 'stored valid, now collision: .*touches scene object wall'" _ "$out"
check "... not through the robot's body" sh -c \
    "printf '%s\n' \"\$1\" | grep '^experiment ' | grep -q '2 of 2 successes no longer hold (0 through'" _ "$out"

check "the database itself is untouched" test "$(md5sum <"$DB")" = "$sum"

# Held joints: the sliding block held at 0.5 (robot.joint_values) is in
# the way of the arm's straight line, so the run is stored a collision
# with the matrix generated for that value; mpb verify holds the query's
# stored values too, so nothing changes (at the default, 0, the block
# would sit on the arm, the pair allowed, the line free).
HDB=$work/held.db
cat >"$work/held.yaml" <<EOT
experiment: {name: held, runs: 1, time_limit: 5}
robot:
  format: urdf
  file: $data/sliding_block.urdf
  joints: [j]
  joint_values: {slide: 0.5}
scenes:
  - name: empty
    format: moveit-scene
    text: "(empty)\n.\n"
    queries:
      - {name: sweep, start: [-1], goal: [1.5]}
planners:
  - {planner: null, algorithms: [straight_line]}
EOT
mpb_timeout 60 "$daemon" -d "$HDB" "$work/held.yaml" >"$work/held.log" 2>&1
check "held: the experiment completes" eq $? 0
check "... the line stored a collision with the block it holds in the way" \
    sh -c "sqlite3 '$HDB' \"SELECT verdict || ': ' || verdict_detail FROM stages\" | grep -q '^collision: .*self-collision between arm and block'"
check "... the query's held value stored" test \
    "$(sqlite3 "$HDB" 'SELECT held FROM queries')" = "slide=0.5"
out=$("$mpb" verify "$HDB")
check "... verified again holding it: exit 0, nothing changed" test "$?:$(totals "$out")" = \
    "0:experiment 1: 1 runs with stages, 1 stages verified again; 0 stages of 0 runs changed verdict; 0 of 0 successes no longer hold (0 through the robot's own body)"
check "... its claim refused again" test "$(outcomes "$out")" = \
    "outcomes by the success rule: unclaimed 0, verified 0, refused 1, late 0, unclaimed_valid 0; 0 runs decided otherwise than stored"
check "... and the depth of its collision counted" \
    sh -c "printf '%s\\n' \"\$1\" | grep -q '^1 collision verdicts, 1 with a depth: '" _ "$out"

# Bad command lines and inputs: one line each.
"$mpb" verify >/dev/null 2>&1
check "no database: exit 2" eq $? 2
out=$("$mpb" verify -e 7 "$DB" 2>&1)
check "an unknown experiment: exit 1, one line" test "$?:$out" = \
    "1:mpb verify: $DB: no experiment 7"
out=$("$mpb" verify -r 0 "$DB" 2>&1)
check "a step of 0: exit 2, one line" test "$?:$out" = \
    "2:mpb verify: --resolution wants a step in rad, more than 0 and at most 1, not '0'"

mpb_finish
