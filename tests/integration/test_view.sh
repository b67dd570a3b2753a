#!/bin/sh
# mpb view: a PR2 kitchen run whose straight line goes through the counter
# (the null planner's, found in collision by the verifier) is written as a
# page, opened in a real headless Chromium with every request but the file
# refused, and checked there (view_check.js): no console errors, a 3-D view
# that is not blank, a slider that moves the robot, a goal that is drawn,
# the verifier's message and the two bodies in contact on the page. The
# same for a planar run, and for a valid OMPL run to a goal region. A page
# with a broken script fails the same checks. Bad input (an unknown
# run, a run with no stages, a database that is not mpbench's) gets one
# line and exit 1, and no page.
#
# MPB_VIEW_SCREENSHOT=FILE keeps the kitchen page's screenshot there (how
# docs/images/view-kitchen.png is made); MPB_KEEP=1 keeps the work folder
# (the pages, the screenshots) to look at.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; [ -n "${MPB_KEEP:-}" ] || rm -rf "$work"' EXIT
DB=$work/view.db
mpb=$MPB_BUILD/tools/mpb
export MPB_WEB_MODULES="$MPB_SOURCE/.cache/web/node_modules"
if [ ! -d "$MPB_WEB_MODULES/playwright-core" ] || [ ! -x /usr/bin/chromium ]; then
    echo "not ok - chromium and playwright-core are needed: run make deps (tools/web_env.sh)"
    exit 1
fi

joints="[r_shoulder_pan_joint, r_shoulder_lift_joint, r_upper_arm_roll_joint, r_elbow_flex_joint, r_forearm_roll_joint, r_wrist_flex_joint, r_wrist_roll_joint]"
cat >"$work/kitchen.yaml" <<EOF
experiment: {name: kitchen-view, runs: 1, time_limit: 5}
robot: {format: urdf, file: $MPB_SOURCE/scenes/robots/pr2_right_arm.urdf, joints: $joints}
scenes:
  - name: kitchen
    format: moveit-scene
    file: $MPB_SOURCE/scenes/paper/kitchen.scene
    queries:
      - {name: through_the_counter, start: [0, 0, 0, -1, 0, -1, 0], goal: [-1.2, 1.1, -1.5, -1.9, 0, -0.6, 0], tolerance: 0.01}
      - name: counter_cup
        start: [-1.2, 1.1, -1.5, -1.9, 0, -0.6, 0]
        goal: {link: r_gripper_tool_frame, position: [0.62, -0.08, 1.0], position_tolerance: [0.01, 0.01, 0.01], rpy: [0, 1.5708, 0], rpy_tolerance: [0.05, 0.05, 0.05]}
planners:
  - {planner: null, algorithms: [straight_line]}
EOF
mpb_spawn "$work/null.log" "$MPB_BUILD/planners/null/mpb-planner-null"
mpb_timeout 60 "$MPB_BUILD/daemon/mpbenchd" -d "$DB" "$work/kitchen.yaml" >"$work/daemon.log" 2>&1
check "the kitchen experiment completes" eq $? 0
run=$(q "SELECT r.id FROM runs r JOIN queries q ON q.id = r.query_id WHERE q.name = 'through_the_counter'")
detail=$(q "SELECT verdict_detail FROM stages WHERE run_id = $run")
check "the straight line through the counter is found colliding" \
    test "$(q "SELECT verdict FROM stages WHERE run_id = $run")" = collision

"$mpb" view "$DB" "$run" -o "$work/kitchen.html" >"$work/out" 2>&1
check "mpb view writes the page" eq $? 0
check "... and says where" grep -q "^wrote $work/kitchen.html$" "$work/out"
check "... with three.js in it, the page needs no network" \
    grep -q 'Copyright 2010-2024 Three.js Authors' "$work/kitchen.html"
node "$MPB_SOURCE/tests/integration/view_check.js" "$work/kitchen.html" \
    "$detail" "$work/kitchen.png" >"$work/check.out" 2>&1
status=$?
sed 's/^/    /' "$work/check.out"
check "headless Chromium: every check of the kitchen page passes" eq $status 0
check "... the message it looked for is the verifier's" test -n "$detail"
if [ -n "${MPB_VIEW_SCREENSHOT:-}" ] && [ -f "$work/kitchen.png" ]; then
    cp "$work/kitchen.png" "$MPB_VIEW_SCREENSHOT"
fi

