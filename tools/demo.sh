#!/bin/sh
# demo.sh - `make demo`: start the planners and the daemon, run the demo
# benchmark (scenes/experiments/demo.yaml), print its report. Results stay
# in mpbench.db in the project root.
#
# LCM traffic stays on this machine: as root (or where user namespaces are
# allowed) in a private network namespace; otherwise on the host's loopback
# with ttl=0, which needs a multicast route (see README).
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
MPB_BUILD=${MPB_BUILD:-$root/build}
. "$root/tests/integration/lib.sh"

if [ -n "${MPB_IN_NETNS:-}" ] || [ "$(id -u)" -eq 0 ] || unshare -rn true 2>/dev/null; then
    mpb_enter_netns "$0" "$@"
fi

db=$root/mpbench.db
logs=$MPB_BUILD/demo-logs
mkdir -p "$logs"
trap mpb_stop_all EXIT INT TERM

echo "demo: starting planners (logs in $logs)"
mpb_spawn "$logs/ompl.log" "$MPB_BUILD/planners/ompl/mpb-planner-ompl"
mpb_spawn "$logs/null.log" "$MPB_BUILD/planners/null/mpb-planner-null"

echo "demo: running scenes/experiments/demo.yaml"
"$MPB_BUILD/daemon/mpbenchd" -d "$db" "$root/scenes/experiments/demo.yaml"
mpb_stop_all
echo
"$MPB_BUILD/tools/mpb" report "$db"
echo
echo "demo: results are in $db; try: sqlite3 -header -column mpbench.db 'SELECT * FROM results LIMIT 10'"
