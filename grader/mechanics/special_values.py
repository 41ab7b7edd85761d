"""Special values: an answer at the configuration where a condition holds.

``where = "normal_force = 0"`` asks for the configuration u* where the body leaves the sphere. The
condition, after the engine has expressed it in one independent coordinate u (velocities removed
with energy conservation), may have many roots (cos θ = 2/3 holds at ±48.19° and again after a
turn); the one asked for is the first that the motion from ``[initial]`` reaches. So we follow the
motion numerically: scan from u0 in the direction it moves (that of u̇0, else of ü0, else +, the
direction of an infinitesimal push away from an unstable equilibrium), stopping where the energy no
longer allows motion, and take the first sign change. The closed form is then chosen among sympy's
symbolic roots (and their periodic images) as the one equal to that numeric root, checked at two
parameter points so that a coincidence cannot pick the wrong branch.

Examples
--------
>>> from grader.mechanics.lagrange import derive
>>> from grader.mechanics.scene import load_scene
>>> derive(load_scene("problems/sphere.toml")).answers["separation_cos"]
2/3
"""

from __future__ import annotations

import math

import numpy
import sympy
from scipy.optimize import brentq

from grader.mechanics.scene import AnswerSpec, SceneError
from grader.mechanics.simplification import human_form

__all__ = ["special_value"]

_SCAN_STEPS = 4000


def special_value(evaluator, spec: AnswerSpec) -> sympy.Expr:
    """Closed form of ``spec.expr`` where ``spec.where`` holds, on the motion from [initial]."""
    scene = evaluator.scene
    key = f"answers ({spec.name}).where"
    params = evaluator.parameters
    lhs, rhs = spec.where
    condition = evaluator.reduce(lhs - rhs, params | evaluator.state_symbols(velocities=False), key)
    coordinates = [u for u in evaluator.reduction.independent.values() if u.symbol in condition.free_symbols]
    if len(coordinates) != 1:
        raise SceneError(scene.source, key,
                         "the condition must fix one coordinate; after eliminating velocities it depends on "
                         f"{', '.join(u.name for u in coordinates) or 'no coordinate'}")
    u = coordinates[0]
    points = _parameter_points(scene)
    # Follow the motion first: "never reached" is the more useful message when both fail.
    numeric_roots = [_first_root_on_motion(evaluator, condition, u, point, key) for point in points]
    roots = _symbolic_roots(condition, u, scene.source, key)
    chosen = None
    for point, numeric_root in zip(points, numeric_roots):
        match = [r for r in roots if _close(r, numeric_root, point)]
        if not match:
            raise SceneError(scene.source, key,
                             f"the motion reaches {u.name} = {numeric_root:.12g} where the condition holds, "
                             "but the engine found no closed form for that root")
        if chosen is None:
            chosen = match[0]
        elif not _close(chosen, numeric_root, point):
            raise SceneError(scene.source, key, "the root reached depends on the parameter values")
    target = evaluator.target(spec, default_state=False) | {u.symbol}
    value = evaluator.reduce(spec.expr, target, f"answers ({spec.name}).expr")
    value = human_form(value.xreplace({u.symbol: chosen}))
    leftover = value.free_symbols - evaluator.target(spec, default_state=False)
    if leftover:
        raise SceneError(scene.source, f"answers ({spec.name})",
                         f"at the special point it still depends on {', '.join(sorted(map(str, leftover)))}")
    return value


def _symbolic_roots(condition: sympy.Expr, u, source: str, key: str) -> list[sympy.Expr]:
    try:
        roots = sympy.solve(condition, u.symbol)
    except NotImplementedError:
        roots = []
    if not roots:
        raise SceneError(source, key, f"no solution for {u.name} in closed form")
    periodic = any(isinstance(f, (sympy.sin, sympy.cos, sympy.tan)) for f in condition.atoms(sympy.Function))
    candidates = []
    for r in roots:
        images = [r]
        if periodic:
            images += [-r, sympy.pi - r]
            images += [i + k * 2 * sympy.pi for i in list(images) for k in (-1, 1)]
        candidates += images
    return candidates


