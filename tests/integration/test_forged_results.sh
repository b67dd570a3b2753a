#!/bin/sh
# Forged results: one for a run id that was never sent, one for a real run
# in flight but from a planner the run did not go to, one with a malformed
# run id. All are rejected and counted; none reaches the database. Then a
# forger that is the runs' planner sends results that are wrong in every
# way a planner's can be: each stored with its reason, none a success.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
DB=$work/test.db
forge=$MPB_BUILD/tests/mpb-test-forge-result

mpb_planar_experiment "$work/exp.yaml" "name: forged, runs: 6, time_limit: 5" \
    "{planner: null, algorithms: [straight_line], params: {delay: 0.5}}"
mpb_spawn "$work/null.log" "$MPB_BUILD/planners/null/mpb-planner-null"
"$MPB_BUILD/daemon/mpbenchd" -d "$DB" "$work/exp.yaml" >"$work/daemon.log" 2>&1 &
daemon=$!

# Wait for a run in flight, then forge.
uid=""
for i in $(seq 50); do
    uid=$(q "SELECT attempt_id FROM runs WHERE state = 'sent' LIMIT 1" 2>/dev/null)
    [ -n "$uid" ] && break
    sleep 0.1
done
check "a run is in flight" test -n "$uid"

out=$("$forge" 0123456789abcdef0123456789abcdef "null@elsewhere:1")
check "a result for an unknown run id is refused" test "$out" = "acked rejected"
# (Its acknowledgement cannot be told from the one the real planner's result
# may get meanwhile; the log and the database tell what happened.)
"$forge" "$uid" "null@elsewhere:1" >/dev/null
out=$("$forge" "not-a-run-id" "null@elsewhere:1")
check "a malformed attempt id is refused too" test "$out" = "acked rejected"

mpb_wait $daemon 30
check "the experiment completes" eq $? 0
check "the daemon counted three rejected messages" \
    grep -q "(3 rejected messages)" "$work/daemon.log"
check "it logged each with its reason" \
    eq "$(grep -c 'rejected result' "$work/daemon.log")" 3
check "... the wrong planner's as such" \
    grep -q "rejected result $uid from null@elsewhere:1: sent by a planner the run did not go to" "$work/daemon.log"
check "no forged stage reached the database" \
    eq "$(q "SELECT count(*) FROM stages WHERE name = 'forged'")" 0
check "the attacked run holds the real planner's answer" \
    test "$(q "SELECT planner_id LIKE 'null@%' AND planner_id != 'null@elsewhere:1' AND message != 'forged' FROM runs WHERE attempt_id = '$uid'")" = 1
check "all six runs are solved" eq "$(q "SELECT count(*) FROM runs WHERE status = 'solved'")" 6
# The runs waited on the forger for seconds: their median is said, past
# the 65536 us where the count once stopped.
med=$(sed -n 's/.*result committed: median \([0-9]*\) us.*/\1/p' "$work/daemon.log")
check "a median latency of seconds is written in full" \
    test "${med:-0}" -gt 65536

# The forger as the runs' planner, one run per invocation, in run order.
DB=$work/shaped.db
mpb_planar_experiment "$work/shaped.yaml" "name: shaped, runs: 12, time_limit: 1" \
    "{planner: forger, algorithms: [forged]}"
"$MPB_BUILD/daemon/mpbenchd" -v -d "$DB" "$work/shaped.yaml" >"$work/shaped.log" 2>&1 &
daemon=$!
serve() { "$forge" --serve "$@" forger@forged:1 >>"$work/forger.log" 2>&1; }
serve                                                 # 1: a success
serve --status 5                                      # 2: crash, from a planner
serve --status 42                                     # 3: no such status
serve --time-total -1 --time-other 3 --stage-time -5  # 4: times that are none
serve --time-total nan                                # 5
serve --time-total 0.002 --delay 2.6                  # 6: late by the daemon's clock
serve --stages raw,raw,raw#2 --values n=10,n=20       # 7: names used twice
serve --stages ""                                     # 8: solved, no stages
serve --time-total 3                                  # 9: late by its own clock
serve --wrong-size --stages raw,final                 # 10: a stage of 4 joints
serve --status 3 --message ""                         # 11: failed, no word why
serve --time-total 0.9 --delay 0.9                    # 12: in time
mpb_wait $daemon 30
check "the shaped experiment completes" eq $? 0
run() { q "SELECT $1 FROM runs r JOIN experiments e ON e.id = r.experiment_id WHERE e.name = 'shaped' ORDER BY r.id LIMIT 1 OFFSET $(($2 - 1))"; }
check "a sound forged result is a success" test "$(run success 1)" = 1
check "... with the planner's message as it is" test "$(run message 1)" = forged
check "a planner's status crash is stored as failed" test "$(run status 2)" = failed
check "... saying why" \
    test "$(run "message LIKE 'status 5 (crash, set by the daemon alone)%; planner''s message: forged'" 2)" = 1
