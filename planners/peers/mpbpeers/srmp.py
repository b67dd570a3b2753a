"""srmp.py - the peer `srmp`: srmp 0.2.1 (pip srmp==0.2.1), search-based
motion planning: A*, weighted A*, ARA* and multi-heuristic A* over a
joint-space lattice, collision checking by coal on the URDF's own
collision meshes and the scene's boxes, spheres, cylinders and meshes.

Licence: srmp is AGPL-3.0-or-later. mpbench runs it in a process of its
own, through its Python bindings, and never links it.

As a user: PlannerInterface().add_robot(urdf, name, srdf_path=...,
end_effector=...) with the request's URDF and SRDF as they are (its
disabled pairs are srmp's own filter), the scene's shapes added with
add_box / add_sphere / add_cylinder / add_mesh (Pose's quaternion is w,
x, y, z), then make_planner([robot], {planner_id, time_limit,
validity_backend: coal}) with srmp's own defaults for everything else
(heuristic, weight, lattice of 1 degree a joint), and plan(start,
GoalConstraint(JOINTS, [goal])); its heuristic's occupancy grid reaches
1 m below the robot's base instead of stopping at it, which srmp's own
refusal of goals under a table asks for.

Its lattice path ends within srmp's goal tolerance of the goal (about
0.008 rad short), not at it: the exact goal is appended as the last
waypoint of the stage "raw", as a user who needs the goal reached does;
and where it starts from the start snapped onto its lattice (seen on the
PR2's starts, up to 0.0072 rad away), the exact start is put first.
docs/results-approaches.md says so. srmp's own time limit is the
request's less what the kit spent on IK goals.

An octree or point cloud of the scene: srmp's add_point_cloud (an
octree of world-frame points at a resolution): an octree's leaf cells'
centres at its resolution, the same cells while the octree's pose
keeps its grid (a sensed scene's is the identity); a cloud of spheres
as cells of their diameter.
"""
import time

import ims.pyims as _pyims
import numpy as np
from mpb import plan_result_t
from srmp import GoalConstraint, GoalType, GridConfig, PlannerInterface, Pose

from . import peer

ROBOT = "robot"



class Adapter:
    NAME = "srmp"
    DESCRIPTION = ("srmp 0.2.1 (AGPL, a separate process): A*, weighted A*, "
                   "ARA*, MHA* on a joint lattice, coal collision checking, "
                   "the exact goal appended.")
    ALGORITHMS = ["wAstar", "ARAstar", "MHAstar", "Astar"]
    APPROACH = {a: "search" for a in ALGORITHMS}
    GOAL_REGIONS = False     # joint goals; the kit samples IK for regions
    CLOUDS = "points"        # octrees and point clouds: its own form

    def build(self, problem, world):
        if problem.held:
            raise peer.InvalidRequest("srmp: joints held outside the group "
                                      "are not taken by this peer")
        # srmp's default heuristic searches an occupancy grid of x, y in
        # [-1, 1] and z in [0, 2] m and refuses a goal outside it, as the
        # goals below a MotionBenchMaker table are; its message says to
        # give a grid that covers the workspace, as a user then does:
        # 1 m more below the base (its resolution, 2 cm, its own).
        grid = GridConfig()
        grid.origin_z, grid.size_z = -1.0, 3.0
        pi = PlannerInterface(grid)
        try:
            pi.add_robot(problem.urdf_path, name=ROBOT,
                         srdf_path=problem.srdf_path,
                         end_effector=peer.child_link(problem.urdf,
                                                 problem.joints[-1]))
        except peer.InvalidRequest:
            raise
        except Exception as e:
            raise peer.InvalidRequest(f"srmp refuses the robot: {e}") from None
        names = list(pi.get_move_group_joint_names(ROBOT))
        if names != problem.joints:
            raise peer.InvalidRequest(
                f"srmp's move group is {', '.join(names)}, the request's "
                f"joints {', '.join(problem.joints)}")
        for k, s in enumerate(problem.shapes):
            if s.cloud is not None:
                continue            # below, as srmp's point cloud
            x, y, z, w = s.quat
            pose = Pose(np.array(s.position, dtype=float),
                        np.array([w, x, y, z], dtype=float))
            name = f"scene{k}"
            if s.kind == "box":
                pi.add_box(name, np.array(s.dims, dtype=float), pose)
            elif s.kind == "sphere":
                pi.add_sphere(name, float(s.dims[0]), pose)
            elif s.kind == "cylinder":
                pi.add_cylinder(name, float(s.dims[0]), float(s.dims[1]), pose)
            else:
                pi.add_mesh(name, vertices=np.array(s.vertices, dtype=float),
                            triangles=np.array(s.triangles, dtype=np.int32),
                            pose=pose)
        # An octree or point cloud: srmp's add_point_cloud (an octree of
        # the points, world frame, at a resolution): an octree's leaf
        # cells' centres at its resolution, the same cells where the
        # octree's pose is the world's; a cloud's spheres at their
        # diameter. srmp's Python add_point_cloud drops the resolution
        # (its binding's default, 1 cm, always): the binding's own,
        # which takes it, is called.
        for c in problem.clouds:
            _pyims.PlannerInterface.add_point_cloud(
                pi, f"cloud_{c.id}",
                np.array(c.points(world=True), dtype=float), c.cell)
        return {"pi": pi, "planner": None}

    def plan(self, model, algorithm, start, goals, time_limit, seed, params):
        pi = model["pi"]
        # srmp is deterministic: the seed changes nothing.
        pi.make_planner([ROBOT], {"planner_id": algorithm,
                                  "time_limit": repr(float(time_limit)),
                                  "validity_backend": "coal"})
        goal = goals[0]
        t0 = time.monotonic()
        try:
            traj = pi.plan(np.array(start, dtype=float),
                           GoalConstraint(GoalType.JOINTS,
                                          [np.array(goal, dtype=float)]))
            path = [list(map(float, q)) for q in traj.positions]
            error = ""
        except Exception as e:      # its own "no plan found" and the like
            path, error = [], f"srmp: {e}"
        seconds = time.monotonic() - t0
        if not path:
            status = plan_result_t.TIMEOUT if seconds >= 0.95 * time_limit \
                else plan_result_t.FAILED
            return [], status, error or "srmp: no path", []
        # Its lattice path may start from the start snapped onto the
        # lattice (up to half a step, 0.0087 rad, away) and ends within
        # its goal tolerance: the exact ends are added, as a user whose
        # robot stands at the start and must reach the goal does.
        if max(abs(a - b) for a, b in zip(path[0], start)) > 1e-12:
            path.insert(0, [float(v) for v in start])
        if max(abs(a - b) for a, b in zip(path[-1], goal)) > 1e-12:
            path.append([float(v) for v in goal])
        return [("raw", seconds, path)], plan_result_t.SOLVED, "", []


if __name__ == "__main__":
    peer.main(Adapter())
