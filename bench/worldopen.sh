#!/bin/sh
# bench/worldopen.sh - issue 37 item 4: the first Panda world of a
# process (its SRDF, its collision meshes, an empty scene), each in a
# fresh process (mpb-bench-worldopen), with the wrist tables
#   none: no cache to use (MPB_CACHE_DIR below a regular file): every
#         process builds them, as every process did before the cache;
#   cold: an empty cache: the process builds them and writes them;
#   warm: the cache the cold process left: it reads them.
#
#   bench/worldopen.sh [--build DIR] [--runs N]
#
# N processes each for none and warm (default 5), one cold. Prints the
# median wall and CPU milliseconds as RESULT lines (on a shared machine,
# CPU time is the number to trust). Then the later worlds of a process:
# one process, warm, opens the scenes of the first 10 problems of each of
# MotionBenchMaker's seven Panda sets (bench/mbm_scene.py) after its first
# world, one world each; RESULT later_worlds, their median and mean. The user's own cache is not touched.
# Needs the Panda in .cache/robots (tools/robot_data.sh).
set -u
src=$(cd "$(dirname "$0")/.." && pwd)
. "$src/tools/usage.sh"
. "$src/bench/lib.sh"
BUILD=${MPB_BUILD:-$src/build} RUNS=5
while [ $# -gt 0 ]; do
    case $1 in
    --build) BUILD=$2; shift ;;
    --runs) RUNS=$2; shift ;;
    -h|--help) mpb_usage; exit 0 ;;
    *) echo "bench/worldopen.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
    esac
    shift
done
data=$(sh "$src/tools/robot_data.sh" --check >/dev/null 2>&1 &&
       sh "$src/tools/robot_data.sh") || {
    echo "bench/worldopen.sh: no robot data: run tools/robot_data.sh first" >&2
    exit 1
}
cmake --build "$BUILD" --target mpb-planner-null >/dev/null || exit 1
cmake -S "$src/bench" -B "$BUILD/bench-standalone" -DMPB_BUILD="$BUILD" >/dev/null &&
    cmake --build "$BUILD/bench-standalone" --target mpb-bench-worldopen >/dev/null ||
    exit 1
prog=$BUILD/bench-standalone/mpb-bench-worldopen
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
: >"$work/not-a-dir"

run() { # label cache-dir count
    i=0
    while [ "$i" -lt "$3" ]; do
        MPB_CACHE_DIR=$2 "$prog" "$data/panda" || exit 1
        i=$((i + 1))
    done | awk -v label="$1" '$2 == "world_open" {
            split($3, a, "="); split($4, b, "="); w[NR] = a[2]; c[NR] = b[2] }
        function median(v, n,   i, j, t) {
            for (i = 2; i <= n; i++)
                for (j = i; j > 1 && v[j - 1] > v[j]; j--) { t = v[j]; v[j] = v[j - 1]; v[j - 1] = t }
            return n % 2 ? v[(n + 1) / 2] : (v[n / 2] + v[n / 2 + 1]) / 2 }
        END { printf "RESULT world_open cache=%s runs=%d wall_ms=%.1f cpu_ms=%.1f\n",
                     label, NR, median(w, NR), median(c, NR) }'
}
run none "$work/not-a-dir/cache" "$RUNS"
run cold "$work/cache" 1
run warm "$work/cache" "$RUNS"
python=$src/.venv/bin/python3
[ -x "$python" ] || python=python3
mkdir "$work/scenes"
for set in $(ls "$data/panda/problems"); do
    for f in $(ls "$data/panda/problems/$set"/scene*.yaml | head -10); do
        "$python" "$src/bench/mbm_scene.py" "$f" \
            >"$work/scenes/$set-$(basename "$f" .yaml).scene" || exit 1
    done
done
MPB_CACHE_DIR=$work/cache "$prog" "$data/panda" "$work/scenes"/*.scene |
    grep later_worlds || exit 1
