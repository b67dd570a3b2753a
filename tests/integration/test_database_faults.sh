#!/bin/sh
# The database failing under a running mpbenchd: its file removed or
# replaced, a write lock held by another process past the daemon's wait,
# a second daemon started on it. The daemon must stop (or refuse) with one
# line that names the file and says what happened, exit 1, never say
# "complete", and end a following `mpb status`.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; [ "$FAILS" -eq 0 ] && rm -rf "$work"' EXIT
daemon=$MPB_BUILD/daemon/mpbenchd
mpb=$MPB_BUILD/tools/mpb

# 2 queries x 60 runs of 0.05 s on one planner: about 6 s.
write_experiment() {
    MPB_QUERIES='{name: over_the_pillar, start: [0, 0, 0], goal: [2.6, 0, 0], tolerance: 0.01}
                 {name: small_move, start: [0, 0, 0], goal: [0.3, -0.2, 0.1], tolerance: 0.01}' \
    mpb_planar_experiment "$1" "name: $2, runs: 60, time_limit: 2.0, seed: 5" \
        "{planner: null, algorithms: [straight_line], params: {delay: 0.05}}"
}
write_experiment "$work/exp.yaml" faults
write_experiment "$work/other.yaml" other

mpb_spawn "$work/null.log" "$MPB_BUILD/planners/null/mpb-planner-null"

# start_daemon NAME DB: a follower, then the daemon; $daemon_pid, $follower.
start_daemon() {
    mpb_timeout 30 "$mpb" status >"$work/$1.status" 2>"$work/$1.status.err" &
    follower=$!
    mpb_wait_listening $follower
    "$daemon" -d "$2" "$work/exp.yaml" >"$work/$1.log" 2>&1 &
    daemon_pid=$!
}

# ---- the file removed ------------------------------------------------------
DB=$work/removed.db
start_daemon removed "$DB"
sleep 1.5
rm -f "$DB" "$DB-wal" "$DB-shm"
mpb_wait $daemon_pid 20
check "a daemon whose database is removed exits 1" eq $? 1
cat "$work/removed.log"
check "... saying so in one line, naming the file" \
    grep -Eq "mpbenchd: stopped with [0-9]+ runs left: $DB was removed while in use: what was written to it is lost$" "$work/removed.log"
check "... never that the experiment is complete" \
    sh -c "! grep -q complete '$work/removed.log'"
wait $follower
check "... and a following mpb status ends (exit 1)" eq $? 1
check "... saying the daemon stopped" \
    grep -q 'mpbenchd stopped before the experiment was done' "$work/removed.status.err"

# ---- the file replaced -----------------------------------------------------
DB=$work/replaced.db
start_daemon replaced "$DB"
sleep 1.5
sqlite3 "$work/another.db" "CREATE TABLE t(x)"
mv "$work/another.db" "$DB"
mpb_wait $daemon_pid 20
check "a daemon whose database is replaced exits 1" eq $? 1
cat "$work/replaced.log"
check "... saying so in one line, naming the file" \
    grep -Eq "mpbenchd: stopped with [0-9]+ runs left: $DB was replaced by another file while in use: the file written to is gone, and what was written to it lost$" "$work/replaced.log"
check "... never that the experiment is complete" \
    sh -c "! grep -q complete '$work/replaced.log'"
check "... leaving the other file as it was" \
    test "$(sqlite3 "$DB" "SELECT name FROM sqlite_master")" = t
wait $follower

# ---- a write lock held past the daemon's wait (5 s) ------------------------
DB=$work/locked.db
start_daemon locked "$DB"
sleep 1.5
(echo "BEGIN EXCLUSIVE;"; sleep 7; echo "COMMIT;") | sqlite3 "$DB"
mpb_wait $daemon_pid 20
check "a daemon held off the database for too long exits 1" eq $? 1
cat "$work/locked.log"
check "... printing the error once, naming the file" \
    eq "$(grep -c "mpbenchd: database $DB: begin: database is locked$" "$work/locked.log")" 1
check "... and nothing else about the database" \
    eq "$(grep -c "mpbenchd: database " "$work/locked.log")" 1
