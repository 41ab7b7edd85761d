"""Special values: an answer where a condition holds.

``where = "lhs = rhs"`` names a condition. After the engine has expressed it in the independent
variables (accelerations and multipliers solved, and if needed velocities removed with the first
integrals), it must leave exactly one **unknown**: a symbol that the answer's ``in_terms_of``
(default: the parameters) does not allow. The unknown may be

- a coordinate: the body leaves the sphere where N(θ) = 0, the ladder leaves the wall;
- a velocity: a steady circular orbit, r̈ = 0 solved for φ̇ as a function of r;
- a parameter: a threshold, such as the least launch speed v₀ for which the normal force at the top
  of a loop is zero.

An acceleration set to zero (``thetaddot = 0``) names an equilibrium, whatever the coordinates: it is
read at rest (every velocity 0; a cyclic coordinate's velocity from its conserved momentum, as
Routh's reduction writes it), never along the motion with energy, which would make a velocity term
in the acceleration depend on the start (ẋ² in ẍ of a bead on a spinning hoop in Cartesian x, y).
Only a velocity that ``in_terms_of`` leaves free, or that the answer asks for, is kept: a steady
motion (r̈ = 0 solved for the orbit's φ̇ at r). The answer there is taken as the motion passes through
the equilibrium where [initial] gives one, else at rest.

The condition is solved **algebraically** first, under a time budget (a condition in sin θ alone is
solved as a polynomial in S = sin θ, which is instant where a direct solve can hang), and the
roots are kept where they are real and inside the unknown's domain, at two parameter points. Then:

- for a coordinate that ``[initial]`` gives (and an answer not in terms of a parameter [initial]
  uses, which would make it a formula over a family of motions), the motion from there decides,
  even between roots where the answer has the same value, since it may turn back before any: it moves in the direction of u̇₀ (else
  of ü₀, else +, an infinitesimal push away from an unstable equilibrium) until energy turns it
  back, then the other way until it turns back again; the first root on that path is the one
  reached. Periodic images of an angle are followed turn after turn: there is no fixed range;
- for a velocity, the sign the motion from ``[initial]`` gives it decides;
- otherwise, if the answer has the same value at every root (cos θ = 2/3 at θ = ±48.19°), that
  value is the answer; if not, every root is a right answer (the first the reference, the others
  alternatives), unless the answer must be one value (:func:`_must_be_one_value`): then the roots
  are named and the file is refused.

An answer that asks for the time (``expr = "t"`` with ``t`` not in ``in_terms_of``) is taken at the
first moment t > 0 the condition holds on the motion in closed form (:mod:`grader.mechanics.motion`).
When q(t) has no closed form but the one-coordinate motion has an elementary energy quadrature
t(q) (a body falling radially towards a star from rest), the condition is solved for q* instead,
the root the motion reaches before it first turns back is taken, and the time is t(q*), confirmed
against a numerical integration of the motion.

``kind = "small_oscillation"`` gives the angular frequency of small oscillations of the coordinate
in ``expr`` about the equilibrium ``where`` names: ω² = −∂ü/∂u at rest at the equilibrium, by
linearising the solved equation of motion (no division by sin θ). The equilibrium need not be
reached by the motion; the motion from ``[initial]`` only chooses among several equilibria.

Examples
--------
>>> from grader.mechanics.lagrange import derive
>>> from grader.mechanics.scene import load_scene
>>> derive(load_scene("problems/sphere.toml")).answers["separation_cos"]
2/3
"""

from __future__ import annotations

import contextvars
import itertools
import math

import numpy
import sympy

from grader.expressions.functions import FUNCTIONS
from grader.expressions.implicit import real_roots
from grader.expressions.parser import MAX_LENGTH
from grader.mechanics import budget
from grader.mechanics.scene import AnswerSpec, SceneError
from grader.mechanics.simplification import TIDY_MAX_OPS, human_form, signs_in_front

__all__ = ["special_value", "solve_for"]

_SOLVE_BUDGET_S = 3.0
_SCAN_STEPS = 4000
_TRIG = (sympy.sin, sympy.cos, sympy.tan)


def special_value(evaluator, spec: AnswerSpec) -> sympy.Expr:
    """Closed form of ``spec.expr`` where ``spec.where`` holds (see the module notes)."""
    if _sets_an_acceleration_to_zero(evaluator, spec):
        from grader.mechanics.answers import without_uniform_force

        with without_uniform_force():
            return _special_value(evaluator, spec)
    return _special_value(evaluator, spec)


def _special_value(evaluator, spec: AnswerSpec) -> sympy.Expr:
    scene = evaluator.scene
    key = f"answers ({spec.name}).where"
    target = evaluator.target(spec, default_state=False)
    # At the start first: an answer that depends on t itself (the force of a rod spun up at a rate
    # ω₀ + α t) is read at [initial]'s state and t = 0, with no need of the motion in time.
    if spec.where[0] - spec.where[1] in (scene.time, -scene.time) and spec.kind != "small_oscillation":
        return _at_start(evaluator, spec, target, key)
    asks_time = scene.time in spec.expr.xreplace(evaluator.values).free_symbols
    if asks_time and scene.time not in target and spec.kind != "small_oscillation":
        return _at_time(evaluator, spec, target, key)
    if scene.time not in target and spec.kind != "small_oscillation" and _condition_in_time(evaluator, spec, key):
        # A condition that holds at moments (ẍ = 0 on a plank driven by A sin Ωt: ẍ = A Ω² sin Ωt/3)
        # names a moment of the motion, not a state: read at rest it gave ẋ = 0, at the start.
        try:
            return _at_time(evaluator, spec, target, key)
        except SceneError:
            pass  # no motion in closed form: read as before
    # An acceleration set to zero names an equilibrium, always read at rest (see _condition); without a
    # motion to follow ([initial] does not give it), an answer there is taken at rest too (the force on
    # a bead resting at a spinning hoop's relative equilibrium). With one, as the body passes through it
    # (a pendulum in an accelerating car). (A velocity left free by in_terms_of' coordinates is a steady
    # motion instead: r̈ = 0 for φ̇ at r.)
    at_rest = spec.kind == "small_oscillation" or spec.at_rest or (_sets_an_acceleration_to_zero(evaluator, spec)
                                                   and _no_motion_given(evaluator)
                                                   and not target & evaluator.state_symbols())
    try:
        return _where(evaluator, spec, target, key, at_rest=at_rest)
    except SceneError as error:
        if (not at_rest and scene.time not in target and len(evaluator.reduction.independent) > 1
                and not _sets_an_acceleration_to_zero(evaluator, spec)):
            # With several degrees of freedom energy removes one velocity, not every one: the hanging
            # pulley's ẏ where one of two blocks it pulls across a table reaches the edge keeps both
            # blocks' velocities. A motion with a closed form in time still gives the answer, at the
            # first moment the condition holds, as it does for an answer that asks for t.
            try:
                return _at_time(evaluator, spec, target, key)
            except SceneError:
                raise error from None
        # The equilibrium's answer as the body passes through it failed (with several degrees of freedom
        # energy removes one velocity, not every one: a bead in a hoop rolling down an incline keeps ṡ
        # or θ̇; or the motion, whose start in_terms_of leaves out, runs away from the equilibrium):
        # take it at rest.
        several = len(evaluator.reduction.independent) > 1
        if at_rest or not (_sets_an_acceleration_to_zero(evaluator, spec)
                           and (several or _start_left_out(evaluator, target))):
            raise
        if _asked_velocities_in_condition(evaluator, spec, target, key):
            # At rest would set to zero a velocity the answer is asked in and the condition depends on
            # (θ where θ̈ = 0, in terms of φ̇, for a pendulum whose support is driven round a circle: the
            # φ̇² sin θ cos θ term dropped): a wrong value wherever that velocity is not zero.
            raise
        try:
            return _where(evaluator, spec, target, key, at_rest=True)
        except SceneError:
            raise error from None


def _at_start(evaluator, spec, target: set, key: str) -> sympy.Expr:
    """The answer at t = 0: at the state [initial] gives, whether or not the motion has a closed form
    (a pendulum hung from a bead on a parabola, released at X₀: its tension at release)."""
    everything = evaluator.parameters | evaluator.state_symbols() | {evaluator.scene.time}
    value = evaluator.reduction.initial_value(evaluator.reduce(spec.expr, everything, f"answers ({spec.name}).expr"))
    if value is None:
        names = ", ".join(f"{u.name}, {u.dot.name}" for u in evaluator.reduction.independent.values())
        raise SceneError(evaluator.scene.source, key, f"at t = 0 the answer needs [initial] values for {names}")
    return _no_leftover(evaluator.scene, spec, human_form(value), target)


def _condition_in_time(evaluator, spec, key: str) -> bool:
    """Whether the condition, in the independent variables, depends on t itself."""
    return evaluator.scene.time in _condition_symbols(evaluator, spec, key)


def _asked_velocities_in_condition(evaluator, spec, target: set, key: str) -> bool:
    """Whether the condition, in the independent variables, depends on a velocity that in_terms_of
    names (so it cannot be read at rest)."""
    velocities = {u.dot for u in evaluator.reduction.independent.values()} & target
    return bool(velocities) and bool(_condition_symbols(evaluator, spec, key) & velocities)


def _condition_symbols(evaluator, spec, key: str) -> set:
    """The symbols of the condition written in the independent variables (none where it cannot be)."""
    lhs, rhs = spec.where
    everything = evaluator.parameters | evaluator.state_symbols() | {evaluator.scene.time}
    try:
        return evaluator.reduce(lhs - rhs, everything, key, readable=False).free_symbols
    except SceneError:
        return set()


def _sets_an_acceleration_to_zero(evaluator, spec) -> bool:
    lhs, rhs = spec.where
    accelerations = {u.ddot for u in evaluator.reduction.independent.values()}
    accelerations |= {c.ddot for c in evaluator.scene.coordinates.values()}
    return rhs == 0 and bool(lhs.free_symbols & accelerations)


def _start_left_out(evaluator, target: set) -> bool:
    """Whether [initial] uses parameters, none of which the answer may be written in."""
    used = set().union(*(v.free_symbols for v in evaluator.scene.initial.values())) & evaluator.parameters
    return bool(used) and not used & target


def _no_motion_given(evaluator) -> bool:
    """Whether [initial] leaves out an independent coordinate or its velocity: no motion to follow."""
    initial = evaluator.scene.initial
    return any(u.name not in initial or u.dot.name not in initial for u in evaluator.reduction.independent.values())


# The way a velocity the condition sets moves (θ̇ = −ω₀/2: −1), while its special value is found: the
# moment is the first one the motion passes moving that way (see _first_reached_on).
_MOVING: contextvars.ContextVar[tuple[str, int] | None] = contextvars.ContextVar("moving", default=None)


def _where(evaluator, spec, target: set, key: str, at_rest: bool) -> sympy.Expr:
    """``spec.expr`` where the condition holds: along the motion, or at rest (an equilibrium)."""
    asked = None if at_rest else _velocity_sign_asked(evaluator, spec)
    token = _MOVING.set((asked[0].name, asked[1]) if asked else None)
    try:
        if at_rest:
            return _where_moving(evaluator, spec, target, key, at_rest, None)
        from grader.mechanics.answers import along_the_motion

        with along_the_motion():
            return _where_moving(evaluator, spec, target, key, at_rest, {asked[0].name: asked[1]} if asked else None)
    finally:
        _MOVING.reset(token)


def _velocity_sign_asked(evaluator, spec) -> tuple | None:
    """(u, ±1) when the condition sets an independent velocity to a value of one sign at the
    parameter points (θ̇ = −ω₀/2), else None."""
    fixed = _velocity_the_condition_fixes(evaluator, spec)
    if not fixed:
        return None
    (velocity, value), = fixed.items()
    signs = {numpy.sign(v) for p in _parameter_points(evaluator.scene) if (v := _evaluate(value, p)) is not None}
    if len(signs) != 1 or 0 in signs:
        return None
    u = next(u for u in evaluator.reduction.independent.values() if u.dot == velocity)
    return u, int(signs.pop())


def _where_moving(evaluator, spec, target: set, key: str, at_rest: bool, signs: dict | None) -> sympy.Expr:
    scene = evaluator.scene
    with budget.step("reducing the condition", spec.name):
        condition, unknown = _condition(evaluator, spec, target, key, at_rest, signs)
    with budget.step(f"solving the condition for {unknown}", spec.name):
        try:
            roots = roots_in_domain(evaluator, condition, unknown, solve_for(condition, unknown, scene.source, key))
        except SceneError:
            if spec.numeric is None:
                raise
            roots = []  # over its budget: a numeric answer is found numerically below
    if spec.kind == "numeric" and not all(map(_typeable, roots)):
        roots = []  # a LambertW nobody can type or check: found numerically instead
    if not roots and spec.numeric is not None and spec.kind == "numeric":
        with budget.step(f"finding the root of the condition for {unknown} numerically", spec.name):
            return _implicit(evaluator, spec, condition, unknown, target, key)
    with budget.step("evaluating the answer at the roots", spec.name):
        if spec.kind == "small_oscillation":
            value = _stiffness(evaluator, spec, key)
            chosen, *others = _choose_root(evaluator, spec, condition, unknown, roots, value, key, at_rest)
            u = next(v for v in evaluator.reduction.independent.values() if v.symbol == spec.expr)
            for root in (chosen, *others):
                # −∂ü/∂u anywhere is no frequency: only about a point where ü = 0 at rest
                check_equilibrium(scene, key, u, _at_root(_rest_acceleration(evaluator, u), unknown, root), root)
            result = tidied_within(_at_root(value, unknown, chosen), FREQUENCY_TIDY_S)
        else:
            # The answer in the unknown is only evaluated, at the roots, and tidied where it is
            # substituted: as solved first (tidying it in the unknown, which nobody reads, is most
            # of the cost of a special value); readable where that fails (a variable only tidying
            # removes, a 0/0 only tidying resolves), which decides as before.
            try:
                value, chosen, others, result = _at_roots(evaluator, spec, condition, unknown, roots, target, key,
                                                          readable=False, at_rest=at_rest)
            except SceneError:
                value, chosen, others, result = _at_roots(evaluator, spec, condition, unknown, roots, target, key,
                                                          readable=True, at_rest=at_rest)
        if others:
            # Several admissible roots, none singled out: every one is a right answer.
            evaluator.alternatives[spec.name] = [
                _no_leftover(scene, spec, human_form(_at_root(value, unknown, r)), target) for r in others]
        if spec.kind == "small_oscillation":
            _check_stable(scene, spec, result)
            result = frequency_form(result)
    if spec.kind == "numeric" and spec.numeric is not None and any(
            len(sympy.sstr(form)) > MAX_LENGTH for form in (result, *evaluator.alternatives.get(spec.name, ()))):
        # A closed form longer than the checker reads (the root of a quartic by Ferrari's formulas,
        # where a cylinder leaves another that rolls on the floor) is no reference: a numeric answer
        # is found numerically instead, as at a root nobody can type.
        evaluator.alternatives.pop(spec.name, None)
        with budget.step(f"finding the root of the condition for {unknown} numerically", spec.name):
            return _implicit(evaluator, spec, condition, unknown, target, key)
    return _no_leftover(scene, spec, result, target)


