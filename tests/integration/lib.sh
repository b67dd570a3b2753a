# lib.sh - shared by the integration tests (and tools/demo.sh): a private
# network namespace for LCM, and starting and stopping processes.
#
# Sourced, not run. Expects MPB_BUILD (the build tree), and MPB_SOURCE for
# mpb_planar_experiment.

# Re-run the calling script inside a new network namespace with only a
# loopback interface and a multicast route on it, so that LCM traffic never
# leaves this process tree. As root: `unshare -n`; otherwise a user
# namespace (`unshare -rn`) when the kernel allows it.
mpb_enter_netns() {
    if [ -z "${MPB_IN_NETNS:-}" ]; then
        export MPB_IN_NETNS=1
        if [ "$(id -u)" -eq 0 ]; then
            exec unshare -n sh "$@"
        else
            exec unshare -rn sh "$@"
        fi
    fi
    ip link set lo up
    ip route add 224.0.0.0/4 dev lo
}

# mpb_peer_data_ready [NAME...]: the robots' data and each peer's
# environment (default: every peer) are as `make deps` leaves them, or the
# test stops at once with one line saying what to run. A test does not
# install: rebuilding the kit into eight environments takes minutes, more
# than a test's time limit.
mpb_peer_data_ready() {
    if ! "$MPB_SOURCE/tools/robot_data.sh" --check >/dev/null 2>&1; then
        echo "not ok - the robots' data is missing: make deps (tools/robot_data.sh)"
        exit 1
    fi
    stale=
    for env in ${*:-$(cd "$MPB_SOURCE/planners/peers/requirements" &&
                      ls *.txt | sed 's/\.txt$//')}; do
        sh "$MPB_SOURCE/tools/peers_env.sh" --check "$env" || stale="$stale $env"
    done
    if [ -n "$stale" ]; then
        echo "not ok - .cache/peers is missing or older than the kit or its" \
             "requirements for$stale: make deps (tools/peers_env.sh)"
        exit 1
    fi
}

# mpb_peers_enter SCRIPT ARGS...: what the peer planners' tests share.
# Before the private network (no way out of it): the Panda and its
# problems, and the peers' environments. Then the network namespace;
# panda (the robot's folder) and MPB_MESH_PATH set; and the test skipped
# in a sanitized build: a sanitized libmpbench loads into Python only
# after the ASan runtime, and the libraries' wheels (their own static
# libstdc++) do not run under it (ASan's __cxa_throw interceptor finds no
# real one and aborts, seen in matplotlib's ft2font, which mplib imports).
# Their C++ is not ours to check; the plain build runs these tests.
mpb_peers_enter() {
    [ -n "${MPB_IN_NETNS:-}" ] || mpb_peer_data_ready
    mpb_enter_netns "$@"
    panda=$MPB_PANDA
    export MPB_MESH_PATH=$panda MPB_BUILD
    if ldd "$MPB_BUILD/libmpbench/libmpbench.so" 2>/dev/null | grep -q libasan; then
        echo "skipped: a sanitized build; the peers' wheels do not run under ASan"
        echo "0 passed, 0 failed, 1 skipped"
        exit 0
    fi
}

# MotionBenchMaker's Panda as tools/robot_data.sh fetches it: panda.urdf,
# panda.srdf, its meshes and problems/.
MPB_PANDA=$MPB_SOURCE/.cache/robots/vamp-planner-0.6.4/panda

# mpb_panda_robot: an experiment file's robot entry for that Panda's arm,
# its seven joints, base first; in a here-document, $(mpb_panda_robot).
mpb_panda_robot() {
    cat <<EOT
robot:
  format: urdf
  file: $MPB_PANDA/panda.urdf
  srdf: $MPB_PANDA/panda.srdf
  joints: [panda_joint1, panda_joint2, panda_joint3, panda_joint4,
           panda_joint5, panda_joint6, panda_joint7]
EOT
}

# mpb_ball_robot FILE: a ball of radius 2 cm on prismatic joints x, y, z
# (each -1 .. 1 m), as URDF: the smallest robot that meets a scene.
mpb_ball_robot() {
    cat >"$1" <<'EOT'
<robot name="ball"><link name="base"/><link name="lx"/><link name="ly"/>
<link name="ball"><collision><geometry><sphere radius="0.02"/></geometry></collision></link>
<joint name="x" type="prismatic"><parent link="base"/><child link="lx"/><axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
<joint name="y" type="prismatic"><parent link="lx"/><child link="ly"/><axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
<joint name="z" type="prismatic"><parent link="ly"/><child link="ball"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
EOT
}

