#!/bin/sh
# Runs go to the configurations in turn, whichever planner is free, so
# that an experiment stopped part-way is balanced: two planner families
# on one host share its one slot (runs_per_host: 1), and after about 40
# runs neither configuration is more than 2 runs ahead of the other. Then
# two planners of one family share its runs.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
daemon=$MPB_BUILD/daemon/mpbenchd
null=$MPB_BUILD/planners/null/mpb-planner-null

# experiment NAME RUNS PLANNERS...: RUNS runs of 50 ms each per
# configuration, one at a time on the host.
experiment() {
    name=$1; runs=$2; shift 2
    for p in "$@"; do     # each family name becomes its planners entry
        set -- "$@" "{planner: $p, algorithms: [straight_line], params: {delay: 0.05}}"
        shift
    done
    mpb_planar_experiment "$work/$name.yaml" \
        "name: $name, runs: $runs, time_limit: 1, runs_per_host: 1" "$@"
}

# per_config, per_planner: runs done by each, ascending, on one line (a
# configuration with none done counts 0).
per_config() {
    q "SELECT (SELECT count(*) FROM runs r WHERE r.planner_config_id = c.id
               AND r.state = 'done') AS n FROM planner_configs c ORDER BY n" |
        tr '\n' ' '
}
per_planner() {
    q "SELECT count(*) AS n FROM runs WHERE state = 'done'
       GROUP BY planner_id ORDER BY n" | tr '\n' ' '
}

# Wait (at most 10 s) until every planner log named says it serves: on a
# loaded machine a planner process may start late, and the runs before
# it is up go to the others, as they should, unbalancing the count.
serving() {
    for log in "$@"; do
        ticks=1000
        while ! grep -q "serving as" "$log" 2>/dev/null && [ "$ticks" -gt 0 ]; do
            sleep 0.01
            ticks=$((ticks - 1))
        done
    done
}

# 1. Families "one" and "two" on one host, the host's slot shared: the
# daemon is stopped (SIGINT) after about 2 s, some 40 runs.
experiment families 100 one two
DB=$work/families.db
mpb_spawn "$work/one.log" "$null" --name one
mpb_spawn "$work/two.log" "$null" --name two
serving "$work/one.log" "$work/two.log"
"$daemon" -d "$DB" "$work/families.yaml" >"$work/families.log" 2>&1 &
pid=$!
mpb_wait_count "$DB" 40 10 "SELECT count(*) FROM runs WHERE state = 'done'"
kill -INT $pid
mpb_wait $pid 20
check "families: stopped by SIGINT (exit 130)" eq $? 130
counts=$(per_config)
echo "# runs done per configuration: $counts"
set -- $counts
check "families: neither configuration is more than 2 runs ahead (done: $counts)" \
    test $(($2 - $1)) -le 2
check "families: about 40 runs done in all" ge $(($1 + $2)) 30
mpb_stop_all

# 2. Two planners of family "null" on one host: they take its slot in
# turn.
experiment pair 40 null
DB=$work/pair.db
mpb_spawn "$work/pair1.log" "$null"
mpb_spawn "$work/pair2.log" "$null"
serving "$work/pair1.log" "$work/pair2.log"
"$daemon" -d "$DB" "$work/pair.yaml" >"$work/pair.log" 2>&1 &
mpb_wait $! 60
check "pair: the experiment completes" eq $? 0
counts=$(per_planner)
echo "# runs done per planner: $counts"
set -- $counts
check "pair: both planners planned runs" eq $# 2
check "pair: each planned at least 15 of the 40 (done: $counts)" ge "$1" 15
mpb_finish