check "... and is no crash in the counts" grep -q "0 crashed" "$work/shaped.log"
check "a status outside the list is stored as failed" test "$(run status 3)" = failed
check "... saying why" test "$(run "message LIKE 'status 42 (no such status)%'" 3)" = 1
check "negative times are no success" test "$(run success 4)" = 0
check "... stored as NULL" \
    test "$(run "time_total IS NULL AND time_raw IS NULL AND time_other IS NULL" 4)" = 1
check "... and the stage time too" \
    test "$(q "SELECT time IS NULL FROM stages s JOIN runs r ON r.id = s.run_id WHERE r.attempt_id = '$(run attempt_id 4)'")" = 1
check "... the values sent kept in the message" \
    test "$(run "message LIKE 'time_total -1 s is negative; time_other 3 s exceeds time_total -1 s; stage 0 time -5 s is negative%'" 4)" = 1
check "a NaN time_total is no success, with its reason" \
    test "$(run "success = 0 AND message LIKE 'time_total nan s is not finite%'" 5)" = 1
check "a result late by the daemon's clock is no success" test "$(run success 6)" = 0
check "... saying so" test "$(run "message LIKE '%by the daemon''s clock%over the time limit 1 s plus 1 s slack%'" 6)" = 1
uid7=$(run attempt_id 7)
check "repeated stage names are all kept, renamed in order" \
    test "$(q "SELECT group_concat(name, ' ') FROM (SELECT name FROM stages s JOIN runs r ON r.id = s.run_id WHERE r.attempt_id = '$uid7' ORDER BY idx)")" = "raw raw#3 raw#2"
check "... each with its metrics" \
    eq "$(q "SELECT count(DISTINCT stage) FROM metrics m JOIN runs r ON r.id = m.run_id WHERE r.attempt_id = '$uid7'")" 3
check "repeated value names are all kept" \
    test "$(q "SELECT group_concat(name || '=' || value, ' ') FROM (SELECT name, value FROM planner_values v JOIN runs r ON r.id = v.run_id WHERE r.attempt_id = '$uid7' ORDER BY name)")" = "n=10.0 n#2=20.0"
check "... the renames noted" \
    test "$(run "message LIKE 'stage 1 ''raw'' stored as ''raw#3''%value 1 ''n'' stored as ''n#2''%'" 7)" = 1
check "solved with no stages says so" test "$(run "success = 0 AND message LIKE 'solved, but no stages%'" 8)" = 1
check "an honest time over the limit says so" \
    test "$(run "success = 0 AND message LIKE 'time_total 3 s exceeds the time limit 1 s%'" 9)" = 1
uid10=$(run attempt_id 10)
check "a stage of the wrong size is stored as sent" \
    test "$(q "SELECT s.verdict || ' ' || num_waypoints || ' ' || num_joints || ' ' || length(waypoints) FROM stages s JOIN runs r ON r.id = s.run_id WHERE r.attempt_id = '$uid10' AND idx = 0")" = "wrong_size 2 4 64"
check "a failure without a message gets one" \
    test "$(run message 11)" = "the planner reported failed with no message"
check "a result within the limit and its slack is a success" test "$(run success 12)" = 1
check "every run that is no success says why" \
    eq "$(q "SELECT count(*) FROM runs WHERE success = 0 AND message = ''")" 0
check "the -v log gives each run's verdict and reason" \
    grep -q "run [0-9]* forger/forged: solved, verdict valid: not a success: time_total 3 s exceeds" "$work/shaped.log"

mpb_finish
