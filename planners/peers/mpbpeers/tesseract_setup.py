"""tesseract_setup.py - what a Tesseract user makes from a robot's URDF
and SRDF before Tesseract will load it (the peer `tesseract`,
tesseract.py): Tesseract 0.5.1 reads its own dialect of SRDF, and refuses
the Panda's vamp SRDF ("Group 'hand' is empty or multiple types were
provided": a group mixing links, joints and subgroups).

Made, in a folder of its own, from the request's files:

- robot.urdf: the URDF with every mesh named by a file:// URL of the
  absolute path (peer.Problem resolves them as libmpbench does);
  Tesseract's GeneralResourceLocator reads file:// names, and without
  them `package://` would need TESSERACT_RESOURCE_PATH and a package.xml
  in the package's folder.
- robot.srdf: a reduced SRDF with one group, GROUP, a chain from the
  parent link of the request's first joint to the child link of its last
  (the group's joints must be the request's joints, in order), the
  source SRDF's disable_collisions pairs, and the two plugin files below.
- kinematics_plugins.yaml: KDL forward kinematics (KDLFwdKinChainFactory)
  and KDL inverse kinematics (KDLInvKinChainLMAFactory) for the group,
  from the library tesseract_kinematics_kdl_factories.
- contact_managers_plugins.yaml: Bullet's discrete and cast BVH managers
  (the defaults) and FCL's discrete BVH manager, from the libraries
  tesseract_collision_bullet_factories and _fcl_factories.

Nothing else of the source SRDF is kept (group states, end effectors,
virtual joints, passive joints): a joint-goal planning request uses none
of them.
"""
import os
import re
from xml.sax.saxutils import quoteattr

GROUP = "manipulator"


class SetupError(Exception):
    """The robot cannot be made into Tesseract's files; says why."""


def _joints(urdf):
    """name -> (parent link, child link, type) of every URDF joint."""
    out = {}
    for m in re.finditer(r"<joint\b([^>]*)>(.*?)</joint>", urdf, re.S):
        name = re.search(r'\bname\s*=\s*"([^"]+)"', m.group(1))
        kind = re.search(r'\btype\s*=\s*"([^"]+)"', m.group(1))
        parent = re.search(r'<parent\s+link\s*=\s*"([^"]+)"', m.group(2))
        child = re.search(r'<child\s+link\s*=\s*"([^"]+)"', m.group(2))
        if name and parent and child:
            out[name.group(1)] = (parent.group(1), child.group(1),
                                  kind.group(1) if kind else "")
    return out


def _chain(joints, base, tip):
    """The joints from link base down to link tip, root first, or None."""
    parent_of = {child: (name, parent) for name, (parent, child, _) in
                 joints.items()}
    out, link = [], tip
    while link != base:
        if link not in parent_of:
            return None
        name, link = parent_of[link]
        out.append(name)
    return out[::-1]


def _robot_name(urdf):
    m = re.search(r'<robot\b[^>]*\bname\s*=\s*"([^"]+)"', urdf)
    return m.group(1) if m else "robot"


def chain_of(urdf, joint_names):
    """(base link, tip link) of the chain whose movable joints are
    joint_names; SetupError saying why when there is none."""
    joints = _joints(urdf)
    for j in joint_names:
        if j not in joints:
            raise SetupError(f"tesseract: joint '{j}' not in the URDF")
    base = joints[joint_names[0]][0]
    tip = joints[joint_names[-1]][1]
    chain = _chain(joints, base, tip)
    if chain is None:
        raise SetupError(f"tesseract: no chain from '{base}' to '{tip}'")
    chain = [j for j in chain if joints[j][2] != "fixed"]
    if chain != list(joint_names):
        raise SetupError(f"tesseract: the joints are not one chain from "
                         f"'{base}' to '{tip}' (that chain has "
                         f"{', '.join(chain)})")
    return base, tip


def _kinematics_yaml(base, tip):
    lines = ["kinematic_plugins:",
             "  search_libraries:",
             "    - tesseract_kinematics_kdl_factories",
             "  fwd_kin_plugins:",
             f"    {GROUP}:",
             "      default: KDLFwdKinChain",
             "      plugins:",
             "        KDLFwdKinChain:",
             "          class: KDLFwdKinChainFactory",
             "          config:",
             f"            base_link: {base}",
             f"            tip_link: {tip}",
             "  inv_kin_plugins:",
             f"    {GROUP}:",
             "      default: KDLInvKinChainLMA",
             "      plugins:",
             "        KDLInvKinChainLMA:",
             "          class: KDLInvKinChainLMAFactory",
             "          config:",
             f"            base_link: {base}",
             f"            tip_link: {tip}"]
    return "\n".join(lines) + "\n"


