"""ompl2.py - the peer `ompl2`: OMPL 2.0's Python wheel (pip ompl==2.0.1).

OMPL has no collision model: as its users do, we give SimpleSetup a state
validity checker, here a Python callable that asks libmpbench's world
(the kit's World, the verifier's own geometry) through ctypes. What that
callback costs per check is reported as the named values "collision
checks" and "check time per call (us)". Planning: SimpleSetup.solve(time
limit) (OMPL's own termination condition); then its PathSimplifier's
simplify as the stage "simplified", as SimpleSetup.simplifySolution
does (bounded by the time left); OMPL's defaults otherwise (range, goal bias, the validity checking
resolution of 1% of the space's extent).
"""
import math
import time

from mpb import plan_result_t
from ompl import base as ob
from ompl import geometric as og
from ompl import util as ou

from . import peer

_seeded = []

ALGORITHMS = ["RRTConnect", "AORRTC", "BITstar", "RRTstar", "PRM", "PRMstar",
              "RRT", "KPIECE1", "BKPIECE1", "LBKPIECE1", "FMT", "BFMT",
              "InformedRRTstar", "SORRTstar"]


class Adapter:
    NAME = "ompl2"
    DESCRIPTION = ("OMPL 2.0 (Python wheel), validity checked by "
                   "libmpbench's world through the kit.")
    ALGORITHMS = ALGORITHMS
    APPROACH = {a: "sampling" for a in ALGORITHMS}
    GOAL_REGIONS = False     # the kit samples goal states (GoalStates)

    def build(self, problem, world):
        ou.setLogLevel(ou.LOG_ERROR)
        n = world.num_joints
        if not any(world.wraps):
            space = ob.RealVectorStateSpace(n)
            bounds = ob.RealVectorBounds(n)
            for j in range(n):
                bounds.setLow(j, world.lower[j])
                bounds.setHigh(j, world.upper[j])
            space.setBounds(bounds)
            return {"space": space, "n": n, "world": world, "compound": False}
        # A continuous joint is an SO2 space, as OMPL's users (MoveIt)
        # model it: it interpolates the short way round, as the verifier
        # does; the others one bounded dimension each.
        space = ob.CompoundStateSpace()
        for j in range(n):
            if world.wraps[j]:
                space.addSubspace(ob.SO2StateSpace(), 1.0)
            else:
                sub = ob.RealVectorStateSpace(1)
                b = ob.RealVectorBounds(1)
                b.setLow(world.lower[j])
                b.setHigh(world.upper[j])
                sub.setBounds(b)
                space.addSubspace(sub, 1.0)
        return {"space": space, "n": n, "world": world, "compound": True,
                "wraps": list(world.wraps)}

    def plan(self, model, algorithm, start, goals, time_limit, seed, params):
        space, n, world = model["space"], model["n"], model["world"]
        if model["compound"]:
            wraps = model["wraps"]

            def get(state):
                return [state[i].value if wraps[i] else state[i][0]
                        for i in range(n)]

            def put(state, q):
                for i, v in enumerate(q):
                    if wraps[i]:
                        state[i].value = math.remainder(v, 2 * math.pi)
                    else:
                        state[i][0] = v
        else:
            def get(state):
                return [state[i] for i in range(n)]

            def put(state, q):
                for i, v in enumerate(q):
                    state[i] = v
        ss = og.SimpleSetup(space)
        calls = [0, 0.0]

        def valid(state):
            t = time.perf_counter()
            ok = world.free(get(state))
            calls[0] += 1
            calls[1] += time.perf_counter() - t
            return ok

        ss.setStateValidityChecker(valid)
        si = ss.getSpaceInformation()
        if not _seeded:
            # OMPL seeds its generators once per process: the first run's
            # seed holds for the process (later ones would only warn).
            ou.RNG.setSeed(seed & 0x7FFFFFFF or 1)
            _seeded.append(seed)
        s = space.allocState()
        put(s, start)
        ss.setStartState(s)
        goal = ob.GoalStates(si)
        for q in goals:
            g = space.allocState()
            put(g, q)
            goal.addState(g)
        ss.setGoal(goal)
        ss.setPlanner(getattr(og, algorithm)(si))
        ss.setup()
        t0 = time.monotonic()
        # OMPL's own termination; a tenth of the limit kept for the
        # simplifier, whose time counts too.
        status = ss.solve(0.9 * time_limit)
        t_raw = time.monotonic() - t0
        values = [("collision checks", calls[0]),
                  ("check time per call (us)",
                   1e6 * calls[1] / calls[0] if calls[0] else 0.0)]
        code = status.getStatus()
        if not ss.haveSolutionPath():
            st = (plan_result_t.TIMEOUT
                  if code == ob.PlannerStatus.TIMEOUT else plan_result_t.FAILED)
            return [], st, f"OMPL: {status.asString()}", values
        exact = ss.haveExactSolutionPath()
        path = ss.getSolutionPath()
        raw = [get(path.getState(k)) for k in range(path.getStateCount())]
        stages = [("raw", t_raw, raw)]
        if exact:
            simplified = og.PathGeometric(path)
            t1 = time.monotonic()
            left = max(time_limit - t_raw, 0.0)
            ss.getPathSimplifier().simplify(simplified, 0.9 * left)
            t_simp = time.monotonic() - t1
            stages.append(("simplified", t_simp,
                           [get(simplified.getState(k))
                            for k in range(simplified.getStateCount())]))
        return (stages,
                plan_result_t.SOLVED if exact else plan_result_t.APPROXIMATE,
                "" if exact else f"OMPL: {status.asString()}", values)


if __name__ == "__main__":
    peer.main(Adapter())