def _at_roots(evaluator, spec, condition, unknown, roots, target: set, key: str, readable: bool,
              at_rest: bool = False):
    """(the answer in the unknown, the root chosen, the other roots admitted, the answer at the
    chosen root, tidied); ``readable=False``: with the answer in the unknown as solved (see
    :meth:`AnswerEvaluator.reduce`), refused (SceneError) where it is undefined at a root or at
    the chosen one, or leaves a variable, so that the caller takes the readable way."""
    # Parameters outside in_terms_of may cancel once the root is substituted (b in -2 g b φ
    # at φ = -h/b); the final check catches those that do not.
    allowed = target | evaluator.parameters | {unknown}
    velocities = {u.dot: sympy.Integer(0) for u in evaluator.reduction.independent.values()}
    if at_rest:
        # At an equilibrium the answer is taken at rest too: the normal force on a particle resting
        # relative to a turning plane has no Coriolis term (rather than "udot cannot be eliminated").
        allowed = allowed | set(velocities)
    fixed = {} if at_rest else _velocity_the_condition_fixes(evaluator, spec)
    # A velocity the condition sets (θ̇ = 0, where a block is highest on a free cart's track) is set
    # so in the answer, rather than written with energy and taken at the root: the cart's speed there
    # is m v₀/(M + m), and through θ* it kept R and g (it was refused for them).
    value = evaluator.reduce(spec.expr, allowed | set(fixed), f"answers ({spec.name}).expr", readable=readable)
    if at_rest:
        value = value.xreplace(velocities)
    value = value.xreplace(fixed)
    if not readable:
        _defined_at_roots(evaluator, spec, condition, unknown, roots, value, key)
    chosen, *others = _choose_root(evaluator, spec, condition, unknown, roots, value, key, at_rest)
    try:
        turned = None if at_rest else _turned_back(evaluator, spec, condition, unknown, roots, chosen, key)
    except LeavesTheBranch:
        raise
    except SceneError:
        # Which way the motion passes the root differs across the domains (the circular orbit's radius
        # with the angular momentum a particle in a paraboloid starts with: reached moving out or in):
        # no matter for an answer without a velocity in it.
        if not _without_velocities(evaluator, spec):
            raise
        turned = None
    if turned is not None:
        # Reached after the motion has turned back: u̇ there has the other sign than at the start
        # (θ̇ < 0 where a bob launched upwards comes back down through θ = 0.1).
        value = evaluator.reduce(spec.expr, allowed | set(fixed), f"answers ({spec.name}).expr", readable=readable,
                                 signs=turned).xreplace(fixed)
    result = human_form(_at_root(value, unknown, chosen))
    if not readable:
        if result.has(sympy.nan, sympy.zoo, sympy.oo, -sympy.oo):
            raise SceneError(evaluator.scene.source, key, "undefined at the root as solved")
        _no_leftover(evaluator.scene, spec, result, target)
    return value, chosen, others, result


def _without_velocities(evaluator, spec) -> bool:
    """Whether the answer, with the dynamics solved, has no velocity in it (nor another answer's value,
    which may have one eliminated at an odd power): then the way the motion passes a root is no matter."""
    if spec.expr.free_symbols & set(evaluator.values):
        return False
    everything = evaluator.parameters | evaluator.state_symbols() | {evaluator.scene.time}
    try:
        value = evaluator.reduce(spec.expr, everything, f"answers ({spec.name}).expr", readable=False)
    except SceneError:
        return False
    return not value.free_symbols & {u.dot for u in evaluator.reduction.independent.values()}


def _velocity_the_condition_fixes(evaluator, spec) -> dict:
    """{u̇: c} when the condition is u̇ = c for an independent velocity and c has no state in it, else {}."""
    lhs, rhs = spec.where
    velocities = {u.dot for u in evaluator.reduction.independent.values()}
    for velocity, value in ((lhs, rhs), (rhs, lhs)):
        if velocity in velocities and not value.free_symbols & evaluator.state_symbols():
            return {velocity: value}
    return {}


def _at_root(value: sympy.Expr, x: sympy.Symbol, root: sympy.Expr) -> sympy.Expr:
    """``value`` at x = root; at a root atan(v) (or atan(v) − π) through tan x = v.

    sin(α + atan v) and cos(α + atan v) do not simplify (sympy spent seconds and left nested roots
    in the acceleration of a hoop whose bead rests at tan θ = v); with sin x = ±v/√(1 + v²),
    cos x = ±1/√(1 + v²) after expanding sin(x + α), the even powers that physics leaves are rational.

    >>> th, a, v = sympy.symbols("theta alpha v", positive=True)
    >>> _at_root(sympy.sin(th + a) * sympy.cos(th), th, sympy.atan(v))
    (v*cos(alpha) + sin(alpha))/(v**2 + 1)
    """
    if isinstance(root, sympy.atan):
        v, sign = root.args[0], 1
    elif (isinstance(root, sympy.Add) and len(root.args) == 2 and -sympy.pi in root.args
          and any(isinstance(a, sympy.atan) for a in root.args)):
        v, sign = next(a for a in root.args if isinstance(a, sympy.atan)).args[0], -1
    else:
        multiple, inverse = root.as_coeff_Mul()
        if multiple.is_Rational and multiple not in (0, 1) and isinstance(inverse, (sympy.acos, sympy.asin)):
            # 2 acos c (a spring to a point of a hoop: cos(θ/2) = c): the multiple angles expanded, so
            # that cos θ there is 2c² − 1 rather than cos(2 acos c).
            w = sympy.Dummy("w", real=True)
            value = value.xreplace({x: multiple * w}).replace(
                lambda e: isinstance(e, (sympy.sin, sympy.cos, sympy.tan)) and w in e.free_symbols, sympy.expand_trig)
            return _at_root(value, w, inverse)
        if isinstance(root, (sympy.acos, sympy.asin)):
            # sin(β − x) at x = acos c stays sin(β − acos c) unless expanded first: then cos(acos c) = c
            # and sin(acos c) = √(1 − c²) (two beads at θ ± β on a spun hoop, in equilibrium).
            value = value.replace(
                lambda e: isinstance(e, (sympy.sin, sympy.cos)) and x in e.free_symbols and e.args[0] != x,
                sympy.expand_trig)
        substituted = value.xreplace({x: root})
        if not substituted.has(sympy.atan):
            return substituted
        # cos(2 atan(A/g)) (the far end of a swing about a tilt): sympy writes cos(atan v) as
        # 1/√(1 + v²) once the multiple angle is expanded.
        expanded = substituted.replace(
            lambda e: isinstance(e, (sympy.sin, sympy.cos, sympy.tan)) and e.has(sympy.atan), sympy.expand_trig)
        return substituted if expanded.has(sympy.atan) else _in_single_angles(expanded)
    expanded = value.replace(
        lambda e: isinstance(e, (sympy.sin, sympy.cos)) and x in e.free_symbols and e.args[0] != x,
        sympy.expand_trig)
    # In a symbol V for tan x first: the fraction cancels in V at the cost of a few terms, where
    # with v's own expression in place it took 0.9 s (a hoop whose bead rests at tan θ = v(α)).
    V = sympy.Dummy("v", real=True)
    norm = sympy.sqrt(1 + V ** 2)
    replaced = expanded.xreplace({sympy.sin(x): sign * V / norm, sympy.cos(x): sign / norm, sympy.tan(x): V})
    if x in replaced.free_symbols:
        return value.xreplace({x: root})
    return _in_single_angles(sympy.factor(sympy.cancel(replaced)).xreplace({V: v}))


def _in_single_angles(replaced: sympy.Expr) -> sympy.Expr:
    """One cancelled fraction in sin and cos of one angle (with sin² = 1 − cos²), factored.

    sin 2α beside sin α (a root as the engine writes it, the answer as the scene does) hide a
    common factor, which cancels in sin α, cos α.
    """
    single = sympy.expand_trig(replaced)
    angles = {a.args[0] for a in single.atoms(sympy.sin, sympy.cos)}
    if len(angles) != 1:
        return sympy.factor(sympy.cancel(single))
    (angle,) = angles
    S, C = sympy.Dummy("S"), sympy.Dummy("C")
    numerator, denominator = sympy.fraction(sympy.cancel(
        single.xreplace({sympy.sin(angle): S, sympy.cos(angle): C})))

    def reduced(p):  # S² = 1 − C², so at most linear in S
        try:
            return sympy.Poly(p, S).rem(sympy.Poly(S ** 2 + C ** 2 - 1, S)).as_expr()
        except sympy.PolynomialError:
            return p

    ratio = sympy.cancel(reduced(numerator) / reduced(denominator))
    return sympy.factor(ratio.xreplace({S: sympy.sin(angle), C: sympy.cos(angle)}))


def _reached_in_family(evaluator, u, condition, numeric: dict[int, float], point: dict, key: str) -> int | None:
    """The root the motion from [initial] at ``point`` reaches first, or None where it reaches none."""
    try:
        return _first_reached(evaluator, u, condition, numeric, point, key)
    except LeavesTheBranch:
        raise  # then the formula on this branch may be wrong where the root is: never guessed
    except SceneError:
        return None


def _turned_back(evaluator, spec, condition, x, roots, chosen, key: str) -> dict | None:
    """{u: sign} when the chosen root of the one motion from [initial] is reached moving the other way
    than u starts (after a turning point), else None."""
    variable = _variable(evaluator, x)
    if variable is None or variable[0] != "coordinate":
        return None
    u = variable[1]
    if _family_motion(evaluator, spec, u, condition):
        return _turned_back_in_family(evaluator, condition, x, variable, roots, chosen, key)
    if not _one_motion(evaluator, spec, u, condition):
        return None
    start = evaluator.motion_sign(u, pushed=True)
    if start is None:
        return None
    point = _with_state(evaluator, _parameter_points(evaluator.scene)[0], condition.free_symbols - {x})
    numeric = _numeric_roots(roots, point, variable)
    index = roots.index(chosen)
    if index not in numeric:
        return None
    return _turned_back_at(evaluator, u, start, condition, numeric[index], point, key)


def _turned_back_in_family(evaluator, condition, x, variable, roots, chosen, key: str) -> dict | None:
    """`_turned_back` for an answer about a family of motions (`_family_motion`): the way u moves at
    the chosen root, at the scene's values and across the domains wherever the motion reaches it;
    the same everywhere, or the file is refused (then no one sign is right for the formula)."""
    u = variable[1]
    start = evaluator.motion_sign(u, pushed=True)
    if start is None:
        return None
    index = roots.index(chosen)
    decided = None
    for parameters in _parameter_points(evaluator.scene) + _domain_samples(evaluator.scene):
        point = _with_state(evaluator, parameters, condition.free_symbols - {x})
        numeric = _numeric_roots(roots, point, variable)
        if index not in numeric:
            continue
        try:
            # the first root reached: the chosen one, or one where the answer has its value (a
            # particle leaving a hemisphere at x = ±0.6 R, pushed either way from the top)
            _, direction = _first_reached_on(evaluator, u, condition, numeric, point, key)
        except LeavesTheBranch:
            raise
        except SceneError:  # not reached at these values: they say nothing about the way it goes
            continue
        # The way u moves there, not only whether it turned: released at θ₀ in [-1.5, 1.5] the bob
        # passes the bottom one way or the other, and the sign taken at the scene's θ₀ = 0.8 was
        # wrong for every θ₀ < 0.
        if decided is None:
            decided = direction
        elif direction != decided:
            raise SceneError(evaluator.scene.source, key, _depends_on_parameters(parameters).replace(
                "which root holds", "which way the motion passes the root"))
    return {u.name: int(decided)} if decided is not None and decided * start < 0 else None


def _domain_samples(scene) -> list[dict]:
    """A few parameter points across the declared domains (seeded: the same every time), each keeping
    the declared orders (r₀ below R) as `_parameter_points` does."""
    rng = numpy.random.default_rng(11)
    points = []
    for _ in range(DOMAIN_POINTS):
        point = {p.symbol: p.domain.sample(rng) for p in scene.parameters.values()}
        for p in scene.parameters.values():
            big = scene.parameters[p.below] if p.below is not None else None
            if big is not None and not point[p.symbol] < point[big.symbol] \
                    and p.domain.contains(point[big.symbol]) and big.domain.contains(point[p.symbol]):
                point[p.symbol], point[big.symbol] = point[big.symbol], point[p.symbol]
        points.append(point)
    return points


def _turned_back_at(evaluator, u, start: int, condition, root: float, point: dict, key: str) -> dict | None:
    """{u: sign} when the motion reaches u = ``root`` moving against ``start``, else None."""
    try:
        _, direction = _first_reached_on(evaluator, u, condition, {0: root}, point, key)
    except SceneError:  # (chosen otherwise than by the motion: nothing to say about its direction)
        return None
    return {u.name: int(direction)} if direction * start < 0 else None


def _defined_at_roots(evaluator, spec, condition, x, roots, value, key: str) -> None:
    """SceneError unless ``value`` has a number at every root (exactly, and at the parameter points)."""
    scene = evaluator.scene
    variable = _variable(evaluator, x)
    for r in roots:
        if value.xreplace({x: r}).has(sympy.nan, sympy.zoo):
            raise SceneError(scene.source, key, f"undefined at {x} = {r} as solved")
    for parameters in _parameter_points(scene):
        point, numeric = _with_real_roots(evaluator, parameters, (condition.free_symbols | value.free_symbols) - {x},
                                          roots, variable)
        for index in numeric:
            if _evaluate(value.xreplace({x: roots[index]}), point) is None:
                raise SceneError(scene.source, key, f"undefined at {x} = {roots[index]} as solved")


def _no_leftover(scene, spec, result: sympy.Expr, target: set) -> sympy.Expr:
    leftover = result.free_symbols - target
    if leftover:
        raise SceneError(scene.source, f"answers ({spec.name})",
                         f"at the special point it still depends on {', '.join(sorted(map(str, leftover)))}")
    return result


