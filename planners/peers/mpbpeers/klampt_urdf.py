"""klampt_urdf.py - the copy of a URDF that Klampt 0.10.1 loads as the
robot the URDF means, made as a Klampt user makes it by hand. The peer
`klampt` (klampt.py beside this file) calls klampt_urdf() on every
request's robot; run as a script it writes the copy of a URDF file:

    python3 -m mpbpeers.klampt_urdf IN.urdf OUT.urdf

Four edits, nothing else changes:

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
- A link's second and later <collision> elements each moved into a link
  of its own, LINK__collision2, ..., fixed to LINK at its origin:
  Klampt 0.10.1 keeps only a link's first (the PR2 gripper's palm kept,
  its fingers lost, and paths through shelves claimed free). The parts
  are returned, so that the adapter treats them as their link in
  self-collision.
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


PART = "__collision"     # LINK__collision2: a link's second <collision>


def _split_collisions(text):
    """text with every link's second and later <collision> in a link of
    its own, fixed to it; and {link: [its parts' names]}."""
    parts = {}

    def link(m):
        body = m.group(0)
        name = _attr(body[:body.find(">") + 1], "name")
        found = list(re.finditer(r'<collision\b.*?</collision>|'
                                 r'<collision\b[^>]*/>', body, re.S))
        if name is None or len(found) < 2:
            return body
        kept = body
        extra = []
        for k, c in reversed(list(enumerate(found))):
            if k == 0:
                break
            part = f"{name}{PART}{k + 1}"
            kept = kept[:c.start()] + kept[c.end():]
            extra.insert(0, f'\n  <link name="{part}">{c.group(0)}</link>'
                            f'\n  <joint name="{part}_joint" type="fixed">'
                            f'<parent link="{name}"/><child link="{part}"/>'
                            f'<origin xyz="0 0 0" rpy="0 0 0"/></joint>')
            parts.setdefault(name, []).insert(0, part)
        return kept + "".join(extra)

    return re.sub(r'<link\b[^>]*(?<!/)>.*?</link>', link, text,
                  flags=re.S), parts


def klampt_urdf(urdf, directory):
    """(text, mimics, parts): the URDF text edited for Klampt, its meshes
    named absolutely (a relative name is taken from directory, the source
    URDF's folder), the removed <mimic> tags as Mimic objects, and
    {link: [the links holding its second and later collisions]}."""
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
    text, parts = _split_collisions(text)

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
    return text, mimics, parts


def main(argv):
    if len(argv) != 2:
        print("usage: python3 -m mpbpeers.klampt_urdf IN.urdf OUT.urdf",
              file=sys.stderr)
        return 2
    src, dst = argv
    with open(src) as f:
        urdf = f.read()
    try:
        text, mimics, parts = klampt_urdf(
            urdf, os.path.dirname(os.path.abspath(src)))
    except ValueError as e:
        print(f"{src}: {e}", file=sys.stderr)
        return 1
    with open(dst, "w") as f:
        f.write(text)
    for mi in mimics:
        print(f"{src}: removed <mimic> of joint '{mi.joint}' ({mi.kind}), "
              f"leader '{mi.leader}'", file=sys.stderr)
    for link, names in parts.items():
        print(f"{src}: link '{link}': collisions 2-{len(names) + 1} moved "
              f"into {', '.join(names)}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