def _parameter_points(scene) -> list[dict]:
    """Two parameter points: the scene's values (or a generic point), and a perturbed one."""
    rng = numpy.random.default_rng(7)
    base = {}
    for p in scene.parameters.values():
        base[p.symbol] = p.value if p.value is not None else p.domain.sample(rng)
    other = {}
    for p in scene.parameters.values():
        value = base[p.symbol] * 1.0137
        other[p.symbol] = value if p.domain.contains(value) else base[p.symbol]
    return [base, other]


def _close(candidate: sympy.Expr, root: float, point: dict) -> bool:
    try:
        value = complex(candidate.evalf(30, subs=point))
    except (TypeError, ValueError):
        return False
    return abs(value.imag) < 1e-12 and abs(value.real - root) <= 1e-8 * max(1.0, abs(root))


def _first_root_on_motion(evaluator, condition, u, point: dict, key: str) -> float:
    scene = evaluator.scene
    reduction = evaluator.reduction
    initial = {n: v for n, v in scene.initial.items()}
    if u.name not in initial:
        raise SceneError(scene.source, key, f"a special value follows the motion from [initial]; give {u.name}")
    u0 = float(initial[u.name].evalf(30, subs=point))
    g = _numeric(condition.xreplace({s: sympy.Float(v, 30) for s, v in point.items()}), u.symbol)
    speed2 = None
    if reduction.jacobi_integral() is not None and reduction.initial_value(reduction.jacobi_integral()) is not None:
        squared = evaluator.velocity_squared(u, key)
        speed2 = _numeric(squared.xreplace({s: sympy.Float(v, 30) for s, v in point.items()}), u.symbol)
    direction = _direction(evaluator, u, initial, point)
    span = 2 * math.pi if u.dimension.is_dimensionless else 10 * max(
        [abs(float(v)) for v in point.values()] + [1.0])
    step = direction * span / _SCAN_STEPS
    previous_u, previous = u0, g(u0)
    for k in range(1, _SCAN_STEPS + 1):
        current_u = u0 + k * step
        if not u.domain.contains(current_u):
            break
        if speed2 is not None and k > 1 and speed2(current_u) < 0:
            break  # the motion turns back before this point
        current = g(current_u)
        if math.isfinite(previous) and math.isfinite(current):
            if previous == 0 and k > 1:
                return previous_u
            if previous * current < 0:
                return brentq(g, min(previous_u, current_u), max(previous_u, current_u), xtol=1e-15, rtol=1e-15)
        previous_u, previous = current_u, current
    raise SceneError(scene.source, key,
                     f"the motion from [initial] never reaches a point where the condition holds "
                     f"(scanned {u.name} in the direction of motion within its domain)")


def _direction(evaluator, u, initial: dict, point: dict) -> float:
    velocity = initial.get(u.dot.name)
    if velocity is not None and float(velocity.evalf(subs=point)) != 0:
        return math.copysign(1.0, float(velocity.evalf(subs=point)))
    acceleration = evaluator.reduction.accelerations[u.ddot]
    state = {u.symbol: initial[u.name], u.dot: velocity if velocity is not None else 0}
    value = float(sympy.N(acceleration.xreplace(state).xreplace(
        {s: sympy.Float(v, 30) for s, v in point.items()}).subs(evaluator.scene.time, 0)))
    return math.copysign(1.0, value) if abs(value) > 1e-12 else 1.0


def _numeric(expr: sympy.Expr, symbol: sympy.Symbol):
    """A float function of one symbol; points where the expression is undefined give nan."""
    # The expression comes from the engine (built by our parser from a validated scene), never
    # from raw text, so lambdify's generated code is safe to compile.
    f = sympy.lambdify(symbol, expr, modules="math")

    def call(x: float) -> float:
        try:
            value = f(x)
            return float(value) if not isinstance(value, complex) else math.nan
        except (ValueError, ZeroDivisionError, OverflowError, TypeError):
            return math.nan

    return call
