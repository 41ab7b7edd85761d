"""Extremes over the motion: ``kind = "maximum"`` or ``"minimum"``.

The answer is the largest (smallest) value that ``expr`` takes along the motion from
``[initial]``. The engine writes ``expr`` in one independent coordinate u (velocities removed with
the first integrals), finds its stationary points dA/du = 0 and the turning points of the motion
(u̇² = 0) in closed form (:func:`~grader.mechanics.special_values.solve_for`, under a budget), keeps
those inside the range the motion covers (followed as for special values: until energy turns it
back or it leaves the domain, both ways), and takes the candidate with the largest (smallest)
value at two parameter points, checking that it is the same closed form at both.

Examples
--------
>>> from grader.mechanics.lagrange import derive
>>> from grader.mechanics.scene import load_scene
>>> derive(load_scene("tests/mechanics/scenes/cylinder_in_cylinder.toml")).answers["largest_normal_force"]
g*m*(7 - 4*cos(phi0))/3
"""

from __future__ import annotations

import math

import sympy

from grader.mechanics import budget
from grader.mechanics.scene import AnswerSpec, SceneError
from grader.mechanics.simplification import human_form
from grader.mechanics.special_values import (
    _direction,
    _evaluate,
    _numeric,
    _parameter_points,
    _periodic,
    _speed_squared,
    _bounded,
    _depends_on_parameters,
    _travel,
    _unvalued_scan,
    energy_speed_squared,
    solve_for,
)

__all__ = ["extreme_value"]

#: Samples per period in the numerical check of an extreme in time (see _extreme_in_time).
_PERIOD_SAMPLES = 4000


def extreme_value(evaluator, spec: AnswerSpec) -> sympy.Expr:
    """Closed form of the maximum or minimum of ``spec.expr`` over the motion from [initial]: over the
    coordinate it is written in, else (another coordinate running away, several left) over time, where
    the motion has a closed form (a wedge on a spring under a sliding block: X(t) is periodic though the
    block's s(t) grows as t²)."""
    try:
        return _extreme_over_the_coordinate(evaluator, spec)
    except _NotOverOneCoordinate as refused:
        try:
            return _extreme_in_time(evaluator, spec, f"answers ({spec.name})")
        except SceneError:
            # (as a SceneError: the private class is no part of what the author reads)
            raise SceneError(refused.source, refused.key, refused.problem) from None


class _NotOverOneCoordinate(SceneError):
    """The coordinate's way failed where the motion in time may not: the motion ran away in that
    coordinate, or the quantity needs more than one."""


