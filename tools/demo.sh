#!/bin/sh
# demo.sh - `make demo`: a slice of the paper's benchmark
# (scenes/experiments/paper-demo.yaml: the PR2's right arm, two goals in
# each of the four environments) with the OMPL, ARA* and Python planners,
# then its report and what it says (tools/run_benchmark.sh does the work).
# Results stay in mpbench.db in the project root.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
. "$root/tools/usage.sh"
mpb_no_arguments "$@"
export MPB_BUILD=${MPB_BUILD:-$root/build}
sh "$root/tools/run_benchmark.sh" -d "$root/mpbench.db" -l "$MPB_BUILD/demo-logs" \
    -p ompl,arastar,python "$root/scenes/experiments/paper-demo.yaml"
"$MPB_BUILD/tools/mpb" report --findings "$root/mpbench.db" | sed -n '/^Findings/,$p'
echo
echo "demo: try: sqlite3 -header -column mpbench.db 'SELECT * FROM results LIMIT 10'"
echo "      or:  build/tools/mpb plot mpbench.db -o plots"
