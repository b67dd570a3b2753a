#!/bin/sh
# mbm_check.sh - load all 700 MotionBenchMaker problems of the Panda
# (scenes/experiments/mbm-panda.yaml) with `mpbenchd --check`, which
# refuses any start or goal outside the limits or in collision under the
# full mesh model and the allowed-collision matrix, and say how long it
# took. The data is fetched first if missing (tools/robot_data.sh).
#
#   tools/mbm_check.sh [EXPERIMENT.yaml]     exit 0 if every problem loads
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
. "$root/tools/usage.sh"
mpb_no_options "$@"
MPB_BUILD=${MPB_BUILD:-$root/build}
exp=${1:-$root/scenes/experiments/mbm-panda.yaml}
"$root/tools/robot_data.sh" --check || "$root/tools/robot_data.sh" >/dev/null
start=$(date +%s.%N)
"$MPB_BUILD/daemon/mpbenchd" --check "$exp"
end=$(date +%s.%N)
awk -v a="$start" -v b="$end" 'BEGIN { printf "mbm_check: loaded in %.1f s\n", b - a }' >&2
