"""klampt.py - the peer `klampt`: Klampt 0.10.1 (pip klampt==0.10.1.post1)
and its sampling-based planners (SBL, lazy PRM*, bidirectional RRT) on
its own robot and world model, collision checking by Klampt's own
geometry code (PQP on triangle meshes; its primitives against meshes).

As a user: a WorldModel reads a copy of the request's URDF made for
Klampt (klampt_urdf.py beside this file: mesh names absolute,
<klampt freeze_root_link="1"/>, the <mimic> tags removed, a follower of
a held leader set from it; a link with a <collision> that Klampt loads
without geometry is refused by name), robot.enableSelfCollision(i, j, False) for
every pair the SRDF disables (Klampt itself already skips parent and
child links), the scene's shapes as terrains (WorldModel.makeTerrain):
boxes and spheres as Klampt's GeometricPrimitives, meshes as its
TriangleMesh, cylinders as a triangle mesh (Klampt's cylinder is only
"semi-supported": a 32-sided prism circumscribing the cylinder, so
Klampt's obstacle holds mpbench's); an octree as its occupied cells,
boxes merged as libmpbench merges them, a cloud's spheres as spheres,
each cloud one terrain of a Group geometry (Klampt's OccupancyGrid would
hold the cells, but checks a mesh against it slowly: 1.7 ms for a
360-triangle sphere in a 200^3 grid).
The request's joints are Klampt's
configuration indices of their child links (Klampt numbers its
configuration by link, the frozen root's five virtual links and the
fixed joints included); the other entries hold the request's held values.

Planning: klampt.plan.motionplanning.set_random_seed(seed), then
klampt.plan.robotplanning.plan_to_config(world, robot, goal,
movingSubset=<the request's joints' indices>, type=..., **options) with
Klampt's default edgeCheckResolution (0.01), and planMore(ITERATIONS) in
a loop until getPath() gives a path or the request's time limit is
reached (checked by the wall clock between calls). Options, per
algorithm:

- sbl: perturbationRadius 0.5, randomizeFrequency 1000, shortcut 1:
  what Klampt's robotplanning.preferred_plan_options() gives for a
  feasible plan (its SBL default radius 0.1 failed the box-wall problem
  that 0.5 solved in the facts checked for issue 49);
- rrt: bidirectional 1, perturbationRadius 0.5, shortcut 1: the options
  of preferred_plan_options() for RRT without its restart (a restart
  spends the whole time limit on optimising, which none of the other
  algorithms here does);
- lazyprm*: Klampt's defaults for it (Klampt refuses shortcut and
  restart for lazy PRM*: "incompatible").

With shortcut set, Klampt's planner shortcuts the path after its first
solution, in the later planMore calls (random shortcuts that split
edges: the waypoints may grow while the length falls). Stages: "raw",
the path getPath() gives at the first solution (and the planMore time
until then); "shortcut", the path after SHORTCUT_ITERATIONS further
planMore iterations (their time; no call begins that the longest so far
would carry past the time limit), when it changed. SHORTCUT_ITERATIONS
is 40: on MotionBenchMaker's bookshelf_small 0002 and table_pick 0005
(two seeds each) the first 40 took the largest-joint-change length from
2.9-6.4 rad to 2.9-3.8, the next 100 gained 3% at most, and 100
iterations cost 3.8 s on average over the 35-problem slice, against
SBL's 1.4 s to its first path. Lazy PRM* (an optimising planner) stops
at its first solution, as the others do.

Deviations from Klampt's users: none in the planner; the URDF copy is
what its users make by hand (klampt_urdf.py); the cylinders' prism.
PARAMS override the options above.
"""
import math
import os
import time
import xml.etree.ElementTree as ET

from mpb import plan_result_t

from klampt import GeometricPrimitive, Geometry3D, TriangleMesh, WorldModel
from klampt import robotsim
from klampt.plan import motionplanning, robotplanning

from . import peer
from .klampt_urdf import klampt_urdf

ITERATIONS = 20            # planMore's iterations between clock checks
SHORTCUT_ITERATIONS = 40   # planMore's iterations of shortcutting
CYLINDER_SIDES = 32

# Klampt's C++ logs every link and mesh it loads to stdout (some 30 lines
# a model): its errors only, in the planner's log.
robotsim.set_log_level("ERROR")

OPTIONS = {
    "sbl": {"type": "sbl", "perturbationRadius": 0.5,
            "randomizeFrequency": 1000, "shortcut": 1},
    "rrt": {"type": "rrt", "bidirectional": 1, "perturbationRadius": 0.5,
            "shortcut": 1},
    "lazyprm*": {"type": "lazyprm*"},
}


