#!/bin/sh
# bench/agree.sh - issue 37: do the certified and the sampled collision
# checks agree on the stored paths of the paper's demo suite
# (scenes/experiments/paper-demo.yaml, what `make demo` runs), of its
# quick suite (paper-quick.yaml) and of
# scenes/experiments/mbm-panda-quick.yaml? (docs/results-paper.md,
# docs/results-mbm.md)
#
#   bench/agree.sh [--bin DIR] [--no-quick] DBDIR
#
#   1. Makes what DBDIR lacks, once, niced: DBDIR/paper-demo.db (the
#      demo's experiment, planners ompl, arastar, python), DBDIR/
#      paper-quick.db (the same planners; about 30 minutes on 2 cores;
#      not with --no-quick) and DBDIR/mbm-panda-quick.db (planner ompl;
#      needs the Panda and MotionBenchMaker's problems in .cache/robots,
#      tools/robot_data.sh; without them it is skipped), each by
#      tools/run_benchmark.sh (root: a private network namespace).
#   2. Runs `mpb verify --compare` on each database there: every stored
#      stage verified again certified and sampled, each stage the
#      certified check newly refuses listed with its colliding
#      configuration, each whose proof fell back to sampling, and the
#      counts (with the CPU time of each check). The databases are only
#      read: run it again after the verifier changed, on the same ones.
# Prints a header line per database, then mpb's output. Exit 1 if a
# sampled collision passes the certified check (a bug) or on an error.
# DIR is the build tree (default MPB_BUILD or build/).
set -u
src=$(cd "$(dirname "$0")/.." && pwd)
. "$src/tools/usage.sh"
BUILD=${MPB_BUILD:-$src/build} QUICK=1
while [ $# -gt 0 ]; do
    case $1 in
    --bin) BUILD=$2; shift 2 ;;
    --no-quick) QUICK=0; shift ;;
    -h|--help) mpb_usage; exit 0 ;;
    -*) echo "bench/agree.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
    *) break ;;
    esac
done
[ $# -eq 1 ] || { echo "usage: bench/agree.sh [--bin DIR] [--no-quick] DBDIR" >&2; exit 2; }
dir=$1
mkdir -p "$dir" || exit 1
export MPB_BUILD=$BUILD
data=$(sh "$src/tools/robot_data.sh" --check >/dev/null 2>&1 &&
       sh "$src/tools/robot_data.sh") || data=""

make_db() {   # make_db NAME PLANNERS: DBDIR/NAME.db from its experiment file
    [ -f "$dir/$1.db" ] && return 0
    echo "bench/agree.sh: making $dir/$1.db (log $dir/$1.log)" >&2
    nice -n 10 sh "$src/tools/run_benchmark.sh" -d "$dir/$1.db" \
        -l "$dir/$1-logs" -p "$2" "$src/scenes/experiments/$1.yaml" \
        >"$dir/$1.log" 2>&1 || {
        echo "bench/agree.sh: $1 did not complete: see $dir/$1.log" >&2
        return 1
    }
}

status=0
make_db paper-demo ompl,arastar,python || status=1
[ "$QUICK" -eq 0 ] || make_db paper-quick ompl,arastar,python || status=1
if [ -n "$data" ]; then
    make_db mbm-panda-quick ompl || status=1
    # The URDF's package:// meshes.
    export MPB_MESH_PATH=$data/panda
else
    echo "bench/agree.sh: no robot data (tools/robot_data.sh): mbm-panda-quick skipped" >&2
fi
for db in "$dir"/paper-demo.db "$dir"/paper-quick.db "$dir"/mbm-panda-quick.db; do
    [ -f "$db" ] || continue
    echo "== mpb verify --compare $db ($(date -u +%Y-%m-%dT%H:%MZ), load $(cut -d' ' -f1-3 /proc/loadavg))"
    nice -n 10 "$BUILD/tools/mpb" verify --compare "$db" || status=1
done
exit $status
