#!/bin/sh
# python_env.sh - the project's own Python environment, .venv: the PyPI
# `lcm` package that the Python planner (planners/python) speaks LCM with,
# pytest for the kit's tests (tests/python) and pandas for
# docs/analysis.md's example, exact versions and
# hashes from planners/python/requirements.txt. Run by `make deps` after
# tools/deps.sh (which installs python3-venv).
#
# Idempotent: when .venv holds what the requirements file says it does
# nothing, without the network.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
. "$root/tools/usage.sh"
mpb_no_arguments "$@"
venv=$root/.venv
reqs=$root/planners/python/requirements.txt

if [ -x "$venv/bin/python3" ] && [ -f "$venv/.installed" ] &&
        cmp -s "$reqs" "$venv/.installed"; then
    echo "deps: .venv is ready"
    exit 0
fi
# Debian's python3, whatever else is first on PATH: it is the one the
# python3-venv package completes.
python=/usr/bin/python3
[ -x "$python" ] || python=python3
echo "deps: making .venv from $reqs"
[ -x "$venv/bin/python3" ] || "$python" -m venv "$venv"
"$venv/bin/python3" -m pip install --quiet --disable-pip-version-check \
    --require-hashes -r "$reqs"
"$venv/bin/python3" -c "import lcm, pytest, pandas"
cp "$reqs" "$venv/.installed"
