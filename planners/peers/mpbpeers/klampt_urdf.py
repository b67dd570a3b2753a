"""klampt_urdf.py - the copy of a URDF that Klampt 0.10.1 loads as the
robot the URDF means, made as a Klampt user makes it by hand. The peer
`klampt` (klampt.py beside this file) calls klampt_urdf() on every
request's robot; run as a script it writes the copy of a URDF file:

    python3 -m mpbpeers.klampt_urdf IN.urdf OUT.urdf

Three edits, nothing else changes:

- Mesh file names absolute: Klampt knows no package:// (relative names
  are taken from the URDF's folder, but Klampt 0.10.1 lost the Panda's
  hand.obj, silently, when its relative name began with ../../../ while
  the other meshes loaded; absolute names loaded at every depth tried).
- <klampt freeze_root_link="1"/> in the robot element: without it
  Klampt gives the root link a 6-dof floating base (six virtual links
  ahead of the URDF's), which the URDF does not have. (Klampt still
  numbers its configuration by its own links, fixed joints included: the
  adapter maps joint names to indices through the child links.)
- <mimic> tags removed: Klampt turns one into an affine driver, and
  plan_to_config with a moving subset then fails inside its affine
  embedding. The removed tags are returned, so that the adapter sets a
  follower from its leader (and refuses a request whose moving joints
  lead one: Klampt's planner could not keep the coupling).
"""
import os
import re
import sys


class Mimic:
    """One removed <mimic>: the follower joint, its type, the leader,
    value = multiplier * leader + offset."""

    def __init__(self, joint, kind, leader, multiplier, offset):
        self.joint, self.kind, self.leader = joint, kind, leader
        self.multiplier, self.offset = multiplier, offset


def _attr(tag, name, default=None):
    m = re.search(r'\b%s\s*=\s*"([^"]*)"' % name, tag)
    return m.group(1) if m else default


def klampt_urdf(urdf, directory):
    """(text, mimics): the URDF text edited for Klampt, its meshes named
    absolutely (a relative name is taken from directory, the source
    URDF's folder), and the removed <mimic> tags as Mimic objects."""
    def absolute(m):
        name = m.group(2)
        if name.startswith("file://"):
            name = name[7:]
        if name.startswith("package://"):
            raise ValueError(f"mesh '{name}': resolve package:// names "
                             f"first (mpbench's peers do)")
        return m.group(1) + os.path.join(directory, name) + m.group(3)

    text = re.sub(r'(<mesh[^>]*filename=")([^"]+)(")', absolute, urdf)

    mimics = []

    def joint(m):
        body = m.group(0)
        head = body[:body.find(">") + 1]
        mm = re.search(r'<mimic\b[^>]*?(/>|>\s*</mimic>)', body, re.S)
        if not mm:
            return body
        tag = mm.group(0)
        mimics.append(Mimic(_attr(head, "name"), _attr(head, "type"),
                            _attr(tag, "joint"),
                            float(_attr(tag, "multiplier", "1")),
                            float(_attr(tag, "offset", "0"))))
        return body[:mm.start()] + body[mm.end():]

    text = re.sub(r'<joint\b.*?</joint>', joint, text, flags=re.S)

    m = re.search(r'<klampt\b[^>]*?/?>', text)
    if m:
        tag = m.group(0)
        if _attr(tag, "freeze_root_link") is None:
            text = (text[:m.start()] + '<klampt freeze_root_link="1"'
                    + tag[len("<klampt"):] + text[m.end():])
    else:
        r = re.search(r'<robot\b[^>]*>', text)
        if not r:
            raise ValueError("no <robot> element")
        text = (text[:r.end()] + '\n  <klampt freeze_root_link="1"/>'
                + text[r.end():])
    return text, mimics


def main(argv):
    if len(argv) != 2:
        print("usage: python3 -m mpbpeers.klampt_urdf IN.urdf OUT.urdf",
              file=sys.stderr)
        return 2
    src, dst = argv
    with open(src) as f:
        urdf = f.read()
    try:
        text, mimics = klampt_urdf(urdf, os.path.dirname(os.path.abspath(src)))
    except ValueError as e:
        print(f"{src}: {e}", file=sys.stderr)
        return 1
    with open(dst, "w") as f:
        f.write(text)
    for mi in mimics:
        print(f"{src}: removed <mimic> of joint '{mi.joint}' ({mi.kind}), "
              f"leader '{mi.leader}'", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