# -- a moment of the motion in time ---------------------------------------------------------------
def _at_time(evaluator, spec, target: set, key: str) -> sympy.Expr:
    """The answer at the first moment t > 0 the condition holds on the motion from [initial].

    Used when the answer asks for t (``expr = "t"``: the time to reach the end of a rod) and
    ``in_terms_of`` does not allow it: the coordinates are replaced by the motion in closed form
    (:mod:`grader.mechanics.motion`), which leaves t as the condition's one unknown. Without q(t),
    the energy quadrature t(q) gives the time (:func:`_time_by_quadrature`).
    """
    from grader.mechanics.motion import motion_in_time, quadrature

    scene = evaluator.scene
    t = scene.time
    everything = evaluator.parameters | evaluator.state_symbols() | {t}
    with budget.step("reducing the condition", spec.name):
        lhs, rhs = spec.where
        condition = evaluator.reduce(lhs - rhs, everything, key)
        asked = evaluator.reduce(spec.expr, everything, f"answers ({spec.name}).expr")
        # A moment fixed by the parameters alone (α²t² = g/a: when a hoop spun up at α makes its lowest
        # point unstable) needs no motion, which may have no closed form.
        timed = (condition.free_symbols | asked.free_symbols) & evaluator.state_symbols()
        try:
            motion = motion_in_time(evaluator, key) if timed else {}
        except SceneError as refused:
            # No q(t); the time may still come from the quadrature t(q) itself.
            try:
                quad = quadrature(evaluator, key)
            except SceneError:
                raise refused from None
            return _time_by_quadrature(evaluator, spec, target, key, quad)
        condition = condition.xreplace(motion)
        # A polynomial in t (a uniformly accelerated motion) is solved as it is: its readable form
        # took longer than the solve (0.35 s, a wedge with a block on it and another hanging).
        condition = _essential(condition if condition.is_polynomial(t) else human_form(condition))
    others = sorted(map(str, condition.free_symbols - target - {t}))
    if t not in condition.free_symbols or others:
        raise SceneError(scene.source, key,
                         "along the motion in time the condition must leave t as its one unknown; it "
                         f"leaves {', '.join(others) or 'no t'}")
    with budget.step("solving the condition for t", spec.name):
        roots = solve_for(condition, t, scene.source, key)
        period = _time_period(condition, t)
        if period is not None:
            # solve gives the roots of one period about 0 (0 and a negative one, for a box on a
            # spring whose speed is next 0 after half a period): their images a period or two on
            roots = roots + [r + n * period for n in (1, 2) for r in roots]
    with budget.step("evaluating the answer at the roots", spec.name):
        value = asked.xreplace(motion)
        chosen = _first_time(scene, roots, t, key)
        result = human_form(value.xreplace({t: chosen}))
    return _no_leftover(scene, spec, result, target)


def _time_by_quadrature(evaluator, spec, target: set, key: str, quad) -> sympy.Expr:
    """The answer where the condition first holds, at the time t(q*) the quadrature gives.

    The condition is written in the one coordinate q (velocities removed with energy), solved
    for q*, and the root the motion reaches first on its way from [initial] is taken: it must lie
    before the motion first turns back, where the quadrature stops following it. The time is then
    confirmed against a numerical integration of the equations of motion.
    """
    from grader.mechanics.motion import numeric_motion

    scene = evaluator.scene
    t, u = scene.time, quad.u
    q = u.symbol
    lhs, rhs = spec.where
    with budget.step("reducing the condition", spec.name):
        condition = _essential(human_form(evaluator.reduce(lhs - rhs, target | evaluator.parameters | {q}, key)))
    others = sorted(map(str, condition.free_symbols - target - {q}))
    if q not in condition.free_symbols or others:
        raise SceneError(scene.source, key,
                         f"the time is found from the quadrature t({u.name}), so the condition must leave {u.name} "
                         f"as its one unknown; it leaves {', '.join(others) or f'no {u.name}'}")
    with budget.step(f"solving the condition for {u.name}", spec.name):
        roots = solve_for(condition, q, scene.source, key)
    chosen = count = None
    near = _parameter_points(scene)
    for n, point in enumerate(near + _domain_points(scene, roots)):
        across = n >= len(near)  # as in _choose_root: the same root where there are as many ahead
        speed2 = _numeric(quad.speed_squared.xreplace({s: sympy.Float(v, 30) for s, v in point.items()}), q)
        q0 = _evaluate(evaluator.reduction.initial_value(q), point)
        end, why = _travel(u, q0, quad.sign, speed2)
        ahead = {}
        for index, root in enumerate(roots):
            value = _evaluate(root, point)
            if value is None or (u.domain.kind != "real" and not u.domain.contains(value)):
                continue
            distance = quad.sign * (value - q0)
            if distance > 1e-12 and (end is None or distance <= quad.sign * (end - q0) + 1e-12):
                ahead[index] = distance
        if across:
            if len(ahead) == count and min(ahead, key=ahead.get) != chosen:
                raise SceneError(scene.source, key, _depends_on_parameters(point))
            continue
        if not ahead:
            listed = ", ".join(sympy.sstr(r) for r in roots) or "none in closed form"
            turns = f"{why} at {u.name} = {end:.6g}" if end is not None else why
            raise SceneError(scene.source, key,
                             f"the motion from [initial] {turns} before it reaches the condition ({u.name} = "
                             f"{listed}); the quadrature t({u.name}) follows it only until it first turns back")
        first = min(ahead, key=ahead.get)
        if chosen is not None and chosen != first:
            raise SceneError(scene.source, key, _depends_on_parameters(point, "which root is reached first"))
        chosen, count = first, len(ahead)
    root = roots[chosen]
    moment = human_form(quad.time.xreplace({q: root}))
    # Confirmed numerically: the motion reaches q* at that moment.
    point = _parameter_points(scene)[0]
    expected_t = _evaluate(moment, point)
    expected_q = _evaluate(root, point)
    run = numeric_motion(evaluator, point, horizon=1.05 * expected_t if expected_t else None)
    reached = run.time_at(u, expected_q) if expected_q is not None else None
    if expected_t is None or reached is None or abs(reached - expected_t) > 1e-6 * max(abs(expected_t), 1e-12):
        raise SceneError(scene.source, key,
                         f"the time from the quadrature, t = {sympy.sstr(moment)}, disagrees with a numerical "
                         f"integration of the equations of motion ({expected_t} against {reached}); refused rather "
                         "than risk a wrong closed form")
    with budget.step("evaluating the answer at the roots", spec.name):
        value = evaluator.reduce(spec.expr, target | evaluator.parameters | {q, t}, f"answers ({spec.name}).expr")
        result = human_form(value.xreplace({q: root, t: moment}))
    return _no_leftover(scene, spec, result, target)


def _time_period(condition: sympy.Expr, t: sympy.Symbol) -> sympy.Expr | None:
    """The period in t of a condition where t enters only through sines, cosines and tangents of
    commensurate multiples of t (a t + b, a free of t), or None.

    >>> t, w = sympy.symbols("t omega", positive=True)
    >>> _time_period(sympy.sin(w*t) + sympy.cos(2*w*t) - 1, t)
    2*pi/omega
    >>> _time_period(sympy.sin(w*t) - t, t) is None
    True
    """
    atoms = [f for f in condition.atoms(*_TRIG) if t in f.free_symbols]
    if not atoms or t in condition.xreplace({f: sympy.Dummy() for f in atoms}).free_symbols:
        return None
    rates = []
    for f in atoms:
        rate = sympy.diff(f.args[0], t)
        if rate == 0 or t in rate.free_symbols:
            return None
        rates.append(rate)
    ratios = [sympy.nsimplify(r / rates[0]) for r in rates]
    if not all(q.is_Rational for q in ratios):
        return None
    base = rates[0] / sympy.ilcm(*[q.q for q in ratios]) if len(ratios) > 1 else rates[0]
    period = 2 * sympy.pi / base
    return period if period.is_positive else sympy.Abs(period)


def _first_time(scene, roots: list[sympy.Expr], t: sympy.Symbol, key: str) -> sympy.Expr:
    """The root the motion reaches first: the least t > 0, the same root at two parameter points."""
    chosen = None
    for point in _parameter_points(scene):
        times = {i: v for i, r in enumerate(roots) if (v := _evaluate(r, point)) is not None and v > 1e-12}
        if not times:
            listed = ", ".join(sympy.sstr(r) for r in roots) or "none in closed form"
            raise SceneError(scene.source, key,
                             f"the motion from [initial] never reaches the condition at a time t > 0 (roots: "
                             f"{listed})")
        first = min(times, key=times.get)
        if chosen is not None and chosen != first:
            raise SceneError(scene.source, key, _depends_on_parameters(point, "which root is reached first"))
        chosen, count = first, len(times)
    # The same across the domains, where there are as many times (see _choose_root).
    for point in _domain_points(scene, roots):
        times = {i: v for i, r in enumerate(roots) if (v := _evaluate(r, point)) is not None and v > 1e-12}
        if len(times) == count and min(times, key=times.get) != chosen:
            raise SceneError(scene.source, key, _depends_on_parameters(point))
    return roots[chosen]


def _depends_on_parameters(point: dict, what: str = "which root holds") -> str:
    """Why a choice made at the scene's values (a root, an extreme, a time) cannot be the reference:
    at ``point`` (another point of the domains, or a student's draw) another closed form holds."""
    where = ", ".join(f"{s} = {v:.4g}" for s, v in sorted(point.items(), key=lambda i: str(i[0])))
    return (f"{what} depends on the parameter values: the closed form that holds at the scene's "
            f"values (generic ones for a parameter without a number) is not the one reached at {where}; narrow the parameters' domains or random ranges, or give "
            "them values (or write the scene with a ratio of them), so that one closed form holds throughout")


# -- the condition --------------------------------------------------------------------------------
def _condition(evaluator, spec, target: set, key: str, at_rest: bool = False,
               signs: dict | None = None) -> tuple[sympy.Expr, sympy.Symbol]:
    """The condition in the independent variables, and its one unknown (``at_rest``: every velocity 0;
    ``signs``: the sign of a velocity the condition sets, when energy eliminates it)."""
    scene = evaluator.scene
    lhs, rhs = spec.where
    everything = evaluator.parameters | evaluator.state_symbols() | {scene.time}
    expr = lhs - rhs
    velocities = {u.dot for u in evaluator.reduction.independent.values()} | {c.dot for c in scene.coordinates.values()}
    if not at_rest and (expr in velocities or -expr in velocities):
        # u̇ = 0 (a turning point) as u̇² = 0: with the velocity from energy it is F(u) = 0, a polynomial
        # in cos θ for a spherical pendulum, where √F = 0 ran out of the solve's budget.
        expr = expr ** 2
    if at_rest:
        # An equilibrium: at rest.
        expr = expr.xreplace({u.dot: 0 for u in evaluator.reduction.independent.values()})
        expr = expr.xreplace({c.dot: 0 for c in scene.coordinates.values()})
    along_motion = target | evaluator.parameters | evaluator.state_symbols(velocities=False)
    # (allowed, at rest, velocities set first, velocities from conserved momenta)
    attempts = [(everything, at_rest, {}, {}), (along_motion, at_rest, {}, {})]
    if not at_rest and _sets_an_acceleration_to_zero(evaluator, spec):
        # An acceleration set to zero names an equilibrium, never a moment of the motion: read along
        # the motion, its velocity terms would be written with energy from [initial] (ẋ² in ẍ of a
        # bead on a spinning hoop in the hoop's own x, y: x* then depended on x₀). Read as it stands
        # (θ̈ of a pendulum in a car has no velocity; r̈ = 0 solved for φ̇ at r, a steady orbit), else
        # at rest with the velocities of cyclic coordinates from their conserved momenta (Routh's
        # reduction: the radius of a particle's circular orbit in a paraboloid, with the angular
        # momentum it starts with), else as a steady motion (r constant, the orbit's φ̇ free, where
        # in_terms_of leaves out what [initial] gives the momentum), else at rest in every coordinate.
        attempts = [(everything, False, {}, {})]
        momenta = _routh_momenta(evaluator, target, key)
        if momenta:
            attempts.append((everything, True, {}, momenta))
        steady = _steady(evaluator, spec)
        if steady:
            attempts.append((everything, False, steady, {}))
        attempts.append((everything, True, {}, {}))
    found = []
    deferred = False
    for allowed, resting, still, momenta in attempts:
        here = expr.xreplace(still)
        if resting and not at_rest:
            kept = set(momenta)
            here = expr.xreplace({u.dot: 0 for u in evaluator.reduction.independent.values() if u.dot not in kept})
            here = here.xreplace({c.dot: 0 for c in scene.coordinates.values() if c.dot not in kept})
        try:
            condition = evaluator.reduce(here, allowed, key, signs=signs)
        except SceneError:
            continue
        condition = condition.xreplace(still)
        if momenta:
            condition = condition.xreplace(momenta)
        if resting:
            condition = condition.xreplace({u.dot: 0 for u in evaluator.reduction.independent.values()})
        condition = _essential(condition)
        state = (condition.free_symbols & evaluator.state_symbols()) - target
        if (not deferred and allowed is everything and not resting and not still and state
                and not state & evaluator.state_symbols(velocities=False)):
            # Velocities and no coordinate (θ̇ = 0, the end of a swing): a moment of the motion, read
            # along it (the velocity from energy, the coordinate the unknown) before as it stands,
            # which would solve θ̇ = 0 for θ̇ and leave the answer in θ.
            deferred = True
            attempts.append((allowed, resting, still, momenta))
            continue
        # A state variable is the unknown when there is one (the condition picks a configuration;
        # parameters outside in_terms_of may still cancel from the answer); else a parameter
        # (a threshold).
        unknowns = sorted((condition.free_symbols - target) & evaluator.state_symbols(), key=str) or sorted(
            condition.free_symbols - target, key=str)
        if len(unknowns) == 1:
            return condition, unknowns[0]
        found.append(unknowns)
    names = ", ".join(str(s) for s in (found[-1] if found else [])) or "nothing"
    raise SceneError(scene.source, key,
                     f"the condition must leave exactly one unknown that in_terms_of does not allow; it "
                     f"leaves {names}")


def _routh_momenta(evaluator, target: set, key: str) -> dict:
    """{u̇: its value from the conserved momentum} for the cyclic coordinates [initial] gives a momentum
    (as Routh's reduction writes them), or {} where there are none or a momentum is written with a
    parameter that [initial] uses and in_terms_of leaves out: then the equilibrium is read at rest."""
    try:
        momenta = evaluator.momentum_substitution(target, key)
    except SceneError:
        return {}
    used = set().union(*(v.free_symbols for v in evaluator.scene.initial.values())) & evaluator.parameters
    if any((v.free_symbols & used) - target for v in momenta.values()):
        return {}
    return momenta


def _steady(evaluator, spec) -> dict:
    """u̇ = 0 for the coordinates whose acceleration the condition sets to zero, when that leaves
    other velocities free ({} otherwise: then it is the equilibrium's reading, at rest)."""
    lhs, _ = spec.where
    independent = evaluator.reduction.independent.values()
    still = {u.dot: sympy.Integer(0) for u in independent if u.ddot in lhs.free_symbols}
    return still if still and len(still) < len(independent) else {}


