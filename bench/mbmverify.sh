#!/bin/sh
# bench/mbmverify.sh - issue 27: verification plus metrics on the Panda
# trajectories OMPL returns for MotionBenchMaker's problems, waypoints per
# second (docs/performance.md, item 4v). mpbenchd does this for every
# result it stores.
#
#   bench/mbmverify.sh [--bin DIR] [--db FILE] [--keep FILE] [--seconds S]
#
# Needs the Panda and MotionBenchMaker's problem sets in .cache/robots
# (tools/robot_data.sh fetches them; without them it says so and stops).
#   1. Without --db: scenes/experiments/mbm-panda-quick.yaml with OMPL's
#      RRTConnect only (its 35 problems, 10 s a run; a copy of the file
#      without the other planners), run by tools/run_benchmark.sh -p ompl
#      into a new database, kept as FILE with --keep. Root only: LCM runs
#      in the private network namespace run_benchmark.sh makes. About a
#      minute. With --db FILE: that database's newest experiment instead,
#      only read (no root, no network).
#   2. mpb-bench-verifydb on it: every stage of every finished run (its
#      stored world, start, goal and waypoints) verified at the
#      experiment's resolution and measured with every metric the daemon
#      stores, in process, as mpbenchd does per result; verification +
#      metrics, verification alone and metrics alone, each repeated for at
#      least S seconds (default 5): waypoints per second in wall and CPU
#      time. Opening the worlds is timed apart.
# Prints RESULT lines (verify_mbm ...), which bench/run.sh collects and
# bench/table.sh reads. DIR is the build tree (default MPB_BUILD or
# build/): it needs DIR/daemon/mpbenchd, DIR/planners/ompl/mpb-planner-ompl
# and DIR/tools/mpb; the bench program is built in DIR/bench-standalone.
set -u
src=$(cd "$(dirname "$0")/.." && pwd)
. "$src/tools/usage.sh"
. "$src/bench/lib.sh"
BUILD=${MPB_BUILD:-$src/build} DB="" KEEP="" SECS=5
while [ $# -gt 0 ]; do
    case $1 in
    --bin) BUILD=$2; shift ;;
    --db) DB=$2; shift ;;
    --keep) KEEP=$2; shift ;;
    --seconds) SECS=$2; shift ;;
    -h|--help) mpb_usage; exit 0 ;;
    *) echo "bench/mbmverify.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
    esac
    shift
done

data=$(sh "$src/tools/robot_data.sh" --check >/dev/null 2>&1 &&
       sh "$src/tools/robot_data.sh") || {
    echo "bench/mbmverify.sh: no robot data: run tools/robot_data.sh first" >&2
    exit 1
}
panda=$data/panda
# The URDF's package:// meshes, for the planner and the bench alike.
export MPB_MESH_PATH=$panda
if [ -n "$DB" ] && [ ! -f "$DB" ]; then
    echo "bench/mbmverify.sh: $DB: no such database" >&2
    exit 1
fi
if [ -z "$DB" ]; then
    [ "$(id -u)" -eq 0 ] || {
        echo "bench/mbmverify.sh: running the planner needs root (a private network namespace); or give --db" >&2
        exit 1
    }
    for b in daemon/mpbenchd planners/ompl/mpb-planner-ompl tools/mpb; do
        [ -x "$BUILD/$b" ] || { echo "bench/mbmverify.sh: $BUILD/$b is not built" >&2; exit 1; }
    done
fi
cmake --build "$BUILD" --target mpb-planner-null >/dev/null || exit 1
cmake -S "$src/bench" -B "$BUILD/bench-standalone" -DMPB_BUILD="$BUILD" >/dev/null &&
    cmake --build "$BUILD/bench-standalone" --target mpb-bench-verifydb >/dev/null || exit 1

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
if [ -z "$DB" ]; then
    # The quick slice, its paths made absolute, RRTConnect its only planner.
    exp=$work/mbm-panda-quick-rrtconnect.yaml
    sed -e "s|\.\./\.\./\.cache/robots/vamp-planner-0\.6\.4|$data|" \
        -e 's|^  name: mbm-panda-quick$|  name: mbm-panda-quick-rrtconnect|' \
        -e 's|^    algorithms: \[RRTConnect, .*\]$|    algorithms: [RRTConnect]|' \
        "$src/scenes/experiments/mbm-panda-quick.yaml" >"$exp"
    [ "$(grep -c 'algorithms: \[RRTConnect\]$\|name: mbm-panda-quick-rrtconnect$' "$exp")" -eq 2 ] || {
        echo "bench/mbmverify.sh: scenes/experiments/mbm-panda-quick.yaml changed; cannot make its RRTConnect slice" >&2
        exit 1
    }
    DB=${KEEP:-$work/mbm.db}
    rm -f "$DB" "$DB-wal" "$DB-shm"
    echo "== 4v. RRTConnect on mbm-panda-quick's 35 problems, 10 s each (tools/run_benchmark.sh -p ompl)"
    start=$(date +%s)
    env -u MPB_LCM_URL MPB_BUILD="$BUILD" timeout -k 10 900 \
        sh "$src/tools/run_benchmark.sh" -p ompl -d "$DB" -l "$work/logs" "$exp" \
        >"$work/run.log" 2>&1 || {
        echo "bench/mbmverify.sh: tools/run_benchmark.sh failed:" >&2
        tail -20 "$work/run.log" >&2
        exit 1
    }
    echo "RESULT mbmverify_run seconds=$(($(date +%s) - start))"
fi
echo "== 4v. verification + metrics on the stored trajectories of $DB"
timeout -k 5 900 "$BUILD/bench-standalone/mpb-bench-verifydb" --db "$DB" \
    --seconds "$SECS" --key verify_mbm \
    --label "Panda, MotionBenchMaker"
