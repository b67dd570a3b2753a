#!/bin/sh
# Without a secret, anybody on the network may send anything: a daemon
# that has sent requests is not stopped by a status claiming an older
# daemon on its URL (it logs it once and goes on), and what forged
# messages say reaches its log escaped, one line each, with no control
# character or terminal escape sequence of theirs.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; [ "$FAILS" -eq 0 ] && rm -rf "$work"' EXIT
DB=$work/test.db
python=$MPB_SOURCE/.venv/bin/python3

mpb_planar_experiment "$work/exp.yaml" "name: untrusted, runs: 20, time_limit: 5" \
    "{planner: null, algorithms: [straight_line], params: {delay: 0.1}}"
mpb_spawn "$work/null.log" "$MPB_BUILD/planners/null/mpb-planner-null"
"$MPB_BUILD/daemon/mpbenchd" -d "$DB" "$work/exp.yaml" >"$work/daemon.log" 2>&1 &
daemon=$!
mpb_wait_count "$DB" 3 30 "SELECT count(*) FROM runs WHERE state = 'done'"
check "the daemon is at work" eq $? 0

cat >"$work/forge.py" <<'EOT'
import time
import lcm
from mpb import daemon_status_t, plan_result_t, planner_announce_t

lc = lcm.LCM()
# A daemon that says it started a day ago, on this URL.
st = daemon_status_t()
st.utime = int(time.time() * 1e6)
st.daemon_id, st.experiment, st.state = "mpbenchd@forger:1", "x", "running"
st.elapsed_s = 86400.0
# A planner whose text would clear the screen and add a line of its own.
a = planner_announce_t()
a.utime = st.utime
a.planner_id, a.name, a.host, a.pid = "evil@h:1", "evil", "h", 1
a.language = "c\x1b[2J\nfake line\x07"
a.version, a.heartbeat_ms, a.capacity = "1", 500, 1
a.algorithms, a.num_algorithms = ["x"], 1
bad = planner_announce_t()
bad.utime = st.utime
bad.planner_id, bad.name, bad.host = "bad\x1b[31m\nid", "evil", "h"
bad.language, bad.version, bad.heartbeat_ms = "c", "1", 500
r = plan_result_t()
r.utime = st.utime
r.attempt_id, r.planner_id, r.message = "\x1b]0;title\x07", "evil@h:1", ""
for i in range(3):
    lc.publish("MPB_STATUS", st.encode())
    lc.publish("MPB_ANNOUNCE", a.encode())
    lc.publish("MPB_ANNOUNCE", bad.encode())
    lc.publish("MPB_RESULT", r.encode())
    time.sleep(0.2)
EOT
PYTHONPATH="$MPB_BUILD/lcmtypes/python" "$python" "$work/forge.py"

mpb_wait $daemon 60
check "the daemon goes on and completes its runs" eq $? 0
check "... every run solved" \
    eq "$(q "SELECT count(*) FROM runs WHERE status = 'solved'")" 20
check "it says once that it ignored the forged status" \
    eq "$(grep -c 'a status from mpbenchd@forger:1 says it started on this LCM URL before this one: ignored' "$work/daemon.log")" 1
check "the forged planner's language is shown escaped, on its line" \
    grep -qF 'planner evil@h:1 joined (c\x1b[2J\x0afake line\x07, 1 algorithm)' \
    "$work/daemon.log"
check "... so is a forged planner id" \
    grep -qF "planner id 'bad\\x1b[31m\\x0aid' has characters outside" \
    "$work/daemon.log"
check "... and a forged run id" \
    grep -qF 'rejected result \x1b]0;title\x07 from evil@h:1' "$work/daemon.log"
check "no line of the log begins with their text" \
    sh -c "! grep -q '^fake line\|^id' '$work/daemon.log'"
check "no escape or bell character reached the log" \
    sh -c "! grep -q \"\$(printf '[\\033\\007]')\" '$work/daemon.log'"

# mpb status shows a forged status's text escaped too.
cat >"$work/forge-status.py" <<'EOT'
import time
import lcm
from mpb import daemon_status_t, planner_seen_t

lc = lcm.LCM()
st = daemon_status_t()
st.daemon_id, st.experiment, st.state = "d\x1b[1m", "x\x1b[2J\nline", "running"
p = planner_seen_t()
p.planner_id, p.name = "p\x1b[31m", "n\x07"
st.planners, st.num_planners = [p], 1
for i in range(30):
    st.utime = int(time.time() * 1e6)
    lc.publish("MPB_STATUS", st.encode())
    time.sleep(0.1)
EOT
mpb_timeout 10 "$MPB_BUILD/tools/mpb" status --once >"$work/status.out" 2>&1 &
follower=$!
PYTHONPATH="$MPB_BUILD/lcmtypes/python" "$python" "$work/forge-status.py"
wait $follower
check "mpb status prints a forged status" eq $? 0
check "... with its text escaped" \
    grep -qF 'p\x1b[31m (n\x07)' "$work/status.out"
check "... and no escape or bell character of it" \
    sh -c "! grep -q \"\$(printf '[\033\007]')\" '$work/status.out'"

mpb_finish
