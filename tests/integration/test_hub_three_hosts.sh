#!/bin/sh
# Three hosts with no multicast route anywhere, each a network namespace
# with its own host name, joined by veth links on a bridge: lcm-java's hub
# and the daemon on one, a planner on each of the two others, all through
# tcpq://. The experiment runs across both planner hosts; one cut off
# mid-run, its run is redone on the other, and each run is stored once;
# back on the network, it takes part again.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
if [ "$(id -u)" -ne 0 ]; then
    echo "skipped: needs root for network namespaces joined by veth"
    echo "0 passed, 0 failed, 1 skipped"
    exit 0
fi
mpb_need_hub
mpb_enter_netns "$0" "$@"
mpb_no_multicast

work=$(mktemp -d)
trap 'mpb_stop_all; [ -n "${KEEP:-}" ] || rm -rf "$work"' EXIT
DB=$work/test.db
url=tcpq://10.213.1.1:7700

# This namespace is the hub's host; a bridge is the network between the
# hosts. The addresses exist only inside the namespaces this test made.
ip link add lan0 type bridge
ip link set lan0 up
ip addr add 10.213.1.1/24 dev lan0

# new_host NAME N: a sleeping process that holds the host's namespaces.
new_host() {
    unshare -n -u sh -c "hostname $1; exec sleep 600" &
    pid=$!
    MPB_PIDS="$MPB_PIDS $pid"
    sleep 0.2
    ip link add "veth$1" type veth peer name eth0 netns "$pid"
    ip link set "veth$1" master lan0 up
    nsenter -t "$pid" -n sh -c "ip link set lo up; ip link set eth0 up;
        ip addr add 10.213.1.$2/24 dev eth0"
    eval "pid_$1=$pid"
}
new_host hostA 11
new_host hostB 12
check "no multicast route on any host" test -z "$(ip route show 224.0.0.0/4;
    nsenter -t "$pid_hostA" -n ip route show 224.0.0.0/4;
    nsenter -t "$pid_hostB" -n ip route show 224.0.0.0/4)"

mpb_spawn_hub "$work/hub.log"
nsenter -t "$pid_hostA" -n -u "$MPB_BUILD/planners/null/mpb-planner-null" \
    --lcm-url "$url" >"$work/a.log" 2>&1 &
MPB_PIDS="$MPB_PIDS $!"
nsenter -t "$pid_hostB" -n -u "$MPB_BUILD/planners/null/mpb-planner-null" \
    --lcm-url "$url" >"$work/b.log" 2>&1 &
MPB_PIDS="$MPB_PIDS $!"

MPB_QUERIES='{name: a, start: [0, 0, 0], goal: [0.3, -0.2, 0.1], tolerance: 0.01}
             {name: b, start: [0, 0, 0], goal: [-0.2, 0.3, 0.2], tolerance: 0.01}' \
mpb_planar_experiment "$work/exp.yaml" "name: hub, runs: 20, time_limit: 2, retries: 2" \
    "{planner: null, algorithms: [straight_line], params: {delay: 0.2}}"
mpb_spawn "$work/daemon.log" \
    "$MPB_BUILD/daemon/mpbenchd" --lcm-url "$url" -d "$DB" "$work/exp.yaml"
daemon=$MPB_SPAWNED

# Let both hosts work for a while, then cut hostB off.
mpb_wait_count "$DB" 10 30 "SELECT count(*) FROM runs WHERE state = 'done'"
ip link set vethhostB down

mpb_wait $daemon 60
status=$?
check "the experiment completes with a host cut off" eq $status 0
[ $status -eq 0 ] || tail -20 "$work/daemon.log"
check "both planner hosts did runs" \
    eq "$(q "SELECT count(DISTINCT substr(planner_id, 1, instr(planner_id, ':'))) FROM runs WHERE planner_id LIKE 'null@host_:%'")" 2
check "the daemon saw hostB go" grep -q "planner null@hostB:[0-9]* is gone" "$work/daemon.log"
check "40 runs, each done once" eq "$(q "SELECT count(*) FROM runs WHERE state = 'done'")" 40
check "every run solved in the end" eq "$(q "SELECT count(*) FROM runs WHERE status = 'solved'")" 40
check "the run cut off was redone" ge "$(q 'SELECT sum(crashes) FROM runs')" 1
check "runs after the cut went to hostA" \
    eq "$(q "SELECT planner_id LIKE 'null@hostA:%' FROM runs ORDER BY finished DESC LIMIT 1")" 1

# hostB back on the network: its planner takes part again (on its old
# connection, or a new one once the kernel gave the old one up).
ip link set vethhostB up
mpb_planar_experiment "$work/again.yaml" "name: again, runs: 30, time_limit: 2" \
    "{planner: null, algorithms: [straight_line], params: {delay: 0.2}}"
mpb_timeout 90 "$MPB_BUILD/daemon/mpbenchd" --lcm-url "$url" -d "$DB" \
    "$work/again.yaml" >"$work/again.log" 2>&1
check "with hostB back, the next experiment completes" eq $? 0
check "... hostB's planner doing runs in it again" \
    ge "$(q "SELECT count(*) FROM runs r JOIN experiments e ON e.id = r.experiment_id
             WHERE e.name = 'again' AND r.planner_id LIKE 'null@hostB:%'")" 1

mpb_finish
