#!/bin/sh
# Planners that misbehave as a planner's first version does, and what the
# daemon makes of them:
#   1. a run that hangs past its deadline is its own configuration's crash,
#      not the next runs' on the same planner (they wait for it to stop);
#   2. a planner that never acknowledges a request is told from a slow one;
#   3. a planner that declines every request gets fewer and fewer;
#   4. an announcement with an invalid planner id is logged, with the id;
#   5. a run given up on before a daemon restart holds its planner's slot
#      after the restart too.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
daemon=$MPB_BUILD/daemon/mpbenchd
null=$MPB_BUILD/planners/null/mpb-planner-null
rogue=$MPB_BUILD/tests/mpb-test-rogue-planner

# experiment NAME TIME_LIMIT PLANNERS...: one query on the planar arm.
experiment() {
    name=$1; limit=$2; shift 2
    mpb_planar_experiment "$work/$name.yaml" "name: $name, runs: 1, time_limit: $limit" "$@"
}

# 1. One planner; the first run sleeps 12 s against a limit of 0.5 s. It
# is a crash at 5.5 s, but the planner goes on with it to 12 s: the four
# runs of the other configurations wait for it instead of being sent to
# it, and crashing one after the other, meanwhile.
experiment hang 0.5 \
    "{planner: null, algorithms: [straight_line], params: {delay: 12}, name: hang}" \
    "{planner: null, algorithms: [straight_line], runs: 2, name: quick}" \
    "{planner: null, algorithms: [straight_line], runs: 2, params: {delay: 0.01}, name: slow}"
DB=$work/hang.db
mpb_spawn "$work/hang-planner.log" "$null"
"$daemon" -d "$DB" "$work/hang.yaml" >"$work/hang.log" 2>&1 &
mpb_wait $! 60
check "hang: the experiment completes" eq $? 0
check "hang: the hung run is a crash, past its deadline" \
    eq "$(q "SELECT count(*) FROM runs r JOIN planner_configs c ON c.id = r.planner_config_id
             WHERE c.name LIKE '%#hang' AND r.status = 'crash'
               AND r.message = 'no result within the time limit and grace'")" 1
check "hang: the 4 runs of the other configurations solved, none crashed" \
    eq "$(q "SELECT count(*) FROM runs r JOIN planner_configs c ON c.id = r.planner_config_id
             WHERE c.name NOT LIKE '%#hang' AND r.status = 'solved'
               AND r.crashes = 0 AND r.attempts = 1")" 4
check "hang: the daemon says why it waits" \
    grep -q "still plans run 1, given up on at its deadline" "$work/hang.log"
check "hang: ... and when it goes on" \
    grep -q "has stopped planning run 1" "$work/hang.log"
mpb_stop_all

# 2. A planner that announces itself but never reads its request channel.
experiment deaf 0.5 "{planner: deaf, algorithms: [x]}"
DB=$work/deaf.db
mpb_spawn "$work/deaf-planner.log" "$rogue" deaf deaf@rogue:1 deaf x 12
"$daemon" -d "$DB" "$work/deaf.yaml" >"$work/deaf.log" 2>&1 &
mpb_wait $! 30
check "deaf: the experiment completes" eq $? 0
check "deaf: the crash says the request was never acknowledged" \
    eq "$(q "SELECT count(*) FROM runs WHERE message GLOB
        'request never acknowledged ([0-9]* sends): is the planner subscribed to MPB_REQUEST_deaf@rogue:1?'")" 1
mpb_stop_all

