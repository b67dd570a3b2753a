#!/bin/sh
# run_benchmark.sh - run one or more experiment files end to end: start the
# planner processes and the daemon, run each experiment in turn, print each
# report, stop everything. Results accumulate in one database; running the
# same command again resumes whatever was left unfinished.
#
# LCM traffic stays on this machine: as root (or where user namespaces are
# allowed) in a private network namespace; otherwise on the host's loopback
# with ttl=0, which needs a multicast route (see README). With --lcm-url (or
# MPB_LCM_URL) it runs on that URL in the host's own network instead, so
# that planners started apart and `mpb status` can join; with --hub PORT it
# also starts lcm-java's TCP hub there (docs/topology.md).
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
MPB_BUILD=${MPB_BUILD:-$root/build}

usage() {
    cat <<EOF
usage: tools/run_benchmark.sh [OPTIONS] EXPERIMENT.yaml...

Start the planners and mpbenchd, run each experiment file in turn, and
print its report. Stop with Ctrl-C; the same command resumes.

Options:
  -d, --db FILE        the results database (default: ./mpbench.db)
  -p, --planners LIST  planner processes to start, comma-separated, from
                       null, ompl, arastar, python, and the peers (each
                       of planners/peers/requirements/NAME.txt) (default:
                       those the experiment files name, of those built
                       and, for peers, installed by make deps)
  -n, --copies N       processes of each planner (default 1; more than one
                       per core skews timings)
  -f, --format FORMAT  the report's format: text, markdown, csv, latex, json
  -r, --record FILE    also record all LCM traffic with lcm-logger into
                       FILE (mpbenchd --replay rebuilds a database from it)
  -l, --logs DIR       planner and daemon logs (default: BUILD/run-logs)
  -u, --lcm-url URL    run on this LCM URL in this machine's own network
                       (default: \$MPB_LCM_URL); planners of your own and
                       'mpb status --lcm-url URL' can then join. With
                       --planners none, only your planners run.
                       tcpq://HOST:PORT joins a TCP hub (docs/topology.md)
      --hub PORT       start lcm-java's TCP hub (lcm.lcm.TCPService, from
                       liblcm-java) on PORT of this machine, its heap
                       bounded by \$MPB_HUB_HEAP (default 256m), and run on
                       it: --lcm-url defaults to tcpq://127.0.0.1:PORT, and
                       planners on other hosts join with
                       --lcm-url tcpq://THIS_HOST:PORT
  -h, --help           print this help

Without --lcm-url, as root (or where user namespaces are allowed), the
daemon and the planners run in a private network namespace of their own:
nothing outside it, not your own planners nor 'mpb status', can reach
them. Otherwise they use LCM's default URL on this machine.

Environment: MPB_BUILD, the build tree (default: build/); MPB_LCM_URL, as
--lcm-url.
EOF
}

db=$PWD/mpbench.db
planners=""
copies=1
format=text
record=""
logs=$MPB_BUILD/run-logs
lcm_url=${MPB_LCM_URL:-}
hub=""
# Option $1 needs a value: $2 is the number of words from it on.
value() {
    [ "$2" -ge 2 ] || {
        echo "run_benchmark: $1 wants a value (try --help)" >&2
        exit 2
    }
}
while [ $# -gt 0 ]; do
    case $1 in
        -d|--db|-p|--planners|-n|--copies|-f|--format|-r|--record|-l|--logs|-u|--lcm-url|--hub)
            value "$1" $# ;;
    esac
    case $1 in
        -d|--db) db=$2; shift 2 ;;
        -p|--planners) planners=$(echo "$2" | tr ',' ' '); shift 2 ;;
        -n|--copies) copies=$2; shift 2 ;;
        -f|--format) format=$2; shift 2 ;;
        -r|--record) record=$2; shift 2 ;;
        -l|--logs) logs=$2; shift 2 ;;
        -u|--lcm-url) lcm_url=$2; shift 2 ;;
        --hub) hub=$2; shift 2 ;;
        -h|--help) usage; exit 0 ;;
        --) shift; break ;;
        -*) echo "run_benchmark: unknown option '$1' (try --help)" >&2; exit 2 ;;
        *) break ;;
    esac
done
if [ $# -eq 0 ]; then
    usage >&2
    exit 2
fi
case $copies in
    ''|*[!0-9]*|0) echo "run_benchmark: --copies wants a whole number > 0" >&2; exit 2 ;;
