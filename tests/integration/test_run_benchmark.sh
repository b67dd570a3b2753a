#!/bin/sh
# tools/run_benchmark.sh, the batch script behind `make demo`: it starts the
# planners and the daemon in a namespace of its own, runs the experiment,
# prints the report and leaves the runs in the database; a second call on
# a finished experiment runs it again and keeps the first; bad options,
# options without a value, unknown formats and unknown planners are refused,
# before anything starts,
# in one line.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
DB=$work/batch.db
script=$MPB_SOURCE/tools/run_benchmark.sh
mpb_planar_experiment "$work/exp.yaml" "name: batch, runs: 4, time_limit: 2" \
    "{planner: null, algorithms: [straight_line]}" \
    "{planner: ompl, algorithms: [RRTConnect]}"

# From a user's shell: none of the test harness's MPB_SOURCE.
out=$(env -u MPB_SOURCE MPB_BUILD=$MPB_BUILD timeout --kill-after=5 120 \
      sh "$script" -d "$DB" -p null,ompl -l "$work/logs" "$work/exp.yaml" 2>&1)
check "the batch completes, started as a user starts it" eq $? 0
check "it prints the report's table" \
    sh -c "printf '%s\n' \"\$1\" | grep -q 'Scene pillars'" _ "$out"
check "all 8 runs are in the database" \
    eq "$(q "SELECT count(*) FROM runs WHERE state = 'done'")" 8
check "both planners ran" \
    eq "$(q "SELECT count(DISTINCT planner_id) FROM runs")" 2

MPB_BUILD=$MPB_BUILD mpb_timeout 120 sh "$script" -d "$DB" -p null,ompl \
    -l "$work/logs" "$work/exp.yaml" >/dev/null 2>&1
check "a second call runs the finished experiment again, as a new one" \
    eq "$(q "SELECT count(*) FROM experiments WHERE name = 'batch'")" 2
check "... and keeps the first one's runs" \
    eq "$(q "SELECT count(*) FROM runs WHERE state = 'done'")" 16

# Without --planners: the planners the experiment names, and no others
# (arastar and python are built, peers may be installed).
MPB_BUILD=$MPB_BUILD mpb_timeout 120 sh "$script" -d "$work/named.db" \
    -l "$work/named-logs" "$work/exp.yaml" >"$work/named.out" 2>&1
check "without --planners the batch completes" eq $? 0
check "... starting the planners the experiment names: $(ls "$work/named-logs" | tr '\n' ' ')" \
    test "$(ls "$work/named-logs" | grep -- '-1\.log$' | sort | tr '\n' ' ')" = "null-1.log ompl-1.log "
check "... which ran its 8 runs" \
    test "$(sqlite3 "$work/named.db" "SELECT count(*) FROM runs WHERE state = 'done'")" = 8

# --lcm-url: on the caller's own URL, in the caller's network (here a
# namespace of the test's own), where a planner started apart joins; with
# --planners none the script starts none of its own.
mpb_planar_experiment "$work/own.yaml" "name: own, runs: 3, time_limit: 2" \
    "{planner: null, algorithms: [straight_line]}"
unshare -n sh -c '
    ip link set lo up && ip route add 224.0.0.0/4 dev lo || exit 9
    url="udpm://239.255.76.67:7667?ttl=0"
    "$1/planners/null/mpb-planner-null" --lcm-url "$url" --name null >"$2/own-planner.log" 2>&1 &
    p=$!
    MPB_BUILD=$1 timeout 60 sh "$3" -u "$url" -p none -d "$2/own.db" \
        -l "$2/own-logs" "$2/own.yaml" >"$2/own.out" 2>&1
    rc=$?
    kill $p
    exit $rc' _ "$MPB_BUILD" "$work" "$script"
check "--lcm-url with --planners none: a planner of the caller's own runs the experiment" eq $? 0
check "... all 3 runs done, by that one planner" \
    test "$(sqlite3 "$work/own.db" "SELECT count(*) || ' ' || count(DISTINCT planner_id) FROM runs WHERE state = 'done'")" = "3 1"
check "... and no planner of the script's own started" \
    sh -c "! ls '$work/own-logs' | grep -q 'null-1'"
check "--help says what the private namespace keeps out" \
    sh -c "sh '$script' --help | grep -q 'not your own planners nor'"

err=$(sh "$script" --bogus "$work/exp.yaml" 2>&1)
check "an unknown option exits 2" eq $? 2
check "... in one line" eq "$(printf '%s\n' "$err" | wc -l)" 1
err=$(MPB_BUILD=$MPB_BUILD sh "$script" -p nosuch "$work/exp.yaml" 2>&1)
check "an unknown planner exits 2" eq $? 2
check "... naming it" sh -c "printf '%s\n' \"\$1\" | grep -q nosuch" _ "$err"

# Checked before anything starts: no database, no logs, at once.
err=$(MPB_BUILD=$MPB_BUILD mpb_timeout 120 sh "$script" -d "$work/never.db" -f xml \
      -l "$work/never-logs" "$work/exp.yaml" 2>&1)
check "an unknown report format exits 2" eq $? 2
check "... in one line naming it" \
    eq "$(printf '%s\n' "$err" | grep -c "unknown format 'xml'")" 1
check "... before anything ran" sh -c "! [ -e '$work/never.db' ] && ! [ -e '$work/never-logs' ]"
for opt in -d --db -p -n -f --format -r -l -u --lcm-url; do
    err=$(sh "$script" "$opt" 2>&1)
    check "$opt without a value exits 2" eq $? 2
    check "... in one line naming it" test "$err" = \
        "run_benchmark: $opt wants a value (try --help)"
done

echo "$PASSES passed, $FAILS failed"
[ "$FAILS" -eq 0 ]
