#!/usr/bin/env python3
"""bench/peer_worker_cost.py - what the peers' worker process costs per
run (planners/peers/mpbpeers/peer.py: each library plans in a worker
forked by the serving process, which sends it the encoded request over a
pipe and reads the encoded result back, and kills it past the time
limit): the same requests solved in-process (peer.Peer.solve) and
through the worker (peer.Worker.solve), in the same process, alternated,
models built beforehand on both sides (world_setup_time is not a run's).

Two measurements:
- `null`: an adapter whose plan returns at once a 21-waypoint stage (the
  size of TrajOpt's): the worker's own cost, IPC of request and result
  plus the kit's handling, in ms per run;
- the peer's algorithm (default tesseract TrajOpt, which has no random
  seed: both sides do about the same work): its wall time per run both
  ways, and the ratio.

Run with the peer's environment and the build's libmpbench:

    MPB_LIBMPBENCH=build/libmpbench/libmpbench.so \\
    MPB_MESH_PATH=.cache/robots/vamp-planner-0.6.4/panda \\
    PYTHONPATH=planners/peers .cache/peers/tesseract/bin/python3 \\
        bench/peer_worker_cost.py [--peer tesseract] [--algorithm TrajOpt]
        [--set table_pick_panda] [--count 3] [--rounds 5] [--null-rounds 200]

The problems are MotionBenchMaker's (SET's first COUNT), their scenes
converted by bench/mbm_scene.py. No LCM: the daemon's side is not
measured here.
"""
import argparse
import hashlib
import importlib
import os
import re
import statistics
import subprocess
import sys
import time

from mpb import goal_t, plan_request_t, plan_result_t

from mpbpeers import peer

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
PANDA = os.path.join(ROOT, ".cache/robots/vamp-planner-0.6.4/panda")
JOINTS = [f"panda_joint{i}" for i in range(1, 8)]


def _request_values(path):
    """(start, goal) of the Panda joints from an MBM request YAML."""
    text = open(path).read()
    goal = {}
    for m in re.finditer(r"(?:joint_name:\s*(\S+)\s*\n\s*position:\s*(\S+))|"
                         r"(?:position:\s*(\S+)\s*\n\s*joint_name:\s*(\S+))",
                         text):
        name, value = (m.group(1), m.group(2)) if m.group(1) else \
            (m.group(4), m.group(3))
        goal[name] = float(value)
    js = text[text.index("joint_state:"):]
    names = re.search(r"name:\s*\[([^\]]*)\]", js).group(1)
    values = re.search(r"position:\s*\[([^\]]*)\]", js).group(1)
    start = dict(zip([n.strip() for n in names.split(",")],
                     [float(v) for v in values.split(",")]))
    return [start[j] for j in JOINTS], [goal[j] for j in JOINTS]


def requests(problem_set, count, algorithm, time_limit):
    robot = open(os.path.join(PANDA, "panda.urdf")).read() + \
        open(os.path.join(PANDA, "panda.srdf")).read()
    folder = os.path.join(PANDA, "problems", problem_set)
    out = []
    for k in range(1, count + 1):
        scene = subprocess.run(
            [sys.executable, os.path.join(HERE, "mbm_scene.py"),
             os.path.join(folder, f"scene{k:04d}.yaml")],
            check=True, capture_output=True, text=True).stdout
        start, goal = _request_values(os.path.join(folder,
                                                   f"request{k:04d}.yaml"))
        r = plan_request_t()
        r.attempt_id = f"bench{k}"
        r.planner_id = "bench"
        r.algorithm = algorithm
        r.params, r.num_params = [], 0
        r.time_limit, r.seed, r.memory_limit = time_limit, 1, 0.0
        r.robot_format, r.robot = "urdf", robot
        r.robot_hash = hashlib.sha256(robot.encode()).hexdigest()
        r.scene_format, r.scene = "moveit-scene", scene
        r.scene_hash = hashlib.sha256(scene.encode()).hexdigest()
        r.joint_names, r.num_joints = list(JOINTS), len(JOINTS)
        r.start = start
        g = goal_t()
        g.kind = goal_t.JOINTS
        g.joints, g.num_joints = goal, len(goal)
        g.joint_tolerance = 1e-3
        g.link = ""
        g.position = [0.0] * 3
        g.orientation_rpy = [0.0] * 3
        g.position_tolerance = [0.0] * 3
        g.orientation_tolerance = [0.0] * 3
        r.goal = g
        r.held_names, r.held_values, r.num_held = [], [], 0
        r.stored, r.num_stored = [], 0
        out.append((f"{problem_set}/{k:04d}", r))
    return out


