#!/bin/sh
# When the first run of every planner configuration fails with the same
# world error (here: the planner cannot find the robot's mesh, which lies
# beside the URDF where only mpbenchd looks), mpbenchd says so in one line
# and stops instead of running every doomed run; the runs stored stay,
# and the same command resumes once the planner is fixed. A failure of
# one configuration alone does not stop it.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
DB=$work/doomed.db
daemon=$MPB_BUILD/daemon/mpbenchd
planner=$MPB_BUILD/planners/ompl/mpb-planner-ompl
data=$MPB_SOURCE/tests/support/data/meshes
unset MPB_MESH_PATH ROS_PACKAGE_PATH

cat >"$work/exp.yaml" <<EOT
experiment: {name: doomed, runs: 20, time_limit: 2, seed: 1}
robot: {format: urdf, file: $data/mesh_arm.urdf, joints: [j]}
scenes:
  - name: empty
    format: moveit-scene
    text: "(empty)\n.\n"
    queries:
      - {name: q, start: [0], goal: [0.5]}
planners:
  - {planner: ompl, algorithms: [RRTConnect, RRT]}
EOT

mpb_spawn "$work/lost.log" "$planner"
mpb_timeout 120 "$daemon" -d "$DB" "$work/exp.yaml" >"$work/d1.log" 2>&1
status=$?
mpb_stop_all
check "mpbenchd stops with exit 1" eq "$status" 1
check "... saying why in one line, the planner's error named" \
    sh -c "grep -c \"stopped: the first run of every planner configuration (2) failed with the same error, so every run would: world: mesh 'package://mesh_pkg/meshes/cube.stl': not found.*runs left: fix it and run the same command to resume\" '$work/d1.log' | grep -qx 1"
done1=$(q "SELECT count(*) FROM runs WHERE state = 'done'")
check "... before running most of the 40 runs ($done1 done)" test "$done1" -lt 20
[ "$status" -eq 1 ] || cat "$work/d1.log"

# Fixed: the same command resumes, keeps what was stored, runs the rest.
MPB_MESH_PATH=$data mpb_spawn "$work/fixed.log" "$planner"
mpb_timeout 120 "$daemon" -d "$DB" "$work/exp.yaml" >"$work/d2.log" 2>&1
status=$?
mpb_stop_all
check "the same command resumes and completes" eq "$status" 0
check "... one experiment, all 40 runs done" \
    eq "$(q "SELECT count(*) FROM runs r JOIN experiments e ON r.experiment_id = e.id WHERE r.state = 'done'")" 40
check "... the runs stored before the stop kept" \
    eq "$(q "SELECT count(*) FROM runs WHERE status = 'invalid_request'")" "$done1"
check "... the others solved" \
    eq "$(q "SELECT count(*) FROM results WHERE success = 1")" $((40 - done1))
[ "$status" -eq 0 ] || cat "$work/d2.log"

# Only one configuration fails (an algorithm the planner lacks is not a
# world error; here one config's planner finds the mesh): no stop. A
# null planner configuration alongside, which needs no mesh.
cat >"$work/mixed.yaml" <<EOT
experiment: {name: mixed, runs: 3, time_limit: 2, seed: 1}
robot: {format: urdf, file: $data/mesh_arm.urdf, joints: [j]}
scenes:
  - name: empty
    format: moveit-scene
    text: "(empty)\n.\n"
    queries:
      - {name: q, start: [0], goal: [0.5]}
planners:
  - {planner: ompl, algorithms: [RRTConnect]}
  - {planner: null, algorithms: [straight_line]}
EOT
mpb_spawn "$work/lost2.log" "$planner"
mpb_spawn "$work/null.log" "$MPB_BUILD/planners/null/mpb-planner-null"
mpb_timeout 120 "$daemon" -d "$DB" "$work/mixed.yaml" >"$work/d3.log" 2>&1
status=$?
mpb_stop_all
check "a failure of one configuration alone does not stop the runs" eq "$status" 0
[ "$status" -eq 0 ] || cat "$work/d3.log"
mpb_finish
