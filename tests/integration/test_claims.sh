#!/bin/sh
# Claims in both directions, and the approach as data (issue 49, items 3
# and 4), with the real daemon, the C null and OMPL planners and a Python
# planner over LCM in a private network namespace:
# - the null planner answering FAILED or APPROXIMATE with a straight line
#   that mpbench verifies valid is stored and reported as an unclaimed
#   valid path, never a success; answering SOLVED with a line through the
#   pillar is a refused claim; s_r stays the claims confirmed;
# - the approach the OMPL planner announces (sampling) is stored, the
#   experiment file's approach: stands over it, the null planner declares
#   none; mpb report groups and labels its columns by approach;
# - a planner that announces the older message (planner_announce_v1_t,
#   no approaches) is still served, its approach unknown;
# - mpb verify decides every run as the daemon did, with the same rule;
# - a database made before the new columns is reported all the same.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
DB=$work/claims.db
daemon=$MPB_BUILD/daemon/mpbenchd
mpb=$MPB_BUILD/tools/mpb
python=$MPB_SOURCE/.venv/bin/python3
kitpath=$MPB_SOURCE/planners/python:$MPB_BUILD/lcmtypes/python

MPB_QUERIES='{name: over_the_pillar, start: [0, 0, 0], goal: [2.6, 0, 0], tolerance: 0.01}
             {name: small_move, start: [0, 0, 0], goal: [0.3, -0.2, 0.1], tolerance: 0.01}' \
mpb_planar_experiment "$work/exp.yaml" "name: claims, runs: 1, time_limit: 5, seed: 3" \
    "{planner: null, algorithms: [straight_line], params: {status: failed}, name: failed}" \
    "{planner: null, algorithms: [straight_line], params: {status: approximate}, name: approx}" \
    "{planner: null, algorithms: [straight_line], name: solved}" \
    "{planner: old, algorithms: [line]}" \
    "{planner: ompl, algorithms: [RRT], approach: hybrid}" \
    "{planner: ompl, algorithms: [RRTConnect]}"

# A planner of before approaches: the Python kit, announcing the older
# message (planner_announce_v1_t's layout and fingerprint); built before
# attempt_id too, so it speaks that layout of the other messages
# (MPB_KIT_LAYOUT, test-only), as the daemon then sends them.
cat >"$work/old.py" <<'EOT'
import os, time
from mpb import plan_result_t, planner_announce_v1_t, stage_t
from mpbplanner import node

class OldNode(node.Node):
    def _announce(self):
        a = planner_announce_v1_t()
        a.utime = int(time.time() * 1e6)
        a.planner_id, a.name, a.host = self.planner_id, self.name, self.host
        a.pid, a.language, a.version = os.getpid(), "python", "0.0.9"
        a.heartbeat_ms = int(node.HEARTBEAT_S * 1000)
        a.algorithms, a.num_algorithms = list(self.algorithms), len(self.algorithms)
        a.capacity = 1
        with self.lock:
            a.active_runs = list(self.active)
        a.num_active = len(a.active_runs)
        self._publish(node.ANNOUNCE, a.encode())

def solve(req):
    res = plan_result_t()
    st = stage_t()
    st.name, st.num_waypoints, st.num_joints = "raw", 2, req.num_joints
    st.waypoints = list(req.start) + list(req.goal.joints)
    st.num_values = len(st.waypoints)
    res.status, res.stages, res.num_stages = plan_result_t.SOLVED, [st], 1
    return res

OldNode("old", ["line"], "").serve(solve)
EOT

mpb_spawn "$work/null.log" "$MPB_BUILD/planners/null/mpb-planner-null"
mpb_spawn "$work/ompl.log" "$MPB_BUILD/planners/ompl/mpb-planner-ompl"
PYTHONPATH=$kitpath MPB_KIT_LAYOUT=before-attempt-id "$python" "$work/old.py" \
    >"$work/old.log" 2>&1 &
MPB_PIDS="$MPB_PIDS $!"

"$daemon" -d "$DB" "$work/exp.yaml" >"$work/daemon.log" 2>&1 &
mpb_wait $! 120
status=$?
check "the experiment completes" eq "$status" 0
[ "$status" -eq 0 ] || cat "$work/daemon.log" "$work/old.log"

# outcome CONFIG QUERY: the run's stored outcome.
outcome() {
    q "SELECT r.outcome FROM runs r JOIN planner_configs c ON c.id = r.planner_config_id
       JOIN queries qu ON qu.id = r.query_id WHERE c.name = '$1' AND qu.name = '$2'"
}

# Every path verified whatever its status.
check "a FAILED answer's straight line is verified: valid" test \
    "$(q "SELECT r.status || ' ' || r.valid || ' ' || r.verdict || ' ' || r.success
          FROM runs r JOIN planner_configs c ON c.id = r.planner_config_id
          JOIN queries qu ON qu.id = r.query_id
          WHERE c.name = 'null/straight_line#failed' AND qu.name = 'small_move'")" = \
    "failed 1 valid 0"
