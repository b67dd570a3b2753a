"""solve.py - one plan request in, one plan result out.

Everything about a run that is not messaging: reading the request (its
world, start, goal and parameters), planning with RRT-Connect, shortening
the path, and timing each stage as docs/protocol.md describes.
"""
import random
import time

from mpb import goal_t, named_value_t, plan_result_t, stage_t

from . import rrt_connect
from .world import World, WorldError


class InvalidRequest(Exception):
    """A request this planner cannot use; the message says why."""


def _param(req, key, default, lo):
    for p in req.params:
        if p.key == key:
            try:
                v = float(p.value)
            except ValueError:
                raise InvalidRequest(f"param {key} must be a number, "
                                     f"not '{p.value}'") from None
            if not v >= lo:
                raise InvalidRequest(f"param {key} must be >= {lo}")
            return v
    return default


# The named value a planner reports the preparation of a world in (s):
# loading its robot and scene, outside time_total (docs/protocol.md).
WORLD_SETUP_TIME = "world_setup_time"


class WorldCache:
    """The last world built, reused while requests name the same robot,
    scene and joints (their hashes say so)."""

    def __init__(self):
        self.key, self.world = None, None
        self.setup_time = None  # s the last get() spent building a world

    def get(self, req):
        key = (req.robot_format, req.robot_hash, req.scene_format,
               req.scene_hash, tuple(req.joint_names))
        self.setup_time = None
        if key != self.key:
            t0 = time.monotonic()
            if self.world:
                self.world.close()
            self.key, self.world = None, None
            try:
                self.world = World(req.robot_format, req.robot,
                                   req.scene_format, req.scene,
                                   list(req.joint_names))
            except WorldError as e:
                raise InvalidRequest(str(e)) from None
            self.key = key
            self.setup_time = time.monotonic() - t0
        try:
            self.world.hold(list(req.held_names), list(req.held_values))
        except WorldError as e:
            raise InvalidRequest(f"held joints: {e}") from None
        return self.world


def _goal_configs(world, req, space, deadline):
    """Configurations the goal tree starts from: the joint goal, or up to
    five collision-free IK samples inside the pose region."""
    g = req.goal
    if g.kind == goal_t.JOINTS:
        if g.num_joints != world.num_joints:
            raise InvalidRequest(f"goal has {g.num_joints} joints, the "
                                 f"robot {world.num_joints}")
        return [list(g.joints)]
    if g.kind != goal_t.POSE_REGION:
        raise InvalidRequest(f"unknown goal kind {g.kind}")
    try:
        region = world.goal_region(g.link, g.position, g.position_tolerance,
                                   g.orientation_rpy, g.orientation_tolerance)
    except WorldError as e:
        raise InvalidRequest(str(e)) from None
    rng = [req.seed & 0xFFFFFFFFFFFFFFFF]
    goals = []
    for attempt in range(50):
        if len(goals) == 5 or time.monotonic() >= deadline:
            break
        # IK seeded by the start lands near it, where the path is short;
        # but near a colliding answer all collide: then start at random.
        seed = list(req.start) if attempt % 8 == 0 else None
        q = world.sample_goal(region, seed, rng)
        if q is not None and space.free(q):
            goals.append(q)
    return goals


def _stage(name, seconds, path, num_joints):
    st = stage_t()
    st.name, st.time = name, seconds
    st.num_waypoints, st.num_joints = len(path), num_joints
    st.waypoints = [x for q in path for x in q]
    st.num_values = len(st.waypoints)
    return st


def solve(req, cache, limits):
    """Answer one plan_request_t with a plan_result_t (run_id and planner_id
    left for the caller), by limits.deadline (limits.py) unless
    limits.stopping() says to stop first."""
    t0 = time.monotonic()
    deadline = limits.deadline
    res = plan_result_t()
    res.stages, res.values, res.progress = [], [], []
    try:
        step = _param(req, "range", 0.5, 1e-6)
        resolution = _param(req, "resolution", 0.005, 1e-6)
        # Tests of the kit's memory measure and limit: hold this many MB,
        # written (so resident), while planning; past memory_limit the
        # MemoryError reaches the kit, which answers MEMORY.
        held = b"\x01" * int(_param(req, "allocate", 0, 0) * 1048576)
        if req.algorithm != "RRTConnect":
            raise InvalidRequest(f"unknown algorithm '{req.algorithm}' "
                                 f"(RRTConnect)")
        world = cache.get(req)
        if cache.setup_time is not None:
            # Building the world is not this run's time (tau_t): it is
            # reported on its own, as OMPL's Benchmark keeps its setup.
            t0 += cache.setup_time
            deadline += cache.setup_time
            setup_value = named_value_t()
            setup_value.name = WORLD_SETUP_TIME
            setup_value.value = cache.setup_time
            res.values.append(setup_value)
        if req.num_joints != world.num_joints:
            raise InvalidRequest(f"start has {req.num_joints} joints, the "
                                 f"robot {world.num_joints}")
        space = rrt_connect.Space(world, resolution,
                                  random.Random(req.seed))
        start = list(req.start)
        if not space.free(start):
            raise InvalidRequest("the start state is in collision")
        goals = _goal_configs(world, req, space, deadline)
        t_setup = time.monotonic()
        if not goals:
            res.status = plan_result_t.FAILED
            res.message = "no collision-free goal configuration found"
        else:
            path = rrt_connect.plan(space, start, goals, step, deadline,
                                    limits.stopping)
            t_raw = time.monotonic()
            if path is None:
                res.status = plan_result_t.TIMEOUT
                res.message = "no path within the time limit"
            else:
                res.status = plan_result_t.SOLVED
                res.stages.append(_stage("raw", t_raw - t_setup, path,
                                         world.num_joints))
                short = rrt_connect.shortcut(space, path, 100, deadline,
                                             limits.stopping)
                res.stages.append(_stage("shortcut", time.monotonic() - t_raw,
                                         short, world.num_joints))
        res.time_other = t_setup - t0
        res.values.append(named_value_t())
        res.values[-1].name, res.values[-1].value = "collision checks", space.checks
    except InvalidRequest as e:
        res.status = plan_result_t.INVALID_REQUEST
        res.message = str(e)
    res.time_total = time.monotonic() - t0
    res.num_stages, res.num_values = len(res.stages), len(res.values)
    res.num_progress = 0
    res.message = getattr(res, "message", "") or ""
    return res
