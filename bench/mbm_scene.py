#!/usr/bin/env python3
"""bench/mbm_scene.py - one MotionBenchMaker scene (a MoveIt PlanningScene
serialized as YAML, sceneNNNN.yaml) as a MoveIt .scene text, for the bench
until mpbench reads MoveIt YAML itself.

    python3 bench/mbm_scene.py SCENE.yaml > OUT.scene

Only what the MotionBenchMaker sets hold is read: world.collision_objects,
each with an id, primitives (box, sphere, cylinder, cone) and their
primitive_poses in the planning frame. shape_msgs dimensions: a box's full
sides, a sphere's radius, a cylinder's and a cone's [height, radius]; the
.scene text wants [radius, length]. Quaternions are [x, y, z, w] in both.
Anything else (meshes, planes, an object pose, attached objects) stops the
conversion with a message: the bench must not measure a different scene.

No YAML library: the files are block mappings and sequences with flow
lists of numbers, which the small reader below handles, and nothing here
depends on a package that the build does not install.
"""
import re
import sys


def scalar(text):
    text = text.strip()
    if len(text) >= 2 and text[0] == text[-1] and text[0] in "'\"":
        return text[1:-1]
    try:
        return int(text)
    except ValueError:
        pass
    try:
        return float(text)
    except ValueError:
        return text


def flow(text, i=0):
    """A flow value ([..], {..} or a scalar) at text[i:]; (value, next i)."""
    while text[i] == " ":
        i += 1
    if text[i] in "[{":
        close = "]" if text[i] == "[" else "}"
        items, i = [], i + 1
        while True:
            while text[i] in " ,":
                i += 1
            if text[i] == close:
                break
            if close == "}":
                key, rest = text[i:].split(":", 1)
                value, j = flow(text, i + len(key) + 1)
                items.append((key.strip(), value))
                i = j
            else:
                value, i = flow(text, i)
                items.append(value)
        return (dict(items) if close == "}" else items), i + 1
    m = re.match(r"[^,\]\}]*", text[i:])
    return scalar(m.group(0)), i + len(m.group(0))


def value_of(text):
    text = text.strip()
    return flow(text)[0] if text[:1] in "[{" else scalar(text)


def parse(lines):
    """A block structure from (indent, text) lines, comments removed."""
    def block(k, indent):
        if lines[k][1].startswith("- "):
            seq = []
            while k < len(lines) and lines[k][0] == indent and \
                    lines[k][1].startswith("- "):
                # "- key: v" opens a mapping indented by the dash's width
                rest = lines[k][1][2:]
                lines[k] = (indent + 2, rest)
                if ":" in rest and not rest.startswith(("[", "{")):
                    item, k = block(k, indent + 2)
                else:
                    item, k = value_of(rest), k + 1
                seq.append(item)
            return seq, k
        mapping = {}
        while k < len(lines) and lines[k][0] == indent:
            key, rest = lines[k][1].split(":", 1)
            k += 1
            if rest.strip():
                mapping[key.strip()] = value_of(rest)
            elif k < len(lines) and (lines[k][0] > indent or (
                    lines[k][0] == indent and lines[k][1].startswith("- "))):
                mapping[key.strip()], k = block(k, lines[k][0])
            else:
                mapping[key.strip()] = None
        return mapping, k
    return block(0, lines[0][0])[0]


def read(path):
    lines = []
    with open(path, encoding="utf-8") as f:
        for raw in f:
            text = raw.split(" #", 1)[0].rstrip()
            if text.strip() and not text.lstrip().startswith("#"):
                lines.append((len(text) - len(text.lstrip()), text.strip()))
    return parse(lines)


def fail(path, what):
    sys.exit("bench/mbm_scene.py: %s: %s" % (path, what))


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: python3 bench/mbm_scene.py SCENE.yaml > OUT.scene")
    path = sys.argv[1]
    doc = read(path)
    objects = (doc.get("world") or {}).get("collision_objects") or []
    out = [doc.get("name") or path.rsplit("/", 1)[-1]]
    for o in objects:
        for key in ("meshes", "planes", "pose", "mesh_poses", "plane_poses"):
            if o.get(key):
                fail(path, "object %s has %s, which this script does not "
                     "convert" % (o.get("id"), key))
        prims, poses = o.get("primitives") or [], o.get("primitive_poses") or []
        if len(prims) != len(poses):
            fail(path, "object %s: %d primitives, %d poses"
                 % (o.get("id"), len(prims), len(poses)))
        out += ["* %s" % o["id"], "0 0 0", "0 0 0 1", str(len(prims))]
        for p, pose in zip(prims, poses):
            d = [float(x) for x in p["dimensions"]]
            kind = p["type"]
            if kind in ("cylinder", "cone"):
                d = [d[1], d[0]]        # [height, radius] -> radius length
            elif kind not in ("box", "sphere"):
                fail(path, "object %s: primitive type %s" % (o["id"], kind))
            out += [kind, " ".join(repr(x) for x in d),
                    " ".join(repr(float(x)) for x in pose["position"]),
                    " ".join(repr(float(x)) for x in pose["orientation"]),
                    "0 0 0 0"]
        out.append("0")
    if doc.get("robot_state", {}).get("attached_collision_objects"):
        fail(path, "attached objects are not converted")
    out.append(".")
    print("\n".join(out))


main()