def _extreme_over_the_coordinate(evaluator, spec: AnswerSpec) -> sympy.Expr:
    scene = evaluator.scene
    key = f"answers ({spec.name})"
    allowed = evaluator.parameters | evaluator.state_symbols(velocities=False) | {scene.time}
    with budget.step("writing the quantity in one coordinate", spec.name):
        value = evaluator.reduce(spec.expr, allowed, key)
    coordinates = [u for u in evaluator.reduction.independent.values() if u.symbol in value.free_symbols]
    if scene.time in value.free_symbols:
        return _extreme_in_time(evaluator, spec, key)
    if len(coordinates) != 1:
        raise _NotOverOneCoordinate(scene.source, key,
                                    "an extreme over the motion needs the quantity as a function of one coordinate "
                                    "(after removing velocities with the first integrals)")
    u = coordinates[0]
    if u.name not in scene.initial:
        raise SceneError(scene.source, key, f"an extreme over the motion follows it from [initial]; give {u.name}")
    # The quantity on the way out (u̇ with the sign it starts with) and on the way back (the other
    # sign): θ̇ of a swing is −√(…) one way and +√(…) the other, and its maximum is on the way back.
    # Before any solving: where other coordinates move too, that is the reason, whatever the solves
    # would do (one that ran out of its budget on a loaded machine gave that reason instead).
    _one_coordinate_moves(evaluator, spec, u, key)
    start = int(_direction(evaluator, u, _parameter_points(scene)[0]))
    with budget.step("writing the quantity in one coordinate", spec.name):
        branches = {sign: evaluator.reduce(spec.expr, allowed, key, signs={u.name: sign}) for sign in (start, -start)}
    with budget.step(f"solving for the stationary and turning points in {u.name}", spec.name):
        candidates = []
        for branch in dict.fromkeys(branches.values()):
            candidates += [r for r in _stationary_points(branch, u.symbol, scene.source, key) if r not in candidates]
        squared = _turning_condition(evaluator, u, key)
        if squared is not None:
            candidates += [r for r in solve_for(squared, u.symbol, scene.source, key) if r not in candidates]
    periodic = _periodic(value, u.symbol)
    want_max = spec.kind == "maximum"

    def best_at(point):
        """(value, candidate index, sign) of the extreme at ``point``, or SceneError."""
        legs = _motion_legs(evaluator, u, point, key)
        # (an angle's turn: a length that swings over more than 6.28 of its unit goes round nothing)
        if not periodic and u.dimension.is_dimensionless and any(
                low is not None and high - low >= 2 * math.pi - 1e-12 for _, low, high in legs):
            raise SceneError(scene.source, key, f"the motion from [initial] goes round and round in {u.name}, and "
                                                f"{spec.expr} is not periodic in it: it has no {spec.kind}")
        if squared is None and len(legs) > 1:
            # The motion turns back, and the extreme may be where it does; without that point among
            # the candidates the best of the others would be a wrong answer, not a missing one.
            raise SceneError(scene.source, key,
                             f"the motion from [initial] turns back, but where it does ({u.dot.name} = 0) is not "
                             f"given by energy conservation in closed form here, so the {spec.kind} of {spec.expr} "
                             "cannot be located")
        best = None
        for sign, low, high in legs:
            for index, candidate in enumerate(candidates):
                position = _evaluate(candidate, point)
                if position is None or not _inside(position, low, high, periodic):
                    continue
                amount = _evaluate(branches[sign * start].xreplace({u.symbol: candidate}), point)
                if amount is None:
                    continue
                if best is None or (amount > best[0] + 1e-12 * abs(amount) if want_max
                                    else amount < best[0] - 1e-12 * abs(amount)):
                    best = (amount, index, sign * start)
        missed = _beyond_the_candidates(branches, start, u, legs, point, None if best is None else best[0], want_max)
        if missed is not None:
            # A stationary or turning point whose condition has no closed form (x beside sin x, as energy
            # gives where a winding pendulum turns back) was left out: the best of the others is wrong.
            raise SceneError(scene.source, key,
                             f"the {spec.kind} of {spec.expr} on the motion from [initial] is near {u.name} = "
                             f"{missed:.6g}, a stationary or turning point that has no closed form here; only "
                             "the points found in closed form could be compared, so it is not given")
        if best is None:
            low, high = legs[0][1], legs[0][2]
            if low is None or high is None:
                coupled = (_coupled_in_the_energy(evaluator, u)
                           if energy_speed_squared(evaluator, u, key, readable=False) is None else [])
                if coupled:
                    # (it was said to run away: energy gave no u̇²(u) to follow the motion with)
                    raise _NotOverOneCoordinate(
                        scene.source, key,
                        f"{spec.expr} has no {spec.kind} found in closed form on the motion from [initial]: the "
                        f"energy couples {u.dot.name} with {', '.join(v.dot.name for v in coupled)} "
                        f"({', '.join(v.name for v in coupled)} move{'s' if len(coupled) == 1 else ''} as well as "
                        f"{u.name}), so it does not give {u.dot.name}^2 as a function of {u.name} alone, and the "
                        f"range of {u.name} the motion covers is not known in closed form")
                raise _NotOverOneCoordinate(scene.source, key, f"{spec.expr} has no {spec.kind} on the motion from "
                                                               "[initial]: the motion runs away")
            raise SceneError(scene.source, key,
                             f"{spec.expr} has no {spec.kind} on the motion from [initial] (no stationary or "
                             f"turning point between {u.name} = {low:.6g} and {high:.6g})")
        return best

    def same_as_chosen(point, best) -> bool:
        at = _evaluate(candidates[chosen[0]], point)
        amount = None if at is None else _evaluate(branches[chosen[1]].xreplace({u.symbol: candidates[chosen[0]]}), point)
        return amount is not None and abs(amount - best[0]) <= 1e-9 * max(1, abs(best[0]))

    chosen = None
    for point in _parameter_points(scene):
        best = best_at(point)
        if chosen is None:
            chosen = best[1:]
        elif not same_as_chosen(point, best):
            raise SceneError(scene.source, key, _depends_on_parameters(point, f"where the {spec.kind} lies"))
    # A parameter without a number gives no regime: the same closed form across its domain, where the
    # motion there lets it be found (elsewhere it says nothing).
    for point in _unvalued_scan(scene):
        try:
            best = best_at(point)
        except SceneError:
            continue
        if not same_as_chosen(point, best):
            raise SceneError(scene.source, key, _depends_on_parameters(point, f"where the {spec.kind} lies"))
    result = human_form(branches[chosen[1]].xreplace({u.symbol: candidates[chosen[0]]}))
    leftover = result.free_symbols - evaluator.target(spec, default_state=False)
    if leftover:
        raise SceneError(scene.source, key, f"the {spec.kind} still depends on {', '.join(sorted(map(str, leftover)))}")
    return result