def _essential(condition: sympy.Expr) -> sympy.Expr:
    """The condition's numerator without factors that cannot vanish (m in m (v₀²/R − 5g) = 0).

    >>> m, v, g = sympy.symbols("m v g", positive=True)
    >>> _essential(m*(v**2 - 5*g)/g)
    -5*g + v**2
    """
    numerator = sympy.numer(sympy.together(condition))
    factors = sympy.Mul.make_args(sympy.factor_terms(numerator))
    kept = [f for f in factors if not (f.is_positive or f.is_negative)]
    return sympy.Mul(*kept) if kept else numerator


def solve_for(condition: sympy.Expr, x: sympy.Symbol, source: str, key: str) -> list[sympy.Expr]:
    """Closed-form roots of ``condition = 0`` in ``x``, under a time budget.

    The condition is factored first (the ladder's (3 sin θ − 2 sin θ₀) cos θ is two easy
    conditions, not one hard one). A factor in which x appears only through one of sin x, cos x,
    tan x is solved as a polynomial in that function (S = sin θ), and the roots mapped back.

    >>> theta, a = sympy.symbols("theta a", positive=True)
    >>> solve_for(3*sympy.cos(theta) - 2, theta, "f.toml", "k")
    [acos(2/3), -acos(2/3)]
    """
    # Over one denominator, √(cos θ − cos θ₀) beside 1/√(cos θ − cos θ₀) (the slope of a speed) is
    # the polynomial (3 cos θ − 2 cos θ₀) sin θ; solve spent seconds on the sum of square roots.
    numerator, denominator = budget.attempt(lambda: sympy.fraction(sympy.together(condition)),
                                            _SOLVE_BUDGET_S, fallback=lambda: (condition, sympy.Integer(1)))

    def factors_of():
        try:
            return [f for f, _ in sympy.factor_list(numerator)[1]]
        except sympy.PolynomialError:
            pass
        factors = []
        for product in sympy.Mul.make_args(sympy.factor_terms(numerator)):
            try:
                factors += [f for f, _ in sympy.factor_list(product)[1]]
            except sympy.PolynomialError:  # e^{ωt} beside e^{−ωt}, √2 √g: factor_list refuses them
                factors.append(product)
        return factors

    factors = budget.attempt(factors_of, _SOLVE_BUDGET_S, fallback=lambda: [numerator])
    roots = []
    for factor in factors:
        if x not in factor.free_symbols:
            continue
        for root in _solve_factor(factor, x, source, key):
            # a root of the numerator where the denominator vanishes is a pole, not a root
            if root not in roots and not (x in denominator.free_symbols
                                          and denominator.xreplace({x: root}).is_zero):
                roots.append(root)
    return roots


def _solve_factor(condition: sympy.Expr, x: sympy.Symbol, source: str, key: str) -> list[sympy.Expr]:
    from grader.mechanics.motion import _transcendental_in
    from grader.mechanics.simplification import _pythagorean

    S = sympy.Dummy("S")
    for function in _TRIG:
        # cos²x + sin x is a polynomial in sin x once cos²x = 1 − sin²x.
        rewritten = condition if function is sympy.tan else sympy.expand(
            _pythagorean(condition, function))
        substituted = rewritten.xreplace({function(x): S})
        if substituted != condition and x not in substituted.free_symbols:
            values = _budgeted_solve(substituted, S)
            if values is None:
                break
            inverse = {sympy.sin: lambda v: [sympy.asin(v), sympy.pi - sympy.asin(v)],
                       sympy.cos: lambda v: [sympy.acos(v), -sympy.acos(v)],
                       sympy.tan: lambda v: [sympy.atan(v), sympy.atan(v) - sympy.pi]}[function]
            roots = []
            for v in values:
                roots += [r for r in inverse(v) if r not in roots]
            return roots
    homogeneous = _homogeneous_in_sin_cos(condition, x, source, key)
    if homogeneous is not None:
        return homogeneous
    exponential = _through_exponentials(condition, x, source, key)
    if exponential is not None:
        return exponential
    compound = condition.replace(
        lambda e: isinstance(e, (sympy.sin, sympy.cos, sympy.tan)) and x in e.free_symbols and e.args[0] != x,
        sympy.expand_trig)
    if compound != condition:
        # sin(θ + β) beside sin(θ − β) (two beads at θ ± β on a spun hoop): in sin θ and cos θ alone the
        # substitutions above apply; the general solver ran out of its budget on them.
        return solve_for(sympy.expand(compound), x, source, key)
    if _transcendental_in(condition, x, _TRANSCENDENTAL) is not None:
        # x beside a function of x (m g l sin θ = k θ, x eˣ = c): no closed form a student could type
        # (at best a LambertW), and solve would spend its whole budget finding that out.
        return []
    roots = _budgeted_solve(condition, x)
    if roots is None:
        raise SceneError(source, key, f"solving the condition for {x} ran out of its {_SOLVE_BUDGET_S:g} s "
                                      "budget; write the condition in a simpler form")
    return roots


# Functions that, applied to the unknown beside the unknown itself, leave no elementary solution.
_TRANSCENDENTAL = (sympy.sin, sympy.cos, sympy.tan, sympy.cot, sympy.sec, sympy.csc, sympy.sinh, sympy.cosh,
                   sympy.tanh, sympy.coth, sympy.sech, sympy.csch, sympy.exp, sympy.log, sympy.asin, sympy.acos,
                   sympy.atan, sympy.acot, sympy.asinh, sympy.acosh, sympy.atanh)


def _is_one_plus_square(poly: sympy.Poly) -> bool:
    """Whether a polynomial in T is c (1 + T²) (no real root; a cheap test, where simplify took seconds)."""
    T = poly.gens[0]
    return (poly.degree() == 2 and poly.coeff_monomial(T) == 0
            and sympy.expand(poly.coeff_monomial(T ** 2) - poly.coeff_monomial(1)) == 0)


