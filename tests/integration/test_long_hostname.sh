#!/bin/sh
# A host with a long name, like a cloud VM's: planners there (the C kit's
# and the Python kit's) take and answer runs. Their ids, and so their
# channels MPB_REQUEST_<id> and MPB_ACK_<id>, stay within LCM's 63
# characters: the host's first characters, then a hash of all of it.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; [ "$FAILS" -eq 0 ] && rm -rf "$work"' EXIT
DB=$work/test.db
host=ip-172-31-10-20.eu-central-1.compute.internal.benchmark-lab1
check "the host name has 60 characters" eq ${#host} 60

# Run a command in a UTS namespace of its own, named $host.
on_long_host() {
    unshare -u sh -c 'hostname "$0" && exec "$@"' "$host" "$@"
}

mpb_planar_experiment "$work/exp.yaml" \
    "name: longhost, runs: 4, time_limit: 5, runs_per_host: 2" \
    "{planner: null, algorithms: [straight_line]}" \
    "{planner: python, algorithms: [RRTConnect]}"
mpb_spawn "$work/null.log" on_long_host "$MPB_BUILD/planners/null/mpb-planner-null"
mpb_spawn "$work/python.log" on_long_host \
    "$MPB_BUILD/planners/python/mpb-planner-python"
on_long_host "$MPB_BUILD/daemon/mpbenchd" -d "$DB" "$work/exp.yaml" \
    >"$work/daemon.log" 2>&1 &
mpb_wait $! 90
check "the experiment completes" eq $? 0
check "every run is solved" \
    eq "$(q "SELECT count(*) FROM runs WHERE status = 'solved'")" 8
check "... by planners on the long host, of both kits" eq "$(q "SELECT
    count(DISTINCT planner_id) FROM runs WHERE planner_id GLOB
    '*@ip-172-31-10-20.eu-central-1*-[0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f]:[0-9]*'")" 2
check "no id is longer than 51 characters" \
    eq "$(q "SELECT count(*) FROM runs WHERE length(planner_id) > 51")" 0
check "LCM never refused a channel name" \
    sh -c "! grep -qi 'channel name too long' '$work/daemon.log' '$work/null.log' '$work/python.log'"

mpb_finish
