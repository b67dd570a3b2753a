#!/bin/sh
# A planner built before attempt_id (the attempt's id named run_id on the
# wire) against today's daemon: the Python kit forced to those layouts
# (MPB_KIT_LAYOUT=before-attempt-id, test-only: it sends its
# announcements, acks and results under the older fingerprints and takes
# requests and acks only under theirs). The daemon tells it by its
# announcements and sends it requests and acks in its layout; every run is
# stored once and verified valid, with a shared secret too. Today's kit
# beside it is still served in today's layouts.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
planner=$MPB_BUILD/planners/python/mpb-planner-python
daemon=$MPB_BUILD/daemon/mpbenchd

MPB_QUERIES='{name: over, start: [0, 0, 0], goal: [2.6, 0, 0], tolerance: 0.01}
             {name: fold, start: [0, 0, 0], goal: [-1.2, 1.5, 1.0], tolerance: 0.01}' \
mpb_planar_experiment "$work/planar.yaml" "name: planar, runs: 4, time_limit: 5, seed: 7" \
    "{planner: python, algorithms: [RRTConnect]}"

# run_old NAME [ARGS]: one daemon, one Python planner speaking the older
# layouts.
run_old() {
    name=$1; shift
    MPB_KIT_LAYOUT=before-attempt-id \
        mpb_spawn "$work/$name-planner.log" "$planner" -v "$@"
    "$daemon" -d "$work/$name.db" "$@" "$work/planar.yaml" \
        >"$work/$name-daemon.log" 2>&1 &
    mpb_wait $! 60
    rc=$?
    mpb_stop_all
    return $rc
}

DB=$work/old.db
run_old old
check "old planner: the experiment completes" eq $? 0
check "old planner: the daemon knows it for one built before attempt_id" \
    grep -q "was built before attempt_id" "$work/old-daemon.log"
check "old planner: 8 runs done" \
    eq "$(q "SELECT count(*) FROM runs WHERE state = 'done'")" 8
check "old planner: every run verified valid" \
    eq "$(q "SELECT count(*) FROM runs WHERE success = 1")" 8
check "old planner: each run's result stored once (one raw stage each)" \
    eq "$(q "SELECT count(*) FROM stages WHERE name = 'raw'")" 8
check "old planner: each run planned once, in one attempt" \
    eq "$(q "SELECT count(*) FROM runs WHERE attempts = 1")" 8
check "old planner: nothing it sent was rejected" \
    grep -q "complete: 8 runs, 8 succeeded, 0 crashed (0 rejected messages)" \
    "$work/old-daemon.log"

# With a secret: the trailer seals the bytes the older planner takes.
head -c 32 /dev/urandom >"$work/secret"
DB=$work/secret.db
run_old secret --secret-file "$work/secret"
check "old planner with --secret-file: completes" eq $? 0
check "old planner with --secret-file: 8 runs verified valid" \
    eq "$(q "SELECT count(*) FROM runs WHERE success = 1")" 8

# An old planner and today's in one experiment, each of its own family so
# that each plans its own runs: each is served in its own layouts.
mpb_planar_experiment "$work/two.yaml" "name: two, runs: 4, time_limit: 5, seed: 9" \
    "{planner: old, algorithms: [RRTConnect]}" \
    "{planner: new, algorithms: [RRTConnect]}"
MPB_KIT_LAYOUT=before-attempt-id mpb_spawn "$work/two-old.log" "$planner" -v -n old
mpb_spawn "$work/two-new.log" "$planner" -v -n new
"$daemon" -d "$work/two.db" "$work/two.yaml" >"$work/two-daemon.log" 2>&1 &
mpb_wait $! 60
check "old and new planner: the experiment completes" eq $? 0
mpb_stop_all
DB=$work/two.db
check "old and new planner: 4 runs each verified valid" \
    test "$(q "SELECT c.planner, count(*) FROM runs r
               JOIN planner_configs c ON c.id = r.planner_config_id
               WHERE r.success = 1 GROUP BY c.planner ORDER BY c.planner" |
            tr '\n' ' ')" = "new|4 old|4 "
check "old and new planner: only the old one is sent the older layouts" \
    test "$(grep -c "was built before attempt_id" "$work/two-daemon.log")" = 1
check "old and new planner: nothing was rejected" \
    grep -q "(0 rejected messages)" "$work/two-daemon.log"

mpb_finish
