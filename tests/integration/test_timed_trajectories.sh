#!/bin/sh
# Timed trajectories (docs/protocol.md, docs/metrics.md): a stage may carry
# the time of every waypoint. The null planner's straight line across the
# PR2 test arm (tests/support/data/pr2_right_arm.urdf; r_shoulder_pan_joint
# from -1.2 to 0.5 rad, its URDF velocity limit 2.088 rad/s), in an empty
# scene, timed by its "duration" parameter:
#   fast      0.5 s: 3.4 rad/s, 1.63 times the limit: refused with
#             velocity_limit, no success, the limit named in the message;
#   slow      2 s in 5 waypoints: 0.85 rad/s: valid, a success, its times,
#             duration and largest velocity stored;
#   untimed   no times: valid, no timed metric, no times stored;
#   backwards times decreasing: refused with bad_times, naming the stage.
# A planner built before waypoint times (the Python kit with bindings
# generated from the layout before them, lcmtypes/*_v1_t.lcm, and so
# before attempt_id too) is still read: its run a verified success, untimed, nothing rejected. `mpb verify`
# reaches the same verdicts again from the stored times.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
DB=$work/test.db
data=$MPB_SOURCE/tests/support/data

printf 'empty\n.\n' >"$work/empty.scene"
cat >"$work/timed.yaml" <<EOT
experiment: {name: timed, time_limit: 10, seed: 5}
robot:
  format: urdf
  file: $data/pr2_right_arm.urdf
  srdf: $data/pr2_right_arm.srdf
  joints: [r_shoulder_pan_joint, r_shoulder_lift_joint, r_upper_arm_roll_joint, r_elbow_flex_joint, r_forearm_roll_joint, r_wrist_flex_joint, r_wrist_roll_joint]
scenes:
  - name: empty
    format: moveit-scene
    file: $work/empty.scene
    queries:
      - {name: across, start: [-1.2, 0, 0, 0, 0, 0, 0], goal: [0.5, 0, 0, 0, 0, 0, 0]}
planners:
  - {planner: null, algorithms: [straight_line], params: {duration: 0.5}, name: fast}
  - {planner: null, algorithms: [straight_line], params: {duration: 2, waypoints: 5}, name: slow}
  - {planner: null, algorithms: [straight_line], name: untimed}
  - {planner: null, algorithms: [straight_line], params: {duration: -1, waypoints: 5}, name: backwards}
  - {planner: old, algorithms: [line], name: old}
EOT

