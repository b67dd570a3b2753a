#!/bin/sh
# Acknowledgements ride on requests: a result the daemon has committed is
# acknowledged in the `stored` list of the next request to its planner, and
# alone on MPB_ACK_<planner_id> only when no request comes within the hold
# (the last runs). lcm-logger records the whole benchmark; the log shows
# every run acknowledged, nearly all of them on requests, and no result
# sent twice: the planner took the riding acknowledgements as such (one it
# missed would be re-sent after 0.2 s, and these runs last 0.6 s).
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
DB=$work/test.db
lcmlog=$work/bench.lcmlog
url="udpm://239.255.76.67:7667?ttl=0"
python=$MPB_SOURCE/.venv/bin/python3

mpb_planar_experiment "$work/exp.yaml" "name: acks, runs: 200, time_limit: 5" \
    "{planner: null, algorithms: [straight_line], params: {delay: 0.003}}"
mpb_spawn "$work/null.log" "$MPB_BUILD/planners/null/mpb-planner-null"
lcm-logger -q --lcm-url="$url" "$lcmlog" >"$work/logger.log" 2>&1 &
logger=$!
for i in $(seq 100); do
    [ -s "$lcmlog" ] && break
    sleep 0.1
done
check "lcm-logger records the planner's announcements" test -s "$lcmlog"

mpb_timeout 120 "$MPB_BUILD/daemon/mpbenchd" -d "$DB" "$work/exp.yaml" >"$work/daemon.log" 2>&1
check "mpbenchd completes the experiment" eq $? 0
sleep 0.5       # the last acknowledgements reach the log
kill "$logger"; wait "$logger" 2>/dev/null

cat >"$work/count.py" <<'EOT'
import sys
import lcm
from mpb import plan_request_t, plan_result_t, run_ack_t

riding, alone, results = set(), set(), []
for ev in lcm.EventLog(sys.argv[1], "r"):
    if ev.channel.startswith("MPB_REQUEST_"):
        riding.update(plan_request_t.decode(ev.data).stored)
    elif ev.channel.startswith("MPB_ACK_"):
        a = run_ack_t.decode(ev.data)
        if a.kind == run_ack_t.RESULT_STORED:
            alone.add(a.attempt_id)
    elif ev.channel == "MPB_RESULT":
        results.append(plan_result_t.decode(ev.data).attempt_id)
done = set(open(sys.argv[2]).read().split())
print(len(done), len(done - riding - alone), len(riding & done),
      len(alone & done), len(results), len(set(results)))
EOT
q "SELECT attempt_id FROM runs WHERE state = 'done'" >"$work/done.txt"
set -- $(PYTHONPATH="$MPB_BUILD/lcmtypes/python" "$python" "$work/count.py" "$lcmlog" "$work/done.txt")
check "the 200 runs are done" eq "${1:-0}" 200
check "every run was acknowledged" eq "${2:-1}" 0
check "nearly all on a request (at least 190)" ge "${3:-0}" 190
check "the last ones alone, with no request left to ride on" ge "${4:-0}" 1
check "one result per run on the network" eq "${5:-0}" 200
check "... each run's once" eq "${6:-0}" 200
mpb_finish
