#!/bin/sh
# The peer planners (planners/peers: ompl2, roboplan, mplib,
# pybullet_planning), each a real process with its library in its own
# environment (make deps: tools/peers_env.sh), against the real daemon on
# two MotionBenchMaker Panda problems:
# - a path the library claims is verified valid by mpbench (at least one);
# - a parameter the peer does not take is answered INVALID_REQUEST with a
#   message naming it, and an unknown algorithm (which the daemon never
#   sends) too, asked of the peer's own code;
# - the planner killed with SIGKILL in the middle of a run: the run is
#   re-sent (retries: 1) to a new process and stored once;
# - every answer within the time limit plus 0.5 s: the planner's time
#   (time_total) by the daemon's record, and the daemon's wall time less
#   the world's setup, with 2 s more for a loaded machine.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
PASSES=0
FAILS=0
PEERS=${MPB_TEST_PEERS:-ompl2 roboplan mplib pybullet_planning tesseract drake klampt srmp}

mpb_peers_enter "$0" "$@"

work=$(mktemp -d)
trap 'mpb_stop_all; rm -rf "$work"' EXIT
daemon=$MPB_BUILD/daemon/mpbenchd
launcher=$MPB_SOURCE/planners/peers/mpb-planner-peer

algorithm_of() {
    case $1 in
        ompl2) echo RRTConnect ;;
        roboplan) echo RRTConnect ;;
        mplib) echo RRTConnect ;;
        pybullet_planning) echo birrt ;;
        tesseract) echo TrajOpt ;;
        drake) echo KTO ;;
        klampt) echo sbl ;;
        srmp) echo wAstar ;;
    esac
}

# A peer's parameters for the claimed-path check, where its defaults
# need more than the 3 s a loaded machine gives: drake's KTO evaluates
# its distance constraint at 25 path parameters instead of 100.
params_of() {
    case $1 in
        drake) echo ", params: {samples: '25'}" ;;
    esac
}

# experiment FILE NAME RUNS PLANNERS...: two Panda problems, the first
# table_pick's (or FIRST's: a problem set's name).
experiment() {
    f=$1; name=$2; runs=$3; shift 3
    cat >"$f" <<EOT
experiment: {name: $name, runs: $runs, time_limit: 3, seed: 5, retries: 1}
$(mpb_panda_robot)
scenes:
  - {problems: $panda/problems/${FIRST:-table_pick_panda}, count: 1, clamp_joint_values: true}
  - {problems: $panda/problems/box_panda, first: 4, count: 1, clamp_joint_values: true}
planners:
EOT
    for p in "$@"; do echo "  - $p" >>"$f"; done
}

