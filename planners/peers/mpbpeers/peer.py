"""peer.py - what every peer planner shares: a library's adapter plugged
into the Python kit (mpbplanner).

A peer is another library's planner, used as its own users use it and
judged by mpbench's verifier. This module turns a plan request into what
such a user holds: the URDF and SRDF as files (meshes at absolute paths),
the scene's objects as plain shapes in the world frame, the start and the
goal configurations; the adapter (one file per library beside this one)
builds its library's model from them and plans. Goal regions the library
cannot take become goal configurations sampled by IK in the region with
libmpbench (the kit's World), counted in time_other (tau_o).

Each library runs in a worker process of its own, forked before LCM
starts: C++ bindings that hold Python's lock while they plan (mplib's,
pybullet's) would otherwise silence the kit's heartbeats, and the daemon
would take the planner for gone. The worker measures the run's peak
memory (the kit's Watch) and enforces its memory_limit; the serving
process answers TIMEOUT, and starts a new worker, when one has not
answered by the time limit plus 0.3 s after its model was built, or has
not built it in 120 s; the library's own limit comes first. The daemon
is told when a model is built and when planning starts (run_ack_t
SETTING_UP, PLANNING), so that its deadline waits for the build.

Timing: building the library's model (and the kit's World) is reported as
world_setup_time, outside time_total (also in a TIMEOUT answer for a
worker that was stopped: the worker says what it took when planning
starts); each stage's time is the library's
call alone (raw: its planning call; then its own simplification or
smoothing); time_total is time_other plus the stages (plus the
planning call, for a run that returns no path).
"""
import argparse
import math
import multiprocessing
import os
import re
import struct
import sys
import tempfile
import time

from mpb import goal_t, named_value_t, plan_request_t, plan_result_t

from mpbplanner import request as kit_request
from mpbplanner.auth import Auth, AuthError
from mpbplanner.memory import Watch
from mpbplanner.node import Node
from mpbplanner.world import World, WorldError, split_robot_text

from . import clouds


class InvalidRequest(Exception):
    """A request this peer cannot take; the message says why."""


# ---- the request as a library's user holds it -----------------------------

def _quat_matrix(x, y, z, w):
    n = math.sqrt(x * x + y * y + z * z + w * w) or 1.0
    x, y, z, w = x / n, y / n, z / n, w / n
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]


