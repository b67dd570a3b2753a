"""world.py - libmpbench's world model from Python, through ctypes.

The Python planner checks collisions and samples goal regions with the same
C code the daemon verifies with (libmpbench/include/mpbench/world.h and
robot.h), so a path it accepts is judged by the same geometry. The library
is found as libmpbench.py says (MPB_LIBMPBENCH, or the loader's path).
"""
from __future__ import annotations

import ctypes
from ctypes import (POINTER, Structure, byref, c_char_p, c_double, c_int,
                    c_size_t, c_uint64, c_void_p)
from typing import List, Optional, Sequence, Tuple

from .libmpbench import declare, library, path


class WorldError(Exception):
    """A robot or scene the library refused; the message names where."""


try:
    library()
except OSError as e:
    raise WorldError(f"cannot load libmpbench ({path()}): {e}") from e
_doubles = POINTER(c_double)


class _GoalRegion(Structure):
    """robot.h's mpb_goal_region."""
    _fields_ = [("link", c_int), ("offset", c_double * 3),
                ("center", c_double * 3), ("half_extents", c_double * 3),
                ("ref_rpy", c_double * 3), ("rpy_tolerance", c_double * 3)]


_world_open = declare("mpb_world_open_group", c_int, c_char_p, c_char_p,
                      c_char_p, c_char_p, POINTER(c_char_p), c_int,
                      POINTER(c_void_p), c_char_p, c_size_t)
_world_close = declare("mpb_world_close", None, c_void_p)
_num_joints = declare("mpb_world_num_joints", c_int, c_void_p)
_limits = declare("mpb_world_joint_limits", None, c_void_p, c_int, _doubles,
                  _doubles)
_continuous = declare("mpb_world_joint_is_continuous", c_int, c_void_p, c_int)
_in_collision = declare("mpb_world_in_collision", c_int, c_void_p, _doubles)
_robot_load = declare("mpb_robot_open_urdf_joints", c_int, c_char_p,
                      POINTER(c_char_p), c_int, POINTER(c_void_p), c_char_p,
                      c_size_t)
_robot_free = declare("mpb_robot_close", None, c_void_p)
_world_hold = declare("mpb_world_hold", c_int, c_void_p, POINTER(c_char_p),
                      _doubles, c_int, c_char_p, c_size_t)
_robot_set_passive = declare("mpb_robot_set_passive", c_int, c_void_p,
                             c_char_p, c_double)
_link_index = declare("mpb_robot_link_index", c_int, c_void_p, c_char_p)
_region_sample = declare("mpb_goal_region_sample", c_int, c_void_p,
                         POINTER(_GoalRegion), _doubles, c_void_p, c_int,
                         POINTER(c_uint64), _doubles)
_region_contains = declare("mpb_goal_region_contains", c_int, c_void_p,
                           POINTER(_GoalRegion), _doubles)


_text_split = declare("mpb_robot_text_split", c_int, c_char_p,
                      POINTER(c_size_t), POINTER(c_size_t))


def split_robot_text(text: str) -> Tuple[str, Optional[str]]:
    """A "urdf" robot text as (URDF, SRDF or None), split where libmpbench
    splits it (mpb_robot_text_split(), world.h)."""
    raw = text.encode()
    urdf_len, srdf_at = c_size_t(), c_size_t()
    if _text_split(raw, byref(urdf_len), byref(srdf_at)) != 0:
        raise WorldError("robot text: cannot split")
    srdf = raw[srdf_at.value:].decode() if srdf_at.value < len(raw) else None
    return raw[:urdf_len.value].decode(), srdf


def _names(names: Sequence[str]) -> ctypes.Array:
    return (c_char_p * len(names))(*[n.encode() for n in names])


