"""Event machinery of the simulation: what an event reports, and the guards around scipy's events.

scipy's ``solve_ivp`` locates a sign change of an event function between two steps (only into the
declared ``direction``) with ``brentq`` on the dense output. Two guards sit around that:

- :func:`guard_start`: at the start of a segment (after an event) an event function of the new
  mode may be exactly zero while it moves away from zero (the gap just after a tangential
  lift-off, the slip velocity just after slipping starts). ``brentq`` would return the segment's
  start as a root; the guard reports the side the function moves into instead. Which side that is
  comes from the mode decision (the sign of a zero force's derivative), not from a time epsilon.
- :func:`within_budget`: a right-hand side that gives up once a wall-clock deadline has passed.

Examples
--------
>>> def gap(t, y):
...     return y[0]
>>> gap.terminal, gap.direction = True, -1.0
>>> guarded = guard_start(gap, 0.0, [0.0])
>>> guarded(0.0, [0.0]) > 0, guarded(0.5, [-1.0])
(True, -1.0)
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

__all__ = ["EventRecord", "SimulationError", "guard_start", "within_budget"]


class SimulationError(RuntimeError):
    """The motion cannot be continued (integrator failure, endless events)."""


@dataclass(frozen=True)
class EventRecord:
    """An effect switching: when, what, on which constraint, and the state the motion continues from."""

    t: float
    effect: str  # "release" | "contact" | "bounce" | "slip" | "stick"
    constraint: str
    state: dict[str, float]

    def to_json(self) -> dict:
        return {"t": self.t, "effect": self.effect, "constraint": self.constraint, "state": self.state}


def within_budget(rhs, deadline: float):
    """``rhs`` that stops the integration once the clock passes ``deadline``."""
    calls = 0

    def limited(t, y):
        nonlocal calls
        calls += 1
        if calls % 256 == 0 and time.monotonic() > deadline:
            raise SimulationError(f"stopped at t = {t:.6g}: the simulation took longer than its time budget")
        return rhs(t, y)

    return limited


def guard_start(g, t0: float, y0: np.ndarray):
    """``g`` with its value at the segment's start moved to the side it leaves towards.

    The mode was chosen (:meth:`grader.simulate.trajectory.Simulation.settle`) so that every event
    function of the new mode starts on its non-firing side or at zero moving away from it (the gap
    just after a lift-off, the slip velocity just after slipping starts). At exactly zero scipy would take the start of
    the first step as a root (brentq returns an endpoint where the function is 0), and miss a
    real crossing later in that step (a ball that bounces and lands within one step), so at the
    start the function reports the side it moves into.
    """
    away = -g.direction
    start = g(t0, y0)
    start = start if start * away > 0 else away * 1e-300

    def guarded(t, y):
        return start if t == t0 else g(t, y)

    guarded.terminal, guarded.direction = g.terminal, g.direction
    return guarded
