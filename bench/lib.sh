# bench/lib.sh - what the bench scripts share (POSIX sh,
# sourced, not run). The sourcing script sets src (the source tree).
#
#   bench_netns NAME      inside `unshare -n`: loopback up with a multicast
#                         route; exits, naming NAME, unless loopback is the
#                         namespace's only interface
#   bench_netns_check NAME  only the check (a namespace already set up)
#   bench_snapshot NAME DIR BINARY...  before `unshare -n`: exits, naming
#                         NAME, unless root and every BINARY is built;
#                         then copies them into DIR/bin, made anew, so a
#                         run measures one set whatever others rebuild
#   bench_program BUILD NAME  the path of bench program NAME (mpb-bench-*)
#                         in BUILD: bench/'s own build or the main one
#   PIDS, cleanup         background processes to stop: cleanup kills and
#                         waits for every pid in PIDS, then empties it
#   get KEY FIELD         a field of the RESULT line KEY in the file $RAW
#                         ("nan" if there is none)
#   calc EXPR [DIGITS]    EXPR (awk) with DIGITS decimals (default 1);
#                         "nan" if EXPR holds a "nan" (a value get did
#                         not find) or gives one
#   planners_n N          "1 null planner", "N null planners"
#   daemon_latency LOG    "median p99 runs" of mpbenchd's own latency count
#                         (us; request first sent to result committed),
#                         from its log; nothing if the log has none
#   panda_robot DIR       an experiment file's robot entry for the Panda
#                         arm in DIR (panda.urdf, panda.srdf): its seven
#                         joints, base first
#   experiment NAME RUNS RUNS_PER_HOST FILE [QUEUE_AT_PLANNER]
#                         writes the planar throughput experiment: the
#                         3-joint arm among the pillars, query small_move
#                         (a free straight line), the null planner;
#                         requests waiting at a busy planner (default 0,
#                         the daemon's)

bench_netns() { # name
    ip link set lo up && ip route add 224.0.0.0/4 dev lo || exit 1
    bench_netns_check "$1"
}

bench_netns_check() { # name
    if [ "$(ip -o link show | wc -l)" -ne 1 ]; then
        echo "$1: not in a private network namespace; refusing" >&2
        exit 1
    fi
}

bench_snapshot() { # name dir binary...
    name=$1 dir=$2
    shift 2
    [ "$(id -u)" -eq 0 ] || { echo "$name: needs root (unshare -n)" >&2; exit 1; }
    for b in "$@"; do
        [ -x "$b" ] || { echo "$name: $b not built (bench/run.sh builds it)" >&2; exit 1; }
    done
    rm -rf "$dir" && mkdir -p "$dir/bin" && cp "$@" "$dir/bin/" || exit 1
}

bench_program() { # build name
    if [ -x "$1/bench-standalone/$2" ]; then echo "$1/bench-standalone/$2"
    else echo "$1/bench/$2"; fi
}

get() { # key field
    awk -v k="$1" -v f="$2" '$1 == "RESULT" && $2 == k {
        for (i = 3; i <= NF; i++) { split($i, kv, "="); if (kv[1] == f) v = kv[2] } }
        END { print (v == "" ? "nan" : v) }' "$RAW"
}
calc() { # expr [digits]
    case $1 in
    *nan*) echo nan ;;      # a missing value: awk would take it for 0
    *) awk "BEGIN { v = $1; if (v != v) print \"nan\"; else printf \"%.${2:-1}f\", v }" ;;
    esac
}

daemon_latency() { # log
    sed -n 's/.*request sent to result committed: median \([0-9]*\) us, p99 \(over \)\{0,1\}\([0-9]*\) us (\([0-9]*\) runs).*/\1 \3 \4/p' "$1"
}

planners_n() { [ "$1" -eq 1 ] && echo "1 null planner" || echo "$1 null planners"; }

PIDS=""
cleanup() {
    # CONT: a planner held by mpb-bench-fidelity pace would not end.
    for p in $PIDS; do kill "$p" 2>/dev/null; kill -CONT "$p" 2>/dev/null; done
    for p in $PIDS; do wait "$p" 2>/dev/null; done
    PIDS=""
}

panda_robot() { # dir
    cat <<EOT
robot:
  format: urdf
  file: $1/panda.urdf
  srdf: $1/panda.srdf
  joints: [panda_joint1, panda_joint2, panda_joint3, panda_joint4,
           panda_joint5, panda_joint6, panda_joint7]
EOT
}

experiment() { # name runs runs_per_host file [queue_at_planner]
    cat >"$4" <<EOF
experiment:
  name: $1
  runs: $2
  time_limit: 1.0
  seed: 1
  runs_per_host: $3
  queue_at_planner: ${5:-0}
robot:
  format: planar
  file: $src/scenes/planar/arm3.robot
scenes:
  - name: pillars
    format: planar
    file: $src/scenes/planar/pillars.scene
    queries:
      - name: small_move
        start: [0.0, 0.0, 0.0]
        goal: [0.3, -0.2, 0.1]
        tolerance: 0.01
planners:
  - planner: null
    algorithms: [straight_line]
EOF
}