def _one_coordinate_moves(evaluator, spec: AnswerSpec, u, key: str) -> None:
    """Refuses, with the true reason, an extreme over a motion in which other coordinates move too: energy
    then gives u̇² only with them in it, so the range of u the motion covers is not known in closed
    form (it was said to "run away": an elastic pendulum released tilted swings and bounces, bounded).
    Coordinates the motion leaves at rest (:meth:`resting_coordinates`: released hanging straight down)
    do not count: along the motion they stay at their start."""
    squared = energy_speed_squared(evaluator, u, key, readable=False)
    if squared is None:
        return  # no energy integral: as before (a driven plank's drift is found in time)
    others = sorted({v.name for v in evaluator.reduction.independent.values()
                     if v is not u and squared.free_symbols & {v.symbol, v.dot}})
    if others:
        raise _NotOverOneCoordinate(
            evaluator.scene.source, key,
            f"{spec.expr} has no {spec.kind} found in closed form on the motion from [initial]: "
            f"{', '.join(others)} move{'s' if len(others) == 1 else ''} as well as {u.name}, so energy gives "
            f"{u.dot.name}^2 only with {', '.join(others)} in it, and the range of {u.name} the motion covers "
            "is not known in closed form")


def _coupled_in_the_energy(evaluator, u) -> list:
    """The other independent coordinates whose velocities multiply u̇ in the conserved energy (none where
    energy is not conserved or [initial] does not give it)."""
    reduction = evaluator.reduction
    h = reduction.jacobi_integral()
    if h is None or reduction.initial_value(h) is None:
        return []
    cross = sympy.expand(sympy.diff(h, u.dot))
    return [v for v in reduction.independent.values() if v is not u and v.dot in cross.free_symbols]


#: Samples per stretch of the motion in the check that no extreme lies off the closed-form candidates.
_SCAN_SAMPLES = 400


def _beyond_the_candidates(branches: dict, start: int, u, legs, point: dict, best: float | None,
                           want_max: bool) -> float | None:
    """Where, on the stretches of the motion, the quantity sampled beats the best closed-form candidate
    (or any value, where there is none): an extreme at a point that solving in closed form missed.
    None where nothing does, or where the quantity cannot be evaluated in floats."""
    numbers = {s: sympy.Float(v, 30) for s, v in point.items()}
    found = None
    for sign, low, high in legs:
        if low is None or high is None or not high > low:
            continue
        try:
            f = sympy.lambdify(u.symbol, branches[sign * start].xreplace(numbers), "math")
        except Exception:  # noqa: BLE001 - a form lambdify cannot print: no check, as before
            return None
        for i in range(_SCAN_SAMPLES + 1):
            x = low + (high - low) * i / _SCAN_SAMPLES
            try:
                y = complex(f(x))
            except (ValueError, ZeroDivisionError, OverflowError, TypeError):
                continue
            if not math.isfinite(y.real) or abs(y.imag) > 1e-12 * max(1.0, abs(y.real)):
                continue
            margin = 1e-9 * max(1.0, abs(y.real))
            if best is None or (y.real > best + margin if want_max else y.real < best - margin):
                if found is None or (y.real > found[1] if want_max else y.real < found[1]):
                    found = (x, y.real)
    return None if found is None else found[0]


