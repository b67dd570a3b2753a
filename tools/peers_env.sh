#!/bin/sh
# peers_env.sh - the peer planners' Python environments: one virtual
# environment per library under .cache/peers/NAME (they conflict: mplib
# needs numpy < 2, roboplan numpy >= 2), each from its requirements file
# planners/peers/requirements/NAME.txt (exact versions and sha256 hashes,
# pip --require-hashes, the machine's configured index), plus the Python
# kit (planners/python) built into it. Run by `make deps`; after it the
# peers need no network.
#
#   tools/peers_env.sh [NAME...]     install (default: every peer)
#   tools/peers_env.sh --check NAME  exit 0 when NAME's environment is ready
#   tools/peers_env.sh --lock NAME SPEC...  rewrite NAME's requirements
#                      file: pip download SPEC (e.g. mplib==0.2.1), its
#                      dependencies and wheel (the kit's build), then pip
#                      hash each file (network; review the diff)
#
# Idempotent: a ready environment is left alone (no network); the kit is
# reinstalled only when its sources or lcmtypes/ changed.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
. "$root/tools/usage.sh"
reqs=$root/planners/peers/requirements
dest=$root/.cache/peers
# The peers: one requirements file each (planners/peers/mpbpeers/NAME.py
# is its adapter).
ALL=$(cd "$reqs" && ls *.txt | sed 's/\.txt$//' | tr '\n' ' ')

module_of() {
    case $1 in
        ompl2) echo ompl ;;
        tesseract) echo tesseract_robotics ;;
        drake) echo pydrake ;;
        *) echo "$1" ;;
    esac
}

# The newest source of the kit (its Python files and the .lcm types).
kit_stamp_stale() {
    stamp=$dest/$1/.kit-stamp
    [ -f "$stamp" ] || return 0
    [ -z "$(find "$root/planners/python/mpbplanner" "$root/planners/python/mpbrrt" "$root/lcmtypes" \
                 "$root/planners/python/setup.py" "$root/planners/python/pyproject.toml" \
                 -newer "$stamp" \( -name '*.py' -o -name '*.lcm' -o -name '*.toml' \) \
                 2>/dev/null | head -n 1)" ] && return 1
    return 0
}

ready() {
    py=$dest/$1/bin/python3
    [ -x "$py" ] && [ -f "$dest/$1/.installed" ] &&
        cmp -s "$reqs/$1.txt" "$dest/$1/.installed" &&
        ! kit_stamp_stale "$1"
}

if [ "${1:-}" = --check ]; then
    [ $# -eq 2 ] || { echo "peers_env: --check wants one NAME" >&2; exit 2; }
    ready "$2"
    exit $?
fi

lock() {
    name=$1; shift
    tmp=$(mktemp -d)
    "$python" -m pip download --quiet --disable-pip-version-check -d "$tmp" \
        "$@" "lcm==1.5.3" "wheel==0.45.1"
    {
        echo "# $name: exact versions and hashes of everything its planner needs,"
        echo "# installed by tools/peers_env.sh into .cache/peers/$name with"
        echo "# \`pip install --require-hashes\` (from pip download + pip hash on"
        echo "# CPython 3.11, manylinux x86_64). Regenerate: tools/peers_env.sh --lock."
        for f in "$tmp"/*; do
            base=$(basename "$f")
            case $base in
                *.whl) nv=$(echo "$base" | cut -d- -f1,2) ;;
                *.tar.gz) nv=${base%.tar.gz} ;;
                *) continue ;;
            esac
            n=$(echo "${nv%-*}" | tr 'A-Z_.' 'a-z--')
            echo "$n==${nv##*-} \\"
            echo "    $("$python" -m pip hash "$f" | tail -n 1)"
        done | sed 's/^\(.*\)$/\1/'
    } >"$reqs/$name.txt"
    rm -rf "$tmp"
}

python=/usr/bin/python3
[ -x "$python" ] || python=python3
case $("$python" -c 'import sys; print("%d.%d" % sys.version_info[:2])') in
    3.11) ;;
    *) echo "peers_env: the pinned wheels are for CPython 3.11; $python is not" >&2
       exit 1 ;;
esac

if [ "${1:-}" = --lock ]; then
    [ $# -ge 3 ] || { echo "peers_env: --lock wants NAME SPEC..." >&2; exit 2; }
    shift
    lock "$@"
    exit 0
fi

mpb_no_options "$@"
for name in ${*:-$ALL}; do
    [ -f "$reqs/$name.txt" ] || {
        echo "peers_env: unknown peer '$name' ($ALL)" >&2
        exit 2
    }
    env=$dest/$name
    if ready "$name"; then
        echo "deps: .cache/peers/$name is ready"
        continue
    fi
    if ! [ -f "$env/.installed" ] || ! cmp -s "$reqs/$name.txt" "$env/.installed"; then
        echo "deps: making .cache/peers/$name from $reqs/$name.txt"
        rm -rf "$env"
        "$python" -m venv "$env"
        "$env/bin/python3" -m pip install --quiet --disable-pip-version-check \
            --require-hashes -r "$reqs/$name.txt"
        "$env/bin/python3" -c "import $(module_of "$name")"
        cp "$reqs/$name.txt" "$env/.installed"
    fi
    # The kit, built here (lcm-gen from the environment's lcm): no index.
    # A copy keeps the checkout free of setuptools' build/ and egg-info.
    tmp=$(mktemp -d)
    mkdir -p "$tmp/planners/python" "$tmp/lcmtypes"
    cp -R "$root/planners/python/pyproject.toml" "$root/planners/python/setup.py" \
          "$root/planners/python/mpbplanner" "$root/planners/python/mpbrrt" \
          "$tmp/planners/python/"
    cp "$root"/lcmtypes/*.lcm "$tmp/lcmtypes/"
    touch "$env/.kit-stamp.new"
    "$env/bin/python3" -m pip install --quiet --disable-pip-version-check \
        --no-index --no-build-isolation --no-deps --force-reinstall "$tmp/planners/python" ||
        { rm -rf "$tmp"; exit 1; }
    rm -rf "$tmp"
    mv "$env/.kit-stamp.new" "$env/.kit-stamp"
    echo "deps: .cache/peers/$name has $(module_of "$name") and the kit"
done
