#!/bin/sh
# bench/run.sh - the benchmark of the benchmark (docs/performance.md).
#
#   bench/run.sh [--quick] [--runs N] [--report-runs N] [--fidelity-runs N]
#                [--fidelity-np-runs N] [--long-runs N] [--keep]
#
# Builds the bench programs, then, inside a private network namespace that
# it creates (only a loopback interface, with a multicast route), measures:
#   1. the LCM round-trip floor (mpb-bench-floor),
#   2. per-run latency end to end: real mpbenchd + one null planner, each
#      run from its request's first send to its commit (mpbenchd's own
#      count, nothing else listening), again in rounds that alternate
#      with the floor (bench/latency.sh), then its parts from the
#      daemon's timestamps on the network (mpb-bench-watch listening),
#   3. throughput with 1, 2, 3, 4 and 8 null planners, with and without a
#      request waiting at each; 8 planners over 1,000,000 runs each way,
#      the daemon's memory sampled throughout,
#   4. verification + metrics, waypoints per second (mpb-bench-verify), for
#      the planar demo arm and for the PR2 right arm in the kitchen; a
#      mesh robot against it (4m, bench/meshspeed.sh: the Panda with its
#      SRDF and meshes in a MotionBenchMaker scene, when tools/robot_data.sh
#      has fetched it: a state check's cost over the PR2's, and its
#      verification + metrics); timing
#      fidelity: RRTConnect on the first query of the paper's narrow
#      passage (about 30 ms a run) and of its kitchen (about 2 ms) through
#      mpbenchd and mpb-planner-ompl vs OMPL's own Benchmark and a bare
#      solve() (bench/fidelity.sh): in interleaved blocks, then run by run
#      with a fourth side, a bare solve() in a process of its own (4h),
#   5. the store's write cost per run, and `mpb report` over a database of
#      a million runs (mpb-bench-mkdb),
#   6. an OMPL log of 50,000 runs into a Planner Arena database, `mpb
#      import -p` against OMPL's ompl_benchmark_statistics.py (not part of
#      mpbench: bench/ompl_peer.sh takes it from Debian's source package of
#      the installed OMPL, unless OMPL_STATS names a copy) (bench/import.sh).
# Prints a table (bench/table.sh) and writes it, with the machine and the
# raw results, to bench/results/<date>.md. Every step has a count and a
# time limit.
#
#   --quick          small counts (about 2 minutes in all)
#   --runs N         runs per throughput experiment (default 100000)
#   --long-runs N    runs of the two long ones, 8 planners (default
#                    1000000; with --quick, the --runs count)
#   --report-runs N  runs in the report database (default 1000000)
#   --fidelity-runs N  RRTConnect runs on each side for the timing fidelity
#                    in the kitchen, in 20 interleaved blocks (4 with
#                    --quick; default 5000, 200 with --quick)
#   --fidelity-np-runs N  the same in the narrow passage, 20 blocks (3 with
#                    --quick; default 2000, 60 with --quick); run by run,
#                    half as many of each
#   --keep           keep the work directory (databases, logs)
set -u

