"""A scene file as numbers: numeric callables for the integrator and every named quantity.

This adapter is what keeps the numerical experiment independent of the symbolic engine. From a
:class:`~grader.mechanics.scene.Scene` it takes only the instructor's own input, as the scene
loader parsed it: the energies T and V, the constraint functions f, the parametrization's map,
the ``[initial]`` values and the answers' defining expressions. Those are turned into plain
functions with ``sympy.lambdify(..., modules="mpmath")``; nothing here calls
:mod:`grader.mechanics.lagrange` (or the modules it uses), and nothing differentiates or solves
symbolically. Every derivative is taken numerically by :mod:`grader.simulate.lagrangian_numeric`.

Names are the scene's own: ``theta``, ``thetadot``, ``thetaddot``, ``lambda_<constraint>``,
``Q_<constraint>_<coordinate>``, ``t``, the parameters, and the variables of a
``[parametrization]`` (recovered from the scene coordinates numerically, see
:class:`SceneModel.quantities`).

Examples
--------
The yo-yo: a cylinder of mass 0.25 unwinding from a string (f = R θ - s). The string tension
``-Q_unwind_s`` of the file's answer is m g / 3 at the start.

>>> from grader.mechanics.scene import parse_scene
>>> scene = parse_scene('''
... id = "yoyo"
... [parameters]
... m = { dimension = "mass", domain = "positive", value = 0.25 }
... g = { dimension = "acceleration", domain = "positive", value = 9.81 }
... R = { dimension = "length", domain = "positive", value = 0.03 }
... [coordinates]
... s = { dimension = "length" }
... theta = { dimension = "angle" }
... [energy]
... kinetic = "m/2*sdot^2 + m*R^2/4*thetadot^2"
... potential = "-m*g*s"
... [[constraints]]
... name = "unwind"
... f = "R*theta - s"
... [[answers]]
... name = "tension"
... expr = "-Q_unwind_s"
... ''')
>>> model = SceneModel(scene)
>>> start = model.initial_state()
>>> state = snapshot(model.numeric, start.t, start.q, start.qdot)
>>> round(model.evaluate(scene.answer("tension").expr, model.quantities(state)), 12)
0.8175
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Mapping

import mpmath
import numpy as np
import sympy

from grader.simulate.lagrangian_numeric import (
    NumericConstraint,
    NumericScene,
    Snapshot,
    function_terms,
    snapshot,
)
from grader.simulate.manifold import ConstraintViolation, project_positions, project_velocities

__all__ = ["InitialState", "SceneModel", "numeric_scene", "parameter_values"]

_EVAL_DPS = 30


def parameter_values(scene, fallback: Mapping[str, float] | None = None) -> dict[str, float]:
    """Each parameter's ``value`` from the scene file, else from ``fallback``.

    Raises
    ------
    KeyError
        For a parameter with neither.
    """
    fallback = fallback or {}
    values = {}
    for name, parameter in scene.parameters.items():
        value = parameter.value if parameter.value is not None else fallback.get(name)
        if value is None:
            raise KeyError(f"{scene.source}: parameter '{name}' has no value; pass one")
        values[name] = float(value)
    return values


def _lambdify(symbols: list[sympy.Symbol], expr: sympy.Expr) -> Callable:
    # The expression was built by our whitelist parser from a validated scene (never from raw
    # text), so compiling lambdify's generated code is safe.
    return sympy.lambdify(symbols, expr, modules="mpmath")


def numeric_scene(scene, values: Mapping[str, float], *, dps: int = 40) -> NumericScene:
    """T(q, q̇, t), V(q, t) and the constraints of a scene as mpmath callables.

    Parameters
    ----------
    scene : grader.mechanics.scene.Scene
    values : mapping of str to float
        A number for every parameter (see :func:`parameter_values`).
    dps : int
        Working precision of the numerical derivatives.
    """
    coordinates = list(scene.coordinates.values())
    q = [c.symbol for c in coordinates]
    qdot = [c.dot for c in coordinates]
    names = list(scene.parameters)
    p = [scene.parameters[n].symbol for n in names]
    # Exact binary values of the floats; the precision of the arithmetic is set by the caller.
    pv = [mpmath.mpf(values[n]) for n in names]

    kinetic = _lambdify(q + qdot + [scene.time] + p, scene.kinetic)
    potential = _lambdify(q + [scene.time] + p, scene.potential)
    constraints = []
    for c in scene.constraints:
        f = _lambdify(q + [scene.time] + p, c.f)
        constraints.append(NumericConstraint(c.name, lambda qq, t, f=f: f(*qq, t, *pv), c.kind == "unilateral"))
    return NumericScene(
        coordinates=tuple(c.name for c in coordinates),
        kinetic=lambda qq, vv, t: kinetic(*qq, *vv, t, *pv),
        potential=lambda qq, t: potential(*qq, t, *pv),
        constraints=tuple(constraints),
        dps=dps,
    )


@dataclass(frozen=True)
class InitialState:
    """A consistent initial state and, if one was needed, the push that set it moving.

    Attributes
    ----------
    t, q, qdot : start time, coordinates and velocities (on the constraint manifold)
    pushed : name of the velocity that was given ``push`` because [initial] is an equilibrium
        at rest (e.g. ``"thetadot"`` on top of the sphere), else None
    push : its value
    """

    t: float
    q: np.ndarray
    qdot: np.ndarray
    pushed: str | None = None
    push: float = 0.0


class _Parametrization:
    """The map q = Φ(u, t) of a ``[parametrization]``, forwards and (numerically) backwards."""

    def __init__(self, scene, values: Mapping[str, float], dps: int):
        self.variables = list(scene.parametrization.variables.values())
        u = [v.symbol for v in self.variables]
        names = list(scene.parameters)
        p = [scene.parameters[n].symbol for n in names]
        pv = [mpmath.mpf(values[n]) for n in names]
        self.dps = dps
        self.maps = []
        for c in scene.coordinates.values():
            f = _lambdify(u + [scene.time] + p, scene.parametrization.mapping[c.symbol])
            self.maps.append(lambda uu, t, f=f: f(*uu, t, *pv))
        self.names = [f"parametrization.map.{c}" for c in scene.coordinates]

    def forward(self, t: float, u, udot) -> tuple[np.ndarray, np.ndarray]:
        terms = function_terms(self.maps, t, u, dps=self.dps, names=self.names)
        return terms.value, terms.jacobian @ np.asarray(udot, dtype=float) + terms.rate

    def inverse(self, s: Snapshot, guess: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """u, u̇, ü with Φ(u, t) = q, by Gauss–Newton from ``guess`` (follow the motion with it)."""
        u = np.array(guess, dtype=float)
        for _ in range(50):
            terms = function_terms(self.maps, s.t, u, dps=self.dps, names=self.names)
            step, *_ = np.linalg.lstsq(terms.jacobian, s.q - terms.value, rcond=None)
            u += step
            if np.all(np.abs(step) <= 1e-15 * (1 + np.abs(u))):
                break
        terms = function_terms(self.maps, s.t, u, dps=self.dps, names=self.names)
        misfit = np.abs(s.q - terms.value)
        if np.any(misfit > 1e-9 * (1 + np.abs(s.q))):
            raise ConstraintViolation(f"the state q = {s.q.tolist()} is not on the parametrization's map "
                                      f"(closest u = {u.tolist()})")
        D = terms.jacobian
        udot, *_ = np.linalg.lstsq(D, s.qdot - terms.rate, rcond=None)
        # q̈ = D ü + b(u, u̇, t): the same directional second difference as a constraint's bias.
        b = function_terms(self.maps, s.t, u, udot, dps=self.dps, names=self.names).bias
        uddot, *_ = np.linalg.lstsq(D, s.qddot - b, rcond=None)
        return u, udot, uddot


class SceneModel:
    """A scene with numbers: the integrator's callables and the scene's quantities by name.

    Parameters
    ----------
    scene : grader.mechanics.scene.Scene
    fallback : mapping of str to float, optional
        Values for parameters whose scene entry has no ``value``.
    dps : int
        Working precision of the numerical derivatives.

    Attributes
    ----------
    scene, values, numeric : the scene, its parameter values and its :class:`NumericScene`
    """

    def __init__(self, scene, fallback: Mapping[str, float] | None = None, *, dps: int = 40):
        self.scene = scene
        self.values = parameter_values(scene, fallback)
        self.numeric = numeric_scene(scene, self.values, dps=dps)
        self._parametrization = _Parametrization(scene, self.values, dps) if scene.parametrization else None
        self._u_guess: np.ndarray | None = None
        self._compiled: dict[sympy.Expr, tuple[list[str], Callable]] = {}

    # -- initial state --------------------------------------------------------------------------
    def initial_value(self, name: str) -> float | None:
        """An ``[initial]`` entry as a number (its expression may use parameters)."""
        expr = self.scene.initial.get(name)
        return None if expr is None else self.evaluate(expr, {})

    def initial_state(self, *, t0: float = 0.0, push: float = 0.0) -> InitialState:
        """The [initial] state completed to a consistent one (unnamed values are solved for).

        Coordinates and velocities that [initial] leaves out start at 0 unless the constraints
        fix them. If the state is an equilibrium at rest (q̇ = 0 and q̈ = 0, e.g. the top of a
        sphere) and ``push`` is nonzero, the first independent velocity that [initial] names is
        set to ``push`` so that the motion starts; its effect on energy-based closed forms is
        of order ``push²``. The push is positive, the direction the engine assumes too.
        """
        if self._parametrization is not None:
            q, qdot, velocity_names = self._initial_from_parametrization(t0, push=0.0)
        else:
            q, qdot, velocity_names = self._initial_from_coordinates(t0, push=0.0)
        if push and not np.any(qdot) and np.all(np.abs(snapshot(self.numeric, t0, q, qdot).qddot) < 1e-10):
            for name in velocity_names:
                try:
                    if self._parametrization is not None:
                        q, qdot, _ = self._initial_from_parametrization(t0, push=push, pushed=name)
                    else:
                        q, qdot, _ = self._initial_from_coordinates(t0, push=push, pushed=name)
                except ConstraintViolation:
                    continue  # this velocity is fixed by the constraints; try the next
                return InitialState(t0, q, qdot, name, push)
        return InitialState(t0, q, qdot)

    def _initial_from_parametrization(self, t0: float, push: float, pushed: str | None = None):
        variables = self._parametrization.variables
        missing = [v.name for v in variables if v.name not in self.scene.initial]
        if missing:
            raise ConstraintViolation(f"{self.scene.source}: [initial] gives no value for {', '.join(missing)}")
        u = np.array([self.initial_value(v.name) for v in variables])
        udot = np.array([self.initial_value(v.dot.name) or 0.0 for v in variables])
        for i, v in enumerate(variables):
            if v.dot.name == pushed:
                udot[i] = push
        self._u_guess = u
        q, qdot = self._parametrization.forward(t0, u, udot)
        named = [v.dot.name for v in variables if v.dot.name in self.scene.initial]
        return q, qdot, named + [v.dot.name for v in variables if v.dot.name not in named]

    def _initial_from_coordinates(self, t0: float, push: float, pushed: str | None = None):
        coordinates = list(self.scene.coordinates.values())
        given_q = [c.name in self.scene.initial for c in coordinates]
        given_v = [c.dot.name in self.scene.initial or c.dot.name == pushed for c in coordinates]
        q = np.array([self.initial_value(c.name) or 0.0 for c in coordinates])
        qdot = np.array([push if c.dot.name == pushed else (self.initial_value(c.dot.name) or 0.0)
                         for c in coordinates])
        q = project_positions(self.numeric, t0, q, free=[not g for g in given_q])
        qdot = project_velocities(self.numeric, t0, q, qdot, free=[not g for g in given_v])
        named = [c.dot.name for c in coordinates if c.dot.name in self.scene.initial]
        return q, qdot, named + [c.dot.name for c in coordinates if c.dot.name not in named]

    # -- quantities -----------------------------------------------------------------------------
    def quantities(self, s: Snapshot) -> dict[str, float]:
        """Every named quantity of the scene at a snapshot: parameters, t, q, q̇, q̈, λ, Q.

        With a [parametrization], its variables u, u̇, ü are recovered from q, q̇, q̈ by
        Gauss–Newton starting from the previous call's u (or [initial]): call this along the
        motion, in time order, so that angles stay on their branch.
        """
        scene = self.scene
        values: dict[str, float] = dict(self.values)
        values[scene.time.name] = s.t
        for i, c in enumerate(scene.coordinates.values()):
            values[c.name], values[c.dot.name], values[c.ddot.name] = s.q[i], s.qdot[i], s.qddot[i]
        for i, k in enumerate(scene.constraints):
            values[k.multiplier.name] = s.multipliers[i]
            for j, c in enumerate(scene.coordinates.values()):
                values[scene.forces[(k.name, c.name)].name] = s.forces[i, j]
        if self._parametrization is not None:
            variables = self._parametrization.variables
            guess = self._u_guess if self._u_guess is not None else np.zeros(len(variables))
            u, udot, uddot = self._parametrization.inverse(s, guess)
            self._u_guess = u
            for i, v in enumerate(variables):
                values[v.name], values[v.dot.name], values[v.ddot.name] = u[i], udot[i], uddot[i]
        return {name: float(value) for name, value in values.items()}

    def definition(self, expr: sympy.Expr) -> sympy.Expr:
        """``expr`` with each answer name replaced by that answer's defining expression."""
        by_symbol = {spec.symbol: spec.expr for spec in self.scene.answers}
        for _ in range(len(by_symbol) + 1):
            if not expr.free_symbols & by_symbol.keys():
                return expr
            expr = expr.xreplace(by_symbol)
        raise ValueError(f"{self.scene.source}: answers refer to each other in a cycle")

    def evaluate(self, expr: sympy.Expr, values: Mapping[str, float]) -> float:
        """A number from an expression over the scene's names (answer names allowed).

        Symbols are matched by name, so an expression built elsewhere with other assumptions
        on the same names (e.g. the engine's closed forms) evaluates the same way.

        Raises
        ------
        KeyError
            When the expression uses a name that ``values`` (and the parameters) do not give.
        """
        if expr not in self._compiled:
            expanded = self.definition(sympy.sympify(expr, strict=True))
            symbols = sorted(expanded.free_symbols, key=lambda s: s.name)
            self._compiled[expr] = ([s.name for s in symbols], _lambdify(symbols, expanded))
        names, function = self._compiled[expr]
        known = {**self.values, **values}
        missing = [n for n in names if n not in known]
        if missing:
            raise KeyError(f"no numeric value for {', '.join(missing)} in {expr}")
        with mpmath.workdps(_EVAL_DPS):
            value = function(*[mpmath.mpf(known[n]) for n in names])
            if isinstance(value, mpmath.mpc):
                if abs(value.imag) > 1e-20 * max(1, abs(value.real)):
                    raise ValueError(f"{expr} is complex ({value}) at this state")
                value = value.real
            return float(value)
