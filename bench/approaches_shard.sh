#!/bin/sh
# bench/approaches_shard.sh - issue 49's 700 Panda problems a slice at a
# time: mbm-panda-approaches.yaml (every configuration, 10 s a run) is
# about 9,100 runs, some 11 hours on a 2-core machine, longer than one
# sitting. Shard K of 10 runs problems 10(K-1)+1 to 10K of each of the
# seven problem sets (70 problems, 910 runs, about an hour), exports its
# runs to bench/results/approaches/shard-K.csv (mpb export --runs-csv)
# and prints the tables of docs/results-approaches.md for every shard
# exported so far (bench/approaches_summary.py).
#
#   bench/approaches_shard.sh [--build DIR] [--db FILE] K
#
# The database defaults to BUILD/approaches/shard-K.db; the same command
# resumes an interrupted shard. Planner and daemon logs go beside it.
set -u
src=$(cd "$(dirname "$0")/.." && pwd)
. "$src/tools/usage.sh"
BUILD=${MPB_BUILD:-$src/build} DB= K=
while [ $# -gt 0 ]; do
    case $1 in
    --build) BUILD=$2; shift ;;
    --db) DB=$2; shift ;;
    -h|--help) mpb_usage; exit 0 ;;
    -*) echo "bench/approaches_shard.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
    *) K=$1 ;;
    esac
    shift
done
case $K in
[1-9]|10) ;;
*) echo "bench/approaches_shard.sh: which shard, 1 to 10? (see --help)" >&2; exit 2 ;;
esac
mpb=$BUILD/tools/mpb
[ -x "$mpb" ] || { echo "bench/approaches_shard.sh: no $mpb (build it)" >&2; exit 1; }
out=$src/bench/results/approaches
DB=${DB:-$BUILD/approaches/shard-$K.db}
mkdir -p "$out" "$(dirname "$DB")" || exit 1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# The experiment file's paths are relative to its folder: made absolute,
# the slice can live anywhere. Every problem set gets the same slice.
full=$src/scenes/experiments/mbm-panda-approaches.yaml
yaml=$work/mbm-panda-approaches-shard-$K.yaml
sed -e "s#^\(  *[a-z_-]*: \)\.\./\.\./#\1$src/#" \
    -e "s#^\( *- problems: \)\.\./\.\./#\1$src/#" \
    -e "s#^\(  name: mbm-panda-approaches\)\$#\1-shard-$K#" \
    -e "/^ *- problems:/a\\
    first: $((10 * (K - 1) + 1))\\
    count: 10" "$full" > "$yaml" || exit 1
grep -q "name: mbm-panda-approaches-shard-$K\$" "$yaml" ||
    { echo "bench/approaches_shard.sh: $full: no 'name: mbm-panda-approaches'" >&2; exit 1; }

MPB_BUILD=$BUILD sh "$src/tools/run_benchmark.sh" --db "$DB" \
    --logs "$(dirname "$DB")/logs-$K" "$yaml" > "$work/report.txt" || {
    tail -20 "$work/report.txt" >&2
    exit 1
}
"$mpb" export --runs-csv --force "$DB" "$out/shard-$K.csv" || exit 1
python3 "$src/bench/approaches_summary.py" "$out"/shard-*.csv
