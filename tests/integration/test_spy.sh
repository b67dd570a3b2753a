#!/bin/sh
# mpb spy: lcm-spy, started by `mpb spy` under Xvfb in a private network
# namespace, decodes every mpbench channel of a live experiment (mpbenchd,
# the null and OMPL planners). What lcm-spy decoded is read from inside it: a
# small lcm-spy plugin (data/MpbSpyProbe.java), put on the class path with
# `mpb spy --classpath`, prints lcm-spy's channel table and the fields of
# the last message it decoded on each channel. A screenshot is taken too
# (kept where MPB_SPY_SCREENSHOT says; docs/images/lcm-spy.png is one).
set -u
# MPB_KEEP=1 keeps the work directory (its logs) for a look afterwards.
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
[ -z "${MPB_KEEP:-}" ] || echo "# work directory: $work"
trap 'mpb_stop_all; [ -n "${MPB_KEEP:-}" ] || rm -rf "$work"' EXIT
DB=$work/spy.db
mpb=$MPB_BUILD/tools/mpb

# wait_for PATTERN FILE SECONDS: until a line of FILE matches (grep -E).
wait_for() {
    tenths=$(($3 * 10))
    until grep -Eq "$1" "$2" 2>/dev/null; do
        [ "$tenths" -gt 0 ] || return 1
        sleep 0.1
        tenths=$((tenths - 1))
    done
}

# ---- the launcher on its own ----------------------------------------------
"$mpb" spy --help >"$work/help.out"
check "mpb spy --help exits 0" eq $? 0
check "... with the usage" grep -q '^usage: mpb spy \[--lcm-url URL\]' "$work/help.out"
"$mpb" spy --no-such-option >/dev/null 2>"$work/bad.err"
check "an unknown option exits 2" eq $? 2
check "... with one line" eq "$(wc -l <"$work/bad.err")" 1

"$mpb" spy --print-command --lcm-url 'udpm://239.255.76.67:7667?ttl=0' \
    >"$work/command.out"
check "--print-command exits 0" eq $? 0
check "... runs lcm.spy.Spy with lcm.jar, jchart2d.jar and the built mpb_types.jar" \
    grep -q " -cp /usr/share/java/lcm.jar:/usr/share/java/jchart2d.jar:$MPB_BUILD/lcmtypes/mpb_types.jar lcm.spy.Spy " "$work/command.out"
check "... passing the LCM URL through" \
    grep -q "lcm.spy.Spy '--lcm-url=udpm://239.255.76.67:7667?ttl=0'\$" "$work/command.out"

# A copy of mpb away from the build tree has no mpb_types.jar beside it.
mkdir -p "$work/elsewhere/bin"
cp "$mpb" "$work/elsewhere/bin/mpb"
"$work/elsewhere/bin/mpb" spy >/dev/null 2>"$work/nojar.err"
check "without mpb_types.jar it exits 1" eq $? 1
check "... naming the jar" grep -q '^mpb spy: mpb_types.jar not found' "$work/nojar.err"
env -u JAVA_HOME PATH=/nonexistent "$mpb" spy >/dev/null 2>"$work/nojava.err"
check "without java it exits 1" eq $? 1
check "... saying so" grep -q '^mpb spy: java not found' "$work/nojava.err"
env -u DISPLAY -u WAYLAND_DISPLAY timeout 30 "$mpb" spy >"$work/nodisplay.out" 2>"$work/nodisplay.err"
check "without a display it exits 1" eq $? 1
check "... in one line saying so, no Java stack trace" \
    sh -c "[ \$(wc -l <'$work/nodisplay.err') -eq 1 ] && grep -q '^mpb spy: no display' '$work/nodisplay.err' && ! grep -q Exception '$work/nodisplay.err' '$work/nodisplay.out'"

# ---- lcm-spy on a live experiment -----------------------------------------
mkdir -p "$work/probe"
javac -nowarn -cp /usr/share/java/lcm.jar -d "$work/probe" \
    "$MPB_SOURCE/tests/integration/data/MpbSpyProbe.java"