# A goal region (its box and orientation cone): a real OMPL run, valid.
RDB=$work/region.db
sed -e 's/name: kitchen-view/name: region-view/' -e '/through_the_counter/d' \
    -e 's/planner: null, algorithms: \[straight_line\]/planner: ompl, algorithms: [RRTConnect]/' \
    "$work/kitchen.yaml" >"$work/region.yaml"
mpb_spawn "$work/ompl.log" "$MPB_BUILD/planners/ompl/mpb-planner-ompl"
mpb_timeout 60 "$MPB_BUILD/daemon/mpbenchd" -d "$RDB" "$work/region.yaml" >"$work/region.log" 2>&1
check "the region experiment completes" eq $? 0
check "... its run valid" test "$(sqlite3 "$RDB" "SELECT verdict FROM runs")" = valid
"$mpb" view "$RDB" 1 -o "$work/region.html" >/dev/null 2>&1
check "mpb view writes the region goal's page" eq $? 0
check "... with the goal region in it" \
    grep -q '"goal":{"kind":"region","link":"r_gripper_tool_frame","center":\[0.62,-0.08,1\]' "$work/region.html"
node "$MPB_SOURCE/tests/integration/view_check.js" "$work/region.html" \
    "valid" "$work/region.png" valid >"$work/region.out" 2>&1
status=$?
sed 's/^/    /' "$work/region.out"
check "headless Chromium: every check of the region page passes" eq $status 0

# The checks can fail: the same page with its script broken.
sed 's/setStage(firstBad);/setStage(firstBad); undefinedFunction();/' \
    "$work/kitchen.html" >"$work/broken.html"
node "$MPB_SOURCE/tests/integration/view_check.js" "$work/broken.html" \
    "$detail" "$work/broken.png" >"$work/broken.out" 2>&1
check "a page with a broken script fails the checks" test $? -ne 0
check "... saying so" grep -q "not ok - no console errors" "$work/broken.out"

# The planar world: a straight line over the pillar.
PDB=$work/planar.db
MPB_QUERIES='{name: over_the_pillar, start: [0, 0, 0], goal: [2.6, 0, 0], tolerance: 0.01}' \
    mpb_planar_experiment "$work/planar.yaml" "name: planar-view, runs: 1, time_limit: 5" \
    "{planner: null, algorithms: [straight_line]}"
mpb_timeout 60 "$MPB_BUILD/daemon/mpbenchd" -d "$PDB" "$work/planar.yaml" >"$work/planar.log" 2>&1
check "the planar experiment completes" eq $? 0
pdetail=$(sqlite3 "$PDB" "SELECT verdict_detail FROM stages WHERE run_id = 1")
"$mpb" view "$PDB" 1 -o "$work/planar.html" >/dev/null 2>&1
check "mpb view writes the planar page" eq $? 0
node "$MPB_SOURCE/tests/integration/view_check.js" "$work/planar.html" \
    "$pdetail" "$work/planar.png" >"$work/planar.out" 2>&1
status=$?
sed 's/^/    /' "$work/planar.out"
check "headless Chromium: every check of the planar page passes" eq $status 0

# A stage with a NaN in it (as a forged result may have) is listed with
# its verdict, not drawn, and the rest of the page is written.
cp "$DB" "$work/nan.db"
sqlite3 "$work/nan.db" "UPDATE stages SET waypoints = X'000000000000F87F$(printf '0000000000000000%.0s' $(seq 13))', verdict = 'not_finite', verdict_detail = 'waypoint 0 joint r_shoulder_pan_joint is nan' WHERE run_id = $run"
"$mpb" view "$work/nan.db" "$run" -o "$work/nan.html" >/dev/null 2>&1
check "a stage with a NaN still gets a page" eq $? 0
check "... the stage listed with its verdict, no frame drawn" \
    grep -q '"verdict":"not_finite","detail":"waypoint 0 joint r_shoulder_pan_joint is nan","segment":0,"waypoints":0,"frames":0' "$work/nan.html"

# Where a run is, said once: "kitchen / through_the_counter"; a query
# named as its scene (MotionBenchMaker's problems name both
# "cage_panda/0001"), or under it, is not repeated (issue 40).
check "the page's title names the scene and the query" \
    grep -q "<title>mpb view: run $run, null/straight_line, kitchen / through_the_counter</title>" \
    "$work/kitchen.html"
check "... and so does its data, which titles the page" \
    grep -q '"place":"kitchen / through_the_counter"' "$work/kitchen.html"