def _matrix_quat(m):
    t = m[0][0] + m[1][1] + m[2][2]
    if t > 0:
        s = math.sqrt(t + 1.0) * 2
        return [(m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s,
                (m[1][0] - m[0][1]) / s, 0.25 * s]
    i = max(range(3), key=lambda k: m[k][k])
    j, k = (i + 1) % 3, (i + 2) % 3
    s = math.sqrt(1.0 + m[i][i] - m[j][j] - m[k][k]) * 2
    q = [0.0] * 4
    q[i] = 0.25 * s
    q[j] = (m[j][i] + m[i][j]) / s
    q[k] = (m[k][i] + m[i][k]) / s
    q[3] = (m[k][j] - m[j][k]) / s
    return q


def _compose(p1, q1, p2, q2):
    """Pose (p1, q1) times pose (p2, q2); quaternions x y z w."""
    r1, r2 = _quat_matrix(*q1), _quat_matrix(*q2)
    p = [p1[i] + sum(r1[i][k] * p2[k] for k in range(3)) for i in range(3)]
    r = [[sum(r1[i][k] * r2[k][j] for k in range(3)) for j in range(3)]
         for i in range(3)]
    return p, _matrix_quat(r)


class Shape:
    """One shape of the scene in the world frame: kind box (dims = side
    lengths), sphere (radius), cylinder (radius, length along z) or mesh
    (vertices, triangles); position xyz and quaternion xyzw; cloud: the
    id of the octree or point cloud it stands for (a merged box of its
    occupied cells, a sphere of its points), None for an object's."""

    def __init__(self, name, kind, dims, position, quat, vertices=None,
                 triangles=None, cloud=None):
        self.name, self.kind, self.dims = name, kind, dims
        self.position, self.quat = position, quat
        self.vertices, self.triangles = vertices, triangles
        self.cloud = cloud

    def matrix(self):
        """The 4x4 homogeneous pose, as nested lists."""
        r = _quat_matrix(*self.quat)
        return [r[0] + [self.position[0]], r[1] + [self.position[1]],
                r[2] + [self.position[2]], [0.0, 0.0, 0.0, 1.0]]


def parse_scene(text):
    """The shapes of a MoveIt .scene text's objects (docs/scenes.md),
    world frame; its octrees and point clouds are read_clouds()'s.
    Cones, planes and carried objects are refused: no peer takes them
    as a user would without changing the problem."""
    lines = text.splitlines()
    if not any(ln.strip() for ln in lines):
        return []
    i = 1
    shapes = []
    newer = None
    tokens = []

    def next_line():
        nonlocal i
        while i < len(lines) and not lines[i].strip():
            i += 1
        if i >= len(lines):
            raise InvalidRequest("scene: unexpected end")
        i += 1
        return lines[i - 1].strip()

    def numbers(count):
        while len(tokens) < count:
            tokens.extend(next_line().split())
        out = [float(t) for t in tokens[:count]]
        del tokens[:count]
        return out

    while True:
        line = next_line() if not tokens else tokens.pop(0)
        if line == ".":
            break
        if not line.startswith("*"):
            raise InvalidRequest(f"scene line {i}: expected '*' or '.'")
        oid = line[1:].strip()
        if newer is None:
            newer = len(lines[i].split()) > 1 if i < len(lines) else False
        pos, quat = [0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]
        if newer:
            pos, quat = numbers(3), numbers(4)
        count = int(numbers(1)[0])
        for s in range(count):
            kind = (tokens.pop(0) if tokens else next_line()).strip()
            verts = tris = None
            if kind == "box":
                dims = numbers(3)
            elif kind == "sphere":
                dims = numbers(1)
            elif kind == "cylinder":
                dims = numbers(2)
            elif kind == "mesh":
                nv, nt = (int(v) for v in numbers(2))
                verts = [numbers(3) for _ in range(nv)]
                tris = [[int(v) for v in numbers(3)] for _ in range(nt)]
                dims = []
            else:
                raise InvalidRequest(f"scene object '{oid}': shape '{kind}' "
                                     f"is not taken by this peer")
            spos, squat = numbers(3), numbers(4)
            numbers(4)  # colour
            wp, wq = _compose(pos, quat, spos, squat)
            shapes.append(Shape(f"{oid}#{s}", kind, dims, wp, wq, verts, tris))
        if newer:
            for _ in range(int(numbers(1)[0])):
                next_line()
                numbers(7)
    data = 0        # base64 characters of an octree line still to come
    for ln in lines[i:]:
        words = ln.split()
        if data > 0:
            data -= len(ln.strip())
            continue
        word = words[0] if words else ""
        if word == "attach":
            raise InvalidRequest("scene: carried objects ('attach') are not "
                                 "taken by this peer")
        if word == "octree" and len(words) > 4 and words[4].isdigit():
            data = 4 * ((int(words[4]) + 2) // 3)
    return shapes


def read_clouds(text):
    """The scene's octrees and point clouds (its octree and spheres lines,
    read by libmpbench: clouds.py), and the shapes that stand for them in
    the world frame, each with its cloud's id: an octree's occupied cells
    as boxes, merged as libmpbench merges them (union exactly the cells),
    a cloud's spheres. Each cloud gets position and quat (x y z w), its
    pose as a Shape's. ([], []) for a scene without any."""
    after = text.split("\n.", 1)
    if len(after) < 2 or not re.search(r"^\s*(octree|spheres)\s", after[1],
                                       re.M):
        return [], []
    try:
        found = clouds.read(text)
    except clouds.CloudError as e:
        raise InvalidRequest(str(e)) from None
    shapes = []
    for c in found:
        quat = _matrix_quat(c.rotation)
        c.position, c.quat = list(c.translation), list(quat)
        if c.kind == "octree":
            parts = [("box", d, p) for p, d in c.boxes]
        else:
            parts = [("sphere", [c.resolution], p) for p in c.centres]
        for k, (kind, dims, p) in enumerate(parts):
            wp = [c.translation[i] + sum(c.rotation[i][j] * p[j]
                                         for j in range(3)) for i in range(3)]
            shapes.append(Shape(f"{c.id}#{k}", kind, list(dims), wp,
                                list(quat), cloud=c.id))
    return found, shapes


def _mesh_dirs():
    dirs = []
    for var in ("MPB_MESH_PATH", "ROS_PACKAGE_PATH"):
        dirs += [d for d in os.environ.get(var, "").split(":") if d]
    return dirs


def resolve_mesh(uri):
    """A URDF mesh URI as an absolute path, found as libmpbench finds it
    (docs/scenes.md, "Meshes and search paths")."""
    if uri.startswith("file://"):
        return uri[7:]
    if uri.startswith("/"):
        return uri
    tried = []
    if uri.startswith("package://"):
        pkg, _, rest = uri[10:].partition("/")
        for d in _mesh_dirs():
            tried += [os.path.join(d, pkg, rest)]
            if os.path.basename(d.rstrip("/")) == pkg:
                tried.append(os.path.join(d, rest))
    else:
        tried = [os.path.join(d, uri) for d in _mesh_dirs()]
    for t in tried:
        if os.path.isfile(t):
            return os.path.abspath(t)
    raise InvalidRequest(f"mesh '{uri}' not found (MPB_MESH_PATH, "
                         f"ROS_PACKAGE_PATH)")


class Problem:
    """A request as files and plain values: urdf_path, srdf_path (or
    None), urdf and srdf texts (meshes absolute), shapes, joints, the
    held joints, start, and the experiment's base name. The scene's
    octrees and point clouds are in shapes as boxes and spheres (their
    cloud set), for a library that takes no cloud, and in clouds
    (clouds.Cloud: points() for a library's point cloud API), for one
    that does and leaves those shapes out."""

    def __init__(self, req, workdir, mesh_map=None):
        if req.robot_format != "urdf":
            raise InvalidRequest(f"robot format '{req.robot_format}' is not "
                                 f"taken by peers (urdf)")
        if req.scene_format not in ("moveit-scene", ""):
            raise InvalidRequest(f"scene format '{req.scene_format}' is not "
                                 f"taken by peers (moveit-scene)")
        urdf, srdf = split_robot_text(req.robot)
        if "</robot" not in urdf:
            raise InvalidRequest("robot: no </robot>")
        srdf = (srdf or "").strip()

        def absolute(m):
            path = resolve_mesh(m.group(2))
            if mesh_map:
                path = mesh_map(path)
            return m.group(1) + path + m.group(3)

        urdf = re.sub(r'(<mesh[^>]*filename=")([^"]+)(")', absolute, urdf)
        self.urdf, self.srdf = urdf, srdf or None
        self.urdf_path = os.path.join(workdir, "robot.urdf")
        with open(self.urdf_path, "w") as f:
            f.write(urdf)
        self.srdf_path = None
        if srdf:
            self.srdf_path = os.path.join(workdir, "robot.srdf")
            with open(self.srdf_path, "w") as f:
                f.write(srdf)
        self.shapes = parse_scene(req.scene)
        self.clouds, shapes = read_clouds(req.scene)
        self.shapes += shapes
        self.joints = list(req.joint_names)
        self.held = dict(zip(req.held_names, req.held_values))


def child_link(urdf, joint):
    """The child link of joint in the URDF text: a planning group's tip is
    its last joint's child (MPLib's move group, srmp's end effector)."""
    m = re.search(r'<joint[^>]*name="%s".*?<child\s+link="([^"]+)"'
                  % re.escape(joint), urdf, re.S)
    if not m:
        raise InvalidRequest(f"joint '{joint}' not in the URDF")
    return m.group(1)


def write_obj(path, shape):
    """A scene's mesh shape as an OBJ file (for libraries that load meshes
    from files only)."""
    with open(path, "w") as f:
        for v in shape.vertices:
            f.write(f"v {v[0]!r} {v[1]!r} {v[2]!r}\n")
        for t in shape.triangles:
            f.write(f"f {t[0] + 1} {t[1] + 1} {t[2] + 1}\n")


def acm_pairs(srdf):
    """The SRDF's disable_collisions pairs."""
    return re.findall(r'<disable_collisions\s+link1="([^"]+)"\s+'
                      r'link2="([^"]+)"', srdf or "")


# ---- the run ----------------------------------------------------------------

def _stage(name, seconds, path, n, times=None):
    """A stage_t; times (a waypoint's time, s), when given, go on the wire
    as stage_t.times (the daemon checks them: one per waypoint, finite,
    from 0 or later, non-decreasing)."""
    return kit_request.stage(name, seconds, path, n, times)


def _value(name, v):
    nv = named_value_t()
    nv.name, nv.value = name, float(v)
    return nv


class Peer:
    """Serves one library: adapter has NAME, ALGORITHMS, APPROACH (each
    algorithm's kind of planner: "sampling", "search", "optimisation" or
    "hybrid"), GOAL_REGIONS (False: the kit samples IK goals), CLOUDS
    ("points": it gives the library the scene's octrees and point clouds
    as points, problem.clouds; else it takes their boxes and spheres
    from problem.shapes; each run says which, as the named value
    cloud_points or cloud_shapes: how many),
    build(problem) -> model (cached while the robot and scene hashes
    stay), and plan(model, algorithm, start, goals, time_limit, seed,
    params) -> (stages, status, message, values), stages a list of
    (name, seconds, path) or (name, seconds, path, times): times the
    trajectory's time at each waypoint (s, from 0), for a library that
    returns a time-parameterised trajectory. Return the path the library
    gave whatever its own verdict: mpbench verifies it either way."""

    def __init__(self, adapter):
        self.adapter = adapter
        self.key = None
        self.model = self.world = None
        self.cloud_values = []
        self.workdir = tempfile.mkdtemp(prefix=f"mpb-{adapter.NAME}-")

    def _prepare(self, req, building):
        """The library's model and the kit's World; seconds spent, or None
        when cached. building() is called first when they are built."""
        key = (req.robot_hash, req.scene_hash, tuple(req.joint_names))
        if key == self.key:
            return None
        building()
        t0 = time.monotonic()
        if self.world:
            self.world.close()
        self.key = self.model = self.world = None
        try:
            self.world = World(req.robot_format, req.robot, req.scene_format,
                               req.scene, list(req.joint_names))
        except WorldError as e:
            raise InvalidRequest(str(e)) from None
        problem = Problem(req, self.workdir,
                          getattr(self.adapter, "mesh_map", None))
        self.model = self.adapter.build(problem, self.world)
        self.key = key
        # What the library was given for the scene's octrees and point
        # clouds, as named values of every run (docs/results-peers.md).
        self.cloud_values = []
        if problem.clouds and getattr(self.adapter, "CLOUDS", "") == "points":
            self.cloud_values = [("cloud_points", sum(
                c.count_points() for c in problem.clouds))]
        elif problem.clouds:
            self.cloud_values = [("cloud_shapes", sum(
                1 for s in problem.shapes if s.cloud is not None))]
        return time.monotonic() - t0

    def _goals(self, req, deadline):
        """The joint goal, or up to five collision-free IK samples inside
        the pose region: the Python planner's own sampling (solve.py)."""
        if req.goal.kind == goal_t.POSE_REGION and \
                getattr(self.adapter, "GOAL_REGIONS", False) is None:
            raise InvalidRequest(f"{self.adapter.NAME} takes joint goals "
                                 f"only")
        try:
            return kit_request.goal_configs(self.world, req, self.world.free,
                                           deadline)
        except kit_request.InvalidRequest as e:
            raise InvalidRequest(str(e)) from None

    def solve(self, req, ready=lambda setup: None, building=lambda: None):
        """The result of one request; building() is called when the models
        must be built first, ready(setup) once they are, when planning
        starts: setup the seconds they took (None: cached)."""
        res = plan_result_t()
        res.stages, res.values, res.progress = [], [], []
        res.message = ""
        try:
            t_plan = 0.0
            params = {p.key: p.value for p in req.params}
            known = getattr(self.adapter, "PARAMS", {})
            for key in params:
                if key not in known:
                    raise InvalidRequest(
                        f"unknown parameter '{key}' ({self.adapter.NAME} "
                        f"takes " + (", ".join(sorted(known)) if known else
                                     "none: the library's own defaults")
                        + ")")
            if req.algorithm not in self.adapter.ALGORITHMS:
                raise InvalidRequest(f"unknown algorithm '{req.algorithm}' "
                                     f"({', '.join(self.adapter.ALGORITHMS)})")
            setup = self._prepare(req, building)
            if setup is not None:
                res.values.append(_value("world_setup_time", setup))
            for name, v in self.cloud_values:
                res.values.append(_value(name, v))
            self.world.hold(list(req.held_names), list(req.held_values))
            ready(setup)
            if req.num_joints != self.world.num_joints:
                raise InvalidRequest(f"start has {req.num_joints} joints, "
                                     f"the robot {self.world.num_joints}")
            t0 = time.monotonic()
            goals = self._goals(req, t0 + req.time_limit)
            res.time_other = time.monotonic() - t0
            if not goals:
                res.status = plan_result_t.FAILED
                res.message = "no collision-free goal configuration found by IK"
            else:
                left = max(req.time_limit - res.time_other, 0.01)
                t_plan = time.monotonic()
                stages, status, message, values = self.adapter.plan(
                    self.model, req.algorithm, list(req.start), goals, left,
                    req.seed, params)
                t_plan = time.monotonic() - t_plan
                res.status, res.message = status, message or ""
                for name, seconds, path, *times in stages:
                    res.stages.append(_stage(name, seconds, path,
                                             self.world.num_joints,
                                             times[0] if times else None))
                for name, v in values:
                    res.values.append(_value(name, v))
            # The stages' times (the library's calls alone); a run
            # without a path spent its planning call.
            res.time_total = res.time_other + (
                sum(s.time for s in res.stages) if res.stages else
                t_plan)
            if res.time_total <= 0:
                res.time_total = 1e-9
        except InvalidRequest as e:
            res.status = plan_result_t.INVALID_REQUEST
            res.message = str(e)
        res.num_stages, res.num_values = len(res.stages), len(res.values)
        res.num_progress = 0
        return res


GRACE_S = 0.3        # past the time limit, the worker is stopped
SETUP_MAX_S = 120.0  # at most this long to build a library's model, as
                     # mpbenchd waits (MPBD_SETUP_ALLOWANCE_S)


_CLOUD_FORMS = ("cloud_points", "cloud_shapes")


def _pack_clouds(values):
    """A Peer's cloud_values (at most one) for the b"S" message, so that
    a run stopped at its time limit still says what the library was
    given."""
    return b"".join(struct.pack("<Bd", _CLOUD_FORMS.index(n), v)
                    for n, v in values[:1])


def _unpack_clouds(data):
    if len(data) != 9 or data[0] >= len(_CLOUD_FORMS):
        return []
    return [(_CLOUD_FORMS[data[0]], struct.unpack("<d", data[1:])[0])]


def _die_with_parent():
    """Linux: SIGKILL this process when the serving process dies, even by
    SIGKILL, so that no worker outlives its planner."""
    try:
        import ctypes
        import signal
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, int(signal.SIGKILL), 0, 0, 0)   # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        pass


def _worker(adapter, conn, parent_end):
    """The worker process: encoded requests in, encoded results out."""
    parent_end.close()      # else the pipe never ends for us
    _die_with_parent()
    if os.getppid() == 1:
        os._exit(0)
    p = Peer(adapter)
    while True:
        try:
            data = conn.recv_bytes()
        except (EOFError, OSError):
            os._exit(0)
        req = plan_request_t.decode(data)
        with Watch(req.memory_limit) as watch:
            try:
                res = p.solve(req, lambda setup: conn.send_bytes(
                    b"S" + struct.pack("<d", -1.0 if setup is None else setup)
                    + _pack_clouds(p.cloud_values)),
                    lambda: conn.send_bytes(b"B"))
            except MemoryError:
                res = None
            except Exception as e:      # the library's: say so, go on
                import traceback
                traceback.print_exc()
                res = plan_result_t()
                res.stages, res.values, res.progress = [], [], []
                res.num_stages = res.num_values = res.num_progress = 0
                res.status = plan_result_t.FAILED
                res.message = f"{type(e).__name__}: {e}"[:1000]
            if res is None:
                res = plan_result_t()
                res.stages, res.values, res.progress = [], [], []
                res.num_stages = res.num_values = res.num_progress = 0
                res.status = plan_result_t.MEMORY
                res.message = f"out of memory (MemoryError) under the " \
                              f"memory_limit of {watch.limit_mb:g} MB"
        res.memory = watch.peak_mb
        if watch.note:
            res.message = watch.note + ("; " + res.message if res.message else "")
        try:
            conn.send_bytes(res.encode())
        except OSError:
            os._exit(0)


class Worker:
    """The serving process's handle on the worker."""

    def __init__(self, adapter):
        self.adapter = adapter
        self.ctx = multiprocessing.get_context("fork")
        self.proc = self.conn = None
        self.stopped = []       # killed workers, reaped later
        self._start()

    def _start(self):
        mine, theirs = self.ctx.Pipe()
        self.proc = self.ctx.Process(target=_worker,
                                     args=(self.adapter, theirs, mine),
                                     daemon=True)
        self.proc.start()
        theirs.close()
        self.conn = mine

    def _restart(self):
        # SIGKILL, and a new worker at once: the old one's exit (its
        # memory given back, 50-100 ms for a built model) is not waited
        # for before the TIMEOUT answer; it is reaped at the next request.
        self.proc.kill()
        self.stopped.append(self.proc)
        self.conn.close()
        self._start()

    def solve(self, req, limits=None):
        while self.stopped:
            self.stopped.pop().join()
        t0 = time.monotonic()
        self.conn.send_bytes(req.encode())
        # Building the models may come first (b"B"): not the run's time,
        # so the deadline starts when the worker says planning starts
        # (b"S"), and mpbenchd is told both (Limits.setting_up(),
        # planning()) so that its deadline waits for the build too.
        limit = req.time_limit + GRACE_S + SETUP_MAX_S
        setup = None
        clouds_given = []
        while True:
            if self.conn.poll(0.05):
                try:
                    data = self.conn.recv_bytes()
                except EOFError:            # the worker is gone
                    self.proc.join(1.0)
                    code = self.proc.exitcode
                    self._start()
                    raise RuntimeError(f"{self.adapter.NAME}'s worker died "
                                       f"(exit {code})") from None
                if data == b"B":
                    if limits is not None:
                        limits.setting_up()
                    continue
                if len(data) not in (9, 18) or data[:1] != b"S":
                    return plan_result_t.decode(data)
                t0 = time.monotonic()
                setup = struct.unpack("<d", data[1:9])[0]
                clouds_given = _unpack_clouds(data[9:])
                limit = req.time_limit + GRACE_S
                if limits is not None and setup >= 0:
                    limits.planning()
                continue
            if not self.proc.is_alive():
                code = self.proc.exitcode
                self._start()
                raise RuntimeError(f"{self.adapter.NAME}'s worker died "
                                   f"(exit {code})")
            if time.monotonic() - t0 > limit:
                self._restart()
                res = plan_result_t()
                res.stages, res.values, res.progress = [], [], []
                res.num_stages = res.num_values = res.num_progress = 0
                res.status = plan_result_t.TIMEOUT
                res.message = (
                    f"{self.adapter.NAME} did not return by the time limit "
                    f"plus {GRACE_S} s after its model was built: stopped"
                    if setup is not None else
                    f"{self.adapter.NAME} did not build its model within "
                    f"{SETUP_MAX_S:g} s: stopped")
                res.time_total = time.monotonic() - t0
                # The model built for this run (by the worker now gone)
                # stays the world's setup, outside the run's time.
                if setup is not None and setup >= 0:
                    res.values = [_value("world_setup_time", setup)]
                res.values += [_value(n, v) for n, v in clouds_given]
                res.num_values = len(res.values)
                return res


def main(adapter, argv=None):
    ap = argparse.ArgumentParser(
        prog=f"mpb-planner-{adapter.NAME}",
        description=f"mpbench peer planner: {adapter.DESCRIPTION} "
                    f"Algorithms: {', '.join(adapter.ALGORITHMS)}.")
    ap.add_argument("-u", "--lcm-url", default="")
    ap.add_argument("-s", "--secret-file", metavar="FILE")
    ap.add_argument("-v", "--verbose", action="store_true")
    args = ap.parse_args(argv)
    try:
        auth = Auth(args.secret_file) if args.secret_file else None
    except AuthError as e:      # libmpbench's line, naming the file
        print(f"mpb-planner-{adapter.NAME}: {e}", file=sys.stderr)
        sys.exit(1)
    worker = Worker(adapter)    # forked before LCM's threads start
    node = Node(adapter.NAME, adapter.ALGORITHMS, args.lcm_url, auth,
                args.verbose, getattr(adapter, "APPROACH", None))
    import signal
    signal.signal(signal.SIGTERM, lambda *_: node.stop())
    signal.signal(signal.SIGINT, lambda *_: node.stop())
    node.log(f"{node.planner_id} ready: {', '.join(adapter.ALGORITHMS)}")
    node.serve(worker.solve)
    sys.stdout.flush()
    sys.stderr.flush()
    # Skip the interpreter's teardown: some libraries' bindings (nanobind,
    # pybullet) print or crash when destroyed late.
    os._exit(0)
