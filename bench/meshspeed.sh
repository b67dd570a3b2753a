#!/bin/sh
# bench/meshspeed.sh - issue 27, "meshes at speed": a robot with real
# meshes checked against the paper's primitive PR2, in the same run
# (docs/performance.md, item 4m). In process, no network.
#
#   bench/meshspeed.sh [--bin DIR] [--states N] [--rounds N] [--seconds S]
#                      [--set NAME] [--scene N]
#
# Needs the Panda and MotionBenchMaker's problem sets in .cache/robots
# (tools/robot_data.sh fetches them; without them it says so and stops).
# bench/mbm_scene.py turns one scene (default table_pick_panda scene 1)
# into a .scene text; then
#   1. mpb-bench-meshcheck: the Panda (its SRDF, its collision meshes) at
#      N fixed-seed random states in that scene against the primitive PR2
#      right arm in the paper's kitchen, in interleaved rounds, thread CPU
#      time: collision, contact and clearance per check, and their ratios
#      (at most 3x for a collision check is the target);
#   2. mpb-bench-verify: verification + metrics on a free straight Panda
#      path in that scene, waypoints per second, at the resolution (0.01
#      rad) and 0.1 rad apart.
# Prints RESULT lines (meshcheck_*, verify_panda_*), which bench/run.sh
# collects and bench/table.sh reads. DIR holds the bench programs
# (default: built now in the build tree, MPB_BUILD).
set -u
src=$(cd "$(dirname "$0")/.." && pwd)
. "$src/tools/usage.sh"
. "$src/bench/lib.sh"
BUILD=${MPB_BUILD:-$src/build}
BIN="" STATES=2000 ROUNDS=10 SECS=1 SET=table_pick_panda NUM=0001
while [ $# -gt 0 ]; do
    case $1 in
    --bin) BIN=$2; shift ;;
    --states) STATES=$2; shift ;;
    --rounds) ROUNDS=$2; shift ;;
    --seconds) SECS=$2; shift ;;
    --set) SET=$2; shift ;;
    --scene) NUM=$(printf %04d "$2"); shift ;;
    -h|--help) mpb_usage; exit 0 ;;
    *) echo "bench/meshspeed.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
    esac
    shift
done

data=$(sh "$src/tools/robot_data.sh" --check >/dev/null 2>&1 &&
       sh "$src/tools/robot_data.sh") || {
    echo "bench/meshspeed.sh: no robot data: run tools/robot_data.sh first" >&2
    exit 1
}
panda=$data/panda
if [ -z "$BIN" ]; then
    cmake --build "$BUILD" --target mpb-planner-null >/dev/null || exit 1
    cmake -S "$src/bench" -B "$BUILD/bench-standalone" -DMPB_BUILD="$BUILD" >/dev/null &&
        cmake --build "$BUILD/bench-standalone" --target mpb-bench-meshcheck \
            mpb-bench-verify >/dev/null || exit 1
    BIN=$BUILD/bench-standalone
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scene=$work/$SET-$NUM.scene
python3 "$src/bench/mbm_scene.py" "$panda/problems/$SET/scene$NUM.yaml" >"$scene" || exit 1

PANDA_JOINTS=panda_joint1,panda_joint2,panda_joint3,panda_joint4,panda_joint5,panda_joint6,panda_joint7
PR2_JOINTS=r_shoulder_pan_joint,r_shoulder_lift_joint,r_upper_arm_roll_joint,r_elbow_flex_joint,r_forearm_roll_joint,r_wrist_flex_joint,r_wrist_roll_joint
echo "RESULT meshspeed_setup set=$SET scene=$NUM"
echo "== 4m. a state check: Panda (SRDF, meshes) in $SET scene $NUM vs the PR2 arm in the kitchen ($STATES states, $ROUNDS rounds)"
timeout -k 5 600 "$BIN/mpb-bench-meshcheck" \
    --robot "$panda/panda.urdf" --srdf "$panda/panda.srdf" --scene "$scene" \
    --joints "$PANDA_JOINTS" --label "Panda, $SET $NUM" \
    --ref-robot "$src/scenes/robots/pr2_right_arm.urdf" \
    --ref-scene "$src/scenes/paper/kitchen.scene" --ref-joints "$PR2_JOINTS" \
    --ref-label "PR2 right arm, kitchen" --states "$STATES" --rounds "$ROUNDS"
echo "== 4m. verification + metrics, Panda in $SET scene $NUM"
for sp in 0.01 0.1; do
    timeout -k 5 300 "$BIN/mpb-bench-verify" --robot "$panda/panda.urdf" \
        --srdf "$panda/panda.srdf" --scene "$scene" --robot-format urdf \
        --scene-format moveit-scene --joints "$PANDA_JOINTS" --waypoints 2000 \
        --spacing "$sp" --seconds "$SECS" --label "Panda, $SET $NUM" \
        >"$work/verify.log" 2>&1
    sed "s/^RESULT verify /RESULT verify_panda_$sp /" "$work/verify.log"
done