# mpb_need_hub: skip the test (exit 0, saying why) unless java and
# lcm.jar (Debian's liblcm-java), which lcm-java's TCP hub needs, are here.
mpb_need_hub() {
    if ! [ -r /usr/share/java/lcm.jar ] || ! command -v java >/dev/null; then
        echo "skipped: needs java and lcm.jar (liblcm-java) for the hub"
        echo "0 passed, 0 failed, 1 skipped"
        exit 0
    fi
}

# mpb_no_multicast: after mpb_enter_netns, take the multicast route away:
# the namespace can reach other processes through a hub (tcpq://) only.
mpb_no_multicast() {
    ip route del 224.0.0.0/4 dev lo
}

# mpb_spawn_hub LOG [PORT]: start lcm-java's TCP hub on PORT (default
# 7700), its heap bounded, appending to LOG; remember it; its pid in
# MPB_HUB_PID.
mpb_spawn_hub() {
    java -Xmx128m -cp /usr/share/java/lcm.jar lcm.lcm.TCPService "${2:-7700}" \
        >>"$1" 2>&1 &
    MPB_HUB_PID=$!
    MPB_PIDS="$MPB_PIDS $MPB_HUB_PID"
}

MPB_PIDS=""

# mpb_kit_env: the environment a test's own script on the Python kit needs
# to load the build's libmpbench (its authentication and hub link), as the
# launcher planners/python/mpb-planner-python does: the kit and the types
# on PYTHONPATH, MPB_LIBMPBENCH, and under AddressSanitizer its runtime
# first. Words for env: `env $(mpb_kit_env) "$python" script.py ...`.
mpb_kit_env() {
    lib=$MPB_BUILD/libmpbench/libmpbench.so
    echo "PYTHONPATH=$MPB_SOURCE/planners/python:$MPB_BUILD/lcmtypes/python"
    echo "MPB_LIBMPBENCH=$lib"
    asan=$(ldd "$lib" 2>/dev/null | awk '/libasan/ {print $3; exit}')
    [ -z "$asan" ] ||
        echo "LD_PRELOAD=$asan ASAN_OPTIONS=detect_leaks=0:allocator_may_return_null=1"
}

# Start a command in the background, its output to a log file; remember it.
# mpb_spawn LOG CMD...: CMD in the background, its output in LOG, stopped
# by mpb_stop_all; its pid in MPB_SPAWNED.
mpb_spawn() {
    log=$1; shift
    "$@" >"$log" 2>&1 &
    MPB_SPAWNED=$!
    MPB_PIDS="$MPB_PIDS $MPB_SPAWNED"
}

# mpb_stall_hub LOG: a client of the hub at 127.0.0.1:7700 that subscribes
# to every channel and never reads (tests/tools/stall_client.py), which
# blocks lcm-java's hub once its buffers fill; mpb_unstall_hub ends it.
mpb_stall_hub() {
    mpb_spawn "$1" python3 "$MPB_SOURCE/tests/tools/stall_client.py" \
        127.0.0.1 7700 200
    MPB_STALLER=$MPB_SPAWNED
}

mpb_unstall_hub() {
    kill "$MPB_STALLER" 2>/dev/null
    wait "$MPB_STALLER" 2>/dev/null
}

mpb_stop_all() {
    for pid in $MPB_PIDS; do
        kill "$pid" 2>/dev/null || true
    done
    for pid in $MPB_PIDS; do
        wait "$pid" 2>/dev/null || true
    done
    MPB_PIDS=""
}

# Wait at most SECONDS for the background process PID to end by itself,
# then kill it; returns its exit status (137 if it had to be killed).
mpb_wait() {
    pid=$1
    tenths=$(($2 * 10))
    while kill -0 "$pid" 2>/dev/null && [ "$tenths" -gt 0 ]; do
        sleep 0.1
        tenths=$((tenths - 1))
    done
    kill -KILL "$pid" 2>/dev/null
    wait "$pid"
}

