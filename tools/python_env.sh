#!/bin/sh
# python_env.sh - the project's own Python environment, .venv, with the
# PyPI `lcm` package that the Python planner (planners/python) speaks LCM
# with. Run by `make deps` after tools/deps.sh (which installs python3-venv).
#
# Idempotent: when .venv already imports lcm it does nothing, without the
# network.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
venv=$root/.venv
LCM_VERSION=1.5.3   # wire-compatible with Debian's LCM 1.3.1 (shared/DESIGN.md)

if [ -x "$venv/bin/python3" ] && "$venv/bin/python3" -c "import lcm" 2>/dev/null; then
    echo "deps: .venv has lcm"
    exit 0
fi
# Debian's python3, whatever else is first on PATH: it is the one the
# python3-venv package completes.
python=/usr/bin/python3
[ -x "$python" ] || python=python3
echo "deps: making .venv with lcm $LCM_VERSION"
"$python" -m venv "$venv"
"$venv/bin/python3" -m pip install --quiet --disable-pip-version-check "lcm==$LCM_VERSION"