def _cylinder_mesh(radius, length):
    """A prism of CYLINDER_SIDES sides about z circumscribing the
    cylinder: (vertices, triangles)."""
    n = CYLINDER_SIDES
    r = radius / math.cos(math.pi / n)
    h = length / 2
    verts = []
    for z in (-h, h):
        for k in range(n):
            a = 2 * math.pi * k / n
            verts.append([r * math.cos(a), r * math.sin(a), z])
    verts += [[0.0, 0.0, -h], [0.0, 0.0, h]]
    tris = []
    for k in range(n):
        a, b = k, (k + 1) % n
        tris += [[a, b, n + b], [a, n + b, n + a],
                 [2 * n, b, a], [2 * n + 1, n + a, n + b]]
    return verts, tris


def _mesh_geometry(verts, tris, shape):
    import numpy as np
    mesh = TriangleMesh()
    mesh.setVertices(np.array(verts, dtype=float))
    mesh.setIndices(np.array(tris, dtype=np.int32))
    g = Geometry3D(mesh)
    m = shape.matrix()
    g.transform([m[r][c] for c in range(3) for r in range(3)],
                [m[0][3], m[1][3], m[2][3]])
    return g


def _geometry(s):
    """Klampt's geometry of one scene shape, in the world frame."""
    m = s.matrix()
    if s.kind == "box":
        rot = [m[r][c] for c in range(3) for r in range(3)]   # column-major
        corner = [m[i][3] - sum(m[i][k] * s.dims[k] / 2 for k in range(3))
                  for i in range(3)]
        p = GeometricPrimitive()
        p.setBox(corner, rot, list(s.dims))
        return Geometry3D(p)
    if s.kind == "sphere":
        p = GeometricPrimitive()
        p.setSphere(list(s.position), s.dims[0])
        return Geometry3D(p)
    if s.kind == "cylinder":
        verts, tris = _cylinder_mesh(*s.dims)
        return _mesh_geometry(verts, tris, s)
    return _mesh_geometry(s.vertices, s.triangles, s)


def _collision_links(urdf):
    """The URDF's links that have a <collision>."""
    return [link.get("name") for link in ET.fromstring(urdf).iter("link")
            if link.find("collision") is not None]


def _child_links(urdf):
    """joint name -> its child link, from the URDF."""
    out = {}
    for joint in ET.fromstring(urdf).iter("joint"):
        child = joint.find("child")
        if joint.get("name") and child is not None and child.get("link"):
            out[joint.get("name")] = child.get("link")
    return out