check "... then that it stopped and how to resume" \
    grep -Eq 'mpbenchd: stopped by a database error with [0-9]+ runs left; run the same command to resume$' "$work/locked.log"
wait $follower
check "... and a following mpb status ends (exit 1)" eq $? 1
check "... saying the daemon stopped" \
    grep -q 'mpbenchd stopped before the experiment was done' "$work/locked.status.err"
mpb_timeout 60 "$daemon" -d "$DB" "$work/exp.yaml" >"$work/locked2.log" 2>&1
check "the same command then resumes it to the end" eq $? 0
check "... every run done once" \
    eq "$(q "SELECT count(*) FROM runs WHERE state = 'done' AND attempts >= 1")" 120

# ---- a full disk --------------------------------------------------------
# A 3 MB tmpfs in a mount namespace of its own, filled while quick runs
# (one result in nearly every transaction) are stored: the commit fails.
# The runs left that the daemon names are those its resume finds to do.
MPB_QUERIES='{name: small_move, start: [0, 0, 0], goal: [0.3, -0.2, 0.1], tolerance: 0.01}' \
mpb_planar_experiment "$work/full.yaml" "name: full, runs: 3000, time_limit: 2.0" \
    "{planner: null, algorithms: [straight_line], params: {delay: 0.002}}"
mkdir "$work/small"
unshare -m sh -c '
    . "$MPB_SOURCE/tests/integration/lib.sh"
    work=$1 daemon=$2 DB=$1/small/full.db
    mount -t tmpfs -o size=3m tmpfs "$work/small" || exit 1
    "$daemon" -d "$DB" "$work/full.yaml" >"$work/full.log" 2>&1 &
    pid=$!
    mpb_wait_count "$DB" 300 30 "SELECT count(*) FROM runs WHERE state = '"'done'"'"
    dd if=/dev/zero of="$work/small/fill" bs=4k 2>/dev/null
    mpb_wait $pid 30
    echo $? >"$work/full.exit"
    rm "$work/small/fill"
    mpb_timeout 2 "$daemon" -d "$DB" "$work/full.yaml" >"$work/full2.log" 2>&1
    umount "$work/small"
' sh "$work" "$daemon"
check "a daemon whose disk is full exits 1" eq "$(cat "$work/full.exit")" 1
check "... naming the error" grep -q "commit: database or disk is full" "$work/full.log"
left=$(sed -n 's/.*stopped by a database error with \([0-9]*\) runs left.*/\1/p' "$work/full.log")
to_do=$(sed -n 's/.*(id 1): \([0-9]*\) of 3000 runs to do.*/\1/p' "$work/full2.log")
check "... and the runs left it names ($left) are those its resume does ($to_do)" \
    test -n "$left" -a "$left" = "$to_do"

# ---- a second daemon on the same database ----------------------------------
DB=$work/shared.db
start_daemon first "$DB"
sleep 1
mpb_timeout 10 "$daemon" -d "$DB" "$work/exp.yaml" >"$work/second.log" 2>&1
check "a second daemon on the same database exits 1" eq $? 1
check "... saying why in one line" test "$(cat "$work/second.log")" = \
    "mpbenchd: $DB is in use by another mpbenchd: wait for it to end, or give another --db"
mpb_timeout 10 "$daemon" -d "$DB" "$work/other.yaml" >"$work/third.log" 2>&1
check "so is one with another experiment" eq $? 1
check "... the same way" grep -q "is in use by another mpbenchd" "$work/third.log"
mpb_timeout 10 "$mpb" report "$DB" >"$work/report.out" 2>&1
check "mpb report reads the database meanwhile" eq $? 0
mpb_wait $daemon_pid 30
check "the first daemon completes the experiment" eq $? 0
wait $follower
check "... alone: each run sent once" \
    eq "$(q "SELECT count(*) FROM runs WHERE state = 'done' AND attempts = 1")" 120
mpb_timeout 60 "$daemon" -d "$DB" "$work/other.yaml" >"$work/after.log" 2>&1
check "once it has ended, another daemon takes the database" eq $? 0

mpb_finish
