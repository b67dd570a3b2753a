"""drake.py - the peer `drake`: Drake 1.51.1 (pip drake==1.51.1, the
newest wheel for CPython 3.11; 1.58 needs Python 3.12), trajectory
optimisation with its KinematicTrajectoryOptimization (KTO): a B-spline
in joint space, solved by SNOPT (bundled in the wheel), collision
avoidance as Drake's MinimumDistanceLowerBoundConstraint evaluated by its
SceneGraph.

The model, as Drake's users make it: RobotDiagramBuilder(time_step=0),
its Parser's AddModels on the request's URDF (the kit hands it with the
meshes at absolute paths, so no package map is needed), the URDF's root
link welded to the world, the scene's boxes, spheres and cylinders (and
meshes, written as OBJ files) registered on the world body as collision
geometry, then the SRDF's disabled pairs through SceneGraph's collision
filter manager (CollisionFilterDeclaration().ExcludeBetween). Drake
filters parent-child and welded bodies itself. Collision model: SceneGraph
computes signed distances between a link's mesh and an obstacle on the
mesh's convex hull (Drake's Mesh documentation: a general mesh is replaced
by its convex hull for these queries), so it is conservative where a
link is concave (the hand and fingers' gap, link6's shape); obstacles are
exact primitives. Drake has no octree or point cloud geometry: an octree
of the scene comes as its occupied cells, boxes merged as libmpbench
merges them (a cloud's spheres as spheres), at most MAX_CLOUD_SHAPES.

KTO, as Drake's own tutorial uses it: KinematicTrajectoryOptimization(n,
16 control points, order 4), AddDurationCost(1), AddPathLengthCost(1),
AddPositionBounds and AddVelocityBounds from the URDF's limits,
AddDurationConstraint(0.1, 20 s), start and goal as path constraints at
s = 0 and 1 with zero velocity there. Seed: the straight line from start
to goal, solved first without collision constraints; that solution then
seeds a second solve with MinimumDistanceLowerBoundConstraint(plant,
0.02 m, influence 0.01 m more; a bound of 0.9 times the start's or
goal's own clearance in Drake's model where that is less: else the
constraint at s = 0 or 1 cannot hold) at 100 evenly spaced path parameters (25
left collisions between samples in the checks of
shared/reference/trajectory-optimisation-libraries.md). The request's
time limit becomes SNOPT's "Time limit" option (a fifth for the first
solve, 0.9 of what is left for the second); SNOPT counts CPU seconds
there, so a callback at each evaluation also stops it at the wall-clock
deadline and the last iterate is returned (status TIMEOUT). When the
first solution already keeps the distance at every sample, the
constraints are inactive at it and it is returned without the second
solve (which would only confirm it). Status: result.is_success() of the
last solve (SOLVED), else FAILED (TIMEOUT when SNOPT says its time limit
ended it); the spline is returned either way, for mpbench to verify.

KTO+RRT (hybrid): a bidirectional RRT (RRT-Connect, written here: pydrake
has none) on Drake's own SceneGraphCollisionChecker (edges checked every
0.05 rad, the checker's own edge step) finds a path (stage "raw"), and
KTO, its control points seeded by that path resampled to 16 points along
its length, optimises it with the collision constraints from the start
(stage "optimized").

Parameters (strings, as every planner's): control_points (16),
samples (100), margin (0.02 m), the values above.

Deviations from a user's use: the stage is the spline sampled uniformly
in time, so densely that consecutive samples are at most 0.01 rad apart
in the largest joint (what mpbench verifies, with straight lines between
samples, is then what the spline does to within a few micrometres); each
sample carries the spline's time (a time-parameterised trajectory). The
second solve is not retried from other seeds, as a user might.
"""
import math
import os
import re
import time

import numpy as np
from mpb import plan_result_t

from . import peer

NUM_CONTROL_POINTS = 16
SPLINE_ORDER = 4
NUM_SAMPLES = 100          # path parameters with the distance constraint
MARGIN_M = 0.02            # the distance constraint's lower bound
INFLUENCE_M = 0.01         # its influence distance, past the bound
DURATION_S = (0.1, 20.0)   # the spline's duration bounds
MAX_STEP_RAD = 0.01        # largest joint change between stage samples
RRT_STEP_RAD = 0.2         # the RRT's extension step
ROUNDING_RAD = 1e-9        # past a limit by rounding (see _sample)
SNOPT_LIMIT_SHARE = 0.9    # of the time left, SNOPT's own limit
# The most shapes an octree's cells (a cloud's spheres) may give drake:
# SceneGraphCollisionChecker's setup grows with the square of the world's
# geometries (1000 boxes: 1.9 s and 0.5 GB; 2500: 19 s and 2.4 GB; a
# sensed MotionBenchMaker scene's 5871: 160 s and 12 GB).
MAX_CLOUD_SHAPES = 1000

