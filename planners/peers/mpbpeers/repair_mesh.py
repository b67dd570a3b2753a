"""repair_mesh.py - what an mplib user does about a mesh mplib refuses.

mplib 0.2.1 loads meshes with assimp and refuses one holding a primitive
of two vertices ("has a face with 2 vertices"): the Panda's
meshes/collision/link6.obj of vamp-planner 0.6.4 holds three OBJ line
elements (`l 13 14`, `l 7 8`, `l 15 16`) after its triangles. This writes
a copy of an OBJ file without its line elements and degenerate triangles
(fewer than three distinct corners); neither has an area, so the surface
is the same. Every other mesh is used as it is; the library is not
patched.

    python3 repair_mesh.py MESH.obj OUT_DIR    # prints the path to use
"""
import hashlib
import os
import sys


def _corner(token):
    return int(token.split("/")[0])


def degenerate_faces(lines):
    """Indices (into lines) of the line elements and of the faces without
    three distinct positions."""
    positions = []
    bad = []
    for k, line in enumerate(lines):
        parts = line.split()
        if not parts:
            continue
        if parts[0] == "v":
            positions.append(tuple(parts[1:4]))
        elif parts[0] == "l":
            bad.append(k)
        elif parts[0] == "f":
            idx = [_corner(t) for t in parts[1:]]
            pts = {positions[i - 1 if i > 0 else len(positions) + i]
                   for i in idx}
            if len(pts) < 3:
                bad.append(k)
    return bad


def repaired(path, out_dir):
    """The path to load instead of path: path itself when it needs no
    repair (or is not an OBJ file), else a repaired copy in out_dir
    (made once; its name carries the original's content hash)."""
    if not path.lower().endswith(".obj"):
        return path
    with open(path, "rb") as f:
        data = f.read()
    lines = data.decode("utf-8", errors="replace").splitlines()
    bad = set(degenerate_faces(lines))
    if not bad:
        return path
    digest = hashlib.blake2b(data, digest_size=8).hexdigest()
    folder = os.path.join(out_dir, digest)
    out = os.path.join(folder, os.path.basename(path))
    if not os.path.exists(out):
        os.makedirs(folder, exist_ok=True)
        tmp = out + f".{os.getpid()}.tmp"
        with open(tmp, "w") as f:
            f.write(f"# {os.path.basename(path)} without its {len(bad)} "
                    f"line elements and degenerate triangles (planners/peers/repair_mesh.py)\n")
            for k, line in enumerate(lines):
                # mtllib points to a file beside the original: drop it,
                # materials play no part in collision checking.
                if k in bad or line.startswith("mtllib") or \
                        line.startswith("usemtl"):
                    continue
                f.write(line + "\n")
        os.replace(tmp, out)
    return out


if __name__ == "__main__":
    if len(sys.argv) != 3:
        print("usage: repair_mesh.py MESH.obj OUT_DIR", file=sys.stderr)
        sys.exit(2)
    print(repaired(sys.argv[1], sys.argv[2]))
