#!/bin/sh
# The planner written in Python (planners/python) against the real daemon:
# its runs on the planar arm and on the PR2 with a pose-region goal are
# stored and verified valid; the same seed gives the same path; a request
# it cannot use gets INVALID_REQUEST and a malformed message changes
# nothing; with a shared secret it takes part as the C planners do. The
# kit (mpbplanner.node) under a planner of the test's own: an exception in
# its solve() and an algorithm it does not offer are answered, not fatal.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
planner=$MPB_BUILD/planners/python/mpb-planner-python
daemon=$MPB_BUILD/daemon/mpbenchd
scenes=$MPB_SOURCE/scenes
python=$MPB_SOURCE/.venv/bin/python3

MPB_QUERIES='{name: over, start: [0, 0, 0], goal: [2.6, 0, 0], tolerance: 0.01}
             {name: fold, start: [0, 0, 0], goal: [-1.2, 1.5, 1.0], tolerance: 0.01}' \
mpb_planar_experiment "$work/planar.yaml" "name: planar, runs: 5, time_limit: 5, seed: 7" \
    "{planner: python, algorithms: [RRTConnect]}"

# The PR2 in the kitchen, from the paper's first goal region.
sed -n '/^experiment:/,/^      - name: counter_front/p' \
    "$scenes/experiments/paper-demo.yaml" | sed '$d' |
    sed -e 's#file: \.\./#file: '"$scenes"'/#' -e 's/runs: 3/runs: 2/' >"$work/pr2.yaml"
cat >>"$work/pr2.yaml" <<EOT

planners:
  - {planner: python, algorithms: [RRTConnect]}
EOT

# run_experiment NAME YAML [PLANNER ARGS]: one daemon, one Python planner.
run_experiment() {
    name=$1; yaml=$2; shift 2
    mpb_spawn "$work/$name-planner.log" "$planner" -v "$@"
    "$daemon" -d "$work/$name.db" "$@" "$yaml" >"$work/$name-daemon.log" 2>&1 &
    mpb_wait $! 60
    rc=$?
    mpb_stop_all
    return $rc
}

DB=$work/planar.db
run_experiment planar "$work/planar.yaml"
check "planar: the experiment completes" eq $? 0
check "planar: 10 runs stored" eq "$(q "SELECT count(*) FROM runs WHERE state = 'done'")" 10
check "planar: every run verified valid" \
    eq "$(q "SELECT count(*) FROM runs WHERE success = 1")" 10
check "planar: the approach it announces, sampling, is stored" \
    test "$(q "SELECT approach FROM planner_configs")" = sampling
check "planar: the world's setup is reported once, by the first run" \
    eq "$(q "SELECT count(*) FROM planner_values WHERE name = 'world_setup_time'")" 1
check "planar: raw and shortcut stages" \
    eq "$(q "SELECT count(DISTINCT name) FROM stages WHERE name IN ('raw', 'shortcut')")" 2
check "planar: the shortcut stage is never longer" \
    eq "$(q "SELECT count(*) FROM metrics r JOIN metrics s ON s.run_id = r.run_id
             AND s.name = 'path_length' AND s.stage = 'shortcut'
             WHERE r.name = 'path_length' AND r.stage = 'raw'
               AND s.value > r.value + 1e-9")" 0

