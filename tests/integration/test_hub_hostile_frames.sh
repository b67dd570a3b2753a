#!/bin/sh
# Hostile TCP input, as test_hostile_datagrams.sh does for UDP, in a
# namespace with no multicast route. (1) During an experiment through lcm-java's
# hub, hostile clients send the hub frames claiming 4 GiB and 2 GiB
# payloads and channels, frames cut short, random bytes, a channel with a
# NUL, malformed messages, and real 17 MiB messages (which the hub relays
# whole) on every channel the daemon, the C and Python planners and `mpb
# status` subscribe to: every process survives within bounded memory, and
# every run is stored once. (2) A hostile hub answers the C and Python
# planners' connections with such frames itself: they survive, within
# bounded memory, and keep reconnecting.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_need_hub
mpb_enter_netns "$0" "$@"
mpb_no_multicast

work=$(mktemp -d)
trap 'mpb_stop_all; [ -n "${KEEP:-}" ] || rm -rf "$work"' EXIT
B=$MPB_BUILD
url=tcpq://127.0.0.1:7700
forge="python3 $MPB_SOURCE/tests/tools/hostile_frames.py"
py=$B/planners/python/mpb-planner-python
[ -x "$MPB_SOURCE/.venv/bin/python3" ] || py=""

# Peak resident memory of a process (MB), 0 if gone.
hwm() { awk '/VmHWM/ {print int($2 / 1024)}' "/proc/$1/status" 2>/dev/null || echo 0; }
alive() { kill -0 "$1" 2>/dev/null; }

mpb_spawn_hub "$work/hub.log"
hub=$MPB_HUB_PID
mpb_spawn "$work/null1.log" "$B/planners/null/mpb-planner-null" --lcm-url "$url"
null1=$MPB_SPAWNED
mpb_spawn "$work/null2.log" "$B/planners/null/mpb-planner-null" --lcm-url "$url"
null2=$MPB_SPAWNED
pyplanner=""
if [ -n "$py" ]; then
    mpb_spawn "$work/python.log" "$py" --lcm-url "$url"
    pyplanner=$MPB_SPAWNED
fi
mpb_planar_experiment "$work/exp.yaml" "name: hostile, runs: 300, time_limit: 2" \
    "{planner: null, algorithms: [straight_line], params: {delay: 0.1}}"
DB=$work/test.db
mpb_spawn "$work/daemon.log" \
    "$B/daemon/mpbenchd" --lcm-url "$url" -d "$DB" "$work/exp.yaml"
daemon=$MPB_SPAWNED
mpb_spawn "$work/status.log" "$B/tools/mpb" status --lcm-url "$url" --timeout 60
status_pid=$MPB_SPAWNED

mpb_wait_count "$DB" 5 30 "SELECT count(*) FROM runs WHERE state = 'done'"
ids=$(grep -o 'planner [^ ]* joined' "$work/daemon.log" | cut -d' ' -f2)
channels="MPB_ANNOUNCE MPB_RESULT MPB_ACK MPB_STATUS"
for id in $ids; do
    channels="$channels MPB_REQUEST_$id MPB_ACK_$id"
done
mpb_timeout 120 $forge 127.0.0.1 7700 $channels >"$work/forge.log" 2>&1
check "the hostile clients sent everything" eq $? 0
check "... while the experiment was still running" alive $daemon
daemon_hwm=$(hwm $daemon)

mpb_wait $daemon 90
rc=$?
check "the experiment completes" eq $rc 0
[ $rc -eq 0 ] || tail -20 "$work/daemon.log"
check "300 runs, each done once" eq "$(q "SELECT count(*) FROM runs WHERE state = 'done'")" 300
check "every run solved, none crashed" \
    eq "$(q "SELECT count(*) FROM runs WHERE status = 'solved' AND crashes = 0")" 300
check "the daemon dropped the oversized frames the hub relayed" \
    grep -q "hub link: dropped [1-9]" "$work/daemon.log"
check "the daemon rejected the malformed messages" \
    grep -q "rejected a message on MPB_" "$work/daemon.log"
check "the daemon stayed within 200 MB" test "$daemon_hwm" -lt 200
check "the hub survived" alive $hub
for p in $null1 $null2 $pyplanner; do
    check "planner $p survived, within 200 MB" \
        sh -c "kill -0 $p && [ \$(awk '/VmHWM/ {print int(\$2 / 1024)}' /proc/$p/status) -lt 200 ]"
done
mpb_wait $status_pid 10
check "mpb status survived and saw the end" eq $? 0
mpb_stop_all

# (2) A hostile hub.
mpb_spawn "$work/serve.log" $forge --serve 7702 6
sleep 0.5
mpb_spawn "$work/null3.log" "$B/planners/null/mpb-planner-null" \
    --lcm-url tcpq://127.0.0.1:7702
null3=$MPB_SPAWNED
if [ -n "$py" ]; then
    mpb_spawn "$work/python2.log" "$py" --lcm-url tcpq://127.0.0.1:7702
    pyplanner=$MPB_SPAWNED
fi
sleep 5.5
hwm() { awk '/VmHWM/ {print int($2 / 1024) " MB"}' "/proc/$1/status" 2>/dev/null || echo gone; }
# 100 MB, or 200 under AddressSanitizer, whose shadow memory and
# allocator add 40-70 MB to each process here (the C planner 11 -> 52
# MB, the Python one 29 -> 92-100 MB), hostile frames or not.
bound=100
ldd "$B/libmpbench/libmpbench.so" 2>/dev/null | grep -q libasan && bound=200
for p in $null3 $pyplanner; do
    check "planner $p survived a hostile hub, within $bound MB ($(hwm $p))" \
        sh -c "kill -0 $p && [ \$(awk '/VmHWM/ {print int(\$2 / 1024)}' /proc/$p/status) -lt $bound ]"
done
sleep 1
check "they kept reconnecting (10 connections or more)" \
    test "$(grep -o 'served [0-9]*' "$work/serve.log" | cut -d' ' -f2)" -ge 10
mpb_finish
