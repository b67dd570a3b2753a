#!/bin/sh
# A reader with no busy timeout is never refused (issue 47): 3,000 queries
# of the sqlite3 shell, as users' scripts make them (no .timeout), three
# shells at a time, while the daemon stores runs as fast as two null
# planners answer and checkpoints its WAL. Without the daemon's read lock
# on SQLite's PENDING byte (store.c, admit_readers) a shell closing while
# another opens refuses it, a few times in a thousand.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; [ -n "${KEEP:-}" ] || rm -rf "$work"' EXIT
DB=$work/test.db
null=$MPB_BUILD/planners/null/mpb-planner-null

mpb_planar_experiment "$work/exp.yaml" "name: readers, runs: 40000, time_limit: 2" \
    "{planner: null, algorithms: [straight_line], params: {waypoints: 100, delay: 0.002}}"
mpb_spawn "$work/p1.log" "$null"
mpb_spawn "$work/p2.log" "$null"
mpb_spawn "$work/daemon.log" \
    "$MPB_BUILD/daemon/mpbenchd" -d "$DB" "$work/exp.yaml"
daemon=$MPB_SPAWNED
mpb_wait_count "$DB" 50 60 "SELECT count(*) FROM runs WHERE state = 'done'"

first=$(q "SELECT count(*) FROM runs WHERE state = 'done'")
readers() {
    n=0
    while [ $n -lt 1000 ]; do
        case $((n % 3)) in
        0) sqlite3 "$DB" "SELECT count(*) FROM experiments" ;;
        1) sqlite3 "$DB" "SELECT count(*) FROM stages WHERE run_id = 1" ;;
        2) sqlite3 "$DB" "SELECT status FROM runs WHERE id = 1" ;;
        esac >/dev/null 2>>"$work/readers$1.err"
        n=$((n + 1))
    done
}
readers 1 & r1=$!
readers 2 & r2=$!
readers 3 & r3=$!
wait $r1 $r2 $r3
cat "$work"/readers?.err >"$work/readers.err"
last=$(q "SELECT count(*) FROM runs WHERE state = 'done'")
kill -INT $daemon
mpb_wait $daemon 30
check "the daemon wrote runs while the readers read" ge $((last - first)) 100
check "3,000 readers without a busy timeout: none refused" \
    eq "$(grep -c 'locked\|busy' "$work/readers.err")" 0
[ -s "$work/readers.err" ] && sort "$work/readers.err" | uniq -c | head -5
check "... nor failed otherwise" test ! -s "$work/readers.err"
mpb_finish
