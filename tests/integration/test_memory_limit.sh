#!/bin/sh
# Memory (issue 30): every run's peak memory, as the planner process saw
# it, is stored in runs.memory and grows with what the planner allocated;
# an experiment's memory_limit is enforced by the planner kit, and a run
# that allocates past it is stored as failed for memory (status
# 'memory'), whether the planner answers so (its malloc failed) or dies
# of it (abort(), as an uncaught std::bad_alloc would: the kit's last
# words), and the runs after it go on. The report and the Planner Arena
# export carry the memory.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
DB=$work/test.db
mpb=$MPB_BUILD/tools/mpb
null=$MPB_BUILD/planners/null/mpb-planner-null

# The null planner allocates and touches "allocate" MB; the limit is 128
# MB over what the process held when the run began. The failing
# configurations come first, so that runs of the others follow them.
mpb_planar_experiment "$work/exp.yaml" \
    "name: memory, runs: 2, time_limit: 10, memory_limit: 128" \
    "{planner: null, algorithms: [straight_line], name: over, params: {allocate: 400}}" \
    "{planner: null, algorithms: [straight_line], name: dies, params: {allocate: 400, out_of_memory: abort}}" \
    "{planner: null, algorithms: [straight_line], name: small, params: {allocate: 8}}" \
    "{planner: null, algorithms: [straight_line], name: big, params: {allocate: 72}}"

"$MPB_BUILD/daemon/mpbenchd" --check "$work/exp.yaml" >/dev/null
check "mpbenchd --check takes memory_limit" eq $? 0

# A planner that dies is started again, as a supervisor would; the
# current one's pid is in null.pid.
( while :; do
      "$null" >>"$work/null.log" 2>&1 &
      echo $! >"$work/null.pid"
      wait $!
      sleep 0.1
  done ) 2>/dev/null &
loop=$!
mpb_timeout 120 "$MPB_BUILD/daemon/mpbenchd" -d "$DB" "$work/exp.yaml" \
    >"$work/daemon.log" 2>&1
status=$?
kill "$loop" 2>/dev/null; wait "$loop" 2>/dev/null
MPB_PIDS=$(cat "$work/null.pid")
check "mpbenchd completes the experiment" eq "$status" 0
[ "$status" -eq 0 ] || tail -20 "$work/daemon.log"

cfg() { echo "(SELECT id FROM planner_configs WHERE name LIKE '%#$1')"; }
check "8 runs, all done" \
    eq "$(q "SELECT count(*) FROM runs WHERE state = 'done'")" 8
check "the runs past the limit are failed for memory, none crashed" \
    eq "$(q "SELECT count(*) FROM runs WHERE status = 'memory'
             AND planner_config_id IN ($(cfg over), $(cfg dies))")" 4
check "... with no success" \
    eq "$(q "SELECT count(*) FROM runs WHERE status = 'memory' AND success = 0")" 4
check "... the ones that died say so (last words)" \
    eq "$(q "SELECT count(*) FROM runs WHERE planner_config_id = $(cfg dies)
             AND message LIKE '%planner process died (SIGABRT%memory_limit of 128 MB%'")" 2
check "... and the planner that died was another each time" \
    eq "$(q "SELECT count(DISTINCT planner_id) FROM runs
             WHERE planner_config_id = $(cfg dies)")" 2
check "the runs within the limit are solved, after the failures" \
    eq "$(q "SELECT count(*) FROM runs WHERE status = 'solved' AND success = 1
             AND finished > (SELECT min(finished) FROM runs WHERE status = 'memory')")" 4
check "every run has its peak memory" \
    eq "$(q "SELECT count(*) FROM runs WHERE memory > 0")" 8
check "... at least what the planner allocated" \
    eq "$(q "SELECT count(*) FROM runs WHERE planner_config_id = $(cfg small)
             AND memory >= 8")" 2
check "... growing with it: 64 MB more allocated, over 56 MB more memory" \
    eq "$(q "SELECT (SELECT min(memory) FROM runs WHERE planner_config_id = $(cfg big))
             - (SELECT max(memory) FROM runs WHERE planner_config_id = $(cfg small)) > 56")" 1
check "... and a run stopped by the limit went past what the others used" \
    eq "$(q "SELECT (SELECT min(memory) FROM runs WHERE planner_config_id = $(cfg over))
             > (SELECT max(memory) FROM runs WHERE planner_config_id = $(cfg big))")" 1

"$mpb" report "$DB" >"$work/report.txt" 2>&1
check "mpb report shows a memory row with numbers" \
    grep -Eq '^memory \(Mean, MB\) +[0-9]' "$work/report.txt"
"$mpb" report --format json "$DB" >"$work/report.json"
check "... JSON: memory in MB over every run of 'big'" \
    test "$(python3 -c '
import json, sys
r = json.load(open(sys.argv[1]))
p = [p for p in r["scenes"][0]["planners"] if p["name"].endswith("#big")][0]
m = p["metrics"]["memory"]
print(r["units"]["memory"], m["n"], m["mean"] > 72)' "$work/report.json")" = "MB 2 True"

"$mpb" export --planner-arena "$DB" "$work/pa.db" >/dev/null 2>&1
check "mpb export --planner-arena succeeds" eq $? 0
check "... its runs carry memory, as OMPL's Benchmark writes it" \
    eq "$(sqlite3 "$work/pa.db" "SELECT count(*) FROM runs WHERE memory > 0")" 8
check "... its experiment the limit, as OMPL's memorylimit" \
    test "$(sqlite3 "$work/pa.db" "SELECT memorylimit FROM experiments")" = 128.0
check "... and its status enum names the memory failures" \
    eq "$(sqlite3 "$work/pa.db" "SELECT count(*) FROM runs r JOIN enums e
             ON e.name = 'status' AND e.value = r.status
             WHERE e.description = 'Out of memory'")" 4

mpb_finish
