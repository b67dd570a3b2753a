"""roboplan.py - the peer `roboplan`: roboplan 0.7.0 (pip
roboplan==0.7.0): an RRT on Pinocchio's model of the robot, collision
checking by Coal (FCL's successor) on the URDF's own collision meshes and
the scene's boxes, cylinders, spheres and meshes added to its Scene.

As a user: loadUrdfSceneDescription(urdf), Scene(name, description),
Scene.importSrdf(srdf) (its groups and disabled pairs), the scene's shapes
with add*Geometry on the "universe" frame (their pairs among themselves
allowed with setCollisions: roboplan checks them too), a group of the request's
joints (Scene.addGroup), then roboplan.rrt.RRT with its own RRTOptions
defaults but group_name, max_planning_time (its time limit) and, for the
algorithm RRTConnect, rrt_connect=True. Its PathShortcutter, with its
default options, gives the stage "shortcut" after "raw".

An octree or point cloud of the scene: roboplan's OcTree (Coal's
octree of an OctoMap tree, Scene.addOcTreeGeometry at the cloud's pose)
from the cells in Coal's toBoxes() format: an octree's leaf cells at its
resolution, so the same cells; a cloud of spheres as cells of their
diameter.
"""
import os
import time

import numpy as np
from mpb import plan_result_t
from roboplan import core, rrt

from . import peer

GROUP = "mpb_group"
OCCUPIED = 0.97      # a cell's occupancy: OctoMap's clamping maximum
THRESHOLD = 0.5      # OctoMap's default occupancy threshold


class Adapter:
    NAME = "roboplan"
    DESCRIPTION = ("roboplan 0.7.0: RRT (and its rrt_connect option) on "
                   "Pinocchio, Coal collision checking, PathShortcutter.")
    ALGORITHMS = ["RRT", "RRTConnect"]
    APPROACH = {a: "sampling" for a in ALGORITHMS}
    GOAL_REGIONS = False     # RRT.plan takes one goal configuration
    CLOUDS = "points"        # octrees and point clouds: its own form

    def build(self, problem, world):
        try:
            desc = core.loadUrdfSceneDescription(problem.urdf_path)
            scene = core.Scene("mpb", desc)
            if problem.srdf:
                scene.importSrdf(problem.srdf)
            # Adjacent links may touch, in mpbench's matrix as in MoveIt's.
            scene.allowAdjacentLinkCollisions()
            scene.addGroup(GROUP, problem.joints)
        except Exception as e:
            raise peer.InvalidRequest(f"roboplan refuses the robot: {e}") \
                from None
        color = np.array([0.5, 0.5, 0.5, 1.0])
        objs = []
        for k, s in enumerate(problem.shapes):
            if s.cloud is not None:
                continue            # below, as roboplan's OcTree
            tform = np.asfortranarray(np.array(s.matrix(), dtype=float))
            name = f"scene{k}"
            objs.append(name)
            if s.kind == "box":
                scene.addBoxGeometry(name, "universe", core.Box(*s.dims),
                                     tform, color)
            elif s.kind == "sphere":
                scene.addSphereGeometry(name, "universe",
                                        core.Sphere(s.dims[0]), tform, color)
            elif s.kind == "cylinder":
                scene.addCylinderGeometry(name, "universe",
                                          core.Cylinder(*s.dims), tform, color)
            else:
                path = os.path.join(os.path.dirname(problem.urdf_path),
                                    f"{name}.obj")
                peer.write_obj(path, s)
                scene.addMeshGeometry(name, "universe", core.Mesh(path),
                                      tform, color)
        # An octree or point cloud: roboplan's OcTree (Coal's, on an
        # OctoMap tree) from its cells as Coal's toBoxes() gives them
        # (x, y, z, size, occupancy, threshold): each leaf cell's centre,
        # in the cloud's frame at its resolution, the same cells; a
        # cloud's spheres at their diameter.
        for c in problem.clouds:
            name = f"cloud_{c.id}"
            boxes = [np.array([x, y, z, c.cell, OCCUPIED, THRESHOLD])
                     for x, y, z in c.points()]
            tform = np.asfortranarray(np.array(c.matrix(), dtype=float))
            scene.addOcTreeGeometry(name, "universe",
                                    core.OcTree(boxes, c.cell), tform, color)
            objs.append(name)
        # roboplan checks scene objects against each other too; the
        # problems' objects touch (a shelf's boards): a user allows those
        # pairs, as MoveIt never checks the world against itself.
        pairs = [(a, b) for i, a in enumerate(objs) for b in objs[i + 1:]]
        if pairs:
            scene.setCollisions(pairs, False)
        names = list(scene.getJointNames())
        return {"scene": scene, "names": names, "held": problem.held,
                "joints": problem.joints}

    def plan(self, model, algorithm, start, goals, time_limit, seed, params):
        scene = model["scene"]
        full = np.array([model["held"].get(n, 0.0) for n in model["names"]],
                        dtype=float)
        idx = [model["names"].index(j) for j in model["joints"]]
        full[idx] = start
        # Pinocchio holds a continuous joint as (cos, sin): roboplan's
        # own expand/collapse converts, as its users do.
        expand = lambda q: core.expandContinuousJointPositions(  # noqa: E731
            scene, GROUP, np.array(q, dtype=float))
        collapse = lambda q: core.collapseContinuousJointPositions(  # noqa: E731
            scene, GROUP, np.array(q, dtype=float))
        if len(full) == len(idx):
            scene.setJointPositions(expand(full))
        else:
            scene.setJointPositions(full)
        scene.setRngSeed(seed & 0x7FFFFFFF)
        opts = rrt.RRTOptions()
        opts.group_name = GROUP
        opts.max_planning_time = 0.9 * time_limit
        opts.rrt_connect = algorithm == "RRTConnect"
        planner = rrt.RRT(scene, opts)
        planner.setRngSeed(seed & 0x7FFFFFFF)
        joints = model["joints"]
        a = core.JointConfiguration(joints, expand(start))
        b = core.JointConfiguration(joints, expand(goals[0]))
        t0 = time.monotonic()
        try:
            path = planner.plan(a, b)
        except Exception as e:
            return [], plan_result_t.FAILED, f"roboplan: {e}", []
        t_raw = time.monotonic() - t0
        if path is None or len(path.positions) == 0:
            return [], plan_result_t.TIMEOUT, "roboplan: no path", []
        raw = [list(map(float, collapse(q))) for q in path.positions]
        stages = [("raw", t_raw, raw)]
        sopts = core.PathShortcuttingOptions()
        sopts.group_name = GROUP
        sopts.seed = seed & 0x7FFFFFFF
        t1 = time.monotonic()
        short = core.PathShortcutter(scene, sopts).shortcut(path)
        stages.append(("shortcut", time.monotonic() - t1,
                       [list(map(float, collapse(q))) for q in short.positions]))
        return stages, plan_result_t.SOLVED, "", []


if __name__ == "__main__":
    peer.main(Adapter())