for peer in $PEERS; do
    alg=$(algorithm_of "$peer")
    DB=$work/$peer.db
    experiment "$work/$peer.yaml" "$peer" 1 \
        "{planner: $peer, algorithms: [$alg]$(params_of "$peer")}" \
        "{planner: $peer, algorithms: [$alg], params: {bogus: 1}, name: bogus}"
    mpb_spawn "$work/$peer-planner.log" "$launcher" "$peer" -v
    mpb_timeout 120 "$daemon" -d "$DB" "$work/$peer.yaml" >"$work/$peer-daemon.log" 2>&1
    status=$?
    mpb_stop_all
    check "$peer: the experiment completes" eq "$status" 0
    [ "$status" -eq 0 ] || tail -n 20 "$work/$peer-daemon.log" "$work/$peer-planner.log"
    check "$peer: a claimed path verified valid by mpbench" \
        ge "$(q "SELECT count(*) FROM results WHERE planner = '$peer/$alg'
                 AND claimed_success = 1 AND success = 1")" 1
    check "$peer: the approach its adapter announces (APPROACH) is stored" \
        eq "$(q "SELECT count(*) FROM planner_configs WHERE name = '$peer/$alg'
                 AND approach IN ('sampling', 'search', 'optimisation', 'hybrid')")" 1
    check "$peer: an unknown parameter answered INVALID_REQUEST naming it" \
        eq "$(q "SELECT count(*) FROM results WHERE planner = '$peer/$alg#bogus'
                 AND status = 'invalid_request'
                 AND message LIKE '%unknown parameter ''bogus''%'")" 2
    check "$peer: its time_total within the time limit + 0.5 s" \
        eq "$(q "SELECT count(*) FROM runs WHERE state = 'done'
                 AND NOT time_total <= 3.5")" 0
    check "$peer: its answers within the time limit + 0.5 s (+ 2 s load)" \
        eq "$(q "SELECT count(*) FROM runs WHERE state = 'done' AND
                 wall_time - coalesce(world_setup_time, 0) > 5.5")" 0
    check "$peer: world_setup_time reported apart from time_total" \
        ge "$(q "SELECT count(*) FROM runs WHERE world_setup_time > 0")" 1

    # The peer's own code asked for an algorithm it does not offer.
    out=$(cd "$work" && PYTHONPATH=$MPB_SOURCE/planners/peers \
        MPB_LIBMPBENCH=$MPB_BUILD/libmpbench/libmpbench.so \
        "$MPB_SOURCE/.cache/peers/$peer/bin/python3" -c "
import os, sys
from mpb import plan_request_t
from mpbpeers import $peer as m, peer
req = plan_request_t()
req.algorithm = 'NoSuchPlanner'
req.params = []
res = peer.Peer(m.Adapter()).solve(req)
print(res.status, res.message)
sys.stdout.flush()
os._exit(0)" 2>&1 | tail -n 1)
    check "$peer: an unknown algorithm answered INVALID_REQUEST ($out)" \
        sh -c "printf '%s' \"\$1\" | grep -q \"^4 unknown algorithm 'NoSuchPlanner'\"" _ "$out"

    # Killed mid-run: the first request's log line, then SIGKILL. The
    # first problem is a cage's (the peers take 0.05-2.6 s there, 4 ms
    # on a table), so the kill lands before an answer; if the answer came
    # first anyway (a fast machine), the scenario is made again, at most
    # three times: what it tests needs a run in flight.
    DB=$work/$peer-kill.db
    for attempt in 1 2 3; do
        rm -f "$DB"
        FIRST=cage_panda experiment "$work/$peer-kill.yaml" "$peer-kill" 1 \
            "{planner: $peer, algorithms: [$alg]}"
        "$launcher" "$peer" -v >"$work/$peer-victim.log" 2>&1 &
        victim=$!
        "$daemon" -d "$DB" "$work/$peer-kill.yaml" >"$work/$peer-kill-daemon.log" 2>&1 &
        dpid=$!
        MPB_PIDS="$MPB_PIDS $dpid"
        ticks=3000
        while ! grep -q ": run [0-9a-f]*: $alg" "$work/$peer-victim.log" &&
              [ "$ticks" -gt 0 ]; do
            sleep 0.01
            ticks=$((ticks - 1))
        done
        kill -STOP "$victim" 2>/dev/null
        answered=$(grep -c "status" "$work/$peer-victim.log")
        kill -KILL "$victim" 2>/dev/null
        wait "$victim" 2>/dev/null
        [ "$answered" -eq 0 ] && break
        echo "# $peer answered before the kill (attempt $attempt)"
        mpb_stop_all
    done
    mpb_spawn "$work/$peer-kill-planner.log" "$launcher" "$peer" -v
    mpb_wait "$dpid" 120
    status=$?
    mpb_stop_all
    check "$peer: killed mid-run, the experiment still completes" eq "$status" 0
    check "$peer: ... the killed process had not answered" eq "$answered" 0
    resent=$(q "SELECT count(*) FROM runs WHERE state = 'done' AND attempts = 2
                AND status != 'crash'")
    check "$peer: ... its run was re-sent (2 attempts) and stored" eq "$resent" 1
    # What happened instead, to find the cause (seen once on a loaded
    # machine: 2026-12-02, drake).
    [ "$resent" = 1 ] || { q "SELECT id, attempts, crashes, status, message FROM runs";
                           tail -5 "$work/$peer-kill-daemon.log"; }
    check "$peer: ... once: 2 runs, one first stage each" \
        eq "$(q "SELECT count(*) FROM runs r WHERE state = 'done' AND
                 (status != 'solved' OR (SELECT count(*) FROM stages s
                   WHERE s.run_id = r.id AND s.name = (SELECT f.name
                   FROM stages f WHERE f.run_id = r.id AND f.idx = 0)) = 1)")" 2
done

mpb_finish
