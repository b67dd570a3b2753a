#!/bin/sh
# demo.sh - `make demo`: run the demo benchmark with every planner that is
# built and print its report (tools/run_benchmark.sh does the work).
# Results stay in mpbench.db in the project root.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
export MPB_BUILD=${MPB_BUILD:-$root/build}
sh "$root/tools/run_benchmark.sh" -d "$root/mpbench.db" -l "$MPB_BUILD/demo-logs" \
    "$root/scenes/experiments/demo.yaml"
echo "demo: try: sqlite3 -header -column mpbench.db 'SELECT * FROM results LIMIT 10'"
