#!/bin/sh
# paper_suite.sh - regenerate the paper's experiment files,
# scenes/experiments/paper.yaml, paper-quick.yaml and paper-demo.yaml, from
# scenes/paper/suite.txt (goals, start state, scenes) with mpb-paper-suite.
# Run it after editing suite.txt, a scene or the robot, and commit the
# result: the test suite checks that the committed files are what this
# generates (tests/integration/test_region_goals.sh).
#
# Usage: tools/paper_suite.sh [BUILD_DIR]     (default: build)
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
. "$root/tools/usage.sh"
mpb_no_options "$@"
build=${1:-$root/build}
cmake --build "$build" --target mpb-paper-suite >/dev/null
gen=$build/tools/mpb-paper-suite
suite=$root/scenes/paper/suite.txt
out=$root/scenes/experiments

# Into a temporary file first: a goal without an IK solution fails the
# generator, and must not leave a half-written experiment file behind.
variants="paper paper-quick paper-demo"
trap 'for v in $variants; do rm -f "$out/$v.yaml.new"; done' EXIT
for v in $variants; do
    "$gen" --variant "$v" "$suite" >"$out/$v.yaml.new"
done
for v in $variants; do
    mv "$out/$v.yaml.new" "$out/$v.yaml"
    echo "wrote $out/$v.yaml"
done
