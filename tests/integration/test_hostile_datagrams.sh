#!/bin/sh
# No datagram can crash an mpbench process (issue 28, lcm_filter.h): while a
# planar experiment runs with the null, OMPL and Python planners (and the
# ARA* planner listening, though it serves no planar world), mpb status and
# mpb spy (lcm-spy under Xvfb, with the probe plugin of test_spy) watch,
# mpb-test-hostile sends to the LCM group, on every channel they
# subscribe to, the fragment whose offset wraps liblcm's bounds check (as
# fragment 0 and as fragment 1), a fragment past its total, a message over
# MPB_LCM_MESSAGE_MAX, a short message whose channel has no NUL after a
# filler (the Python crash), then 1500 datagrams of random LCM-like bytes
# at 300 a second. The experiment cannot end before that: it also has runs
# for a null planner named "late", started only afterwards. Every process
# is still alive at the end, no warning of an unfiltered socket is
# printed, lcm-spy still decodes the daemon's last status, the experiment
# completes, and every run is stored exactly once and done by a planner
# (none counted a crash).
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
DB=$work/test.db
planners=$MPB_BUILD/planners

mpb_planar_experiment "$work/exp.yaml" "name: hostile, runs: 12, time_limit: 5, seed: 3" \
    "{planner: null, algorithms: [straight_line]}" \
    "{planner: ompl, algorithms: [RRTConnect]}" \
    "{planner: python, algorithms: [RRTConnect]}" \
    "{planner: late, algorithms: [straight_line]}"

# wait_for PATTERN FILE SECONDS: until a line of FILE matches (grep -E).
wait_for() {
    tenths=$(($3 * 10))
    until grep -Eq "$1" "$2" 2>/dev/null; do
        [ "$tenths" -gt 0 ] || return 1
        sleep 0.1
        tenths=$((tenths - 1))
    done
}

mkdir -p "$work/probe"
javac -nowarn -cp /usr/share/java/lcm.jar -d "$work/probe" \
    "$MPB_SOURCE/tests/integration/data/MpbSpyProbe.java"
Xvfb -displayfd 3 -screen 0 1024x600x24 -nolisten tcp 3>"$work/display" \
    >"$work/xvfb.log" 2>&1 &
xvfb=$!
wait_for '^[0-9]+$' "$work/display" 30
DISPLAY=:$(cat "$work/display")
export DISPLAY
mpb_spawn "$work/spy.log" "$MPB_BUILD/tools/mpb" spy --classpath "$work/probe"
spy=$!
wait_for '^probe: (watching|failed)' "$work/spy.log" 90
check "mpb spy starts lcm-spy with the probe" grep -q '^probe: watching' "$work/spy.log"

mpb_spawn "$work/null.log" "$planners/null/mpb-planner-null"
mpb_spawn "$work/ompl.log" "$planners/ompl/mpb-planner-ompl"
mpb_spawn "$work/arastar.log" "$planners/arastar/mpb-planner-arastar"
mpb_spawn "$work/python.log" "$planners/python/mpb-planner-python" -v
listeners=${MPB_PIDS#" $spy"}

# The planners' ids name their channels: wait until each has said it.
tenths=300
while [ "$tenths" -gt 0 ]; do
    ids=$(sed -n 's/.*serving as \([^ ]*\)$/\1/p; s/^mpb-planner-python: \([^ ]*\) ready:.*/\1/p' \
        "$work/null.log" "$work/ompl.log" "$work/arastar.log" "$work/python.log")
    [ "$(printf '%s\n' "$ids" | grep -c @)" -eq 4 ] && break
    sleep 0.1
    tenths=$((tenths - 1))
done
check "the four planners serve" eq "$(printf '%s\n' "$ids" | grep -c @)" 4
channels="MPB_ANNOUNCE MPB_RESULT MPB_ACK MPB_STATUS"
for id in $ids; do
    channels="$channels MPB_REQUEST_$id MPB_ACK_$id"
done

"$MPB_BUILD/tools/mpb" status >"$work/status.log" 2>&1 &
status_pid=$!
mpb_wait_listening $status_pid
"$MPB_BUILD/daemon/mpbenchd" -d "$DB" "$work/exp.yaml" >"$work/daemon.log" 2>&1 &
daemon=$!
sleep 0.5
# shellcheck disable=SC2086  # one word a channel
mpb_timeout 60 "$MPB_BUILD/tests/mpb-test-hostile" -n 1500 -r 300 -s 28 $channels \
    >"$work/hostile.log" 2>&1
check "the hostile datagrams are sent" grep -q "datagrams sent" "$work/hostile.log"
check "... and mpbenchd, waiting for the late planner, is alive" kill -0 "$daemon"
mpb_spawn "$work/late.log" "$planners/null/mpb-planner-null" --name late

mpb_wait "$daemon" 120
check "mpbenchd completes the experiment and exits 0" eq $? 0
alive=0
for pid in $listeners; do
    kill -0 "$pid" 2>/dev/null && alive=$((alive + 1))
done
check "the four planners are alive" eq "$alive" 4
mpb_wait "$status_pid" 10
check "mpb status follows to the end and exits 0" eq $? 0
wait_for '^probe: MPB_STATUS state=done' "$work/spy.log" 30
check "lcm-spy decodes the daemon's last status" \
    grep -q '^probe: MPB_STATUS state=done' "$work/spy.log"
check "... and runs on" kill -0 "$spy"
check "no process warns of an unfiltered socket" \
    eq "$(cat "$work"/*.log | grep -c "has no filter")" 0

check "48 runs, each stored once" eq "$(q "SELECT count(*) FROM runs")" 48
check "... each done" eq "$(q "SELECT count(*) FROM runs WHERE state = 'done'")" 48
check "... each under its own run id" eq "$(q "SELECT count(DISTINCT attempt_id) FROM runs")" 48
check "... none a crash, none re-sent to another planner" \
    eq "$(q "SELECT count(*) FROM runs WHERE crashes > 0 OR status = 'crash'")" 0
check "... no stage stored twice" \
    eq "$(q "SELECT count(*) FROM (SELECT run_id, name FROM stages
             GROUP BY run_id, name HAVING count(*) > 1)")" 0
check "every run verified valid" eq "$(q "SELECT count(*) FROM runs WHERE success = 1")" 48
kill "$xvfb" 2>/dev/null
if [ "$FAILS" -ne 0 ]; then
    for f in "$work"/*.log; do echo "== $f"; tail -n 5 "$f"; done
fi
mpb_finish
