#!/bin/sh
# Verification in a pool of threads (mpbenchd --verify-threads) judges
# every run as one thread does: on the paper's quick suite (the PR2 in its
# four environments, every query, one run of OMPL's RRTConnect and
# KPIECE1 at a 1 s limit), with three verifier threads, each with its own
# copy of the scenes' worlds, every run is stored once, and mpb verify,
# checking every stage again in one thread against the experiment's own
# worlds, agrees with the daemon on every run.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
DB=$work/threads.db
mpb=$MPB_BUILD/tools/mpb

mpb_paper_quick_experiment "$work/exp.yaml"
cat >>"$work/exp.yaml" <<EOT
  - planner: ompl
    algorithms: [RRTConnect, KPIECE1]
EOT

# Two planners, so that results arrive while others are being verified.
mpb_spawn "$work/ompl1.log" "$MPB_BUILD/planners/ompl/mpb-planner-ompl"
mpb_spawn "$work/ompl2.log" "$MPB_BUILD/planners/ompl/mpb-planner-ompl"
"$MPB_BUILD/daemon/mpbenchd" --verify-threads 3 -d "$DB" "$work/exp.yaml" \
    >"$work/daemon.log" 2>&1 &
mpb_wait $! 240
status=$?
check "the quick suite completes with three verifier threads" eq "$status" 0
[ "$status" -eq 0 ] || tail -20 "$work/daemon.log"
check "... the daemon says it verifies in three threads" grep -q \
    "verifying in 3 threads, each with its own copy of the 4 scene worlds" \
    "$work/daemon.log"
check "... every query, two configurations, each run stored once" eq \
    "$(q "SELECT count(*) FROM runs WHERE state = 'done'")" \
    "$(q "SELECT 2 * count(*) FROM queries")"
check "... every stage verified" eq \
    "$(q "SELECT count(*) FROM stages WHERE verdict IS NULL")" 0

out=$("$mpb" verify "$DB")
status=$?
check "mpb verify agrees with the pool on every run: exit 0" eq "$status" 0
[ "$status" -eq 0 ] || printf '%s\n' "$out" | tail -20
check "... 0 runs decided otherwise than stored" test -n \
    "$(printf '%s\n' "$out" | tail -1 | grep '; 0 runs decided otherwise than stored$')"
check "... and some runs were verified" test \
    "$(q "SELECT count(*) > 0 FROM runs WHERE outcome = 'verified'")" = 1

bad=$("$MPB_BUILD/daemon/mpbenchd" --verify-threads 0 -d "$work/x.db" \
    "$work/exp.yaml" 2>&1)
check "--verify-threads 0 is refused in one line" test \
    "$bad" = "mpbenchd: --verify-threads must be a whole number from 1 to 256, not '0'"

mpb_finish
