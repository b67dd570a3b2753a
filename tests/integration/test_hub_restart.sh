#!/bin/sh
# The hub (lcm-java's TCPService, a process of its own) killed mid-run and
# started again, in a namespace with no multicast route: every process
# reconnects (the daemon says so), planners are not counted gone nor runs
# crashed for the hub's absence, and every run is stored once. Then the
# hub killed for good: the daemon stops with one clear line, and the same
# command, once a hub is back, resumes and completes, nothing lost,
# nothing stored twice.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_need_hub
mpb_enter_netns "$0" "$@"
mpb_no_multicast

work=$(mktemp -d)
trap 'mpb_stop_all; [ -n "${KEEP:-}" ] || rm -rf "$work"' EXIT
B=$MPB_BUILD
url=tcpq://127.0.0.1:7700
py=$B/planners/python/mpb-planner-python
[ -x "$MPB_SOURCE/.venv/bin/python3" ] || py=""

start_hub() {
    mpb_spawn_hub "$work/hub.log"
    hub=$MPB_HUB_PID
}
# Runs done in the newest experiment.
done_runs() {
    q "SELECT count(*) FROM runs WHERE state = 'done'
       AND experiment_id = (SELECT max(id) FROM experiments)"
}

start_hub
mpb_spawn "$work/null1.log" "$B/planners/null/mpb-planner-null" --lcm-url "$url"
mpb_spawn "$work/null2.log" "$B/planners/null/mpb-planner-null" --lcm-url "$url"
[ -z "$py" ] || mpb_spawn "$work/python.log" "$py" --lcm-url "$url"
mpb_planar_experiment "$work/exp.yaml" "name: restart, runs: 60, time_limit: 2" \
    "{planner: null, algorithms: [straight_line], params: {delay: 0.1}}" \
    ${py:+"{planner: python, algorithms: [RRTConnect], runs: 4}"}
DB=$work/test.db
total=60
[ -z "$py" ] || total=64
mpb_spawn "$work/daemon.log" \
    "$B/daemon/mpbenchd" --lcm-url "$url" -d "$DB" "$work/exp.yaml"
daemon=$MPB_SPAWNED

mpb_wait_count "$DB" 10 30 "SELECT count(*) FROM runs WHERE state = 'done'"
kill -KILL $hub
wait $hub 2>/dev/null
sleep 4                             # past the planners' 2 s of silence
start_hub
mpb_wait $daemon 90
rc=$?
check "the experiment completes across the hub's restart" eq $rc 0
[ $rc -eq 0 ] || tail -20 "$work/daemon.log"
check "the daemon saw the hub go" grep -q "lost the hub" "$work/daemon.log"
check "... and come back" grep -q "the hub is back after" "$work/daemon.log"
check "$total runs, each done once" eq "$(done_runs)" $total
check "none crashed nor retried for the hub's absence" \
    eq "$(q 'SELECT coalesce(sum(crashes), 0) FROM runs')" 0
check "no planner counted gone" eq "$(grep -c 'is gone' "$work/daemon.log")" 0

# The hub gone for good: the daemon waits for it (MPBD_HUB_AWAY_MAX_S,
# 60 s, then stops by itself); stopped here by a signal, as a user would,
# it resumes with the same command once a hub is back.
mpb_spawn "$work/daemon2.log" \
    "$B/daemon/mpbenchd" --again --lcm-url "$url" -d "$DB" "$work/exp.yaml"
daemon=$MPB_SPAWNED
for i in $(seq 300); do
    [ "$(q 'SELECT count(*) FROM experiments')" -ge 2 ] &&
        [ "$(done_runs)" -ge 10 ] && break
    sleep 0.1
done
kill -KILL $hub
wait $hub 2>/dev/null
sleep 1
kill -INT $daemon
mpb_wait $daemon 20
check "the daemon, its hub gone, stops when told to" eq $? 130
check "... saying the hub is away" grep -q "lost the hub" "$work/daemon2.log"
start_hub
mpb_timeout 90 "$B/daemon/mpbenchd" --lcm-url "$url" -d "$DB" "$work/exp.yaml" \
    >"$work/daemon3.log" 2>&1
check "the same command resumes once the hub is back" eq $? 0
check "... resuming" grep -q "resuming experiment" "$work/daemon3.log"
check "the second experiment's $total runs, each done once" eq "$(done_runs)" $total
check "... none crashed" eq "$(q 'SELECT coalesce(sum(crashes), 0) FROM runs')" 0
mpb_finish