class World:
    """A robot in a scene, its planning group given by joint names."""

    def __init__(self, robot_format: str, robot: str, scene_format: str,
                 scene: str, joints: Sequence[str]) -> None:
        err = ctypes.create_string_buffer(512)
        handle = c_void_p()
        rc = _world_open(robot_format.encode(), robot.encode(),
                         scene_format.encode(), scene.encode(), _names(joints),
                         len(joints), byref(handle), err, len(err))
        if rc != 0:
            raise WorldError(err.value.decode(errors="replace"))
        self._w = handle
        self._robot = None
        self._held = ([], [])
        self._format, self._urdf, self._joints = robot_format, robot, joints
        n = _num_joints(handle)
        self.num_joints = n
        self.lower, self.upper, self.wraps = [], [], []
        lo, hi = c_double(), c_double()
        for j in range(n):
            _limits(handle, j, byref(lo), byref(hi))
            self.lower.append(lo.value)
            self.upper.append(hi.value)
            self.wraps.append(bool(_continuous(handle, j)))
        self._q = (c_double * n)()

    def close(self) -> None:
        """Free the world and its robot; safe to call twice."""
        if self._robot:
            _robot_free(self._robot)
            self._robot = None
        if self._w:
            _world_close(self._w)
            self._w = None

    def hold(self, names: Sequence[str], values: Sequence[float]) -> None:
        """Hold the joints outside the group at these values (world.h:
        mpb_world_hold()), in the world and in the robot for IK, as the
        daemon's verifier holds them for the run."""
        self._held = (list(names), list(values))
        if not names:
            return
        err = ctypes.create_string_buffer(512)
        if _world_hold(self._w, _names(names), (c_double * len(values))(*values),
                       len(names), err, len(err)) != 0:
            raise WorldError(err.value.decode(errors="replace"))
        if self._robot:
            self._hold_robot()

    def _hold_robot(self) -> None:
        for name, value in zip(*self._held):
            if _robot_set_passive(self._robot, name.encode(), value) != 0:
                raise WorldError(f"joint '{name}' cannot be held at {value}")

    def free(self, q: Sequence[float]) -> bool:
        """True when the robot at q touches nothing."""
        self._q[:] = q
        return _in_collision(self._w, self._q) == 0

    def _robot_handle(self) -> c_void_p:
        """The kinematic model for goal regions (URDF robots only)."""
        if self._robot is None:
            if self._format != "urdf":
                raise WorldError(f"pose-region goals need a urdf robot, not "
                                 f"'{self._format}'")
            err = ctypes.create_string_buffer(512)
            handle = c_void_p()
            if _robot_load(self._urdf.encode(), _names(self._joints),
                           len(self._joints), byref(handle), err,
                           len(err)) != 0:
                raise WorldError(err.value.decode(errors="replace"))
            self._robot = handle
            self._hold_robot()
        return self._robot

    def goal_region(self, link: str, center: Sequence[float],
                    half_extents: Sequence[float], rpy: Sequence[float],
                    rpy_tolerance: Sequence[float]) -> _GoalRegion:
        """A pose region for `link`, as robot.h describes it."""
        robot = self._robot_handle()
        index = _link_index(robot, link.encode())
        if index < 0:
            raise WorldError(f"goal link '{link}' is not a link of the robot")
        return _GoalRegion(index, (c_double * 3)(0, 0, 0),
                           (c_double * 3)(*center), (c_double * 3)(*half_extents),
                           (c_double * 3)(*rpy), (c_double * 3)(*rpy_tolerance))

    def sample_goal(self, region: _GoalRegion,
                    seed_q: Optional[Sequence[float]],
                    rng_state: List[int]) -> Optional[List[float]]:
        """A configuration inside the region by IK (started from seed_q, or
        from random configurations when it is None), or None. rng_state is
        a one-element list holding the 64-bit generator state; it advances."""
        rng = c_uint64(rng_state[0])
        seed = (c_double * self.num_joints)(*seed_q) if seed_q else None
        out = (c_double * self.num_joints)()
        rc = _region_sample(self._robot_handle(), byref(region), seed, None,
                            0, byref(rng), out)
        rng_state[0] = rng.value
        return list(out) if rc == 0 else None

    def in_region(self, region: _GoalRegion, q: Sequence[float]) -> bool:
        """True when the link is inside the region at q."""
        self._q[:] = q
        return _region_contains(self._robot_handle(), byref(region), self._q) == 1
