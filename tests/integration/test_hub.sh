#!/bin/sh
# Every process through lcm-java's TCP hub (tcpq://) in a network namespace
# with no multicast route: scenes/experiments/demo.yaml with the OMPL and
# null planners (C++ and C kits), 42 of 42 runs each stored once; the
# Python kit's planner, without and with a shared secret; `mpb status`
# following the daemon; with a shared secret as over multicast; and a daemon stopped mid-run resumed over the
# hub; run_benchmark.sh --hub, recording for --replay. No process warns of
# an unfiltered socket.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_need_hub
mpb_enter_netns "$0" "$@"
mpb_no_multicast                      # the hub or nothing

work=$(mktemp -d)
trap 'mpb_stop_all; [ -n "${KEEP:-}" ] || rm -rf "$work"' EXIT
B=$MPB_BUILD
url=tcpq://127.0.0.1:7700
python=$MPB_SOURCE/.venv/bin/python3

check "no multicast route in this namespace" \
    test -z "$(ip route show 224.0.0.0/4)"
mpb_spawn_hub "$work/hub.log"
mpb_spawn "$work/ompl.log" "$B/planners/ompl/mpb-planner-ompl" --lcm-url "$url"
mpb_spawn "$work/null.log" "$B/planners/null/mpb-planner-null" --lcm-url "$url"

DB=$work/demo.db
mpb_timeout 120 "$B/daemon/mpbenchd" --lcm-url "$url" -d "$DB" \
    "$MPB_SOURCE/scenes/experiments/demo.yaml" >"$work/daemon.log" 2>&1 &
daemon=$!
mpb_timeout 60 "$B/tools/mpb" status --lcm-url "$url" --once >"$work/status.out" 2>&1
check "mpb status hears the daemon through the hub" eq $? 0
wait $daemon
status=$?
check "demo.yaml completes through the hub" eq $status 0
[ $status -eq 0 ] || tail -20 "$work/daemon.log"
check "42 of 42 runs done" eq "$(q "SELECT count(*) FROM runs WHERE state = 'done'")" 42
check "each run done once: one raw stage per run at most" \
    eq "$(q "SELECT count(*) FROM (SELECT run_id FROM stages WHERE name = 'raw' GROUP BY run_id HAVING count(*) > 1)")" 0
check "no planner went silent" eq "$(q 'SELECT coalesce(sum(crashes), 0) FROM runs')" 0
check "no process warns of an unfiltered socket" \
    eq "$(cat "$work"/*.log | grep -c 'has no filter')" 0
check "the daemon says it reached the hub" grep -q "connected to the hub" "$work/daemon.log"

# A shared secret through the hub, and a daemon stopped and resumed.
head -c 32 /dev/urandom >"$work/secret"
mpb_planar_experiment "$work/planar.yaml" "name: planar, runs: 30, time_limit: 2" \
    "{planner: null, algorithms: [straight_line], params: {delay: 0.05}}"
mpb_spawn "$work/null-s.log" "$B/planners/null/mpb-planner-null" --lcm-url "$url" \
    --secret-file "$work/secret"
DB=$work/planar.db
"$B/daemon/mpbenchd" --lcm-url "$url" -d "$DB" --secret-file "$work/secret" \
    "$work/planar.yaml" >"$work/planar1.log" 2>&1 &
daemon=$!
mpb_wait_count "$DB" 8 30 "SELECT count(*) FROM runs WHERE state = 'done'"
kill -INT $daemon
wait $daemon
mpb_timeout 60 "$B/daemon/mpbenchd" --lcm-url "$url" -d "$DB" \
    --secret-file "$work/secret" "$work/planar.yaml" >"$work/planar2.log" 2>&1
check "with a secret, stopped and resumed, the experiment completes" eq $? 0
check "the second daemon resumed" grep -q "resuming experiment" "$work/planar2.log"
check "30 runs, each done once" \
    eq "$(q "SELECT count(*) FROM runs WHERE state = 'done'")" 30
check "the planner's authenticated results were taken" \
    eq "$(q "SELECT count(*) FROM runs WHERE planner_id LIKE 'null@%' AND state = 'done'")" 30

# The Python kit through the hub.
if [ -x "$python" ]; then
    mpb_planar_experiment "$work/py.yaml" "name: py, runs: 3, time_limit: 5" \
        "{planner: python, algorithms: [RRTConnect]}"
    mpb_spawn "$work/python.log" "$B/planners/python/mpb-planner-python" \
        --lcm-url "$url"
    DB=$work/py.db
    mpb_timeout 90 "$B/daemon/mpbenchd" --lcm-url "$url" -d "$DB" \
        "$work/py.yaml" >"$work/py-daemon.log" 2>&1
    check "the Python planner's runs complete through the hub" eq $? 0
    check "3 Python runs done" eq "$(q "SELECT count(*) FROM runs WHERE state = 'done'")" 3
    check "the Python kit warns of no filter either" \
        eq "$(grep -c 'has no filter' "$work/python.log")" 0

    # And with the shared secret: the kit seals and checks through
    # libmpbench over libmpbench's hub link, and the C daemon believes
    # it; the planner above, without the secret, takes no run.
    mpb_spawn "$work/python-s.log" "$B/planners/python/mpb-planner-python" \
        --lcm-url "$url" --secret-file "$work/secret" -v
    sealed=$MPB_SPAWNED
    DB=$work/py-secret.db
    mpb_timeout 90 "$B/daemon/mpbenchd" --lcm-url "$url" -d "$DB" \
        --secret-file "$work/secret" "$work/py.yaml" >"$work/py-secret.log" 2>&1
    check "with a secret, the Python planner's runs complete through the hub" eq $? 0
    check "... 3 runs done, verified valid, by the planner holding it" \
        eq "$(q "SELECT count(*) FROM runs WHERE state = 'done' AND success = 1
                 AND planner_id LIKE 'python@%:$sealed'")" 3
    check "... the planner without it never joined" \
        eq "$(grep -c 'planner python@.* joined' "$work/py-secret.log")" 1
fi

# tools/run_benchmark.sh --hub starts its own hub (a second, on another
# port), recording the traffic with lcm-logger for mpbenchd --replay.
mpb_planar_experiment "$work/rb.yaml" "name: rb, runs: 5, time_limit: 2" \
    "{planner: null, algorithms: [straight_line]}"
MPB_BUILD=$B mpb_timeout 90 "$MPB_SOURCE/tools/run_benchmark.sh" --hub 7701 \
    -p null -d "$work/rb.db" -l "$work/rb-logs" -r "$work/rb.lcmlog" \
    "$work/rb.yaml" >"$work/rb.out" 2>&1
check "run_benchmark.sh --hub runs an experiment through its own hub" eq $? 0
DB=$work/rb.db
check "5 runs done" eq "$(q "SELECT count(*) FROM runs WHERE state = 'done'")" 5
check "it started the hub" grep -q "starting the TCP hub on port 7701" "$work/rb.out"
check "and stopped it" test -z "$(ss -ltnH 'sport = :7701')"
"$B/daemon/mpbenchd" --replay "$work/rb.lcmlog" -d "$work/replay.db" \
    "$work/rb.yaml" >"$work/replay.log" 2>&1
check "what lcm-logger recorded through the hub replays" eq $? 0
DB=$work/replay.db
check "... to the same 5 runs" eq "$(q "SELECT count(*) FROM runs WHERE state = 'done'")" 5
mpb_finish