SNOPT_TIME_LIMIT_INFO = 74  # SNOPT: "time limit reached"


def _root_link(urdf):
    links = re.findall(r'<link\s[^>]*name="([^"]+)"', urdf)
    children = set(re.findall(r'<child\s[^>]*link="([^"]+)"', urdf))
    roots = [ln for ln in links if ln not in children]
    if len(roots) != 1:
        raise peer.InvalidRequest(f"robot: {len(roots)} root links in the "
                                  f"URDF (drake wants one to weld)")
    return roots[0]


class Adapter:
    NAME = "drake"
    DESCRIPTION = ("Drake 1.51.1: KinematicTrajectoryOptimization (B-spline, "
                   "SNOPT) with minimum-distance constraints on SceneGraph "
                   "(convex hulls of meshes), from a straight seed or an RRT.")
    ALGORITHMS = ["KTO", "KTO+RRT"]
    APPROACH = {"KTO": "optimisation", "KTO+RRT": "hybrid"}
    GOAL_REGIONS = False     # KTO takes one goal configuration
    PARAMS = {"control_points": f"an integer >= {SPLINE_ORDER} (the "
                                f"B-spline's, default {NUM_CONTROL_POINTS})",
              "samples": f"an integer >= 2 (path parameters with the "
                         f"distance constraint, default {NUM_SAMPLES})",
              "margin": f"a number (the distance bound in m, default "
                        f"{MARGIN_M})"}

    def build(self, problem, world):
        cloud_shapes = sum(1 for s in problem.shapes if s.cloud is not None)
        if cloud_shapes > MAX_CLOUD_SHAPES:
            raise peer.InvalidRequest(
                f"drake: the scene's octrees and point clouds are "
                f"{cloud_shapes} boxes and spheres, more than the "
                f"{MAX_CLOUD_SHAPES} this peer gives drake (its collision "
                f"checker's setup grows with their square)")
        from pydrake.geometry import (Box, CollisionFilterDeclaration,
                                      Cylinder, GeometrySet, Mesh, Sphere)
        from pydrake.math import RigidTransform
        from pydrake.common.eigen_geometry import Quaternion
        from pydrake.multibody.plant import CoulombFriction
        from pydrake.planning import (RobotDiagramBuilder,
                                      SceneGraphCollisionChecker)

        builder = RobotDiagramBuilder(time_step=0.0)
        plant = builder.plant()
        try:
            instances = builder.parser().AddModels(file_name=problem.urdf_path)
            root = _root_link(problem.urdf)
            plant.WeldFrames(plant.world_frame(), plant.GetFrameByName(root))
        except peer.InvalidRequest:
            raise
        except Exception as e:
            raise peer.InvalidRequest(f"drake refuses the robot: "
                                      f"{str(e).splitlines()[0]}") from None
        friction = CoulombFriction(0.9, 0.5)
        for k, s in enumerate(problem.shapes):
            x, y, z, w = s.quat
            pose = RigidTransform(Quaternion(w, x, y, z), np.array(s.position))
            if s.kind == "box":
                shape = Box(*s.dims)
            elif s.kind == "sphere":
                shape = Sphere(s.dims[0])
            elif s.kind == "cylinder":
                shape = Cylinder(s.dims[0], s.dims[1])
            else:
                path = os.path.join(os.path.dirname(problem.urdf_path),
                                    f"scene{k}.obj")
                peer.write_obj(path, s)
                shape = Mesh(path)
            plant.RegisterCollisionGeometry(plant.world_body(), pose, shape,
                                            f"scene{k}", friction)
        diagram = builder.Build()
        # The SRDF's disabled pairs, in SceneGraph's own filter.
        sg = diagram.scene_graph()
        filters = sg.collision_filter_manager()
        for a, b in peer.acm_pairs(problem.srdf):
            if not (plant.HasBodyNamed(a) and plant.HasBodyNamed(b)):
                continue
            ga = plant.GetCollisionGeometriesForBody(plant.GetBodyByName(a))
            gb = plant.GetCollisionGeometriesForBody(plant.GetBodyByName(b))
            if ga and gb:
                filters.Apply(CollisionFilterDeclaration().ExcludeBetween(
                    GeometrySet(ga), GeometrySet(gb)))
        n = plant.num_positions()
        index = []
        for j in problem.joints:
            if not plant.HasJointNamed(j):
                raise peer.InvalidRequest(f"joint '{j}' is not a joint of "
                                          f"drake's model of the robot")
            joint = plant.GetJointByName(j)
            if joint.num_positions() != 1:
                raise peer.InvalidRequest(f"joint '{j}': drake gives it "
                                          f"{joint.num_positions()} positions")
            index.append(joint.position_start())
        nominal = np.zeros(n)
        for jn, v in problem.held.items():
            if plant.HasJointNamed(jn):
                joint = plant.GetJointByName(jn)
                if joint.num_positions() == 1:
                    nominal[joint.position_start()] = v
        # Drake's checker (for the RRT) takes the diagram over; the KTO
        # constraints use a context of the same diagram.
        checker = SceneGraphCollisionChecker(
            model=diagram, robot_model_instances=list(instances),
            edge_step_size=0.05, implicit_context_parallelism=False)
        diagram = checker.model()
        plant = checker.plant()
        context = diagram.CreateDefaultContext()
        plant_context = plant.GetMyMutableContextFromRoot(context)
        return {"plant": plant, "diagram": diagram, "context": context,
                "plant_context": plant_context, "checker": checker,
                "index": index, "nominal": nominal,
                "lower": plant.GetPositionLowerLimits(),
                "upper": plant.GetPositionUpperLimits(),
                "vlower": plant.GetVelocityLowerLimits(),
                "vupper": plant.GetVelocityUpperLimits()}

    # ---- helpers -------------------------------------------------------

    @staticmethod
    def _full(model, q):
        x = model["nominal"].copy()
        x[model["index"]] = q
        return x

    @staticmethod
    def _sample(traj, index, lower, upper):
        """The spline sampled uniformly in time, consecutive samples at
        most MAX_STEP_RAD apart in the largest joint: (path, times).
        A sample past a joint limit by rounding alone (the spline lies
        in its control points' hull, and they in the limits: 5e-16 rad
        was seen) is put on the limit."""
        t0, t1 = traj.start_time(), traj.end_time()
        m = 101
        while True:
            ts = np.linspace(t0, t1, m)
            qs = np.array([traj.value(t)[:, 0] for t in ts])[:, index]
            step = float(np.max(np.abs(np.diff(qs, axis=0))))
            if step <= MAX_STEP_RAD or m >= 64001:
                break
            m = int(math.ceil((m - 1) * step / MAX_STEP_RAD * 1.1)) + 1
        lo, hi = lower[index], upper[index]
        qs = np.where((qs < lo) & (qs > lo - ROUNDING_RAD), lo, qs)
        qs = np.where((qs > hi) & (qs < hi + ROUNDING_RAD), hi, qs)
        return qs.tolist(), (ts - t0).tolist()

    def _rrt(self, model, a, b, deadline, rng):
        """RRT-Connect on Drake's checker: a list of full configurations,
        or None by the deadline."""
        checker = model["checker"]
        lo, hi = model["lower"].copy(), model["upper"].copy()
        idx = model["index"]
        lo = np.where(np.isfinite(lo), lo, -math.pi)
        hi = np.where(np.isfinite(hi), hi, math.pi)
        trees = [([a], [-1]), ([b], [-1])]

        def nearest(tree, q):
            d = np.max(np.abs(np.array(tree[0])[:, idx] - q[idx]), axis=1)
            return int(np.argmin(d))

        def extend(tree, q):
            """Steps towards q: index of the last node added, reached?"""
            i = nearest(tree, q)
            while True:
                near = tree[0][i]
                d = q - near
                dist = np.max(np.abs(d[idx]))
                new = q if dist <= RRT_STEP_RAD else near + d * (RRT_STEP_RAD / dist)
                if not checker.CheckEdgeCollisionFree(near, new):
                    return i, False
                tree[0].append(new)
                tree[1].append(i)
                i = len(tree[0]) - 1
                if dist <= RRT_STEP_RAD:
                    return i, True

        def branch(tree, i):
            out = []
            while i >= 0:
                out.append(tree[0][i])
                i = tree[1][i]
            return out

        while time.monotonic() < deadline:
            q = model["nominal"].copy()
            q[idx] = rng.uniform(lo[idx], hi[idx])
            if not checker.CheckConfigCollisionFree(q):
                continue
            i, _ = extend(trees[0], q)
            # Connect the other tree to the node just added.
            j, reached = extend(trees[1], trees[0][0][i])
            if reached:
                p0, p1 = branch(trees[0], i), branch(trees[1], j)
                path = p0[::-1] + p1[1:]
                if trees[0][0][0] is not a:
                    path = path[::-1]
                return path
            trees.reverse()
        return None

    def _params(self, params):
        """control_points, samples, margin from the request, or the
        defaults."""
        out = []
        for key, kind, default, least in (
                ("control_points", int, NUM_CONTROL_POINTS, SPLINE_ORDER),
                ("samples", int, NUM_SAMPLES, 2),
                ("margin", float, MARGIN_M, -math.inf)):
            text = params.get(key)
            try:
                v = default if text is None else kind(text)
            except ValueError:
                v = None
            if v is None or not v >= least or (kind is float and
                                                not math.isfinite(v)):
                raise peer.InvalidRequest(
                    f"parameter '{key}': '{text}' is not {self.PARAMS[key]}")
            out.append(v)
        return out

    def _seed(self, path, index, ncp):
        """A path's points resampled to the control points' count, evenly
        along its length (largest joint change)."""
        pts = np.array(path)
        seg = np.max(np.abs(np.diff(pts[:, index], axis=0)), axis=1)
        s = np.concatenate([[0.0], np.cumsum(seg)])
        s = s / s[-1] if s[-1] > 0 else np.linspace(0, 1, len(pts))
        u = np.linspace(0, 1, ncp)
        return np.array([[np.interp(v, s, pts[:, k]) for v in u]
                         for k in range(pts.shape[1])])

    # ---- the run -------------------------------------------------------

    def plan(self, model, algorithm, start, goals, time_limit, seed, params):
        from pydrake.math import BsplineBasis, KnotVectorType
        from pydrake.multibody.inverse_kinematics import \
            MinimumDistanceLowerBoundConstraint
        from pydrake.planning import KinematicTrajectoryOptimization
        from pydrake.solvers import SnoptSolver, SolverOptions
        from pydrake.trajectories import BsplineTrajectory

        ncp, samples, margin = self._params(params)
        t_start = time.monotonic()
        deadline = t_start + time_limit
        plant, idx = model["plant"], model["index"]
        n = plant.num_positions()
        q0, qf = self._full(model, start), self._full(model, goals[0])
        stages = []
        snopt = SnoptSolver()

        vmax = np.minimum(np.abs(model["vlower"]), np.abs(model["vupper"]))
        vmax = np.where(vmax > 0, vmax, 1.0)
        duration = max(float(np.max(np.abs(qf - q0) / vmax)) * 1.5, 0.5)

        seed_path = None
        if algorithm == "KTO+RRT":
            rng = np.random.default_rng(seed & 0xFFFFFFFF)
            budget = t_start + 0.5 * time_limit
            raw = self._rrt(model, q0, qf, budget, rng)
            t_raw = time.monotonic() - t_start
            if raw is None:
                return [], plan_result_t.TIMEOUT, \
                    "RRT-Connect on Drake's checker: no path", []
            stages.append(("raw", t_raw, [list(map(float, q[idx]))
                                          for q in raw]))
            seed_path = raw

        t_opt = time.monotonic()
        trajopt = KinematicTrajectoryOptimization(
            n, ncp, SPLINE_ORDER, duration)
        prog = trajopt.get_mutable_prog()
        trajopt.AddDurationCost(1.0)
        trajopt.AddPathLengthCost(1.0)
        trajopt.AddPositionBounds(model["lower"], model["upper"])
        trajopt.AddVelocityBounds(model["vlower"], model["vupper"])
        trajopt.AddDurationConstraint(*DURATION_S)
        trajopt.AddPathPositionConstraint(q0, q0, 0)
        trajopt.AddPathPositionConstraint(qf, qf, 1)
        zero = np.zeros(n)
        trajopt.AddPathVelocityConstraint(zero, zero, 0)
        trajopt.AddPathVelocityConstraint(zero, zero, 1)
        basis = BsplineBasis(SPLINE_ORDER, ncp,
                             KnotVectorType.kClampedUniform, 0.0, duration)
        if seed_path is None:
            cps = np.linspace(q0, qf, ncp).T
        else:
            cps = self._seed(seed_path, list(range(n)), ncp)
        trajopt.SetInitialGuess(BsplineTrajectory(
            basis, [cps[:, [k]] for k in range(ncp)]))
        # SNOPT's "Time limit" counts CPU seconds; on a loaded machine the
        # wall clock runs ahead, so a callback at every evaluation stops
        # SNOPT at the wall-clock deadline too (Drake catches the
        # exception, stops SNOPT and raises it again), keeping the last
        # iterate it evaluated.
        last = {"x": None}

        class _Deadline(Exception):
            pass

        def watch(x):
            last["x"] = np.array(x)
            if time.monotonic() > stop_at[0]:
                raise _Deadline()

        stop_at = [deadline]
        prog.AddVisualizationCallback(watch, prog.decision_variables())
        cp_index = prog.FindDecisionVariableIndices(
            list(trajopt.control_points().flatten()))
        knots = np.array(trajopt.basis().knots())

        def from_x(x):
            # SNOPT hands user code its nonlinear variables only: the
            # duration (in linear terms alone) is not among them, so it
            # is the least that keeps the velocity bounds.
            cp = np.asarray(x)[cp_index].reshape(n, ncp)
            cps = [cp[:, [k]] for k in range(ncp)]
            unit = BsplineTrajectory(BsplineBasis(SPLINE_ORDER, list(knots)),
                                     cps)
            d = np.abs(np.hstack(unit.MakeDerivative().control_points()))
            t = max(float(np.max(d / vmax[:, None])), DURATION_S[0])
            return BsplineTrajectory(
                BsplineBasis(SPLINE_ORDER, list(knots * t)), cps)

        def solve(seconds):
            """SNOPT for at most seconds (CPU by its limit, wall by the
            callback): (trajectory, result or None when stopped)."""
            stop_at[0] = min(time.monotonic() + seconds, deadline)
            o = SolverOptions()
            o.SetOption(snopt.solver_id(), "Time limit", max(seconds, 0.01))
            try:
                result = snopt.Solve(prog, None, o)
            except RuntimeError as e:
                if "_Deadline" not in str(e) or last["x"] is None:
                    raise
                return from_x(last["x"]), None
            return trajopt.ReconstructTrajectory(result), result

        infos = []
        stopped = False
        if seed_path is None:
            # The straight line first, without collision constraints.
            traj, result = solve(0.2 * (deadline - time.monotonic()))
            infos.append(result.get_solver_details().info if result
                         else "stopped")
            stopped = result is None
            trajopt.SetInitialGuess(traj)
        # The bound no tighter than the start's and goal's own clearance
        # in Drake's model (MotionBenchMaker's goals come 9-22 mm from an
        # object): at or above it, the constraints at s = 0 or 1 can
        # never hold and SNOPT can only report infeasible.
        ends = [model["checker"].CalcRobotClearance(q, margin + INFLUENCE_M)
                for q in (q0, qf)]
        clear = min([float(np.min(c.distances())) for c in ends
                     if len(c.distances())] + [margin / 0.9])
        bound = min(margin, 0.9 * clear) if clear > 0 else 1.1 * clear - 1e-4
        dist = MinimumDistanceLowerBoundConstraint(
            plant, bound, model["plant_context"], None, INFLUENCE_M)
        params_s = np.linspace(0.0, 1.0, samples)
        # The collision-free optimum already keeps the distance at every
        # sample: it is the optimum with the constraints too (they are
        # inactive there), and the second solve would only confirm it.
        inactive = (seed_path is None and not stopped and
                    result.is_success() and all(
                        dist.CheckSatisfied(traj.value(
                            traj.start_time() + v * (traj.end_time() -
                                                     traj.start_time()))[:, 0])
                        for v in params_s))
        if not stopped and not inactive:
            for v in params_s:
                trajopt.AddPathPositionConstraint(dist, v)
            traj, result = solve(SNOPT_LIMIT_SHARE *
                                 (deadline - time.monotonic()))
            infos.append(result.get_solver_details().info if result
                         else "stopped")
        path, times = self._sample(traj, idx, model["lower"], model["upper"])
        t_opt = time.monotonic() - t_opt
        stages.append(("optimized" if seed_path is not None else "raw",
                       t_opt, path, times))
        values = [("duration", traj.end_time() - traj.start_time()),
                  ("distance_bound", bound), ("solves", len(infos))]
        solves = ", ".join(map(str, infos))
        if result is None:
            return stages, plan_result_t.TIMEOUT, (
                f"SNOPT stopped at the time limit (solves: {solves}); "
                f"the last iterate returned"), values
        info = result.get_solver_details().info
        values.append(("snopt_info", info))
        if result.is_success():
            return stages, plan_result_t.SOLVED, "", values
        status = (plan_result_t.TIMEOUT if info == SNOPT_TIME_LIMIT_INFO
                  else plan_result_t.FAILED)
        return stages, status, (f"SNOPT info {info} (solves: {solves}): "
                                f"not a solution by Drake's word"), values


if __name__ == "__main__":
    peer.main(Adapter())
