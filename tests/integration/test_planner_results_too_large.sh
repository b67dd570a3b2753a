#!/bin/sh
# A result too large for one LCM message (MPB_LCM_MESSAGE_MAX, 16 MiB)
# would be dropped by the daemon's socket and its run end as a crash
# after the deadline. The planner kits send a failure saying so instead,
# which the daemon stores once: the C kit (under the null planner, asked
# for 700,000 waypoints of 3 joints, 16.8 MB) and the Python kit (under a
# planner of the test's own), with and without a shared secret.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
daemon=$MPB_BUILD/daemon/mpbenchd
null=$MPB_BUILD/planners/null/mpb-planner-null
head -c 32 /dev/urandom >"$work/secret"

# The 3-joint path of N waypoints, encoded: 16.8 MB for 700,000.
mpb_planar_experiment "$work/c.yaml" "name: c, runs: 1, time_limit: 5" \
    "{planner: null, algorithms: [straight_line], params: {waypoints: 700000}, name: huge}" \
    "{planner: null, algorithms: [straight_line], params: {waypoints: 1000}, name: fine}"

# c_case NAME [DAEMON AND PLANNER ARGS]
c_case() {
    label=$1; shift
    DB=$work/$label.db
    mpb_spawn "$work/$label-planner.log" "$null" "$@"
    "$daemon" -d "$DB" "$@" "$work/c.yaml" >"$work/$label.log" 2>&1 &
    mpb_wait $! 60
    check "$label: the experiment completes" eq $? 0
    check "$label: the huge result is stored once, failed, saying why" \
        eq "$(q "SELECT count(*) FROM runs r JOIN planner_configs c ON c.id = r.planner_config_id
                 WHERE c.name LIKE '%#huge' AND r.status = 'failed' AND r.crashes = 0
                   AND r.message LIKE 'result too large: 168_____ bytes, over the 16777216-byte (16 MiB) bound of an LCM message'")" 1
    check "$label: ... and no other run of it" \
        eq "$(q "SELECT count(*) FROM runs r JOIN planner_configs c ON c.id = r.planner_config_id
                 WHERE c.name LIKE '%#huge'")" 1
    check "$label: the result of 1000 waypoints is solved" \
        eq "$(q "SELECT count(*) FROM runs r JOIN planner_configs c ON c.id = r.planner_config_id
                 WHERE c.name LIKE '%#fine' AND r.status = 'solved'")" 1
    mpb_stop_all
}
c_case c
c_case c-secret --secret-file "$work/secret"

# The Python kit, under a planner of the test's own that returns the
# straight line in as many waypoints as its "waypoints" parameter asks.
python=$MPB_SOURCE/.venv/bin/python3
cat >"$work/long.py" <<'EOT'
import sys
from mpb import plan_result_t, stage_t
from mpbplanner.auth import Auth
from mpbplanner.node import Node

def solve(req):
    m = int(next(p.value for p in req.params if p.key == "waypoints"))
    n, a, b = req.num_joints, list(req.start), list(req.goal.joints)
    st = stage_t()
    st.name, st.num_waypoints, st.num_joints = "raw", m, n
    st.waypoints = [a[j] + i / (m - 1) * (b[j] - a[j])
                    for i in range(m) for j in range(n)]
    st.num_values = len(st.waypoints)
    res = plan_result_t()
    res.status, res.stages, res.num_stages = plan_result_t.SOLVED, [st], 1
    return res

auth = Auth(sys.argv[1]) if len(sys.argv) > 1 else None
Node("long", ["line"], "", auth=auth).serve(solve)
EOT
mpb_planar_experiment "$work/py.yaml" "name: py, runs: 1, time_limit: 10" \
    "{planner: long, algorithms: [line], params: {waypoints: 700000}, name: huge}" \
    "{planner: long, algorithms: [line], params: {waypoints: 1000}, name: fine}"

# py_case NAME [SECRET FILE]
py_case() {
    label=$1; shift
    DB=$work/$label.db
    env $(mpb_kit_env) "$python" "$work/long.py" "$@" >"$work/$label-planner.log" 2>&1 &
    MPB_PIDS="$MPB_PIDS $!"
    if [ $# -gt 0 ]; then set -- --secret-file "$1"; fi
    "$daemon" -d "$DB" "$@" "$work/py.yaml" >"$work/$label.log" 2>&1 &
    mpb_wait $! 60
    check "$label: the experiment completes" eq $? 0
    check "$label: the huge result is stored once, failed, saying why" \
        eq "$(q "SELECT count(*) FROM runs r JOIN planner_configs c ON c.id = r.planner_config_id
                 WHERE c.name LIKE '%#huge' AND r.status = 'failed' AND r.crashes = 0
                   AND r.message LIKE 'result too large: 168_____ bytes, over the 16777216-byte (16 MiB) bound of an LCM message'")" 1
    check "$label: ... and no other run of it" \
        eq "$(q "SELECT count(*) FROM runs r JOIN planner_configs c ON c.id = r.planner_config_id
                 WHERE c.name LIKE '%#huge'")" 1
    check "$label: the result of 1000 waypoints is solved" \
        eq "$(q "SELECT count(*) FROM runs r JOIN planner_configs c ON c.id = r.planner_config_id
                 WHERE c.name LIKE '%#fine' AND r.status = 'solved'")" 1
    mpb_stop_all
}
py_case py
py_case py-secret "$work/secret"

mpb_finish
