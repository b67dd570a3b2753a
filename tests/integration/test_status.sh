#!/bin/sh
# mpb status follows a real experiment: mpbenchd and two null planners over
# LCM in a private network namespace. It must see the runs progress, exit 0
# on "done" with the counts the database holds, redraw one line on a
# terminal, print plain lines otherwise, and give up (exit 1) when no
# daemon talks or the daemon stops early.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
DB=$work/test.db
mpb=$MPB_BUILD/tools/mpb
null=$MPB_BUILD/planners/null/mpb-planner-null

# small.yaml's scene with the null planner only and more runs: 2 queries x
# 40 runs of 0.08 s. The straight line through the pillar fails
# verification, the small move succeeds: both counts are nonzero.
write_experiment() {
    MPB_QUERIES='{name: over_the_pillar, start: [0, 0, 0], goal: [2.6, 0, 0], tolerance: 0.01}
                 {name: small_move, start: [0, 0, 0], goal: [0.3, -0.2, 0.1], tolerance: 0.01}' \
    mpb_planar_experiment "$1" "name: $2, runs: 40, time_limit: 2.0, seed: 7" \
        "{planner: null, algorithms: [straight_line], params: {delay: 0.08}}"
}
write_experiment "$work/follow.yaml" follow
write_experiment "$work/stopped.yaml" stopped

# ---- nobody talking --------------------------------------------------------
start=$(date +%s)
"$mpb" status --timeout 1 >"$work/none.out" 2>"$work/none.err"
check "with no daemon, --timeout 1 exits 1" eq $? 1
check "... within a few seconds" ge $((start + 4)) "$(date +%s)"
check "... saying what it waited for" \
    grep -q '^mpb status: no status from mpbenchd on udpm://.* for 1 s' "$work/none.err"
check "... and prints nothing on stdout" test ! -s "$work/none.out"

"$mpb" status --timeout soon >/dev/null 2>&1
check "a timeout that is not a number is a usage error" eq $? 2
for t in 0x10 1e1 inf; do
    "$mpb" status --timeout "$t" >/dev/null 2>"$work/t.err"
    check "--timeout $t (not decimal) is a usage error" eq $? 2
    check "... naming it" grep -q "not '$t'" "$work/t.err"
done
"$mpb" status --timeout 0.5 >/dev/null 2>&1
check "--timeout 0.5 is taken (no daemon: exit 1)" eq $? 1
"$mpb" status -u bogus://x --timeout 1 >/dev/null 2>"$work/bogus.err"
check "a bad LCM URL exits 1" eq $? 1
check "... without the multicast route hint" \
    sh -c "grep -q '^mpb status: cannot start LCM on bogus://x' '$work/bogus.err' && ! grep -q 'multicast route' '$work/bogus.err'"
"$mpb" status extra >/dev/null 2>&1
check "an argument is a usage error" eq $? 2
"$mpb" status --help | grep -q '^usage: mpb status \[--lcm-url URL\]'
check "--help shows the usage" eq $? 0

# ---- following an experiment to the end ----------------------------------
mpb_spawn "$work/null1.log" "$null"
mpb_spawn "$work/null2.log" "$null"

# Followers start first: a plain one (stdout is a file), one on a terminal
# (script(1) gives it a pseudo-terminal), one for another experiment.
"$mpb" status --timeout 30 >"$work/plain.out" 2>"$work/plain.err" &
plain=$!
script -qfec "'$mpb' status --timeout 30" "$work/tty.out" >/dev/null 2>&1 &
tty=$!
"$mpb" status --experiment nosuch --timeout 3 >"$work/other.out" 2>"$work/other.err" &
other=$!
for f in $plain $tty $other; do mpb_wait_listening $f; done

mpb_timeout 120 "$MPB_BUILD/daemon/mpbenchd" -d "$DB" "$work/follow.yaml" \
    >"$work/daemon.log" 2>&1 &
