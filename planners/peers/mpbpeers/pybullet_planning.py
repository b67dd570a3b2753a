"""pybullet_planning.py - the peer `pybullet_planning`: pybullet-planning
0.6.1 (pip pybullet-planning==0.6.1) on pybullet 3.2.7: BiRRT with random
restarts, collision checking by Bullet (closest points at distance 0) on
Bullet's model of the URDF (its collision meshes as convex hulls, as
Bullet loads an OBJ) and of the scene (boxes, cylinders, spheres, OBJ
meshes as bodies).

As a user: connect(use_gui=False), load_pybullet(urdf, fixed_base=True),
the scene's shapes with create_box / create_cylinder / create_sphere /
create_obj and set_pose, the SRDF's disabled pairs as disabled_collisions,
then what plan_joint_motion does, with its get_*_fn defaults (resolution
0.05 rad), birrt with max_time (its time limit) and no smoothing as "raw",
then the library's smooth_path (its default iterations) as "smoothed".

Bullet has no octree: an octree of the scene comes as its occupied cells,
boxes merged as libmpbench merges them, sixteen to a body (a cloud's
spheres alike).
"""
import os
import random
import time

import numpy as np
import pybullet_planning as pp
from mpb import plan_result_t
from pybullet_planning.motion_planners import meta

from . import peer

ARRAY_MAX = 16      # shapes a pybullet shape array keeps


class Adapter:
    NAME = "pybullet_planning"
    DESCRIPTION = ("pybullet-planning 0.6.1: birrt on Bullet collision "
                   "checking, then its smooth_path.")
    ALGORITHMS = ["birrt"]
    APPROACH = {a: "sampling" for a in ALGORITHMS}
    GOAL_REGIONS = False     # birrt takes one goal configuration

    def build(self, problem, world):
        if not pp.is_connected():
            pp.connect(use_gui=False)
        pp.reset_simulation()
        try:
            robot = pp.load_pybullet(problem.urdf_path, fixed_base=True)
        except Exception as e:
            raise peer.InvalidRequest(f"pybullet refuses the robot: {e}") \
                from None
        obstacles = []
        chunks = {}
        for k, s in enumerate(problem.shapes):
            if s.cloud is not None:
                chunks.setdefault(s.cloud, []).append(s)
                continue
            if s.kind == "box":
                body = pp.create_box(*s.dims)
            elif s.kind == "sphere":
                body = pp.create_sphere(s.dims[0])
            elif s.kind == "cylinder":
                body = pp.create_cylinder(s.dims[0], s.dims[1])
            else:
                path = os.path.join(os.path.dirname(problem.urdf_path),
                                    f"scene{k}.obj")
                peer.write_obj(path, s)
                body = pp.create_obj(path)
            pp.set_pose(body, (tuple(s.position), tuple(s.quat)))
            obstacles.append(body)
        # An octree's merged cells (a cloud's spheres): Bullet has no
        # octree; its boxes go into bodies of 16 shapes each, the most a
        # shape array keeps (createCollisionShapeArray drops the rest,
        # silently), where a body a box would cost birrt's collision_fn
        # one call per box and link.
        for shapes in chunks.values():
            for i in range(0, len(shapes), ARRAY_MAX):
                part = shapes[i:i + ARRAY_MAX]
                geoms = [pp.get_box_geometry(*s.dims) if s.kind == "box"
                         else pp.get_sphere_geometry(s.dims[0]) for s in part]
                poses = [(tuple(s.position), tuple(s.quat)) for s in part]
                collision, _ = pp.create_shape_array(geoms, poses)
                obstacles.append(pp.create_body(collision))
        links = {pp.get_link_name(robot, link) for link in pp.get_links(robot)}
        links.add(pp.get_base_name(robot))
        pairs = [(a, b) for a, b in peer.acm_pairs(problem.srdf)
                 if a in links and b in links]
        disabled = pp.get_disabled_collisions(robot, pairs)
        try:
            joints = pp.joints_from_names(robot, problem.joints)
        except Exception as e:
            raise peer.InvalidRequest(f"pybullet's model lacks a joint: {e}") \
                from None
        for name, value in problem.held.items():
            try:
                pp.set_joint_position(robot, pp.joint_from_name(robot, name),
                                      value)
            except Exception:
                pass            # a joint Bullet made fixed holds anyway
        return {"robot": robot, "joints": joints, "obstacles": obstacles,
                "disabled": disabled}

    def plan(self, model, algorithm, start, goals, time_limit, seed, params):
        robot, joints = model["robot"], model["joints"]
        random.seed(seed)
        np.random.seed(seed & 0xFFFFFFFF)
        pp.set_joint_positions(robot, joints, start)
        sample_fn = pp.get_sample_fn(robot, joints)
        distance_fn = pp.get_distance_fn(robot, joints)
        extend_fn = pp.get_extend_fn(robot, joints)
        collision_fn = pp.get_collision_fn(
            robot, joints, obstacles=model["obstacles"], self_collisions=True,
            disabled_collisions=model["disabled"])
        t0 = time.monotonic()
        if collision_fn(list(start)) or collision_fn(list(goals[0])):
            # birrt's own first check (check_direct) says only "no path".
            which = "start" if collision_fn(list(start)) else "goal"
            return [], plan_result_t.FAILED, (
                f"birrt: the {which} is in collision in Bullet's model"), []
        path = pp.birrt(list(start), list(goals[0]), distance_fn, sample_fn,
                        extend_fn, collision_fn, max_time=0.8 * time_limit,
                        smooth=0)
        t_raw = time.monotonic() - t0
        if not path:
            return [], plan_result_t.TIMEOUT, "birrt: no path", []
        raw = [list(map(float, q)) for q in path]
        stages = [("raw", t_raw, raw)]
        t1 = time.monotonic()
        smooth = pp.smooth_path(path, extend_fn, collision_fn,
                                distance_fn=distance_fn,
                                max_smooth_iterations=meta.RRT_SMOOTHING,
                                max_time=max(time_limit - t_raw, 0.0) * 0.8)
        stages.append(("smoothed", time.monotonic() - t1,
                       [list(map(float, q)) for q in smooth]))
        return stages, plan_result_t.SOLVED, "", []


if __name__ == "__main__":
    peer.main(Adapter())