class NullAdapter:
    """No library: the goal reached in one 21-waypoint stage at once."""
    NAME = "null"
    DESCRIPTION = "no planning"
    ALGORITHMS = ["straight"]
    APPROACH = {"straight": "sampling"}
    GOAL_REGIONS = False

    def build(self, problem, world):
        return None

    def plan(self, model, algorithm, start, goals, time_limit, seed, params):
        g = goals[0]
        path = [[a + (b - a) * i / 20 for a, b in zip(start, g)]
                for i in range(21)]
        return [("raw", 1e-6, path)], plan_result_t.SOLVED, "", []


def timed(fn, req):
    t0 = time.perf_counter()
    res = fn(req)
    return time.perf_counter() - t0, res


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--peer", default="tesseract")
    ap.add_argument("--algorithm", default="TrajOpt")
    ap.add_argument("--set", default="table_pick_panda")
    ap.add_argument("--count", type=int, default=3)
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--null-rounds", type=int, default=200)
    ap.add_argument("--time-limit", type=float, default=30.0)
    a = ap.parse_args()
    adapter = importlib.import_module(f"mpbpeers.{a.peer}").Adapter()
    null = NullAdapter()
    reqs = requests(a.set, a.count, a.algorithm, a.time_limit)
    # Workers first: forked before anything else runs here.
    nw, aw = peer.Worker(null), peer.Worker(adapter)
    ni, ai = peer.Peer(null), peer.Peer(adapter)

    print(f"# {a.peer} {a.algorithm} on {a.set} 1-{a.count}; "
          f"load average {os.getloadavg()[0]:.1f}")
    _, nreq = reqs[0]
    nreq.algorithm = "straight"
    for fn in (ni.solve, nw.solve):      # models built
        fn(nreq)
    inproc, worker = [], []
    for _ in range(a.null_rounds):
        inproc.append(timed(ni.solve, nreq)[0])
        worker.append(timed(nw.solve, nreq)[0])
    mi, mw = statistics.median(inproc), statistics.median(worker)
    print(f"null: in-process {mi * 1e3:.2f} ms, worker {mw * 1e3:.2f} ms "
          f"per run (median of {a.null_rounds}): the worker adds "
          f"{(mw - mi) * 1e3:.2f} ms")
    nreq.algorithm = a.algorithm

    total_i, total_w = [], []
    for name, req in reqs:
        for fn in (ai.solve, aw.solve):  # models built
            res = fn(req)
        ti, tw = [], []
        for _ in range(a.rounds):
            t, ri = timed(ai.solve, req)
            ti.append(t)
            t, rw = timed(aw.solve, req)
            tw.append(t)
        mi, mw = statistics.median(ti), statistics.median(tw)
        total_i.append(mi)
        total_w.append(mw)
        print(f"{name}: status {ri.status}/{rw.status}, in-process "
              f"{mi:.3f} s, worker {mw:.3f} s (medians of {a.rounds}), "
              f"ratio {mw / mi:.3f}")
        sys.stdout.flush()
    si, sw = sum(total_i), sum(total_w)
    print(f"all: in-process {si:.3f} s, worker {sw:.3f} s, ratio "
          f"{sw / si:.3f}")
    sys.stdout.flush()
    os._exit(0)     # skip the bindings' late teardown


if __name__ == "__main__":
    main()
