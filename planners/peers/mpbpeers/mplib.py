"""mplib.py - the peer `mplib`: MPLib 0.2.1 (pip mplib==0.2.1), the motion
planner of ManiSkill and SAPIEN: RRTConnect of OMPL inside, collision
checking with FCL on its own model of the robot (the URDF's collision
meshes, loaded by assimp) and the scene (FCL boxes, cylinders, spheres and
BVH meshes in its PlanningWorld).

As a user: mplib.Planner(urdf, move_group, srdf=...) with the move group
the last joint's child link, the scene's shapes added as FCLObjects, then
what Planner.plan_qpos does, stage by stage: its OMPLPlanner.plan
(RRTConnect, range 0.1, plan_qpos's default) without simplification, as
"raw"; OMPLPlanner.simplify_path, as "simplified"; Planner.TOPP (TOPP-RA
at plan_qpos's time step 0.1 s) sampled positions with the time of each
sample, as "toppra", a timed stage (mpbench measures its duration and
velocities against the URDF's limits). Its time limit: plan(time=...).

An octree or point cloud of the scene: what Planner.update_point_cloud
builds, MPLib's FCL OcTree of the points at a resolution (fcl.OcTree,
in an FCLObject at the cloud's pose): an octree's leaf cells' centres at
its resolution, so the same cells; a cloud of spheres at their diameter
(MPLib's word for the resolution), cubes where the verifier has balls.

mplib refuses the Panda's link6.obj ("face with 2 vertices"): as a user
would, every mesh goes through repair_mesh.py, which loads a copy without
OBJ line elements (.cache/peers/mesh-repair), docs/results-peers.md.
"""
import os
import re
import time

import mplib as _mplib
import numpy as np
from mpb import plan_result_t
from mplib.collision_detection import fcl

from . import peer
from . import repair_mesh

RRT_RANGE = 0.1      # Planner.plan_qpos's default rrt_range
TIME_STEP = 0.1      # Planner.plan_qpos's default time_step (TOPP)


def _repair_dir():
    return os.path.join(os.environ.get("MPB_PEER_CACHE", "/tmp"),
                        "mesh-repair")



class Adapter:
    NAME = "mplib"
    DESCRIPTION = ("MPLib 0.2.1: RRTConnect, FCL on its own robot and "
                   "scene model, simplify_path, TOPP-RA.")
    ALGORITHMS = ["RRTConnect"]
    APPROACH = {a: "sampling" for a in ALGORITHMS}
    GOAL_REGIONS = False     # it takes goal configurations (IK by the kit)
    CLOUDS = "points"        # octrees and point clouds: its own form

    def mesh_map(self, path):
        return repair_mesh.repaired(path, _repair_dir())

    def build(self, problem, world):
        # mplib reads mesh paths relative to the URDF's folder.
        urdf = re.sub(r'(<mesh[^>]*filename=")([^"]+)(")',
                      lambda m: m.group(1) + os.path.relpath(
                          m.group(2), os.path.dirname(problem.urdf_path))
                      + m.group(3), problem.urdf)
        path = problem.urdf_path[:-5] + "-mplib.urdf"
        with open(path, "w") as f:
            f.write(urdf)
        move_group = peer.child_link(problem.urdf, problem.joints[-1])
        try:
            planner = _mplib.Planner(path, move_group,
                                     srdf=problem.srdf_path or None)
        except Exception as e:
            raise peer.InvalidRequest(f"mplib refuses the robot: {e}") from None
        names = list(planner.user_joint_names)
        if names[:len(problem.joints)] != problem.joints and \
                sorted(names) != sorted(problem.joints):
            missing = [j for j in problem.joints if j not in names]
            if missing:
                raise peer.InvalidRequest(f"mplib's move group lacks "
                                          f"{', '.join(missing)}")
        for k, s in enumerate(problem.shapes):
            if s.cloud is not None:
                continue            # below, as MPLib's point cloud
            if s.kind == "box":
                geom = fcl.Box(*s.dims)
            elif s.kind == "sphere":
                geom = fcl.Sphere(s.dims[0])
            elif s.kind == "cylinder":
                geom = fcl.Cylinder(s.dims[0], s.dims[1])
            else:
                geom = fcl.BVHModel()
                geom.begin_model()
                geom.add_sub_model(vertices=np.array(s.vertices, dtype=float),
                                   faces=np.array(s.triangles, dtype=np.int32))
                geom.end_model()
            x, y, z, w = s.quat
            pose = _mplib.Pose(np.array(s.position), np.array([w, x, y, z]))
            obj = fcl.FCLObject(f"scene{k}", pose,
                                [fcl.CollisionObject(geom)], [_mplib.Pose()])
            planner.planning_world.add_object(obj)
        for c in problem.clouds:
            # What Planner.update_point_cloud builds (an FCL OcTree of
            # the points at a resolution), in the cloud's own frame: an
            # octree's leaf cells at its resolution, the same cells;
            # spheres at their diameter.
            tree = fcl.OcTree(vertices=np.array(c.points(), dtype=float),
                              resolution=c.cell)
            x, y, z, w = c.quat
            pose = _mplib.Pose(np.array(c.position, dtype=float),
                               np.array([w, x, y, z]))
            planner.planning_world.add_object(fcl.FCLObject(
                f"cloud_{c.id}", pose, [fcl.CollisionObject(tree)],
                [_mplib.Pose()]))
        return {"planner": planner, "names": names, "joints": problem.joints,
                "held": problem.held}

    def plan(self, model, algorithm, start, goals, time_limit, seed, params):
        planner, names = model["planner"], model["names"]
        _mplib.set_global_seed(seed & 0x7FFFFFFF)
        # The whole robot's configuration: the group's joints from the
        # start, the others held.
        full = np.array([model["held"].get(n, 0.0) for n in names], dtype=float)
        idx = [names.index(j) for j in model["joints"]]
        full[idx] = start
        planner.robot.set_qpos(full, True)
        t0 = time.monotonic()
        status, raw = planner.planner.plan(
            np.array(start, dtype=float),
            [np.array(g, dtype=float) for g in goals],
            time=time_limit * 0.9, range=RRT_RANGE, simplify=False)
        t_raw = time.monotonic() - t0
        if status != "Exact solution":
            return [], plan_result_t.TIMEOUT if "imeout" in status or \
                "No solution" in status else plan_result_t.FAILED, \
                f"mplib: {status}", []
        stages = [("raw", t_raw, raw.tolist())]
        t1 = time.monotonic()
        simple = planner.planner.simplify_path(raw)
        stages.append(("simplified", time.monotonic() - t1, simple.tolist()))
        t2 = time.monotonic()
        try:
            ts, pos, _, _, _ = planner.TOPP(simple, TIME_STEP)
            stages.append(("toppra", time.monotonic() - t2, pos.tolist(),
                           ts.tolist()))
        except Exception as e:      # TOPP-RA's own failures: say so
            return stages, plan_result_t.SOLVED, f"TOPP-RA failed: {e}", []
        return stages, plan_result_t.SOLVED, "", []


if __name__ == "__main__":
    peer.main(Adapter())
