"""Numerical constrained motion: integrate a scene and report multipliers and reaction forces.

This is the numerical experiment that confirms the symbolic engine. It uses only the numeric
callables of a :class:`~grader.simulate.lagrangian_numeric.NumericScene`: at every instant the
accelerations and multipliers come from the KKT system of
:func:`~grader.simulate.lagrangian_numeric.snapshot`, and the state (q, q̇) is advanced with
scipy's DOP853 (an 8th-order Runge–Kutta method) at tight tolerances.

The constraints enter at the acceleration level (index reduction, no Baumgarte terms), so
f and ḟ drift with the integration error. Integration therefore runs in segments that end at
every requested sample time (and every ``projection_interval``); at each segment end the
state is projected back onto f = 0, ḟ = 0 (:mod:`grader.simulate.manifold`) before it is
reported or integration restarts. Events are located by scipy on the dense output (to a few
ulps in t) and the state there is projected too.

Unilateral constraints are integrated as bilateral ones: the motion is the constrained one even
after a contact force changes sign. Use :func:`multiplier_zero` to find where a contact would
release.

Examples
--------
A bead sliding from the top of a sphere of radius 1 (polar coordinates, contact r - R = 0):
it leaves the surface where cos θ = 2/3 (the tiny starting speed 1e-6 rad/s, needed to leave
the unstable top, raises that by only R θ̇0²/(3 g) ≈ 3e-14).

>>> import mpmath
>>> m, g, R = 1.0, 9.81, 1.0
>>> sphere = NumericScene(("r", "theta"),
...     kinetic=lambda q, v, t: m / 2 * (v[0]**2 + q[0]**2 * v[1]**2),
...     potential=lambda q, t: m * g * q[0] * mpmath.cos(q[1]),
...     constraints=(NumericConstraint("surface", lambda q, t: q[0] - R, unilateral=True),))
>>> motion = simulate(sphere, [1.0, 0.0], [0.0, 1e-6], t_end=10.0,
...                   events=[multiplier_zero("surface")])
>>> motion.stopped_by
'lambda_surface = 0'
>>> round(float(np.cos(motion.first("lambda_surface = 0").coordinate("theta"))), 10)
0.6666666667
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, Sequence

import numpy as np
from scipy.integrate import solve_ivp

from grader.simulate.lagrangian_numeric import NumericConstraint, NumericScene, Snapshot, constraint_terms, snapshot
from grader.simulate.manifold import ConstraintViolation, project_positions, project_velocities

__all__ = [
    "Event",
    "Motion",
    "NumericConstraint",
    "NumericScene",
    "Snapshot",
    "multiplier_zero",
    "simulate",
]


@dataclass(frozen=True)
class Event:
    """A condition g(snapshot) = 0 to be located along the motion.

    Parameters
    ----------
    name : str
        How the event is reported in :attr:`Motion.events` and :attr:`Motion.stopped_by`.
    function : callable
        ``g(snapshot) -> float``; it sees the accelerations, multipliers and forces.
    direction : float
        As in :func:`scipy.integrate.solve_ivp`: 0 any crossing, > 0 only from negative to
        positive, < 0 only from positive to negative.
    terminal : bool
        Stop the integration at the first occurrence.
    """

    name: str
    function: Callable[[Snapshot], float]
    direction: float = 0.0
    terminal: bool = True


def multiplier_zero(constraint: str, *, direction: float = 0.0, terminal: bool = True) -> Event:
    """The event "λ of this constraint crosses zero", e.g. where a contact force vanishes.

    Examples
    --------
    >>> multiplier_zero("surface").name
    'lambda_surface = 0'
    """
    return Event(f"lambda_{constraint} = 0", lambda s: s.multiplier(constraint), direction, terminal)


@dataclass(frozen=True)
class Motion:
    """The result of :func:`simulate`.

    Attributes
    ----------
    t : ndarray, shape (k,)
        Times of the integrator's steps (the trajectory as computed, before projection).
    q, qdot : ndarray, shape (k, n)
        Coordinates and velocities at those times.
    samples : tuple of Snapshot
        Full states (with q̈, λ, Q) at the requested sample times reached before a terminal event.
    end : Snapshot
        The full state where the integration ended (t_end or a terminal event), on the
        constraint manifold: start a continuation from ``end.t, end.q, end.qdot``.
    events : dict
        Event name -> tuple of Snapshots where it occurred, in time order.
    stopped_by : str or None
        The terminal event that ended the integration, if any.
    evaluations : int
        How many times the dynamics (the KKT system) were evaluated.
    """

    t: np.ndarray
    q: np.ndarray
    qdot: np.ndarray
    samples: tuple[Snapshot, ...]
    end: Snapshot
    events: dict[str, tuple[Snapshot, ...]] = field(default_factory=dict)
    stopped_by: str | None = None
    evaluations: int = 0

    def first(self, event: str) -> Snapshot | None:
        """The first occurrence of an event, or None if it did not occur."""
        found = self.events.get(event, ())
        return found[0] if found else None


class _Dynamics:
    """The ODE right-hand side, remembering the last state so that an event evaluated at the
    end of a step (where DOP853 has just evaluated the dynamics) costs nothing."""

    def __init__(self, scene: NumericScene):
        self.scene, self.n, self.evaluations = scene, len(scene.coordinates), 0
        self._key: tuple | None = None
        self._last: Snapshot | None = None

    def at(self, t: float, y: np.ndarray) -> Snapshot:
        key = (float(t), y.tobytes())
        if key != self._key:
            self._last = snapshot(self.scene, t, y[: self.n], y[self.n:])
            self._key = key
            self.evaluations += 1
        return self._last

    def rhs(self, t: float, y: np.ndarray) -> np.ndarray:
        s = self.at(t, y)
        return np.concatenate([s.qdot, s.qddot])

    def event(self, event: Event) -> Callable[[float, np.ndarray], float]:
        def g(t, y):
            return float(event.function(self.at(t, y)))

        g.terminal, g.direction = event.terminal, event.direction
        return g


def _on_manifold(scene: NumericScene, t: float, y: np.ndarray) -> np.ndarray:
    n = len(scene.coordinates)
    q = project_positions(scene, t, y[:n])
    return np.concatenate([q, project_velocities(scene, t, q, y[n:])])


def _check_consistent(scene: NumericScene, t: float, q: np.ndarray, qdot: np.ndarray) -> None:
    # A caller's inconsistent initial state is an error, not something to fix silently: the
    # minimum-norm projection would pick *some* state, not necessarily the intended one.
    if not scene.constraints:
        return
    terms = constraint_terms(scene, t, q)
    J = terms.jacobian
    position_scale = np.abs(J) @ np.abs(q) + 1.0
    velocity_scale = np.abs(J) @ np.abs(qdot) + np.abs(terms.rate) + 1.0
    off = [name for name, f, fs, v, vs in zip(scene.constraint_names, terms.value, position_scale,
                                             J @ qdot + terms.rate, velocity_scale)
           if abs(f) > 1e-9 * fs or abs(v) > 1e-9 * vs]
    if off:
        raise ConstraintViolation(f"the initial state violates the constraint(s) {', '.join(off)}; "
                                  "complete it with grader.simulate.manifold.project_positions/"
                                  "project_velocities (free=...) first")


def _breakpoints(t0: float, t_end: float, samples: Sequence[float], interval: float | None) -> list[float]:
    points = {float(t_end)} | {float(s) for s in samples if t0 < s < t_end}
    if interval:
        points |= set(np.arange(t0 + interval, t_end, interval).tolist())
    return sorted(points)


def simulate(scene: NumericScene, q0: Sequence[float], qdot0: Sequence[float], t_end: float, *,
             t0: float = 0.0, sample_times: Sequence[float] = (), events: Sequence[Event] = (),
             rtol: float = 1e-11, atol: float = 1e-12, projection_interval: float | None = None,
             max_step: float = np.inf) -> Motion:
    """Integrate the constrained motion from a consistent initial state.

    Parameters
    ----------
    scene : NumericScene
    q0, qdot0 : sequence of float
        Initial coordinates and velocities; they must satisfy f = 0 and ḟ = 0 (to 1e-9
        relative). Complete partial data with :mod:`grader.simulate.manifold` first.
    t_end : float
        Integrate over [t0, t_end] unless a terminal event stops earlier.
    t0 : float
        Initial time (matters for rheonomic constraints and time-dependent energies).
    sample_times : sequence of float
        Times in [t0, t_end] at which to report full :class:`Snapshot` s.
    events : sequence of Event
        Conditions to locate, with unique names; see :func:`multiplier_zero`.
    rtol, atol : float
        Tolerances of DOP853.
    projection_interval : float, optional
        Also project onto the constraint manifold every this much time (besides each sample
        time); useful for long runs.
    max_step : float
        Largest step DOP853 may take.

    Returns
    -------
    Motion

    Raises
    ------
    ConstraintViolation
        If the initial state is not on the constraint manifold.
    RuntimeError
        If the integrator fails (e.g. the motion runs into a singularity of the coordinates).

    Examples
    --------
    A half-Atwood machine: block m1 = 2 on a smooth table, m2 = 1 hanging, x1 = y2 by the string.
    The string tension is λ = m1 m2 g / (m1 + m2) = 6.54.

    >>> atwood = NumericScene(("x1", "y2"), lambda q, v, t: (2 * v[0]**2 + v[1]**2) / 2,
    ...     lambda q, t: -9.81 * q[1], (NumericConstraint("string", lambda q, t: q[0] - q[1]),))
    >>> motion = simulate(atwood, [0.0, 0.0], [0.0, 0.0], t_end=1.0, sample_times=[0.5, 1.0])
    >>> [round(s.multiplier("string"), 9) for s in motion.samples]
    [6.54, 6.54]
    """
    if t_end <= t0:
        raise ValueError(f"t_end ({t_end}) must be after t0 ({t0})")
    n = len(scene.coordinates)
    q0, qdot0 = np.asarray(q0, dtype=float), np.asarray(qdot0, dtype=float)
    if q0.shape != (n,) or qdot0.shape != (n,):
        raise ValueError(f"expected {n} initial coordinates and velocities")
    _check_consistent(scene, t0, q0, qdot0)

    names = [e.name for e in events]
    if len(set(names)) != len(names):
        raise ValueError(f"event names must be unique: {names}")
    dynamics = _Dynamics(scene)
    ivp_events = [dynamics.event(e) for e in events]
    wanted = sorted(float(s) for s in sample_times)
    if any(s < t0 or s > t_end for s in wanted):
        raise ValueError(f"sample times must lie in [{t0}, {t_end}]")

    y = _on_manifold(scene, t0, np.concatenate([q0, qdot0]))
    times, states = [np.array([t0])], [y[None, :]]
    samples, found = [], {e.name: [] for e in events}
    if wanted and wanted[0] == t0:
        samples.append(dynamics.at(t0, y))
    stopped_by, t_start, step = None, float(t0), None
    for t_stop in _breakpoints(t0, t_end, wanted, projection_interval):
        # Restart with the step the last segment settled on: choosing a first step afresh costs
        # evaluations, and the tolerance has already told us what step the motion allows.
        first_step = min(step, t_stop - t_start) if step else None
        solution = solve_ivp(dynamics.rhs, (t_start, t_stop), y, method="DOP853", rtol=rtol, atol=atol,
                             events=ivp_events or None, max_step=max_step, first_step=first_step)
        if solution.status == -1:
            raise RuntimeError(f"integration failed at t = {solution.t[-1]}: {solution.message}")
        times.append(solution.t[1:])
        states.append(solution.y.T[1:])
        for event, t_hits, y_hits in zip(events, solution.t_events or [], solution.y_events or []):
            for t_hit, y_hit in zip(t_hits, y_hits):
                found[event.name].append(dynamics.at(t_hit, _on_manifold(scene, t_hit, y_hit)))
        if solution.status == 1:  # a terminal event
            stopped_by = next(e.name for e, hits in zip(events, solution.t_events) if e.terminal and len(hits))
            end = found[stopped_by][-1]
            break
        steps = np.diff(solution.t)
        # The last step is often cut short by the segment's end; the one before it is not.
        step = float(steps[-2] if len(steps) > 1 else steps[-1]) if len(steps) else step
        t_start, y = t_stop, _on_manifold(scene, t_stop, solution.y[:, -1])
        end = dynamics.at(t_stop, y)
        if t_stop in wanted:
            samples.append(end)

    trajectory = np.concatenate(states)
    return Motion(t=np.concatenate(times), q=trajectory[:, :n], qdot=trajectory[:, n:], samples=tuple(samples),
                  end=end, events={name: tuple(hits) for name, hits in found.items()}, stopped_by=stopped_by,
                  evaluations=dynamics.evaluations)
