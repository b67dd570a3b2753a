#!/bin/sh
# MotionBenchMaker on the Panda: a fixed sample of the seven problem sets
# (the first 5 of each, scenes/experiments/mbm-panda-quick.yaml) loads,
# and every start and goal is collision-free under the full mesh model
# and the allowed-collision matrix (mpbenchd --check refuses a state in
# collision, naming the bodies). Then OMPL's RRTConnect, a real planner
# process, solves two problems and mpbench verifies both paths in the
# same world: meshes, matrix and held joints. tools/mbm_check.sh checks
# all 700.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
PASSES=0
FAILS=0

# The data before the private network (which has no way out).
if [ -z "${MPB_IN_NETNS:-}" ]; then
    "$MPB_SOURCE/tools/robot_data.sh" --check ||
        "$MPB_SOURCE/tools/robot_data.sh" >/dev/null || exit 1
fi
mpb_enter_netns "$0" "$@"
panda=$MPB_PANDA

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
DB=$work/test.db
daemon=$MPB_BUILD/daemon/mpbenchd

out=$("$daemon" --check "$MPB_SOURCE/scenes/experiments/mbm-panda-quick.yaml" 2>&1)
check "the sample of 35 problems loads, every start and goal free" \
    sh -c "printf '%s' \"\$1\" | grep -q 'ok: 35 scenes, 35 queries'" _ "$out"
check "... and the daemon says the fixed fingers' values were skipped" \
    sh -c "printf '%s' \"\$1\" | grep -q '0 joint values moved into their limits and 140 of fixed joints ignored'" _ "$out"

# Two problems, planned by a real OMPL planner, which finds the meshes
# through MPB_MESH_PATH (the URDF says package://meshes/...).
cat >"$work/two.yaml" <<EOT
experiment: {name: two, time_limit: 10, seed: 3}
$(mpb_panda_robot)
scenes:
  - {problems: $panda/problems/bookshelf_thin_panda, first: 3, count: 1, clamp_joint_values: true}
  - {problems: $panda/problems/table_pick_panda, count: 1, clamp_joint_values: true}
planners:
  - {planner: ompl, algorithms: [RRTConnect]}
EOT
MPB_MESH_PATH=$panda mpb_spawn "$work/ompl.log" "$MPB_BUILD/planners/ompl/mpb-planner-ompl"
mpb_timeout 120 "$daemon" -d "$DB" "$work/two.yaml" >"$work/daemon.log" 2>&1
status=$?
check "mpbenchd runs both problems and exits 0" eq "$status" 0
[ "$status" -eq 0 ] || cat "$work/daemon.log" "$work/ompl.log"
check "RRTConnect solves both, each path verified by mpbench" \
    eq "$(q "SELECT count(*) FROM results WHERE success = 1")" 2
check "... the queries named after their set and number" \
    eq "$(q "SELECT count(*) FROM queries WHERE name IN
             ('bookshelf_thin_panda/0003', 'table_pick_panda/0001')")" 2
check "... and each scene's robot text carries the scene's allowed pairs" \
    eq "$(q "SELECT count(*) FROM scenes WHERE robot LIKE '%reason=\"Scene\"%'")" 2

mpb_finish
