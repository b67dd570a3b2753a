#!/usr/bin/env python3
"""bench/tesseract_octree.py - what Tesseract's setup of a sensed scene
costs with the octree as its own Octree geometry (planners/peers/mpbpeers/
tesseract.py: the cells written as a .bt, read by Tesseract's URDF
parser, one link) against the fallback, the cells merged into boxes on
one link, and what a collision check then costs on each.

Per problem (MotionBenchMaker's, SET's FIRST.. COUNT of them: the scene
converted by bench/mbm_scene.py, then what `mpb sense` sees of it with
its default two cameras, 1 cm cells, as `seen: {sense:}` does):
- setup: Adapter.build() alone, the robot's Environment kept (as the
  peer keeps it: the last scene's links removed, the new ones added),
  median of ROUNDS, the two ways alternated; the kit's reading of the
  scene (peer.Problem: libmpbench's cells and boxes) is the same for
  both and given apart;
- check: one discrete contact test (Tesseract's default manager,
  Bullet, first contact) of the Panda at each of 21 states on the
  straight line from start to goal and at 200 states drawn in the
  joints' limits (seed 1), median per test, and how many touch the
  scene.

Run with the peer's environment and the build's libmpbench:

    MPB_LIBMPBENCH=build/libmpbench/libmpbench.so \\
    MPB_MESH_PATH=.cache/robots/vamp-planner-0.6.4/panda \\
    PYTHONPATH=planners/peers:planners/python \\
    .cache/peers/tesseract/bin/python3 bench/tesseract_octree.py \\
        [--set table_pick_panda] [--first 1] [--count 2] [--rounds 9]
"""
import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from types import SimpleNamespace

import numpy as np

from mpbpeers import peer, tesseract
from tesseract_robotics.tesseract_collision import (ContactRequest,
                                                    ContactResultMap,
                                                    ContactResultVector,
                                                    ContactTestType_FIRST)

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
PANDA = os.path.join(ROOT, ".cache/robots/vamp-planner-0.6.4/panda")
JOINTS = [f"panda_joint{i}" for i in range(1, 8)]
sys.path.insert(0, HERE)
from peer_worker_cost import _request_values  # noqa: E402


def sensed(scene_yaml, mpb):
    """The sensed scene text of a MotionBenchMaker scene file."""
    with tempfile.TemporaryDirectory() as d:
        src, out = os.path.join(d, "in.scene"), os.path.join(d, "out.scene")
        with open(src, "w") as f:
            f.write(subprocess.run(
                [sys.executable, os.path.join(HERE, "mbm_scene.py"),
                 scene_yaml], check=True, capture_output=True,
                text=True).stdout)
        subprocess.run([mpb, "sense", src, "-o", out], check=True,
                       capture_output=True)
        return open(out).read()


def problem(robot, scene, workdir):
    req = SimpleNamespace(robot_format="urdf", scene_format="moveit-scene",
                          robot=robot, scene=scene, joint_names=JOINTS,
                          held_names=[], held_values=[])
    return peer.Problem(req, workdir)


LOWER = [-2.8973, -1.7628, -2.8973, -3.0718, -2.8973, -0.0175, -2.8973]
UPPER = [2.8973, 1.7628, 2.8973, -0.0698, 2.8973, 3.7525, 2.8973]


def check_cost(model, states, rounds):
    """(median seconds per contact test, how many states touch)."""
    env = model["env"]
    manager = env.getDiscreteContactManager()
    times, touching = [], 0
    for r in range(rounds):
        for q in states:
            env.setState(JOINTS, q)
            state = env.getState()
            manager.setCollisionObjectsTransform(state.link_transforms)
            found = ContactResultMap()
            t0 = time.perf_counter()
            manager.contactTest(found, ContactRequest(ContactTestType_FIRST))
            times.append(time.perf_counter() - t0)
            if r == 0:
                flat = ContactResultVector()
                found.flattenMoveResults(flat)
                touching += any("mpb_scene" in c.link_names[0] +
                                c.link_names[1] for c in flat)
    return statistics.median(times), touching


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--set", default="table_pick_panda")
    ap.add_argument("--first", type=int, default=1)
    ap.add_argument("--count", type=int, default=2)
    ap.add_argument("--rounds", type=int, default=9)
    ap.add_argument("--mpb", default=os.path.join(
        os.environ.get("MPB_BUILD", os.path.join(ROOT, "build")),
        "tools", "mpb"))
    a = ap.parse_args()
    robot = open(os.path.join(PANDA, "panda.urdf")).read() + \
        open(os.path.join(PANDA, "panda.srdf")).read()
    work = tempfile.mkdtemp(prefix="mpb-bench-tess-")
    ways = {"octree": tesseract.Adapter(), "boxes": tesseract.Adapter()}
    ways["boxes"].OCTREES = False
    print(f"# tesseract setup of sensed {a.set} {a.first}.."
          f"{a.first + a.count - 1}, {a.rounds} rounds; load average "
          f"{os.getloadavg()[0]:.1f}")
    folder = os.path.join(PANDA, "problems", a.set)
    for k in range(a.first, a.first + a.count):
        scene = sensed(os.path.join(folder, f"scene{k:04d}.yaml"), a.mpb)
        start, goal = _request_values(os.path.join(folder,
                                                   f"request{k:04d}.yaml"))
        t0 = time.perf_counter()
        prob = problem(robot, scene, work)
        t_read = time.perf_counter() - t0
        cells = sum(c.count_points() for c in prob.clouds)
        boxes = sum(1 for s in prob.shapes if s.cloud is not None)
        for adapter in ways.values():       # the Environment made
            adapter.build(prob, None)
        setup = {w: [] for w in ways}
        for _ in range(a.rounds):
            for w, adapter in ways.items():
                t0 = time.perf_counter()
                model = adapter.build(prob, None)
                setup[w].append(time.perf_counter() - t0)
        line = [f"{a.set}/{k:04d}: {cells} cells, {boxes} merged boxes; "
                f"the kit's reading {t_read * 1e3:.0f} ms"]
        straight = [np.array(start) + (np.array(goal) - np.array(start)) * s
                    for s in np.linspace(0.0, 1.0, 21)]
        drawn = list(np.random.default_rng(1).uniform(LOWER, UPPER,
                                                      (200, 7)))
        for w, adapter in ways.items():
            model = adapter.build(prob, None)
            assert adapter.CLOUDS == ("points" if w == "octree" else "")
            line_t, line_n = check_cost(model, straight, a.rounds)
            drawn_t, drawn_n = check_cost(model, drawn, 1)
            line.append(f"{w}: setup {statistics.median(setup[w]) * 1e3:.0f}"
                        f" ms (min {min(setup[w]) * 1e3:.0f}); a check "
                        f"{line_t * 1e3:.2f} ms on the line ({line_n}/21 "
                        f"touch), {drawn_t * 1e3:.2f} ms drawn ({drawn_n}/200)")
        print("\n  ".join(line))
        sys.stdout.flush()
    os._exit(0)     # skip the bindings' late teardown


if __name__ == "__main__":
    main()
