"""tesseract_octree_fallback.py - the Tesseract peer's two ways with a
sensed octree (planners/peers/mpbpeers/tesseract.py): as Tesseract's own
Octree geometry when its URDF parser takes the cells, and, when it
refuses them, the same cells as libmpbench's merged boxes on one link,
said in one line on stderr. Either way the wall blocks the arm: a state
reaching through it touches the scene and the arm drawn back does not.

Run with Tesseract's environment (make deps) and the build's libmpbench:
    MPB_LIBMPBENCH=... MPB_MESH_PATH=PANDA PYTHONPATH=planners/peers:\
planners/python .cache/peers/tesseract/bin/python3 THIS MPB PANDA_DIR
"""
import contextlib
import io
import os
import shutil
import subprocess
import sys
import tempfile
from types import SimpleNamespace

import numpy as np

from mpbpeers import peer, tesseract
from tesseract_robotics.tesseract_collision import (ContactRequest,
                                                    ContactResultMap,
                                                    ContactResultVector,
                                                    ContactTestType_ALL)
from tesseract_robotics.tesseract_geometry import (GeometryType_BOX,
                                                   GeometryType_OCTREE)

JOINTS = [f"panda_joint{i}" for i in range(1, 8)]
# A board 5 cm thick, 0.45-0.5 m in front of the Panda's base.
WALL = """(noname)+
* wall
0 0 0
0 0 0 1
1
box
0.05 0.6 0.8
0.5 0 0.4
0 0 0 1
0 0 0 0
0
.
"""
AWAY = [0, -0.785, 0, -2.356, 0, 1.571, 0.785]      # the hand at x 0.3
THROUGH = [0, 0.6, 0, -1.2, 0, 1.9, 0.785]          # the hand past 0.5
FAILS = []


def check(what, ok):
    print(f"{'ok' if ok else 'not ok'} - {what}")
    if not ok:
        FAILS.append(what)


def touches_scene(env, q):
    env.setState(JOINTS, np.array(q, dtype=float))
    # Each SWIG value in a variable: a chained temporary is freed before
    # its use (0.5.1; here a loop without end).
    manager = env.getDiscreteContactManager()
    state = env.getState()
    manager.setCollisionObjectsTransform(state.link_transforms)
    found = ContactResultMap()
    manager.contactTest(found, ContactRequest(ContactTestType_ALL))
    flat = ContactResultVector()
    found.flattenMoveResults(flat)
    return any("mpb_scene" in c.link_names[0] + c.link_names[1]
               for c in flat)


def scene_geometry(env):
    link = env.getSceneGraph().getLink("mpb_scene_0")
    return [] if link is None else \
        [c.geometry.getType() for c in link.collision]


def build(adapter, problem):
    """adapter.build(problem), with what it said on stderr."""
    said = io.StringIO()
    with contextlib.redirect_stderr(said):
        model = adapter.build(problem, None)
    return model, said.getvalue()


def main(mpb, panda):
    work = tempfile.mkdtemp(prefix="mpb-test-tess-")
    try:
        return checks(mpb, panda, work)
    finally:
        shutil.rmtree(work)


def checks(mpb, panda, work):
    with open(os.path.join(work, "wall.scene"), "w") as f:
        f.write(WALL)
    subprocess.run([mpb, "sense", os.path.join(work, "wall.scene"), "-o",
                    os.path.join(work, "wall.sensed")], check=True,
                   capture_output=True)
    robot = open(os.path.join(panda, "panda.urdf")).read() + \
        open(os.path.join(panda, "panda.srdf")).read()
    req = SimpleNamespace(robot_format="urdf", scene_format="moveit-scene",
                          robot=robot,
                          scene=open(os.path.join(work, "wall.sensed")).read(),
                          joint_names=JOINTS, held_names=[], held_values=[])
    problem = peer.Problem(req, work)
    boxes = sum(1 for s in problem.shapes if s.cloud is not None)
    check("the sensed wall is one octree with merged boxes",
          len(problem.clouds) == 1 and problem.clouds[0].kind == "octree"
          and boxes > 0)

    model, said = build(tesseract.Adapter(), problem)
    check("taken as it is, the octree is Tesseract's own Octree",
          scene_geometry(model["env"]) == [GeometryType_OCTREE])
    check("... and nothing is said on stderr",
          model is not None and said == "")
    octree = tesseract.Adapter()
    octree.build(problem, None)
    check("... the CLOUDS it reports are points", octree.CLOUDS == "points")
    check("... a state reaching through the wall touches it",
          touches_scene(model["env"], THROUGH))
    check("... the arm drawn back does not",
          not touches_scene(model["env"], AWAY))

    # Tesseract's parser refusing the cells, as it refuses a file it
    # cannot read: the real parser replaced for this one build.
    def refuse(*_):
        raise RuntimeError("octree file unreadable")
    real = tesseract.parseURDFString
    tesseract.parseURDFString = refuse
    try:
        fallback = tesseract.Adapter()
        model, said = build(fallback, problem)
    finally:
        tesseract.parseURDFString = real
    check("refused, the octree goes in as its merged boxes, one link",
          scene_geometry(model["env"]) == [GeometryType_BOX] * boxes)
    check("... said in one line naming the octree and why",
          said == "mpb-planner-tesseract: octree 'sensed' as boxes: "
                  "tesseract_urdf: octree file unreadable\n")
    check("... the CLOUDS it reports are shapes, not points",
          fallback.CLOUDS == "")
    check("... the boxes block the state reaching through the wall",
          touches_scene(model["env"], THROUGH))
    check("... and not the arm drawn back",
          not touches_scene(model["env"], AWAY))
    folder = os.path.dirname(problem.urdf_path)
    check("no octree file is left beside the robot",
          not any(n.endswith(".bt") for n in os.listdir(folder)))
    return 1 if FAILS else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
