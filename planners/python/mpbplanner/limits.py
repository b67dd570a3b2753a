"""limits.py - when a solve() must end, as the C kit's mpb_solve_limits:
the run's deadline (time.monotonic()) and the node's stop flag."""
from __future__ import annotations

import inspect
import time
from typing import Callable


class Limits:
    """Given to solve(req, limits) by Node.serve(): start is when the node
    called solve(), deadline start + req.time_limit; stopping() is true
    once the node is asked to stop (Node.stop(), a signal); tell(phase)
    says "setting_up" or "planning" to mpbenchd (setting_up(),
    planning())."""

    def __init__(self, start: float, time_limit: float,
                 stopping: Callable[[], bool] = lambda: False,
                 tell: Callable[[str], None] = lambda phase: None) -> None:
        self.start = start
        self.deadline = start + time_limit
        self.stopping = stopping
        self._tell = tell
        self._told: set = set()     # shared by the copies moved()

    def _say(self, phase: str) -> None:
        if phase not in self._told:
            self._told.add(phase)
            self._tell(phase)

    def setting_up(self) -> None:
        """Say that the planner first builds its model of a new robot and
        scene (outside the run's time: report it as world_setup_time).
        mpbenchd's deadline then waits for it, up to 120 s, instead of
        counting it in the time limit and its 5 s of grace. Once per run,
        before building; then planning()."""
        self._say("setting_up")

    def planning(self) -> None:
        """Say that planning starts now, the model built: mpbenchd's time
        limit and grace run from here. Once per run, after
        setting_up()."""
        self._say("planning")

    def should_stop(self) -> bool:
        """True when solve() should give up now: stopping, or the deadline
        has passed. The one stop check of every planner, as the C kit's
        mpb_solve_should_stop()."""
        return self.stopping() or time.monotonic() >= self.deadline

    def moved(self, seconds: float) -> Limits:
        """A copy with the deadline seconds later (earlier when negative),
        stopping the same: a planner's own budget inside the run's, e.g.
        the deadline moved by the world's setup, which mpbenchd leaves
        out of the run's time (mpb_solve_limits_moved())."""
        copy = Limits(self.start, 0.0, self.stopping, self._tell)
        copy._told = self._told
        copy.deadline = self.deadline + seconds
        return copy


def takes_limits(solve: Callable[..., object]) -> bool:
    """Whether solve takes (req, limits): two positional parameters without
    defaults, *args, or a second one named limits (solve(req,
    limits=None)). A solve(req) of older planners, or a solve(req,
    cache=None), is called with the request alone."""
    try:
        params = list(inspect.signature(solve).parameters.values())
    except (TypeError, ValueError):
        return False
    if any(p.kind == p.VAR_POSITIONAL for p in params):
        return True
    if len(params) >= 2 and params[1].name == "limits":
        return True
    positional = [p for p in params
                  if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)
                  and p.default is p.empty]
    return len(positional) >= 2
