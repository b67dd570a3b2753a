#!/bin/sh
# Two daemons on one LCM URL would share its planners and disturb each
# other's runs, so the one that started later stops, before it sends a
# request, and says how to run it apart:
#   1. a daemon started beside a running one stops at once, in one line
#      naming the other and -u, having sent nothing; the first goes on
#      undisturbed, and the second's command, run again once the first has
#      ended, resumes and completes; `mpb status` follows the first, and
#      is not ended by the second's stop, even when it heard the second
#      first;
#   2. of two daemons started at the same moment, exactly one stops;
#   3. on URLs of their own, two daemons run at once.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
daemon=$MPB_BUILD/daemon/mpbenchd
null=$MPB_BUILD/planners/null/mpb-planner-null
other_url='udpm://239.255.76.68:7668?ttl=0'

# experiment NAME RUNS: RUNS runs of 50 ms each.
experiment() {
    mpb_planar_experiment "$work/$1.yaml" "name: $1, runs: $2, time_limit: 1" \
        "{planner: null, algorithms: [straight_line], params: {delay: 0.05}}"
}

# 1. "first" runs 100 runs (5 s); "second" starts once it has done 5.
experiment first 100
experiment second 10
mpb_spawn "$work/planner.log" "$null"
"$daemon" -d "$work/first.db" "$work/first.yaml" >"$work/first.log" 2>&1 &
first=$!
mpb_wait_count "$work/first.db" 5 10 "SELECT count(*) FROM runs WHERE state = 'done'"
"$MPB_BUILD/tools/mpb" status --timeout 30 >"$work/status.log" 2>&1 &
status=$!
sleep 1.5
# A second `mpb status` must hear the second daemon before the first
# publishes again (once a second), and then leave it for the first, which
# stays. So it is started just after one of the first's statuses (a line
# in status.log), and the second daemon only once it listens: its LCM
# socket is bound (ss), and it has heard nothing yet.
lines=$(wc -l <"$work/status.log")
for _ in $(seq 200); do
    [ "$(wc -l <"$work/status.log")" -gt "$lines" ] && break
    sleep 0.01
done
"$MPB_BUILD/tools/mpb" status --timeout 30 >"$work/status2.log" 2>&1 &
status2=$!
listening=no
mpb_wait_listening $status2 && listening=yes
check "beside: a second mpb status listens, having heard nothing, before the second starts" \
    test "$listening" = yes -a ! -s "$work/status2.log"
"$daemon" -d "$work/second.db" "$work/second.yaml" >"$work/second.log" 2>&1 &
second=$!
mpb_wait $second 10
check "beside: the second daemon stops with exit 1" eq $? 1
check "beside: ... in one line naming the first, its experiment and -u" \
    grep -q "stopped: another mpbenchd, mpbenchd@[^ ]*:$first (experiment 'first', started [0-9.]* s before this one), is on this LCM URL (udpm://[^)]*), .*own URL (-u" "$work/second.log"
check "beside: ... having sent no request" \
    eq "$(sqlite3 "$work/second.db" "SELECT count(*) FROM runs WHERE state != 'pending'")" 0
mpb_wait $first 30
check "beside: the first completes" eq $? 0
check "beside: ... every run solved at its first attempt" \
    eq "$(sqlite3 "$work/first.db" "SELECT count(*) FROM runs WHERE status = 'solved' AND attempts = 1")" 100
check "beside: ... no message of its rejected" \
    grep -q "(0 rejected messages)" "$work/first.log"
check "beside: ... and it names the second, which stops" \
    grep -q "another mpbenchd, mpbenchd@[^ ]*:$second (experiment 'second'), started on this LCM URL after this one: it stops" "$work/first.log"
mpb_wait $status 10
check "beside: mpb status follows the first to its end (exit 0)" eq $? 0
check "beside: ... and prints nothing of the second" \
    test "$(grep -c second "$work/status.log")" -eq 0
mpb_wait $status2 10
check "beside: mpb status that heard the second first follows the first to its end (exit 0)" \
    eq $? 0
check "beside: ... having heard the second first" \
    grep -q "^second: " "$work/status2.log"
check "beside: ... and ends on the first's last line" \
    test "$(tail -n 1 "$work/status2.log" | cut -d, -f1)" = "first: done"
"$daemon" -d "$work/second.db" "$work/second.yaml" >"$work/second-again.log" 2>&1 &
mpb_wait $! 30
check "beside: the second's command, run again, completes" eq $? 0
check "beside: ... resuming its experiment (id 1), every run solved" \
    eq "$(sqlite3 "$work/second.db" "SELECT count(*) FROM runs WHERE status = 'solved' AND experiment_id = 1")" 10

# 2. Two started at the same moment: one stops, the other completes.
experiment left 10
experiment right 10
"$daemon" -d "$work/left.db" "$work/left.yaml" >"$work/left.log" 2>&1 &
left=$!
"$daemon" -d "$work/right.db" "$work/right.yaml" >"$work/right.log" 2>&1 &
right=$!
mpb_wait $left 30; left_rc=$?
mpb_wait $right 30; right_rc=$?
check "together: one exits 1, the other 0 (left $left_rc, right $right_rc)" \
    eq $((left_rc + right_rc)) 1
check "together: the one that stopped sent no request" \
    eq $(($(sqlite3 "$work/left.db" "SELECT count(*) FROM runs WHERE state != 'pending'") +
          $(sqlite3 "$work/right.db" "SELECT count(*) FROM runs WHERE state != 'pending'"))) 10
mpb_stop_all

# 3. On URLs of their own, each with its planner, both complete.
experiment apart1 10
experiment apart2 10
mpb_spawn "$work/apart1-planner.log" "$null"
mpb_spawn "$work/apart2-planner.log" "$null" --lcm-url "$other_url"
"$daemon" -d "$work/apart1.db" "$work/apart1.yaml" >"$work/apart1.log" 2>&1 &
one=$!
"$daemon" -u "$other_url" -d "$work/apart2.db" "$work/apart2.yaml" >"$work/apart2.log" 2>&1 &
two=$!
mpb_wait $one 30; one_rc=$?
mpb_wait $two 30; two_rc=$?
check "apart: both complete" eq $((one_rc + two_rc)) 0
mpb_finish