check "the probe plugin compiles" eq $? 0

# Xvfb picks a free display itself and writes its number on fd 3.
Xvfb -displayfd 3 -screen 0 1450x600x24 -nolisten tcp 3>"$work/display" \
    >"$work/xvfb.log" 2>&1 &
MPB_PIDS="$MPB_PIDS $!"
wait_for '^[0-9]+$' "$work/display" 30
check "Xvfb starts" eq $? 0
DISPLAY=:$(cat "$work/display")
export DISPLAY

MPB_SPY_PROBE_VIEW=MPB_STATUS mpb_spawn "$work/spy.log" \
    "$mpb" spy --classpath "$work/probe"
wait_for '^probe: (watching|failed)' "$work/spy.log" 90
check "mpb spy starts lcm-spy, which loads the probe plugin" \
    grep -q '^probe: watching' "$work/spy.log"

MPB_QUERIES='{name: over_the_pillar, start: [0, 0, 0], goal: [2.6, 0, 0], tolerance: 0.01}
             {name: small_move, start: [0, 0, 0], goal: [0.3, -0.2, 0.1], tolerance: 0.01}' \
mpb_planar_experiment "$work/spydemo.yaml" "name: spydemo, runs: 40, time_limit: 2.0, seed: 3" \
    "{planner: null, algorithms: [straight_line], params: {delay: 0.05}}" \
    "{planner: ompl, algorithms: [RRTConnect]}"
mpb_spawn "$work/null.log" "$MPB_BUILD/planners/null/mpb-planner-null"
mpb_spawn "$work/ompl.log" "$MPB_BUILD/planners/ompl/mpb-planner-ompl"
mpb_timeout 120 "$MPB_BUILD/daemon/mpbenchd" -d "$DB" "$work/spydemo.yaml" \
    >"$work/daemon.log" 2>&1 &
daemon=$!

wait_for '^probe: MPB_RESULT type=' "$work/spy.log" 60
wait_for '^probe: MPB_STATUS state=running' "$work/spy.log" 60
wait_for '^probe: viewer open MPB_STATUS' "$work/spy.log" 30
wait_for '^probe: MPB_REQUEST_ompl@' "$work/spy.log" 60
# The picture, while the experiment runs (and once the viewer has drawn).
sleep 2
xwd -root -silent | xwdtopnm 2>/dev/null | pnmtopng >"$work/lcm-spy.png" 2>/dev/null
check "a screenshot is taken" test -s "$work/lcm-spy.png"
check "... of the whole screen" \
    sh -c "pngtopnm '$work/lcm-spy.png' | pnmfile | grep -q '1450 by 600'"
check "... showing windows, not an empty screen (many colours)" \
    sh -c "[ \$(pngtopnm '$work/lcm-spy.png' | ppmhist -noheader | wc -l) -gt 50 ]"
if [ -n "${MPB_SPY_SCREENSHOT:-}" ]; then
    cp "$work/lcm-spy.png" "$MPB_SPY_SCREENSHOT"
fi

wait $daemon
check "mpbenchd completes the experiment" eq $? 0
wait_for '^probe: MPB_STATUS state=done' "$work/spy.log" 30