CONTACT_MANAGERS_YAML = """\
contact_manager_plugins:
  search_libraries:
    - tesseract_collision_bullet_factories
    - tesseract_collision_fcl_factories
  discrete_plugins:
    default: BulletDiscreteBVHManager
    plugins:
      BulletDiscreteBVHManager:
        class: BulletDiscreteBVHManagerFactory
      FCLDiscreteBVHManager:
        class: FCLDiscreteBVHManagerFactory
  continuous_plugins:
    default: BulletCastBVHManager
    plugins:
      BulletCastBVHManager:
        class: BulletCastBVHManagerFactory
"""


def make(urdf, srdf, joint_names, folder):
    """Write Tesseract's files for the robot into folder (made if need
    be): urdf and srdf are texts (the URDF's mesh names absolute paths or
    file:// URLs), joint_names the planning joints. Returns (urdf path,
    srdf path, base link, tip link)."""
    os.makedirs(folder, exist_ok=True)
    base, tip = chain_of(urdf, joint_names)

    def url(m):
        name = m.group(2)
        if name.startswith("/"):
            name = "file://" + name
        return m.group(1) + name + m.group(3)

    urdf = re.sub(r'(<mesh[^>]*filename=")([^"]+)(")', url, urdf)
    kin = os.path.join(folder, "kinematics_plugins.yaml")
    contact = os.path.join(folder, "contact_managers_plugins.yaml")
    with open(kin, "w") as f:
        f.write(_kinematics_yaml(base, tip))
    with open(contact, "w") as f:
        f.write(CONTACT_MANAGERS_YAML)
    pairs = re.findall(r'<disable_collisions\s+link1="([^"]+)"\s+'
                       r'link2="([^"]+)"', srdf or "")
    out = ['<?xml version="1.0"?>',
           f"<robot name={quoteattr(_robot_name(urdf))}>",
           f"  <group name={quoteattr(GROUP)}>",
           f"    <chain base_link={quoteattr(base)} tip_link={quoteattr(tip)}/>",
           "  </group>",
           f"  <kinematics_plugin_config filename={quoteattr(kin)}/>",
           f"  <contact_managers_plugin_config "
           f"filename={quoteattr(contact)}/>"]
    for a, b in pairs:
        out.append(f"  <disable_collisions link1={quoteattr(a)} "
                   f"link2={quoteattr(b)} reason=\"SRDF\"/>")
    out.append("</robot>")
    urdf_path = os.path.join(folder, "robot.urdf")
    srdf_path = os.path.join(folder, "robot.srdf")
    with open(urdf_path, "w") as f:
        f.write(urdf)
    with open(srdf_path, "w") as f:
        f.write("\n".join(out) + "\n")
    return urdf_path, srdf_path, base, tip


if __name__ == "__main__":
    # python -m mpbpeers.tesseract_setup URDF SRDF FOLDER JOINT...
    # (mesh names resolved as libmpbench resolves them: MPB_MESH_PATH).
    import argparse
    from .peer import InvalidRequest, resolve_mesh
    ap = argparse.ArgumentParser(
        prog="python -m mpbpeers.tesseract_setup",
        description="Write the files Tesseract 0.5.1 loads a robot from: "
                    "the URDF with file:// mesh names, a reduced SRDF of "
                    "one chain group and the SRDF's disabled pairs, and "
                    "the kinematics and contact-manager plugin YAMLs. "
                    "Meshes are found through MPB_MESH_PATH.")
    ap.add_argument("urdf")
    ap.add_argument("srdf")
    ap.add_argument("folder")
    ap.add_argument("joints", nargs="+", help="the planning joints, in order")
    a = ap.parse_args()
    with open(a.urdf) as f:
        u = f.read()
    with open(a.srdf) as f:
        s = f.read()
    try:
        u = re.sub(r'(<mesh[^>]*filename=")([^"]+)(")',
                   lambda m: m.group(1) + resolve_mesh(m.group(2))
                   + m.group(3), u)
        print("\n".join(make(u, s, a.joints, a.folder)[:2]))
    except (SetupError, InvalidRequest) as e:
        raise SystemExit(f"{a.urdf}: {e}")