def _stationary_points(value: sympy.Expr, x: sympy.Symbol, source: str, key: str) -> list[sympy.Expr]:
    """Where ``value`` may have an extreme inside the motion's range: where its derivative vanishes and,
    for a value with |…| in it (the least friction coefficient |F|/N), where each bar's argument does.

    |g| h is ± g h wherever g ≠ 0, with the same stationary points, so the bars are dropped before
    differentiating (the derivative of |g| has sign(g) in it, which solve ran out of its budget on);
    the zeros of g, where |g| h has a corner, are candidates too. Each is then judged with the bars.

    >>> th, k = sympy.symbols("theta k", positive=True)
    >>> sorted(_stationary_points(sympy.Abs(sympy.sin(th)) / (2 + sympy.cos(th)), th, "f.toml", "k"), key=str)
    [-2*pi/3, 0, 2*pi/3, pi]
    """
    arguments = [a.args[0] for a in value.atoms(sympy.Abs) if x in a.free_symbols]
    signed = value.replace(lambda e: isinstance(e, sympy.Abs), lambda e: e.args[0]) if arguments else value
    try:
        found = solve_for(sympy.diff(signed, x), x, source, key)
    except SceneError as refused:
        # solve_for's own advice (write the condition more simply) means nothing here: nobody wrote one
        raise SceneError(source, key, f"the extreme lies where d/d{x} of {sympy.sstr(value)} is zero, and "
                                      f"{refused.problem.split(';')[0]}; ask instead for the value at a state "
                                      f"(in_terms_of with {x})") from None
    for argument in arguments:
        found += [r for r in solve_for(argument, x, source, key) if r not in found]
    return found


def _turning_condition(evaluator, u, key: str) -> sympy.Expr | None:
    """u̇² = 0 as a condition in u, when energy gives u̇²."""
    squared = energy_speed_squared(evaluator, u, key)
    return None if squared is None else sympy.numer(sympy.together(squared))


def _motion_legs(evaluator, u, point: dict, key: str) -> list[tuple[int, float | None, float | None]]:
    """The stretches of the motion from [initial] as (+1 on the way out, −1 on the way back; the
    range of u covered): out until energy turns it back (or it leaves the domain), back until it
    turns again, and, if it does, out again over the whole swing."""
    u0 = _evaluate(evaluator.scene.initial[u.name], point)
    direction = _direction(evaluator, u, point)
    speed2 = _speed_squared(evaluator, u, point, key)
    end, why = _travel(u, u0, direction, speed2)
    if end is None:
        if _circulates(evaluator, u, key, why):
            # An angle that energy never turns back, with u̇² periodic in it (a block round a whole loop, a
            # pendulum launched over the top): the motion goes round and round, covering every angle.
            return [(1, min(u0, u0 + 2 * math.pi * direction), max(u0, u0 + 2 * math.pi * direction))]
        return [(1, None, None)]
    legs = [(1, min(u0, end), max(u0, end))]
    if why == "turns back" or _at_a_pole(evaluator, u, end, why, u0, point):
        back, again = _travel(u, end, -direction, speed2, skip=True)
        if back is None:
            legs.append((-1, None, None))
        else:
            legs.append((-1, min(end, back), max(end, back)))
            if again == "turns back" or _at_a_pole(evaluator, u, back, again, u0, point):
                legs.append((1, min(end, back), max(end, back)))
    return legs


