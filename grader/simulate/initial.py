"""A scene's ``[initial]`` state with numbers, completed by the constraints.

``[initial]`` may give some coordinates and velocities (numbers or expressions in the parameters),
or the variables of a ``[parametrization]``. Coordinates it leaves out are solved from the
constraints (all of them: a scene starts with its contacts closed unless it places the body off
them; when the coordinates left out cannot close every constraint they enter, they must be given),
velocities it leaves out from ḟ = 0; whatever is neither given nor fixed starts at 0. The
completed state must satisfy every bilateral and rolling constraint, and lie on the allowed side
(f ≥ 0) of every unilateral one; otherwise :class:`InitialStateError` says which constraint fails.

Examples
--------
>>> from grader.mechanics.scene import load_scene
>>> from grader.simulate.compiled import CompiledScene, parameter_values
>>> scene = load_scene("problems/sphere.toml")
>>> compiled = CompiledScene(scene, parameter_values(scene))
>>> q, qdot = initial_state(scene, compiled)
>>> q.tolist(), (qdot + 0.0).tolist()
([0.8, 0.0], [0.0, 0.0])
"""

from __future__ import annotations

import numpy as np
import sympy

__all__ = ["InitialStateError", "initial_state"]

_TOL = 1e-9


class InitialStateError(ValueError):
    """The ``[initial]`` state cannot be completed to one on the constraints."""


def _number(scene, expr: sympy.Expr, values: dict) -> float:
    value = complex(sympy.N(expr.xreplace(values), 17))
    if value.imag:
        raise InitialStateError(f"{scene.source}: initial value {expr} is not a real number")
    return value.real


def initial_state(scene, compiled, t0: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Coordinates and velocities at ``t0`` from ``[initial]`` (see the module docstring).

    Raises
    ------
    InitialStateError
        When a value is missing or the state is off the constraints.
    """
    values = {p.symbol: sympy.Float(compiled.values[name], 17) for name, p in scene.parameters.items()}
    values[scene.time] = sympy.Float(t0, 17)
    coordinates = list(scene.coordinates.values())
    n = len(coordinates)
    if scene.parametrization is not None:
        variables = list(scene.parametrization.variables.values())
        missing = [v.name for v in variables if v.name not in scene.initial]
        if missing:
            raise InitialStateError(f"{scene.source}: [initial] gives no value for {', '.join(missing)}")
        point = {v.symbol: sympy.Float(_number(scene, scene.initial[v.name], values), 17) for v in variables}
        point.update(values)
        rates = {v.symbol: _number(scene, scene.initial.get(v.dot.name, sympy.Integer(0)), values)
                 for v in variables}
        mapping = [scene.parametrization.mapping[c.symbol] for c in coordinates]
        q = np.array([_number(scene, e, point) for e in mapping])
        qdot = np.array([_number(scene, sum((sympy.diff(e, v.symbol) * rates[v.symbol] for v in variables),
                                            sympy.diff(e, scene.time)), point) for e in mapping])
        given_q = given_v = np.ones(n, dtype=bool)
    else:
        given_q = np.array([c.name in scene.initial for c in coordinates])
        given_v = np.array([c.dot.name in scene.initial for c in coordinates])
        q = np.array([_number(scene, scene.initial[c.name], values) if g else 0.0
                      for c, g in zip(coordinates, given_q)])
        qdot = np.array([_number(scene, scene.initial[c.dot.name], values) if g else 0.0
                         for c, g in zip(coordinates, given_v)])
        q = _solve_positions(compiled, t0, q, ~given_q)
        _check_solved(scene, compiled, t0, q, ~given_q)
    f, J = compiled.gaps(t0, q)
    closed = np.array([abs(v) <= _TOL * (1 + np.abs(Ji) @ np.abs(q)) for v, Ji in zip(f, J)], dtype=bool)
    if np.any(~given_v) and np.any(closed):
        qdot = _solve_velocities(compiled, t0, q, qdot, ~given_v, closed)
    _check(scene, compiled, t0, q, qdot)
    return q, qdot


def _solve_positions(compiled, t0: float, q: np.ndarray, free: np.ndarray) -> np.ndarray:
    if not compiled.m or not np.any(free):
        return q
    q = q.copy()
    for _ in range(60):
        f, J = compiled.gaps(t0, q)
        step, *_ = np.linalg.lstsq(J[:, free], -f, rcond=None)
        q[free] += step
        if np.all(np.abs(step) <= 1e-15 * (1 + np.abs(q[free]))):
            break
    return q


def _check_solved(scene, compiled, t0: float, q: np.ndarray, free: np.ndarray) -> None:
    """The coordinates left out must close every constraint they enter. Two contacts that cannot
    hold at once (a body on a sphere above a floor, with r left out) got a least-squares compromise
    on neither, refused as 'the wrong side of surface' without saying that r was the problem."""
    if not compiled.m or not np.any(free):
        return
    f, J = compiled.gaps(t0, q)
    involved = np.any(J[:, free] != 0, axis=1)
    open_ = [k.name for k, v, Ji, used in zip(scene.constraints, f, J, involved)
             if used and abs(v) > _TOL * (1 + np.abs(Ji) @ np.abs(q))]
    if open_:
        names = [c.name for c, left in zip(scene.coordinates.values(), free) if left]
        closing = [k.name for k, used in zip(scene.constraints, involved) if used]
        raise InitialStateError(
            f"{scene.source}: [initial] leaves out {', '.join(names)}, and no value of "
            f"{'it' if len(names) == 1 else 'them'} closes every constraint "
            f"{'it enters' if len(names) == 1 else 'they enter'} ({', '.join(closing)}) at once: "
            f"give {', '.join(names)} in [initial] (a contact may start open)")


def _solve_velocities(compiled, t0, q, qdot, free, closed) -> np.ndarray:
    qdot = qdot.copy()
    qdot[free] = 0.0
    _, J = compiled.gaps(t0, q)
    rates = compiled.rates(t0, q, qdot)  # the given velocities' share of ḟ, with ∂f/∂t
    step, *_ = np.linalg.lstsq(J[closed][:, free], -rates[closed], rcond=None)
    qdot[free] = step
    return qdot


def _check(scene, compiled, t0: float, q: np.ndarray, qdot: np.ndarray) -> None:
    f, J = compiled.gaps(t0, q)
    rates = compiled.rates(t0, q, qdot)
    for k, value, Ji, rate in zip(scene.constraints, f, J, rates):
        scale = 1 + np.abs(Ji) @ np.abs(q)
        if k.kind == "unilateral":
            if value < -_TOL * scale:
                raise InitialStateError(f"{scene.source}: the initial state is on the wrong side of constraint "
                                        f"'{k.name}' (f = {value:.6g} < 0)")
            continue
        if abs(value) > _TOL * scale:
            raise InitialStateError(f"{scene.source}: the initial state is off constraint '{k.name}' "
                                    f"(f = {value:.6g}, not 0)")
        if k.kind == "bilateral" and abs(rate) > _TOL * (1 + np.abs(Ji) @ np.abs(qdot)):
            raise InitialStateError(f"{scene.source}: the initial velocities break constraint '{k.name}' "
                                    f"(its rate is {rate:.6g}, not 0)")
