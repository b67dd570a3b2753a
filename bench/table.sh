#!/bin/sh
# bench/table.sh - the table of a benchmark run, from its RESULT lines
#
#   bench/table.sh FILE
#
# FILE holds the RESULT lines of a run of bench/run.sh: its raw results,
# or a results file it wrote (bench/results/*.md, which ends with them).
# Prints the markdown table that bench/run.sh prints and writes, and that
# docs/performance.md keeps: each measurement, per floor, the target and
# whether it was met. A field that is missing reads "nan", a verdict
# without a number "not measured", so an older file or a partial run
# still gives its table.
set -u
src=$(cd "$(dirname "$0")/.." && pwd)
. "$src/tools/usage.sh"

case ${1:-} in
-h|--help) mpb_usage; exit 0 ;;
"") echo "usage: bench/table.sh FILE (bench/table.sh --help)" >&2; exit 2 ;;
-*) echo "bench/table.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
esac
[ -r "$1" ] || { echo "bench/table.sh: cannot read $1" >&2; exit 1; }
. "$src/bench/lib.sh"
RAW=$1
FLOOR=$(get floor median_us)
PR2_WHERE=$(get verify_pr2_setup scene)
[ "$PR2_WHERE" = nan ] && PR2_WHERE=kitchen

ratio() { calc "$1 / $FLOOR" 1; }
verdict() { # value [op target]
    awk -v v="$1" -v t="${3:-}" -v op="${2:-}" 'BEGIN {
        if (v == "nan" || v != v + 0) { print "not measured"; exit }
        ok = (op == "<=") ? v <= t : v >= t; print ok ? "met" : "**missed**" }'
}
# Flat: less than 1 MB more at the end than half way through. SQLite's
# page cache fills over the first tens of thousands of runs: fewer runs
# cannot tell.
flat() { # growth_kb runs
    awk -v g="$1" -v n="$2" 'BEGIN {
        if (g == "nan" || n == "nan" || g != g + 0) { print "not measured"; exit }
        if (n < 100000) { printf "too few runs to tell (%+d kB)", g; exit }
        printf "%s (%+d kB over the second half, %.2f B per run)",
               g <= 1024 ? "flat" : "**grows**", g, g * 1024 / (n * 0.5) }'
}
lat=$(get run_latency_own median_us) lat99=$(get run_latency_own p99_us)
# The verdict on the latency: against floors measured in turns with it
# (bench/latency.sh) where the run has them, else against the floor of
# item 1, measured a minute before.
if [ "$(get latency_paired ratio_median)" = nan ]; then
    lat_status=$(verdict "$(calc "$lat / $FLOOR" 3)" "<=" 3)
else
    lat_status="(the verdict is the next row's)"
fi
wlat=$(get run_latency median_us) wlat99=$(get run_latency p99_us)
cyc=$(get run_cycle median_us) cyc99=$(get run_cycle p99_us)
# A field of the throughput runs with 1, 2, 3, 4 and 8 planners, joined
# by " / ", each through fn (a function, or nothing) and followed by unit.
each() { # prefix field unit [fn]
    out=""
    for np in 1 2 3 4 8; do
        v=$(get "$1$np" "$2"); [ -n "${4:-}" ] && v=$($4 "$v")
        out="${out:+$out / }$v"
    done
    echo "$out$3"
}
# How much of one CPU mpbenchd (all its threads) used in a throughput run:
# well below 100 %, the planners did not keep it busy.
busy() { # key
    calc "$(get "$1" daemon_cpu_us_per_run) * $(get "$1" runs_per_s) / 1e4" 0 | sed 's/$/ %/'
}
rss_row() { # key: RSS at 10 % / 50 % / end / max of a throughput run
    echo "$(get "$1" rss_early_kb) / $(get "$1" rss_half_kb) / $(get "$1" rss_end_kb) / $(get "$1" rss_max_kb) kB"
}
rep=$(get report seconds)
vw=$(get verify_0.01 wps) vs=$(get verify_0.1 wps)
pw=$(get verify_pr2_0.01 wps) ps=$(get verify_pr2_0.1 wps)
# A fidelity comparison: medians, ratio, its intervals; and its verdict.
fidelity() { # key
    echo "$(calc "$(get "$1" median_a_s) * 1000" 3) / $(calc "$(get "$1" median_b_s) * 1000" 3) ms: \
ratio $(get "$1" ratio), 95 % CI $(get "$1" paired_lo)-$(get "$1" paired_hi) (seeds resampled, \
both sides' runs of a seed together; each side's runs resampled alone: \
$(get "$1" ci_lo)-$(get "$1" ci_hi); whole blocks: $(get "$1" blockboot_lo)-$(get "$1" blockboot_hi)); \
the blocks' own ratios: median $(get "$1" block_ratio_median), \
$(get "$1" block_ratio_min)-$(get "$1" block_ratio_max); the same seed's run on both sides: \
time ratio median $(get "$1" seed_ratio_median), the same graph $(get "$1" seeds_same_graph) \
of $(get "$1" seeds_paired)"
}
fid_verdict() { # key
    case $(get "$1" verdict) in
    met) echo met ;; missed) echo "**missed**" ;; not_settled) echo "not settled" ;;
    *) echo "not measured" ;;
    esac
}
st=$(get store_tx1 finish_us_per_run)

