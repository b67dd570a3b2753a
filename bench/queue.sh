#!/bin/sh
# bench/queue.sh - what a request waiting at each planner buys
# (experiment queue_at_planner; docs/performance.md, 4d): runs per second
# with queue_at_planner 0 and 1, in turns (--rounds R, default 3), for
#   null1  one null planner, N runs (--runs, default 20000)
#   null3  three null planners, 3N runs
#   ompl   one mpb-planner-ompl, RRTConnect with its default stages on the
#          paper's first kitchen query (the PR2's right arm), N/20 runs
# Runs per second are counted in the database: runs over the time from the
# first send to the last finish. The timing fidelity side of the trade is
# bench/fidelity.sh --queue 1.
#
#   bench/queue.sh [--runs N] [--rounds R] [--out DIR]
#
# Inside a private network namespace (only loopback, with a multicast
# route; as bench/run.sh). Prints a RESULT line per experiment.
set -u

src=$(cd "$(dirname "$0")/.." && pwd)
. "$src/tools/usage.sh"
. "$src/bench/lib.sh"
BUILD=${MPB_BUILD:-$src/build}
case $BUILD in /*) ;; *) BUILD=$src/$BUILD ;; esac
RUNS=20000 ROUNDS=3 OUT="" IN_NETNS=0
while [ $# -gt 0 ]; do
    case $1 in
    --runs) RUNS=$2; shift ;;
    --rounds) ROUNDS=$2; shift ;;
    --out) OUT=$2; shift ;;
    --in-netns) IN_NETNS=1 ;;
    -h|--help) mpb_usage; exit 0 ;;
    *) echo "bench/queue.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
    esac
    shift
done
case $RUNS$ROUNDS in *[!0-9]*|"")
    echo "bench/queue.sh: --runs and --rounds want whole numbers" >&2; exit 2 ;;
esac
[ "$RUNS" -ge 20 ] || { echo "bench/queue.sh: --runs at least 20" >&2; exit 2; }
: "${OUT:=$BUILD/bench-run/queue}"

if [ "$IN_NETNS" -eq 0 ]; then
    bench_snapshot bench/queue.sh "$OUT" "$BUILD/daemon/mpbenchd" \
        "$BUILD/planners/null/mpb-planner-null" "$BUILD/planners/ompl/mpb-planner-ompl"
    exec unshare -n sh "$0" --in-netns --runs "$RUNS" --rounds "$ROUNDS" --out "$OUT"
fi

bench_netns bench/queue.sh
BIN=$OUT/bin
trap cleanup EXIT
trap 'exit 130' INT TERM

kitchen() { # name runs queue file
    cat >"$4" <<EOF
experiment: {name: $1, runs: $2, time_limit: 10, seed: 5, queue_at_planner: $3}
robot:
  format: urdf
  file: $src/scenes/robots/pr2_right_arm.urdf
  joints: [r_shoulder_pan_joint, r_shoulder_lift_joint, r_upper_arm_roll_joint,
           r_elbow_flex_joint, r_forearm_roll_joint, r_wrist_flex_joint,
           r_wrist_roll_joint]
scenes:
  - name: kitchen
    format: moveit-scene
    file: $src/scenes/paper/kitchen.scene
    queries:
      - name: counter_cup
        start: [-1.2, 1.1, -1.5, -1.9, 0, -0.6, 0]
        goal: [-0.261284, -0.420386, -1.523717, -1.031201, -1.236424,
               -1.761224, -2.299770]
        tolerance: 0.01
planners:
  - {planner: ompl, algorithms: [RRTConnect]}
EOF
}

# One experiment: runs per second, and how many runs were done.
measure() { # key queue round
    db=$OUT/$1-q$2-$3.db
    rm -f "$db"*
    timeout -k 5 600 "$BIN/mpbenchd" -d "$db" "$OUT/$1-q$2.yaml" \
        >"$OUT/$1-q$2-$3.log" 2>&1 || echo "mpbenchd failed: see $OUT/$1-q$2-$3.log" >&2
    set -- "$1" "$2" "$3" $(sqlite3 -separator ' ' "$db" "SELECT count(*),
        printf('%.0f', count(*) / (max(finished) - min(sent))) FROM runs
        WHERE state = 'done'")
    echo "RESULT queue_$1 queue_at_planner=$2 round=$3 runs=${4:-0} runs_per_s=${5:-nan}"
}

series() { # key planner count
    for q in 0 1; do
        case $1 in
        ompl) kitchen "bench-queue-$1" $((RUNS / 20)) $q "$OUT/$1-q$q.yaml" ;;
        *) experiment "bench-queue-$1" $((RUNS * $3)) "$3" "$OUT/$1-q$q.yaml" $q ;;
        esac
    done
    for i in $(seq "$3"); do
        "$BIN/mpb-planner-$2" >"$OUT/$1-planner$i.log" 2>&1 &
        PIDS="$PIDS $!"
    done
    sleep 0.5   # their first announcements
    for r in $(seq "$ROUNDS"); do
        measure "$1" 0 "$r"
        measure "$1" 1 "$r"
    done
    cleanup
}

series null1 null 1
series null3 null 3
series ompl ompl 1
