"""The motion from ``[initial]`` in closed form, q(t), when its equations are linear.

Most motions have no closed form, but the first examples of a course do: a block sliding down an
incline (s̈ = g sin α, so s = s₀ + v₀t + g sin α t²/2), a bead on a rod rotating at constant ω
(r̈ = ω²r, so r = r₀ cosh ωt from rest), a mass on a spring on a driven support. When every
solved acceleration is linear in the independent coordinates and velocities (with coefficients
and forcing in the parameters and t), the engine integrates them with ``sympy.dsolve`` from the
``[initial]`` state at t = 0, under a CPU-time budget. An answer may then be a value as a function
of time (``in_terms_of = [..., "t"]`` without the coordinate) or the time at which a condition
holds (``expr = "t"``, ``where = "r = L"``; see :mod:`grader.mechanics.special_values`).

Examples
--------
>>> from grader.mechanics.lagrange import derive
>>> from grader.mechanics.scene import load_scene
>>> derive(load_scene("tests/mechanics/scenes/bead_rotating_rod.toml")).answers["radius_in_time"]
r0*cosh(omega*t)
"""

from __future__ import annotations

import sympy
from sympy.simplify.simplify import exptrigsimp

from grader.mechanics import budget
from grader.mechanics.scene import SceneError
from grader.mechanics.simplification import human_form

__all__ = ["motion_in_time"]

_DSOLVE_BUDGET_S = 4.0


def motion_in_time(evaluator, key: str) -> dict[sympy.Symbol, sympy.Expr]:
    """``{u: u(t), u̇: u̇(t)}`` for every independent coordinate (computed once per scene).

    Raises :class:`SceneError` naming what stops it: an acceleration that is not linear in the
    state, a coordinate or velocity that ``[initial]`` does not give, or a system ``dsolve``
    cannot integrate within its budget.
    """
    cache = evaluator.__dict__.setdefault("_motion_cache", {})
    if "motion" not in cache:
        try:
            cache["motion"] = _integrate(evaluator)
        except SceneError as exc:
            cache["motion"] = exc
    result = cache["motion"]
    if isinstance(result, SceneError):
        raise SceneError(evaluator.scene.source, key, result.problem)
    return result


def _integrate(evaluator) -> dict[sympy.Symbol, sympy.Expr]:
    scene = evaluator.scene
    reduction = evaluator.reduction
    t = scene.time
    independent = list(reduction.independent.values())
    state = [s for u in independent for s in (u.symbol, u.dot)]
    functions = {u.name: sympy.Function(u.name)(t) for u in independent}
    to_functions = {}
    for u in independent:
        to_functions[u.symbol] = functions[u.name]
        to_functions[u.dot] = functions[u.name].diff(t)
    equations = []
    for u in independent:
        acceleration = reduction.accelerations[u.ddot]
        if not _linear(acceleration, state):
            raise SceneError(scene.source, "", f"the motion has no closed form in t here: {u.ddot.name} is not "
                                               "linear in the coordinates and velocities")
        equations.append(sympy.Eq(functions[u.name].diff(t, 2), acceleration.xreplace(to_functions)))
    initial = {}
    for u in independent:
        for symbol, condition in ((u.symbol, functions[u.name].subs(t, 0)),
                                  (u.dot, functions[u.name].diff(t).subs(t, 0))):
            value = reduction.initial_value(symbol)
            if value is None:
                raise SceneError(scene.source, "", f"the motion in time needs [initial] values for "
                                                   f"{', '.join(str(s) for s in state)}")
            initial[condition] = value

    def solve():
        if len(equations) == 1:
            return [sympy.dsolve(equations[0], functions[independent[0].name], ics=initial)]
        return sympy.dsolve(equations, list(functions.values()), ics=initial)

    def attempt():
        try:
            return solve()
        except (NotImplementedError, ValueError, TypeError):
            return None

    with budget.step("integrating the motion in time"):
        solutions = budget.attempt(attempt, _DSOLVE_BUDGET_S, fallback=lambda: None)
    if not solutions:
        raise SceneError(scene.source, "", "the motion has no closed form in t that sympy finds within "
                                           f"{_DSOLVE_BUDGET_S:g} s")
    by_function = {s.lhs: s.rhs for s in solutions}
    motion = {}
    for u in independent:
        q = _readable(by_function[functions[u.name]])
        motion[u.symbol] = q
        motion[u.dot] = _readable(sympy.diff(q, t))
    return motion


def _linear(expr: sympy.Expr, state: list[sympy.Symbol]) -> bool:
    """Whether expr is a polynomial of degree at most one in the state variables."""
    present = [s for s in state if s in expr.free_symbols]
    if not present:
        return True
    try:
        return sympy.Poly(sympy.expand(expr), *present).total_degree() <= 1
    except sympy.PolynomialError:
        return False


def _readable(expr: sympy.Expr) -> sympy.Expr:
    """r₀ cosh ωt rather than r₀ e^{ωt}/2 + r₀ e^{−ωt}/2."""
    candidates = [human_form(expr)]
    if expr.has(sympy.exp):
        candidates.append(human_form(exptrigsimp(expr)))
        # exp(ωt) = cosh ωt + sinh ωt; simplify then gathers r₀ (e^{ωt} + e^{−ωt})/2 into r₀ cosh ωt.
        budget.attempt(lambda: candidates.append(sympy.simplify(sympy.expand(expr.rewrite(sympy.cosh)))),
                       1.0, fallback=lambda: None)
    return min(candidates, key=lambda e: (sympy.count_ops(e), len(str(e))))