check "... stored as an unclaimed valid path, not a success" test \
    "$(outcome null/straight_line#failed small_move)" = unclaimed_valid
check "... so is an APPROXIMATE answer's" test \
    "$(outcome null/straight_line#approx small_move)" = unclaimed_valid
check "... with the planner's own words kept" test \
    "$(q "SELECT r.message FROM runs r JOIN planner_configs c ON c.id = r.planner_config_id
          JOIN queries qu ON qu.id = r.query_id
          WHERE c.name = 'null/straight_line#approx' AND qu.name = 'small_move'")" = \
    "answered approximate as asked (parameter status)"
check "a FAILED line through the pillar: unclaimed, a collision" test \
    "$(outcome null/straight_line#failed over_the_pillar)" = unclaimed
check "a SOLVED line through the pillar is a refused claim" test \
    "$(outcome null/straight_line#solved over_the_pillar)" = refused
check "... and the SOLVED free line is verified" test \
    "$(outcome null/straight_line#solved small_move)" = verified
check "every success is a verified outcome, and the other way round" eq \
    "$(q "SELECT count(*) FROM runs WHERE (success = 1) != (outcome = 'verified')")" 0
check "the results view has the outcome" eq \
    "$(q "SELECT count(*) FROM results WHERE outcome = 'unclaimed_valid' AND success = 0")" 2

# The approach as data.
approach() {
    q "SELECT coalesce(approach, 'none') FROM planner_configs WHERE name = '$1'"
}
check "OMPL's announced approach is stored: sampling" test \
    "$(approach ompl/RRTConnect)" = sampling
check "the experiment file's approach stands over the announcement" test \
    "$(approach ompl/RRT)" = hybrid
check "the null planner declares none" test \
    "$(approach null/straight_line#solved)" = none
check "a planner announcing the older message is served" test \
    "$(q "SELECT group_concat(outcome, ' ') FROM (SELECT r.outcome FROM runs r
          JOIN planner_configs c ON c.id = r.planner_config_id
          WHERE c.name = 'old/line' ORDER BY r.query_id)")" = "refused verified"
check "... its approach unknown" test "$(approach old/line)" = none

# row LABEL: a report row's cells, single-spaced.
row() {
    grep "^$1  " "$work/report.txt" | sed "s/^$1 *//" | tr -s ' '
}
"$mpb" report "$DB" >"$work/report.txt"
check "mpb report exits 0" eq $? 0
check "... its columns grouped by approach, sampling first, none last, not by id" test \
    "$(grep '^Metric ' "$work/report.txt" | tr -s ' ')" = \
    "Metric ompl/RRTConnect ompl/RRT null/straight_line#failed null/straight_line#approx null/straight_line#solved old/line"
check "... each labelled by its approach" test "$(row Approach)" = \
    "sampling hybrid - - - -"
check "... claimed" test "$(row claimed)" = "2 2 0 0 2 2"
check "... verified" test "$(row verified)" = "2 2 0 0 1 1"
check "... refused claims" test "$(row 'refused claims')" = "0 0 0 0 1 1"
check "... unclaimed valid" test "$(row 'unclaimed valid')" = "0 0 1 1 0 0"
check "... and s_r the claims confirmed, unclaimed valid paths no success" \
    test "$(row 's_r (%)')" = "100.0 100.0 0.0 0.0 50.0 50.0"

# mpb verify decides every run again by the same rule, and agrees.
out=$("$mpb" verify "$DB")
check "mpb verify agrees with the daemon on every run: exit 0" eq $? 0
check "... and counts the same outcomes" test "$(printf '%s\n' "$out" | tail -1)" = \
    "outcomes by the success rule: unclaimed 2, verified 6, refused 2, late 0, unclaimed_valid 2; 0 runs decided otherwise than stored"

# A database made before outcome, in_time and approach (as an older
# mpbench left it), read only: the report counts the claims the same.
cp "$DB" "$work/old.db"
sqlite3 "$work/old.db" "DROP VIEW results; DROP VIEW run_summary;
    ALTER TABLE runs DROP COLUMN outcome; ALTER TABLE runs DROP COLUMN in_time;
    ALTER TABLE planner_configs DROP COLUMN approach"
chmod a-w "$work/old.db"
"$mpb" report "$work/old.db" >"$work/report.txt"
check "an older database is reported" eq $? 0
check "... with the same claims" test \
    "$(row claimed)|$(row verified)|$(row 'refused claims')|$(row 'unclaimed valid')" = \
    "0 0 2 2 2 2|0 0 1 1 2 2|0 0 1 1 0 0|1 1 0 0 0 0"
chmod u+w "$work/old.db"
out=$("$mpb" verify "$work/old.db")
check "... mpb verify agrees on it too" test "$?:$(printf '%s\n' "$out" | tail -1)" = \
    "0:outcomes by the success rule: unclaimed 2, verified 6, refused 2, late 0, unclaimed_valid 2; 0 runs decided otherwise than stored"

mpb_finish
