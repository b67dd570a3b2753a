#!/bin/sh
# Planners tell a stalled hub (issue 47): a client that subscribes to every
# channel and never reads (tests/tools/stall_client.py) blocks lcm-java's
# hub mid-run. The C kit (mpb-planner-null) and the Python kit
# (mpb-planner-python) each hear none of their own heartbeats come back
# through it and say so in one line, hold their results meanwhile, and
# say in one line more when it relays again; the daemon tells it too.
# The client goes before the daemon's 60 s limit: the experiment then
# completes, every run stored once, none charged with the stall.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_need_hub
if ! [ -x "$MPB_SOURCE/.venv/bin/python3" ]; then
    echo "skipped: needs .venv for the Python planner (make deps)"
    echo "0 passed, 0 failed, 1 skipped"
    exit 0
fi
mpb_enter_netns "$0" "$@"
mpb_no_multicast

work=$(mktemp -d)
trap 'mpb_stop_all; [ -n "${KEEP:-}" ] || rm -rf "$work"' EXIT
B=$MPB_BUILD
url=tcpq://127.0.0.1:7700
DB=$work/test.db
stalled='the hub is stalled: connected, but none of this planner.s heartbeats'
again='the hub relays again after'

mpb_spawn_hub "$work/hub.log"
mpb_spawn "$work/null.log" "$B/planners/null/mpb-planner-null" --lcm-url "$url"
mpb_spawn "$work/python.log" "$B/planners/python/mpb-planner-python" --lcm-url "$url"
# Results of 48 KB from the C planner: the stalled client's buffers fill
# within seconds. retries: 0: a run charged with the stall is a crash.
mpb_planar_experiment "$work/exp.yaml" "name: stalled, runs: 150, time_limit: 2, retries: 0" \
    "{planner: null, algorithms: [straight_line], params: {delay: 0.05, waypoints: 2000}}" \
    "{planner: python, algorithms: [RRTConnect]}"
mpb_spawn "$work/daemon.log" \
    "$B/daemon/mpbenchd" --lcm-url "$url" -d "$DB" "$work/exp.yaml"
daemon=$MPB_SPAWNED
mpb_wait_count "$DB" 10 60 "SELECT count(*) FROM runs WHERE state = 'done'"
mpb_stall_hub "$work/stall.log"
# The client stays until both planners have said so, or 40 s, then 5 s
# more of holding (the daemon stops after 60 s of a stalled hub).
tenths=400
while [ $tenths -gt 0 ] && ! { grep -q "$stalled" "$work/null.log" &&
                                grep -q "$stalled" "$work/python.log"; }; do
    sleep 0.1
    tenths=$((tenths - 1))
done
sleep 5
done_in_stall=$(q "SELECT count(*) FROM runs WHERE state = 'done'")
mpb_unstall_hub
mpb_wait $daemon 150
rc=$?
check "the experiment completes once the client is gone" eq $rc 0
[ $rc -eq 0 ] || tail -5 "$work/daemon.log"
check "... it was stalled mid-run (done then: $done_in_stall of 300)" \
    test "$done_in_stall" -lt 300
for p in null python; do
    check "the $p planner says the hub is stalled, in one line" \
        eq "$(grep -c "$stalled" "$work/$p.log")" 1
    check "... and that it relays again, in one line" \
        eq "$(grep -c "$again" "$work/$p.log")" 1
done
check "the daemon says so too, in one line" \
    eq "$(grep -c 'the hub is stalled' "$work/daemon.log")" 1
check "... no planner counted gone meanwhile" \
    eq "$(grep -c 'is gone' "$work/daemon.log")" 0
check "300 runs, each stored once and solved" \
    eq "$(q "SELECT count(*) FROM runs WHERE state = 'done' AND status = 'solved'")" 300
check "... none charged with the stall: first attempts, no crash" \
    eq "$(q "SELECT count(*) FROM runs WHERE attempts != 1 OR crashes != 0")" 0
check "... one row a run" \
    eq "$(q "SELECT count(DISTINCT planner_config_id || '/' || query_id || '/' || repetition) FROM runs")" 300
mpb_finish
