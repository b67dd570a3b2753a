#!/bin/sh
# bench/mbmload.sh - issue 27: loading MotionBenchMaker's 700 Panda
# problems, and what a planner pays for a world it has not built yet
# (docs/performance.md, "Loading MotionBenchMaker").
#
#   bench/mbmload.sh [--bin DIR] [--problems N]
#
#   1. `mpbenchd --check scenes/experiments/mbm-panda.yaml` (what
#      tools/mbm_check.sh runs, and what the daemon does when the
#      experiment starts: one world per scene, all 700 kept open) under
#      /usr/bin/time: wall and CPU seconds, peak resident memory;
#   2. in a private network namespace (root: unshare -n), the daemon and
#      OMPL's planner on N problems (default 4), one of each of the first
#      N sets, RRTConnect, 1 s: each run's world_setup_time (the planner
#      opening the scene's world: robot, meshes, scene; outside
#      time_total), from the database: the first run's (the first world
#      of the process) and the others'. Twice, with a wrist-table cache
#      of its own (MPB_CACHE_DIR): empty (cold: the first world builds
#      the tables and writes them), then as the first run left it (warm:
#      the first world reads them).
# DIR is a build tree (default MPB_BUILD or build/): DIR/daemon/mpbenchd
# and DIR/planners/ompl/mpb-planner-ompl. Prints RESULT lines. Needs the
# Panda in .cache/robots (tools/robot_data.sh).
set -u
src=$(cd "$(dirname "$0")/.." && pwd)
. "$src/tools/usage.sh"
. "$src/bench/lib.sh"
BIN=${MPB_BUILD:-$src/build} N=4 INNER=0
while [ $# -gt 0 ]; do
    case $1 in
    --bin) BIN=$2; shift ;;
    --problems) N=$2; shift ;;
    --inner) INNER=1 ;;
    -h|--help) mpb_usage; exit 0 ;;
    *) echo "bench/mbmload.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
    esac
    shift
done
data=$(sh "$src/tools/robot_data.sh" --check >/dev/null 2>&1 &&
       sh "$src/tools/robot_data.sh") || {
    echo "bench/mbmload.sh: no robot data: run tools/robot_data.sh first" >&2
    exit 1
}
panda=$data/panda
export MPB_MESH_PATH=$panda

if [ "$INNER" -eq 0 ]; then
    t=$(mktemp)
    cold=$(mktemp -d)       # a cold wrist-table cache, not the user's
    MPB_CACHE_DIR=$cold /usr/bin/time -f '%e %U %S %M' -o "$t" \
        "$BIN/daemon/mpbenchd" --check "$src/scenes/experiments/mbm-panda.yaml" \
        >/dev/null 2>&1 || { echo "bench/mbmload.sh: --check failed" >&2; exit 1; }
    read -r wall user sys rss <"$t"
    rm -rf "$t" "$cold"
    echo "RESULT mbm_check wall_s=$wall cpu_s=$(calc "$user + $sys") peak_rss_mb=$(calc "$rss / 1024" 0)"
    [ "$(id -u)" -eq 0 ] || { echo "bench/mbmload.sh: part 2 needs root (unshare -n)" >&2; exit 0; }
    exec unshare -n sh "$0" --inner --bin "$BIN" --problems "$N"
fi

bench_netns bench/mbmload.sh
work=$(mktemp -d)
trap 'cleanup; rm -rf "$work"' EXIT
{
    cat <<EOT
experiment: {name: mbmload, time_limit: 1, seed: 1}
$(panda_robot "$panda")
scenes:
EOT
    for set in $(ls "$panda/problems" | head -n "$N"); do
        echo "  - {problems: $panda/problems/$set, count: 1, clamp_joint_values: true}"
    done
    echo "planners:"
    echo "  - {planner: ompl, algorithms: [RRTConnect]}"
} >"$work/exp.yaml"
export MPB_CACHE_DIR="$work/cache"
for cache in cold warm; do
    "$BIN/planners/ompl/mpb-planner-ompl" >"$work/ompl.log" 2>&1 &
    pid=$!
    PIDS="$PIDS $pid"
    rm -f "$work/db"*
    timeout 300 "$BIN/daemon/mpbenchd" -d "$work/db" "$work/exp.yaml" >"$work/daemon.log" 2>&1 || {
        echo "bench/mbmload.sh: the daemon failed:" >&2
        cat "$work/daemon.log" >&2
        exit 1
    }
    kill "$pid" 2>/dev/null
    wait "$pid" 2>/dev/null
    sqlite3 "$work/db" "SELECT 1000 * world_setup_time FROM runs
                        WHERE world_setup_time IS NOT NULL ORDER BY rowid" |
        awk -v cache="$cache" '{ v[NR] = $1; if (NR > 1) { s += $1; if (NR == 2 || $1 > mx) mx = $1 } }
             END { printf "RESULT planner_world_setup cache=%s runs=%d first_ms=%.1f others_mean_ms=%.1f others_max_ms=%.1f\n",
                          cache, NR, v[1], (NR > 1 ? s / (NR - 1) : 0), mx }'
done
