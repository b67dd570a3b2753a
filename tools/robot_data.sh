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
cache=$root/.cache/robots
VERSION=0.6.4
SHA256=d3150c6b67ff941af9ad56480b31d3fb73b12211ea21dc684f7737b059f6daba
URL=https://files.pythonhosted.org/packages/f2/e3/df472573bab9194d796cf6a156edcf95089c14e5c932b2874cdef0d60a8b/vamp_planner-$VERSION.tar.gz
ROBOTS="panda ur5 fetch baxter"
dest=$cache/vamp-planner-$VERSION
stamp=$dest/.complete

if [ -f "$stamp" ]; then
    [ "${1:-}" = --check ] || echo "$dest"
    exit 0
fi
[ "${1:-}" = --check ] && exit 1

python=/usr/bin/python3
[ -x "$python" ] || python=python3
mkdir -p "$cache"
tarball=$cache/vamp_planner-$VERSION.tar.gz
echo "robot data: fetching vamp-planner $VERSION from PyPI" >&2
# Python does the download, the hash and both archives (the problems are
# bzip2, which a minimal Debian may lack as a command).
"$python" - "$URL" "$SHA256" "$tarball" "$dest" $ROBOTS <<'EOF'
import hashlib, os, shutil, sys, tarfile, urllib.request
url, want, tarball, dest, robots = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], sys.argv[5:]

def sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()

if not os.path.exists(tarball) or sha256(tarball) != want:
    tmp = tarball + ".part"
    with urllib.request.urlopen(url, timeout=120) as r, open(tmp, "wb") as f:
        shutil.copyfileobj(r, f)
    got = sha256(tmp)
    if got != want:
        os.remove(tmp)
        sys.exit(f"robot data: {url}: sha256 {got}, expected {want}")
    os.replace(tmp, tarball)

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
