#!/bin/sh
# bench/fidelity.sh - timing fidelity: does mpbench make a planner look
# slower or faster than it is? (docs/performance.md, 4b, 4c, 4e and 4h)
#
#   bench/fidelity.sh [--scene kitchen|narrow_passage] [--runs N]
#                     [--blocks K] [--pin CPU|none] [--queue Q] [--boot B]
#                     [--interleave block|run] [--apart] [--busy K] [--keep]
#
# RRTConnect on the first query of one of the paper's environments (the
# PR2's right arm; start and goal as in scenes/experiments/paper.yaml, the
# goal the configuration the suite's IK gave): the kitchen (default; about
# 2 ms a run) or the narrow passage (about 30 ms a run). N runs on each of
# three sides (default 5000), in K interleaved blocks (default 20) of N/K
# runs:
#   mpbench  through mpbenchd and mpb-planner-ompl, the "raw" stage's time;
#   ompl     OMPL 1.5's ompl::tools::Benchmark in process, its "time";
#   plain    a bare solve() in process, timed as mpb-planner-ompl times it.
# Block k runs mpbench, then ompl, then plain; the next block the other way
# round, so a drift of the machine lands on every side alike. Each block has
# seeds of its own (those mpbenchd draws for it), the same on the three
# sides; a seed is the same run on every side (mpb-bench-fidelity seeds as
# the planner process does: the graph each run made shows it). mpb-planner-ompl and mpbenchd start once
# (mpbenchd once per block: its start is not in the times compared), and
# mpb-bench-fidelity once per block, 5 warm-up runs first on each side (the
# first 5 of each mpbench block are dropped alike).
#
# The processes that plan (mpb-planner-ompl, mpb-bench-fidelity) run on one
# CPU (--pin, default the last; taskset), mpbenchd on the others; --pin none
# leaves placement to the scheduler. --queue sets the experiment's
# queue_at_planner (default 0, the daemon's: the planner waits for the
# daemon between runs; 1: its next request waits for it, 4d).
#
# --interleave run (4e): within each block, each run through mpbenchd is
# followed by the in-process runs of its seed (Benchmark and bare in turns)
# before the planner may start the next one: mpb-bench-fidelity pace holds
# the planner process (SIGSTOP) from its result until those are done and
# mpbenchd has stored the result. The sides' runs of a seed are then
# milliseconds apart, not seconds; the planner no longer idles between
# runs (the CPU runs the other sides meanwhile), so what the pause costs it
# on this VM (4b) is left out. Runs longer than 0.3 s are left out of every
# side (LONG: their in-process runs would hold the planner so long that
# mpbenchd takes it for gone). Not with --queue 1. With --pin none each
# side plans alone on a machine whose other CPU is idle, as a user runs
# Benchmark: its time-limit thread then wakes on the idle CPU (4g). Runs
# whose result the pacer saw only after mpbenchd had sent the next request
# (LATE: 6-8 % unpinned, none pinned) are left out of mpbench's side.
#
# --apart (4h) adds a fourth side, "apart": the bare solve() in a process
# of its own (mpb-bench-fidelity apart-worker) that waits on a pipe between
# runs, as the planner process waits for its next request: another process
# than the in-process sides, with its own copy of the world, but no LCM, no
# daemon and no planner kit. What mpbench reads over it is mpbench's own.
# Paced, it waits as the planner does; in blocks it plans its block's seeds
# back to back, with no pause between them.
#
# --busy K keeps the daemon's verifiers busy meanwhile, as other planners
# of a cluster would: before the first block, 20 RRTConnect runs of the
# query make a results database; three mpb-planner-load processes (on the
# daemon's CPUs) replay their paths, answering at once, in a second
# configuration of each block with K times the block's runs, every
# planner a run at once on the host (runs_per_host 4), so the daemon
# verifies paths without pause while RRTConnect plans (K about 200
# paced, 100 in blocks). Only RRTConnect's runs are
# compared; each block's line says how busy its verifiers were.
#
# If mpb-planner-ompl ends, the script stops at once (exit 1) rather than
# leave mpbenchd waiting for a planner until the block's timeout.
#
# Then `mpb-bench-fidelity stats`: the ratio of the pooled medians of the
# solved runs (mpbench / Benchmark, mpbench / bare, mpbench / the planner's
# solve() timed inside Benchmark, 4f; with --apart, mpbench / bare apart and
# bare apart / bare, 4h), bootstrap 95 %
# intervals of it (B resamples, default 2000), the median of the blocks' own
# ratios, success rates. The runs are pairs (a seed makes the same graph on
# every side), so the verdict takes the interval that resamples seeds with
# both sides' runs of a seed together: "met" when it lies inside 0.97-1.03,
# "missed" when outside, "not settled" otherwise. RESULT lines; every run is
# kept in WORK/runs.txt.
#
# Runs inside a private network namespace, as bench/run.sh (which calls it,
# --in-netns, with its copies of the binaries: --bin DIR --work DIR).
set -u

