"""tesseract.py - the peer `tesseract`: Tesseract 0.5.1 (pip
tesseract-robotics==0.5.1, its SWIG bindings; numpy 2.4.6), the ROS-
Industrial motion planning framework: TrajOpt (sequential convex
optimisation of a joint trajectory, trajopt_sco with its own QP solver)
and OMPL inside Tesseract, collision checking by Tesseract's own Bullet
contact managers on the URDF's collision meshes (each mesh as Bullet's
BVH of its triangles; Tesseract's default discrete manager) and the
scene's boxes, spheres, cylinders and meshes as Tesseract geometry.
An octree of the scene is Tesseract's own Octree geometry (sub-shapes
boxes: each occupied leaf cell a box in Bullet's compound), at the
octree's resolution and pose, on a link of its own: its cells written
as an OctoMap .bt file (clouds.py, libmpbench) and read as a Tesseract
user reads one, by Tesseract's URDF parser (tesseract_urdf.
parseURDFString: a collision element <octomap shape_type="box"><octree
filename=.../></octomap>). That is the one way in from Python: 0.5.1's
tesseract_geometry.Octree constructors take an octomap::OcTree, and
its bindings have no way to make one (tesseract_geometry.OcTree has no
constructor; no point cloud constructor is wrapped). Where that fails
(Tesseract refuses the file) the octree comes as its occupied cells,
boxes merged as libmpbench merges them, all on one link, and the run
says so (cloud_shapes in place of cloud_points). A cloud of spheres is
always its spheres on one link: Tesseract's Octree sub-shapes are cells
(boxes, or spheres inside or around them), not a sphere of the cloud's
radius about each point.

Algorithms:

- `TrajOpt` (optimisation): the program a Tesseract user writes for a
  free-space joint move (a CompositeInstruction of two FREESPACE
  MoveInstructions holding JointWaypoints, start and goal, profile
  "DEFAULT"), seeded by Tesseract's own straight line in joint space
  (generateInterpolatedProgram with SEED_STEPS steps: SEED_STEPS + 1
  states), then TrajOptMotionPlanner with TrajOptDefaultPlanProfile and
  TrajOptDefaultCompositeProfile as they come: a collision constraint
  (margin 0.01 m, coefficient 20) and a cost (margin 0.025 m), both
  evaluated DISCRETE_CONTINUOUS (the swept segment between states, by
  Bullet's cast manager) with longest_valid_segment_length 0.1; smooth
  joint velocities as the cost. Its output, the optimised states, is the
  stage "optimized".
- `OMPL+TrajOpt` (hybrid): what Tesseract's own free-space pipeline
  does: OMPLMotionPlanner with OMPLRealVectorPlanProfile's defaults
  (RRTConnect, run in parallel instances as the profile sets, planning
  time at most the profile's 5 s: "Exceeded allowed time" is answered
  TIMEOUT; states checked by Tesseract's discrete manager at its longest
  valid segment) on the straight-seeded program, its path as Tesseract
  returns it (OMPL's path interpolated to the program's 21 states) as the
  stage "raw"; then TrajOpt as above seeded with that path, the stage
  "optimized". Tesseract hands OMPL's states back as StateWaypoints,
  which TrajOpt would hold fixed (it fails at once then): the seed
  program is made of them as generateInterpolatedProgram makes a seed,
  start and goal constrained JointWaypoints, the states between
  unconstrained ones (what Tesseract's own OMPL-then-TrajOpt pipeline
  means: OMPL's path as TrajOpt's seed).

Each stage's time is its planner's solve() call alone (with the seed's
interpolation for TrajOpt). The path is returned whatever the library's
own verdict ("Failed to find valid solution: ..." with TrajOpt's last
iterate is answered FAILED with the stage): mpbench verifies it either
way. Returned: joint states, no waypoint times (TrajOpt here optimises
positions only; no time parameterisation is run).

Deviations from how Tesseract's users use it, and why:

- The robot: Tesseract 0.5.1 refuses the Panda's vamp SRDF (a group
  mixing links, joints and subgroups). tesseract_setup.py (beside this
  file) makes what a Tesseract user writes instead: a reduced SRDF with
  one chain group, GROUP, from the parent link of the request's first
  joint to the child link of its last, the source SRDF's
  disable_collisions pairs, the kinematics plugin YAML (KDL) and the
  contact-manager plugin YAML (Bullet, FCL); the URDF's meshes named by
  absolute file paths (GeneralResourceLocator). Nothing else of the SRDF
  is read.
- Time limit: none reachable from Python in 0.5.1 (TrajOptSolverProfile
  with max_iter and max_time is abstract, OMPL's solver_config an
  unwrapped SWIG object): the kit enforces the request's limit (peer.py:
  a run not answered by the time limit plus 0.3 s after the model is
  built is stopped by killing the worker process and answered TIMEOUT;
  the next request is served by a new worker).
- Seed: OMPL's random seed is not reachable either; OMPL+TrajOpt runs are
  not repeatable by the request's seed. TrajOpt has no seed, and its
  result is not quite repeatable either (table_pick_panda/0001: four
  different paths in six runs, from fresh environments, all successful).
- Goals: the kit's goal configurations (GOAL_REGIONS False); TrajOpt and
  this use of OMPL take one, the first.
- Obstacles: each scene shape a link fixed to the URDF's root link by
  AddLinkCommand (mpbench's world frame is the root's); an octree's a
  link whose one collision is the parsed Octree at the octree's pose
  (the parsed URDF's links are not added: only its geometry is taken).
  One Environment
  per robot is kept, as Tesseract's users keep one: a new scene removes
  the last one's links (RemoveLinkCommand) and adds its own (0.06-0.1 s
  where Environment.init takes 0.35-1.3 s on this machine).
"""
import os
import sys
import time