# mpb_wait_listening PID [SECONDS]: wait (default 10 s) until the process
# PID, or one it started (within three generations: a backgrounded
# mpb_timeout, script(1)), has a UDP socket bound: an LCM process that
# subscribes at start (mpb status) then hears every message from here
# on, which a sleep cannot promise on a loaded machine. 1 if none has.
mpb_wait_listening() {
    hundredths=$((${2:-10} * 100))
    while [ "$hundredths" -gt 0 ]; do
        family=$1 generation=$1
        for _ in 1 2 3; do
            generation=$(for p in $generation; do
                cat /proc/"$p"/task/*/children; done 2>/dev/null)
            family="$family $generation"
        done
        sockets=$(ss -uanp 2>/dev/null)
        for p in $family; do
            case $sockets in *"pid=$p,"*) return 0 ;; esac
        done
        sleep 0.01
        hundredths=$((hundredths - 1))
    done
    return 1
}

# Run a command with a time limit in seconds; its exit status, or 124.
mpb_timeout() {
    secs=$1; shift
    timeout --kill-after=5 "$secs" "$@"
}

# mpb_wait_count DB N SECONDS SQL: wait until the count SQL selects from DB
# is at least N (the database may not exist yet), looking every 0.1 s, at
# most SECONDS; 1 if it never was.
mpb_wait_count() {
    mpb_db=$1; mpb_n=$2; mpb_tenths=$(($3 * 10)); mpb_sql=$4
    while [ "$mpb_tenths" -gt 0 ]; do
        mpb_got=$(sqlite3 "$mpb_db" "$mpb_sql" 2>/dev/null)
        [ "${mpb_got:-0}" -ge "$mpb_n" ] 2>/dev/null && return 0
        sleep 0.1
        mpb_tenths=$((mpb_tenths - 1))
    done
    return 1
}

# mpb_planar_experiment FILE FIELDS PLANNER...: write an experiment file for
# the planar arm among the pillars. FIELDS is the inside of the experiment
# map ("name: x, runs: 4, time_limit: 1"), each PLANNER one entry of the
# planners list (a YAML flow map). The queries are MPB_QUERIES, one flow map
# a line, or else query "a", whose straight line is free.
mpb_planar_experiment() {
    mpb_file=$1; mpb_fields=$2; shift 2
    mpb_queries=${MPB_QUERIES:-'{name: a, start: [0, 0, 0], goal: [0.3, -0.2, 0.1], tolerance: 0.01}'}
    cat >"$mpb_file" <<EOT
experiment: {$mpb_fields}
robot: {format: planar, file: $MPB_SOURCE/scenes/planar/arm3.robot}
scenes:
  - name: pillars
    format: planar
    file: $MPB_SOURCE/scenes/planar/pillars.scene
    queries:
$(printf '%s\n' "$mpb_queries" | sed 's/^[[:space:]]*/      - /')
planners:
$(printf '  - %s\n' "$@")
EOT
}

# mpb_paper_quick_experiment FILE: the paper's quick suite (the PR2 in its
# four environments, every query) at one run a query and a 1 s limit, up
# to its planners: key, for the caller to append its planner entries to.
mpb_paper_quick_experiment() {
    sed -n '1,/^planners:/p' "$MPB_SOURCE/scenes/experiments/paper-quick.yaml" |
        sed -e 's#file: \.\./#file: '"$MPB_SOURCE/scenes"'/#' \
            -e 's/^  runs: 3/  runs: 1/' \
            -e 's/^  time_limit: 10.0/  time_limit: 1.0/' >"$1"
}

FAILS=0
PASSES=0

# check NAME CONDITION...: evaluate a test condition, count and report it.
check() {
    name=$1; shift
    if "$@"; then
        PASSES=$((PASSES + 1))
        echo "ok - $name"
    else
        FAILS=$((FAILS + 1))
        echo "not ok - $name"
    fi
}

# Compare two integers: eq A B
eq() { [ "$1" -eq "$2" ]; }
ge() { [ "$1" -ge "$2" ]; }

# One value from the database.
q() { sqlite3 "$DB" "$1"; }

mpb_finish() {
    mpb_stop_all
    echo "$PASSES passed, $FAILS failed"
    [ "$FAILS" -eq 0 ]
}