daemon=$!
# Halfway, a snapshot.
sleep 2
"$mpb" status --once >"$work/once.out" 2>"$work/once.err"
once=$?
wait $daemon
check "mpbenchd completes the experiment" eq $? 0

wait $plain
check "mpb status exits 0 when the experiment is done" eq $? 0
wait $tty
check "... on a terminal too" eq $? 0
wait $other
check "following another experiment's name times out (exit 1)" eq $? 1
check "... naming it" grep -q 'for experiment nosuch' "$work/other.err"

total=$(q "SELECT count(*) FROM runs")
succeeded=$(q "SELECT count(*) FROM runs WHERE success = 1")
crashed=$(q "SELECT count(*) FROM runs WHERE status = 'crash'")
failed=$(q "SELECT count(*) FROM runs WHERE state = 'done' AND success = 0 AND status != 'crash'")
check "the experiment has 80 runs" eq "$total" 80
check "... some succeeded, some failed" sh -c "[ $succeeded -gt 0 ] && [ $failed -gt 0 ]"

last=$(tail -n 1 "$work/plain.out")
echo "# last line: $last"
check "the plain output ends with the done line" \
    sh -c "echo '$last' | grep -q '^follow: done, 80/80 runs (100%), '"
check "... whose counts are the database's" \
    sh -c "echo '$last' | grep -q ', $succeeded succeeded, $failed failed, $crashed crashed, 0 in flight, '"
check "... with the time taken and the planners seen" \
    sh -c "echo '$last' | grep -q 'took [0-9.]* s, planners: null x2$'"
check "plain lines only: no carriage return, no escape sequence" \
    sh -c "! grep -q \"\$(printf '[\r\033]')\" '$work/plain.out'"
check "nothing on stderr" test ! -s "$work/plain.err"

# Progress was seen on the way: a running line strictly between 0 and 80,
# with a rate and a time left; runs done never go back.
check "a line shows runs in progress" \
    grep -Eq '^follow: running, ([1-9]|[1-7][0-9])/80 runs \([0-9]+%\), [0-9]+ succeeded, [0-9]+ failed, [0-9]+ crashed, [0-9]+ in flight, [0-9.]+ runs/s, [0-9]+ s left, planners: null x2$' "$work/plain.out"
check "runs done never decrease" sh -c "
    sed -n 's|^follow: [a-z]*, \([0-9]*\)/80 runs.*|\1|p' '$work/plain.out' |
    awk 'NR > 1 && \$1 < prev { bad = 1 } { prev = \$1 } END { exit bad }'"
check "a line is printed only when the numbers change" \
    sh -c "[ \$(sort '$work/plain.out' | uniq -d | wc -l) -eq 0 ]"

check "on a terminal the line is redrawn in place" \
    sh -c "[ \$(tr -cd '\r' <'$work/tty.out' | wc -c) -ge 3 ]"
check "... under a line naming the experiment and the daemon" \
    grep -q 'experiment follow (mpbenchd@' "$work/tty.out"
check "... with a progress bar that fills up" \
    grep -Eq "\[#+\] 80/80 100%  $succeeded ok  $failed failed  $crashed crashed  [0-9.]+/s  in [0-9.]+ s  null x2" "$work/tty.out"
check "... and a partly filled one on the way" \
    grep -Eq '\[#+-+\] [0-9]+/80 [0-9]+%  [0-9]+ ok  [0-9]+ failed  [0-9]+ crashed  [0-9.]+/s  [0-9]+ s left  null x2' "$work/tty.out"
check "... no line longer than 80 columns" \
    sh -c "tr '\r' '\n' <'$work/tty.out' | sed 's/\x1b\[K//g' | awk 'length > 79 && !/^Script/ { bad = 1 } END { exit bad }'"

check "--once during the run exits 0" eq "$once" 0
check "... with the status line" grep -q '^follow: running, ' "$work/once.out"
check "... and a line per planner process" \
    sh -c "[ \$(grep -c '^  null@[^ ]* (null): [0-9]* runs done, [0-9]* active, last heard' '$work/once.out') -eq 2 ]"

