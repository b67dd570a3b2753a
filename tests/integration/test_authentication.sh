#!/bin/sh
# Shared-secret authentication (--secret-file): a planner with the right
# secret does the runs; one with another secret cannot even join; a result
# without a tag, even one naming the right run and planner, is rejected.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
mpb_enter_netns "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
DB=$work/test.db
null=$MPB_BUILD/planners/null/mpb-planner-null
head -c 32 /dev/urandom >"$work/secret"
head -c 32 /dev/urandom >"$work/other"

mpb_planar_experiment "$work/exp.yaml" \
    "name: auth, runs: 10, time_limit: 5, runs_per_host: 2" \
    "{planner: null, algorithms: [straight_line], params: {delay: 0.1}}"
"$null" --secret-file "$work/secret" >"$work/good.log" 2>&1 &
good=$!
"$null" --secret-file "$work/other" >"$work/bad.log" 2>&1 &
bad=$!
MPB_PIDS="$good $bad"

# All along, a status of a daemon that says it started an hour before,
# "running", with a trailer whose tag is wrong: believed, it would stop
# the daemon; it is dropped, counted and logged (issue 40).
cat >"$work/forge_status.py" <<'PY'
import os, sys, time
import lcm
from mpb import daemon_status_t
m = daemon_status_t()
m.utime = int(time.time() * 1e6)
m.daemon_id = "forged-elder"
m.experiment = "auth"
m.state = "running"
m.elapsed_s = 3600.0
m.num_planners = 0
m.planners = []
data = m.encode() + os.urandom(56)
lc = lcm.LCM()
for _ in range(300):
    lc.publish("MPB_STATUS", data)
    time.sleep(0.1)
PY
PYTHONPATH="$MPB_BUILD/lcmtypes/python" "$MPB_SOURCE/.venv/bin/python3" \
    "$work/forge_status.py" &
forger=$!
MPB_PIDS="$MPB_PIDS $forger"
sleep 0.5
"$MPB_BUILD/daemon/mpbenchd" --secret-file "$work/secret" -d "$DB" \
    "$work/exp.yaml" >"$work/daemon.log" 2>&1 &
daemon=$!

uid=""
for i in $(seq 50); do
    uid=$(q "SELECT attempt_id FROM runs WHERE state = 'sent' LIMIT 1" 2>/dev/null)
    [ -n "$uid" ] && break
    sleep 0.1
done
# The right run id and the right planner, but no tag.
"$MPB_BUILD/tests/mpb-test-forge-result" "$uid" "null@$(hostname):$good" >/dev/null

mpb_wait $daemon 30
check "the experiment completes" eq $? 0
check "every run was done by the planner holding the secret" \
    eq "$(q "SELECT count(*) FROM runs WHERE status = 'solved' AND planner_id LIKE '%:$good'")" 10
check "the planner with another secret never joined" \
    sh -c "! grep -q 'planner null@.*:$bad joined' '$work/daemon.log'"
check "its messages were rejected for their tag" \
    grep -q "wrong authentication tag" "$work/daemon.log"
check "the untagged result did not reach the database" \
    eq "$(q "SELECT count(*) FROM stages WHERE name = 'forged'")" 0
check "the forged status did not stop the daemon (it completed, above)" \
    sh -c "! grep -q 'forged-elder' '$work/daemon.log'"
check "... and each copy was counted and logged as rejected" \
    grep -q "rejected a message on MPB_STATUS: a daemon status without the right tag" \
    "$work/daemon.log"

# Without the secret, the daemon hears nobody it can trust and says so.
"$MPB_BUILD/daemon/mpbenchd" --secret-file "$work/nosuch" -d "$DB" "$work/exp.yaml" \
    >"$work/missing.log" 2>&1
check "a missing secret file is refused" test $? -ne 0
check "... naming the file" grep -q "nosuch: cannot read secret" "$work/missing.log"
head -c 5 /dev/urandom >"$work/short"
"$MPB_BUILD/daemon/mpbenchd" --secret-file "$work/short" -d "$DB" "$work/exp.yaml" \
    >"$work/short.log" 2>&1
check "a secret shorter than 16 bytes is refused" grep -q "at least 16 bytes" "$work/short.log"
"$MPB_BUILD/daemon/mpbenchd" --secret-file "$work" -d "$DB" "$work/exp.yaml" \
    >"$work/dir.log" 2>&1
check "a directory given as the secret file is said to be one" \
    grep -q "^mpbenchd: $work: cannot read secret: Is a directory$" "$work/dir.log"

mpb_finish