esac
if [ -n "$hub" ]; then
    case $hub in
        ''|*[!0-9]*) echo "run_benchmark: --hub wants a port number" >&2; exit 2 ;;
    esac
    [ "$hub" -ge 1 ] && [ "$hub" -le 65535 ] ||
        { echo "run_benchmark: --hub wants a port from 1 to 65535" >&2; exit 2; }
    command -v java >/dev/null && [ -r "${MPB_LCM_JAR:-/usr/share/java/lcm.jar}" ] || {
        echo "run_benchmark: --hub needs java and lcm.jar (Debian's liblcm-java)" >&2
        exit 1
    }
    lcm_url=${lcm_url:-tcpq://127.0.0.1:$hub}
fi
# The report's format, checked by mpb report itself (it reads --format
# before --help), so that a bad one stops us before anything starts.
if ! err=$("$MPB_BUILD/tools/mpb" report --format "$format" --help 2>&1 >/dev/null); then
    echo "run_benchmark: ${err#mpb report: }" >&2
    exit 2
fi

# Absolute paths: the namespace re-runs this script from the same directory,
# but the daemon resolves nothing relative to it.
abspath() { case $1 in /*) echo "$1" ;; *) echo "$PWD/$1" ;; esac; }
db=$(abspath "$db")
[ -z "$record" ] || record=$(abspath "$record")
for f in "$@"; do
    [ -f "$f" ] || { echo "run_benchmark: $f: no such experiment file" >&2; exit 2; }
done

# lib.sh finds the robot data and scripts through MPB_SOURCE, which a
# user's shell does not set.
MPB_SOURCE=$root
. "$root/tests/integration/lib.sh"

planner_program() {
    case $1 in
        null|ompl|arastar|python) echo "$MPB_BUILD/planners/$1/mpb-planner-$1" ;;
        *)  # a peer: planners/peers/requirements/NAME.txt
            [ -f "$root/planners/peers/requirements/$1.txt" ] || return 1
            echo "$root/planners/peers/mpb-planner-$1" ;;
    esac
}

if [ "$planners" = none ]; then
    planners=" "    # the caller's own, on --lcm-url
elif [ -z "$planners" ]; then
    # The planner families the experiments name (mpbenchd --list-planners),
    # each whose program is here: a peer's when make deps made its
    # environment (tools/peers_env.sh).
    for experiment in "$@"; do
        named=$("$MPB_BUILD/daemon/mpbenchd" --list-planners "$experiment") || exit 2
        for p in $named; do
            case " $planners " in *" $p "*) continue ;; esac
            prog=$(planner_program "$p") && [ -x "$prog" ] &&
                { [ -x "$MPB_BUILD/planners/$p/mpb-planner-$p" ] ||
                  [ -x "$root/.cache/peers/$p/bin/python3" ]; } && {
                planners="$planners $p"
                continue
            }
            echo "run_benchmark: warning: $experiment names planner '$p', which is not built or installed here (make, make deps); its runs wait for one you start (--lcm-url)" >&2
        done
    done
fi
for p in $planners; do
    prog=$(planner_program "$p") || {
        echo "run_benchmark: unknown planner '$p' (null, ompl, arastar, python, or a peer of planners/peers/requirements)" >&2
        exit 2
    }
    [ -x "$prog" ] || {
        echo "run_benchmark: $prog is not built (run make)" >&2
        exit 1
    }
done

if [ -z "$lcm_url" ] &&
   { [ -n "${MPB_IN_NETNS:-}" ] || [ "$(id -u)" -eq 0 ] || unshare -rn true 2>/dev/null; }; then
    plist=$(echo $planners | tr ' ' ',')
    mpb_enter_netns "$0" -d "$db" -p "${plist:-none}" \
        -n "$copies" -f "$format" ${record:+-r "$record"} -l "$logs" -- "$@"
fi

mkdir -p "$logs"
trap mpb_stop_all EXIT INT TERM

# Planners look for a robot's meshes in MPB_MESH_PATH and ROS_PACKAGE_PATH,
# mpbenchd also beside its URDF: the planners started here get the
# experiments' robot folders after both, so that they find what mpbenchd
# finds, in the same order (docs/scenes.md).
robot_dirs=""
for experiment in "$@"; do
    dir=$("$MPB_BUILD/daemon/mpbenchd" --mesh-path "$experiment" 2>/dev/null) || dir=""
    [ -z "$dir" ] || robot_dirs=${robot_dirs:+$robot_dirs:}$dir
done
if [ -n "$robot_dirs" ]; then
    MPB_MESH_PATH=${MPB_MESH_PATH:+$MPB_MESH_PATH:}${ROS_PACKAGE_PATH:+$ROS_PACKAGE_PATH:}$robot_dirs
    export MPB_MESH_PATH
fi

if [ -n "$hub" ]; then
    echo "run_benchmark: starting the TCP hub on port $hub"
    mpb_spawn "$logs/hub.log" java -Xmx"${MPB_HUB_HEAP:-256m}" \
        -cp "${MPB_LCM_JAR:-/usr/share/java/lcm.jar}" lcm.lcm.TCPService "$hub"
    hub_pid=${MPB_PIDS##* }
    # Listening before anyone connects (they would retry, but say nothing).
    i=0
    while ! ss -ltnH "sport = :$hub" 2>/dev/null | grep -q .; do
        kill -0 "$hub_pid" 2>/dev/null && [ $i -lt 100 ] || {
            echo "run_benchmark: the hub did not start on port $hub:" >&2
            tail -n 5 "$logs/hub.log" >&2
            exit 1
        }
        sleep 0.1
        i=$((i + 1))
    done
fi
if [ -n "$record" ]; then
    echo "run_benchmark: recording LCM traffic into $record"
    mpb_spawn "$logs/lcm-logger.log" lcm-logger --quiet --force \
        ${lcm_url:+--lcm-url="$lcm_url"} "$record"
    sleep 0.5   # subscribed before the first request goes out
fi
[ -z "$lcm_url" ] || echo "run_benchmark: on LCM URL $lcm_url"
echo "run_benchmark: starting planners:${planners% } (logs in $logs)"
for p in $planners; do
    i=1
    while [ "$i" -le "$copies" ]; do
        mpb_spawn "$logs/$p-$i.log" "$(planner_program "$p")" \
            ${lcm_url:+--lcm-url "$lcm_url"}
        i=$((i + 1))
    done
done

status=0
for experiment in "$@"; do
    echo "run_benchmark: running $experiment"
    # --again: an experiment run to its end before is run once more.
    if ! "$MPB_BUILD/daemon/mpbenchd" --again ${lcm_url:+--lcm-url "$lcm_url"} \
         -d "$db" "$experiment"; then
        echo "run_benchmark: mpbenchd failed on $experiment" >&2
        status=1
        continue
    fi
    echo
    "$MPB_BUILD/tools/mpb" report --format "$format" "$db" || status=1
    echo
done
mpb_stop_all
echo "run_benchmark: results are in $db"
exit "$status"
