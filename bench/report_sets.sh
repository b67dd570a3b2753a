#!/bin/sh
# bench/report_sets.sh - issue 50: `mpb report --by set` over a million
# runs, MotionBenchMaker's shape: 625 one-query scenes in 5 problem sets
# (set_K/NNNN), 4 configurations, 400 runs each, one stage a run, 9 in
# 10 successes (mpb-bench-mkdb). Times the report N times (default 3)
# and prints the median wall seconds as a RESULT line, with CPU seconds
# beside it (on a shared machine, the number to trust).
#
#   bench/report_sets.sh [--build DIR] [--runs N] [--db FILE]
#
# --db reuses a database mpb-bench-mkdb wrote before (it takes a few
# minutes and 700 MB); without it one is made in a temporary folder and
# removed. The first report warms the page cache and is not counted.
set -u
src=$(cd "$(dirname "$0")/.." && pwd)
. "$src/tools/usage.sh"
. "$src/bench/lib.sh"
BUILD=${MPB_BUILD:-$src/build} RUNS=3 DB=
while [ $# -gt 0 ]; do
    case $1 in
    --build) BUILD=$2; shift ;;
    --runs) RUNS=$2; shift ;;
    --db) DB=$2; shift ;;
    -h|--help) mpb_usage; exit 0 ;;
    *) echo "bench/report_sets.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
    esac
    shift
done
mpb=$BUILD/tools/mpb
mkdb=$(bench_program "$BUILD" mpb-bench-mkdb)
[ -x "$mpb" ] || { echo "bench/report_sets.sh: no $mpb (build it)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
if [ -z "$DB" ]; then
    [ -x "$mkdb" ] || { echo "bench/report_sets.sh: no $mkdb (bench/run.sh builds it)" >&2; exit 1; }
    DB=$work/million.db
    "$mkdb" --db "$DB" --robot "$src/scenes/planar/arm3.robot" \
        --scene "$src/scenes/planar/pillars.scene" --runs 1000000 --configs 4 \
        --queries 1 --scenes 625 --sets 5 --stages 1 || exit 1
fi
runs=$(sqlite3 "file:$DB?mode=ro" "SELECT count(*) FROM runs WHERE state = 'done'")
"$mpb" report --by set "$DB" >"$work/report.txt" || exit 1   # warm-up
walls="" cpus=""
i=0
while [ "$i" -lt "$RUNS" ]; do
    # GNU time's wall and CPU (user + system) seconds.
    /usr/bin/time -f '%e %U %S' -o "$work/time" "$mpb" report --by set "$DB" \
        >"$work/report.txt" || exit 1
    read -r wall user sys <"$work/time"
    walls="$walls $wall" cpus="$cpus $(calc "$user + $sys" 2)"
    i=$((i + 1))
done
median() { echo "$1" | tr ' ' '\n' | grep . | sort -n | awk '{ v[NR] = $1 }
    END { print NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
tables=$(grep -c '^Problem set \|^All problems' "$work/report.txt")
echo "mpb report --by set over $runs runs ($tables tables): wall$walls s, cpu$cpus s"
echo "RESULT report_sets runs=$runs tables=$tables wall_s=$(median "$walls") cpu_s=$(median "$cpus") load=$(cut -d' ' -f1 /proc/loadavg)"
