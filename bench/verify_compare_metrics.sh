#!/bin/sh
# bench/verify_compare_metrics.sh - does this mpbench verify and measure
# the stored runs of a database as the mpbench that stored them did?
# Every stage of every finished run is measured again in process, as
# mpbenchd measures a result (mpb-bench-verifydb --compare-stored): its
# verdict (name, detail, certified or sampled) must equal the stored one
# and every metric the stored value to TOL (default 1e-9); then
# `mpb verify` and `mpb verify --compare` run on the database too.
#
#   bench/verify_compare_metrics.sh [--tol TOL] [--robot-dir DIR] DB...
#
# Exit 0 when every database agrees, 1 otherwise. The databases are only
# read. Make them with the older mpbench (tools/run_benchmark.sh).
set -eu
src=$(cd "$(dirname "$0")/.." && pwd)
. "$src/tools/usage.sh"
BUILD=${MPB_BUILD:-$src/build}
TOL=1e-9
ROBOT_DIR=$src/.cache/robots/vamp-planner-0.6.4/panda
while [ $# -gt 0 ]; do
    case $1 in
    --tol) TOL=$2; shift 2 ;;
    --robot-dir) ROBOT_DIR=$2; shift 2 ;;
    -h|--help) mpb_usage; exit 0 ;;
    --) shift; break ;;
    -*) echo "verify_compare_metrics: unknown option '$1'" >&2; exit 2 ;;
    *) break ;;
    esac
done
[ $# -gt 0 ] || { echo "verify_compare_metrics: wants DB... (--help)" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
status=0
for db in "$@"; do
    echo "== $db"
    if ! "$BUILD/tests/mpb-bench-verifydb" --db "$db" --robot-dir "$ROBOT_DIR" \
            --compare-stored "$tmp/now" > "$tmp/verdicts"; then
        status=1
    fi
    grep -v '^RESULT' "$tmp/verdicts"
    exp=$(sqlite3 "$db" "SELECT max(id) FROM experiments")
    sqlite3 -separator '|' "$db" "SELECT m.run_id, m.stage, m.name,
            CASE WHEN m.value IS NULL THEN '-' ELSE printf('%.17g', m.value) END
        FROM metrics m JOIN runs r ON r.id = m.run_id
        WHERE r.experiment_id = $exp" > "$tmp/stored"
    # Each metric measured now against the stored one; the stored ones
    # never measured now count as differences too.
    if ! awk -F'|' -v tol="$TOL" '
        function num(v) { return v == "-" || tolower(v) ~ /nan/ ? "nan" : v + 0 }
        NR == FNR { k = $1 "|" $2 "|" $3; stored[k] = $4; next }
        {
            k = $1 "|" $2 "|" $3; n++
            if (!(k in stored)) { print "  not stored: " k " = " $4; bad++; next }
            a = stored[k]; b = $4; delete stored[k]
            if (num(a) == "nan" || num(b) == "nan") {
                if (num(a) != num(b)) { print "  " k ": stored " a ", now " b; bad++ }
                next
            }
            d = a - b; if (d < 0) d = -d
            if (d > worst) worst = d
            if (d > tol) { print "  " k ": stored " a ", now " b; bad++ }
        }
        END {
            for (k in stored) { print "  stored, not measured now: " k; bad++ }
            printf "  metrics: %d compared, %d differ by more than %s, " \
                   "largest difference %.3g\n", n, bad, tol, worst
            printf "RESULT verify_compare_metrics metrics=%d differ=%d " \
                   "tol=%s worst=%.3g\n", n, bad, tol, worst
            exit bad > 0
        }' "$tmp/stored" "$tmp/now"; then
        status=1
    fi
    MPB_MESH_PATH=${MPB_MESH_PATH:-$ROBOT_DIR}
    export MPB_MESH_PATH
    "$BUILD/tools/mpb" verify "$db" | tail -3 | sed 's/^/  mpb verify: /' || status=1
    "$BUILD/tools/mpb" verify --compare "$db" | tail -3 |
        sed 's/^/  mpb verify --compare: /' || status=1
done
exit $status
