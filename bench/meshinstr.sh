#!/bin/sh
# bench/meshinstr.sh - issue 27, "meshes at speed", in instructions: what
# one collision check costs the Panda (its SRDF, its collision meshes, in
# a MotionBenchMaker scene) and the primitive PR2 right arm (the paper's
# kitchen), counted by callgrind, which the machine's load does not move
# (docs/performance.md, item 4m; bench/meshspeed.sh times the same checks).
#
#   bench/meshinstr.sh [--bin DIR] [--states N] [--set NAME] [--scene N]
#
# Each robot is run on both sides of mpb-bench-meshcheck (--query
# in_collision, N fixed-seed random states, default 200, one round), with
# callgrind collecting in the timed passes only (a warm-up pass and the
# round, both sides: 4 N checks; opening the worlds is left out). Prints
# the instructions per check of each and their ratio as RESULT lines.
# Needs valgrind, and the Panda in .cache/robots (tools/robot_data.sh).
# DIR holds mpb-bench-meshcheck (default: built now in the build tree,
# MPB_BUILD or build/).
set -u
src=$(cd "$(dirname "$0")/.." && pwd)
. "$src/tools/usage.sh"
BUILD=${MPB_BUILD:-$src/build}
BIN="" STATES=200 SET=table_pick_panda NUM=0001
while [ $# -gt 0 ]; do
    case $1 in
    --bin) BIN=$2; shift ;;
    --states) STATES=$2; shift ;;
    --set) SET=$2; shift ;;
    --scene) NUM=$(printf %04d "$2"); shift ;;
    -h|--help) mpb_usage; exit 0 ;;
    *) echo "bench/meshinstr.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
    esac
    shift
done
command -v valgrind >/dev/null 2>&1 && command -v callgrind_annotate >/dev/null 2>&1 || {
    echo "bench/meshinstr.sh: needs valgrind (apt-get install valgrind)" >&2
    exit 1
}
data=$(sh "$src/tools/robot_data.sh" --check >/dev/null 2>&1 &&
       sh "$src/tools/robot_data.sh") || {
    echo "bench/meshinstr.sh: no robot data: run tools/robot_data.sh first" >&2
    exit 1
}
panda=$data/panda
if [ -z "$BIN" ]; then
    cmake -S "$src/bench" -B "$BUILD/bench-standalone" -DMPB_BUILD="$BUILD" >/dev/null &&
        cmake --build "$BUILD/bench-standalone" --target mpb-bench-meshcheck >/dev/null || exit 1
    BIN=$BUILD/bench-standalone
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scene=$work/$SET-$NUM.scene
python3 "$src/bench/mbm_scene.py" "$panda/problems/$SET/scene$NUM.yaml" >"$scene" || exit 1
PANDA_JOINTS=panda_joint1,panda_joint2,panda_joint3,panda_joint4,panda_joint5,panda_joint6,panda_joint7
PR2_JOINTS=r_shoulder_pan_joint,r_shoulder_lift_joint,r_upper_arm_roll_joint,r_elbow_flex_joint,r_forearm_roll_joint,r_wrist_flex_joint,r_wrist_roll_joint
PR2_URDF=$src/scenes/robots/pr2_right_arm.urdf
KITCHEN=$src/scenes/paper/kitchen.scene

# count NAME ARGS...: instructions per check of one world on both sides
count() {
    name=$1
    shift
    timeout -k 5 600 valgrind --tool=callgrind --callgrind-out-file="$work/$name.cg" \
        --toggle-collect=pass "$BIN/mpb-bench-meshcheck" "$@" --states "$STATES" \
        --rounds 1 --query in_collision >"$work/$name.log" 2>&1 || {
        echo "bench/meshinstr.sh: callgrind of $name failed:" >&2
        tail -5 "$work/$name.log" >&2
        exit 1
    }
    total=$(callgrind_annotate "$work/$name.cg" 2>/dev/null |
            awk '/PROGRAM TOTALS/ { gsub(",", "", $1); print $1 }')
    echo $((total / (4 * STATES)))
}
p=$(count panda --robot "$panda/panda.urdf" --srdf "$panda/panda.srdf" \
    --scene "$scene" --joints "$PANDA_JOINTS" --ref-robot "$panda/panda.urdf" \
    --ref-srdf "$panda/panda.srdf" --ref-scene "$scene" \
    --ref-joints "$PANDA_JOINTS") || exit 1
r=$(count pr2 --robot "$PR2_URDF" --scene "$KITCHEN" --joints "$PR2_JOINTS" \
    --ref-robot "$PR2_URDF" --ref-scene "$KITCHEN" --ref-joints "$PR2_JOINTS") || exit 1
echo "Panda ($SET $NUM): $p instructions a collision check; PR2 arm (kitchen): $r"
echo "RESULT meshinstr_in_collision panda=$p pr2=$r ratio=$(awk -v a="$p" -v b="$r" 'BEGIN { printf "%.3f", a / b }') states=$STATES set=$SET scene=$NUM"
