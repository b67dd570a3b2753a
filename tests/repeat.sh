#!/bin/sh
# tests/repeat.sh - the integration tests N times in a row on a clean
# clone of this repository's HEAD, each test once a round (no rerun),
# stopping at the first round with a failure: how a flake is found, and
# how "N consecutive clean-clone runs pass" is checked.
#
#   tests/repeat.sh [N] [LABEL]
#
# N defaults to 10, LABEL (a ctest label) to integration. The clone and
# its build are made once in a temporary folder (make deps installs what
# is missing, as make test does); a line per round says its failures and
# time, and a failed round's ctest output is kept in ./repeat-failed-R.log.
# The last line says how many consecutive rounds passed. An integration
# round takes about 25 minutes on the 2-core machine.
set -u
src=$(cd "$(dirname "$0")/.." && pwd)
. "$src/tools/usage.sh"
mpb_no_options "$@"
N=${1:-10}
LABEL=${2:-integration}
case $N in
''|*[!0-9]*|0) echo "tests/repeat.sh: N must be a count, not '$N' (see --help)" >&2; exit 2 ;;
esac
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
git clone -q "$src" "$work/clone" || exit 1
cd "$work/clone" || exit 1
echo "repeat: $(git log -1 --format='%h %s'), $N rounds of label '$LABEL'"
make deps all >"$work/build.log" 2>&1 || {
    tail -20 "$work/build.log" >&2
    exit 1
}
passed=0
for r in $(seq 1 "$N"); do
    t0=$(date +%s)
    (cd build && ctest -L "$LABEL" --output-on-failure) >"$work/round.log" 2>&1
    rc=$?
    secs=$(( $(date +%s) - t0 ))
    failed=$(sed -n 's/^[[:space:]]*[0-9]* - \(.*\) (.*)$/\1/p' "$work/round.log" | tr '\n' ' ')
    if [ "$rc" -eq 0 ]; then
        passed=$((passed + 1))
        echo "round $r: passed ($secs s)"
    else
        cp "$work/round.log" "$src/repeat-failed-$r.log"
        echo "round $r: FAILED: ${failed:-ctest exit $rc} ($secs s; repeat-failed-$r.log)"
        break
    fi
done
echo "repeat: $passed consecutive rounds passed of $N"
[ "$passed" -eq "$N" ]
