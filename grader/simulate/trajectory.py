"""Simulating a scene with its declared effects: trajectory, reaction forces and events.

The motion is integrated with scipy's DOP853 on the compiled equations of motion
(:mod:`grader.simulate.compiled`), in one *mode* at a time (:class:`~grader.simulate.effects.Mode`:
which constraints hold, which slip). Each mode has event functions only for the effects the scene
declares (:mod:`grader.simulate.effects`):

==============================  =====================  ============================
effect, state                   event function         then
==============================  =====================  ============================
unilateral, in contact          λ ↓ 0                  ``release``: the body leaves
unilateral, open                f ↓ 0                  ``contact`` (impact) or ``bounce``
rolling, sticking               μ_s N ∓ λ ↓ 0          ``slip``
rolling, slipping with sign σ   σ ḟ ↓ 0                ``stick`` (or slip the other way)
==============================  =====================  ============================

A scene with only bilateral constraints has no event function, no extra unknowns and no
switching: its right-hand side is :meth:`~grader.simulate.compiled.CompiledScene.rhs` itself.

**Events.** scipy locates a sign change of an event function on DOP853's dense output; a few Newton
steps along the flow (with the true right-hand side) then put the event on the root to ~1e-12,
and the state is projected onto the constraints that hold. The new mode is decided from the state
alone (:meth:`Simulation.settle`): a constraint force that is zero there counts by the sign of its
time derivative, so restarting at an event, with the state the event reports, continues in the
same mode and does not fire the event again. Event functions have a direction (only a crossing
into the forbidden sign counts), so a function that starts at zero and moves away (the gap just
after a tangential lift-off, the slip velocity just after slipping starts) does not fire.
scipy tests event functions only at the ends of its steps; each function is also tested at three
points inside every step, and a minimum between them is followed down on the dense output, so a
force that turns negative and back within one step (a bob whirled just below the critical speed)
is a release (:meth:`Simulation._within_steps`). A gap fires only below −1e-13 of its scale, a
contact force only below −1e-9 of its scale, never at exactly zero: rounding is not an impact or
a release, and a tension that touches zero (a whirl at exactly the critical speed) holds.

**Impacts** (:meth:`Simulation._impacts`) follow Newton's law contact by contact: a resting contact
that would have to pull lets go (a struck Atwood mass slackens its string), and one with
restitution > 0 is struck in turn when the impulses drive it in (Newton's cradle). Friction at an
impact follows Coulomb's law for impulses. A contact that would leave too slowly to lift its gap
out of rounding holds, which ends a Zeno sequence of bounces in resting contact.

Examples
--------
A body released from rest at θ₀ = 0.3 on a smooth sphere leaves it where cos θ = (2/3) cos θ₀:

>>> import math
>>> from grader.mechanics.scene import load_scene
>>> trajectory = simulate_scene(load_scene("problems/sphere.toml"), {}, t_end=2.0,
...                             initial={"theta": 0.3})
>>> event = trajectory.events[0]
>>> event.effect, event.constraint
('release', 'surface')
>>> abs(math.cos(event.state["theta"]) - 2 / 3 * math.cos(0.3)) < 1e-10
True
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Callable, Mapping, Sequence

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq, minimize_scalar

from grader.simulate.compiled import CompiledScene, SingularDynamics, kkt_solve, parameter_values
from grader.simulate.effects import Effect, Mode, declared_effects
from grader.simulate.events import EventRecord, SimulationError, guard_start, within_budget
from grader.simulate.initial import initial_state

__all__ = ["Simulation", "Trajectory", "simulate_scene"]

_TOL = 1e-9          # relative: what counts as zero for a gap, a rate or a force at a mode decision
_H = 1e-6            # s: step of the central differences along the flow (signs, Newton step)
_MAX_EVENTS = 10_000
_SCAN = np.array([0.0, 0.25, 0.5, 0.75])  # where inside each step event functions are also tested
_NOISE = 1e-13      # relative: a gap or contact force this far below zero is rounding (event functions)
_BAND = 1e-11        # relative: friction within this of μ_s N still holds (rounding, not physics)
_MAX_IMPACT_ROUNDS = 100_000  # contacts struck one after the other at one instant (Newton's cradle)


@dataclass
class Trajectory:
    """Samples of the motion with the reaction forces, and every event.

    Attributes
    ----------
    t : ndarray (k,)
    q, qdot : ndarray (k, n)
    multipliers : ndarray (k, m)
        λ of every constraint (0 while it is open; for a slipping rolling constraint, the
        kinetic friction −σ μ_k N, so that ``forces`` is λ ∂f/∂q throughout).
    forces : ndarray (k, m, n)
        Generalized reaction forces Q_ij = λ_i ∂f_i/∂q_j.
    active : ndarray (k, m) of bool
        Whether each constraint held (f = 0, or its offset after a slip) at each sample: False
        while a contact is open or a rolling constraint slips.
    events : list of EventRecord
    """

    coordinates: tuple[str, ...]
    constraints: tuple[str, ...]
    t: np.ndarray
    q: np.ndarray
    qdot: np.ndarray
    multipliers: np.ndarray
    forces: np.ndarray
    active: np.ndarray
    events: list[EventRecord] = field(default_factory=list)

    def sample_rows(self) -> list[dict[str, float]]:
        """One dict per sample: t, each coordinate and its dot, each λ and Q."""
        rows = []
        for k in range(len(self.t)):
            row = {"t": float(self.t[k])}
            for j, name in enumerate(self.coordinates):
                row[name] = float(self.q[k, j])
                row[f"{name}dot"] = float(self.qdot[k, j])
            for i, c in enumerate(self.constraints):
                row[f"lambda_{c}"] = float(self.multipliers[k, i])
                for j, name in enumerate(self.coordinates):
                    row[f"Q_{c}_{name}"] = float(self.forces[k, i, j])
            rows.append(row)
        return rows

    def to_json(self) -> dict:
        """``{"events": [...], "samples": [...]}``, the contract of ``grader simulate --json``."""
        return {"events": [e.to_json() for e in self.events], "samples": self.sample_rows()}


class _Evaluator:
    """The dynamics of one mode, remembering the last state so that events evaluated where the
    integrator has just evaluated the right-hand side cost nothing."""

    def __init__(self, simulation: "Simulation", mode: Mode):
        self.simulation, self.mode = simulation, mode
        self._key: tuple | None = None
        self._value = None

    def at(self, t: float, y: np.ndarray):
        key = (float(t), y.tobytes())
        if key != self._key:
            self._value = self.simulation.solve(t, y, self.mode)
            self._key = key
        return self._value

    def rhs(self, t: float, y: np.ndarray) -> np.ndarray:
        return np.concatenate([y[self.simulation.n:], self.at(t, y)[0]])


class Simulation:
    """The effect-aware integrator of one compiled scene.

    Parameters
    ----------
    compiled : CompiledScene
    effects : list of Effect
        One per constraint, in the scene's order (see :func:`declared_effects`).
    rtol, atol : float
        DOP853 tolerances.
    """

    def __init__(self, compiled: CompiledScene, effects: Sequence[Effect], *, rtol: float = 1e-11,
                 atol: float = 1e-12):
        self.compiled, self.effects = compiled, list(effects)
        self.n, self.m = compiled.n, compiled.m
        self.rtol, self.atol = rtol, atol
        self.switching = any(e.kind != "bilateral" for e in self.effects)
        self._deadline: float | None = None

    # -- dynamics in a mode -----------------------------------------------------------------------
    def solve(self, t: float, y: np.ndarray, mode: Mode):
        """q̈, λ (all m; see :class:`Trajectory`), J and F at a state, in a mode."""
        n = self.n
        q, v = y[:n], y[n:]
        M, F, J, b = self.compiled.terms(t, q, v)
        active = sorted(mode.active)
        extra = None
        friction = [(r, s) for r, s in mode.slipping.items() if s and self.effects[r].normal in mode.active]
        if friction:
            extra = np.zeros((n, len(active)))
            for r, sigma in friction:
                effect = self.effects[r]
                extra[:, active.index(effect.normal)] += effect.mu_k * sigma * J[r]
        qddot, lam_active = kkt_solve(M, F, J[active], b[active], extra, t=t)
        lam = np.zeros(self.m)
        lam[active] = lam_active
        for r, sigma in friction:
            lam[r] = -self.effects[r].mu_k * sigma * lam[self.effects[r].normal]
        return qddot, lam, J, F

    def _flow_derivative(self, g: Callable[[float, np.ndarray], float], t: float, y: np.ndarray,
                         mode: Mode) -> float:
        ydot = np.concatenate([y[self.n:], self.solve(t, y, mode)[0]])
        return (g(t + _H, y + _H * ydot) - g(t - _H, y - _H * ydot)) / (2 * _H)

    # -- event functions of a mode ----------------------------------------------------------------
    def _friction_margin(self, r: int, sign: float, evaluator: _Evaluator):
        # |f| > μ_s N is strict: a friction equal to the limit up to rounding (an incline exactly
        # at the threshold) holds, so the margin gets a band of _BAND relative.
        effect = self.effects[r]

        def margin(t, y):
            lam = evaluator.at(t, y)[1]
            limit = effect.mu_s * lam[effect.normal]
            return limit - sign * lam[r] + _BAND * (abs(limit) + abs(lam[r]))

        return margin

    def event_functions(self, mode: Mode, evaluator: _Evaluator, t0: float | None = None,
                        y0: np.ndarray | None = None) -> list[tuple[Callable, str, int]]:
        """(g, effect, constraint index) per event the mode can meet; g has its direction set.

        With the segment's start (t0, y0), the gap of an open contact fires only below −1e-13 of
        its scale (:data:`_NOISE`), the force of a closed one only below what counts as zero at a
        mode decision (:data:`_TOL`, 1e-9 relative: a tension that only touches zero at the top
        of a whirl at the critical speed is not a release; the release is then put where λ = 0),
        and neither at exactly zero:
        after a lift-off whose gap grows only like t³ (a string going slack where its tension
        barely turns negative) the gap stays at rounding level, ±1e-16, for many steps; counting
        that as an impact closed the contact, which released again at once, thousands of times.
        A contact force that is exactly 0 all along (a block sliding on a floor without gravity)
        is a crossing for scipy (0 ≤ 0), which reported a release after the first step."""
        functions = []
        gap_band = force_band = np.zeros(self.m)
        if y0 is not None:
            force_tol, gap_tol, _ = self._noise_scales(t0, y0, mode)
            force_band = force_tol + 1e-300
            gap_band = _NOISE / _TOL * gap_tol + 1e-300

        def add(g, direction, effect, index, band=0.0):
            g.terminal, g.direction, g.band = True, direction, band
            functions.append((g, effect, index))

        for e in self.effects:
            i = e.index
            if e.kind == "unilateral":
                if i in mode.active:
                    add(lambda t, y, i=i, o=float(force_band[i]): evaluator.at(t, y)[1][i] + o,
                        -1.0, "release", i, float(force_band[i]))
                else:
                    add(lambda t, y, i=i, o=float(gap_band[i]): self.compiled.gaps(t, y[:self.n])[0][i] + o,
                        -1.0, "contact", i, float(gap_band[i]))
            elif e.kind == "rolling" and e.normal in mode.active:
                if i in mode.active:
                    for sign in (1.0, -1.0):
                        add(self._friction_margin(i, sign, evaluator), -1.0, "slip", i)
                elif mode.slipping.get(i):
                    sigma = mode.slipping[i]
                    add(lambda t, y, i=i, s=sigma: s * self.compiled.rates(t, y[:self.n], y[self.n:])[i],
                        -1.0, "stick", i)
        return functions

    # -- mode decisions ---------------------------------------------------------------------------
    def _scales(self, t: float, y: np.ndarray):
        q, v = y[:self.n], y[self.n:]
        f, J = self.compiled.gaps(t, q)
        rates = self.compiled.rates(t, q, v)
        norms = np.linalg.norm(J, axis=1) + 1e-300
        return f, rates, _TOL * (1 + np.abs(J) @ np.abs(q)), _TOL * (1 + np.abs(J) @ np.abs(v)), norms

    def settle(self, t: float, y: np.ndarray, mode: Mode) -> tuple[Mode, list[tuple[str, int]]]:
        """The consistent mode at a state, starting from a candidate; returns it and the switches.

        A unilateral constraint whose force is negative opens; one whose force is zero opens if
        the force is decreasing. A sticking rolling constraint whose friction exceeds μ_s N
        (or equals it and is rising beyond) slips; a slipping one whose slip velocity is zero
        tries to stick.
        """
        mode = mode.copy()
        switches: list[tuple[str, int]] = []
        f, rates, f_tol, v_tol, norms = self._scales(t, y)
        for _ in range(4 * self.m + 4):
            self._reconsider_rolling(mode, f, rates, v_tol)
            _, lam, _, F = self.solve(t, y, mode)
            force_tol = _TOL * (np.linalg.norm(F) + np.abs(lam).max(initial=0.0)) / norms
            change = None
            for e in self.effects:
                i = e.index
                if e.kind == "unilateral" and i in mode.active:
                    if lam[i] < -force_tol[i]:
                        change = ("release", i, False)
                    elif abs(lam[i]) <= force_tol[i] and self._flow_derivative(
                            lambda tt, yy, i=i, md=mode: self.solve(tt, yy, md)[1][i], t, y, mode) < 0:
                        change = ("release", i, True)
                if e.kind == "rolling" and i in mode.active:
                    sign = 1.0 if lam[i] >= 0 else -1.0
                    limit = e.mu_s * lam[e.normal]
                    margin, band = limit - sign * lam[i], _BAND * (abs(limit) + abs(lam[i]))
                    if margin < -band:
                        change = ("slip", i, False)
                    elif (abs(margin) <= band and abs(lam[i]) > force_tol[i]
                          and self._flow_derivative(self._margin(i, sign, mode), t, y, mode) < 0):
                        change = ("slip", i, True)
                if change is not None:
                    break
            if change is None:
                return mode, switches
            effect, i, _ = change
            mode.active.discard(i)
            if effect == "slip":
                mode.slipping[i] = -1.0 if lam[i] > 0 else 1.0
            switches.append(change)
        raise SimulationError(f"at t = {t:.9g} no consistent contact mode was found")

    def _margin(self, r: int, sign: float, mode: Mode):
        effect = self.effects[r]
        return lambda t, y: effect.mu_s * self.solve(t, y, mode)[1][effect.normal] - sign * self.solve(t, y, mode)[1][r]

    def _reconsider_rolling(self, mode: Mode, f, rates, v_tol) -> None:
        """Rolling constraints follow their normal contact: no friction while it is open; when it
        holds, a slip velocity of zero is a candidate for sticking."""
        for e in self.effects:
            if e.kind != "rolling":
                continue
            i = e.index
            if e.normal not in mode.active:
                mode.active.discard(i)
                mode.slipping[i] = float(np.sign(rates[i])) if abs(rates[i]) > v_tol[i] else 0.0
            elif i not in mode.active and not mode.slipping.get(i):
                if abs(rates[i]) > v_tol[i]:
                    mode.slipping[i] = float(np.sign(rates[i]))
                else:
                    mode.slipping.pop(i, None)
                    mode.active.add(i)
                    mode.offsets[i] = float(f[i])
            if i in mode.active:
                mode.slipping.pop(i, None)

    def initial_mode(self, t: float, y: np.ndarray) -> tuple[Mode, np.ndarray, list[tuple[str, int, bool]]]:
        """The mode and state at the start: every contact that touches and does not separate
        holds; one that touches while moving into the surface is an impact at the start."""
        f, rates, f_tol, v_tol, _ = self._scales(t, y)
        mode = Mode({e.index for e in self.effects if e.kind == "bilateral"})
        touching = [e.index for e in self.effects
                    if e.kind == "unilateral" and f[e.index] <= f_tol[e.index] and rates[e.index] <= v_tol[e.index]]
        impacts = [i for i in touching if rates[i] < -v_tol[i]]
        mode.active |= set(touching) - set(impacts)
        mode, switches = self.settle(t, y, mode)
        for i in impacts:
            if i not in mode.active:
                mode, y, more = self.transition(t, y, mode, "contact", i)
                switches += more
        return mode, y, switches

    # -- transitions ------------------------------------------------------------------------------
    def project(self, t: float, y: np.ndarray, mode: Mode) -> np.ndarray:
        """The nearest state on the constraints that hold (positions Gauss–Newton, velocities in the
        kinetic-energy metric)."""
        if not mode.active:
            return y
        n, active = self.n, sorted(mode.active)
        target = np.array([mode.offsets.get(i, 0.0) for i in active])
        q = y[:n].copy()
        for _ in range(5):
            f, J = self.compiled.gaps(t, q)
            step, *_ = np.linalg.lstsq(J[active], target - f[active], rcond=None)
            q += step
            if np.all(np.abs(step) <= 1e-16 * (1 + np.abs(q))):
                break
        v = y[n:].copy()
        v += self._velocity_change(t, q, v, active, -self.compiled.rates(t, q, v)[active])
        return np.concatenate([q, v])

    def _velocity_change(self, t, q, v, rows, change) -> np.ndarray:
        """Δq̇ with M Δq̇ = Jᵀ Λ and J Δq̇ = ``change`` for the constraints ``rows`` (an impulse)."""
        M, _, J, _ = self.compiled.terms(t, q, v)
        return _impulse(M, J[rows].T, J[rows], change)[0]

    def _impacts(self, t, q, v, mode: Mode, struck: list[int]) -> tuple[np.ndarray, set[int], set[int], set[int]]:
        """Newton's impact law on the contacts ``struck``, then on every contact the impulses
        drive in, round after round: (q̇ after, unilateral contacts that hold after, contacts struck,
        rolling constraints that slip).

        In each round the struck contacts take their impulses together, each by its own
        restitution, with the bilateral constraints kept, the rolling ones by Coulomb's law (see
        :meth:`_impact_round`) and the resting contacts of restitution 0 kept at rest; a resting contact that could only be kept by pulling (a
        string whose mass is struck towards the pulley, a ball under a block that the block's
        string jerks away) lets go, and so does a struck one whose joint impulse would pull.
        A resting contact with restitution > 0 takes no part in the round: if the impulses
        drive it in, it is struck in the next one (Newton's cradle passes the blow on to the
        last ball; a ball resting on a bigger one bounces off it after the big one's rebound).
        """
        y = np.concatenate([q, v])
        f, _, f_tol, v_tol, _ = self._scales(t, y)
        unilateral = {e.index for e in self.effects if e.kind == "unilateral"}
        touching = {j for j in unilateral if abs(f[j]) <= f_tol[j]} | set(struck)
        rigid = mode.active - unilateral
        held = {j for j in mode.active & unilateral if self.effects[j].restitution == 0}
        # A contact leaving at a rate that cannot lift its gap out of rounding (ḟ² < 2 |f̈| × 4 ε
        # of its scale, f̈ with it open and the others as they were) does not leave: the last
        # cycles of a Zeno sequence gained or lost that much energy at each inexact impact and
        # went on for ever below 1e-7 m/s (a ball bouncing on a stop; a block lifted off the
        # floor by a string and landing again while the other mass flies on the slack string; a
        # small ball bouncing on a big one resting on the floor).
        bias = self.compiled.terms(t, q, v)[3]
        for j in touching:
            try:
                qddot, _, J, _ = self.solve(t, y, Mode(mode.active - {j}, dict(mode.slipping), dict(mode.offsets)))
            except SingularDynamics:  # open, it would leave a massless coordinate free
                continue
            pull = -(J[j] @ qddot + bias[j])
            v_tol[j] = max(v_tol[j], np.sqrt(max(2 * pull * 4 * np.finfo(float).eps / _TOL * f_tol[j], 0.0)))
        hit: set[int] = set()
        slipped: set[int] = set()
        for round_ in range(_MAX_IMPACT_ROUNDS + 1):
            # Rounds of restitution below 1 shrink the approach geometrically and stop below the
            # rounding band; elastic ones end after finitely many (π √(M/m) for a heavy block
            # pushing a light one into a wall). Taking the rest together inelastically, as after
            # 1,000 rounds before, lost all the energy of that block at M = 10⁶ m.
            if round_ == _MAX_IMPACT_ROUNDS or (round_ % 256 == 255 and self._deadline is not None
                                                and time.monotonic() > self._deadline):
                names = ", ".join(self.effects[j].name for j in struck)
                raise SimulationError(f"at t = {t:.9g} the contacts ({names}) were still striking one another "
                                      f"after {round_} impacts at that instant")
            v, held, bounced, sliding = self._impact_round(t, q, v, rigid, held, struck, v_tol)
            rigid -= sliding
            slipped |= sliding
            hit |= set(struck)
            rates = self.compiled.rates(t, q, v)
            struck = sorted(j for j in touching - held if rates[j] < -v_tol[j])
            if not struck:
                break
        # Every contact that touches and does not move off holds (settle then releases it if it
        # carries no load): a big ball left at rest on the floor by the small one's rebound.
        rates = self.compiled.rates(t, q, v)
        resting = {j for j in touching if rates[j] <= v_tol[j]}
        return v, held | resting, hit, slipped

    def _impact_round(self, t, q, v, rigid: set[int], held: set[int], struck: list[int], v_tol
                      ) -> tuple[np.ndarray, set[int], set[int], set[int]]:
        """One round of :meth:`_impacts`: (q̇ after, contacts held, struck contacts that bounced,
        rolling constraints that slip).

        Friction at the contacts that take an impulse follows Coulomb's law for impulses: a
        rolling constraint whose normal contact is in the round sticks through it if the friction
        impulse that needs stays within μ_s times the normal impulse, else it takes μ_k times the
        normal impulse, against the slip it would otherwise stop. Before, a rolling constraint
        that rolled was held rigid (a ball rolling into a smooth wall had its spin reversed by a
        friction impulse from a floor that took no impulse at all, and rolled back at e v instead
        of (2 − 5e) v/7), and one that did not roll took no impulse (a spinning ball landing on
        a rough floor bounced with its spin unchanged)."""
        rates = self.compiled.rates(t, q, v)
        bounced = set()
        targets = {}
        for j in struck:
            bounce = -self.effects[j].restitution * rates[j]
            if bounce > v_tol[j]:
                bounced.add(j)
            targets[j] = bounce if j in bounced else 0.0
        M, _, J, _ = self.compiled.terms(t, q, v)
        contacts = rigid | held | set(struck)
        rough = {e.index for e in self.effects if e.kind == "rolling" and e.normal in contacts}
        let_go: set[int] = set()
        saturated: dict[int, float] = {}   # rolling index -> sign of its friction impulse
        while True:
            rows = sorted((contacts | rough) - let_go - set(saturated))
            if not rows:
                return v, set(), set(), rough & rigid
            # M Δq̇ = J_rowsᵀ P + Σ J_rᵀ σ μ_k P_normal for the saturated frictions
            B = J[rows].T.copy()
            for r, sign in saturated.items():
                effect = self.effects[r]
                if effect.normal in rows:
                    B[:, rows.index(effect.normal)] += sign * effect.mu_k * J[r]
            target = np.array([targets.get(r, 0.0) for r in rows])
            change, impulse = _impulse(M, B, J[rows], target - rates[rows])
            band = 1e-9 * np.abs(impulse).max(initial=0.0)
            pulling = [(impulse[k], r) for k, r in enumerate(rows)
                       if self.effects[r].kind == "unilateral" and impulse[k] < -band]
            if pulling:
                let_go.add(min(pulling)[1])
                continue
            sliding = []
            for k, r in enumerate(rows):
                effect = self.effects[r]
                if effect.kind == "rolling":
                    normal = impulse[rows.index(effect.normal)] if effect.normal in rows else 0.0
                    excess = abs(impulse[k]) - effect.mu_s * max(normal, 0.0)
                    if excess > band:
                        sliding.append((excess, r, 1.0 if impulse[k] > 0 else -1.0))
            if not sliding:
                break
            _, r, sign = max(sliding)
            saturated[r] = sign
        held = (held | (set(struck) - bounced)) - let_go
        return v + change, held, bounced - let_go, (let_go | set(saturated)) & rigid

    def transition(self, t: float, y: np.ndarray, mode: Mode, effect: str, i: int
                   ) -> tuple[Mode, np.ndarray, list[tuple[str, int]]]:
        """Apply one event and settle into the next consistent mode."""
        mode = mode.copy()
        switches: list[tuple[str, int]] = []
        if effect == "release":
            mode.active.discard(i)
            switches.append(("release", i, False))
        elif effect == "slip":
            _, lam, _, _ = self.solve(t, y, mode)
            mode.active.discard(i)
            mode.slipping[i] = -1.0 if lam[i] > 0 else 1.0
            switches.append(("slip", i, False))
        elif effect == "stick":
            f, _ = self.compiled.gaps(t, y[:self.n])
            mode.slipping.pop(i, None)
            mode.active.add(i)
            mode.offsets[i] = float(f[i])
            trial, later = self.settle(t, self.project(t, y, mode), mode)
            if i in trial.active:
                y = self.project(t, y, mode)
                switches.append(("stick", i, False))
            return trial, y, switches + later
        elif effect == "contact":
            q, v = y[:self.n], y[self.n:]
            f, rates, f_tol, v_tol, _ = self._scales(t, y)
            # Every open contact that touches and moves in at this instant is struck together
            # with i (a rod falling flat lands on both ends at once), each by its own restitution;
            # one after the other, a symmetric rod with 0 < e < 1 was set spinning.
            struck = [i] + [e.index for e in self.effects
                            if e.kind == "unilateral" and e.index != i and e.index not in mode.active
                            and abs(f[e.index]) <= f_tol[e.index] and rates[e.index] < -v_tol[e.index]]
            before = set(mode.active)
            v, holding, hit, slipped = self._impacts(t, q, v, mode, struck)
            unilateral = [e.index for e in self.effects if e.kind == "unilateral"]
            for j in [i] + [j for j in unilateral if j != i]:
                if j in hit:
                    switches.append(("contact" if j in holding else "bounce", j, False))
                elif j in before and j not in holding:
                    switches.append(("release", j, False))
            mode.active = (mode.active - set(unilateral) - slipped) | holding
            switches += [("slip", r, False) for r in sorted(slipped)]
            y = np.concatenate([q, v])
        mode, later = self.settle(t, self.project(t, y, mode), mode)
        return mode, self.project(t, y, mode), switches + later

    # -- integration ------------------------------------------------------------------------------
    def run(self, t0: float, q0, qdot0, t_end: float, sample_times: Sequence[float] = (), *,
            project_every: float | None = None, max_events: int = _MAX_EVENTS,
            budget_s: float | None = None) -> Trajectory:
        """Integrate from (t0, q0, q̇0) to t_end; samples at ``sample_times`` (within [t0, t_end]).

        ``project_every`` (s): also put the state back onto the constraints that hold at these
        intervals; the constraints enter only through the accelerations, so over long runs f
        and ḟ drift with the integration error unless projected. ``budget_s``: give up with a
        :class:`SimulationError` after this much computing time (checked every 256 evaluations).

        Raises
        ------
        SimulationError
            Integrator failure, endless events, or the budget spent.
        SingularDynamics
            Equations of motion that cannot be solved, or that are not finite (a square root of
            a negative number, a division by zero), at some state.
        """
        self._deadline = None if budget_s is None else time.monotonic() + budget_s
        # A scene's expressions may divide by zero or leave their domain at some state; the
        # result is then not finite and reported by kkt_solve, not as a numpy warning.
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            return self._run(t0, q0, qdot0, t_end, sample_times, project_every, max_events)

    def _run(self, t0, q0, qdot0, t_end, sample_times, project_every, max_events) -> Trajectory:
        y = np.concatenate([np.asarray(q0, float), np.asarray(qdot0, float)])
        wanted = np.array(sorted(float(s) for s in sample_times))
        stops = [float(x) for x in np.arange(t0 + project_every, t_end, project_every)] if project_every else []
        stops.append(float(t_end))
        events: list[EventRecord] = []
        rows: list[tuple] = []
        if not self.switching:
            # No effect declared: the plain compiled right-hand side, no event function.
            mode, t = Mode(set(range(self.m))), float(t0)
            for stop in stops:
                solution = self._integrate(self.compiled.rhs, t, stop, y, [])
                self._sample(solution, mode, self._inside(wanted, t, stop, rows), rows)
                t, y = stop, self.project(stop, solution.y[:, -1], mode) if project_every else solution.y[:, -1]
            return self._trajectory(rows, events)

        mode, y, switches = self.initial_mode(t0, y)
        y = self.project(t0, y, mode)
        # A force that is exactly zero at the start (a restart at an event) switches by the sign of
        # its derivative: that is the event already reported, not a new one.
        events += self._records(t0, y, [s for s in switches if not s[2]])
        t, done = float(t0), 0
        while t < t_end:
            stop = next(x for x in stops if x > t)
            evaluator = _Evaluator(self, mode)
            functions = self.event_functions(mode, evaluator, t, y)
            guarded = [guard_start(g, t, y) for g, _, _ in functions]
            solution = self._integrate(evaluator.rhs, t, stop, y, guarded)
            hits = [(hit[0], k) for k, hit in enumerate(solution.t_events or []) if len(hit)]
            missed = self._within_steps(solution, guarded)
            if missed is not None and (not hits or missed[0] < min(hits)[0]):
                hits = [missed]
            self._sample(solution, mode, self._inside(wanted, t, min(hits)[0] if hits else solution.t[-1], rows), rows)
            if not hits:
                t, y = stop, self.project(stop, solution.y[:, -1], mode)
                continue
            t_hit, k = min(hits)
            g, effect, i = functions[k]
            # A release counts once λ is below the band, a contact once the gap is; they happen
            # where λ = 0 and the gap = 0. Located on the threshold (the gap at −1e-13), a bounce
            # restarted there and the gap's rounding fired it again at once (a bead on a stop).
            level = lambda tt, yy, g=g: g(tt, yy) - g.band  # noqa: E731
            t_root = t_hit
            t_hit, y_hit = self._refine(level, t_hit, solution.sol(t_hit), mode, t)
            if level(t_hit, y_hit) < -g.band / 2 and level(t_root, solution.sol(t_root)) < 0:
                # Too slow an approach for Newton's steps (a ball rolling into a wall at 1e-8 m/s
                # reaches the band 1e-5 s after the gap's zero): the zero on the dense output, or
                # the segment's start if it began there. Left on the threshold, the bounce fired
                # again at once, thousands of times.
                start = level(t, solution.sol(t))
                t_hit = t if start <= 0 else brentq(lambda tt: level(tt, solution.sol(tt)), t, t_root,
                                                    xtol=1e-15, rtol=4 * np.finfo(float).eps)
                y_hit = solution.sol(t_hit)
            mode, y, switches = self.transition(t_hit, self.project(t_hit, y_hit, mode), mode, effect, i)
            events += self._records(t_hit, y, switches)
            done += 1
            if done > max_events:
                raise SimulationError(f"more than {max_events} events by t = {t_hit:.9g} (chattering contact?)")
            t = t_hit
        return self._trajectory(rows, events)

    def _noise_scales(self, t: float, y: np.ndarray, mode: Mode):
        """What counts as zero for a force, a gap and a rate at a mode decision (as in :meth:`settle`)."""
        _, _, f_tol, v_tol, norms = self._scales(t, y)
        _, lam, _, F = self.solve(t, y, mode)
        return _TOL * (np.linalg.norm(F) + np.abs(lam).max(initial=0.0)) / norms, f_tol, v_tol

    @staticmethod
    def _within_steps(solution, guarded) -> tuple[float, int] | None:
        """The first crossing scipy missed: it tests event functions only at the ends of its steps,
        so a force that dips below zero and recovers within one step (the tension of a bob
        whirled just below the critical speed, negative for a few ms about the top) kept its
        contact. Each function is also evaluated at three points inside every step; a sign change
        between them, or a minimum among them that the dense output puts below zero, is a
        crossing, located with brentq (the functions carry their rounding band, see
        :meth:`event_functions`). Returns (t, index of the function) or None."""
        if not guarded or len(solution.t) < 2:
            return None
        ts = solution.t
        points = np.concatenate([(ts[:-1, None] + np.diff(ts)[:, None] * _SCAN).ravel(), ts[-1:]])
        states = solution.sol(points)
        # Point by point, all functions: the release functions of one point share one KKT solve.
        table = np.array([[-g.direction * g(tt, states[:, j]) for g in guarded] for j, tt in enumerate(points)])
        found = None
        for k, g in enumerate(guarded):
            away = -g.direction

            def h(tt, g=g, away=away):
                return away * g(tt, solution.sol(tt))

            values = table[:, k]
            for j in range(1, len(points)):
                if found is not None and points[j - 1] >= found[0]:
                    break
                root = None
                if values[j] < 0 <= values[j - 1]:
                    root = points[j - 1] if values[j - 1] == 0 else brentq(h, points[j - 1], points[j], xtol=1e-15,
                                                                          rtol=4 * np.finfo(float).eps)
                elif (j + 1 < len(points) and 0 < values[j] <= min(values[j - 1], values[j + 1])
                      and values[j] <= max(values[j - 1], values[j + 1]) - values[j]):
                    # A quadratic through three such samples has its minimum at most 1/4 of that
                    # rise below the middle one: only these minima can reach zero.
                    low = minimize_scalar(h, bounds=(points[j - 1], points[j + 1]), method="bounded",
                                          options={"xatol": 1e-14 * max(1.0, abs(points[j]))})
                    if low.fun < 0:
                        root = brentq(h, points[j - 1], low.x, xtol=1e-15, rtol=4 * np.finfo(float).eps)
                if root is not None:
                    if found is None or root < found[0]:
                        found = (float(root), k)
                    break
        return found

    @staticmethod
    def _inside(wanted: np.ndarray, start: float, stop: float, rows: list) -> np.ndarray:
        """The sample times in this segment not sampled by an earlier one."""
        after = wanted > rows[-1][0] if rows else wanted >= start
        return wanted[after & (wanted <= stop)]

    def _integrate(self, rhs, t0, t_end, y, events):
        if self._deadline is not None:
            rhs = within_budget(rhs, self._deadline)
        try:
            solution = solve_ivp(rhs, (t0, t_end), y, method="DOP853", rtol=self.rtol, atol=self.atol,
                                 events=events or None, dense_output=True)
        except np.linalg.LinAlgError as exc:  # pragma: no cover - kkt_solve turns these into errors
            raise SimulationError(str(exc)) from None
        if solution.status == -1:
            raise SimulationError(f"integration failed at t = {solution.t[-1]:.9g}: {solution.message}")
        return solution

    def _refine(self, g, t_hit: float, y_hit: np.ndarray, mode: Mode, start: float) -> tuple[float, np.ndarray]:
        """Newton steps along the flow from scipy's root on the dense output, each a second-order
        Taylor step of the true right-hand side, never back before the segment's ``start`` nor
        more than 10 µs from scipy's root (one Euler step went back before it, and left the root
        off by a·dt²/2: the slow rebounds of a bead bouncing on a stop, struck that far inside
        it, gained energy at every bounce and never ended)."""
        t, y = t_hit, y_hit
        for _ in range(4):
            value = g(t, y)
            slope = self._flow_derivative(g, t, y, mode)
            if not (slope and np.isfinite(slope)):
                break
            dt = -value / slope
            if not (abs(t + dt - t_hit) < 1e-5 and t + dt > start):
                break
            qddot = self.solve(t, y, mode)[0]
            v = y[self.n:]
            y = np.concatenate([y[:self.n] + dt * v + dt * dt / 2 * qddot, v + dt * qddot])
            t += dt
            if abs(dt) <= 4 * np.finfo(float).eps * max(1.0, abs(t)):
                break
        return t, y

    def _sample(self, solution, mode: Mode, times: np.ndarray, rows: list) -> None:
        if not len(times):
            return
        states = solution.sol(times)
        active = np.array([i in mode.active for i in range(self.m)], dtype=bool)
        for k, t in enumerate(times):
            y = states[:, k]
            _, lam, J, _ = self.solve(t, y, mode)
            rows.append((float(t), y[:self.n], y[self.n:], lam, lam[:, None] * J, active))

    def _records(self, t: float, y: np.ndarray, switches) -> list[EventRecord]:
        state = {}
        for j, name in enumerate(self.compiled.coordinates):
            state[name] = float(y[j])
            state[f"{name}dot"] = float(y[self.n + j])
        return [EventRecord(float(t), s[0], self.effects[s[1]].name, dict(state)) for s in switches]

    def _trajectory(self, rows, events) -> Trajectory:
        n, m = self.n, self.m
        if rows:
            t, q, v, lam, Q, active = (np.array(x) for x in zip(*rows))
        else:
            t, q, v = np.zeros(0), np.zeros((0, n)), np.zeros((0, n))
            lam, Q, active = np.zeros((0, m)), np.zeros((0, m, n)), np.zeros((0, m), dtype=bool)
        k = len(t)
        return Trajectory(self.compiled.coordinates, self.compiled.constraints, t, q, v,
                          lam.reshape(k, m), Q.reshape(k, m, n), active.reshape(k, m), events)


def _impulse(M: np.ndarray, B: np.ndarray, J: np.ndarray, change: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(Δq̇, P) with M Δq̇ = B P and J Δq̇ = ``change``, solved together: M alone may be singular
    (a massless pulley's coordinate, held by its strings), which made ``solve(M, ...)`` raise
    numpy's bare "Singular matrix" when such a scene's start was put on its constraints."""
    n, k = B.shape
    K = np.zeros((n + k, n + k))
    K[:n, :n], K[:n, n:], K[n:, :n] = M, -B, J
    rhs = np.concatenate([np.zeros(n), change])
    try:
        x = np.linalg.solve(K, rhs)
    except np.linalg.LinAlgError:
        x = np.linalg.lstsq(K, rhs, rcond=None)[0]
    return x[:n], x[n:]


