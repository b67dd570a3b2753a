#!/bin/sh
# bench/infra.sh - issue 37: the infrastructure's share of the daemon's
# wall time on MotionBenchMaker's Panda problems (docs/performance.md,
# "The infrastructure's share").
#
#   bench/infra.sh [--bin DIR] [--problems N] [--verification MODE]...
#                  [--rounds R] [--keep DIR]
#
# In a private network namespace (root: unshare -n), mpbenchd and one
# OMPL planner (RRTConnect, 10 s a run) on N problems of each of the
# seven problem sets (default 10: 70 problems), once per MODE (default
# both, `certified` then `sampled`: the experiment's `verification:`),
# R rounds of that (default 1), lcm-logger recording. From the log (when
# each request and result was published) and the database (time_total,
# world_setup_time, verify_time, finished), bench/infra_split.py:
#   wall     = last result stored - first request published
#   share    = 1 - sum(time_total) / wall, the issue's measure, and its
#              parts, each over wall:
#   setup    the planner opening each scene's world (outside time_total)
#   planner  request to result, less time_total and world setup: the
#            messages' way and the planner kit's untimed work
#   daemon   a result published to the next request published
#   tail     the last result published to stored: its verification, and
#            whatever was still waiting for the verifier
#   verify_beside  sum(verify_time) / wall: verification done beside the
#            planner (above 1: the verifier could not keep up)
# One RESULT line per database. DIR is a build tree (default MPB_BUILD or
# build/; its lcmtypes/python decodes the log). Needs the Panda in
# .cache/robots (tools/robot_data.sh) and Python's lcm (.venv). About a
# minute a database on an idle machine with `sampled`.
set -u
src=$(cd "$(dirname "$0")/.." && pwd)
. "$src/tools/usage.sh"
. "$src/bench/lib.sh"
BIN=${MPB_BUILD:-$src/build} N=10 INNER=0 MODES="" ROUNDS=1 KEEP=""
while [ $# -gt 0 ]; do
    case $1 in
    --bin) BIN=$2; shift ;;
    --problems) N=$2; shift ;;
    --verification) MODES="$MODES $2"; shift ;;
    --rounds) ROUNDS=$2; shift ;;
    --keep) KEEP=$2; shift ;;
    --inner) INNER=1 ;;
    -h|--help) mpb_usage; exit 0 ;;
    *) echo "bench/infra.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
    esac
    shift
done
MODES=${MODES:-certified sampled}
for m in $MODES; do
    case $m in certified|sampled) ;;
    *) echo "bench/infra.sh: --verification is certified or sampled, not '$m'" >&2; exit 2 ;;
    esac
done
data=$(sh "$src/tools/robot_data.sh" --check >/dev/null 2>&1 &&
       sh "$src/tools/robot_data.sh") || {
    echo "bench/infra.sh: no robot data: run tools/robot_data.sh first" >&2
    exit 1
}
panda=$data/panda

if [ "$INNER" -eq 0 ]; then
    [ "$(id -u)" -eq 0 ] || { echo "bench/infra.sh: needs root (unshare -n)" >&2; exit 1; }
    args="--bin $BIN --problems $N --rounds $ROUNDS"
    for m in $MODES; do args="$args --verification $m"; done
    [ -n "$KEEP" ] && args="$args --keep $KEEP"
    exec unshare -n sh "$0" --inner $args
fi

bench_netns bench/infra.sh
export MPB_MESH_PATH=$panda
work=$(mktemp -d)
trap 'cleanup; rm -rf "$work"' EXIT
[ -n "$KEEP" ] && mkdir -p "$KEEP"

experiment_file() { # mode file
    {
        cat <<EOT
experiment: {name: infra-$1, runs: 1, time_limit: 10, seed: 1, verification: $1}
$(panda_robot "$panda")
scenes:
EOT
        for set in $(ls "$panda/problems"); do
            echo "  - {problems: $panda/problems/$set, count: $N, clamp_joint_values: true}"
        done
        echo "planners:"
        echo "  - {planner: ompl, algorithms: [RRTConnect]}"
    } >"$2"
}

python=$src/.venv/bin/python3
[ -x "$python" ] || python=python3

r=1
while [ "$r" -le "$ROUNDS" ]; do
    for mode in $MODES; do
        experiment_file "$mode" "$work/$mode.yaml"
        db=$work/$mode-$r.db
        lcm-logger -f "$db.lcm" >/dev/null 2>&1 &
        logger=$!
        "$BIN/planners/ompl/mpb-planner-ompl" >"$work/ompl.log" 2>&1 &
        PIDS="$logger $!"
        timeout 900 "$BIN/daemon/mpbenchd" -d "$db" "$work/$mode.yaml" \
            >"$work/daemon.log" 2>&1 || {
            echo "bench/infra.sh: the daemon failed:" >&2
            cat "$work/daemon.log" >&2
            exit 1
        }
        kill -INT "$logger"     # it writes out what it has
        wait "$logger"
        cleanup
        [ -n "$KEEP" ] && cp "$db" "$db.lcm" "$KEEP/"
        "$python" "$src/bench/infra_split.py" "$BIN/lcmtypes/python" \
            "$db.lcm" "$db" "$mode" "$r" || exit 1
    done
    r=$((r + 1))
done