class Adapter:
    NAME = "klampt"
    DESCRIPTION = ("Klampt 0.10.1: SBL, lazy PRM*, bidirectional RRT "
                   "(plan_to_config, its shortcutting), its own PQP "
                   "triangle-mesh collision checking.")
    ALGORITHMS = ["sbl", "lazyprm*", "rrt"]
    APPROACH = {"sbl": "sampling", "lazyprm*": "sampling", "rrt": "sampling"}
    GOAL_REGIONS = False     # plan_to_config takes a goal configuration
    PARAMS = {
        "perturbationRadius": "SBL's and RRT's step (rad); 0.5 here",
        "edgeCheckResolution": "the edge check's resolution (rad); 0.01",
        "shortcut": "1: Klampt's shortcutting after the first solution",
    }

    def build(self, problem, world):
        directory = os.path.dirname(problem.urdf_path)
        try:
            text, mimics, parts = klampt_urdf(problem.urdf, directory)
        except ValueError as e:
            raise peer.InvalidRequest(f"robot: {e}") from None
        path = os.path.join(directory, "robot-klampt.urdf")
        with open(path, "w") as f:
            f.write(text)
        kworld = WorldModel()
        if not kworld.readFile(path) or kworld.numRobots() != 1:
            raise peer.InvalidRequest("Klampt refuses the robot (its URDF "
                                      "parser, on the copy klampt_urdf made)")
        robot = kworld.robot(0)
        index = {robot.link(i).getName(): i for i in range(robot.numLinks())}
        child = _child_links(text)
        for link in _collision_links(text):
            if link in index and robot.link(index[link]).geometry().empty():
                raise peer.InvalidRequest(
                    f"link '{link}': Klampt loaded none of its collision "
                    f"geometry (its mesh file?)")

        def config_index(joint):
            link = child.get(joint)
            if link is None or link not in index:
                raise peer.InvalidRequest(f"joint '{joint}': no child link "
                                          f"in Klampt's robot")
            return index[link]

        moving = [config_index(j) for j in problem.joints]
        held = {config_index(j): v for j, v in problem.held.items()}
        for mi in mimics:
            if mi.kind == "fixed":
                continue
            if mi.leader in problem.joints:
                raise peer.InvalidRequest(
                    f"joint '{mi.joint}' mimics the moving joint "
                    f"'{mi.leader}': Klampt's plan_to_config with a moving "
                    f"subset cannot keep the coupling")
            lead = problem.held.get(mi.leader, 0.0)
            held[config_index(mi.joint)] = mi.multiplier * lead + mi.offset
        # A link's collision parts (klampt_urdf) are that link: with it
        # and with each other never checked, in each of its pairs.
        def pieces(link):
            return [link] + parts.get(link, [])
        for link, names in parts.items():
            for a in pieces(link):
                for b in pieces(link):
                    if a < b and a in index and b in index:
                        robot.enableSelfCollision(index[a], index[b], False)
        for a, b in peer.acm_pairs(problem.srdf):
            for pa in pieces(a):
                for pb in pieces(b):
                    if pa in index and pb in index:
                        robot.enableSelfCollision(index[pa], index[pb], False)
        groups = {}
        for k, s in enumerate(problem.shapes):
            if s.cloud is not None:
                groups.setdefault(s.cloud, []).append(s)
                continue
            terrain = kworld.makeTerrain(f"scene{k}")
            terrain.geometry().set(_geometry(s))
        for cid, shapes in groups.items():
            g = Geometry3D()
            g.setGroup()
            for i, s in enumerate(shapes):
                g.setElement(i, _geometry(s))
            kworld.makeTerrain(f"cloud_{cid}").geometry().set(g)
        return {"world": kworld, "robot": robot, "moving": moving,
                "held": held}

    def plan(self, model, algorithm, start, goals, time_limit, seed, params):
        t_start = time.monotonic()
        robot, moving = model["robot"], model["moving"]
        q0 = [0.0] * robot.numLinks()
        for i, v in model["held"].items():
            q0[i] = v
        qg = list(q0)
        for i, a, b in zip(moving, start, goals[0]):
            q0[i], qg[i] = a, b
        options = dict(OPTIONS[algorithm])
        resolution = 1e-2
        for key, value in params.items():
            try:
                v = float(value)
            except ValueError:
                raise peer.InvalidRequest(f"parameter '{key}': '{value}' is "
                                          f"not a number") from None
            if key == "edgeCheckResolution":
                resolution = v
            else:
                options[key] = v
        motionplanning.set_random_seed(seed & 0x7FFFFFFF)
        robot.setConfig(q0)
        try:
            plan = robotplanning.plan_to_config(
                model["world"], robot, qg, edgeCheckResolution=resolution,
                movingSubset=moving, verbose=False, **options)
        except (ValueError, RuntimeError) as e:
            return [], plan_result_t.FAILED, f"klampt: {e}", []
        if plan is None:
            return [], plan_result_t.FAILED, ("klampt: the start or the goal "
                                              "is infeasible in Klampt's "
                                              "model"), []
        deadline = t_start + time_limit
        try:
            t0 = time.monotonic()
            path = None
            while time.monotonic() < deadline:
                plan.planMore(ITERATIONS)
                path = plan.getPath()
                if path:
                    break
            t_raw = time.monotonic() - t0
            if not path:
                return [], plan_result_t.TIMEOUT, \
                    "klampt: no path within the time limit", []
            raw = [[q[i] for i in moving] for q in path]
            stages = [("raw", t_raw, raw)]
            if options.get("shortcut"):
                # Shortcutting is optional: no call begins that the
                # longest one so far would carry past the time limit.
                t1 = time.monotonic()
                done, longest = 0, 0.0
                while done < SHORTCUT_ITERATIONS:
                    t = time.monotonic()
                    if t + longest > deadline:
                        break
                    plan.planMore(ITERATIONS)
                    longest = max(longest, time.monotonic() - t)
                    done += ITERATIONS
                short = [[q[i] for i in moving] for q in plan.getPath()]
                if short and short != raw:
                    stages.append(("shortcut", time.monotonic() - t1, short))
            stats = plan.getStats()
        finally:
            plan.close()
        values = []
        for key in ("numIters", "numMilestones", "numComponents"):
            if key in stats:
                try:
                    values.append((f"klampt_{key}", float(stats[key])))
                except (TypeError, ValueError):
                    pass
        return stages, plan_result_t.SOLVED, "", values


if __name__ == "__main__":
    peer.main(Adapter())
