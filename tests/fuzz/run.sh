#!/bin/sh
# run.sh - build the libFuzzer targets and run each for a while.
#   tests/fuzz/run.sh [SECONDS_PER_TARGET]   (default 20; CI uses that)
# A long run, e.g. an hour a target:  tests/fuzz/run.sh 3600
# MPB_FUZZ_SEED=N fixes libFuzzer's seed, so that a short run (CI's) walks
# the same inputs each time and fails only on a change to the code or the
# corpus; unset, each run draws a new seed and explores further.
# New interesting inputs go to build-fuzz/corpus/<target>/; a crash leaves
# build-fuzz/crash-* and fails the script.
set -eu
root=$(cd "$(dirname "$0")/../.." && pwd)
secs=${1:-20}
seed=${MPB_FUZZ_SEED:-0}
build=$root/build-fuzz
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DMPB_FUZZ=ON \
    -DCMAKE_BUILD_TYPE=Debug >/dev/null
# Every target, one list: what is built is what is run.
targets="messages planar experiment scene urdf ompl_log lcm_filter octree"
cmake --build "$build" -j "$(nproc)" --target $(printf 'fuzz_%s ' $targets)
cd "$build"
status=0
for target in $targets; do
    mkdir -p "corpus/$target"
    echo "== fuzz_$target, $secs s"
    if ! UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
         ASAN_OPTIONS=detect_leaks=1 \
         LSAN_OPTIONS=suppressions="$root/tests/fuzz/lsan.supp" \
         "./tests/fuzz/fuzz_$target" -max_total_time="$secs" -seed="$seed" -timeout=10 \
             -rss_limit_mb=2048 -print_final_stats=1 \
             "corpus/$target" "$root/tests/fuzz/corpus/$target" 2>"fuzz_$target.log"; then
        tail -40 "fuzz_$target.log"
        status=1
    else
        grep -E 'stat::number_of_executed_units|Done' "fuzz_$target.log" | head -2
    fi
done
[ $status -eq 0 ] && echo "fuzz: every target ran clean for $secs s"
exit $status