def _circulates(evaluator, u, key: str, why: str) -> bool:
    """Whether the motion goes round an angle for ever: u is an angle free to turn (no interval of less
    than a turn), energy gives u̇² as a function of u alone, 2π-periodic in it, and the scan never
    found it turning back."""
    if why != "never turns back" or not u.dimension.is_dimensionless or _bounded(u):
        return False
    squared = energy_speed_squared(evaluator, u, key, readable=False)
    if squared is None:
        return False
    others = evaluator.reduction.independent.values()
    if any(squared.free_symbols & {v.symbol, v.dot} for v in others if v is not u):
        return False
    return _periodic(squared, u.symbol)


def _at_a_pole(evaluator, u, end: float, why: str, u0: float, point: dict) -> bool:
    """Whether the motion leaves u's domain at ``end`` where the coordinates are singular (the mass matrix
    of the independent velocities is, there), as at the pole of a polar angle: the body goes on through
    it, and u, on its domain, comes back the way it went with the other sign of u̇ (a spherical pendulum
    released with no spin swings through θ = 0 and up the other side: its largest θ̇ is there, and came
    out 0 when the motion was taken to end at the pole). An end where they are regular (a bead at the
    end of its rod) ends the motion the scene describes."""
    if why != "leaves the domain":
        return False
    reduction = evaluator.reduction
    matrix = sympy.hessian(reduction.lagrangian, [v.dot for v in reduction.independent.values()])
    numbers = {s: sympy.Float(v, 30) for s, v in point.items()}

    def size(x: float) -> float | None:
        entries = matrix.xreplace({**numbers, u.symbol: sympy.Float(x, 30)})
        if entries.free_symbols:
            return None  # other coordinates in it: their values along the motion are not known here
        return abs(float(entries.det()))

    there, start = size(end), size(u0)
    # (1e-6: an end written to four decimals, 3.1416 for π, leaves sin² of a few 1e-11 there)
    return there is not None and start is not None and there <= 1e-6 * start


def _inside(x: float, low: float | None, high: float | None, periodic: bool) -> bool:
    if low is None or high is None:
        return False
    if periodic and high - low >= 2 * math.pi:
        return True
    images = [x + 2 * math.pi * k for k in range(-3, 4)] if periodic else [x]
    return any(low - 1e-9 <= y <= high + 1e-9 for y in images)