# The Python kit with the bindings of the layout before waypoint times:
# stage_t and plan_result_t as they were (stage_v1_t and plan_result_v1_t,
# the attempt's id under the kit's name), every other type as it is. Such
# a planner was built before attempt_id too: the kit speaks those layouts
# (MPB_KIT_LAYOUT, test-only), its results under the fingerprint of
# plan_result_v2_t, which here is plan_result_v1_t's layout.
mkdir -p "$work/oldlcm" "$work/oldtypes"
for f in "$MPB_SOURCE"/lcmtypes/*.lcm; do
    case $(basename "$f") in
    stage_t.lcm|plan_result_t.lcm|stage_v1_t.lcm|plan_result_v1_t.lcm) ;;
    plan_result_v2_t.lcm) ;;
    *) cp "$f" "$work/oldlcm/" ;;
    esac
done
sed 's/stage_v1_t/stage_t/' "$MPB_SOURCE/lcmtypes/stage_v1_t.lcm" \
    >"$work/oldlcm/stage_t.lcm"
sed 's/plan_result_v1_t/plan_result_t/; s/stage_v1_t/stage_t/; s/run_id;/attempt_id;/' \
    "$MPB_SOURCE/lcmtypes/plan_result_v1_t.lcm" >"$work/oldlcm/plan_result_t.lcm"
sed 's/plan_result_v1_t/plan_result_v2_t/; s/stage_v1_t/stage_t/' \
    "$MPB_SOURCE/lcmtypes/plan_result_v1_t.lcm" >"$work/oldlcm/plan_result_v2_t.lcm"
lcm-gen -p --ppath "$work/oldtypes" "$work/oldlcm"/*.lcm >/dev/null
python=$MPB_SOURCE/.venv/bin/python3
oldpath=$MPB_SOURCE/planners/python:$work/oldtypes
check "the old bindings' stage_t has no times" \
    test "$(PYTHONPATH=$oldpath "$python" -c \
        'from mpb import stage_t; print(hasattr(stage_t(), "times"))')" = False
check "... and their results go under plan_result_v1_t's fingerprint" \
    test "$(PYTHONPATH=$oldpath "$python" -c \
        'from mpb import plan_result_v2_t as p; print(p._get_packed_fingerprint().hex())')" = \
         "$(PYTHONPATH=$MPB_BUILD/lcmtypes/python "$python" -c \
        'from mpb import plan_result_v1_t as p; print(p._get_packed_fingerprint().hex())')"
cat >"$work/old.py" <<'EOT'
from mpb import plan_result_t, stage_t
from mpbplanner.node import Node

def solve(req):
    n, a, b = req.num_joints, list(req.start), list(req.goal.joints)
    st = stage_t()
    st.name, st.time, st.num_waypoints, st.num_joints = "raw", 0.001, 2, n
    st.waypoints = a + b
    st.num_values = len(st.waypoints)
    res = plan_result_t()
    res.status, res.stages, res.num_stages = plan_result_t.SOLVED, [st], 1
    return res

Node("old", ["line"], "").serve(solve)
EOT

mpb_spawn "$work/null.log" "$MPB_BUILD/planners/null/mpb-planner-null"
PYTHONPATH=$oldpath MPB_KIT_LAYOUT=before-attempt-id "$python" "$work/old.py" \
    >"$work/old.log" 2>&1 &
MPB_PIDS="$MPB_PIDS $!"
mpb_timeout 120 "$MPB_BUILD/daemon/mpbenchd" -d "$DB" "$work/timed.yaml" \
    >"$work/daemon.log" 2>&1
status=$?
check "mpbenchd completes the experiment and exits 0" eq "$status" 0
[ "$status" -eq 0 ] || cat "$work/daemon.log"

# run CONFIG COLUMN: a column of the results view for that configuration.
run() { q "SELECT $2 FROM results WHERE planner LIKE '%#$1'"; }
# contains TEXT PART
contains() { case $1 in *"$2"*) return 0 ;; esac; return 1; }
# metric CONFIG NAME: a metric of its final stage, 6 digits.
metric() {
    q "SELECT printf('%.6g', m.value) FROM metrics m JOIN results r ON r.run = m.run_id
       WHERE r.planner LIKE '%#$1' AND m.stage = r.final_stage AND m.name = '$2'"
}
stage() {
    q "SELECT $2 FROM stages g JOIN results r ON r.run = g.run_id
       WHERE r.planner LIKE '%#$1'"
}

check "too fast: claimed, refused with velocity_limit" \
    test "$(run fast "claimed_success, success, verdict")" = "1|0|velocity_limit"
check "too fast: the detail names the segment, joint, velocity and limit" \
    contains "$(stage fast verdict_detail)" \
    "segment 0 (waypoints 0-1, 0 s to 0.5 s): joint r_shoulder_pan_joint at 3.4, 1.628 times its URDF velocity limit 2.088"
check "too fast: the run's message says why it is no success" \
    eq "$(q "SELECT count(*) FROM runs r JOIN planner_configs c ON c.id = r.planner_config_id
             WHERE c.name LIKE '%#fast' AND r.message LIKE '%velocity_limit%2.088%'")" 1
check "too fast: its largest velocity and its ratio to the limit are stored" \
    test "$(metric fast max_velocity) $(metric fast velocity_limit_ratio)" = \
        "3.4 1.62835"

check "within the limits: a verified success" \
    test "$(run slow "claimed_success, success, verdict")" = "1|1|valid"
check "within the limits: its 5 times are stored (40 bytes)" \
    eq "$(stage slow "length(times)")" 40
check "within the limits: duration 2 s" test "$(metric slow duration)" = 2
check "within the limits: largest velocity 0.85 rad/s" \
    test "$(metric slow max_velocity)" = 0.85
check "within the limits: no acceleration between its equal segments, but rounding" \
    eq "$(q "SELECT count(*) FROM metrics m JOIN results r ON r.run = m.run_id
             WHERE r.planner LIKE '%#slow' AND m.name = 'max_acceleration'
               AND abs(m.value) < 1e-12")" 1

check "untimed: a verified success" \
    test "$(run untimed "success, verdict")" = "1|valid"
check "untimed: no times stored" eq "$(stage untimed "times IS NULL")" 1
check "untimed: no timed metric" \
    eq "$(q "SELECT count(*) FROM metrics m JOIN results r ON r.run = m.run_id
             WHERE r.planner LIKE '%#untimed'
               AND m.name IN ('duration', 'max_velocity', 'max_acceleration',
                              'velocity_limit_ratio')")" 0

check "times decreasing: refused with bad_times" \
    test "$(run backwards "success, verdict")" = "0|bad_times"
check "times decreasing: the detail names the stage and the times" \
    test "$(stage backwards verdict_detail)" = \
        "stage 'raw' waypoint times: time 1 (-0.25 s) is below time 0 (0 s)"

check "the planner built before waypoint times: a verified success" \
    test "$(run old "claimed_success, success, verdict")" = "1|1|valid"
check "... its stage untimed" eq "$(stage old "times IS NULL")" 1
check "... and no message rejected" \
    eq "$(grep -c "complete: 5 runs, 3 succeeded, 0 crashed (0 rejected messages)" "$work/daemon.log")" 1

# mpb verify: the same verdicts again, times read from the database.
"$MPB_BUILD/tools/mpb" verify "$DB" >"$work/verify.log" 2>&1
vstatus=$?
check "mpb verify exits 0" eq "$vstatus" 0
check "mpb verify checks the 4 stages again (bad_times stands) and agrees" \
    contains "$(cat "$work/verify.log")" \
    "4 stages verified again; 0 stages of 0 runs changed verdict; 0 of 3 successes no longer hold"
[ "$vstatus" -eq 0 ] || cat "$work/verify.log"

mpb_finish