# Every mpbench channel lcm-spy saw is decoded with its mpb type.
planner=$(sed -n 's/^mpb-planner-null: serving as //p' "$work/null.log")
ompl=$(sed -n 's/^mpb-planner-ompl: serving as //p' "$work/ompl.log")
echo "# planners: $planner $ompl"
for pair in "MPB_ANNOUNCE planner_announce_t" "MPB_REQUEST_$planner plan_request_t" \
            "MPB_REQUEST_$ompl plan_request_t" \
            "MPB_ACK_$planner run_ack_t" "MPB_RESULT plan_result_t" "MPB_STATUS daemon_status_t"; do
    channel=${pair% *}
    type=${pair#* }
    check "lcm-spy decodes $channel as mpb.$type" \
        grep -q "^probe: $channel type=$type class=mpb.$type undecodable=0\$" "$work/spy.log"
done
# Any other line names a channel lcm-spy could not decode (or one in an
# older layout, whose type has digits, _v1_t: no planner here is that
# old), shown so that a failure says which.
undecoded=$(grep -E '^probe: MPB_[^ ]* type=' "$work/spy.log" |
            grep -Ev 'type=([a-z_]*) class=mpb\.\1 undecodable=0$')
check "lcm-spy saw no mpbench channel it could not decode" test -z "$undecoded"
[ -z "$undecoded" ] || echo "$undecoded" | sed 's/^/# /'
check "... while it lists its own self-test channel as undecoded (the check sees those)" \
    grep -Eq '^probe: LCM_SELF_TEST type=\?\? [0-9a-f]+ class=none undecodable=' "$work/spy.log"

# The decoded fields are the experiment's.
total=$(q "SELECT count(*) FROM runs")
succeeded=$(q "SELECT count(*) FROM runs WHERE success = 1")
check "the database holds 160 runs" eq "$total" 160
check "the announce names a planner and its algorithm" \
    sh -c "grep -q '^probe: MPB_ANNOUNCE name=null\$' '$work/spy.log' &&
           grep -q '^probe: MPB_ANNOUNCE algorithms\[0\]=straight_line\$' '$work/spy.log' ||
           grep -q '^probe: MPB_ANNOUNCE name=ompl\$' '$work/spy.log'"
check "a request carries the algorithm and the planar robot" \
    sh -c "grep -q '^probe: MPB_REQUEST_$planner algorithm=straight_line\$' '$work/spy.log' &&
           grep -q '^probe: MPB_REQUEST_$planner robot_format=planar\$' '$work/spy.log'"
check "a result comes from one of the planners" \
    grep -Eq "^probe: MPB_RESULT planner_id=($planner|$ompl)\$" "$work/spy.log"
check "the status names the experiment" \
    grep -q '^probe: MPB_STATUS experiment=spydemo$' "$work/spy.log"
check "... with its number of runs" \
    grep -q "^probe: MPB_STATUS runs_total=$total\$" "$work/spy.log"
check "... runs in progress on the way" \
    sh -c "sed -n 's/^probe: MPB_STATUS runs_done=//p' '$work/spy.log' |
           awk '\$1 > 0 && \$1 < $total { seen = 1 } END { exit !seen }'"
check "... the planners it sees" \
    sh -c "grep -Eq '^probe: MPB_STATUS planners\[[01]\].planner_id=$planner\$' '$work/spy.log' &&
           grep -Eq '^probe: MPB_STATUS planners\[[01]\].name=ompl\$' '$work/spy.log'"
# The last status: done, with the database's counts.
last=$work/last_status
awk '/^probe: MPB_STATUS type=/ { n++ } { if (/^probe: MPB_STATUS /) block[n] = block[n] $0 "\n" }
     END { printf "%s", block[n] }' "$work/spy.log" >"$last"
check "the last status says done" grep -q '^probe: MPB_STATUS state=done$' "$last"
check "... with every run done" grep -q "^probe: MPB_STATUS runs_done=$total\$" "$last"
check "... and the database's successes" \
    grep -q "^probe: MPB_STATUS runs_succeeded=$succeeded\$" "$last"
check "... and no rejected messages" \
    grep -q '^probe: MPB_STATUS rejected_messages=0$' "$last"
check "the probe never failed" sh -c "! grep -q '^probe: failed' '$work/spy.log'"
echo "# snapshots taken again (lcm-spy changing its table meanwhile):" \
    "$(grep -c '^probe: retry' "$work/spy.log")"
grep -E '^probe: (retry|failed)' "$work/spy.log" | sort | uniq -c | head -5 | sed 's/^/# /'

mpb_finish
