"""solve.py - one plan request in, one plan result out.

Everything about a run that is not messaging: reading the request (its
world, start, goal and parameters), planning with RRT-Connect, shortening
the path, and timing each stage as docs/protocol.md describes.
"""
import random
import time

from mpb import named_value_t, plan_result_t

from mpbplanner.request import (WORLD_SETUP_TIME, InvalidRequest,
                                goal_configs, param as _param,
                                stage as _stage)

from . import rrt_connect


def solve(req, cache, limits):
    """Answer one plan_request_t with a plan_result_t (attempt_id and
    planner_id left for the caller), stopping when limits.should_stop()
    (limits.py) says so."""
    t0 = time.monotonic()
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
        world = cache.get(req, limits)
        if cache.setup_time is not None:
            # Building the world is not this run's time (tau_t): it is
            # reported on its own, as OMPL's Benchmark keeps its setup.
            t0 += cache.setup_time
            limits = limits.moved(cache.setup_time)
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
        goals = goal_configs(world, req, space.free, limits.deadline)
        t_setup = time.monotonic()
        if not goals:
            res.status = plan_result_t.FAILED
            res.message = "no collision-free goal configuration found"
        else:
            path = rrt_connect.plan(space, start, goals, step,
                                    limits.should_stop)
            t_raw = time.monotonic()
            if path is None:
                res.status = plan_result_t.TIMEOUT
                res.message = "no path within the time limit"
            else:
                res.status = plan_result_t.SOLVED
                res.stages.append(_stage("raw", t_raw - t_setup, path,
                                         world.num_joints))
                short = rrt_connect.shortcut(space, path, 100,
                                             limits.should_stop)
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