def _extreme_in_time(evaluator, spec: AnswerSpec, key: str) -> sympy.Expr:
    """The extreme of a quantity that the motion makes a periodic function of t (a plank driven as
    A sin Ωt: the largest friction on the cylinder on it is m A Ω²/3).

    The quantity is written in t with the motion in closed form (:mod:`grader.mechanics.motion`);
    its candidates are t = 0 and the stationary points df/dt = 0 in closed form. A periodic f takes
    over t ≥ 0 the values of one period, so the extreme is the best candidate; it is confirmed
    against f sampled densely over a period at two parameter points (and must be the same candidate
    at both). Other functions of t are refused: over an unbounded time the extreme may not exist.
    """
    from grader.mechanics.motion import motion_in_time

    scene = evaluator.scene
    t = scene.time
    everything = evaluator.parameters | evaluator.state_symbols() | {t}
    with budget.step("writing the quantity in time", spec.name):
        value = evaluator.reduce(spec.expr, everything, key)
        if value.free_symbols & evaluator.state_symbols():
            # Cancelled: a drift in the motion may cancel in the quantity (x + AΩt/3 = A sin(Ωt)/3).
            along = value.xreplace(motion_in_time(evaluator, key))
            value = budget.attempt(lambda: sympy.cancel(along), 1.0, fallback=lambda: along)
    leftover = value.free_symbols - evaluator.parameters - {t}
    if leftover:
        raise SceneError(scene.source, key, f"along the motion in time, {spec.expr} still depends on "
                                            f"{', '.join(sorted(map(str, leftover)))}")
    bounded = [u.name for u in evaluator.reduction.independent.values() if u.domain.kind == "interval"]
    if bounded:
        # The motion in closed form holds only while it stays in the domain: a period later it may
        # have left it (a cylinder rolled off the end of the plank).
        raise SceneError(scene.source, key,
                         f"an extreme over the motion in time is found only for coordinates without bounds; "
                         f"{', '.join(bounded)} has a bounded domain the motion may leave")
    period = _period(value, t)
    if period is None:
        raise SceneError(scene.source, key,
                         f"{spec.expr} = {sympy.sstr(value)} along the motion: an extreme over the motion in time "
                         "is found only where the quantity is periodic in t (sines and cosines of multiples "
                         "of one frequency); over an unbounded time this one may have none")
    with budget.step("solving for the stationary points in t", spec.name):
        candidates = [sympy.Integer(0)] + solve_for(sympy.diff(value, t), t, scene.source, key)
    want_max = spec.kind == "maximum"
    chosen = None
    for point in _parameter_points(scene):
        amounts = {i: _evaluate(value.xreplace({t: c}), point) for i, c in enumerate(candidates)}
        amounts = {i: a for i, a in amounts.items() if a is not None}
        if not amounts:
            raise SceneError(scene.source, key, f"{spec.expr} is undefined at every stationary point in t")
        best = (max if want_max else min)(amounts, key=lambda i: (amounts[i], -i))
        samples = _samples(value, t, _evaluate(period, point), point)
        extreme = (max if want_max else min)(samples) if samples else None
        scale = max(1.0, abs(amounts[best]))
        if extreme is None or (amounts[best] < extreme - 1e-9 * scale if want_max
                               else amounts[best] > extreme + 1e-9 * scale):
            raise SceneError(scene.source, key,
                             f"the stationary points of {spec.expr} in t found in closed form do not give its "
                             f"{spec.kind} over a period (sampled: {extreme}, best found: {amounts[best]})")
        if chosen is None:
            chosen = best
        elif chosen not in amounts or abs(amounts[chosen] - amounts[best]) > 1e-9 * scale:
            raise SceneError(scene.source, key, _depends_on_parameters(point, f"when the {spec.kind} comes"))
    result = human_form(value.xreplace({t: candidates[chosen]}))
    leftover = result.free_symbols - evaluator.target(spec, default_state=False)
    if leftover:
        raise SceneError(scene.source, key, f"the {spec.kind} still depends on {', '.join(sorted(map(str, leftover)))}")
    return result


def _period(expr: sympy.Expr, t: sympy.Symbol) -> sympy.Expr | None:
    """A period of ``expr`` in t when t enters only through sin, cos, tan of k·ω t + c with rational
    ratios k between the frequencies; None otherwise.

    >>> t, w = sympy.symbols("t omega", positive=True)
    >>> _period(sympy.sin(w*t) + sympy.cos(3*w*t/2), t)
    4*pi/omega
    >>> _period(t*sympy.sin(w*t), t) is None
    True
    """
    functions = [f for f in expr.atoms(sympy.sin, sympy.cos, sympy.tan) if t in f.free_symbols]
    if not functions or t in expr.xreplace({f: sympy.Dummy() for f in functions}).free_symbols:
        return None
    frequencies = []
    for f in functions:
        frequency = sympy.diff(f.args[0], t)
        if t in frequency.free_symbols or frequency == 0:
            return None
        frequencies.append(frequency)
    denominators = 1
    for frequency in frequencies:
        ratio = sympy.cancel(frequency / frequencies[0])
        if not ratio.is_Rational:
            return None
        denominators = sympy.ilcm(denominators, ratio.q)
    return 2 * sympy.pi * denominators / sympy.Abs(frequencies[0])


def _samples(value: sympy.Expr, t: sympy.Symbol, period: float | None, point: dict) -> list[float]:
    """``value`` at evenly spaced times over one period (its finite values)."""
    if period is None or not period > 0:
        return []
    f = _numeric(value.xreplace({s: sympy.Float(v, 30) for s, v in point.items()}), t)
    values = (f(period * k / _PERIOD_SAMPLES) for k in range(_PERIOD_SAMPLES + 1))
    return [v for v in values if math.isfinite(v)]
