#!/bin/sh
# The same mpbenchd command on a complete experiment says so in one line,
# exits 0 and runs nothing; --again runs it once more, as a new
# experiment. A daemon that cannot start LCM writes nothing.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; [ "$FAILS" -eq 0 ] && rm -rf "$work"' EXIT
DB=$work/test.db
daemon=$MPB_BUILD/daemon/mpbenchd

mpb_planar_experiment "$work/exp.yaml" "name: once, runs: 3, time_limit: 5" \
    "{planner: null, algorithms: [straight_line]}"
mpb_spawn "$work/null.log" "$MPB_BUILD/planners/null/mpb-planner-null"

mpb_timeout 60 "$daemon" -d "$DB" "$work/exp.yaml" >"$work/first.log" 2>&1
check "the experiment completes" eq $? 0
sqlite3 "$DB" .dump >"$work/before.sql"

mpb_timeout 60 "$daemon" -d "$DB" "$work/exp.yaml" >"$work/again.out" 2>"$work/again.err"
check "the same command again exits 0" eq $? 0
check "... saying in one line that it is complete" test "$(cat "$work/again.out")" = \
    "mpbenchd: $DB: experiment 'once' (id 1) is complete: 3 runs, 3 succeeded, 0 crashed, finished $(date -d @"$(q "SELECT CAST(finished AS INTEGER) FROM experiments")" '+%Y-%m-%d %H:%M'); nothing to do (--again runs it once more)"
check "... and nothing else" test ! -s "$work/again.err"
sqlite3 "$DB" .dump >"$work/after.sql"
check "... leaving the database as it was" cmp -s "$work/before.sql" "$work/after.sql"

mpb_timeout 60 "$daemon" --again -d "$DB" "$work/exp.yaml" >"$work/repeat.log" 2>&1
check "--again runs it once more" eq $? 0
check "... as a new experiment" eq "$(q "SELECT count(*) FROM experiments WHERE finished IS NOT NULL")" 2
check "... of its own runs, all done" \
    eq "$(q "SELECT count(*) FROM runs WHERE experiment_id = 2 AND status = 'solved'")" 3
mpb_timeout 60 "$daemon" -d "$DB" "$work/exp.yaml" >"$work/third.out" 2>&1
check "then the same command says the newest is complete" \
    grep -q "experiment 'once' (id 2) is complete: 3 runs" "$work/third.out"

# LCM that cannot start: nothing written, not even a new database.
mpb_timeout 60 "$daemon" -u "nosuch://x" -d "$work/new.db" "$work/exp.yaml" \
    >"$work/nolcm.log" 2>&1
check "a daemon that cannot start LCM exits 1" eq $? 1
check "... saying so" grep -q "^mpbenchd: cannot start LCM on nosuch://x" "$work/nolcm.log"
check "... creating no database" test ! -e "$work/new.db"
sqlite3 "$DB" .dump >"$work/before.sql"
mpb_timeout 60 "$daemon" --new -u "nosuch://x" -d "$DB" "$work/exp.yaml" \
    >"$work/nolcm2.log" 2>&1
check "... nor writing an experiment into one that exists" eq $? 1
sqlite3 "$DB" .dump >"$work/after.sql"
check "... which stays as it was" cmp -s "$work/before.sql" "$work/after.sql"

mpb_finish