DB=$work/again.db
run_experiment again "$work/planar.yaml"
check "planar again: completes" eq $? 0
same=$(sqlite3 "$work/planar.db" "ATTACH '$work/again.db' AS b;
    SELECT count(*) FROM runs r JOIN stages s ON s.run_id = r.id
      JOIN b.runs r2 ON r2.seed = r.seed
      JOIN b.stages s2 ON s2.run_id = r2.id AND s2.name = s.name
     WHERE s.name = 'raw' AND s.waypoints = s2.waypoints")
check "the same seed gives the same raw path (10 of 10)" eq "$same" 10
differ=$(q "SELECT count(DISTINCT s.waypoints) FROM stages s JOIN runs r ON r.id = s.run_id
           JOIN queries qu ON qu.id = r.query_id WHERE s.name = 'raw' AND qu.name = 'fold'")
check "different seeds give different paths" ge "$differ" 2

DB=$work/pr2.db
run_experiment pr2 "$work/pr2.yaml"
check "PR2 region goal: completes" eq $? 0
check "PR2 region goal: both runs verified valid" \
    eq "$(q "SELECT count(*) FROM runs WHERE success = 1")" 2
check "PR2 region goal: the goal was a region" \
    eq "$(q "SELECT count(*) FROM queries WHERE goal_kind = 'pose_region'")" 1

# A request naming joints the robot does not have, and bytes that are no message,
# sent straight to the planner: it answers the first with INVALID_REQUEST
# and goes on announcing itself after the second.
mpb_spawn "$work/forged-planner.log" "$planner" -v
cat >"$work/forge.py" <<'EOT'
import os, sys, time
import lcm
from mpb import plan_request_t, plan_result_t, planner_announce_t
lc = lcm.LCM()
seen = {}
def on_announce(channel, data):
    a = planner_announce_t.decode(data)
    if a.name == "python":
        seen["id"] = a.planner_id
        seen["announces"] = seen.get("announces", 0) + 1
def on_result(channel, data):
    seen["status"] = plan_result_t.decode(data).status
lc.subscribe("MPB_ANNOUNCE", on_announce)
lc.subscribe("MPB_RESULT", on_result)
end = time.time() + 10
while "id" not in seen and time.time() < end:
    lc.handle_timeout(100)
robot = open(sys.argv[1]).read()
r = plan_request_t()
r.attempt_id, r.planner_id, r.algorithm = "f" * 32, seen["id"], "RRTConnect"
r.time_limit, r.seed = 1.0, 1
r.robot_format, r.robot, r.scene_format, r.scene = "planar", robot, "planar", ""
r.robot_hash = r.scene_hash = ""
r.num_joints, r.joint_names, r.start = 2, ["a", "b"], [0.0, 0.0]
r.goal.kind, r.goal.link = 0, ""
r.goal.num_joints, r.goal.joints = 2, [0.1, 0.1]
lc.publish("MPB_REQUEST_" + seen["id"], b"\x00garbage")
lc.publish("MPB_REQUEST_" + seen["id"], r.encode())
seen["announces"] = 0
end = time.time() + 3
while time.time() < end:
    lc.handle_timeout(100)
print(seen.get("status", "none"), seen["announces"])
EOT
out=$(PYTHONPATH="$MPB_BUILD/lcmtypes/python" "$python" "$work/forge.py" \
      "$scenes/planar/arm3.robot" 2>&1)
echo "# forged request: $out"
check "a request naming joints the robot lacks gets INVALID_REQUEST (4)" \
    test "${out%% *}" = 4
check "after a malformed message the planner goes on announcing" \
    test "${out##* }" -ge 3
mpb_stop_all

# The kit on its own (mpbplanner.node), as docs/writing-a-planner.md shows
# it: a solve() that raises is answered FAILED with the exception, and the
# planner goes on; a request for an algorithm it does not offer is
# INVALID_REQUEST without a call to solve(); a family the C kit would
# refuse is refused.
kitpath=$MPB_SOURCE/planners/python:$MPB_BUILD/lcmtypes/python
cat >"$work/kit.py" <<'EOT'
import sys
from mpb import plan_result_t, stage_t
from mpbplanner.node import Node

def solve(req):
    if any(p.key == "boom" for p in req.params):
        return 1 / 0
    res = plan_result_t()
    st = stage_t()
    st.name, st.num_waypoints, st.num_joints = "raw", 2, req.num_joints
    st.waypoints = list(req.start) + list(req.goal.joints)
    st.num_values = len(st.waypoints)
    res.status, res.stages, res.num_stages = plan_result_t.SOLVED, [st], 1
    return res

try:
    Node(sys.argv[1], ["line"], "")
except ValueError as e:
    print(e)
    sys.exit(2)
Node("kit", ["line"], "", verbose=True).serve(solve) if sys.argv[1] == "kit" else None
EOT
PYTHONPATH=$kitpath "$python" "$work/kit.py" "py planner" >"$work/kit-name.log" 2>&1
check "kit: Node refuses the family 'py planner' as the C kit does" \
    grep -qx "planner name 'py planner' may hold only letters, digits and '_' '.' '-'" "$work/kit-name.log"
"$planner" --name "py planner" >"$work/python-name.log" 2>&1
check "mpb-planner-python --name 'py planner' exits 2" eq $? 2
mpb_planar_experiment "$work/kit.yaml" "name: kit, runs: 2, time_limit: 2" \
    "{planner: kit, algorithms: [line], params: {boom: 1}, name: boom}" \
    "{planner: kit, algorithms: [line], name: fine}"
PYTHONPATH=$kitpath "$python" "$work/kit.py" kit >"$work/kit-planner.log" 2>&1 &
MPB_PIDS="$MPB_PIDS $!"
DB=$work/kit.db
"$daemon" -d "$DB" "$work/kit.yaml" >"$work/kit-daemon.log" 2>&1 &
mpb_wait $! 30
check "kit: the experiment completes" eq $? 0
check "kit: a solve() that raises is FAILED with the exception, not a crash" \
    eq "$(q "SELECT count(*) FROM runs r JOIN planner_configs c ON c.id = r.planner_config_id
             WHERE c.name = 'kit/line#boom' AND r.status = 'failed'
               AND r.message = 'solve() raised ZeroDivisionError: division by zero'")" 2
check "kit: ... and the planner goes on: the other runs solved" \
    eq "$(q "SELECT count(*) FROM runs r JOIN planner_configs c ON c.id = r.planner_config_id
             WHERE c.name = 'kit/line#fine' AND r.status = 'solved'")" 2
check "kit: a solve() that keeps no time gets the kit's, not 0 s" \
    eq "$(q "SELECT count(*) FROM runs r JOIN planner_configs c ON c.id = r.planner_config_id
             WHERE c.name = 'kit/line#fine' AND r.time_total > 0")" 2
check "kit: the traceback is on the planner's stderr" \
    grep -q "ZeroDivisionError" "$work/kit-planner.log"
cat >"$work/forge-kit.py" <<'EOT'
import time
import lcm
from mpb import plan_request_t, plan_result_t, planner_announce_t
lc = lcm.LCM()
seen = {}
def on_announce(channel, data):
    a = planner_announce_t.decode(data)
    if a.name == "kit":
        seen["id"] = a.planner_id
def on_result(channel, data):
    r = plan_result_t.decode(data)
    seen["answer"] = f"{r.status} {r.message}"
lc.subscribe("MPB_ANNOUNCE", on_announce)
lc.subscribe("MPB_RESULT", on_result)
end = time.time() + 10
while "id" not in seen and time.time() < end:
    lc.handle_timeout(100)
r = plan_request_t()
r.attempt_id, r.planner_id, r.algorithm = "e" * 32, seen["id"], "Nope"
r.robot_format = r.robot = r.scene_format = r.scene = ""
r.robot_hash = r.scene_hash = r.goal.link = ""
lc.publish("MPB_REQUEST_" + seen["id"], r.encode())
end = time.time() + 3
while "answer" not in seen and time.time() < end:
    lc.handle_timeout(100)
print(seen.get("answer", "none"))
EOT
out=$(PYTHONPATH=$kitpath "$python" "$work/forge-kit.py" 2>&1)
check "kit: an algorithm not offered is INVALID_REQUEST (4), solve() not called" \
    test "$out" = "4 algorithm 'Nope' not offered by this planner (offered: line)"
mpb_stop_all

# With a shared secret the planner signs and checks, as the daemon does.
head -c 32 /dev/urandom >"$work/secret"
DB=$work/secret.db
run_experiment secret "$work/planar.yaml" --secret-file "$work/secret"
check "with --secret-file: completes" eq $? 0
check "with --secret-file: 10 runs verified valid" \
    eq "$(q "SELECT count(*) FROM runs WHERE success = 1")" 10

# The kit's trailer, from the generated type's encoding, is
# docs/protocol.md's test vector (the C library's is checked by
# tests/unit/net/test_auth.c, the kit's trailer by tests/python), and a
# replay is told from a message.
cat >"$work/vector.py" <<'EOT'
import sys
from mpb import run_ack_t
from mpbplanner.auth import Auth

with open(sys.argv[1], "wb") as f:
    f.write(b"mpbench test vector secret")
a = Auth(sys.argv[1])
k = run_ack_t()
k.utime, k.attempt_id, k.sender_id, k.kind = 1, "0123456789abcdef" * 2, "null@h:1", 0
trailer = a.trailer("MPB_ACK", k.encode(), 0x0123456789abcdef, 1,
                    0xfedcba9876543210)
print(trailer.hex())
me = Auth(sys.argv[1])
sealed = a.seal("MPB_ACK", k.encode(), me.instance)
print([me.open("MPB_ACK", sealed)[0], me.open("MPB_ACK", sealed)[0],
       me.open("MPB_RESULT", sealed)[0]])
EOT
env $(mpb_kit_env) "$python" "$work/vector.py" "$work/vector-secret" >"$work/vector.out" 2>&1
check "the kit's trailer is the protocol's test vector" test "$(head -1 "$work/vector.out")" = \
    0123456789abcdef0000000000000001fedcba9876543210c2b0ff2c5bce3131db7d09628a9cfa76931dabe273dec4663ce084384854e113
check "... believed once, then a replay; on another channel a wrong tag" \
    test "$(tail -1 "$work/vector.out")" = "[0, 2, 3]"

head -c 5 /dev/urandom >"$work/short-secret"
mpb_timeout 10 "$planner" --secret-file "$work/short-secret" >"$work/short.log" 2>&1
check "a secret shorter than 16 bytes is refused, as by the C kit" \
    test $? -eq 1 -a "$(cat "$work/short.log")" = \
    "mpb-planner-python: $work/short-secret: a secret needs at least 16 bytes, this has 5"

# Memory (docs/protocol.md, "Memory"): the kit measures each run's peak
# and enforces memory_limit; a solve() past it (MemoryError) is answered
# MEMORY and the planner goes on.
mpb_planar_experiment "$work/memory.yaml" \
    "name: memory, runs: 1, time_limit: 5, memory_limit: 96" \
    "{planner: python, algorithms: [RRTConnect], name: over, params: {allocate: 400}}" \
    "{planner: python, algorithms: [RRTConnect], name: none}" \
    "{planner: python, algorithms: [RRTConnect], name: some, params: {allocate: 64}}"
DB=$work/memory.db
run_experiment memory "$work/memory.yaml"
check "memory: the experiment completes" eq $? 0
pmem() { echo "(SELECT memory FROM runs r JOIN planner_configs c
            ON c.id = r.planner_config_id WHERE c.name LIKE '%#$1')"; }
check "memory: the run past the limit is failed for memory" \
    eq "$(q "SELECT count(*) FROM runs WHERE status = 'memory'
             AND message LIKE 'out of memory (MemoryError) under the memory_limit of 96 MB'")" 1
check "memory: ... and the planner went on" \
    eq "$(q "SELECT count(*) FROM runs WHERE status = 'solved'")" 2
check "memory: every run has its peak" \
    eq "$(q "SELECT count(*) FROM runs WHERE memory > 0")" 3
check "memory: 64 MB more held, over 56 MB more peak" \
    eq "$(q "SELECT $(pmem some) - $(pmem none) > 56")" 1

mpb_finish
