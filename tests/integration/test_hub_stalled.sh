#!/bin/sh
# A stalled hub is detected (issue 47): a client that subscribes to every
# channel and never reads (tests/tools/stall_client.py) blocks lcm-java's
# hub once its buffers fill. The daemon, which hears none of its own
# statuses come back (the hub relays every message to its sender too),
# says so in one line, waits as for a hub away (no planner gone, no run
# charged), and after MPBD_HUB_AWAY_MAX_S (60 s) stops in one line. With
# the client gone, the same command resumes and completes every run once.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_need_hub
mpb_enter_netns "$0" "$@"
mpb_no_multicast

work=$(mktemp -d)
trap 'mpb_stop_all; [ -n "${KEEP:-}" ] || rm -rf "$work"' EXIT
B=$MPB_BUILD
url=tcpq://127.0.0.1:7700
DB=$work/test.db

mpb_spawn_hub "$work/hub.log"
mpb_spawn "$work/null1.log" "$B/planners/null/mpb-planner-null" --lcm-url "$url"
mpb_spawn "$work/null2.log" "$B/planners/null/mpb-planner-null" --lcm-url "$url"
# Results of 48 KB: the stalled client's buffers fill within seconds.
mpb_planar_experiment "$work/exp.yaml" "name: stalled, runs: 400, time_limit: 2, retries: 0" \
    "{planner: null, algorithms: [straight_line], params: {delay: 0.05, waypoints: 2000}}"
mpb_spawn "$work/daemon.log" \
    "$B/daemon/mpbenchd" --lcm-url "$url" -d "$DB" "$work/exp.yaml"
daemon=$MPB_SPAWNED
mpb_wait_count "$DB" 10 60 "SELECT count(*) FROM runs WHERE state = 'done'"
mpb_stall_hub "$work/stall.log"
mpb_wait $daemon 150
rc=$?
check "the daemon stops by itself, the hub stalled" eq $rc 1
check "... saying the hub is stalled, in one line" \
    eq "$(grep -c 'the hub is stalled' "$work/daemon.log")" 1
check "... and why it stops, in one line" \
    eq "$(grep -c 'stopped: the hub at .* has been away or stalled for 60 s' "$work/daemon.log")" 1
check "... no planner counted gone meanwhile" \
    eq "$(grep -c 'is gone' "$work/daemon.log")" 0
check "... no run charged with it" \
    eq "$(q "SELECT count(*) FROM runs WHERE status = 'crash' OR crashes > 0")" 0
mpb_unstall_hub
mpb_timeout 120 "$B/daemon/mpbenchd" --lcm-url "$url" -d "$DB" "$work/exp.yaml" \
    >"$work/daemon2.log" 2>&1
rc=$?
check "the same command, the client gone, completes" eq $rc 0
[ $rc -eq 0 ] || tail -5 "$work/daemon2.log"
check "400 runs, each done once, none crashed" \
    eq "$(q "SELECT count(*) FROM runs WHERE state = 'done' AND status = 'solved'
             AND crashes = 0")" 400
mpb_finish