import numpy as np
from mpb import plan_result_t
from tesseract_robotics.tesseract_command_language import (
    CompositeInstruction, InstructionPoly_as_MoveInstructionPoly,
    JointWaypoint, JointWaypointPoly_wrap_JointWaypoint, MoveInstruction,
    MoveInstructionPoly_wrap_MoveInstruction, MoveInstructionType_FREESPACE,
    ProfileDictionary, WaypointPoly_as_StateWaypointPoly)
from tesseract_robotics.tesseract_common import (
    FilesystemPath, GeneralResourceLocator, Isometry3d, ManipulatorInfo,
    VectorVector3d)
from tesseract_robotics.tesseract_environment import (AddLinkCommand,
                                                       Environment,
                                                       RemoveLinkCommand)
from tesseract_robotics.tesseract_geometry import (GeometryType_OCTREE, Box,
                                                    Cylinder, Mesh, Sphere)
from tesseract_robotics.tesseract_motion_planners import PlannerRequest
from tesseract_robotics.tesseract_motion_planners_ompl import (
    OMPLMotionPlanner, OMPLRealVectorPlanProfile)
from tesseract_robotics.tesseract_motion_planners_simple import \
    generateInterpolatedProgram
from tesseract_robotics.tesseract_motion_planners_trajopt import (
    TrajOptDefaultCompositeProfile, TrajOptDefaultPlanProfile,
    TrajOptMotionPlanner)
from tesseract_robotics.tesseract_scene_graph import (Collision, Joint,
                                                      JointType_FIXED, Link)
from tesseract_robotics.tesseract_urdf import parseURDFString

from . import clouds as clouds_
from . import peer
from . import tesseract_setup

GROUP = tesseract_setup.GROUP
PROFILE = "DEFAULT"
TRAJOPT_NS = "TrajOptMotionPlannerTask"   # the planners' profile namespaces
OMPL_NS = "OMPLMotionPlannerTask"
SEED_STEPS = 20     # straight-line seed: 21 states
OMPL_PROFILE_TIME_S = 5.0   # OMPLRealVectorPlanProfile's planning time