src=$(cd "$(dirname "$0")/.." && pwd)
. "$src/tools/usage.sh"
. "$src/bench/lib.sh"
BUILD=${MPB_BUILD:-$src/build}
case $BUILD in /*) ;; *) BUILD=$src/$BUILD ;; esac
RUNS=5000 BLOCKS=20 PIN="" BOOT=2000 KEEP=0 NETNS=0 BIN="" WORK="" SCENE=kitchen
QUEUE=0 INTERLEAVE=block SIDES=ompl,plain BUSY=0
KEYP=fidelity_
while [ $# -gt 0 ]; do
    case $1 in
    --key-prefix) KEYP=$2; shift ;;  # RESULT fidelity_* renamed, for bench/run.sh
    --scene) SCENE=$2; shift ;;
    --runs) RUNS=$2; shift ;;
    --blocks) BLOCKS=$2; shift ;;
    --pin) PIN=$2; shift ;;
    --queue) QUEUE=$2; shift ;;
    --interleave) INTERLEAVE=$2; shift ;;
    --apart) SIDES=apart,ompl,plain ;;
    --busy) BUSY=$2; shift ;;
    --boot) BOOT=$2; shift ;;
    --keep) KEEP=1 ;;
    --in-netns) NETNS=1 ;;          # a namespace bench/run.sh set up
    --new-netns) NETNS=2 ;;         # this script's own, to set up
    --bin) BIN=$2; shift ;;
    --work) WORK=$2; shift ;;
    -h|--help) mpb_usage; exit 0 ;;
    *) echo "bench/fidelity.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
    esac
    shift
done
case $SCENE in kitchen|narrow_passage) ;; *)
    echo "bench/fidelity.sh: --scene kitchen or narrow_passage, not '$SCENE'" >&2; exit 2 ;;
esac
case $INTERLEAVE in block|run) ;; *)
    echo "bench/fidelity.sh: --interleave block or run, not '$INTERLEAVE'" >&2; exit 2 ;;
esac
case $RUNS$BLOCKS$BOOT$QUEUE$BUSY in *[!0-9]*)
    echo "bench/fidelity.sh: --runs, --blocks, --queue, --busy and --boot want whole numbers" >&2; exit 2 ;;
esac
[ "$BLOCKS" -ge 1 ] && [ "$RUNS" -ge "$BLOCKS" ] || {
    echo "bench/fidelity.sh: wants 1 <= blocks <= runs" >&2; exit 2; }
NCPU=$(nproc)
: "${PIN:=$((NCPU - 1))}"
# Paced runs hold the planner between runs: one request at a time.
if [ "$INTERLEAVE" = run ] && [ "$QUEUE" != 0 ]; then
    echo "bench/fidelity.sh: --interleave run wants --queue 0" >&2; exit 2
fi
if [ "$PIN" != none ]; then
    case $PIN in *[!0-9]*|"") echo "bench/fidelity.sh: --pin CPU or none" >&2; exit 2 ;; esac
    [ "$PIN" -lt "$NCPU" ] || { echo "bench/fidelity.sh: no CPU $PIN" >&2; exit 2; }
fi

# ---- outside the namespace: snapshot the binaries, re-enter ---------------
if [ "$NETNS" -eq 0 ]; then
    : "${WORK:=$BUILD/bench-run/fidelity}"
    bench_snapshot bench/fidelity.sh "$WORK" "$BUILD/daemon/mpbenchd" \
        "$BUILD/planners/ompl/mpb-planner-ompl" "$BUILD/planners/load/mpb-planner-load" \
        "$(bench_program "$BUILD" mpb-bench-fidelity)"
    set -- --new-netns --bin "$WORK/bin" --work "$WORK" --runs "$RUNS" \
        --blocks "$BLOCKS" --pin "$PIN" --boot "$BOOT" --scene "$SCENE" --key-prefix "$KEYP" \
        --queue "$QUEUE" --interleave "$INTERLEAVE" --busy "$BUSY"
    [ "$SIDES" = ompl,plain ] || set -- "$@" --apart
    [ "$KEEP" -eq 1 ] && set -- "$@" --keep
    exec unshare -n sh "$0" "$@"
fi

# ---- inside the private network namespace -----------------------------------
if [ "$NETNS" -eq 2 ]; then bench_netns bench/fidelity.sh; else bench_netns_check bench/fidelity.sh; fi
[ -n "$BIN" ] && [ -n "$WORK" ] || { echo "bench/fidelity.sh: --bin and --work" >&2; exit 2; }
mkdir -p "$WORK" || exit 1
trap 'cleanup; [ "$KEEP" -eq 1 ] || rm -f "$WORK"/fid-*.db*' EXIT
trap 'exit 130' INT TERM

JOINTS=r_shoulder_pan_joint,r_shoulder_lift_joint,r_upper_arm_roll_joint,r_elbow_flex_joint,r_forearm_roll_joint,r_wrist_flex_joint,r_wrist_roll_joint
URDF=$src/scenes/robots/pr2_right_arm.urdf
SCENE_FILE=$src/scenes/paper/$SCENE.scene
START=-1.2,1.1,-1.5,-1.9,0,-0.6,0
# The environment's first query: its goal is the start of the second query
# in scenes/experiments/paper.yaml.
case $SCENE in
kitchen)
    QUERY=counter_cup
    GOAL=-0.261284,-0.420386,-1.523717,-1.031201,-1.236424,-1.761224,-2.299770 ;;
narrow_passage)
    QUERY=through_window
    GOAL=-0.602636,-0.372772,-1.662616,-1.158252,-2.607525,-0.583438,-1.715240 ;;
esac
TIME_LIMIT=10 WARMUP=5
LOADS=3         # --busy: one load planner's request, result and ack in
                # turn leave the verifiers idle half the time
PER=$((RUNS / BLOCKS))

if [ "$PIN" = none ]; then
    ON_PIN="" ON_REST=""
else
    rest=$(awk -v n="$NCPU" -v p="$PIN" 'BEGIN { for (c = 0; c < n; c++) if (c != p)
        s = s (s == "" ? "" : ",") c; print s }')
    ON_PIN="taskset -c $PIN"
    ON_REST=${rest:+taskset -c $rest}
fi

list() { echo "[$1]" | sed 's/,/, /g'; }
block_yaml() { # block file [runs]: RUNS, without --busy's planner
    cat >"$2" <<EOF
experiment:
  name: bench-fidelity-$1
  runs: ${3:-$((PER + WARMUP))}
  time_limit: $TIME_LIMIT
  seed: $((7000 + $1))
  queue_at_planner: $QUEUE
  runs_per_host: $([ "$BUSY" -gt 0 ] && [ -z "${3:-}" ] && echo $((LOADS + 1)) || echo 1)
robot:
  format: urdf
  file: $URDF
  joints: $(list "$JOINTS")
scenes:
  - name: $SCENE
    format: moveit-scene
    file: $SCENE_FILE
    queries:
      - name: $QUERY
        start: $(list "$START")
        goal: $(list "$GOAL")
        tolerance: 0.01
planners:
  - planner: ompl
    algorithms: [RRTConnect]
    params: {simplify: 0}
EOF
    [ "$BUSY" -eq 0 ] || [ -n "${3:-}" ] || cat >>"$2" <<EOF
  - planner: load
    algorithms: [replay]
    runs: $((BUSY * (PER + WARMUP)))
EOF
}

RUNS_TXT=$WORK/runs.txt
: >"$RUNS_TXT"
LOAD_START=$(cut -d' ' -f1-3 /proc/loadavg)

# mpb-planner-ompl, once for all blocks, on the planning CPU.
$ON_PIN "$BIN/mpb-planner-ompl" >"$WORK/planner.log" 2>&1 &
PLANNER=$!      # taskset execs the planner: its pid
PIDS="$PIDS $PLANNER"
sleep 0.5   # one announce before the first daemon

# --busy: the paths mpb-planner-load replays, from 20 runs of the query.
if [ "$BUSY" -gt 0 ]; then
    block_yaml paths "$WORK/fid-paths.yaml" 20
    rm -f "$WORK/fid-paths.db"*
    timeout -k 5 300 $ON_REST "$BIN/mpbenchd" -d "$WORK/fid-paths.db" "$WORK/fid-paths.yaml" \
        >"$WORK/daemon-paths.log" 2>&1 ||
        { echo "bench/fidelity.sh: the paths for --busy failed (see $WORK/daemon-paths.log)" >&2; exit 1; }
    for i in $(seq "$LOADS"); do
        $ON_REST "$BIN/mpb-planner-load" --from "$WORK/fid-paths.db" >"$WORK/load-$i.log" 2>&1 &
        PIDS="$PIDS $!"
    done
    sleep 0.5
fi

# A block's seeds: those mpbenchd draws for its experiment, known before
# it runs (mpb-bench-fidelity seeds); the first WARMUP are warm-up runs.
block_seeds() { # block
    "$BIN/mpb-bench-fidelity" seeds $((7000 + $1)) $((PER + WARMUP))
}

mpbench_block() { # block
    db=$WORK/fid-$1.db
    rm -f "$db"*
    block_yaml "$1" "$WORK/fid-$1.yaml"
    timeout -k 5 $(((PER + WARMUP) * (TIME_LIMIT + 2) + 60)) $ON_REST "$BIN/mpbenchd" \
        -d "$db" "$WORK/fid-$1.yaml" >"$WORK/daemon-$1.log" 2>&1 &
    daemon=$!
    # Without its planner mpbenchd would wait for one until the timeout.
    (while kill -0 "$PLANNER" 2>/dev/null; do sleep 1; done; kill "$daemon" 2>/dev/null) &
    watcher=$!
    wait "$daemon" || echo "mpbenchd failed: see $WORK/daemon-$1.log"
    kill "$watcher" 2>/dev/null
    kill -0 "$PLANNER" 2>/dev/null || {
        echo "bench/fidelity.sh: mpb-planner-ompl ended during block $1 (see $WORK/planner.log)" >&2
        [ -n "${pacer:-}" ] && kill "$pacer" 2>/dev/null
        exit 1
    }
    # The recorded runs, as mpb-bench-fidelity prints its own: seed, the
    # raw stage's time, solved (exactly), verified (mpbench's success), the
    # planner's graph.
    sqlite3 -separator ' ' "$db" "SELECT 'RUN', 'mpbench', $1, r.seed,
        coalesce(s.time, 'nan'), r.status = 'solved', coalesce(r.success, 0),
        coalesce((SELECT CAST(v.value AS INTEGER) FROM planner_values v
                  WHERE v.run_id = r.id AND v.name = 'graph states'), -1)
        FROM runs r JOIN planner_configs c ON c.id = r.planner_config_id
        LEFT JOIN stages s ON s.run_id = r.id AND s.name = 'raw'
        WHERE r.state = 'done' AND r.repetition >= $WARMUP AND c.planner = 'ompl'
        ORDER BY r.repetition" >>"$RUNS_TXT"
    drawn=$(sqlite3 "$db" "SELECT group_concat(seed) FROM (SELECT r.seed FROM runs r
        JOIN planner_configs c ON c.id = r.planner_config_id WHERE c.planner = 'ompl'
        ORDER BY r.repetition)")
    # --busy: the replayed paths verified while RRTConnect planned, and
    # the verifiers' time over the span of RRTConnect's runs.
    [ "$BUSY" -eq 0 ] || sqlite3 "$db" "SELECT '  block $1: verifiers busy ' ||
        printf('%.0f', 100.0 * sum(CASE WHEN r.finished <= e.last THEN r.verify_time END)
            / (e.last - e.first)) || ' % of RRTConnect''s span, ' ||
        sum(r.finished <= e.last) || ' replayed paths verified in it'
        FROM runs r JOIN planner_configs c ON c.id = r.planner_config_id,
             (SELECT min(r2.finished) AS first, max(r2.finished) AS last
              FROM runs r2 JOIN planner_configs c2 ON c2.id = r2.planner_config_id
              WHERE c2.planner = 'ompl') e
        WHERE c.planner = 'load' AND r.finished >= e.first"
    [ "$drawn" = "$(block_seeds "$1")" ] ||
        echo "  block $1: mpbenchd drew other seeds than mpb-bench-fidelity seeds gave"
    [ "$KEEP" -eq 1 ] || rm -f "$db"*
}

inprocess_block() { # block sides
    timeout -k 5 $((2 * (PER + WARMUP) * (TIME_LIMIT + 2) + 60)) $ON_PIN \
        "$BIN/mpb-bench-fidelity" run --robot "$URDF" --scene "$SCENE_FILE" \
        --joints "$JOINTS" --start "$START" --goal "$GOAL" --time-limit "$TIME_LIMIT" \
        --block "$1" --sides "$2" --warmup "$WARMUP" \
        --seeds "$(block_seeds "$1" | cut -d, -f$((WARMUP + 1))-)" \
        >>"$RUNS_TXT" 2>"$WORK/inprocess-$1.log" ||
        echo "mpb-bench-fidelity failed: see $WORK/inprocess-$1.log"
}

# A block run by run: mpb-bench-fidelity pace ready on the planning CPU
# before mpbenchd starts, then the block through mpbenchd, each run
# followed by its seed's in-process runs. Runs the planner may have
# started before it was held (LATE) are left out of mpbench's side; runs
# over 0.3 s (LONG) have no in-process runs and are left out of it too.
paced_block() { # block
    out=$WORK/pace-$1.txt log=$WORK/pace-$1.log
    : >"$log"
    timeout -k 5 $((3 * (PER + WARMUP) * (TIME_LIMIT + 2) + 120)) $ON_PIN \
        "$BIN/mpb-bench-fidelity" pace --planner-pid "$PLANNER" --runs $((PER + WARMUP)) \
        --robot "$URDF" --scene "$SCENE_FILE" --joints "$JOINTS" --start "$START" \
        --goal "$GOAL" --time-limit "$TIME_LIMIT" --block "$1" --warmup "$WARMUP" \
        --sides "$SIDES" >"$out" 2>"$log" &
    pacer=$!
    i=0
    until grep -q listening "$log" || [ $i -ge 600 ]; do sleep 0.1; i=$((i + 1)); done
    mpbench_block "$1"
    wait "$pacer" || echo "mpb-bench-fidelity pace failed: see $log"
    kill -CONT "$PLANNER" 2>/dev/null    # never held into the next block
    grep -q '^LATE ' "$out" && echo "  block $1: $(grep -c '^LATE ' "$out") runs not paced (LATE), left out"
    grep -q '^LONG ' "$out" && echo "  block $1: $(grep -c '^LONG ' "$out") runs over 0.3 s (LONG), left out of every side"
    awk 'NR == FNR { if ($1 == "LATE" || $1 == "LONG") out[$2 " " $3] = 1; next }
        !($2 == "mpbench" && ($3 " " $4) in out)' "$out" "$RUNS_TXT" >"$WORK/runs.new"
    grep '^RUN ' "$out" >>"$WORK/runs.new"
    mv "$WORK/runs.new" "$RUNS_TXT"
    grep '^RESULT fidelity_pace ' "$out" >>"$WORK/pace.txt"
}

# The median of a block's solved runs of one side, in ms (for the log).
block_median() { # side block
    awk -v s="$1" -v b="$2" '$2 == s && $3 == b && $6 == 1 { print $5 }' "$RUNS_TXT" |
        sort -g | awk '{ v[NR] = $1 } END { if (NR == 0) print "nan"; else
            printf "%.3f", (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) * 1e3 }'
}

case $SIDES in *apart*) apart=", bare solve() apart" ;; *) apart="" ;; esac
echo "== timing fidelity: RRTConnect, PR2 $SCENE ($QUERY), $BLOCKS blocks of $PER runs on each side" \
     "(mpbench, OMPL's Benchmark, bare solve()$apart), planning on" \
     "$([ "$PIN" = none ] && echo "any CPU (no pinning)" || echo "CPU $PIN")" \
     "$([ "$INTERLEAVE" = run ] && echo "(paced: run by run)")"
: >"$WORK/pace.txt"
k=1
while [ "$k" -le "$BLOCKS" ]; do
    if [ "$INTERLEAVE" = run ]; then
        paced_block "$k"
    elif [ $((k % 2)) -eq 1 ]; then
        mpbench_block "$k"
        inprocess_block "$k" "$SIDES"
    else
        inprocess_block "$k" "$(echo "$SIDES" | tr , '\n' | sed -n '1!G;h;$p' | paste -sd,)"
        mpbench_block "$k"
    fi
    apart=""
    case $SIDES in *apart*) apart=", apart $(block_median apart "$k")" ;; esac
    echo "  block $k: median mpbench $(block_median mpbench "$k"), Benchmark" \
         "$(block_median ompl "$k"), bare $(block_median plain "$k")$apart ms"
    k=$((k + 1))
done
cleanup
LOAD_END=$(cut -d' ' -f1-3 /proc/loadavg)

{
echo "RESULT fidelity_setup scene=$SCENE query=$QUERY blocks=$BLOCKS block_runs=$PER warmup=$WARMUP pin=$PIN" \
     "interleave=$INTERLEAVE busy=$BUSY" \
     "load_start=$(echo "$LOAD_START" | tr ' ' /) load_end=$(echo "$LOAD_END" | tr ' ' /)"
[ "$INTERLEAVE" = run ] && awk '{ for (i = 3; i <= NF; i++) { split($i, kv, "=")
        v[kv[1]] = kv[2] }
    paced += v["paced"]; late += v["late"]; long += v["long"]
    if (v["max_hold_ms"] > hold) hold = v["max_hold_ms"] }
    END { printf "RESULT fidelity_paced blocks=%d paced=%d late=%d long=%d max_hold_ms=%.1f\n",
          NR, paced, late, long, hold }' "$WORK/pace.txt"
"$BIN/mpb-bench-fidelity" stats --boot "$BOOT" "$RUNS_TXT"
} | sed "s/^RESULT fidelity_/RESULT $KEYP/"