# ---- a daemon stopped before the end ---------------------------------------
"$mpb" status --timeout 30 >"$work/stopped.out" 2>"$work/stopped.err" &
follower=$!
mpb_wait_listening $follower
"$MPB_BUILD/daemon/mpbenchd" -d "$work/stopped.db" "$work/stopped.yaml" \
    >"$work/daemon2.log" 2>&1 &
daemon=$!
sleep 1.5
kill -TERM $daemon
wait $daemon
wait $follower
check "a daemon stopped mid-experiment makes mpb status exit 1" eq $? 1
check "... saying so" \
    grep -q 'mpbenchd stopped before the experiment was done' "$work/stopped.err"
check "... after its last line" grep -q '^stopped: stopped, ' "$work/stopped.out"

# ---- the same experiment resumed -------------------------------------------
# Its counts start from the runs done before the stop, as runs done do.
"$mpb" status --timeout 30 >"$work/resumed.out" 2>"$work/resumed.err" &
follower=$!
mpb_wait_listening $follower
mpb_timeout 120 "$MPB_BUILD/daemon/mpbenchd" -d "$work/stopped.db" \
    "$work/stopped.yaml" >"$work/daemon3.log" 2>&1
check "the stopped experiment resumes to the end" eq $? 0
wait $follower
check "mpb status follows the resumed one to the end" eq $? 0
DB=$work/stopped.db
succeeded=$(q "SELECT count(*) FROM runs WHERE success = 1")
crashed=$(q "SELECT count(*) FROM runs WHERE status = 'crash'")
failed=$(q "SELECT count(*) FROM runs WHERE state = 'done' AND success = 0 AND status != 'crash'")
last=$(tail -n 1 "$work/resumed.out")
echo "# last line: $last"
check "... whose done line counts the runs of both sessions" \
    sh -c "echo '$last' | grep -q '^stopped: done, 80/80 runs (100%), $succeeded succeeded, $failed failed, $crashed crashed, '"

# ---- long planner names on an 80-column terminal ---------------------------
# Three families whose names do not fit beside the numbers: the line names
# whole ones and counts the rest, never a name cut short.
mpb_stop_all
fams="a_planner_family_name_one a_planner_family_name_two a_planner_family_name_three"
set --
for f in $fams; do
    mpb_spawn "$work/$f.log" "$null" --name "$f"
    set -- "$@" "{planner: $f, algorithms: [straight_line], params: {delay: 0.2}}"
done
mpb_planar_experiment "$work/names.yaml" "name: names, runs: 4, time_limit: 2.0" "$@"
COLUMNS=80 script -qfec "'$mpb' status --timeout 30" "$work/names.out" >/dev/null 2>&1 &
tty=$!
mpb_wait_listening $tty
mpb_timeout 120 "$MPB_BUILD/daemon/mpbenchd" -d "$work/names.db" \
    "$work/names.yaml" >"$work/daemon4.log" 2>&1
check "the experiment of long-named planners completes" eq $? 0
wait $tty
tr '\r' '\n' <"$work/names.out" | sed 's/\x1b\[K//g' | grep '^\[' >"$work/names.lines"
check "... mpb status drew its line on the terminal" test -s "$work/names.lines"
# What follows the last double space: whole names (then a count of the
# rest), a count of planners, or, with no room for that, the time field.
awk -F '  ' '{ print $NF }' "$work/names.lines" >"$work/names.ends"
check "... each line ends in whole planner names, a count of them or a time" \
    sh -c "! grep -Evx '(a_planner_family_name_(one|two|three)(, a_planner_family_name_(one|two|three))*(, \+[0-9]+ more)?|([0-9]+|no) planners|in [0-9.]+ s|[0-9:]+ s left|[a-z]+)' '$work/names.ends'"
check "... no line longer than 79 columns" \
    sh -c "awk 'length > 79 { bad = 1 } END { exit bad }' '$work/names.lines'"

mpb_finish