def _geometry(shape):
    if shape.kind == "box":
        return Box(*shape.dims)
    if shape.kind == "sphere":
        return Sphere(shape.dims[0])
    if shape.kind == "cylinder":
        return Cylinder(shape.dims[0], shape.dims[1])
    verts = VectorVector3d()
    for v in shape.vertices:
        verts.append(np.array(v, dtype=float))
    faces = np.array([x for t in shape.triangles for x in (3, *t)],
                     dtype=np.int32)
    return Mesh(verts, faces)


class OctreeRefused(Exception):
    """An octree Tesseract's URDF parser would not make an Octree of."""


# A URDF of one link whose collision is an OctoMap file, as Tesseract's
# URDF documents an octree (the parser wants a joint: a root link too).
_OCTREE_URDF = """<robot name="mpb_octree">
  <link name="root"/>
  <link name="octree">
    <collision>
      <geometry>
        <octomap shape_type="box"><octree filename="{path}"/></octomap>
      </geometry>
    </collision>
  </link>
  <joint name="octree_joint" type="fixed">
    <parent link="root"/><child link="octree"/>
  </joint>
</robot>
"""


def _octree(cloud, folder):
    """The cloud's cells as Tesseract's Octree geometry, in the cloud's
    frame: its .bt file (Cloud.octomap_bt()) read by Tesseract's URDF
    parser, then the file removed (OctoMap reads it whole).
    OctreeRefused with why."""
    try:
        data = cloud.octomap_bt()
    except clouds_.CloudError as e:
        raise OctreeRefused(str(e)) from None
    path = os.path.join(folder, "octree.bt")
    with open(path, "wb") as f:
        f.write(data)
    try:
        graph = parseURDFString(_OCTREE_URDF.format(path=path),
                                GeneralResourceLocator())
    except Exception as e:    # SWIG's RuntimeError, Tesseract's message
        raise OctreeRefused(f"tesseract_urdf: {e}") from None
    finally:
        os.unlink(path)
    if graph is None:
        raise OctreeRefused("tesseract_urdf: no scene graph")
    link = graph.getLink("octree")
    geometry = link.collision[0].geometry if link is not None and \
        len(link.collision) == 1 else None
    if geometry is None or geometry.getType() != GeometryType_OCTREE:
        raise OctreeRefused("tesseract_urdf: no Octree geometry")
    return geometry


def _states(results):
    """The joint states of a planner's results (a CompositeInstruction).
    Every intermediate is kept in a variable: chained SWIG temporaries
    are freed early (segfaults in 0.5.1)."""
    flat = results.flatten()
    out = []
    for instr in flat:
        if not instr.isMoveInstruction():
            continue
        move = InstructionPoly_as_MoveInstructionPoly(instr)
        wp = move.getWaypoint()
        if not wp.isStateWaypoint():
            continue
        state = WaypointPoly_as_StateWaypointPoly(wp)
        pos = state.getPosition()
        out.append([float(x) for x in np.asarray(pos).ravel()])
    return out