cp "$DB" "$work/mbm.db"
sqlite3 "$work/mbm.db" "UPDATE scenes SET name = 'cage_panda/0001'; UPDATE queries SET name = 'cage_panda/0001' WHERE id = (SELECT query_id FROM runs WHERE id = $run)"
"$mpb" view "$work/mbm.db" "$run" -o "$work/mbm.html" >/dev/null 2>&1
check "a query named as its scene: mpb view writes the page" eq $? 0
check "... its title says the name once" \
    grep -q "<title>mpb view: run $run, null/straight_line, cage_panda/0001</title>" \
    "$work/mbm.html"
check "... and so does its data" grep -q '"place":"cage_panda/0001"' "$work/mbm.html"
"$mpb" view "$work/mbm.db" --failed -o "$work/mbm-failed" >/dev/null 2>&1
check "... and the index of failed runs" \
    grep -q "<td>cage_panda/0001</td>" "$work/mbm-failed/index.html"
check "... never twice" sh -c "! grep -q 'cage_panda/0001 / cage_panda/0001' '$work/mbm-failed/index.html' '$work/mbm.html'"

# Without -o: a new file, its path said, and that there is no display.
out=$(env -u DISPLAY -u WAYLAND_DISPLAY TMPDIR="$work" "$mpb" view "$DB" "$run")
check "without -o it writes a new file and says where" \
    test -s "$(printf '%s\n' "$out" | sed -n 's/^wrote //p')"
check "... and that there is no display here" \
    test "$(printf '%s\n' "$out" | grep -c 'no display here')" = 1

# Runs chosen by name: one is drawn as a run id would be; the failed ones
# of the experiment, one page each with an index linking them.
"$mpb" view "$DB" --query through_the_counter -o "$work/by-name.html" >/dev/null 2>&1
check "--query with one run writes its page" eq $? 0
check "... the same run's" \
    test "$(grep -o '"run":{"id":[0-9]*' "$work/by-name.html")" = "\"run\":{\"id\":$run"
"$mpb" view "$DB" --failed --planner null/straight_line -o "$work/failed" >"$work/failed.out" 2>&1
check "--failed writes a folder of pages" eq $? 0
check "... a page for the failed run with stages" test -s "$work/failed/run-$run.html"
check "... none for the one without" \
    test "$(ls "$work/failed" | grep -c '^run-.*html$')" = 1
check "... an index that links the page" grep -q "href=\"run-$run.html\"" "$work/failed/index.html"
check "... and lists the run without stages with its reason" \
    grep -q "straight_line needs a joint-space goal" "$work/failed/index.html"

# Bad input: one line, exit 1, no page, the database as it was.
before=$(md5sum <"$DB")
bad() {   # bad NAME EXIT PATTERN ARGS...
    what=$1; want=$2; pattern=$3; shift 3
    rm -f "$work/bad.html"
    "$mpb" view "$@" -o "$work/bad.html" >"$work/bad.out" 2>"$work/bad.err"
    got=$?
    check "$what: exit $want" eq "$got" "$want"
    check "$what: one line naming it" \
        test "$(wc -l <"$work/bad.err")" = 1 -a "$(grep -c -- "$pattern" "$work/bad.err")" = 1
    check "$what: no page" test ! -e "$work/bad.html"
    sed 's/^/    # /' "$work/bad.err"
}
bad "an unknown run id" 1 "view.db: no run 999" "$DB" 999
norun=$(q "SELECT r.id FROM runs r JOIN queries q ON q.id = r.query_id WHERE q.name = 'counter_cup'")
bad "a run with no stages" 1 "run $norun has no stages to draw (invalid_request: straight_line needs a joint-space goal)" "$DB" "$norun"
sqlite3 "$work/other.db" "CREATE TABLE t(x); INSERT INTO t VALUES (1);"
bad "a database that is not mpbench's" 1 "other.db" "$work/other.db" 1
check "... which is left as it was" test "$(sqlite3 "$work/other.db" "SELECT x FROM t")" = 1
bad "a database that is not there" 1 "nothing.db: No such file" "$work/nothing.db" 1
bad "a run id that is not a number" 2 "RUN is a run id (a number), not 'x'" "$DB" x
bad "a query no run has" 1 "no finished run of experiment 1 for query 'none'" "$DB" --query none
bad "a run id and a selection" 2 "a run id, or --experiment" "$DB" 1 --failed
MPB_THREE_JS=$work/none.js bad "three.js missing" 1 "cannot read three.js at $work/none.js" "$DB" "$run"
check "the database is as it was" test "$(md5sum <"$DB")" = "$before"

mpb_finish
