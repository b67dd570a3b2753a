#!/bin/sh
# bench/profile.sh - instructions per run of mpbenchd and of the null
# planners, with valgrind's callgrind: a count that does not move with the
# machine's load, so two versions of the code compare on a busy machine
# (docs/performance.md).
#
#   bench/profile.sh [--runs N] [--planners P] [--strace] [--out DIR]
#
# Inside a private network namespace (only loopback, with a multicast
# route; as bench/run.sh), it runs the planar throughput experiment twice
# under callgrind, once with N/4 runs and once with N (default 3000), the
# daemon and every null planner each under callgrind, and prints the
# instructions per run from the difference of the two: setup (loading the
# experiment, creating the database, starting LCM) cancels out. The
# profiles of the N-run round stay in DIR (default
# $MPB_BUILD/bench-run/profile) for callgrind_annotate. --strace also
# counts the daemon's system calls per run (strace -c -f, N runs, no
# valgrind).
set -u

src=$(cd "$(dirname "$0")/.." && pwd)
. "$src/tools/usage.sh"
. "$src/bench/lib.sh"
BUILD=${MPB_BUILD:-$src/build}
case $BUILD in /*) ;; *) BUILD=$src/$BUILD ;; esac
RUNS=3000 NP=1 OUT="" STRACE=0 IN_NETNS=0
while [ $# -gt 0 ]; do
    case $1 in
    --runs) RUNS=$2; shift ;;
    --planners) NP=$2; shift ;;
    --out) OUT=$2; shift ;;
    --strace) STRACE=1 ;;
    --in-netns) IN_NETNS=1 ;;
    -h|--help) mpb_usage; exit 0 ;;
    *) echo "bench/profile.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
    esac
    shift
done
: "${OUT:=$BUILD/bench-run/profile}"

if [ "$IN_NETNS" -eq 0 ]; then
    command -v valgrind >/dev/null || { echo "bench/profile.sh: needs valgrind" >&2; exit 1; }
    bench_snapshot bench/profile.sh "$OUT" "$BUILD/daemon/mpbenchd" \
        "$BUILD/planners/null/mpb-planner-null"
    set -- --in-netns --runs "$RUNS" --planners "$NP" --out "$OUT"
    [ "$STRACE" -eq 1 ] && set -- "$@" --strace
    exec unshare -n sh "$0" "$@"
fi

bench_netns bench/profile.sh

BIN=$OUT/bin
trap cleanup EXIT
trap 'exit 130' INT TERM

# Total instructions (Ir) of a callgrind profile.
total_ir() { awk '/^(summary|totals):/ { print $2; exit }' "$1"; }

round() { # runs tag
    experiment "profile-$2" "$1" "$NP" "$OUT/$2.yaml"
    rm -f "$OUT/$2.db"*
    i=0
    while [ "$i" -lt "$NP" ]; do
        valgrind --tool=callgrind --callgrind-out-file="$OUT/$2-null.$i.out" \
            "$BIN/mpb-planner-null" >"$OUT/$2-null.$i.log" 2>&1 &
        PIDS="$PIDS $!"
        i=$((i + 1))
    done
    sleep 3     # valgrind starts slowly; one announce before the daemon
    timeout -k 5 900 valgrind --tool=callgrind \
        --callgrind-out-file="$OUT/$2-daemon.out" \
        "$BIN/mpbenchd" -d "$OUT/$2.db" "$OUT/$2.yaml" >"$OUT/$2-daemon.log" 2>&1 ||
        { echo "mpbenchd failed: see $OUT/$2-daemon.log" >&2; exit 1; }
    cleanup     # the planners write their profiles as they exit
    done_runs=$(sqlite3 "$OUT/$2.db" "SELECT count(*) FROM runs WHERE state = 'done'")
    [ "$done_runs" -eq "$1" ] || { echo "only $done_runs of $1 runs done" >&2; exit 1; }
}

SMALL=$((RUNS / 4))
echo "== callgrind: mpbenchd + $NP null planner(s), $SMALL then $RUNS runs"
round "$SMALL" small
round "$RUNS" large
d_small=$(total_ir "$OUT/small-daemon.out") d_large=$(total_ir "$OUT/large-daemon.out")
p_small=0 p_large=0
for f in "$OUT"/small-null.*.out; do p_small=$((p_small + $(total_ir "$f"))); done
for f in "$OUT"/large-null.*.out; do p_large=$((p_large + $(total_ir "$f"))); done
n=$((RUNS - SMALL))
echo "RESULT profile planners=$NP runs=$RUNS daemon_ir_per_run=$(( (d_large - d_small) / n )) \
planners_ir_per_run=$(( (p_large - p_small) / n ))"
echo "profiles: $OUT/large-daemon.out, $OUT/large-null.*.out (callgrind_annotate --inclusive=yes)"

if [ "$STRACE" -eq 1 ]; then
    command -v strace >/dev/null || { echo "bench/profile.sh: --strace needs strace" >&2; exit 1; }
    experiment profile-strace "$RUNS" "$NP" "$OUT/strace.yaml"
    rm -f "$OUT/strace.db"*
    i=0
    while [ "$i" -lt "$NP" ]; do
        "$BIN/mpb-planner-null" >"$OUT/strace-null.$i.log" 2>&1 &
        PIDS="$PIDS $!"
        i=$((i + 1))
    done
    sleep 0.5
    strace -c -f -o "$OUT/strace.txt" "$BIN/mpbenchd" -d "$OUT/strace.db" \
        "$OUT/strace.yaml" >"$OUT/strace-daemon.log" 2>&1
    cleanup
    echo "== mpbenchd system calls per run ($RUNS runs, strace -c -f)"
    awk -v n="$RUNS" '$1 ~ /^[0-9.]+$/ && NF >= 5 {
        printf "  %-16s %6.2f\n", $NF, $4 / n }' "$OUT/strace.txt" | sort -k2 -rn | head -15
fi
