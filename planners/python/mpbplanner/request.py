"""request.py - reading a plan request, as every Python planner does.

What is not a planner's own: the world a request names, built by
libmpbench and kept while the hashes say it is the same (WorldCache);
its numeric parameters (param); the goal as configurations, a joint goal
as it is or IK samples inside a pose region (goal_configs); a stage of
the result from a list of configurations (stage). The example planner
(planners/python/mpbrrt) and the peers (planners/peers/mpbpeers) use
them alike.
"""
from __future__ import annotations

import time
from typing import Callable, List, Optional, Sequence

from mpb import goal_t, plan_request_t, stage_t

from .limits import Limits
from .world import World, WorldError


class InvalidRequest(Exception):
    """A request this planner cannot use; the message says why."""


def param(req: plan_request_t, key: str, default: float,
          lo: float) -> float:
    """The request's parameter key as a number >= lo, or default."""
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

    def __init__(self) -> None:
        self.key, self.world = None, None
        self.setup_time = None  # s the last get() spent building a world

    def get(self, req: plan_request_t, limits: Optional[Limits] = None
            ) -> World:
        """The request's world, built unless the last was the same; with
        limits, a build is told to mpbenchd (Limits.setting_up(), then
        planning()) so that it is not counted in the run's deadline."""
        key = (req.robot_format, req.robot_hash, req.scene_format,
               req.scene_hash, tuple(req.joint_names))
        self.setup_time = None
        if key != self.key:
            if limits is not None:
                limits.setting_up()
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
            if limits is not None:
                limits.planning()
        try:
            self.world.hold(list(req.held_names), list(req.held_values))
        except WorldError as e:
            raise InvalidRequest(f"held joints: {e}") from None
        return self.world


def goal_configs(world: World, req: plan_request_t,
                 free: Callable[[List[float]], bool],
                 deadline: float) -> List[List[float]]:
    """Configurations a planner may end at: the joint goal, or up to five
    IK samples inside the pose region for which free(q) is true, sought
    until deadline (time.monotonic())."""
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
        if q is not None and free(q):
            goals.append(q)
    return goals


def stage(name: str, seconds: float, path: Sequence[Sequence[float]],
          num_joints: int,
          times: Optional[Sequence[float]] = None) -> stage_t:
    """A stage_t named name: path (a list of configurations) taking
    seconds. times, for a time-parameterised trajectory: the time of each
    waypoint (s from its start; the daemon checks there is one per
    waypoint, finite, from 0 or later, non-decreasing); None: untimed."""
    st = stage_t()
    st.name, st.time = name, seconds
    st.num_waypoints, st.num_joints = len(path), num_joints
    st.waypoints = [float(x) for q in path for x in q]
    st.num_values = len(st.waypoints)
    st.times = [] if times is None else [float(t) for t in times]
    st.num_times = len(st.times)
    return st
