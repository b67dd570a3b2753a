#!/bin/sh
# robot_data.sh - the field's robots and problem sets, fetched on demand by
# exact version and hash into .cache/robots (git-ignored; never committed).
#
# Source: the PyPI source distribution vamp-planner 0.6.4 (Apache-2.0; its
# robot resources come from robowflex_resources). Its resources/<robot>/
# hold the URDF, SRDF and meshes of the Panda, UR5, Fetch and Baxter, and
# problems.tar.bz2: MotionBenchMaker's problem sets (MoveIt scene and
# request YAML, 100 pairs a set).
#
#   tools/robot_data.sh            fetch and unpack if missing; print the
#                                  folder that holds panda/, ur5/, ...
#   tools/robot_data.sh --check    exit 0 if unpacked, 1 if not (no network)
#
# After it: .cache/robots/vamp-planner-0.6.4/panda/panda.urdf, panda.srdf,
# meshes/, problems/box_panda/scene0001.yaml, request0001.yaml, ...
# Idempotent: a complete unpacked copy is left alone without the network.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
. "$root/tools/usage.sh"
[ "${1:-}" = --check ] && [ $# -eq 1 ] || mpb_no_arguments "$@"
cache=$root/.cache/robots
VERSION=0.6.4
SHA256=d3150c6b67ff941af9ad56480b31d3fb73b12211ea21dc684f7737b059f6daba
ROBOTS="panda ur5 fetch baxter"
dest=$cache/vamp-planner-$VERSION
stamp=$dest/.complete

if [ -f "$stamp" ]; then
    [ "${1:-}" = --check ] || echo "$dest"
    exit 0
fi
[ "${1:-}" = --check ] && exit 1

mkdir -p "$cache"
tarball=$cache/vamp_planner-$VERSION.tar.gz
sha256() { sha256sum "$1" | cut -d' ' -f1; }
if [ ! -f "$tarball" ] || [ "$(sha256 "$tarball")" != "$SHA256" ]; then
    echo "robot data: fetching vamp-planner $VERSION with pip" >&2
    # pip as the machine configures it (its index, mirrors, proxies):
    # the source distribution only. Only this package is held to its
    # source: with --no-binary :all: pip would build the build tools of
    # its metadata step (CMake among them) from source too, for minutes.
    pip="$root/.venv/bin/python"
    [ -x "$pip" ] || pip=python3
    rm -rf "$cache/download" && mkdir -p "$cache/download"
    "$pip" -m pip download -q --no-deps --no-binary vamp-planner \
        -d "$cache/download" "vamp-planner==$VERSION" >&2 || {
        echo "robot data: pip download vamp-planner==$VERSION failed" >&2
        exit 1
    }
    got=$cache/download/vamp_planner-$VERSION.tar.gz
    [ -f "$got" ] || {
        echo "robot data: pip gave no $(basename "$got")" >&2
        exit 1
    }
    sum=$(sha256 "$got")
    if [ "$sum" != "$SHA256" ]; then
        rm -rf "$cache/download"
        echo "robot data: vamp_planner-$VERSION.tar.gz: sha256 $sum," \
            "expected $SHA256" >&2
        exit 1
    fi
    mv "$got" "$tarball"
    rm -rf "$cache/download"
fi

python=/usr/bin/python3
[ -x "$python" ] || python=python3
# Python does both archives (the problems are bzip2, which a minimal
# Debian may lack as a command).
"$python" - "$tarball" "$dest" $ROBOTS <<'EOF'
import os, shutil, sys, tarfile
tarball, dest, robots = sys.argv[1], sys.argv[2], sys.argv[3:]

staging = dest + ".tmp"
shutil.rmtree(staging, ignore_errors=True)
os.makedirs(staging)

def safe(members, prefix):
    # Only the files under prefix, and none that climbs out of it.
    for m in members:
        if not m.name.startswith(prefix) or ".." in m.name.split("/"):
            continue
        if not (m.isfile() or m.isdir()):
            continue
        m.name = m.name[len(prefix):]
        if m.name:
            yield m

top = "vamp_planner-%s/resources/" % os.path.basename(dest).split("-")[-1]
with tarfile.open(tarball, "r:gz") as t:
    t.extractall(staging, members=safe(t.getmembers(), top))
for robot in robots:
    problems = os.path.join(staging, robot, "problems.tar.bz2")
    if os.path.exists(problems):
        with tarfile.open(problems, "r:bz2") as t:
            t.extractall(os.path.join(staging, robot),
                         members=safe(t.getmembers(), ""))
        os.remove(problems)
shutil.rmtree(dest, ignore_errors=True)
os.replace(staging, dest)
EOF
for robot in $ROBOTS; do
    [ -f "$dest/$robot/$robot.urdf" ] || {
        echo "robot data: $dest/$robot/$robot.urdf missing after unpacking" >&2
        exit 1
    }
done
touch "$stamp"
echo "robot data: unpacked into $dest" >&2
echo "$dest"
