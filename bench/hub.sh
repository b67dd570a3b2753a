#!/bin/sh
# bench/hub.sh - null-planner runs per second and the daemon's latency
# (request first sent to result committed) through lcm-java's TCP hub
# (tcpq://) against UDP multicast, in the same run on the same machine:
# in turns (--rounds R, default 3), with 1 and 4 null planners, N runs per
# planner (--runs, default 5000). Runs per second are counted in the
# database: runs over the time from the first send to the last finish.
# docs/performance.md ("Through a hub") has the figures.
#
#   bench/hub.sh [--runs N] [--rounds R] [--out DIR]
#
# Inside a private network namespace (only loopback, with a multicast
# route; as bench/run.sh). Prints a RESULT line per experiment.
set -u

src=$(cd "$(dirname "$0")/.." && pwd)
. "$src/tools/usage.sh"
. "$src/bench/lib.sh"
BUILD=${MPB_BUILD:-$src/build}
case $BUILD in /*) ;; *) BUILD=$src/$BUILD ;; esac
RUNS=5000 ROUNDS=3 OUT="" IN_NETNS=0
while [ $# -gt 0 ]; do
    case $1 in
    --runs) RUNS=$2; shift ;;
    --rounds) ROUNDS=$2; shift ;;
    --out) OUT=$2; shift ;;
    --in-netns) IN_NETNS=1 ;;
    -h|--help) mpb_usage; exit 0 ;;
    *) echo "bench/hub.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
    esac
    shift
done
case $RUNS$ROUNDS in *[!0-9]*|"")
    echo "bench/hub.sh: --runs and --rounds want whole numbers" >&2; exit 2 ;;
esac
: "${OUT:=$BUILD/bench-run/hub}"

if [ "$IN_NETNS" -eq 0 ]; then
    bench_snapshot bench/hub.sh "$OUT" "$BUILD/daemon/mpbenchd" \
        "$BUILD/planners/null/mpb-planner-null"
    exec unshare -n sh "$0" --in-netns --runs "$RUNS" --rounds "$ROUNDS" --out "$OUT"
fi

bench_netns bench/hub.sh
BIN=$OUT/bin
trap cleanup EXIT
trap 'exit 130' INT TERM

MCAST='udpm://239.255.76.67:7667?ttl=0'
HUB=tcpq://127.0.0.1:7700
java -Xmx256m -cp /usr/share/java/lcm.jar lcm.lcm.TCPService 7700 \
    >"$OUT/hub.log" 2>&1 &
PIDS="$PIDS $!"
sleep 1.5

# One experiment: runs, runs per second, the daemon's median and p99 (us).
measure() { # key url planners round
    db=$OUT/$1-$3-$4.db log=$OUT/$1-$3-$4.log
    rm -f "$db"*
    timeout -k 5 600 "$BIN/mpbenchd" --lcm-url "$2" -d "$db" "$OUT/p$3.yaml" \
        >"$log" 2>&1 || echo "mpbenchd failed: see $log" >&2
    set -- "$1" "$2" "$3" "$4" $(sqlite3 -separator ' ' "$db" "SELECT count(*),
        printf('%.0f', count(*) / (max(finished) - min(sent))) FROM runs
        WHERE state = 'done'") $(daemon_latency "$log")
    echo "RESULT hub_$1_p$3 round=$4 runs=${5:-0} runs_per_s=${6:-nan} median_us=${7:-nan} p99_us=${8:-nan}"
}

for n in 1 4; do
    experiment "bench-hub-p$n" $((RUNS * n)) "$n" "$OUT/p$n.yaml"
    for i in $(seq "$n"); do
        "$BIN/mpb-planner-null" --lcm-url "$MCAST" >"$OUT/mcast-planner$i.log" 2>&1 &
        PIDS="$PIDS $!"
        "$BIN/mpb-planner-null" --lcm-url "$HUB" >"$OUT/hub-planner$i.log" 2>&1 &
        PIDS="$PIDS $!"
    done
    sleep 1     # their first announcements
    for r in $(seq "$ROUNDS"); do
        measure mcast "$MCAST" "$n" "$r"
        measure tcpq "$HUB" "$n" "$r"
    done
    # Stop this count's planners, keep the hub.
    for p in $PIDS; do
        case $(cat /proc/$p/cmdline 2>/dev/null | tr '\0' ' ') in
        *mpb-planner-null*) kill "$p"; wait "$p" 2>/dev/null ;;
        esac
    done
done