src=$(cd "$(dirname "$0")/.." && pwd)
. "$src/tools/usage.sh"
. "$src/bench/lib.sh"
BUILD=${MPB_BUILD:-$src/build}
case $BUILD in /*) ;; *) BUILD=$src/$BUILD ;; esac
WORK=$BUILD/bench-run/work     # databases and logs of one run
SNAP=$BUILD/bench-run/bin      # the binaries measured, copied at the start

QUICK=0 KEEP=0 TPUT_N="" LONG_N="" REPORT_N="" FID_N="" FIDNP_N="" IN_NETNS=0
while [ $# -gt 0 ]; do
    case $1 in
    --quick) QUICK=1 ;;
    --keep) KEEP=1 ;;
    --runs) TPUT_N=$2; shift ;;
    --long-runs) LONG_N=$2; shift ;;
    --report-runs) REPORT_N=$2; shift ;;
    --fidelity-runs) FID_N=$2; shift ;;
    --fidelity-np-runs) FIDNP_N=$2; shift ;;
    --in-netns) IN_NETNS=1 ;;
    -h|--help) mpb_usage; exit 0 ;;
    *) echo "bench/run.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
    esac
    shift
done

if [ "$QUICK" -eq 1 ]; then
    FLOOR_N=2000 LAT_N=2000 LAT_SKIP=200 LAT_ROUNDS=3 LAT_ROUND_N=1000 VERIFY_S=0.3 STORE_N=5000 IMPORT_N=5000
    MESH_STATES=500 MESH_ROUNDS=4
    : "${FID_N:=200}" "${FID_BLOCKS:=4}" "${FIDNP_N:=60}" "${FIDNP_BLOCKS:=3}"
    : "${TPUT_N:=10000}" "${LONG_N:=$TPUT_N}" "${REPORT_N:=100000}"
else
    FLOOR_N=20000 LAT_N=20000 LAT_SKIP=1000 LAT_ROUNDS=20 LAT_ROUND_N=5000 VERIFY_S=1 STORE_N=20000 IMPORT_N=50000
    MESH_STATES=2000 MESH_ROUNDS=10
    : "${FID_N:=5000}" "${FID_BLOCKS:=20}" "${FIDNP_N:=2000}" "${FIDNP_BLOCKS:=20}"
    : "${TPUT_N:=100000}" "${LONG_N:=1000000}" "${REPORT_N:=1000000}"
fi
[ "$FID_N" -ge 1 ] 2>/dev/null && [ "$FID_N" -lt "$FID_BLOCKS" ] && FID_BLOCKS=$FID_N
[ "$FIDNP_N" -ge 1 ] 2>/dev/null && [ "$FIDNP_N" -lt "$FIDNP_BLOCKS" ] && FIDNP_BLOCKS=$FIDNP_N

# ---- outside the namespace: build, snapshot the binaries, re-enter --------
if [ "$IN_NETNS" -eq 0 ]; then
    [ "$(id -u)" -eq 0 ] || { echo "bench/run.sh: needs root (unshare -n)" >&2; exit 1; }
    echo "== building"
    [ -f "$BUILD/CMakeCache.txt" ] || cmake -S "$src" -B "$BUILD" >/dev/null || exit 1
    cmake --build "$BUILD" -j "$(nproc)" --target mpbenchd mpb-planner-null \
        >"$BUILD/bench-build.log" 2>&1 || {
        tail -20 "$BUILD/bench-build.log"; echo "bench/run.sh: build failed" >&2; exit 1; }
    # mpb is needed for item 5 only: a broken tools/ build skips that item.
    cmake --build "$BUILD" -j "$(nproc)" --target mpb >>"$BUILD/bench-build.log" 2>&1 ||
        echo "bench/run.sh: mpb does not build; the report timing is skipped"
    # The OMPL planner, for the timing fidelity only.
    cmake --build "$BUILD" -j "$(nproc)" --target mpb-planner-ompl >>"$BUILD/bench-build.log" 2>&1 ||
        echo "bench/run.sh: mpb-planner-ompl does not build; timing fidelity is skipped"
    # The bench programs: part of the main build if the top-level
    # CMakeLists.txt adds bench/, else a project of their own beside it.
    if grep -q '^[[:space:]]*add_subdirectory(bench)' "$src/CMakeLists.txt"; then
        BENCH_BIN=$BUILD/bench
        cmake --build "$BUILD" -j "$(nproc)" --target mpb-bench-floor \
            mpb-bench-watch mpb-bench-verify mpb-bench-mkdb mpb-bench-meshcheck >>"$BUILD/bench-build.log" 2>&1 &&
        { cmake --build "$BUILD" -j "$(nproc)" --target mpb-bench-fidelity \
            >>"$BUILD/bench-build.log" 2>&1 || true; }
    else
        BENCH_BIN=$BUILD/bench-standalone
        cmake -S "$src/bench" -B "$BENCH_BIN" -DMPB_BUILD="$BUILD" >/dev/null &&
            cmake --build "$BENCH_BIN" -j "$(nproc)" --target mpb-bench-floor \
                mpb-bench-watch mpb-bench-verify mpb-bench-mkdb mpb-bench-meshcheck \
                >>"$BUILD/bench-build.log" 2>&1 &&
            { cmake --build "$BENCH_BIN" -j "$(nproc)" --target mpb-bench-fidelity \
                >>"$BUILD/bench-build.log" 2>&1 ||
              echo "bench/run.sh: mpb-bench-fidelity does not build; timing fidelity is skipped"; }
    fi || { tail -20 "$BUILD/bench-build.log"; echo "bench/run.sh: bench build failed" >&2; exit 1; }
    # Item 6's peer, OMPL's own script, from Debian's source package of the
    # installed OMPL unless OMPL_STATS names it: fetched here, while there
    # is a network.
    if [ -z "${OMPL_STATS:-}" ]; then
        OMPL_STATS=$(MPB_BUILD=$BUILD sh "$src/bench/ompl_peer.sh") &&
            echo "== OMPL's ompl_benchmark_statistics.py: $OMPL_STATS" ||
            echo "bench/run.sh: the import (6) is skipped"
        export OMPL_STATS
    fi
    # Others may rebuild the tree meanwhile: measure one consistent set.
    rm -rf "$SNAP" && mkdir -p "$SNAP"
    cp "$BUILD/daemon/mpbenchd" "$BUILD/planners/null/mpb-planner-null" \
       "$BENCH_BIN"/mpb-bench-* "$SNAP/" || exit 1
    [ -x "$BUILD/tools/mpb" ] && cp "$BUILD/tools/mpb" "$SNAP/"
    [ -x "$BUILD/planners/ompl/mpb-planner-ompl" ] &&
        cp "$BUILD/planners/ompl/mpb-planner-ompl" "$SNAP/"
    set -- --in-netns
    [ "$QUICK" -eq 1 ] && set -- "$@" --quick
    [ "$KEEP" -eq 1 ] && set -- "$@" --keep
    exec unshare -n sh "$0" "$@" --runs "$TPUT_N" --long-runs "$LONG_N" \
        --report-runs "$REPORT_N" \
        --fidelity-runs "$FID_N" --fidelity-np-runs "$FIDNP_N"
fi

# ---- inside the private network namespace ----------------------------------
bench_netns bench/run.sh

rm -rf "$WORK" && mkdir -p "$WORK" || exit 1
RAW=$WORK/results.txt
: >"$RAW"
trap 'cleanup; [ "$KEEP" -eq 1 ] || rm -rf "$WORK"' EXIT
trap 'exit 130' INT TERM

ROBOT=$src/scenes/planar/arm3.robot
SCENE=$src/scenes/planar/pillars.scene

# RESULT lines of the bench programs go to $RAW (get and calc: lib.sh).
collect() { grep '^RESULT ' "$1" >>"$RAW"; }
put() { echo "RESULT $*" >>"$RAW"; }
now() { date +%s.%N; }

planners() { # count logprefix
    i=0
    while [ "$i" -lt "$1" ]; do
        "$SNAP/mpb-planner-null" >"$2.$i.log" 2>&1 &
        PIDS="$PIDS $!"
        i=$((i + 1))
    done
    sleep 0.5   # one announce before the daemon starts
}

# The p-quantile of a column of done runs, from the database.
db_quantile() { # db expr p
    sqlite3 "$1" "SELECT $2 FROM runs WHERE state = 'done' ORDER BY $2
        LIMIT 1 OFFSET (SELECT CAST((count(*) - 1) * $3 AS INTEGER)
                        FROM runs WHERE state = 'done')"
}

load() { cut -d' ' -f1-3 /proc/loadavg; }
LOAD_START=$(load)
STARTED=$(date '+%Y-%m-%d %H:%M:%S %z')

# ---- 1. floor ---------------------------------------------------------------
echo "== 1. LCM round-trip floor ($FLOOR_N exchanges)"
timeout -k 5 300 "$SNAP/mpb-bench-floor" --robot "$ROBOT" --scene "$SCENE" \
    --count "$FLOOR_N" >"$WORK/floor.log" 2>&1
cat "$WORK/floor.log"; collect "$WORK/floor.log"

# ---- 2. per-run latency -----------------------------------------------------
# First with nothing else listening: mpbenchd's own count, request first
# sent to result committed (its log's last lines); the floor has no
# listener either. Then again with mpb-bench-watch listening, for the
# parts of a run (a listener is one more process that every message
# wakes: on 2 cores it slows what it watches by a fifth). No request waits
# at the planner (queue_at_planner 0, the default): each run's request goes
# out after the last run's commit, so its latency is the whole round trip.
echo "== 2. per-run latency, mpbenchd + 1 null planner ($((LAT_N + LAT_SKIP)) runs)"
experiment bench-latency $((LAT_N + LAT_SKIP)) 1 "$WORK/latency.yaml" 0
planners 1 "$WORK/latency-own-null"
timeout -k 5 600 "$SNAP/mpbenchd" -d "$WORK/latency-own.db" "$WORK/latency.yaml" \
    >"$WORK/latency-own-daemon.log" 2>&1 || echo "mpbenchd failed: see $WORK/latency-own-daemon.log"
cleanup
daemon_latency "$WORK/latency-own-daemon.log" | {
    read -r med p99 n
    put "run_latency_own n=${n:-0} median_us=${med:-nan} p99_us=${p99:-nan}"
}
grep "^RESULT run_latency_own " "$RAW" | sed 's/^RESULT /  /'

# The same in turns with the floor, seconds apart (bench/latency.sh): the
# floor of item 1 was measured a minute before, and on this VM it can move
# by half in that time.
echo "== 2. per-run latency in turns with the floor ($LAT_ROUNDS rounds of $LAT_ROUND_N)"
timeout -k 5 900 sh "$src/bench/latency.sh" --in-netns --bin "$SNAP" \
    --out "$WORK/latency-paired" --rounds "$LAT_ROUNDS" --runs "$LAT_ROUND_N" \
    --exchanges "$LAT_ROUND_N" >"$WORK/latency-paired.log" 2>&1
grep '^RESULT latency_paired ' "$WORK/latency-paired.log" | sed 's/^RESULT /  /'
collect "$WORK/latency-paired.log"

echo "== 2. the same, with mpb-bench-watch listening ($LAT_N runs after $LAT_SKIP)"
planners 1 "$WORK/latency-null"
"$SNAP/mpb-bench-watch" --runs "$LAT_N" --skip "$LAT_SKIP" --timeout 600 \
    >"$WORK/watch.log" 2>&1 &
WATCH=$!
sleep 0.3
timeout -k 5 600 "$SNAP/mpbenchd" -d "$WORK/latency.db" "$WORK/latency.yaml" \
    >"$WORK/latency-daemon.log" 2>&1 || echo "mpbenchd failed: see $WORK/latency-daemon.log"
wait "$WATCH"
cleanup
cat "$WORK/watch.log"; collect "$WORK/watch.log"
put "db_wall_time median_us=$(calc "$(db_quantile "$WORK/latency.db" wall_time 0.5) * 1e6") \
p99_us=$(calc "$(db_quantile "$WORK/latency.db" wall_time 0.99) * 1e6")"

# ---- 3. throughput and memory -----------------------------------------------
# Sample a process every half second until it exits: seconds, VmRSS (kB),
# CPU time so far (user + system, clock ticks).
rss_sampler() { # pid out
    t0=$(now)
    while [ -r "/proc/$1/status" ]; do
        rss="" cpu=""
        while read -r k v _; do
            [ "$k" = "VmRSS:" ] && rss=$v
        done <"/proc/$1/status"
        # The command name (field 2) has no spaces here: utime, stime are
        # fields 14 and 15.
        read -r _ _ _ _ _ _ _ _ _ _ _ _ _ ut st _ <"/proc/$1/stat" && cpu=$((ut + st))
        [ -n "$rss" ] && echo "$(calc "$(now) - $t0" 2) $rss ${cpu:-0}"
        sleep 0.5
    done >"$2"
}

throughput() { # planners runs key [queue_at_planner]
    np=$1 runs=$2 key=$3
    experiment "bench-throughput-$np" "$runs" "$np" "$WORK/$key.yaml" "${4:-0}"
    planners "$np" "$WORK/$key-null"
    limit=$((runs / 200 + 120))
    timeout -k 5 "$limit" "$SNAP/mpbenchd" -d "$WORK/$key.db" "$WORK/$key.yaml" \
        >"$WORK/$key-daemon.log" 2>&1 &
    guard=$!
    # The daemon is timeout's child: sample its memory, not timeout's.
    daemon=""
    for _ in 1 2 3 4 5 6 7 8 9 10; do
        daemon=$(pgrep -P "$guard") && break
        sleep 0.05
    done
    rss_sampler "${daemon:-$guard}" "$WORK/$key-rss.txt" &
    sampler=$!
    wait "$guard" || echo "mpbenchd failed or timed out: see $WORK/$key-daemon.log"
    wait "$sampler"
    # The planners' CPU time (clock ticks), all of them together: is the
    # planner side (the null planner and the planner kit) a bottleneck?
    pticks=0
    for p in $PIDS; do
        read -r _ _ _ _ _ _ _ _ _ _ _ _ _ ut st _ 2>/dev/null <"/proc/$p/stat" &&
            pticks=$((pticks + ut + st))
    done
    cleanup
    stats=$(sqlite3 -separator ' ' "$WORK/$key.db" "SELECT count(*),
        max(finished) - min(sent), sum(attempts > 1), sum(status = 'crash'),
        sum(success) FROM runs WHERE state = 'done'")
    # A million runs make a database of about 1.3 GB.
    [ "$KEEP" -eq 1 ] || rm -f "$WORK/$key.db" "$WORK/$key.db-wal" "$WORK/$key.db-shm"
    # RSS after a tenth and half of the run, at the end, the largest; the
    # growth counted is over the second half (SQLite's page cache, 16 MiB
    # at most, fills during the first tens of thousands of runs).
    rss=$(awk '{ t[NR] = $1; r[NR] = $2; c = $3; if ($2 > m) m = $2 }
        END { if (NR == 0) { print "nan nan nan nan nan"; exit }
              for (i = 1; i < NR && t[i] < t[NR] / 10; i++) ;
              for (h = 1; h < NR && t[h] < t[NR] / 2; h++) ;
              print r[i], r[h], r[NR], m, c }' "$WORK/$key-rss.txt")
    hz=$(getconf CLK_TCK)
    echo "$stats $rss $pticks" | {
        read -r n span retried crashed ok early half end max ticks pticks
        put "$key runs=$n seconds=$span runs_per_s=$(calc "$n / $span" 0) \
retried=$retried crashed=$crashed succeeded=$ok rss_early_kb=$early \
rss_half_kb=$half rss_end_kb=$end rss_max_kb=$max \
rss_growth_kb=$(calc "$end - $half" 0) \
daemon_cpu_us_per_run=$(calc "$ticks / $hz / $n * 1e6" 1) \
planners_cpu_us_per_run=$(calc "$pticks / $hz / $n * 1e6" 1)"
    }
    grep "^RESULT $key " "$RAW" | sed 's/^RESULT /  /'
}

# With few planners each waits for its own round trip and the daemon is
# idle between their results; 8 keep it busy, which is what it sustains
# (over a million runs: the rate and the memory).
for np in 1 2 3 4; do
    echo "== 3. throughput, $(planners_n "$np") ($TPUT_N runs)"
    throughput "$np" "$TPUT_N" "tput$np"
done
echo "== 3. throughput, 8 null planners ($LONG_N runs)"
throughput 8 "$LONG_N" tput8
# With the next request waiting at each planner (docs/performance.md, 4d).
for np in 1 3; do
    echo "== 3. throughput, $(planners_n "$np"), queue_at_planner 1 ($TPUT_N runs)"
    throughput "$np" "$TPUT_N" "tput${np}q" 1
done
echo "== 3. throughput, 8 null planners, queue_at_planner 1 ($LONG_N runs)"
throughput 8 "$LONG_N" tput8q 1

# The floor again: how much did the machine drift meanwhile?
timeout -k 5 300 "$SNAP/mpb-bench-floor" --robot "$ROBOT" --scene "$SCENE" \
    --count "$FLOOR_N" >"$WORK/floor2.log" 2>&1
sed 's/^RESULT floor /RESULT floor_again /' "$WORK/floor2.log" >"$WORK/floor2.res"
collect "$WORK/floor2.res"
echo "== 1. floor again: median $(get floor_again median_us) us"

# ---- 4. verification + metrics ----------------------------------------------
echo "== 4. verification + metrics (planar world)"
for sp in 0.01 0.1; do
    "$SNAP/mpb-bench-verify" --robot "$ROBOT" --scene "$SCENE" --spacing "$sp" \
        --seconds "$VERIFY_S" >"$WORK/verify-$sp.log" 2>&1
    cat "$WORK/verify-$sp.log"
    sed "s/^RESULT verify /RESULT verify_$sp /" "$WORK/verify-$sp.log" >"$WORK/verify-$sp.res"
    collect "$WORK/verify-$sp.res"
done

# The PR2 right arm (7 joints, FCL): in the paper's kitchen once
# scenes/paper/kitchen.scene exists, else in the unit tests' tabletop.
PR2_JOINTS=r_shoulder_pan_joint,r_shoulder_lift_joint,r_upper_arm_roll_joint,r_elbow_flex_joint,r_forearm_roll_joint,r_wrist_flex_joint,r_wrist_roll_joint
PR2_URDF=$src/scenes/robots/pr2_right_arm.urdf
[ -f "$PR2_URDF" ] || PR2_URDF=$src/tests/support/data/pr2_right_arm.urdf
if [ -f "$src/scenes/paper/kitchen.scene" ]; then
    PR2_SCENE=$src/scenes/paper/kitchen.scene PR2_WHERE=kitchen
else
    PR2_SCENE=$src/tests/support/data/scene_tabletop.scene PR2_WHERE=tabletop
fi
echo "== 4. verification + metrics (PR2 right arm, $PR2_WHERE)"
put "verify_pr2_setup scene=$PR2_WHERE"
for sp in 0.01 0.1; do
    timeout -k 5 120 "$SNAP/mpb-bench-verify" --robot "$PR2_URDF" \
        --scene "$PR2_SCENE" --robot-format urdf --scene-format moveit-scene \
        --joints "$PR2_JOINTS" --waypoints 2000 --spacing "$sp" \
        --seconds "$VERIFY_S" --label "PR2 right arm, $PR2_WHERE" \
        >"$WORK/verify-pr2-$sp.log" 2>&1
    cat "$WORK/verify-pr2-$sp.log"
    sed "s/^RESULT verify /RESULT verify_pr2_$sp /" "$WORK/verify-pr2-$sp.log" \
        >"$WORK/verify-pr2-$sp.res"
    collect "$WORK/verify-pr2-$sp.res"
done

# ---- 4m. meshes at speed ----------------------------------------------------
# A mesh robot's state check over the PR2's, in one program, interleaved
# (bench/meshspeed.sh); needs the robot data fetched before (no network
# here).
if sh "$src/tools/robot_data.sh" --check; then
    sh "$src/bench/meshspeed.sh" --bin "$SNAP" --states "$MESH_STATES" \
        --rounds "$MESH_ROUNDS" --seconds "$VERIFY_S" >"$WORK/meshspeed.log" 2>&1
    grep -v '^RESULT ' "$WORK/meshspeed.log"; collect "$WORK/meshspeed.log"
else
    echo "== 4m. meshes at speed: skipped (no robot data: tools/robot_data.sh)"
fi

# ---- 4. timing fidelity ------------------------------------------------------
# RRTConnect on the first query of the paper's narrow passage (FIDNP_N runs
# on each side; its RESULT keys renamed fidelity_np_*) and of its kitchen
# (FID_N): through mpbenchd + mpb-planner-ompl, in OMPL's own Benchmark, as
# a bare solve() in process; interleaved blocks, the same seeds on every
# side, the planning processes on the last CPU (bench/fidelity.sh). Then
# both run by run (half as many runs, in blocks of 100 or more, at most 10:
# fidelity_npp_*, fidelity_kp_*; 4e), with the bare solve() also in a
# process of its own that waits between runs as the planner does (4h).
fidelity_run() { # scene runs blocks key-prefix [fidelity.sh options]
    log=$WORK/$4.log
    scene=$1 runs=$2 blocks=$3 key=$4
    shift 4
    set -- --in-netns --bin "$SNAP" --work "$WORK/$key" --scene "$scene" \
        --runs "$runs" --blocks "$blocks" --key-prefix "$key" "$@"
    [ "$KEEP" -eq 1 ] && set -- "$@" --keep
    sh "$src/bench/fidelity.sh" "$@" >"$log" 2>&1
    grep -v '^RESULT ' "$log"; collect "$log"
}
paced_blocks() { # runs
    b=$(($1 / 100)); [ "$b" -lt 1 ] && b=1; [ "$b" -gt 10 ] && b=10; echo "$b"
}
if [ -x "$SNAP/mpb-planner-ompl" ] && [ -x "$SNAP/mpb-bench-fidelity" ]; then
    fidelity_run narrow_passage "$FIDNP_N" "$FIDNP_BLOCKS" fidelity_np_
    fidelity_run kitchen "$FID_N" "$FID_BLOCKS" fidelity_
    n=$((FIDNP_N / 2))
    [ "$n" -ge 1 ] && fidelity_run narrow_passage "$n" "$(paced_blocks "$n")" fidelity_npp_ \
        --interleave run --apart
    n=$((FID_N / 2))
    [ "$n" -ge 1 ] && fidelity_run kitchen "$n" "$(paced_blocks "$n")" fidelity_kp_ \
        --interleave run --apart
else
    echo "== 4. timing fidelity: skipped (needs mpb-planner-ompl, mpb-bench-fidelity)"
fi

# ---- 5. store and reports at scale ------------------------------------------
echo "== 5. store: one transaction per run, as the daemon commits ($STORE_N runs)"
"$SNAP/mpb-bench-mkdb" --db "$WORK/store.db" --robot "$ROBOT" --scene "$SCENE" \
    --runs "$STORE_N" --configs 1 --queries 1 --stages 1 --waypoints 2 \
    --batch 1 >"$WORK/store.log" 2>&1
cat "$WORK/store.log"
sed 's/^RESULT mkdb /RESULT store_tx1 /' "$WORK/store.log" >"$WORK/store.res"
collect "$WORK/store.res"
rm -f "$WORK"/store.db*

echo "== 5. mpb report over $REPORT_N runs"
timeout -k 5 1800 "$SNAP/mpb-bench-mkdb" --db "$WORK/report.db" --robot "$ROBOT" \
    --scene "$SCENE" --runs "$REPORT_N" >"$WORK/mkdb.log" 2>&1
cat "$WORK/mkdb.log"; collect "$WORK/mkdb.log"
if [ -x "$SNAP/mpb" ]; then
    times=""
    for i in 1 2 3; do
        t0=$(now)
        timeout -k 5 300 "$SNAP/mpb" report "$WORK/report.db" >"$WORK/report.txt" 2>&1
        rc=$?
        times="$times $(calc "$(now) - $t0" 3)"
        [ "$rc" -eq 0 ] || { echo "mpb report failed ($rc):"; tail -5 "$WORK/report.txt"; }
    done
    med=$(echo "$times" | tr ' ' '\n' | grep . | sort -n | sed -n 2p)
    put "report runs=$(get mkdb runs) seconds=$med all=$(echo $times | tr ' ' ,) rc=$rc db_mb=$(du -m "$WORK/report.db" | cut -f1)"
    echo "  mpb report: $times s (median $med s)"
else
    put "report runs=$(get mkdb runs) seconds=nan rc=missing"
fi

# ---- 6. import into a Planner Arena database ----------------------------------
# Against OMPL's ompl_benchmark_statistics.py, which is not part of mpbench:
# fetched above (bench/ompl_peer.sh) or named by OMPL_STATS (bench/import.sh).
if [ -n "${OMPL_STATS:-}" ] && [ -f "$OMPL_STATS" ]; then
    echo "== 6. import: an OMPL log of $IMPORT_N runs into a Planner Arena database"
    MPB_BUILD=$BUILD timeout -k 5 1200 sh "$src/bench/import.sh" "$IMPORT_N" \
        >"$WORK/import.log" 2>&1
    grep -v '^RESULT ' "$WORK/import.log"; collect "$WORK/import.log"
else
    echo "== 6. import: skipped (no ompl_benchmark_statistics.py: bench/ompl_peer.sh failed and OMPL_STATS names none)"
fi

# ---- the table ----------------------------------------------------------------
LOAD_END=$(load)
TABLE=$(sh "$src/bench/table.sh" "$RAW")

# Whether the tree measured is the commit named: paths changed, not counting
# the results this run writes.
tree_state() {
    n=$(cd "$src" && GIT_OPTIONAL_LOCKS=0 git status --porcelain -- . ':!bench/results' 2>/dev/null | wc -l)
    case $n in 0) echo "no change in the work tree" ;; 1) echo "1 path changed in the work tree" ;;
    *) echo "$n paths changed in the work tree" ;; esac
}
describe() {
    cat <<EOF
- date: $STARTED
- machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'), $(awk '/MemTotal/ { printf "%.1f GiB", $2 / 1048576 }' /proc/meminfo) memory, kernel $(uname -r)
- load average (1, 5, 15 min): $LOAD_START at the start, $LOAD_END at the end
- commit: $(cd "$src" && git rev-parse --short HEAD 2>/dev/null) ($(tree_state))
- software: LCM $(pkg-config --modversion lcm 2>/dev/null), SQLite $(sqlite3 --version | cut -d' ' -f1), $(cc --version | head -1), build type $(bt=$(sed -n 's/^CMAKE_BUILD_TYPE:[A-Z]*=//p' "$BUILD/CMakeCache.txt"); echo "${bt:-RelWithDebInfo (the default)}")
- counts: floor $FLOOR_N exchanges, latency $LAT_N runs (after $LAT_SKIP warm-up) and $LAT_ROUNDS rounds of $LAT_ROUND_N in turns with floors of $LAT_ROUND_N, throughput $TPUT_N runs, report $REPORT_N runs$( [ "$QUICK" -eq 1 ] && echo " (--quick)")
EOF
}

echo
echo "== results"
describe
echo
echo "$TABLE"

mkdir -p "$src/bench/results"
out=$src/bench/results/$(date +%Y-%m-%d_%H%M).md
{
    echo "# mpbench benchmark, $STARTED"
    echo
    describe
    echo
    echo "$TABLE"
    echo
    echo "Raw results (bench/run.sh):"
    echo
    echo '```'
    cat "$RAW"
    echo '```'
} >"$out"
echo
echo "written to ${out#"$src"/}"