def simulate_scene(scene, overrides: Mapping[str, float] | None = None, *, t_end: float,
                   samples: int = 201, initial: Mapping[str, float] | None = None,
                   rtol: float = 1e-11, atol: float | None = None,
                   project_every: float | None = None, budget_s: float | None = None) -> Trajectory:
    """Simulate a scene from its ``[initial]`` state with its declared effects.

    Parameters
    ----------
    scene : grader.mechanics.scene.Scene
    overrides : mapping of str to float
        Parameter values that replace the file's ``value`` (``--set``).
    t_end : float
        End time (> 0).
    samples : int
        Evenly spaced samples over [0, t_end].
    initial : mapping of str to float, optional
        Replaces ``[initial]`` entries (coordinates or velocities, or the parametrization's).
    rtol, atol : float
        DOP853 tolerances. The default ``atol`` is 1e-12 times the smallest nonzero initial
        coordinate or velocity (at most 1e-12), so that a motion of amplitude 1e-8 is resolved
        to the same relative accuracy as one of amplitude 1.
    project_every, budget_s : float, optional
        See :meth:`Simulation.run`.
    """
    import sympy

    if not t_end > 0:
        raise ValueError(f"t-end must be a positive number of seconds, not {t_end}")
    if initial:
        scene = _with_initial(scene, {k: sympy.Float(v, 17) for k, v in initial.items()})
    compiled = CompiledScene(scene, parameter_values(scene, overrides))
    q0, qdot0 = initial_state(scene, compiled)
    if atol is None:
        sizes = np.abs(np.concatenate([q0, qdot0]))
        atol = 1e-12 * min(1.0, max(sizes[sizes > 0].min(initial=1.0), 1e-200))
    simulation = Simulation(compiled, declared_effects(scene, compiled.values), rtol=rtol, atol=atol)
    return simulation.run(0.0, q0, qdot0, t_end, np.linspace(0.0, t_end, max(samples, 2)),
                          project_every=project_every, budget_s=budget_s)


def _with_initial(scene, initial):
    import dataclasses

    return dataclasses.replace(scene, initial={**scene.initial, **initial})
