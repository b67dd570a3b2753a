#!/bin/sh
# bench/verifyload.sh - issue 46: how many runs a second mpbenchd verifies,
# measures and stores when its planners take no time, on the paths OMPL's
# RRTConnect really returns for MotionBenchMaker's Panda problems
# (docs/performance.md, "Verification cost").
#
#   bench/verifyload.sh [--from DB] [--runs N] [--planners P] [--out DIR]
#
#   1. Without --from: bench/experiments/mbm-panda-quick-rrtconnect.yaml
#      (35 problems, RRTConnect, 10 s a run) by tools/run_benchmark.sh -p
#      ompl into a new database (about a minute). With --from DB: that
#      database's newest experiment (any planner; its paths are taken).
#   2. The same 35 problems N times each (default 20), answered by P
#      mpb-planner-load processes (default 2) from that database: each
#      answers at once with the stages the database holds for the
#      problem. mpbenchd runs them twice, N/4 and N runs a problem, under
#      /usr/bin/time: its CPU time per run is the difference of the two
#      over the difference of their runs (loading the experiment and its
#      35 worlds cancels out): the loop, LCM, verification and metrics of
#      every stage, the SQLite commit. Runs a second: the N-run round's
#      runs over its first request to its last result. runs.verify_time
#      is the verification and metrics alone, each run's (wall time of
#      the daemon's thread, which has a core to itself here).
#   3. RRTConnect's own planning time per run (the mean of tau_t in the
#      source database) over the daemon's CPU per run: how many such
#      planners, each planning without pause, one daemon core keeps up
#      with.
# With mpbenchd --verify-threads (issue 46, item 1), the N-run round runs
# with 1 and 2 verifier threads and their ratio of runs a second is
# printed; without it, with the daemon's one verification thread only.
# Inside a private network namespace (bench/lib.sh). Root. Prints RESULT
# lines; the logs stay in DIR (default $MPB_BUILD/bench-run/verifyload).
set -u
src=$(cd "$(dirname "$0")/.." && pwd)
. "$src/tools/usage.sh"
. "$src/bench/lib.sh"
BUILD=${MPB_BUILD:-$src/build}
case $BUILD in /*) ;; *) BUILD=$src/$BUILD ;; esac
FROM="" RUNS=20 NP=2 OUT=""
while [ $# -gt 0 ]; do
    case $1 in
    --from) FROM=$2; shift ;;
    --runs) RUNS=$2; shift ;;
    --planners) NP=$2; shift ;;
    --out) OUT=$2; shift ;;
    -h|--help) mpb_usage; exit 0 ;;
    *) echo "bench/verifyload.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
    esac
    shift
done
OUT=${OUT:-$BUILD/bench-run/verifyload}
case $RUNS in ''|*[!0-9]*) echo "bench/verifyload.sh: --runs wants a number" >&2; exit 2 ;; esac
[ "$RUNS" -ge 4 ] || { echo "bench/verifyload.sh: --runs wants at least 4" >&2; exit 2; }

if [ -z "${MPB_VERIFYLOAD_IN_NETNS:-}" ]; then
    bench_snapshot bench/verifyload.sh "$OUT" "$BUILD/daemon/mpbenchd" \
        "$BUILD/planners/load/mpb-planner-load"
    data=$(sh "$src/tools/robot_data.sh" --check >/dev/null 2>&1 &&
           sh "$src/tools/robot_data.sh") || {
        echo "bench/verifyload.sh: no robot data: run tools/robot_data.sh first" >&2
        exit 1
    }
    if [ -z "$FROM" ]; then
        FROM=$OUT/rrtconnect.db
        rm -f "$FROM" "$FROM-wal" "$FROM-shm"
        echo "== RRTConnect on mbm-panda-quick's 35 problems (tools/run_benchmark.sh -p ompl)"
        env -u MPB_LCM_URL MPB_BUILD="$BUILD" timeout -k 10 900 \
            sh "$src/tools/run_benchmark.sh" -p ompl -d "$FROM" -l "$OUT/logs" \
            "$src/bench/experiments/mbm-panda-quick-rrtconnect.yaml" \
            >"$OUT/rrtconnect.log" 2>&1 || {
            echo "bench/verifyload.sh: tools/run_benchmark.sh failed:" >&2
            tail -20 "$OUT/rrtconnect.log" >&2
            exit 1
        }
    fi
    [ -f "$FROM" ] || { echo "bench/verifyload.sh: $FROM: no such database" >&2; exit 1; }
    FROM=$(cd "$(dirname "$FROM")" && pwd)/$(basename "$FROM")
    export MPB_VERIFYLOAD_IN_NETNS=1 MPB_VERIFYLOAD_DATA=$data
    exec unshare -n sh "$0" --from "$FROM" --runs "$RUNS" --planners "$NP" --out "$OUT"
fi
bench_netns bench/verifyload.sh
unset MPB_LCM_URL
data=$MPB_VERIFYLOAD_DATA
export MPB_MESH_PATH=$data/panda
bin=$OUT/bin
PIDS=""
trap cleanup EXIT INT TERM

# The slice's problems, its paths absolute, answered by the load planner.
experiment_file() { # file name runs
    sed -e "s|\.\./\.\./\.cache/robots/vamp-planner-0\.6\.4|$data|" \
        -e "s|^  name: mbm-panda-quick-rrtconnect\$|  name: $2|" \
        -e "s|^  runs: 1\$|  runs: $3|" \
        -e 's|^  - planner: ompl$|  - planner: load|' \
        -e 's|^    algorithms: \[RRTConnect\]$|    algorithms: [replay]|' \
        "$src/bench/experiments/mbm-panda-quick-rrtconnect.yaml" >"$1"
    [ "$(grep -c "^  name: $2\$\|^  runs: $3\$\|planner: load\$\|algorithms: \[replay\]\$" "$1")" -eq 4 ] || {
        echo "bench/verifyload.sh: bench/experiments/mbm-panda-quick-rrtconnect.yaml changed; cannot make the load experiment" >&2
        exit 1
    }
}

for i in $(seq "$NP"); do
    "$bin/mpb-planner-load" --from "$FROM" >"$OUT/load$i.log" 2>&1 &
    PIDS="$PIDS $!"
done
sleep 1

threads="1"
"$bin/mpbenchd" --help 2>&1 | grep -q -- '--verify-threads' && threads="1 2"

# round NAME RUNS [THREADS]: the experiment, its daemon's CPU (s) and
# its RESULT line.
round() {
    f=$OUT/$1.yaml db=$OUT/$1.db
    experiment_file "$f" "$1" "$2"
    rm -f "$db" "$db-wal" "$db-shm"
    topt=""
    [ -n "${3:-}" ] && topt="--verify-threads $3"
    # shellcheck disable=SC2086
    /usr/bin/time -f '%U %S' -o "$OUT/$1.time" timeout -k 5 900 \
        "$bin/mpbenchd" $topt -d "$db" "$f" >"$OUT/$1.log" 2>&1 || {
        echo "bench/verifyload.sh: mpbenchd failed on $1:" >&2
        tail -5 "$OUT/$1.log" >&2
        exit 1
    }
    cpu=$(awk '{print $1 + $2}' "$OUT/$1.time")
    sqlite3 "$db" "SELECT count(*), max(finished) - min(sent),
        (SELECT verify_time FROM runs ORDER BY verify_time
         LIMIT 1 OFFSET (SELECT count(*) / 2 FROM runs)),
        avg(verify_time), sum(success) FROM runs WHERE state = 'done'" |
    awk -F'|' -v n="$1" -v cpu="$cpu" '{
        printf "RESULT verifyload_%s runs=%d seconds=%.3f runs_per_s=%.1f " \
               "daemon_cpu_s=%.3f verify_ms_median=%.3f verify_ms_mean=%.3f " \
               "successes=%d\n", n, $1, $2, $1 / $2, cpu, 1e3 * $3, 1e3 * $4, $5
    }'
}

RAW=$OUT/raw.txt
: >"$RAW"
quarter=$((RUNS / 4))
echo "== $NP load planners, 35 problems x $quarter and x $RUNS runs"
round small "$quarter" | tee -a "$RAW"
for t in $threads; do
    name=full
    [ "$threads" = 1 ] || name=full_t$t
    round "$name" "$RUNS" "$([ "$threads" = 1 ] || echo "$t")" | tee -a "$RAW"
done
full=full
[ "$threads" = 1 ] || full=full_t1
n1=$(get verifyload_small runs) n2=$(get verifyload_$full runs)
c1=$(get verifyload_small daemon_cpu_s) c2=$(get verifyload_$full daemon_cpu_s)
per_run=$(calc "($c2 - $c1) / ($n2 - $n1) * 1e3" 3)
plan=$(sqlite3 "$FROM" "SELECT avg(time_total) * 1e3 FROM runs WHERE state = 'done'
    AND experiment_id = (SELECT max(id) FROM experiments)")
keep=$(calc "$plan / $per_run" 1)
echo "daemon CPU per run: $per_run ms (loop, LCM, verification and metrics, commit)"
echo "RRTConnect's planning per run in $(basename "$FROM"): $(calc "$plan" 2) ms (mean tau_t)"
echo "RRTConnect planners one daemon core keeps up with: $keep"
ratio=nan
if [ "$threads" != 1 ]; then
    ratio=$(calc "$(get verifyload_full_t2 runs_per_s) / $(get verifyload_full_t1 runs_per_s)" 2)
    echo "2 verifier threads / 1, runs a second: $ratio"
fi
echo "RESULT verifyload planners=$NP runs=$RUNS daemon_cpu_ms_per_run=$per_run rrtconnect_ms_per_run=$(calc "$plan" 2) planners_per_core=$keep threads2_over_1=$ratio" | tee -a "$RAW"
