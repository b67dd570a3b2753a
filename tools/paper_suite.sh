#!/bin/sh
# paper_suite.sh - regenerate the paper's experiment files,
# scenes/experiments/paper.yaml and paper-quick.yaml, from
# scenes/paper/suite.txt (goals, start state, scenes) with mpb-paper-suite.
# Run it after editing suite.txt, a scene or the robot, and commit the
# result: the test suite checks that the committed files are what this
# generates (tests/integration/test_region_goals.sh).
#
# Usage: tools/paper_suite.sh [BUILD_DIR]     (default: build)
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
cmake --build "$build" --target mpb-paper-suite >/dev/null
gen=$build/tools/mpb-paper-suite
suite=$root/scenes/paper/suite.txt
out=$root/scenes/experiments

# Into a temporary file first: a goal without an IK solution fails the
# generator, and must not leave a half-written experiment file behind.
trap 'rm -f "$out/paper.yaml.new" "$out/paper-quick.yaml.new"' EXIT
"$gen" -v "$suite" >"$out/paper.yaml.new"
"$gen" --quick "$suite" >"$out/paper-quick.yaml.new"
mv "$out/paper.yaml.new" "$out/paper.yaml"
mv "$out/paper-quick.yaml.new" "$out/paper-quick.yaml"
echo "wrote $out/paper.yaml and $out/paper-quick.yaml"
