"""test_klampt_urdf.py - the copy of a URDF the peer `klampt` gives Klampt
(planners/peers/mpbpeers/klampt_urdf.py, plain Python, tested here
without Klampt): each link's second and later <collision> moved into a
link of its own, fixed to it, because Klampt 0.10.1 keeps only a link's
first; links written <link/> left alone."""
import os
import sys
import xml.etree.ElementTree as ET

SOURCE = os.environ["MPB_SOURCE"]
sys.path.insert(0, os.path.join(SOURCE, "planners", "peers"))
from mpbpeers.klampt_urdf import klampt_urdf  # noqa: E402

PR2 = os.path.join(SOURCE, "scenes", "robots", "pr2_right_arm.urdf")


def _xml(element):
    """The element as text, without the whitespace that follows it."""
    element.tail = None
    return ET.tostring(element)


def _collisions(root):
    return {link.get("name"): link.findall("collision")
            for link in root.iter("link")}


def test_every_collision_kept_one_a_link():
    with open(PR2) as f:
        source = f.read()
    text, mimics, parts = klampt_urdf(source, os.path.dirname(PR2))
    before, after = ET.fromstring(source), ET.fromstring(text)
    old, new = _collisions(before), _collisions(after)
    # The palm and its two fingers; the torso's three boxes.
    assert parts["r_gripper_palm_link"] == ["r_gripper_palm_link__collision2",
                                            "r_gripper_palm_link__collision3"]
    assert len(parts["torso_lift_link"]) == 2
    assert all(len(c) <= 1 for c in new.values())
    joints = {j.find("child").get("link"): j for j in after.iter("joint")}
    for link, names in parts.items():
        assert len(old[link]) == len(names) + 1
        # Each part holds its collision as written, origin included,
        # fixed to its link at the link's own origin.
        for k, name in enumerate(names, start=1):
            assert _xml(new[name][0]) == _xml(old[link][k])
            j = joints[name]
            assert j.get("type") == "fixed"
            assert j.find("parent").get("link") == link
            assert j.find("origin").get("xyz") == "0 0 0"
        assert _xml(new[link][0]) == _xml(old[link][0])
    # The self-closing links stay as they were, without geometry.
    assert new["r_upper_arm_roll_link"] == []
    assert "r_upper_arm_roll_link" not in parts
    assert sum(map(len, new.values())) == sum(map(len, old.values()))
    assert mimics == []
