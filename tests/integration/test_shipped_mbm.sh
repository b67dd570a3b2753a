#!/bin/sh
# A shipped MotionBenchMaker experiment runs with tools/run_benchmark.sh
# and nothing set: the planners it starts find the robot's meshes beside
# its URDF, as mpbenchd does (its package:// URIs resolve nowhere else).
# Two problems of scenes/experiments/mbm-panda-quick.yaml, its robot and
# first problem set as written there, with RRTConnect. And mpbenchd
# --check warns about planners started apart, which would not find them.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"

"$MPB_SOURCE/tools/robot_data.sh" --check ||
    "$MPB_SOURCE/tools/robot_data.sh" >/dev/null || exit 1
unset MPB_MESH_PATH ROS_PACKAGE_PATH

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
DB=$work/mbm.db
shipped=$MPB_SOURCE/scenes/experiments/mbm-panda-quick.yaml
# The shipped file's robot and first problem set, paths made absolute
# (the shipped ones are relative to its folder), two problems of it.
exp_dir=$MPB_SOURCE/scenes/experiments
{
    echo "experiment: {name: shipped-mbm, time_limit: 10, seed: 1}"
    sed -n '/^robot:/,/^scenes:/p' "$shipped" | sed "s#: \.\./#: $exp_dir/../#"
    sed -n '/^  - problems:/{p;q}' "$shipped" | sed "s#: \.\./#: $exp_dir/../#"
    echo "    count: 2"
    echo "    clamp_joint_values: true"
    echo "planners:"
    echo "  - {planner: ompl, algorithms: [RRTConnect]}"
} >"$work/two.yaml"

out=$("$MPB_BUILD/daemon/mpbenchd" --check "$shipped" 2>&1)
check "--check on the shipped file warns that planners started apart miss the meshes" \
    sh -c "printf '%s' \"\$1\" | grep -q \"warning: robot: 11 meshes (the first 'package://meshes/collision/link0.obj') are found only beside its URDF\"" _ "$out"
check "... and names the folder to give them" \
    sh -c "printf '%s' \"\$1\" | grep -q 'MPB_MESH_PATH=/.*/panda '" _ "$out"
check "--mesh-path prints that folder" \
    sh -c "[ -f \"\$('$MPB_BUILD/daemon/mpbenchd' --mesh-path '$shipped')/panda.urdf\" ]"

out=$(MPB_BUILD=$MPB_BUILD mpb_timeout 200 sh "$MPB_SOURCE/tools/run_benchmark.sh" \
      -d "$DB" -p ompl -l "$work/logs" "$work/two.yaml" 2>&1)
check "run_benchmark.sh runs the two problems with no variable set" eq $? 0
check "both are solved and verified" \
    eq "$(q "SELECT count(*) FROM results WHERE success = 1")" 2
check "no run was an invalid request" \
    eq "$(q "SELECT count(*) FROM runs WHERE status = 'invalid_request'")" 0
[ "$(q "SELECT count(*) FROM results WHERE success = 1")" = 2 ] ||
    { printf '%s\n' "$out"; cat "$work"/logs/*.log; }
mpb_finish