table() {
cat <<EOF
| # | measurement | result | per floor | target | status |
|---|---|---|---|---|---|
| 1 | LCM round trip, plan request $(get floor request_bytes) B out, result $(get floor result_bytes) B back: median / p99 | $(calc "$FLOOR") / $(calc "$(get floor p99_us)") us | 1 | the floor | (again at the end: $(calc "$(get floor_again median_us)") us) |
| 2 | per-run latency, request first sent to result verified, measured, stored and committed, 1 null planner, nothing else listening (mpbenchd's own count, $(get run_latency_own n) runs): median / p99 | $(calc "$lat") / $(calc "$lat99") us | $(ratio "$lat") / $(ratio "$lat99") | median <= 3x floor | $lat_status |
| 2 | ... the same in turns with the floor (bench/latency.sh): $(get latency_paired rounds) rounds, each a floor of $(get latency_paired exchanges) round trips and $(get latency_paired runs) runs, seconds apart; each round's latency median over its floor median | $(calc "$(get latency_paired latency_median_us)") us over $(calc "$(get latency_paired floor_median_us)") us (medians of the rounds) | $(get latency_paired ratio_median) (rounds $(get latency_paired ratio_min)-$(get latency_paired ratio_max)) | median <= 3x floor | $(verdict "$(get latency_paired ratio_median)" "<=" 3) |
| 2' | ... with mpb-bench-watch listening: request to the acknowledgement the planner receives | $(calc "$wlat") / $(calc "$wlat99") us | $(ratio "$wlat") / $(ratio "$wlat99") | | |
| 2a | ... of which request to result published (network out, planner, network back) | $(calc "$(get run_out_back median_us)") / $(calc "$(get run_out_back p99_us)") us | $(ratio "$(get run_out_back median_us)") | | |
| 2b | ... of which result published to acknowledged (network in, verify, metrics, store, commit, the acknowledgement) | $(calc "$(get run_daemon median_us)") / $(calc "$(get run_daemon p99_us)") us | $(ratio "$(get run_daemon median_us)") | | |
| 2c | a run as the planner sees it: request to its next request, 1 null planner | $(calc "$cyc") / $(calc "$cyc99") us | $(ratio "$cyc") / $(ratio "$cyc99") | | |
$(for np in 1 2 3 4; do k=tput$np; t=$(get $k runs_per_s)
  echo "| 3 | throughput, $(planners_n $np), $(get $k runs) runs (each planner waits for its own round trip, so few planners leave mpbenchd idle) | $t runs/s | $(calc "1e6 / $t / $FLOOR" 1) floors per run | | mpbenchd used $(busy $k) of a CPU |"
done)
| 3 | throughput, what mpbenchd sustains: 8 null planners, $(get tput8 runs) runs | $(get tput8 runs_per_s) runs/s | $(calc "1e6 / $(get tput8 runs_per_s) / $FLOOR" 1) floors per run | >= 10,000 runs/s | $(verdict "$(get tput8 runs_per_s)" ">=" 10000) (mpbenchd used $(busy tput8) of a CPU) |
| 3 | throughput, 1 / 3 / 8 null planners with a request waiting at each (\`queue_at_planner: 1\`, 4d), $(get tput1q runs) / $(get tput3q runs) / $(get tput8q runs) runs | $(get tput1q runs_per_s) / $(get tput3q runs_per_s) / $(get tput8q runs_per_s) runs/s | $(calc "1e6 / $(get tput1q runs_per_s) / $FLOOR" 1) / $(calc "1e6 / $(get tput3q runs_per_s) / $FLOOR" 1) / $(calc "1e6 / $(get tput8q runs_per_s) / $FLOOR" 1) floors per run | >= 10,000 runs/s | $(verdict "$(get tput8q runs_per_s)" ">=" 10000) (8 planners) |
| 3 | mpbenchd CPU time (user + system) per run, 1 / 2 / 3 / 4 / 8 planners | $(each tput daemon_cpu_us_per_run " us") | $(each tput daemon_cpu_us_per_run "" ratio) | | |
| 3 | null planners' CPU time per run (all of them, planner kit included), 1 / 2 / 3 / 4 / 8 planners | $(each tput planners_cpu_us_per_run " us") | $(each tput planners_cpu_us_per_run "" ratio) | | |
| 3 | mpbenchd RSS over $(get tput1 runs) runs (1 planner): at 10 % / 50 % / end / max | $(rss_row tput1) | | flat | $(flat "$(get tput1 rss_growth_kb)" "$(get tput1 runs)") |
| 3 | mpbenchd RSS over $(get tput8 runs) runs (8 planners): at 10 % / 50 % / end / max | $(rss_row tput8) | | flat | $(flat "$(get tput8 rss_growth_kb)" "$(get tput8 runs)") |
| 3 | ... the same with a request waiting at each planner, $(get tput8q runs) runs | $(rss_row tput8q) | | flat | $(flat "$(get tput8q rss_growth_kb)" "$(get tput8q runs)") |
| 4 | verification + metrics, PR2 right arm in the $PR2_WHERE, waypoints at the resolution ($(get verify_pr2_0.01 checks_per_waypoint) checks each) | $pw waypoints/s | | >= 50,000 | $(verdict "$pw" ">=" 50000)$( [ "$PR2_WHERE" = kitchen ] || echo " (not the kitchen)") |
| 4 | verification + metrics, PR2 right arm in the $PR2_WHERE, waypoints 0.1 rad apart ($(get verify_pr2_0.1 checks_per_waypoint) checks each) | $ps waypoints/s | | >= 50,000 | $(verdict "$ps" ">=" 50000) |
| 4m | a state check of a robot with meshes: the Panda, its SRDF and collision meshes, in MotionBenchMaker's $(get meshspeed_setup set) scene $(get meshspeed_setup scene), against the primitive PR2 right arm in the kitchen; $(get meshcheck_setup states) random states each ($(get meshcheck_setup colliding) / $(get meshcheck_setup ref_colliding) in collision), $(get meshcheck_setup rounds) interleaved rounds, thread CPU time: collision | $(calc "$(get meshcheck_in_collision us)" 2) / $(calc "$(get meshcheck_in_collision ref_us)" 2) us: $(get meshcheck_in_collision ratio)x (rounds $(get meshcheck_in_collision ratio_min)-$(get meshcheck_in_collision ratio_max)) | | <= 3x | $(verdict "$(get meshcheck_in_collision ratio)" "<=" 3) |
| 4m | ... contact (the same with the pair named) / clearance (minimum distance to the scene) | $(calc "$(get meshcheck_contact us)" 2) / $(calc "$(get meshcheck_contact ref_us)" 2) us: $(get meshcheck_contact ratio)x; $(calc "$(get meshcheck_clearance us)" 1) / $(calc "$(get meshcheck_clearance ref_us)" 2) us: $(get meshcheck_clearance ratio)x | | | |
| 4m | verification + metrics, Panda (meshes) in the same scene, waypoints at the resolution ($(get verify_panda_0.01 checks_per_waypoint) checks each) / 0.1 rad apart ($(get verify_panda_0.1 checks_per_waypoint) checks each); verification alone | $(get verify_panda_0.01 wps) / $(get verify_panda_0.1 wps) waypoints/s; $(get verify_panda_0.01 verify_wps) / $(get verify_panda_0.1 verify_wps) | | | |
| 4 | verification + metrics, planar arm, waypoints at the resolution ($(get verify_0.01 checks_per_waypoint) checks each) | $vw waypoints/s | | | |
| 4 | verification + metrics, planar arm, waypoints 0.1 rad apart ($(get verify_0.1 checks_per_waypoint) checks each) | $vs waypoints/s | | | |
| 4 | timing fidelity, RRTConnect, PR2 in the paper's narrow passage (its first query), $(get fidelity_np_setup blocks) interleaved blocks of $(get fidelity_np_setup block_runs) runs on each side, the same seeds, planning on CPU $(get fidelity_np_setup pin): median solve time through mpbench / in OMPL's Benchmark (solved runs) | $(fidelity fidelity_np_ompl) | | within 3 % (95 % CI inside 0.97-1.03) | $(fid_verdict fidelity_np_ompl) |
| 4 | ... the same against a bare solve() in process (no Benchmark threads; timed as mpb-planner-ompl times it) | $(fidelity fidelity_np_plain) | | within 3 % | $(fid_verdict fidelity_np_plain) |
| 4 | ... runs solved: through mpbench (verified valid) / in OMPL's Benchmark / bare solve() | $(get fidelity_np_side_mpbench solved) ($(get fidelity_np_side_mpbench verified)) / $(get fidelity_np_side_ompl solved) / $(get fidelity_np_side_plain solved) of $(get fidelity_np_side_mpbench runs) | | same within noise | $(get fidelity_np_ompl success) |
| 4 | timing fidelity, the same in the paper's kitchen (its first query: a run is 1-4 ms, so Benchmark's fixed cost per run weighs more), $(get fidelity_setup blocks) blocks of $(get fidelity_setup block_runs) runs: through mpbench / in OMPL's Benchmark | $(fidelity fidelity_ompl) | | within 3 % | $(fid_verdict fidelity_ompl) |
| 4 | ... the same against a bare solve() in process | $(fidelity fidelity_plain) | | within 3 % | $(fid_verdict fidelity_plain) |
| 4 | ... runs solved: through mpbench (verified valid) / in OMPL's Benchmark / bare solve() | $(get fidelity_side_mpbench solved) ($(get fidelity_side_mpbench verified)) / $(get fidelity_side_ompl solved) / $(get fidelity_side_plain solved) of $(get fidelity_side_mpbench runs) | | same within noise | $(get fidelity_ompl success) |
| 4 | timing fidelity run by run (4e): each run through mpbench followed by its seed's runs in OMPL's Benchmark and as a bare solve(), in process and apart, the planner held meanwhile; the narrow passage, $(get fidelity_npp_setup blocks) blocks of $(get fidelity_npp_setup block_runs) runs ($(get fidelity_npp_paced long) over 0.3 s left out of every side; the in-process sides in turns: apart, Benchmark, bare, then the other way round): through mpbench / in OMPL's Benchmark | $(fidelity fidelity_npp_ompl) | | within 3 % | $(fid_verdict fidelity_npp_ompl) |
| 4 | ... against a bare solve() | $(fidelity fidelity_npp_plain) | | within 3 % | $(fid_verdict fidelity_npp_plain) |
| 4 | ... against a bare solve() apart: in a process of its own that waits between runs, as the planner process does, with no LCM, no daemon, no planner kit (4h: what mpbench itself adds) | $(fidelity fidelity_npp_apart) | | within 3 % | $(fid_verdict fidelity_npp_apart) |
| 4 | ... a bare solve() apart against a bare solve() in process (what a planner in a process of its own costs on this machine) | $(fidelity fidelity_npp_apart_plain) | | | |
| 4 | ... OMPL's Benchmark against a bare solve() | $(fidelity fidelity_npp_bench_plain) | | | |
| 4 | ... through mpbench / the planner's solve() timed inside OMPL's Benchmark (Benchmark's "time" less the start and join of its time-limit thread around it, 4f) | $(fidelity fidelity_npp_ompl_solve) | | within 3 % | $(fid_verdict fidelity_npp_ompl_solve) |
| 4 | ... OMPL's Benchmark against the solve() inside it (what its stopwatch adds) / that solve() against a bare solve() (its time-limit thread waking on the planning CPU) | ratio $(get fidelity_npp_bench_solve ratio) ($(get fidelity_npp_bench_solve paired_lo)-$(get fidelity_npp_bench_solve paired_hi)), per seed $(get fidelity_npp_bench_solve seed_ratio_median) / ratio $(get fidelity_npp_solve_plain ratio) ($(get fidelity_npp_solve_plain paired_lo)-$(get fidelity_npp_solve_plain paired_hi)), per seed $(get fidelity_npp_solve_plain seed_ratio_median) | | | |
| 4 | ... the same in the kitchen, $(get fidelity_kp_setup blocks) blocks of $(get fidelity_kp_setup block_runs) runs: through mpbench / in OMPL's Benchmark | $(fidelity fidelity_kp_ompl) | | within 3 % | $(fid_verdict fidelity_kp_ompl) |
| 4 | ... against a bare solve() | $(fidelity fidelity_kp_plain) | | within 3 % | $(fid_verdict fidelity_kp_plain) |
| 4 | ... against a bare solve() apart (4h) | $(fidelity fidelity_kp_apart) | | within 3 % | $(fid_verdict fidelity_kp_apart) |
| 4 | ... a bare solve() apart against a bare solve() in process | $(fidelity fidelity_kp_apart_plain) | | | |
| 4 | ... OMPL's Benchmark against a bare solve() | $(fidelity fidelity_kp_bench_plain) | | | |
| 4 | ... through mpbench / the planner's solve() timed inside OMPL's Benchmark | $(fidelity fidelity_kp_ompl_solve) | | within 3 % | $(fid_verdict fidelity_kp_ompl_solve) |
| 4 | ... OMPL's Benchmark against the solve() inside it / that solve() against a bare solve() | ratio $(get fidelity_kp_bench_solve ratio) ($(get fidelity_kp_bench_solve paired_lo)-$(get fidelity_kp_bench_solve paired_hi)), per seed $(get fidelity_kp_bench_solve seed_ratio_median) / ratio $(get fidelity_kp_solve_plain ratio) ($(get fidelity_kp_solve_plain paired_lo)-$(get fidelity_kp_solve_plain paired_hi)), per seed $(get fidelity_kp_solve_plain seed_ratio_median) | | | |
| 4 | ... runs solved, the narrow passage / the kitchen: through mpbench (verified valid) / in OMPL's Benchmark / bare solve() | $(get fidelity_npp_side_mpbench solved) ($(get fidelity_npp_side_mpbench verified)) / $(get fidelity_npp_side_ompl solved) / $(get fidelity_npp_side_plain solved) of $(get fidelity_npp_side_mpbench runs); $(get fidelity_kp_side_mpbench solved) ($(get fidelity_kp_side_mpbench verified)) / $(get fidelity_kp_side_ompl solved) / $(get fidelity_kp_side_plain solved) of $(get fidelity_kp_side_mpbench runs) | | same within noise | $(get fidelity_npp_ompl success); $(get fidelity_kp_ompl success) |
| 5 | store, one transaction per run as mpbenchd commits (no network) | $(calc "$st") us per run | $(ratio "$st") | | |
| 5 | store, $(get mkdb batch) runs per transaction, 15 metric rows per run | $(calc "$(get mkdb finish_us_per_run)") us per run | | | |
| 5 | \`mpb report\` over $(get report runs) runs ($(get report db_mb | sed 's/^nan$/?/') MB database) | $rep s | | < 2 s | $(verdict "$rep" "<=" 2) |
| 6 | import: an OMPL log of $(get import runs) runs (written by OMPL's Benchmark) into a Planner Arena database, \`mpb import -p\` / OMPL's \`ompl_benchmark_statistics.py\` (bench/import.sh; the script of Debian's source package of OMPL, bench/ompl_peer.sh) | $(calc "$(get import direct_s)" 3) / $(calc "$(get import ompl_s)" 3) s: $(get import paired_ratio)x faster (median of the pairs' ratios); the same rows: $(get import same_rows) | | >= 4x faster, the same rows | $( [ "$(get import same_rows)" = yes ] && verdict "$(get import paired_ratio)" ">=" 4 || verdict nan) |
EOF
}

table
