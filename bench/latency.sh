#!/bin/sh
# bench/latency.sh - per-run latency as a multiple of the LCM floor, both
# measured in turns (docs/performance.md, 2). On a VM whose round trip
# moves by half from one minute to the next, a floor measured minutes
# away from the latency can put the same latency at 2 or at 3 floors.
# Here each round measures the floor (mpb-bench-floor, --exchanges round
# trips) and the latency (mpbenchd and one null planner, --runs runs,
# mpbenchd's own count: request first sent to result committed) within a
# few seconds of each other, the floor first in odd rounds and second in
# even ones, so a drift weighs on both. The ratio is each round's latency
# median over its floor median; the summary is the median of the rounds'
# ratios, with their range.
#
#   bench/latency.sh [--rounds R] [--runs N] [--exchanges N] [--out DIR]
#
#   --rounds R      rounds (default 10)
#   --runs N        runs of each latency experiment (default 5000)
#   --exchanges N   round trips of each floor (default 5000)
#   --out DIR       logs and databases (default build/bench-run/latency)
#
# Inside a private network namespace (only loopback, with a multicast
# route), which it makes itself, as bench/run.sh does; --in-netns and
# --bin DIR when bench/run.sh calls it from its own. Prints a RESULT line
# per round (latency_round) and one for all (latency_paired).
set -u

src=$(cd "$(dirname "$0")/.." && pwd)
. "$src/tools/usage.sh"
. "$src/bench/lib.sh"
BUILD=${MPB_BUILD:-$src/build}
case $BUILD in /*) ;; *) BUILD=$src/$BUILD ;; esac
ROUNDS=10 RUNS=5000 EXCHANGES=5000 OUT="" BIN="" NETNS=0
while [ $# -gt 0 ]; do
    case $1 in
    --rounds) ROUNDS=$2; shift ;;
    --runs) RUNS=$2; shift ;;
    --exchanges) EXCHANGES=$2; shift ;;
    --out) OUT=$2; shift ;;
    --bin) BIN=$2; shift ;;
    --in-netns) NETNS=1 ;;          # a namespace bench/run.sh set up
    --new-netns) NETNS=2 ;;         # this script's own, to set up
    -h|--help) mpb_usage; exit 0 ;;
    *) echo "bench/latency.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
    esac
    shift
done
case $ROUNDS$RUNS$EXCHANGES in *[!0-9]*|"")
    echo "bench/latency.sh: --rounds, --runs and --exchanges want whole numbers" >&2; exit 2 ;;
esac
[ "$ROUNDS" -ge 1 ] && [ "$RUNS" -ge 100 ] && [ "$EXCHANGES" -ge 100 ] || {
    echo "bench/latency.sh: at least 1 round, 100 runs and 100 exchanges" >&2; exit 2; }
: "${OUT:=$BUILD/bench-run/latency}"

if [ "$NETNS" -eq 0 ]; then
    bench_snapshot bench/latency.sh "$OUT" "$BUILD/daemon/mpbenchd" \
        "$BUILD/planners/null/mpb-planner-null" "$(bench_program "$BUILD" mpb-bench-floor)"
    exec unshare -n sh "$0" --new-netns --bin "$OUT/bin" --out "$OUT" \
        --rounds "$ROUNDS" --runs "$RUNS" --exchanges "$EXCHANGES"
fi
[ -n "$BIN" ] || { echo "bench/latency.sh: --in-netns needs --bin DIR" >&2; exit 2; }
if [ "$NETNS" -eq 2 ]; then bench_netns bench/latency.sh; else bench_netns_check bench/latency.sh; fi
mkdir -p "$OUT" || exit 1
trap cleanup EXIT
trap 'exit 130' INT TERM

ROBOT=$src/scenes/planar/arm3.robot
SCENE=$src/scenes/planar/pillars.scene

# One floor: its median round trip (us), or nan.
floor() { # round
    timeout -k 5 120 "$BIN/mpb-bench-floor" --robot "$ROBOT" --scene "$SCENE" \
        --count "$EXCHANGES" --warmup 500 >"$OUT/floor-$1.log" 2>&1
    RAW=$OUT/floor-$1.log   # floor runs in $(...): RAW stays there
    get floor median_us
}

# One latency experiment: mpbenchd's own median (us), or nan.
latency() { # round
    db=$OUT/latency-$1.db
    rm -f "$db"*
    timeout -k 5 300 "$BIN/mpbenchd" -d "$db" "$OUT/latency.yaml" \
        >"$OUT/latency-$1.log" 2>&1 || echo "mpbenchd failed: see $OUT/latency-$1.log" >&2
    rm -f "$db"*
    set -- $(daemon_latency "$OUT/latency-$1.log")
    echo "${1:-nan}"
}

experiment bench-latency "$RUNS" 1 "$OUT/latency.yaml" 0
"$BIN/mpb-planner-null" >"$OUT/planner.log" 2>&1 &
PIDS=$!
sleep 0.5   # its first announcement

ROUNDS_FILE=$OUT/rounds.txt
: >"$ROUNDS_FILE"
r=1
while [ "$r" -le "$ROUNDS" ]; do
    if [ $((r % 2)) -eq 1 ]; then
        f=$(floor "$r"); l=$(latency "$r")
    else
        l=$(latency "$r"); f=$(floor "$r")
    fi
    echo "RESULT latency_round round=$r floor_us=$f latency_us=$l ratio=$(calc "$l / $f" 3)" |
        tee -a "$ROUNDS_FILE"
    r=$((r + 1))
done

# Medians over the rounds that measured both sides: of the ratios (with
# their range), and of each side's medians, for context.
awk -v all="$ROUNDS" -v runs="$RUNS" -v exchanges="$EXCHANGES" '
    function med(a, n,   i, j, t) {
        for (i = 2; i <= n; i++) { t = a[i]; for (j = i - 1; j >= 1 && a[j] > t; j--) a[j + 1] = a[j]; a[j + 1] = t }
        return (n % 2) ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2
    }
    { for (i = 3; i <= NF; i++) { split($i, kv, "="); x[kv[1]] = kv[2] }
      if (x["ratio"] == "nan" || x["ratio"] == "") next
      n++; q[n] = x["ratio"] + 0; f[n] = x["floor_us"] + 0; l[n] = x["latency_us"] + 0 }
    END {
        if (n == 0) { printf "RESULT latency_paired rounds=0 of=%d ratio_median=nan\n", all; exit }
        m = med(q, n)
        printf "RESULT latency_paired rounds=%d of=%d runs=%d exchanges=%d ratio_median=%.2f ratio_min=%.2f ratio_max=%.2f floor_median_us=%.1f latency_median_us=%.1f\n",
               n, all, runs, exchanges, m, q[1], q[n], med(f, n), med(l, n) }' "$ROUNDS_FILE"