def _homogeneous_in_sin_cos(condition: sympy.Expr, x: sympy.Symbol, source: str, key: str) -> list[sympy.Expr] | None:
    """Roots of a condition that is a homogeneous polynomial in sin x and cos x (each term of the
    same degree n, A cos θ + g sin θ: a pendulum in an accelerating car): cosⁿx times a polynomial
    in tan x, so x = atan(v) (and atan(v) − π), with ±π/2 where cos x = 0 is a root. None otherwise.

    (solve gives 2 atan((g − √(A² + g²))/A), right but unreadable, and the answers at the root with it.)

    >>> th, A, g = sympy.symbols("theta A g", positive=True)
    >>> _homogeneous_in_sin_cos(A*sympy.cos(th) + g*sympy.sin(th), th, "f.toml", "k")
    [-atan(A/g), -atan(A/g) - pi]
    """
    s, c, T = sympy.Dummy("s"), sympy.Dummy("c"), sympy.Dummy("T")
    # sin(θ + α), cos(θ + α) (a bead in a hoop rolling down an incline) are sums in sin θ, cos θ.
    condition = condition.replace(
        lambda e: isinstance(e, (sympy.sin, sympy.cos)) and x in e.free_symbols and e.args[0] != x,
        sympy.expand_trig)
    replaced = sympy.expand(condition.xreplace({sympy.sin(x): s, sympy.cos(x): c}))
    if x in replaced.free_symbols or not replaced.has(s) or not replaced.has(c):
        return None
    try:
        poly = sympy.Poly(replaced, s, c)
    except sympy.PolynomialError:
        return None
    degrees = {sum(monomial) for monomial in poly.monoms()}
    if len({d % 2 for d in degrees}) != 1:
        return None
    # Degrees of one parity (sin θ beside sin θ sin²(θ + α)) become one degree n with
    # sin² + cos² = 1: each term times (s² + c²)^((n − d)/2).
    n = max(degrees)
    poly = sympy.Poly(sum((coefficient * s ** i * c ** j * (s ** 2 + c ** 2) ** ((n - i - j) // 2)
                           for (i, j), coefficient in poly.terms()), sympy.Integer(0)), s, c)
    in_tan = sympy.expand(poly.as_expr().xreplace({s: T, c: 1}))

    def real_factors():
        # 1 + T² (from sin² + cos²) has no real root; the others are solved one by one.
        factors = [f for f, _ in sympy.factor_list(in_tan)[1] if T in f.free_symbols]
        return [f for f in factors if not _is_one_plus_square(sympy.Poly(f, T))]

    factors = budget.attempt(real_factors, _SOLVE_BUDGET_S, fallback=lambda: [in_tan])
    values = []
    for factor in factors:
        found = _budgeted_solve(factor, T)
        if found is None:
            raise SceneError(source, key, f"solving the condition for {x} ran out of its {_SOLVE_BUDGET_S:g} s "
                                          "budget; write the condition in a simpler form")
        values += [v for v in found if v not in values and not (v ** 2 + 1).is_zero]
    roots = []
    for v in values:
        roots += [r for r in (sympy.atan(v), sympy.atan(v) - sympy.pi) if r not in roots]
    # cos x = 0 is a root when the sinⁿ term is missing.
    if poly.coeff_monomial(s ** n) == 0:
        roots += [sympy.pi / 2, -sympy.pi / 2]
    return roots


def _through_exponentials(condition: sympy.Expr, x: sympy.Symbol, source: str, key: str) -> list[sympy.Expr] | None:
    """Roots of a condition in which x appears only through exp, cosh, sinh, tanh of c x + b, the
    slopes c commensurate (a motion in time r₀ cosh ωt, s* + (s₀ − s*) cosh(ω t sin α) = L): a
    polynomial in E = e^{kx}, solved for E, x = log(E)/k; through one of cosh, sinh, tanh of k x
    alone, a polynomial in it, x = acosh(v)/k, ... None when x appears otherwise.

    (solve, given the hyperbolic functions, rewrites every one of them, those of the parameters too,
    and spends its whole budget.)

    >>> t, w, a, L = sympy.symbols("t omega a L", positive=True)
    >>> _through_exponentials(a*sympy.cosh(w*t) + a*sympy.sinh(w*t) - L, t, "f.toml", "k")
    [log(L/a)/omega]
    >>> _through_exponentials(a*sympy.cosh(2*w*t) - L, t, "f.toml", "k")
    [acosh(L/a)/(2*omega), -acosh(L/a)/(2*omega)]
    """
    functions = [f for f in condition.atoms(sympy.exp, sympy.cosh, sympy.sinh, sympy.tanh) if x in f.free_symbols]
    if not functions:
        return None
    slopes = {}
    for f in functions:
        argument = sympy.expand(f.args[0])
        slope = argument.coeff(x)
        if slope == 0 or x in slope.free_symbols or x in (argument - slope * x).free_symbols:
            return None
        slopes[f] = (slope, argument - slope * x)
    if len(functions) == 1 and functions[0].func is not sympy.exp and slopes[functions[0]][1] == 0:
        # One hyperbolic function of k x: a polynomial in it, as sin θ above (acosh(L/r₀)/ω, not a log).
        (f,) = functions
        H = sympy.Dummy("H")
        values = _budgeted_solve(sympy.numer(sympy.together(condition.xreplace({f: H}))), H)
        if values is None:
            raise SceneError(source, key, f"solving the condition for {x} ran out of its {_SOLVE_BUDGET_S:g} s "
                                          "budget; write the condition in a simpler form")
        k = slopes[f][0]
        inverse = {sympy.cosh: lambda v: [sympy.acosh(v), -sympy.acosh(v)], sympy.sinh: lambda v: [sympy.asinh(v)],
                   sympy.tanh: lambda v: [sympy.atanh(v)]}[f.func]
        return [r / k for v in values for r in inverse(v)]
    base = next(iter(slopes.values()))[0]
    ratios = {f: sympy.cancel(slope / base) for f, (slope, _) in slopes.items()}
    if not all(r.is_Rational for r in ratios.values()):
        return None
    n = sympy.ilcm(1, *(r.q for r in ratios.values()))
    k = base / n
    E = sympy.Dummy("E")
    replaced = {}
    for f, (_, offset) in slopes.items():
        up = sympy.exp(offset) * E ** (ratios[f] * n)
        down = 1 / up
        replaced[f] = {sympy.exp: up, sympy.cosh: (up + down) / 2, sympy.sinh: (up - down) / 2,
                       sympy.tanh: (up - down) / (up + down)}[f.func]
    substituted = condition.xreplace(replaced)
    if x in substituted.free_symbols:
        return None
    values = _budgeted_solve(sympy.numer(sympy.together(substituted)), E)
    if values is None:
        raise SceneError(source, key, f"solving the condition for {x} ran out of its {_SOLVE_BUDGET_S:g} s "
                                      "budget; write the condition in a simpler form")
    return [sympy.log(v) / k for v in values if v != 0]


def _budgeted_solve(expr: sympy.Expr, x) -> list[sympy.Expr] | None:
    def solve():
        cubic = _real_cubic_roots(expr, x)
        if cubic is not None:
            return cubic
        try:
            return list(sympy.solve(expr, x))
        except NotImplementedError:
            return []

    return budget.attempt(solve, _SOLVE_BUDGET_S, fallback=lambda: None)


def _real_cubic_roots(expr: sympy.Expr, x) -> list[sympy.Expr] | None:
    """The real roots of a cubic in ``x`` in real closed forms, or None when ``expr`` is not one.

    ``solve`` writes them by Cardano's formula with complex cube roots, in i even where all three are
    real (a block leaving a hemisphere free on a floor: m cos³θ − 3(M + m) cos θ + 2(M + m) = 0); such a
    form cannot be typed nor checked. Written t³ + p t + q = 0 (x = t − b/3a), the roots are Viète's
    2A cos(acos(3q/(2pA))/3 − 2πk/3), A = √(−p/3), k = 0, 1, 2 (cos 3φ = 4 cos³φ − 3 cos φ), real in real
    arithmetic where the cubic is shown to have three real roots on the declared domains (Δ = q²/4 +
    p³/27 < 0); where it is shown to have one (Δ > 0), Cardano's ∛(−q/2 + √Δ) + ∛(−q/2 − √Δ) with real
    cube roots. Where Δ may have either sign, neither form holds throughout (Viète's leaves the reals,
    Cardano's bars and signs of complex numbers give a real number that is no root): None, and
    ``solve`` decides as before.

    >>> c = sympy.Symbol("c")
    >>> [sympy.N(r, 6) for r in _real_cubic_roots(c**3 - 3*c + 1, c)]  # three real roots
    [1.53209, 0.347296, -1.87939]
    >>> [sympy.N(r, 6) for r in _real_cubic_roots(c**3 + c + 1, c)]  # one
    [-0.682328]
    """
    try:
        poly = sympy.Poly(expr, x)
    except sympy.PolynomialError:
        return None
    if poly.degree() != 3 or any(coefficient.has(x) for coefficient in poly.all_coeffs()):
        return None
    a, b, c, d = poly.all_coeffs()
    if not all(coefficient.is_real is not False for coefficient in (a, b, c, d)):
        return None
    p = (3 * a * c - b ** 2) / (3 * a ** 2)
    q = (2 * b ** 3 - 9 * a * b * c + 27 * a ** 2 * d) / (27 * a ** 3)
    if p == 0:
        return None  # x = −b/3a − ∛q: solve writes it readably
    shift = -b / (3 * a)
    # cos 3φ = 3q/(2pA) with A = √(−p/3) itself (not √(−3/p) = 1/A, false on a branch cut): exact for any p
    scale = sympy.sqrt(-p / 3)
    angle = sympy.acos(3 * q / (2 * p * scale)) / 3
    three = [shift + 2 * scale * sympy.cos(angle - 2 * sympy.pi * k / 3) for k in range(3)]
    sign = _sign_on_the_domains(q ** 2 / 4 + p ** 3 / 27)
    if sign == -1:
        return three
    if sign == 1:
        half, delta = -q / 2, sympy.sqrt(q ** 2 / 4 + p ** 3 / 27)
        return [shift + _real_cube_root(half + delta) + _real_cube_root(half - delta)]
    return None  # one real root or three, as the parameters go: neither form holds throughout


def _sign_on_the_domains(expr: sympy.Expr) -> int | None:
    from grader.mechanics.simplification import _bounds_of, _factor_sign, _order_of

    expr = sympy.factor(sympy.together(expr))
    return _factor_sign(expr, _bounds_of(expr.free_symbols), _order_of(expr.free_symbols))


def _real_cube_root(value: sympy.Expr) -> sympy.Expr:
    """The real cube root, negative for a negative value (sympy's principal one is complex there)."""
    return sympy.sign(value) * sympy.Abs(value) ** sympy.Rational(1, 3)


# -- no closed form: a numeric answer at a root found numerically ------------------------------------
# The functions of the one registry: what students type and the checker evaluates.
_TYPEABLE = frozenset(f.sympy_func for f in FUNCTIONS.values() if f.sympy_func is not None)


def _typeable(expr: sympy.Expr) -> bool:
    """Whether a closed form uses only functions of the registry (not LambertW, a RootOf, a Piecewise) and
    real numbers.

    >>> x = sympy.Symbol("x", positive=True)
    >>> _typeable(sympy.acos(x / 2)), _typeable(sympy.LambertW(x))
    (True, False)
    """
    if expr.has(sympy.CRootOf, sympy.Integral, sympy.Derivative, sympy.I):
        return False  # (i: a root that is real written with complex numbers, which no answer can hold)
    return all(f.func in _TYPEABLE for f in expr.atoms(sympy.Function))


#: Parameter draws on which the choice of root is confirmed (each student has one).
IMPLICIT_DRAWS = 12


def _implicit(evaluator, spec, condition, x, target: set, key: str) -> sympy.Expr:
    """The answer in the unknown ``x``, to be taken at a root of the condition found numerically.

    Records in ``evaluator.implicit`` which root (`grader.expressions.implicit.Implicit`): the k-th
    in the unknown's declared interval, k chosen as a closed-form root would be (:func:`_select`:
    the one the motion reaches, or the only one), and the same k at the scene's values and on the
    parameter draws students get.
    """
    scene = evaluator.scene
    condition = _radicands_for_roots(condition)
    variable = _variable(evaluator, x)
    lo, hi = _root_interval(scene, variable, x, key)
    for other in scene.answers:
        used = other.expr.free_symbols | (set().union(*(e.free_symbols for e in other.where)) if other.where else set())
        if other is not spec and spec.symbol in used:
            raise SceneError(scene.source, key, f"the condition has no solution for {x} in closed form, and "
                                                f"answer '{other.name}' uses this one, which is only a number")
    value = evaluator.reduce(spec.expr, target | evaluator.parameters | {x}, f"answers ({spec.name}).expr",
                             readable=True)
    loose = sorted(str(s) for s in (condition.free_symbols | value.free_symbols) - evaluator.parameters - {x})
    if loose:
        raise SceneError(scene.source, key, f"the condition has no solution for {x} in closed form, and it "
                                            f"leaves {', '.join(loose)} without a number")
    base = _parameter_points(scene)[0]
    chosen = _implicit_root(evaluator, spec, condition, x, value, variable, base, (lo, hi), key)
    for point in _draws(scene):
        if _implicit_root(evaluator, spec, condition, x, value, variable, point, (lo, hi), key) != chosen:
            raise SceneError(scene.source, key, _depends_on_parameters(point))
    if variable[0] == "coordinate" and _one_motion(evaluator, spec, variable[1], condition):
        # Reached after the motion turns back: a velocity in the answer has the other sign there
        # (the same on every draw, or the file is refused).
        start = evaluator.motion_sign(variable[1], pushed=True)

        def turned_at(point):
            numbers = {s: sympy.Float(v, 30) for s, v in point.items()}
            roots = real_roots(_numeric(condition.xreplace(numbers), x), lo, hi)
            if start is None or chosen >= len(roots):
                return None
            return _turned_back_at(evaluator, variable[1], start, condition, roots[chosen], point, key)

        turned = turned_at(base)
        for point in _draws(scene):
            if turned_at(point) != turned:
                raise SceneError(scene.source, key, _depends_on_parameters(point))
        if turned is not None:
            value = evaluator.reduce(spec.expr, target | evaluator.parameters | {x}, f"answers ({spec.name}).expr",
                                     readable=True, signs=turned)
    evaluator.implicit[spec.name] = {"condition": sympy.sstr(condition), "unknown": str(x),
                                     "interval": [lo, hi], "root": chosen}
    return value


def _radicands_for_roots(condition: sympy.Expr) -> sympy.Expr:
    """The condition with each square-root factor written as its radicand: the same roots, where a sign
    change shows them (θ̇ = 0 from energy is √(f(θ)) = 0, which touches 0 at a turning point without
    crossing it, and a search for sign changes missed it).

    >>> th = sympy.Symbol("theta")
    >>> _radicands_for_roots(2*sympy.sqrt(sympy.cos(th) - sympy.cos(1)))
    2*cos(theta) - 2*cos(1)
    """
    numerator, denominator = sympy.fraction(sympy.together(condition))
    factors = [f.base ** (f.exp * 2) if f.is_Pow and f.exp.is_Rational and f.exp.q == 2 and f.exp > 0 else f
               for f in sympy.Mul.make_args(numerator)]
    return sympy.Mul(*factors) / denominator


def _root_interval(scene, variable, x, key: str) -> tuple[float, float]:
    """Where the unknown's roots are searched: its declared interval (an angle without one: one turn)."""
    if variable is None or variable[0] not in ("coordinate", "parameter"):
        raise SceneError(scene.source, key, f"the condition has no solution for {x} in closed form, and a "
                                            "velocity's root is not searched numerically")
    domain = variable[1].domain
    if domain.kind == "interval":
        return float(domain.lo), float(domain.hi)
    if variable[0] == "coordinate" and variable[1].dimension.is_dimensionless and domain.kind == "real":
        return -math.pi, math.pi
    raise SceneError(scene.source, key, f"the condition has no solution for {x} in closed form; to find its root "
                                        f"numerically, declare {x}'s domain as an interval [lo, hi]")


def _implicit_root(evaluator, spec, condition, x, value, variable, point: dict, interval, key: str) -> int:
    """Which root (from 0, in increasing order) of the condition in ``interval`` the answer is at."""
    scene = evaluator.scene
    numbers = {s: sympy.Float(v, 30) for s, v in point.items()}
    roots = real_roots(_numeric(condition.xreplace(numbers), x), *interval)
    where = ", ".join(f"{s} = {v:.4g}" for s, v in sorted(point.items(), key=lambda i: str(i[0])))
    if not roots:
        raise SceneError(scene.source, key, f"the condition has no root for {x} in [{interval[0]:g}, "
                                            f"{interval[1]:g}] at {where}")
    numeric = dict(enumerate(roots))
    floats = [sympy.Float(r, 17) for r in roots]
    indices, _ = _select(evaluator, spec, x, floats, value, variable, condition, numeric, point, key)
    index = indices[0]
    if _evaluate(value.xreplace({x: floats[index]}), point) is None:
        raise SceneError(scene.source, key, f"the answer has no real value at the root {x} = {roots[index]:.6g} "
                                            f"(at {where})")
    return index


def _draws(scene) -> list[dict]:
    """Parameter values as students get them (random ranges and choices; fixed values as given): the
    corners of the ranges (where a closed form most often stops holding), then random draws."""
    drawn = [p for p in scene.parameters.values() if p.draw is not None]
    if not drawn:
        return []
    base = _base_point(scene)
    ends = [sorted({min(_draw_values(p)), max(_draw_values(p))}) for p in drawn]
    points = []
    if math.prod(len(e) for e in ends) <= MAX_CORNERS:
        points = [{**base, **{p.symbol: v for p, v in zip(drawn, corner)}} for corner in itertools.product(*ends)]
    rng = numpy.random.default_rng(13)
    for _ in range(IMPLICIT_DRAWS):
        point = dict(base)
        for p in drawn:
            if "choices" in p.draw:
                point[p.symbol] = float(rng.choice(p.draw["choices"]))
            else:
                r = p.draw["random"]
                steps = int((r["max"] - r["min"]) / r["step"] + 1e-9)
                point[p.symbol] = float(r["min"] + r["step"] * rng.integers(0, steps + 1))
        points.append(point)
    # (a coarse grid or a few choices draw the same numbers again: each is confirmed once)
    unique = {tuple(sorted((str(s), v) for s, v in p.items())): p for p in points if _keeps_orders(scene, p)}
    return list(unique.values())


#: Corners of the random ranges tried (all of them for up to four randomised parameters).
MAX_CORNERS = 16


def _draw_values(p) -> list[float]:
    if "choices" in p.draw:
        return [float(c) for c in p.draw["choices"]]
    r = p.draw["random"]
    steps = int((r["max"] - r["min"]) / r["step"] + 1e-9)
    return [float(r["min"]), float(r["min"] + r["step"] * steps)]


def _keeps_orders(scene, point: dict) -> bool:
    """Whether ``point`` keeps every declared order (d below R): draws that break one are drawn again."""
    return all(point[p.symbol] < point[scene.parameters[p.below].symbol]
               for p in scene.parameters.values() if p.below is not None)


# -- choosing among roots ---------------------------------------------------------------------------
def _choose_root(evaluator, spec, condition, x, roots, value, key: str, at_rest: bool = False) -> list[sympy.Expr]:
    """The root the answer is at; several when the domain admits several and nothing decides
    (``at_rest``: the condition read at rest names an equilibrium, see :func:`_select`).

    The first is the reference, the others its alternatives. An answer that must be one value
    (see :func:`_must_be_one_value`) gets the error naming the roots instead. Never empty: where
    no root can be chosen the SceneError says so.
    """
    scene = evaluator.scene
    variable = _variable(evaluator, x)
    if not roots:
        raise SceneError(scene.source, key, f"the condition has no solution for {x} in closed form (asked as "
                                            'kind = "numeric", the answer is found numerically at each student\'s '
                                            "numbers)")
    chosen = base_count = None
    near = _parameter_points(scene)
    symbols = (condition.free_symbols | value.free_symbols) - {x}
    state: dict = {}
    for n, parameters in enumerate(near):
        point, numeric = _with_real_roots(evaluator, parameters, symbols, roots, variable)
        if not numeric and n >= 2:
            # (a student's draw: those numbers would have no answer)
            where = ", ".join(f"{s} = {v:.4g}" for s, v in sorted(parameters.items(), key=lambda i: str(i[0])))
            raise SceneError(scene.source, key, f"the condition has no real root for {x} at {where}, numbers a "
                                                "student may draw; narrow the random ranges so that every draw "
                                                "has an answer")
        if not numeric:
            free = _free_state(evaluator, parameters, symbols)
            where = (f"anywhere in its domain" if not free else
                     f"at any of the states tried ({', '.join(sorted(map(str, free)))} across their domains)")
            raise SceneError(scene.source, key,
                             f"the condition has no real root for {x} {where} (closed forms: "
                             f"{', '.join(sympy.sstr(r) for r in roots)})")
        state = state or {s: v for s, v in point.items() if s not in parameters}
        indices, group_of = _select(evaluator, spec, x, roots, value, variable, condition, numeric, point, key,
                                    at_rest)
        if chosen is None:
            chosen, base_count = indices, _distinct(numeric)
        elif _differ(chosen, indices, group_of):
            raise SceneError(scene.source, key, _depends_on_parameters(parameters))
    # Across the domains: a root formula may be the root the motion reaches on one side of m₁ = m₂
    # and another root on the other (Cardano's branches), so that a reference right at the scene's
    # values is wrong elsewhere. With as many roots there as at the scene's values, the same one must
    # be chosen; a point where the roots are others (no off-axis equilibrium below the critical ω),
    # or where nothing decides, says nothing. A parameter without a number gives no regime: across
    # its domain (_unvalued_scan) the same root is chosen wherever one is, however many roots there
    # are (the bead on a hoop turned at an omega with no number rests at the bottom below the
    # critical rate and off the axis above it).
    across = [(p, True) for p in _domain_points(scene, roots)]
    across += [(p, False) for p in (_unvalued_scan(scene) if len(roots) > 1 else ())]
    for parameters, as_many in across:
        point = _with_state(evaluator, {**parameters, **state}, symbols)
        numeric = _numeric_roots(roots, point, variable)
        if not numeric or (as_many and _distinct(numeric) != base_count):
            continue
        try:
            indices, group_of = _select(evaluator, spec, x, roots, value, variable, condition, numeric, point, key,
                                        at_rest)
        except SceneError:
            continue
        if len(indices) > 1 or (len(chosen) > 1 and set(indices) <= set(chosen)):
            # Nothing decides there, or at the scene's values, where every root is an answer: the
            # one decided here is among them (a top spun fast: slow and fast precession have its
            # sense; an oblate one drawn: only one has).
            continue
        if _differ(chosen, indices, group_of):
            raise SceneError(scene.source, key, _depends_on_parameters(parameters))
    if not chosen:
        # Nothing chosen (the answer has no real value at any admissible root, so no root to
        # choose by it): refused here, by name, never an empty choice for the caller to unpack.
        listed = ", ".join(sympy.sstr(r) for r in roots)
        raise SceneError(scene.source, key,
                         f"no root of the condition for {x} could be chosen for '{spec.name}': the answer has "
                         f"no real value at any admissible root ({listed})")
    return [roots[i] for i in chosen]


def _select(evaluator, spec, x, roots, value, variable, condition, numeric, point, key, at_rest: bool = False):
    """(indices of the roots the answer is at, their groups of equal value) at one parameter point
    (``at_rest``: the condition, read at rest, names an equilibrium)."""
    scene = evaluator.scene
    values = {}
    for index, r in numeric.items():
        v = _evaluate(value.xreplace({x: roots[index]}), point)
        if v is not None:
            values[index] = v
    groups = _groups(values)
    one_motion = variable is not None and variable[0] == "coordinate" and _one_motion(evaluator, spec, variable[1],
                                                                                      condition)
    if one_motion and (spec.kind == "small_oscillation" or at_rest) and len(groups) == 1:
        # An equilibrium need not be reached to oscillate about it, nor to be asked for (the unstable
        # relative equilibrium of a bead on a turning wire, which the motion from [initial] runs away
        # from); the motion only chooses among equilibria.
        index = min(groups[0])
    elif one_motion:
        # Even a single root must be reached: the motion may turn back before it.
        index = _first_reached(evaluator, variable[1], condition, numeric, point, key)
    elif (not at_rest and spec.kind != "small_oscillation" and len(groups) > 1
          and _family_motion(evaluator, spec, variable[1], condition)
          and (index := _reached_in_family(evaluator, variable[1], condition, numeric, point, key)) is not None):
        pass  # the motion at these parameter values reaches that root first (see _family_motion)
    elif len(groups) == 1:
        index = min(groups[0])
    elif variable is not None and variable[0] == "velocity" and _by_momentum(evaluator, variable[1], roots, numeric,
                                                                             groups, point) is not None:
        # The velocity of a cyclic coordinate: the orbit goes the way its conserved momentum says
        # (m r² (ψ̇ + Ω) of a steady orbit seen from a rotating frame, in which ψ̇ may start at 0 or
        # backwards), rather than the way u̇ starts.
        index = _by_momentum(evaluator, variable[1], roots, numeric, groups, point)
    elif variable is not None and variable[0] == "velocity" and _of_the_sign(evaluator, variable[1], numeric,
                                                                             groups) is not None:
        # The sign the motion from [initial] gives u̇ singles out one root (of several groups).
        index = _of_the_sign(evaluator, variable[1], numeric, groups)
    else:
        # Nothing decides: no [initial], or one whose momentum and velocity have the sign of several
        # roots (a top's slow and fast steady precessions, both in the sense it is launched in).
        reason = _must_be_one_value(scene, spec)
        if reason is not None:
            undecided = variable is not None and variable[0] == "velocity" and scene.initial
            raise SceneError(scene.source, key, f"{_ambiguous(x, roots, numeric, undecided)} ({reason})")
        index = None
    indices = [index] if index is not None else [min(g) for g in groups]

    def group_of(i):
        return frozenset(next((g for g in groups if i in g), {i}))

    return indices, group_of


def _by_momentum(evaluator, u, roots, numeric, groups, point) -> int | None:
    """The root of a cyclic coordinate's velocity u̇ at which its conserved momentum has the sign it
    has at the start (None when it is not cyclic, [initial] does not fix the momentum or that does not
    single out one root: then the velocity's sign at the start decides)."""
    if u not in evaluator.cyclic_coordinates():
        return None
    reduction = evaluator.reduction
    momentum = sympy.diff(reduction.lagrangian, u.dot)
    start = reduction.initial_value(momentum)
    p0 = _evaluate(start, point) if start is not None else None
    if not p0:
        return None
    matching = set()
    for index in numeric:
        p = _evaluate(momentum.xreplace({u.dot: roots[index]}), point)
        if p is not None and p * p0 > 0:
            matching.add(min(next((g for g in groups if index in g), {index})))
    return matching.pop() if len(matching) == 1 else None


def _differ(chosen, indices, group_of) -> bool:
    return sorted(map(sorted, map(group_of, chosen))) != sorted(map(sorted, map(group_of, indices)))


def _distinct(numeric: dict[int, float]) -> int:
    """How many different roots (formulas that agree are one root)."""
    return len(_groups(numeric))


def _must_be_one_value(scene, spec) -> str | None:
    """Why an answer cannot accept several values, or None when it can (then they are alternatives).

    A small-oscillation frequency or an extreme is about one point; a numeric answer is one
    number; an answer that a later answer or condition uses must give it one value.
    """
    reasons = {"small_oscillation": "a small-oscillation frequency is about one equilibrium",
               "maximum": "a largest value is one value", "minimum": "a smallest value is one value",
               "numeric": "a numeric answer is one number"}
    if spec.kind in reasons or spec.numeric is not None:
        return reasons.get(spec.kind, reasons["numeric"])
    for other in scene.answers:
        used = other.expr.free_symbols | (set().union(*(e.free_symbols for e in other.where)) if other.where else set())
        if other is not spec and spec.symbol in used:
            return f"answer '{other.name}' uses it, so it must be one value"
    return None


def _allowed_for_motion(evaluator, spec, condition) -> set:
    """The symbols the answer is written in, for telling one motion from a family: its in_terms_of;
    without one (the parameters, all of them), those the condition depends on, so that a condition
    in θ₀ through energy (the force on a bead released at ψ₀ vanishes at cos ψ = 2 cos ψ₀/3) is a
    formula over the family, as with in_terms_of = ["psi0"], while an equilibrium free of θ₀ stays
    the one the motion from [initial] chooses."""
    if spec.in_terms_of is not None:
        return evaluator.target(spec, default_state=False)
    if spec.kind == "small_oscillation" or condition is None:
        return set()
    return evaluator.parameters & condition.free_symbols


def _one_motion(evaluator, spec, u, condition=None) -> bool:
    """Whether the answer is about the one motion from [initial] (then that motion must reach it).

    An answer in terms of a parameter that [initial] uses (θ₀, v₀) is about a family of motions:
    its value at a configuration is a formula in that parameter, reachable for some of its values.
    """
    initial = evaluator.scene.initial
    if u.name not in initial:
        return False
    used = set().union(*(e.free_symbols for e in initial.values()))
    allowed = _allowed_for_motion(evaluator, spec, condition)
    # Another coordinate kept free in the answer (the block y1 beside y2 of an Atwood machine with
    # a spring) makes the root a formula over the states of several degrees of freedom, not a point
    # that the motion along u alone must reach.
    others = {v.symbol for v in evaluator.reduction.independent.values() if v.symbol != u.symbol}
    return not (used & allowed) and not (others & allowed)


def _family_motion(evaluator, spec, u, condition=None) -> bool:
    """Whether the answer is about a family of motions from [initial]: an answer in terms of a
    parameter that [initial] uses (θ₀, v₀), about a coordinate that [initial] gives.

    Its value at a configuration is a formula in that parameter, reachable for some of its values.
    Where the motion from [initial] does reach the root, at the scene's values and across the
    domains, it still decides which root and which way u moves there (a pendulum launched at w₀
    from the bottom meets θ = -0.2 on its way back, θ̇ < 0); where it reaches none, nothing does.
    """
    initial = evaluator.scene.initial
    if u.name not in initial or _one_motion(evaluator, spec, u, condition):
        return False
    used = set().union(*(e.free_symbols for e in initial.values()))
    allowed = _allowed_for_motion(evaluator, spec, condition)
    others = {v.symbol for v in evaluator.reduction.independent.values() if v.symbol != u.symbol}
    return bool(used & allowed) and not (others & allowed)


def _with_state(evaluator, point: dict, symbols: set) -> dict:
    """The parameter point, with numbers for the state variables an answer is written in.

    A steady orbit's φ̇(r) is checked at the radius [initial] gives, else at a generic one.
    """
    point = dict(point)
    initial = evaluator.scene.initial
    for k, s in enumerate(sorted(symbols - set(point), key=str)):
        given = initial.get(s.name)
        value = _evaluate(given, point) if given is not None else None
        point[s] = value if value else 0.7 + 0.13 * k
    return point


def _free_state(evaluator, parameters: dict, symbols: set) -> list:
    """The state variables among ``symbols`` that neither the parameter point nor [initial] gives a
    number: the answer is a formula over them (a steady precession's φ̇ at any tilt θ and spin ψ̇)."""
    initial = evaluator.scene.initial
    return sorted((s for s in symbols - set(parameters) if s.name not in initial), key=str)


def _state_candidates(evaluator, s) -> list[float]:
    """Numbers across the domain of a state variable (a coordinate's declared one; a velocity's real)."""
    domain = None
    for u in evaluator.reduction.independent.values():
        if s == u.symbol:
            domain = getattr(u, "domain", None)
    kind = domain.kind if domain is not None else "real"
    if kind == "interval":
        lo, hi = float(domain.lo), float(domain.hi)
        return [lo + (hi - lo) * f for f in (0.5, 0.2, 0.8, 0.05, 0.95, 0.35, 0.65)]
    magnitudes = [0.7, 3.0, 10.0, 100.0, 1000.0]
    if kind in ("positive", "nonnegative"):
        return magnitudes
    return [v for m in magnitudes for v in (m, -m)]


def _with_real_roots(evaluator, parameters: dict, symbols: set, roots, variable) -> tuple[dict, dict[int, float]]:
    """(the point, its real roots in the domain): the parameter point with numbers for the state an
    answer is written in, as :func:`_with_state` gives them, or, where the roots are not real there
    and the state is free (in in_terms_of, not given by [initial]), the first of a few states across
    the state variables' domains where they are. The roots of (A − C) cos θ φ̇² − C ψ̇ φ̇ + M g l = 0
    are real for a fast spin or cos θ < 0, not at ψ̇ = 0.7: "no real root anywhere" was said there."""
    point = _with_state(evaluator, parameters, symbols)
    numeric = _numeric_roots(roots, point, variable)
    free = _free_state(evaluator, parameters, symbols)
    if not numeric and not free:
        # None is real at the state [initial] gives, and the answer is a formula over that state: the
        # launch speed v0 at which a string goes slack at φ is real only for cos φ < 2/3, not at φ0 = 0.
        free = sorted((s for s in symbols - set(parameters) if s in evaluator.state_symbols()), key=str)
    if len(numeric) == len(roots) or not free:
        return point, numeric
    # Some roots are not real here: a state where more are. cos θ = g/(l φ̇²) of a conical pendulum,
    # beside θ = 0 and π, is real only where φ̇² ≥ g/l; dropped at a slower φ̇, the answer was cos θ = 1.
    best = (point, numeric)
    for numbers in itertools.islice(itertools.product(*(_state_candidates(evaluator, s) for s in free)), 400):
        trial = {**point, **dict(zip(free, numbers))}
        numeric = _numeric_roots(roots, trial, variable)
        if len(numeric) > len(best[1]):
            best = (trial, numeric)
            if len(numeric) == len(roots):
                break
    return best


def _ambiguous(x, roots, numeric, undecided: bool = False) -> str:
    listed = ", ".join(sympy.sstr(roots[i]) for i in sorted(numeric))
    if undecided:
        return (f"the condition has several roots for {x} with different answers ({listed}), and the motion from "
                f"[initial] gives more than one of them the sign it gives {x}; narrow the domain of the unknown")
    return (f"the condition has several roots for {x} with different answers ({listed}); narrow the domain "
            "of the unknown or give [initial] so that the motion decides")


def _of_the_sign(evaluator, u, numeric, groups) -> int | None:
    """The root of u̇ with the sign the motion from [initial] gives it, when exactly one group of
    equal roots has it; else None (no sign, none of that sign, or several: nothing decides)."""
    sign = evaluator.motion_sign(u, True)
    if sign is None:
        return None
    matching = [i for i, r in numeric.items() if r * sign > 0]
    if len({min(g) for g in groups for i in matching if i in g}) != 1:
        return None
    return matching[0]


def _variable(evaluator, x):
    for u in evaluator.reduction.independent.values():
        if x == u.symbol:
            return ("coordinate", u)
        if x == u.dot:
            return ("velocity", u)
    for p in evaluator.scene.parameters.values():
        if x == p.symbol:
            return ("parameter", p)
    return None


def _numeric_roots(roots, point, variable) -> dict[int, float]:
    """Real roots inside the unknown's domain, as numbers at ``point``."""
    result = {}
    for i, r in enumerate(roots):
        v = _evaluate(r, point)
        if v is None:
            continue
        if variable is not None and variable[0] in ("coordinate", "parameter") and not variable[1].domain.contains(v):
            # An angle's roots have been brought into its declared domain (see roots_in_domain): a
            # formula outside is not a root there, whatever its image.
            continue
        result[i] = v
    return result


def roots_in_domain(evaluator, condition: sympy.Expr, x: sympy.Symbol, roots: list[sympy.Expr]) -> list[sympy.Expr]:
    """The roots of a condition in an angle declared in an interval, brought into it: every image
    r + (2π/n)k inside the interval where the condition holds there (at both parameter points), none
    outside. A root in θ/2 (a spring to a point of a hoop: cos(θ/2) = c) is solved as 2 acos(±c) +
    4πk, which may lie outside [0, π) while its image by 2π is the root inside, or may not be one;
    the condition decides, numerically. A root sympy wrapped in a Piecewise whose other branches are
    nan takes the branch that holds at the parameter points. Other unknowns: the roots unchanged.
    """
    variable = _variable(evaluator, x)
    if variable is None:
        return roots
    points = [_with_state(evaluator, parameters, condition.free_symbols - {x})
              for parameters in _parameter_points(evaluator.scene)]
    roots = [_unwrapped(r, points) for r in roots]
    u = variable[1]
    if (variable[0] != "coordinate" or not u.dimension.is_dimensionless or u.domain.kind == "real"
            or not any(x in f.free_symbols for f in condition.atoms(*_TRIG))):
        return roots
    n = 1
    for f in condition.atoms(*_TRIG):
        ratio = sympy.cancel(f.args[0] / x)
        if x in f.free_symbols and ratio.is_Rational:
            n = math.lcm(n, int(abs(ratio.p)))
    step = 2 * sympy.pi / n
    if u.domain.kind != "interval":
        return _onto_half_line(u.domain, condition, x, roots, points, step)
    lo, hi = float(u.domain.lo), float(u.domain.hi)

    def holds(candidate, point) -> bool:
        return _holds(condition, x, candidate, point)

    result: list[sympy.Expr] = []
    seen: list[tuple[float, ...]] = []
    turn = 2 * math.pi

    def add(candidate, numbers, image: bool) -> None:
        # An image is a new root unless it is a kept one, or (a domain a full turn wide, [-π, π]) the
        # same configuration as a kept one, a whole turn away: -π beside π.
        def same(a: float, b: float) -> bool:
            gap = abs(a - b) / turn if image else abs(a - b)
            return abs(gap - round(gap)) <= 1e-9 * max(1.0, abs(a)) and (image or round(gap) == 0)
        if not any(all(same(a, b) for a, b in zip(numbers, other)) for other in seen):
            seen.append(numbers)
            result.append(candidate)

    images = []
    for r in roots:
        values = [_evaluate(r, point) for point in points]
        if any(v is None for v in values):
            result.append(r)  # not real here: the choice of root says so, as before
            continue
        if all(lo <= v <= hi for v in values):
            add(r, tuple(values), image=False)
        width = float(step)
        first = math.ceil((lo - values[0]) / width)
        last = math.floor((hi - values[0]) / width)
        # (a domain of many periods, θ in [0, 10⁶]: the images nearest its low end; each costs a tidy-up and
        # checks, and one a whole turn away from a kept one is the same configuration)
        last = min(last, first + _MOST_IMAGES)
        images += [(r, k, tuple(v + k * width for v in values)) for k in range(first, last + 1) if k != 0]
    for r, k, numbers in images:  # after every root inside: those come first, as solved
        if not all(lo <= w <= hi for w in numbers):
            continue
        candidate = _tidy_inverse(r + k * step)
        if all(holds(candidate, point) for point in points):
            add(candidate, numbers, image=True)
    return result


# The most images of one root looked at in an angle's interval (a few turns' worth).
_MOST_IMAGES = 64


def _holds(condition, x, candidate, point) -> bool:
    """Whether ``condition`` vanishes at x = candidate: zero there, against its size a little to
    either side (30 digits: ~1e-27 at a simple root)."""
    at = _evaluate(condition.xreplace({x: candidate}), point)
    beside = [_evaluate(condition.xreplace({x: candidate + d}), point) for d in (sympy.Rational(1, 10**4),
                                                                                 -sympy.Rational(1, 10**4))]
    if at is None or any(v is None for v in beside):
        return False
    return abs(at) <= 1e-12 * max(abs(v) for v in beside)


def _onto_half_line(domain, condition, x, roots, points, step) -> list[sympy.Expr]:
    """The roots of a condition in an angle declared ``positive`` or ``nonnegative``, each inside:
    a root outside (θ = 0 for θ > 0; 2 acos c − 4π) is replaced by its least image r + (2π/n)k
    inside where the condition holds there (θ = 2π, the same configuration), and dropped where none
    does within two turns; never returned as it is. Several images inside the half-line are the
    same configuration turns apart: as for a real angle, solve's one root (brought inside) stands for
    them. Roots that coincide once inside are one."""
    result: list[sympy.Expr] = []
    seen: list[tuple[float, ...]] = []

    def add(candidate, numbers) -> None:
        if not any(all(abs(a - b) <= 1e-9 * max(1.0, abs(a)) for a, b in zip(numbers, other)) for other in seen):
            seen.append(numbers)
            result.append(candidate)

    width = float(step)
    for r in roots:
        values = [_evaluate(r, point) for point in points]
        if any(v is None for v in values):
            result.append(r)  # not real here: the choice of root says so, as before
            continue
        if all(domain.contains(v) for v in values):
            add(r, tuple(values))
            continue
        first = max(1, math.ceil(-max(values) / width))
        turns = 2 * round(2 * math.pi / width)
        for k in range(first, first + turns + 1):
            numbers = tuple(v + k * width for v in values)
            if not all(domain.contains(w) for w in numbers):
                continue
            candidate = _tidy_inverse(r + k * step)
            if all(_holds(condition, x, candidate, point) for point in points):
                add(candidate, numbers)
                break
    return result


def _unwrapped(root: sympy.Expr, points: list[dict]) -> sympy.Expr:
    """A Piecewise((r, cond), (nan, True)) from solve as r, where cond holds at every point."""
    def unwrap(piecewise):
        branches = [(e, c) for e, c in piecewise.args if e is not sympy.nan]
        if len(branches) != 1:
            return piecewise
        expr, cond = branches[0]
        for point in points:
            value = cond.xreplace({s: sympy.Float(v, 30) for s, v in point.items()})
            if value is not sympy.true:
                return piecewise
        return expr
    if not root.has(sympy.Piecewise):
        return root
    return root.replace(lambda e: isinstance(e, sympy.Piecewise), unwrap)


def _tidy_inverse(expr: sympy.Expr) -> sympy.Expr:
    """acos(−u) as π − acos(u), so that an image 2π − 2 acos(−c) reads 2 acos(c)."""
    return expr.replace(lambda e: isinstance(e, sympy.acos) and e.args[0].could_extract_minus_sign(),
                        lambda e: sympy.pi - sympy.acos(-e.args[0]))


def _groups(values: dict[int, float]) -> list[set[int]]:
    groups: list[tuple[float, set[int]]] = []
    for i, v in values.items():
        for value, members in groups:
            if abs(value - v) <= 1e-9 * max(1.0, abs(v)):
                members.add(i)
                break
        else:
            groups.append((v, {i}))
    return [members for _, members in groups]


def _evaluate(expr: sympy.Expr, point: dict) -> float | None:
    try:
        value = complex(sympy.N(expr.xreplace({s: sympy.Float(v, 30) for s, v in point.items()}), 30))
    except (TypeError, ValueError):
        return None
    if not math.isfinite(value.real) or abs(value.imag) > 1e-12 * max(1.0, abs(value.real)):
        return None
    return value.real


#: Points drawn across the parameters' domains to confirm the choice of root (see _choose_root).
DOMAIN_POINTS = 4


def _domain_points(scene, roots) -> list[dict]:
    """A few parameter points across the declared domains (seeded: the same every time), only when
    there are several roots to choose between."""
    if len(roots) < 2:
        return []
    return _domain_samples(scene)


#: Decades each side of its generic value that a parameter without a number is scanned over.
SCAN_DECADES = 3


def _unvalued_scan(scene) -> list[dict]:
    """Each parameter without a number (no value, no draw) scanned across its domain, the others at
    the scene's values: half-decades over ``SCAN_DECADES`` each side of its generic value on an
    unbounded domain (both signs on the real line), eight points across an interval.

    Such a parameter gives no regime: a choice made at its generic value (about 1, in the SI units of
    its dimension) is one of several. A bob launched at a v0 with no number goes over the top for
    v0 > 2√(gl), 6.3 m/s with g = 9.81 and l = 1, and generic values (0.5 to 3) never get there.
    """
    base = _base_point(scene)
    points = []
    for p in scene.parameters.values():
        if p.value is not None or p.draw is not None:
            continue
        if p.domain.kind == "interval":
            values = [p.domain.sample_stratum(numpy.random.default_rng(17 + j), j, 8) for j in range(8)]
        else:
            values = [base[p.symbol] * 10 ** (k / 2) for k in range(-2 * SCAN_DECADES, 2 * SCAN_DECADES + 1)]
            if p.domain.kind == "real":
                values += [-v for v in values]
        points += [{**base, p.symbol: v} for v in values if v != base[p.symbol]]
    return [point for point in points if _keeps_orders(scene, point)]


def _parameter_points(scene) -> list[dict]:
    """The points where a choice made in closed form must hold: the scene's values (or a generic
    point), a perturbed one, and the draws students get (:func:`_draws`, for randomised parameters).

    A choice made at the scene's values alone (the root, the extreme, the first root reached) is
    the reference for every student's numbers: a bob launched at v0 drawn from [3, 9] goes over the
    top for v0 > 2√(gl) and not below, and its least tension is another closed form on each side.
    Every draw must make the same choice, or the scene is refused, naming one that does not.
    """
    base = _base_point(scene)
    other = {}
    for p in scene.parameters.values():
        value = base[p.symbol] * 1.0137
        other[p.symbol] = value if p.domain.contains(value) else base[p.symbol]
    return [base, other] + _draws(scene)


def _base_point(scene) -> dict:
    """The scene's values; for a parameter without one, the middle of its draws (randomised) or a
    generic point of its domain, keeping the declared orders (d below R)."""
    rng = numpy.random.default_rng(7)
    base = {}
    for p in scene.parameters.values():
        base[p.symbol] = p.value if p.value is not None else p.domain.sample(rng)
        if p.value is None and p.draw is not None:
            base[p.symbol] = _middle_draw(p.draw)
    for p in scene.parameters.values():  # d declared below R: a generic point keeps the order
        big = scene.parameters[p.below] if p.below is not None else None
        if big is not None and not base[p.symbol] < base[big.symbol] and p.domain.contains(base[big.symbol]) \
                and big.domain.contains(base[p.symbol]):
            base[p.symbol], base[big.symbol] = base[big.symbol], base[p.symbol]
    return base


def _middle_draw(draw: dict) -> float:
    """A value students get from ``random = {min, max, step}`` or ``choices``: the middle one."""
    if "choices" in draw:
        choices = sorted(float(c) for c in draw["choices"])
        return choices[len(choices) // 2]
    r = draw["random"]
    steps = int((r["max"] - r["min"]) / r["step"] + 1e-9)
    return float(r["min"] + r["step"] * (steps // 2))


# -- following the motion ----------------------------------------------------------------------------
def _first_reached(evaluator, u, condition, numeric: dict[int, float], point: dict, key: str) -> int:
    """Which root the motion from [initial] reaches first (see the module notes)."""
    return _first_reached_on(evaluator, u, condition, numeric, point, key)[0]


def _first_reached_on(evaluator, u, condition, numeric: dict[int, float], point: dict, key: str) -> tuple[int, float]:
    """(which root the motion from [initial] reaches first, the direction u moves in as it gets there)."""
    scene = evaluator.scene
    u0 = float(sympy.N(scene.initial[u.name].xreplace({s: sympy.Float(v, 30) for s, v in point.items()})))
    periodic = not _bounded(u) and _periodic(condition, u.symbol)
    # The path depends on the motion only: remembered for the other answers and conditions.
    path = _path(evaluator, u, u0, point, key)
    best = None
    at_start = None  # a root at [initial] itself: the answer only when the motion reaches no other
    start = u0
    moving = _MOVING.get()
    for leg, (d, stop, _) in enumerate(path):
        if moving is not None and moving[0] == u.name and d != moving[1]:
            start = stop if stop is not None else start
            continue  # a moment asked moving the other way (θ̇ = −ω₀/2) is not on this leg
        for index, r in numeric.items():
            images = [r] if not periodic else _images_ahead(r, start, d, stop)
            for image in images:
                distance = d * (image - start)
                if leg == 0 and abs(distance) <= 1e-12 and at_start is None:
                    at_start = (index, d)
                if distance < -1e-12 or (distance <= 1e-12 and leg == 0):
                    continue  # behind (the start itself does not count: the motion leaves it)
                if stop is not None and distance > d * (stop - start) + 1e-12:
                    continue
                if best is None or distance < best[0]:
                    best = (distance, index)
        if best is not None:
            return best[1], d
        start = stop if stop is not None else start
    if at_start is not None:
        # launched from the top of a sphere, y = R only at the start: the value there, not a refusal
        return at_start
    stops = ", then ".join(f"{why} at {u.name} = {stop:.6g}" for _, stop, why in path if stop is not None)
    roots = ", ".join(f"{u.name} = {r:.6g}" for r in numeric.values())
    if path[-1][2] == LEAVES_THE_BRANCH:
        raise LeavesTheBranch(scene.source, key, _beyond_the_branch(evaluator, u, path[-1][1], "a root of the "
                                                                    f"condition ({roots})"))
    raise SceneError(scene.source, key,
                     f"the motion from [initial] {stops or 'runs away'} before it reaches a root of the "
                     f"condition ({roots})")


LEAVES_THE_BRANCH = "reaches the end of the solved constraints' branch"


class LeavesTheBranch(SceneError):
    """The motion from [initial] reaches the end of the branch the constraints were solved on (y =
    √(R² − x²) at x = R) before what is asked: beyond, no formula in the independent variables holds."""


def _beyond_the_branch(evaluator, u, where: float, what: str) -> str:
    return (f"the motion from [initial] reaches {u.name} = {where:.6g}, where the constraints as solved "
            f"({evaluator.reduction.branch_of}) change branch, before {what}: beyond it no formula in "
            f"{u.name} follows the motion. List in [coordinates] first the coordinate to keep (the engine "
            "solves for the last ones), so that the motion stays on one branch, or add a [parametrization] "
            "(an angle around a circle)")


def _path(evaluator, u, u0: float, point: dict, key: str) -> list[tuple[float, float | None, str]]:
    """The legs of the motion from u0 at ``point``: (direction, where it ends or None, why); the
    first leg ends where the motion turns back, leaves the domain or the constraints' branch; after a
    turn, one more leg. Remembered for the other answers and conditions (it depends on the motion only)."""
    paths = evaluator.__dict__.setdefault("_motion_paths", {})
    remembered = (u.name, tuple(sorted((str(s), v) for s, v in point.items())))
    if remembered not in paths:
        direction = _direction(evaluator, u, point)
        speed2 = _speed_squared(evaluator, u, point, key)
        end_of_branch = _end_of_branch(evaluator, u, point)
        path = []
        end, why = _travel(u, u0, direction, speed2, end_of_branch=end_of_branch)
        path.append((direction, end, why))
        if why == "turns back":
            other_end, other_why = _travel(u, end, -direction, speed2, skip=True, end_of_branch=end_of_branch)
            path.append((-direction, other_end, other_why))
        paths[remembered] = path
    return paths[remembered]


def motion_stays_on_the_branch(evaluator, spec) -> None:
    """LeavesTheBranch when the motion from [initial] reaches the end of the branch the constraints
    were solved on and the extreme's quantity is another function on the other branch: the largest
    Q_x of a bead on a Cartesian circle, written with x = √(R² − y²), came out 0 (the bead passes the
    bottom, where Q_x changes sign), while the largest Q_y is the same on both sides. Only for one
    coordinate with energy conserved (the path is known); otherwise nothing is said."""
    reduction = evaluator.reduction
    if reduction.branch_end is None or len(reduction.independent) != 1:
        return
    (u,) = reduction.independent.values()
    if u.name not in evaluator.scene.initial:
        return
    point = _parameter_points(evaluator.scene)[0]
    key = f"answers ({spec.name})"
    try:
        u0 = float(sympy.N(evaluator.scene.initial[u.name].xreplace({s: sympy.Float(v, 30) for s, v in point.items()})))
        path = _path(evaluator, u, u0, point, key)
    except (SceneError, TypeError, ValueError):
        return
    stop = next((stop for _, stop, why in path if why == LEAVES_THE_BRANCH), None)
    if stop is None:
        return
    # the quantity the extreme is taken of, as a function of the state
    function = evaluator.reduce(spec.expr, evaluator.parameters | evaluator.state_symbols() | {evaluator.scene.time},
                                key, readable=False)
    if _the_same_on_both_branches(reduction, function, point, u, u0):
        return
    raise LeavesTheBranch(evaluator.scene.source, key, _beyond_the_branch(evaluator, u, stop,
                                                                          "the extreme over the motion"))


def _the_same_on_both_branches(reduction, function: sympy.Expr, point: dict, u, u0: float) -> bool:
    """Whether ``function`` (of the state, on the branch taken) is the same with the branch's root
    negated, i.e. on the other branch, at states near the start: each root √B of the answer whose
    radicand B is a positive multiple of a branch radicand changes sign (odd powers of it only)."""
    numbers = {s: sympy.Float(v, 30) for s, v in point.items()}
    flipped = {}
    for p in function.atoms(sympy.Pow):
        if not (p.exp.is_Rational and p.exp.q == 2):
            continue
        for radicand in reduction.branch_radicands:
            if _positive_multiple(p.base, radicand, numbers, u.symbol, u0):
                flipped[p] = -p
                break
    if not flipped:
        return True
    other = function.xreplace(flipped)
    rng = numpy.random.default_rng(5)
    for _ in range(4):
        state = dict(numbers)
        for s in function.free_symbols - set(numbers):
            state[s] = sympy.Float(u0 * (1 + 0.01 * rng.uniform(-1, 1)) if s == u.symbol else rng.uniform(0.3, 2), 30)
        a, b = _evaluate(function, state), _evaluate(other, state)
        if a is None or b is None:
            continue
        if abs(a - b) > 1e-9 * max(1.0, abs(a), abs(b)):
            return False
    return True


def _positive_multiple(base: sympy.Expr, radicand: sympy.Expr, numbers: dict, x, x0: float) -> bool:
    """Whether base/radicand is one positive constant near x0 (so that √base = c √radicand)."""
    ratios = []
    for k in (-1, 0, 1):
        at = {**numbers, x: sympy.Float(x0 * (1 + 0.003 * k) + 1e-3 * k, 30)}
        b, r = _evaluate(base, at), _evaluate(radicand, at)
        if b is None or r is None or r == 0:
            return False
        ratios.append(b / r)
    return all(r > 0 for r in ratios) and max(ratios) - min(ratios) <= 1e-9 * max(abs(r) for r in ratios)


def _end_of_branch(evaluator, u, point: dict):
    """The float function of u that vanishes where the solved constraints' branch ends, or None (one
    branch, or a function of more than u at this point)."""
    end = evaluator.reduction.branch_end
    if end is None:
        return None
    numbers = end.xreplace({s: sympy.Float(v, 30) for s, v in point.items()})
    if numbers.free_symbols - {u.symbol}:
        return None
    return _numeric(numbers, u.symbol)


def _periodic(condition: sympy.Expr, x: sympy.Symbol) -> bool:
    """Whether x enters the condition only through sin, cos, tan of integer multiples of x."""
    atoms = [f for f in condition.atoms(*_TRIG) if x in f.free_symbols]
    if not all((f.args[0] / x).is_Integer for f in atoms):
        return False
    stripped = condition.xreplace({f: sympy.Dummy() for f in atoms})
    return x not in stripped.free_symbols


def _bounded(u) -> bool:
    return u.domain.kind == "interval" and (u.domain.hi - u.domain.lo) < 2 * math.pi + 1e-3


def _images_ahead(r: float, start: float, d: float, stop: float | None) -> list[float]:
    """Periodic images r + 2πk ahead of ``start`` in direction ``d``, up to ``stop`` (or one turn)."""
    k = math.floor(d * (r - start) / (2 * math.pi))
    first = r - d * 2 * math.pi * k
    images = [first - d * 2 * math.pi, first, first + d * 2 * math.pi]
    return [i for i in images if stop is None or d * (i - stop) <= 1e-12]


def _travel(u, u0: float, d: float, speed2, skip: bool = False, end_of_branch=None) -> tuple[float | None, str]:
    """Where the motion from u0 in direction d stops: a turning point, the domain's end, the end of the
    solved constraints' branch (where ``end_of_branch`` vanishes or stops being defined), or None."""
    limit = None
    if u.domain.kind == "interval":
        limit = u.domain.hi if d > 0 else u.domain.lo
    if speed2 is None:
        return (limit, "leaves the domain") if limit is not None else (None, "never turns back")
    step = (2 * math.pi if u.dimension.is_dimensionless else max(abs(u0), 1.0)) / _SCAN_STEPS
    turn = None if u.dimension.is_dimensionless else _nearby_turn(speed2, u0, d, step)
    if turn is not None:
        # A turn within a few steps (a block on a stiff spring swings over 20 µm; lengths in km): the
        # scan's steps are made a fraction of its distance, as they are of a metre's motion.
        step = turn / _SCAN_STEPS
    x, previous = u0, speed2(u0)
    # The scan has no fixed range: it goes on until the motion turns back or leaves the domain;
    # the step doubles every _SCAN_STEPS steps (a step a few thousandths of the distance covered),
    # so that a runaway motion costs O(log) blocks (it grew linearly: 800,000 steps, 0.7 s, to
    # find that a bead on a turning wire runs away).
    for k in range(1, 40 * _SCAN_STEPS):
        nxt = x + d * step * 2 ** (k // _SCAN_STEPS)
        if limit is not None and d * (nxt - limit) > 0:
            return limit, "leaves the domain"
        value = speed2(nxt)
        if end_of_branch is not None and (k > 1 or not skip):
            here, there = end_of_branch(x), end_of_branch(nxt)
            ends = math.isfinite(here) and here != 0 and (not math.isfinite(there) or here * there <= 0)
            # The branch ends between x and nxt (its function vanishes, or stops being defined, there),
            # unless energy turns the motion back inside the branch first (the test below).
            if ends and not (math.isfinite(value) and value < 0 and math.isfinite(there)):
                return _branch_end_between(end_of_branch, x, nxt), LEAVES_THE_BRANCH
        if math.isfinite(value) and value < 0 and (k > 1 or not skip):
            if math.isfinite(previous) and previous >= 0:
                from scipy.optimize import brentq  # here: importing scipy.optimize costs more than most derivations

                return brentq(speed2, min(x, nxt), max(x, nxt), xtol=1e-14), "turns back"
            return x, "turns back"
        x, previous = nxt, value
    return None, "never turns back"


#: Distances, halving from eight scan steps, at which a nearby turn is probed (down to 2^-60 of them).
_TURN_PROBES = 61


def _nearby_turn(speed2, u0: float, d: float, step: float) -> float | None:
    """The distance from u0 (direction d) to where u̇² first turns negative after it has grown positive,
    if that is within eight of the scan's ``step``s, probed at distances halving from there down to
    2^-60 of it; None otherwise.

    The scan's step is a fraction of a unit of u (a metre): a motion that turns back within a few steps
    of it was stepped over (a block on a spring of 10^7 N/m, or any scene with its lengths in km, was
    said to turn back at once, the way it came).
    """
    reach = 8 * step
    distances = [reach * 2.0 ** -k for k in range(_TURN_PROBES - 1, -1, -1)]
    # Moving: u̇² positive and growing at three distances in a row (near a start at a turning point,
    # the rounding of u̇² ≈ 0 gives either sign and no growth).
    growing, last = 0, 0.0
    for h in distances:
        value = speed2(u0 + d * h)
        if not math.isfinite(value):
            growing, last = 0, 0.0
        elif value > 0:
            # (once moving, u̇² may fall again before the turn: a spring past its rest point)
            growing = growing + 1 if value > last or growing >= 3 else 1
            last = value
        elif value < 0 and growing >= 3:
            return h
        else:
            growing, last = 0, 0.0
    return None


def _branch_end_between(end_of_branch, a: float, b: float) -> float:
    """Where ``end_of_branch`` vanishes between a and b (it may stop being defined past its zero)."""
    fa = end_of_branch(a)
    for _ in range(60):  # bisection: past the zero the function may be nan, which brentq cannot take
        m = 0.5 * (a + b)
        fm = end_of_branch(m)
        if math.isfinite(fm) and fm * fa > 0:
            a, fa = m, fm
        else:
            b = m
    return 0.5 * (a + b)


def energy_speed_squared(evaluator, u, key: str, readable: bool = True) -> sympy.Expr | None:
    """u̇² as a function of u from the conserved energy (and momenta) of the motion from [initial],
    or None when energy is not conserved or [initial] does not give it (``readable=False``: not
    tidied, to be evaluated numerically)."""
    reduction = evaluator.reduction
    h = reduction.jacobi_integral()
    if h is None or reduction.initial_value(h) is None:
        return None
    # Coordinates the motion leaves at rest (at a start where their acceleration vanishes) stay at
    # their start: u̇² along the motion has them so (an elastic pendulum hanging straight down). They
    # are put in the energy before it is solved for u̇²: a cross term u̇ v̇ in it (ż² on a saddle
    # z = (x² − y²)/(2a) has x y ẋ ẏ) vanishes with v̇, and energy is then a u̇² + c (it was refused,
    # and the motion in x along y = 0, turning back at v₀√(a/g), was said to run away).
    rest = {s: e for s, e in evaluator.resting_coordinates().items() if s not in (u.symbol, u.dot)}
    momenta = evaluator.momentum_substitution(set(), key)
    if rest:
        momenta = {**{v: e.xreplace(rest) for v, e in momenta.items()}, **rest}
    try:
        squared = evaluator.velocity_squared(u, key, momenta, readable=readable)
    except SceneError:
        return None
    return squared.xreplace(rest) if rest else squared


def _speed_squared(evaluator, u, point: dict, key: str):
    """u̇²(u) as a float function at ``point`` (numbers only: the form as solved will do, unless
    only tidying removes a variable from it)."""
    squared = energy_speed_squared(evaluator, u, key, readable=False)
    if squared is not None and squared.free_symbols - set(point) - {u.symbol}:
        squared = energy_speed_squared(evaluator, u, key)
    if squared is None or squared.free_symbols - set(point) - {u.symbol}:
        return None
    return _numeric(squared.xreplace({s: sympy.Float(v, 30) for s, v in point.items()}), u.symbol)


def _direction(evaluator, u, point: dict) -> float:
    initial = evaluator.scene.initial
    velocity = initial.get(u.dot.name)
    if velocity is not None:
        v = _evaluate(velocity, point)
        if v:
            return math.copysign(1.0, v)
    acceleration = evaluator.reduction.initial_value(evaluator.reduction.accelerations[u.ddot])
    if acceleration is not None:
        a = _evaluate(acceleration, point)
        if a is not None and abs(a) > 1e-12:
            return math.copysign(1.0, a)
    return 1.0


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


# -- small oscillations ------------------------------------------------------------------------------
#: CPU seconds for tidying a small-oscillation frequency at its equilibrium, and for each of its
#: square root's forms: at the root of a cubic (Cardano's, 458 operations for a particle on a cone
#: held by a −k/s attraction) tidying ran past the whole derivation's 60 s budget.
FREQUENCY_TIDY_S = 4.0
FREQUENCY_FORM_S = 1.0
QUICK_CANCEL_S = 0.5  # for an expression too long to tidy: whether it cancels to a short one


def tidied_within(expr: sympy.Expr, seconds: float) -> sympy.Expr:
    """``human_form(expr)`` if it finishes within ``seconds`` of CPU time, else ``expr`` as it is
    (a closed form all the same, only not tidied). Not tried past `TIDY_MAX_OPS` operations: no
    rewriting makes Cardano's root of a cubic readable, and trying spent the whole budget."""
    if sympy.count_ops(expr) > TIDY_MAX_OPS:
        # (unless it cancels to a short one: a rotating frame's 462 operations are √(3Ω² + k/m))
        cancelled = budget.attempt(lambda: sympy.cancel(expr), QUICK_CANCEL_S, fallback=lambda: expr)
        if sympy.count_ops(cancelled) > TIDY_MAX_OPS:
            return expr
    return budget.attempt(lambda: human_form(expr), seconds, fallback=lambda: expr)


def frequency_form(omega_squared: sympy.Expr) -> sympy.Expr:
    """ω = √(ω²) in its shortest form, each candidate under a budget: √(2g/(3(R − r))) as written,
    rather than sympy's √6·√g·√(1/(R − r))/3; the plain square root where tidying runs out."""
    plain = sympy.sqrt(omega_squared)
    if sympy.count_ops(omega_squared) > TIDY_MAX_OPS:
        return plain
    candidates = [tidied_within(plain, FREQUENCY_FORM_S),
                  budget.attempt(lambda: sympy.Pow(signs_in_front(sympy.factor(omega_squared)), sympy.S.Half,
                                                   evaluate=False), FREQUENCY_FORM_S, fallback=lambda: plain)]
    return min(candidates, key=lambda e: (sympy.count_ops(e), len(str(e))))


def _stiffness(evaluator, spec, key: str) -> sympy.Expr:
    """ω² = −∂ü/∂u at rest, from the solved equation of motion (linearisation)."""
    reduction = evaluator.reduction
    u = next((v for v in reduction.independent.values() if v.symbol == spec.expr), None)
    others = [v for v in reduction.independent.values() if v is not u]
    if u is None or others:
        raise SceneError(evaluator.scene.source, f"answers ({spec.name}).expr",
                         "small oscillations are computed for one degree of freedom; expr must be the "
                         "scene's one independent coordinate")
    rest = {v.dot: 0 for v in reduction.independent.values()}
    acceleration = reduction.accelerations[u.ddot]
    return sympy.cancel(-sympy.diff(acceleration, u.symbol).xreplace(rest))


def _rest_acceleration(evaluator, u) -> sympy.Expr:
    """ü of the one coordinate ``u`` at rest (its equation of motion, solved)."""
    rest = {v.dot: 0 for v in evaluator.reduction.independent.values()}
    return evaluator.reduction.accelerations[u.ddot].xreplace(rest)


def check_equilibrium(scene, key: str, u, acceleration: sympy.Expr, root: sympy.Expr, momenta: bool = False) -> None:
    """Refuse a point where ``u`` would not stay at rest: ``acceleration`` (ü at rest there) nonzero at a
    point of the parameters' values. ``momenta``: the other coordinates' velocities are those their
    conserved momenta from [initial] give (Routh's reduction)."""
    for point in _parameter_points(scene):
        value = _evaluate(acceleration, point)
        scale = max(1.0, abs(_evaluate(root, point) or 0.0))
        if value is not None and abs(value) > 1e-9 * scale:
            given = " with the conserved momenta from [initial]" if momenta else ""
            fix = "start [initial] on the steady motion, or name its condition" if momenta else "name its condition"
            raise SceneError(scene.source, key,
                             f"{u.name} = {sympy.sstr(root)} is not an equilibrium of the motion{given} "
                             f"({u.ddot.name} = {value:.6g} there at rest), so it has no small oscillations about "
                             f"it; {fix} (\"{u.ddot.name} = 0\")")


def _check_stable(scene, spec, omega_squared: sympy.Expr) -> None:
    for point in _parameter_points(scene):
        value = _evaluate(omega_squared, point)
        if value is not None and value < 0:
            raise SceneError(scene.source, f"answers ({spec.name}).where",
                             f"the equilibrium is unstable (ω² = {sympy.sstr(omega_squared)} < 0): there are no "
                             "small oscillations about it")