class Adapter:
    NAME = "tesseract"
    DESCRIPTION = ("Tesseract 0.5.1: TrajOpt from a straight seed, and "
                   "OMPL RRTConnect then TrajOpt; Bullet collision on its "
                   "own model.")
    ALGORITHMS = ["TrajOpt", "OMPL+TrajOpt"]
    APPROACH = {"TrajOpt": "optimisation", "OMPL+TrajOpt": "hybrid"}
    GOAL_REGIONS = False     # joint goals; the kit samples IK goals

    OCTREES = True      # False: every octree as boxes (bench/, tests)

    def __init__(self):
        self.robots = {}    # (URDF, SRDF, joints) -> [Environment, base, tip]
        self.scene_links = []
        # What the kit reports the library was given (peer.Peer): set by
        # build(), "points" when an octree went in as Tesseract's Octree.
        self.CLOUDS = ""

    def _robot(self, problem):
        """The robot's Environment, made once per robot and kept, as a
        Tesseract user keeps one: a new scene removes the last scene's
        links and adds its own (Environment.init takes 0.35-1.2 s here;
        clone() returns a unique_ptr that 0.5.1's planners do not take)."""
        key = (problem.urdf, problem.srdf, tuple(problem.joints))
        if key in self.robots:
            return self.robots[key]
        folder = os.path.join(os.path.dirname(problem.urdf_path),
                              "tesseract")
        try:
            urdf, srdf, base, tip = tesseract_setup.make(
                problem.urdf, problem.srdf, problem.joints, folder)
        except tesseract_setup.SetupError as e:
            raise peer.InvalidRequest(str(e)) from None
        env = Environment()
        locator = GeneralResourceLocator()
        urdf_fs = FilesystemPath(urdf)
        srdf_fs = FilesystemPath(srdf)
        if not env.init(urdf_fs, srdf_fs, locator):
            raise peer.InvalidRequest("tesseract refuses the robot "
                                      "(Environment.init failed)")
        group = env.getJointGroup(GROUP)
        names = list(group.getJointNames())
        if names != list(problem.joints):
            raise peer.InvalidRequest(f"tesseract's group has joints "
                                      f"{', '.join(names)}")
        self.robots = {key: (env, base, tip)}
        self.scene_links = []
        return self.robots[key]

    def build(self, problem, world):
        env, base, tip = self._robot(problem)
        while self.scene_links:
            cmd = RemoveLinkCommand(self.scene_links.pop())
            if not env.applyCommand(cmd):
                self.robots = {}    # a fresh Environment next time
                raise peer.InvalidRequest("tesseract: the last scene's "
                                          "links could not be removed")
        root = env.getRootLinkName()
        # Each octree Tesseract's Octree if it takes it (else its boxes;
        # an empty one has none).
        octrees = {}
        for c in problem.clouds:
            if c.kind != "octree" or not c.boxes or not self.OCTREES:
                continue
            try:
                octrees[c.id] = (c, _octree(c, os.path.dirname(
                    problem.urdf_path)))
            except OctreeRefused as e:
                print(f"mpb-planner-tesseract: octree '{c.id}' as boxes: "
                      f"{e}", file=sys.stderr)
        self.CLOUDS = "points" if octrees else ""
        # A shape a link, but an octree's boxes (a cloud's spheres) one
        # link of many collision shapes: a link each would be thousands
        # of AddLinkCommands (a sensed scene's 5871 took over 300 s).
        # links: lists of (origin, 4x4; a Shape or a Tesseract geometry).
        links = [[(c.matrix(), g)] for c, g in octrees.values()]
        names = list(octrees)
        clouds = {}
        for s in problem.shapes:
            if s.cloud in octrees:
                continue
            part = (s.matrix(), s)
            if s.cloud is None:
                links.append([part])
                names.append(s.name)
            elif s.cloud in clouds:
                clouds[s.cloud].append(part)
            else:
                clouds[s.cloud] = [part]
                links.append(clouds[s.cloud])
                names.append(s.cloud)
        for k, parts in enumerate(links):
            link = Link(f"mpb_scene_{k}")
            for matrix, g in parts:
                col = Collision()
                col.origin = Isometry3d(np.array(matrix, dtype=float))
                col.geometry = _geometry(g) if isinstance(g, peer.Shape) \
                    else g
                link.collision.append(col)
            joint = Joint(f"mpb_scene_{k}_joint")
            joint.type = JointType_FIXED
            joint.parent_link_name = root
            joint.child_link_name = link.getName()
            cmd = AddLinkCommand(link, joint)
            if not env.applyCommand(cmd):
                raise peer.InvalidRequest(f"tesseract refuses scene shape "
                                          f"'{names[k]}'")
            self.scene_links.append(link.getName())
        if problem.held:
            env.setState(list(problem.held), np.array(
                list(problem.held.values()), dtype=float))
        manip = ManipulatorInfo()
        manip.manipulator = GROUP
        manip.tcp_frame = tip
        manip.working_frame = base
        return {"env": env, "manip": manip, "joints": list(problem.joints)}

    def _program(self, model, states):
        """A free-space program through states: the first and last
        constrained JointWaypoints (start and goal), any between
        unconstrained ones (a seed), as generateInterpolatedProgram makes
        them. Returns (program, what must outlive it)."""
        keep = []
        program = CompositeInstruction(PROFILE)
        program.setManipulatorInfo(model["manip"])
        for k, q in enumerate(states):
            wp = JointWaypoint(model["joints"], np.array(q, dtype=float))
            if 0 < k < len(states) - 1:
                wp.setIsConstrained(False)
            poly = JointWaypointPoly_wrap_JointWaypoint(wp)
            move = MoveInstruction(poly, MoveInstructionType_FREESPACE,
                                   PROFILE)
            instr = MoveInstructionPoly_wrap_MoveInstruction(move)
            program.appendMoveInstruction(instr)
            keep += [wp, poly, move, instr]
        return program, keep

    def _trajopt(self, model, instructions):
        profiles = ProfileDictionary()
        plan_profile = TrajOptDefaultPlanProfile()
        composite_profile = TrajOptDefaultCompositeProfile()
        profiles.addProfile(TRAJOPT_NS, PROFILE, plan_profile)
        profiles.addProfile(TRAJOPT_NS, PROFILE, composite_profile)
        request = PlannerRequest()
        request.instructions = instructions
        request.env = model["env"]
        request.profiles = profiles
        planner = TrajOptMotionPlanner(TRAJOPT_NS)
        response = planner.solve(request)
        results = response.results
        return (response.successful, str(response.message),
                _states(results))

    def plan(self, model, algorithm, start, goals, time_limit, seed, params):
        env = model["env"]
        goal = goals[0]
        program, keep = self._program(model, [start, goal])
        stages = []
        t0 = time.monotonic()
        seeded = generateInterpolatedProgram(program, env, 3.14, 1.0, 3.14,
                                             SEED_STEPS)
        if algorithm == "OMPL+TrajOpt":
            profiles = ProfileDictionary()
            plan_profile = OMPLRealVectorPlanProfile()
            profiles.addProfile(OMPL_NS, PROFILE, plan_profile)
            request = PlannerRequest()
            request.instructions = seeded
            request.env = env
            request.profiles = profiles
            planner = OMPLMotionPlanner(OMPL_NS)
            response = planner.solve(request)
            t_raw = time.monotonic() - t0
            if not response.successful:
                # "Exceeded allowed time" after the profile's own planning
                # time (5 s, which Python cannot change in 0.5.1) is a
                # timeout; Tesseract says the same when every thread gave
                # up at once (a start in collision: 0.9 ms), a failure.
                message = str(response.message)
                spent = t_raw >= 0.9 * min(OMPL_PROFILE_TIME_S, time_limit)
                status = plan_result_t.TIMEOUT if "time" in message and spent \
                    else plan_result_t.FAILED
                return [], status, f"tesseract OMPL: {message}", []
            results = response.results
            raw = _states(results)
            stages.append(("raw", t_raw, raw))
            # OMPL's states come back as StateWaypoints, which TrajOpt
            # holds fixed: the seed program is made of them instead, the
            # ends constrained, the states between free.
            t0 = time.monotonic()
            seeded, keep2 = self._program(model, [start] + raw[1:-1] + [goal])
            keep.append(keep2)
        ok, message, path = self._trajopt(model, seeded)
        t_opt = time.monotonic() - t0
        del keep
        if path:
            stages.append(("optimized", t_opt, path))
        if ok:
            return stages, plan_result_t.SOLVED, "", []
        return stages, plan_result_t.FAILED, f"tesseract TrajOpt: {message}", []


if __name__ == "__main__":
    peer.main(Adapter())