# 3. A planner that declines every request while it announces capacity 1:
# it gets a request at 0, 1, 3 and 7 s (not one a heartbeat), the daemon
# says so and why it waits; a planner that takes runs then ends it.
experiment decline 1 "{planner: null, algorithms: [straight_line]}"
DB=$work/decline.db
"$rogue" decline null@rogue:1 null straight_line 10 >"$work/decline-planner.log" 2>&1 &
declining=$!
"$daemon" -d "$DB" "$work/decline.yaml" >"$work/decline.log" 2>&1 &
d=$!
wait $declining
requests=$(cut -d' ' -f1 "$work/decline-planner.log")
echo "# the declining planner saw $requests requests in 10 s"
check "decline: 3 to 5 requests in 10 s" test "$requests" -ge 3 -a "$requests" -le 5
check "decline: the daemon does not call it closing" \
    eq "$(grep -c "is closing" "$work/decline.log")" 0
check "decline: it logs the declines in a row" \
    grep -q "declined run 1, 3 in a row, while it announces capacity 1" "$work/decline.log"
check "decline: it says why it waits" \
    grep -q "null@rogue:1 declined its last" "$work/decline.log"
mpb_spawn "$work/decline-null.log" "$null"
mpb_wait $d 30
check "decline: with a planner that takes it, the experiment completes" eq $? 0
check "decline: the run solved in one attempt" \
    eq "$(q "SELECT count(*) FROM runs WHERE status = 'solved' AND attempts = 1")" 1
mpb_stop_all

# 4. Invalid planner ids: each announcement is rejected, and said so at
# most once in 5 s, naming the id.
long=$(printf 'p%.0s' $(seq 100))
for id in "raw bad@vm:1" "$long@vm:1"; do
    experiment badid 1 "{planner: raw, algorithms: [x]}"
    mpb_spawn "$work/badid-planner.log" "$rogue" deaf "$id" raw x 3
    mpb_timeout 3 "$daemon" -d "$work/badid.db" "$work/badid.yaml" \
        >"$work/badid.log" 2>&1
    mpb_stop_all
    rm -f "$work/badid.db"
    case $id in
    raw*) want="planner id 'raw bad@vm:1' has characters outside \[A-Za-z0-9_.:@-\]" ;;
    *)    want="planner id 'pppppppppppppppppppppppppppppppppppppppp...' is 105 characters long, more than 51" ;;
    esac
    check "bad id ${id%%@*}: logged once, with why" \
        eq "$(grep -c "rejected an announcement: $want" "$work/badid.log")" 1
done

# 5. As 1, but the daemon is killed once the hung run is a crash (5.5 s),
# and started again while the planner still sleeps (to 15 s). The new
# daemon never sent that run, yet the planner says it plans it: the
# other runs wait for it instead of each waiting behind it at the planner
# past its deadline, 5.5 s, and crashing.
experiment restart 0.5 \
    "{planner: null, algorithms: [straight_line], params: {delay: 15}, name: hang}" \
    "{planner: null, algorithms: [straight_line], runs: 2, name: quick}"
DB=$work/restart.db
mpb_spawn "$work/restart-planner.log" "$null"
"$daemon" -d "$DB" "$work/restart.yaml" >"$work/restart1.log" 2>&1 &
d=$!
mpb_wait_count "$DB" 1 15 "SELECT count(*) FROM runs WHERE status = 'crash'"
kill -KILL $d
wait $d 2>/dev/null
"$daemon" -d "$DB" "$work/restart.yaml" >"$work/restart2.log" 2>&1 &
mpb_wait $! 60
check "restart: the resumed experiment completes" eq $? 0
check "restart: the 2 runs of the other configuration solved, none crashed" \
    eq "$(q "SELECT count(*) FROM runs r JOIN planner_configs c ON c.id = r.planner_config_id
             WHERE c.name NOT LIKE '%#hang' AND r.status = 'solved'
               AND r.crashes = 0 AND r.attempts = 1")" 2
check "restart: the daemon says why it waits" \
    grep -q "is planning 1 run this daemon did not send it" "$work/restart2.log"
check "restart: ... and when it goes on" \
    grep -q "has stopped planning the run this daemon did not send it" "$work/restart2.log"
mpb_stop_all

mpb_finish
