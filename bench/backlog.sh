#!/bin/sh
# bench/backlog.sh - the daemon's peak memory under a verification backlog
# (issue 47; docs/performance.md): 8 null planners answer at once with
# paths of 1,000 waypoints while the verifier is slowed tenfold
# (MPBD_TEST_SLOW_VERIFY=10, a test-only knob of daemon/results.c), so
# results pile up faster than they are verified. For each run count
# (--runs, default "2000 10000"), the daemon's peak resident memory
# (VmHWM), with the default bounds
# (--backlog 1000, --backlog-mb 256) and with none (--backlog 0
# --backlog-mb 0). Bounded, the peak does not grow with the run count.
#
#   bench/backlog.sh [--runs "N ..."] [--out DIR]
#
# Inside a private network namespace (only loopback, with a multicast
# route; as bench/run.sh). Prints a RESULT line per experiment.
set -u

src=$(cd "$(dirname "$0")/.." && pwd)
. "$src/tools/usage.sh"
. "$src/bench/lib.sh"
BUILD=${MPB_BUILD:-$src/build}
case $BUILD in /*) ;; *) BUILD=$src/$BUILD ;; esac
RUNS="2000 10000" OUT="" IN_NETNS=0 BOUNDS="bounded unbounded"
while [ $# -gt 0 ]; do
    case $1 in
    --runs) RUNS=$2; shift ;;
    --bounds) BOUNDS=$2; shift ;;
    --out) OUT=$2; shift ;;
    --in-netns) IN_NETNS=1 ;;
    -h|--help) mpb_usage; exit 0 ;;
    *) echo "bench/backlog.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
    esac
    shift
done
: "${OUT:=$BUILD/bench-run/backlog}"

if [ "$IN_NETNS" -eq 0 ]; then
    bench_snapshot bench/backlog.sh "$OUT" "$BUILD/daemon/mpbenchd" \
        "$BUILD/planners/null/mpb-planner-null"
    exec unshare -n sh "$0" --in-netns --runs "$RUNS" --bounds "$BOUNDS" \
        --out "$OUT"
fi

bench_netns bench/backlog.sh
BIN=$OUT/bin
trap cleanup EXIT
trap 'exit 130' INT TERM

for i in 1 2 3 4 5 6 7 8; do
    "$BIN/mpb-planner-null" >"$OUT/planner$i.log" 2>&1 &
    PIDS="$PIDS $!"
done
sleep 0.5   # their first announcements

for n in $RUNS; do
    experiment "bench-backlog" "$n" 8 "$OUT/exp$n.yaml"
    sed -i 's/algorithms: \[straight_line\]/algorithms: [straight_line]\n    params: {waypoints: 1000}/' \
        "$OUT/exp$n.yaml"
    for b in $BOUNDS; do
        case $b in
        bounded) opts="" ;;
        *) opts="--backlog 0 --backlog-mb 0" ;;
        esac
        db=$OUT/$b-$n.db
        rm -f "$db"*
        # shellcheck disable=SC2086
        MPBD_TEST_SLOW_VERIFY=10 "$BIN/mpbenchd" $opts \
            -d "$db" "$OUT/exp$n.yaml" >"$OUT/$b-$n.log" 2>&1 &
        pid=$!
        hwm=0
        while kill -0 $pid 2>/dev/null; do
            h=$(awk '/^VmHWM/ {print $2}' /proc/$pid/status 2>/dev/null)
            [ -n "$h" ] && hwm=$h
            sleep 0.2
        done
        wait $pid || echo "mpbenchd failed: see $OUT/$b-$n.log" >&2
        done_runs=$(sqlite3 "$db" "SELECT count(*) FROM runs WHERE state = 'done'")
        echo "RESULT backlog_$b runs=$n done=$done_runs peak_rss_mb=$(calc "$hwm / 1024" 0)"
    done
done
