#!/bin/sh
# A planner that takes longer to build its model than the time limit and
# its grace (a library loading meshes on a loaded machine) is not a crash
# when it says so. A planner of the test's own on the Python kit, the
# real daemon, LCM in a private network namespace, one experiment with
# a 1 s limit (so 6 s from request to deadline without a setup), two
# configurations, one run each, no retries:
# - "told": limits.setting_up(), 8 s of building, limits.planning(), a
#   straight line: stored solved and valid, with its world_setup_time, and
#   its daemon's wall time counts the build (the deadline waited for it);
# - "silent": the same 8 s without a word: a crash at the deadline, as
#   before, so the grace still bounds a planner that says nothing;
# - "hasty": PLANNING at once, then 8 s of "planning": a crash too, the
#   limit running from PLANNING;
# - and the C kit's the same: mpb-planner-null with its "setup" of 8 s
#   (mpb_solve_setting_up(), mpb_solve_planning()) stored solved.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
daemon=$MPB_BUILD/daemon/mpbenchd
python=$MPB_SOURCE/.venv/bin/python3
kitpath=$MPB_SOURCE/planners/python:$MPB_BUILD/lcmtypes/python

cat >"$work/slow.py" <<'EOT'
import time
from mpb import named_value_t, plan_result_t, stage_t
from mpbplanner.node import Node

BUILD_S = 8.0

def solve(req, limits):
    t0 = time.monotonic()
    if req.algorithm == "told":
        limits.setting_up()
    elif req.algorithm == "hasty":
        limits.planning()
    time.sleep(BUILD_S)
    if req.algorithm == "told":
        limits.planning()
    res = plan_result_t()
    st = stage_t()
    st.name, st.num_waypoints, st.num_joints = "raw", 2, req.num_joints
    st.waypoints = list(req.start) + list(req.goal.joints)
    st.num_values = len(st.waypoints)
    st.time = 0.001
    setup = named_value_t()
    setup.name, setup.value = "world_setup_time", time.monotonic() - t0
    res.status, res.stages, res.num_stages = plan_result_t.SOLVED, [st], 1
    res.values, res.num_values = [setup], 1
    res.time_total = 0.001
    return res

Node("slow", ["told", "silent", "hasty"], "", verbose=True).serve(solve)
EOT
mpb_planar_experiment "$work/slow.yaml" \
    "name: slow, runs: 1, time_limit: 1, retries: 0" \
    "{planner: slow, algorithms: [told, silent, hasty]}" \
    "{planner: null, algorithms: [straight_line], params: {setup: 8}}"
"$MPB_BUILD/planners/null/mpb-planner-null" >"$work/null.log" 2>&1 &
MPB_PIDS="$MPB_PIDS $!"
PYTHONPATH=$kitpath "$python" "$work/slow.py" >"$work/planner.log" 2>&1 &
MPB_PIDS="$MPB_PIDS $!"
DB=$work/slow.db
"$daemon" -d "$DB" "$work/slow.yaml" >"$work/daemon.log" 2>&1 &
mpb_wait $! 90
check "the experiment completes" eq $? 0
run() { q "SELECT r.$1 FROM runs r JOIN planner_configs c ON c.id = r.planner_config_id
           WHERE c.algorithm = '$2' AND r.state = 'done'"; }
check "told: 8 s of setup said, stored solved ($(run status told): $(run message told))" \
    test "$(run status told)" = solved
check "told: ... its path verified valid" \
    eq "$(q "SELECT count(*) FROM runs r JOIN planner_configs c ON c.id = r.planner_config_id
             JOIN stages s ON s.run_id = r.id
             WHERE c.algorithm = 'told' AND s.verdict = 'valid'")" 1
check "told: ... the daemon waited for the build ($(run wall_time told) s)" \
    awk -v w="$(run wall_time told)" 'BEGIN { exit !(w >= 8) }'
check "silent: 8 s without a word is a crash at the deadline ($(run message silent))" \
    sh -c 'test "$1" = crash && printf "%s" "$2" | grep -q "no result within the time limit and grace"' \
    _ "$(run status silent)" "$(run message silent)"
check "hasty: planning said at once, then 8 s: a crash too ($(run status hasty))" \
    test "$(run status hasty)" = crash
check "C kit: 8 s of setup said, stored solved ($(run status straight_line): $(run message straight_line))" \
    test "$(run status straight_line)" = solved
check "C kit: ... its world_setup_time kept ($(run world_setup_time straight_line) s)" \
    awk -v w="$(run world_setup_time straight_line)" 'BEGIN { exit !(w >= 8) }'
[ "$FAILS" -eq 0 ] || tail -n 20 "$work/daemon.log" "$work/planner.log"
mpb_finish
