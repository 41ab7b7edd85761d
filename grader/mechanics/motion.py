"""The motion from ``[initial]`` in closed form, q(t), where it has one in elementary functions.

Most motions have no closed form, but the first examples of a course do. The engine finds q(t)
from the ``[initial]`` state at t = 0 in three ways, tried in this order:

1. **Linear equations.** When every solved acceleration is linear in the independent coordinates
   and velocities (coefficients and forcing may depend on the parameters and t), ``sympy.dsolve``
   integrates them: a block on an incline (s̈ = g sin α), a bead on a rod a motor turns
   (r̈ = ω²r, or r̈ = ω²r − g sin ωt in a vertical plane), a rope sliding off a table
   (ẍ = g x/L), a spring on a support driven as A cos Ωt, coupled oscillators.
2. **Conserved momenta first.** The velocity of a cyclic coordinate is replaced by its conserved
   momentum (φ̇ = r₀²ω₀/r² for a free particle in polar coordinates); when the remaining
   accelerations are linear, they are integrated as in 1. Then u̇_c(t) follows from the momentum
   and u_c(t) = u_c(0) + ∫₀ᵗ u̇_c dt.
3. **An energy quadrature.** With one coordinate q left and no explicit t, energy gives
   q̇² = v²(q) and t = s ∫_{q₀}^{q} dq'/√(v²(q')) (s the sign q̇ starts with, or that of q̈ from
   rest; an integrand in cos q alone also in w = sin(q/2), where the tautochrone's is elementary).
   When sympy integrates it, t(q) is known in closed form; when it also solves t = t(q)
   for q, so is q(t) (r = r₀√(1 + ω₀²t²) for the free particle). The quadrature follows the
   motion only until it turns back; a closed form that goes on matching the motion beyond the
   turning point is kept, others are refused. A motion that starts at rest at an equilibrium has
   no such quadrature (from there, it takes unbounded time to leave).

Every closed form is confirmed against a numerical integration (scipy's ``solve_ivp``) of the
solved accelerations at the scene's parameter values before it is accepted; one that disagrees
is refused. Every ``dsolve``, ``integrate`` and ``solve`` runs under a CPU-time budget
(:mod:`grader.mechanics.budget`).

Everything else (a pendulum, whose quadrature is an elliptic integral; a double pendulum) is
refused with a :class:`SceneError` naming the answer, the acceleration that is not linear and in
what, and what the instructor can ask instead. An answer may then be a value as a function of
time (``in_terms_of = [..., "t"]`` without the coordinate) or the time at which a condition
holds (``expr = "t"``, ``where = "r = L"``; see :mod:`grader.mechanics.special_values`), which
needs only t(q) from the quadrature, not its inverse.

Examples
--------
>>> from grader.mechanics.lagrange import derive
>>> from grader.mechanics.scene import load_scene
>>> derive(load_scene("tests/mechanics/scenes/bead_rotating_rod.toml")).answers["radius_in_time"]
r0*cosh(omega*t)
>>> derive(load_scene("tests/mechanics/scenes/free_particle_polar.toml")).answers["distance_in_time"]
r0*sqrt(omega0**2*t**2 + 1)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import sympy
from sympy.simplify.simplify import exptrigsimp

from grader.mechanics import budget
from grader.mechanics.scene import SceneError
from grader.mechanics.simplification import human_form

__all__ = ["Quadrature", "motion_in_time", "numeric_motion", "quadrature"]

_DSOLVE_BUDGET_S = 4.0
_INTEGRATE_BUDGET_S = 4.0
_CHEAP_INTEGRATE_BUDGET_S = 1.0  # the quadrature without Meijer G-functions, tried first
_SOLVE_BUDGET_S = 3.0
_NUMERIC_BUDGET_S = 6.0
_RTOL = 1e-6  # closed form against the numerical integration, relative to the largest value seen
_SAMPLES = 9
_ASK_INSTEAD = ("ask instead for a value at a state (in_terms_of the coordinates and velocities, without t) "
                "or for a value where a condition holds (where = \"...\")")


def motion_in_time(evaluator, key: str) -> dict[sympy.Symbol, sympy.Expr]:
    """``{u: u(t), u̇: u̇(t)}`` for the independent coordinates (computed once per scene).

    Raises :class:`SceneError` for ``key`` naming what stops it: an acceleration that is not
    linear in the state and no elementary quadrature, a coordinate or velocity that ``[initial]``
    does not give, a system ``dsolve`` cannot integrate within its budget, a closed form that a
    numerical integration does not confirm.
    """
    result = _cached(evaluator, "motion", lambda: _integrate(evaluator))
    if isinstance(result, SceneError):
        raise SceneError(evaluator.scene.source, key, result.problem)
    return result


def cyclic_motion_in_time(evaluator) -> dict[sympy.Symbol, sympy.Expr]:
    """``{u: u(t), u̇: u̇(t)}`` for the cyclic coordinates alone whose conserved momentum gives their
    velocity free of the rest of the state (a pair of pucks' centre of mass, X = X₀ + V t, however the
    spring between them swings; a falling stick's foot, x = x₀, while θ(t) has no closed form),
    confirmed by a numerical integration; ``{}`` where there is none or it is not confirmed."""
    def compute():
        motion: dict = {}
        _cyclic_in_time(evaluator, _plan(evaluator), motion)
        if motion:
            _confirm(evaluator, motion, "the closed form")
        return motion

    result = _cached(evaluator, "cyclic motion", compute)
    return {} if isinstance(result, SceneError) else result


@dataclass
class Quadrature:
    """t(q) = sign · (G(q) − G(q₀)) for one coordinate ``u``, from q̇² = ``speed_squared``(q)."""

    u: object
    sign: int
    speed_squared: sympy.Expr
    time: sympy.Expr  # t as a function of u.symbol, valid until the motion first turns back
    momenta: dict


def quadrature(evaluator, key: str) -> Quadrature:
    """The energy quadrature t(q) of a one-coordinate autonomous motion (computed once per scene).

    Raises :class:`SceneError` for ``key`` when the motion is not of that kind or the integral
    is not elementary (see the module notes).
    """
    result = _cached(evaluator, "quadrature", lambda: _quadrature(evaluator, _plan(evaluator)))
    if isinstance(result, SceneError):
        raise SceneError(evaluator.scene.source, key, result.problem)
    return result


def _cached(evaluator, name: str, compute):
    cache = evaluator.__dict__.setdefault("_motion_cache", {})
    if name not in cache:
        try:
            cache[name] = compute()
        except SceneError as exc:
            cache[name] = exc
    return cache[name]


# -- which kind of motion ---------------------------------------------------------------------------
@dataclass
class _Plan:
    independent: list
    momenta: dict  # cyclic velocity -> its value from the conserved momentum, in the other state
    rest: list  # the coordinates left once the cyclic ones are taken out
    accelerations: dict  # u -> ü of the rest, momenta substituted


def _plan(evaluator) -> _Plan:
    def compute():
        reduction = evaluator.reduction
        independent = list(reduction.independent.values())
        try:
            momenta = evaluator.momentum_substitution(set(), "")
        except SceneError:
            momenta = {}
        rest = [u for u in independent if u.dot not in momenta]
        accelerations = {}
        for u in rest:
            a = reduction.accelerations[u.ddot]
            if momenta:
                substituted = a.xreplace(momenta)
                a = budget.attempt(lambda: sympy.cancel(substituted), 1.0, fallback=lambda: substituted)
            accelerations[u] = a
        return _Plan(independent, momenta, rest, accelerations)

    return _cached(evaluator, "plan", compute)


def _integrate(evaluator) -> dict[sympy.Symbol, sympy.Expr]:
    reduction = evaluator.reduction
    independent = list(reduction.independent.values())
    state = [s for u in independent for s in (u.symbol, u.dot)]
    if all(_linear(reduction.accelerations[u.ddot], state) for u in independent):
        # 1. Linear as it stands.
        motion = _dsolve(evaluator, independent, {u: reduction.accelerations[u.ddot] for u in independent})
    else:
        plan = _plan(evaluator)
        rest_state = [s for u in plan.rest for s in (u.symbol, u.dot)]
        if plan.momenta and all(_linear(plan.accelerations[u], rest_state) for u in plan.rest):
            # 2. Linear once the conserved momenta are substituted.
            motion = _dsolve(evaluator, plan.rest, plan.accelerations) if plan.rest else {}
        else:
            # 3. One coordinate, energy conserved: the quadrature, then its inverse.
            # Through the cache: a time asked after q(t) is refused reuses the same quadrature.
            quad = quadrature(evaluator, "")
            motion = _invert(evaluator, quad)
        _cyclic_in_time(evaluator, plan, motion)
    _confirm(evaluator, motion, "the closed form")
    return motion


def _refusal(evaluator, plan: _Plan, reason: str) -> SceneError:
    """No closed form in elementary functions: which acceleration is nonlinear in what, and why."""
    scene = evaluator.scene
    rest_state = [s for u in plan.rest for s in (u.symbol, u.dot)]
    parts = []
    for u in plan.rest:
        culprits = _nonlinear_in(plan.accelerations[u], rest_state)
        if culprits:
            shown = sympy.sstr(plan.accelerations[u])
            shown = f"{u.ddot.name} = {shown}" if len(shown) <= 100 else u.ddot.name
            listed = culprits[0] if len(culprits) == 1 else f"{', '.join(culprits[:-1])} and {culprits[-1]}"
            parts.append(f"{shown} is nonlinear in {listed}")
    after = ""
    if plan.momenta:
        cyclic = ", ".join(u.name for u in plan.independent if u.dot in plan.momenta)
        after = f" (after the conserved momentum of {cyclic} is substituted)"
    nonlinear = "; ".join(parts) or "the equations of motion are not linear"
    return SceneError(scene.source, "",
                      f"the motion has no closed form in elementary functions: {nonlinear}{after}, {reason}")


def _linear(expr: sympy.Expr, state: list[sympy.Symbol]) -> bool:
    """Whether expr is a polynomial of degree at most one in the state variables."""
    present = [s for s in state if s in expr.free_symbols]
    if not present:
        return True
    try:
        return sympy.Poly(sympy.expand(expr), *present).total_degree() <= 1
    except sympy.PolynomialError:
        return False


def _nonlinear_in(expr: sympy.Expr, state: list[sympy.Symbol]) -> list[str]:
    """The state variables expr is not linear in (r in r₀⁴ω₀²/r³; θ in sin θ; r and φ̇ in r φ̇²)."""
    present = [s for s in state if s in expr.free_symbols]
    found = []
    for s in present:
        derivative = sympy.diff(expr, s)
        if any(w in derivative.free_symbols for w in present):
            found.append(s.name)
    return found


# -- 1 and 2: linear equations ----------------------------------------------------------------------
def _initial(evaluator, symbol):
    value = evaluator.reduction.initial_value(symbol)
    if value is None:
        state = ", ".join(s.name for u in evaluator.reduction.independent.values() for s in (u.symbol, u.dot))
        raise SceneError(evaluator.scene.source, "", f"the motion in time needs [initial] values for {state}")
    return value


def _dsolve(evaluator, coordinates: list, accelerations: dict) -> dict[sympy.Symbol, sympy.Expr]:
    scene = evaluator.scene
    t = scene.time
    direct = _integrated_twice(evaluator, coordinates, accelerations)
    if direct is not None:
        return direct
    functions = {u.name: sympy.Function(u.name)(t) for u in coordinates}
    to_functions = {}
    for u in coordinates:
        to_functions[u.symbol] = functions[u.name]
        to_functions[u.dot] = functions[u.name].diff(t)
    equations = [sympy.Eq(functions[u.name].diff(t, 2), accelerations[u].xreplace(to_functions))
                 for u in coordinates]
    initial = {}
    for u in coordinates:
        initial[functions[u.name].subs(t, 0)] = _initial(evaluator, u.symbol)
        initial[functions[u.name].diff(t).subs(t, 0)] = _initial(evaluator, u.dot)

    def solve():
        if len(equations) == 1:
            return [sympy.dsolve(equations[0], functions[coordinates[0].name], ics=initial)]
        return sympy.dsolve(equations, list(functions.values()), ics=initial)

    def attempt():
        try:
            return solve()
        except (NotImplementedError, ValueError, TypeError):
            return None

    with budget.step("integrating the motion in time"):
        solutions = budget.attempt(attempt, _DSOLVE_BUDGET_S, fallback=lambda: None)
    if not solutions:
        raise SceneError(scene.source, "", "the equations of motion are linear, but sympy finds no closed form of "
                                           f"the motion in t within {_DSOLVE_BUDGET_S:g} s")
    # A coefficient that varies in t (r̈ = r (ω₀ + α t)², a rod spun up at a constant rate) has no
    # closed form; dsolve then answers with a truncated power series, r(t) = … + O(t⁶), not a motion.
    if any(s.rhs.has(sympy.Order) for s in solutions):
        raise SceneError(scene.source, "", "the equations of motion are linear, but their coefficients vary in t "
                                           "and sympy finds only a truncated power series of the motion in t, "
                                           "no closed form")
    by_function = {s.lhs: s.rhs for s in solutions}
    motion = {}
    for u in coordinates:
        q = _readable(by_function[functions[u.name]])
        motion[u.symbol] = q
        motion[u.dot] = _readable(sympy.diff(q, t))
    return motion


def _integrated_twice(evaluator, coordinates: list, accelerations: dict) -> dict[sympy.Symbol, sympy.Expr] | None:
    """u(t) = u₀ + u̇₀ t + ∫∫ ü where every ü depends on t and the parameters only (a spool rolling
    down an incline: ü constant; a cylinder on a plank driven as A sin Ωt): dsolve took 1.4 s to
    find s₀ + g sin α t²/3. None where an acceleration depends on the state, or an integral does not
    come out in closed form."""
    t = evaluator.scene.time
    state = evaluator.state_symbols()
    if any(accelerations[u].free_symbols & state for u in coordinates):
        return None
    if not any(accelerations[u].has(t) for u in coordinates):
        return _uniformly_accelerated(evaluator, coordinates, accelerations)
    s = sympy.Dummy("s", real=True)
    positions = {}

    def integrate():  # under dsolve's budget: an integrand of t can be as hard as the equation
        for u in coordinates:
            velocity = _initial(evaluator, u.dot) + sympy.integrate(accelerations[u].xreplace({t: s}), (s, 0, t))
            positions[u] = _initial(evaluator, u.symbol) + sympy.integrate(velocity.xreplace({t: s}), (s, 0, t))

    budget.attempt(integrate, _DSOLVE_BUDGET_S, fallback=lambda: None)
    if len(positions) < len(coordinates) or any(p.has(sympy.Integral) for p in positions.values()):
        return None
    motion = {}
    for u, position in positions.items():
        motion[u.symbol] = _readable(position)
        motion[u.dot] = _readable(sympy.diff(motion[u.symbol], t))
    return motion


def _uniformly_accelerated(evaluator, coordinates: list, accelerations: dict) -> dict[sympy.Symbol, sympy.Expr]:
    """u(t) = u₀ + u̇₀ t + ü t²/2 for constant accelerations, over the readable form of ü (the one
    its own answer has): a wedge with a block on it and another hanging took 0.6 s to integrate and
    tidy the four polynomials whole."""
    t = evaluator.scene.time
    motion = {}
    for u in coordinates:
        acceleration = human_form(accelerations[u])
        start, speed = _initial(evaluator, u.symbol), _initial(evaluator, u.dot)
        motion[u.symbol] = start + speed * t + acceleration * t**2 / 2
        motion[u.dot] = speed + acceleration * t
    return motion


def _cyclic_in_time(evaluator, plan: _Plan, motion: dict) -> None:
    """u̇_c(t) from the conserved momentum, and u_c(t) = u_c(0) + ∫₀ᵗ u̇_c dt when that is elementary."""
    t = evaluator.scene.time
    tau = sympy.Dummy("tau", real=True)
    for u in plan.independent:
        if u.dot not in plan.momenta:
            continue
        velocity = _readable(plan.momenta[u.dot].xreplace(motion))
        if any(s in velocity.free_symbols for s in evaluator.state_symbols()):
            continue  # the rest of the motion is not known in time
        motion[u.dot] = velocity
        start = evaluator.reduction.initial_value(u.symbol)
        if start is None:
            continue
        integrand = velocity.xreplace({t: tau})

        def integrate():
            try:
                return sympy.integrate(integrand, (tau, 0, t))
            except (NotImplementedError, ValueError, TypeError):
                return None

        with budget.step(f"integrating {u.dot.name} in time"):
            integral = budget.attempt(integrate, _INTEGRATE_BUDGET_S, fallback=lambda: None)
        if integral is not None and not integral.has(sympy.Integral):
            point = _point(evaluator)
            integral = _branch(integral, {**point, t: 1.0})
            motion[u.symbol] = _readable(start + integral)


# -- 3: the energy quadrature -------------------------------------------------------------------------
def _quadrature(evaluator, plan: _Plan) -> Quadrature:
    scene = evaluator.scene
    t = scene.time
    if len(plan.rest) != 1:
        names = ", ".join(u.name for u in plan.rest)
        left = "left once the conserved momenta are used" if plan.momenta else "and no conserved momentum"
        raise _refusal(evaluator, plan,
                       f"and with {len(plan.rest)} coordinates ({names}) {left}, energy alone does not reduce "
                       f"it to a quadrature; {_ASK_INSTEAD}")
    u = plan.rest[0]
    if t in plan.accelerations[u].free_symbols:
        raise _refusal(evaluator, plan,
                       f"and it depends on t (a driven motion), so energy is not conserved and gives no "
                       f"quadrature t = ∫ d{u.name}/{u.dot.name}; {_ASK_INSTEAD}")
    sign = evaluator.motion_sign(u)
    if sign is None:
        if _at_rest_in_equilibrium(evaluator, u):
            raise _refusal(evaluator, plan,
                           f"and the motion from [initial] starts at rest at an equilibrium ({u.ddot.name} = 0 "
                           f"there): it stays there, and pushed away it takes unbounded time to leave, so the "
                           f"quadrature t = ∫ d{u.name}/{u.dot.name} diverges; {_ASK_INSTEAD}")
        raise _refusal(evaluator, plan,
                       f"and [initial] does not fix the direction in which {u.name} starts to move; {_ASK_INSTEAD}")
    try:
        squared = evaluator.velocity_squared(u, "", plan.momenta)
    except SceneError as exc:
        raise _refusal(evaluator, plan, f"and energy gives no quadrature ({exc.problem}); {_ASK_INSTEAD}") from None
    q = u.symbol
    integrand = 1 / sympy.sqrt(squared)
    shown = f"t = ∫ d{u.name}/√({sympy.sstr(squared)})"

    def integrate(options):
        try:
            return sympy.integrate(integrand, q, **options)
        except (NotImplementedError, ValueError, TypeError):
            return None

    # The cheap route first: sympy tries Meijer G-functions before its manual integration, and they
    # cost most of the time on an elementary integrand (a second for the radial fall's
    # √(r/(r₀ − r))) and return a Piecewise over both sides of a branch point. Without them, an
    # antiderivative that does not follow the motion, or none, sends us on to everything sympy has.
    # Between the two, an integrand in cos q alone in half-angles: with w = sin(q/2), dq = 2 dw/cos(q/2) and
    # cos q = 1 − 2w², elementary where the direct one is not for sympy (a bead on a cycloid, ∫ √((1 + cos φ)/
    # (cos φ − cos φ₀)) dφ: the tautochrone). Only where cos(q/2) > 0 on q's whole domain.
    half_angle = _half_angle_integrand(squared, u)
    attempts = [(integrate, {"meijerg": False}, _CHEAP_INTEGRATE_BUDGET_S)]
    if half_angle is not None:
        attempts.append((half_angle, {"meijerg": False}, _CHEAP_INTEGRATE_BUDGET_S))
    attempts.append((integrate, {}, _INTEGRATE_BUDGET_S))
    refused, tried = None, []
    for method, options, seconds in attempts:
        with budget.step(f"integrating the energy quadrature in {u.name}"):
            antiderivative = budget.attempt(lambda: method(options), seconds, fallback=lambda: None)
        if antiderivative is None or antiderivative.has(sympy.Integral) or antiderivative in tried:
            continue
        tried.append(antiderivative)
        try:
            return _quadrature_from(evaluator, plan, u, sign, squared, antiderivative, shown)
        except SceneError as exc:
            refused = exc
    if refused is not None:
        raise refused
    elliptic = " (it is an elliptic integral)" if _elliptic(squared, q) else ""
    raise _refusal(evaluator, plan,
                   f"and the energy quadrature {shown} is not an elementary function{elliptic}: sympy "
                   f"finds no antiderivative (it tries for {_INTEGRATE_BUDGET_S:g} s); {_ASK_INSTEAD}")


def _half_angle_integrand(squared: sympy.Expr, u):
    """∫ dq/√(squared) as a function of options that integrates in w = sin(q/2) and returns G(sin(q/2)),
    or None: where squared is not a function of cos q alone, or q may leave (−π, π) (cos(q/2) > 0 there).

    >>> phi, g, a, c0 = sympy.symbols("phi g a c0", positive=True)
    >>> class U: symbol = phi; domain = type("D", (), {"kind": "interval", "lo": -3.1, "hi": 3.1})()
    >>> integrate = _half_angle_integrand(g*(sympy.cos(phi) - c0)/(a*(sympy.cos(phi) + 1)), U)
    >>> integrate({"meijerg": False}).has(sympy.asin)
    True
    """
    q = u.symbol
    domain = u.domain
    # (to 1e-3: [-3.1416, 3.1416] is how scenes write (−π, π))
    if domain.kind != "interval" or not (-math.pi - 1e-3 <= float(domain.lo) and float(domain.hi) <= math.pi + 1e-3):
        return None
    c = sympy.Dummy("c")
    in_cos = squared.xreplace({sympy.cos(q): c})
    if q in in_cos.free_symbols or c not in in_cos.free_symbols:
        return None
    w = sympy.Dummy("w", real=True)
    # Other cosines (of the start, cos φ₀ from energy) in half-angles too: the radicand is then
    # sin²(φ₀/2) − w², whose arcsine at the start is π/2 as it reads, not asin(√2 sin(φ₀/2)/√(1 − cos φ₀)).
    in_cos = in_cos.replace(lambda e: isinstance(e, sympy.cos), lambda e: 1 - 2 * sympy.sin(e.args[0] / 2) ** 2)
    radicand = sympy.factor(sympy.cancel((1 - w ** 2) * in_cos.xreplace({c: 1 - 2 * w ** 2})))

    # The start's sin(φ₀/2) as a plain symbol while integrating: sympy's integrator works through the
    # function's assumptions at every step, which made ∫ dw/√(s² − w²) cost 0.6 s of CPU instead of 0.05 s,
    # close enough to its 1 s budget that a loaded machine refused the tautochrone (a CI run did).
    constants = {f: sympy.Dummy(positive=True) if f.is_positive else sympy.Dummy(real=True)
                 for f in radicand.atoms(sympy.Function) if f.free_symbols and not f.has(w)}
    plain = radicand.xreplace(constants)
    back = {d: f for f, d in constants.items()}

    def integrate(options):
        try:
            antiderivative = sympy.integrate(2 / sympy.sqrt(plain), w, **options)
        except (NotImplementedError, ValueError, TypeError):
            return None
        if antiderivative.has(sympy.Integral):  # none found (an elliptic integral: a pendulum)
            return None
        return antiderivative.xreplace(back).xreplace({w: sympy.sin(q / 2)})

    return integrate


def _quadrature_from(evaluator, plan: _Plan, u, sign: int, squared: sympy.Expr, antiderivative: sympy.Expr,
                      shown: str) -> Quadrature:
    """t(q) from an antiderivative G: sign · (G(q) − G(q₀)), confirmed against the numerical motion."""
    q = u.symbol
    point = _point(evaluator)
    q0 = _initial(evaluator, q)
    ahead = _ahead(evaluator, u, sign, point)
    antiderivative = _branch(antiderivative, {**point, q: ahead})
    start = antiderivative.xreplace({q: q0})
    if start.has(sympy.nan, sympy.zoo, sympy.oo, -sympy.oo):
        start = budget.attempt(lambda: sympy.limit(antiderivative, q, q0, "+" if sign > 0 else "-"),
                               _SOLVE_BUDGET_S, fallback=lambda: None)
    if start is None or start.has(sympy.nan, sympy.zoo, sympy.Limit):
        raise _refusal(evaluator, plan, f"and the quadrature {shown} cannot be evaluated at the start "
                                        f"{u.name} = {sympy.sstr(q0)}; {_ASK_INSTEAD}")
    time = sign * (antiderivative - start)
    merged = budget.attempt(lambda: _merge_radicals(time), 1.0, fallback=lambda: time)
    time = min((human_form(time), human_form(merged)), key=lambda e: (sympy.count_ops(e), len(str(e))))
    quad = Quadrature(u, sign, squared, time, plan.momenta)
    _confirm_quadrature(evaluator, quad, point, ahead)
    return quad


def _merge_radicals(expr: sympy.Expr) -> sympy.Expr:
    """Terms over the same √B gathered, and B cancelled from their numerator where it divides it.

    sympy's antiderivatives leave r^{3/2}/√(r₀ − r) − r₀√r/√(r₀ − r), which is −√r √(r₀ − r):

    >>> r, r0 = sympy.symbols("r r0", positive=True)
    >>> _merge_radicals(r**sympy.Rational(3, 2)/sympy.sqrt(r0 - r) - r0*sympy.sqrt(r)/sympy.sqrt(r0 - r) + r0)
    -sqrt(r)*sqrt(-r + r0) + r0
    """
    groups: dict = {}
    for term in sympy.Add.make_args(sympy.expand(expr)):
        bases = [f.base for f in sympy.Mul.make_args(term)
                 if f.is_Pow and f.exp == -sympy.S.Half and not (f.base.is_Number or f.base.is_Symbol)]
        groups.setdefault(bases[0] if len(bases) == 1 else None, []).append(term)
    result = []
    for base, terms in groups.items():
        total = sympy.Add(*terms)
        if base is not None:
            numerator = sympy.cancel(sympy.expand(total * sympy.sqrt(base)))
            reduced = sympy.factor(sympy.cancel(numerator / base))
            if sympy.count_ops(reduced) <= sympy.count_ops(numerator):
                total = reduced * sympy.sqrt(base)
        result.append(total)
    return sympy.Add(*result)


def _at_rest_in_equilibrium(evaluator, u) -> bool:
    """Whether [initial] puts u at rest where ü = 0 (at the scene's parameter values)."""
    reduction = evaluator.reduction
    point = _point(evaluator)
    for expr in (reduction.initial_value(u.dot), reduction.initial_value(reduction.accelerations[u.ddot])):
        value = None if expr is None else _evaluate(expr, point)
        if value is None or abs(value) > 1e-12:
            return False
    return True


def _elliptic(squared: sympy.Expr, q: sympy.Symbol) -> bool:
    """Whether ∫ dq/√(squared) is elliptic: a polynomial of degree 3 or 4 in q, or ≥ 1 in cos q or sin q."""
    X = sympy.Dummy("X")
    for function in (sympy.cos, sympy.sin):
        rewritten = squared.xreplace({function(q): X})
        if rewritten != squared and q not in rewritten.free_symbols:
            try:
                return sympy.Poly(sympy.together(rewritten), X).degree() >= 1
            except sympy.PolynomialError:
                return False
    try:
        return sympy.Poly(squared, q).degree() in (3, 4)
    except sympy.PolynomialError:
        return False


def _ahead(evaluator, u, sign: int, point: dict) -> float:
    """A value of u on the first stretch of the motion, where the quadrature's branches are chosen."""
    run = numeric_motion(evaluator, point)
    turn = run.turning_time(u)
    when = run.t_end / 4 if turn is None else min(turn / 2, run.t_end / 4)
    return run.state(when)[u.symbol]


def _invert(evaluator, quad: Quadrature) -> dict[sympy.Symbol, sympy.Expr]:
    """q(t) from t = t(q), the root that follows the motion; refused when there is none."""
    scene = evaluator.scene
    u, t, q = quad.u, scene.time, quad.u.symbol
    plan = _plan(evaluator)

    def solve():
        try:
            return list(sympy.solve(sympy.Eq(quad.time, t), q))
        except (NotImplementedError, ValueError, TypeError):
            return None

    shown = f"t = {sympy.sstr(quad.time)}"
    inverse = _transcendental_in(quad.time, q)
    if inverse is not None:
        raise _refusal(evaluator, plan,
                       f"and the energy quadrature gives {shown} in closed form, but it cannot be solved for "
                       f"{u.name}(t) in elementary functions ({u.name} is both inside {sympy.sstr(inverse)} and "
                       f"outside it); ask for the time at which a condition holds (expr = \"t\", where = "
                       f"\"{u.name} = ...\"), or {_ASK_INSTEAD}")
    with budget.step(f"solving the quadrature for {u.name}(t)"):
        roots = budget.attempt(solve, _SOLVE_BUDGET_S, fallback=lambda: None)
    if not roots:
        raise _refusal(evaluator, plan,
                       f"and the energy quadrature gives {shown} in closed form, but sympy cannot solve it for "
                       f"{u.name}(t) within {_SOLVE_BUDGET_S:g} s; ask for the time at which a condition holds "
                       f"(expr = \"t\", where = \"{u.name} = ...\"), or {_ASK_INSTEAD}")
    point = _point(evaluator)
    run = numeric_motion(evaluator, point)
    turn = run.turning_time(u)
    sample = (run.t_end if turn is None else min(turn, run.t_end)) / 3
    candidates = []
    for root in roots:
        root = _branch(root, {**point, t: sample})
        value = _evaluate(root, {**point, t: sample})
        if value is not None and abs(value - run.state(sample)[q]) <= _RTOL * max(abs(value), 1e-12):
            candidates.append(root)
    if not candidates:
        raise _refusal(evaluator, plan,
                       f"and the energy quadrature gives {shown}, but no solution of it for {u.name}(t) follows "
                       f"the motion; ask for the time at which a condition holds (expr = \"t\"), or {_ASK_INSTEAD}")
    position = _readable(candidates[0])
    return {q: position, u.dot: _readable(sympy.diff(position, t))}


def _transcendental_in(expr: sympy.Expr, q: sympy.Symbol, functions: tuple = ()) -> sympy.Expr | None:
    """An inverse circular or hyperbolic function of q in ``expr`` when q is also outside it, else None
    (``functions``: these function classes instead).

    Then t = expr mixes q with a transcendental function of q, as Kepler's equation does
    (t = asin(√r) − √r √(1 − r) for a radial fall): it has no solution for q in elementary
    functions, and ``solve``, which would try for a while, is not asked. (A logarithm is left to
    it: log q + q = t has q = W(eᵗ).)

    >>> r = sympy.Symbol("r", positive=True)
    >>> _transcendental_in(sympy.asin(sympy.sqrt(r)) - sympy.sqrt(r)*sympy.sqrt(1 - r), r)
    asin(sqrt(r))
    >>> _transcendental_in(sympy.asin(r/2), r) is None, _transcendental_in(sympy.log(r) + r, r) is None
    (True, True)
    """
    inverses = sorted((f for f in expr.atoms(*(functions or _INVERSES)) if q in f.free_symbols),
                      key=sympy.default_sort_key)
    if inverses and q in expr.xreplace({f: sympy.Dummy() for f in inverses}).free_symbols:
        return inverses[0]
    return None


_INVERSES = (sympy.asin, sympy.acos, sympy.atan, sympy.acot, sympy.asec, sympy.acsc,
             sympy.asinh, sympy.acosh, sympy.atanh, sympy.acoth, sympy.asech, sympy.acsch)


def _confirm_quadrature(evaluator, quad: Quadrature, point: dict, ahead: float) -> None:
    """t(q) at a point of the first stretch equals the time the numerical motion gets there."""
    run = numeric_motion(evaluator, point)
    u = quad.u
    expected = run.time_at(u, ahead)
    value = _evaluate(quad.time, {**point, u.symbol: ahead})
    if expected is None or value is None or abs(value - expected) > _RTOL * max(abs(expected), 1e-12):
        raise SceneError(evaluator.scene.source, "",
                         f"the energy quadrature t = {sympy.sstr(quad.time)} disagrees with a numerical "
                         f"integration of the equations of motion at {u.name} = {ahead:.6g} (t = {value} against "
                         f"{expected}); refused rather than risk a wrong closed form")


# -- numbers --------------------------------------------------------------------------------------------
def _point(evaluator) -> dict:
    from grader.mechanics.special_values import _parameter_points

    return _parameter_points(evaluator.scene)[0]


def _evaluate(expr: sympy.Expr, point: dict) -> float | None:
    from grader.mechanics.special_values import _evaluate

    return _evaluate(expr, point)


def _branch(expr: sympy.Expr, point: dict) -> sympy.Expr:
    """expr with each Piecewise replaced by its piece that holds at ``point`` (numbers)."""
    if not expr.has(sympy.Piecewise):
        return expr
    numbers = {s: sympy.Float(v, 30) for s, v in point.items()}

    def piece(p):
        for value, condition in p.args:
            try:
                holds = bool(sympy.sympify(condition, strict=True).xreplace(numbers))
            except TypeError:
                continue
            if holds:
                return value
        return p

    return expr.replace(lambda e: isinstance(e, sympy.Piecewise), piece)


class _Run:
    """A numerical integration of the solved accelerations from [initial] at one parameter point."""

    def __init__(self, evaluator, point: dict, horizon: float | None = None):
        from scipy.integrate import solve_ivp

        reduction = evaluator.reduction
        t = evaluator.scene.time
        self.coordinates = list(reduction.independent.values())
        self.symbols = [s for u in self.coordinates for s in (u.symbol, u.dot)]
        numbers = {s: sympy.Float(v, 30) for s, v in point.items()}
        y0 = []
        for s in self.symbols:
            value = reduction.initial_value(s)
            if value is None and any(s == u.symbol for u in self.coordinates):
                value = sympy.Integer(0)  # a cyclic coordinate [initial] leaves out: nothing depends on it
            if value is None:
                raise SceneError(evaluator.scene.source, "", "the motion in time needs [initial] values for "
                                 + ", ".join(s.name for s in self.symbols))
            y0.append(float(sympy.N(value.xreplace(numbers))))
        # The accelerations come from the engine (built by our parser from a validated scene), never
        # from raw text, so lambdify's generated code is safe to compile.
        accelerations = [reduction.accelerations[u.ddot].xreplace(numbers) for u in self.coordinates]
        f = sympy.lambdify([t, *self.symbols], accelerations, modules="math")
        n = len(self.coordinates)

        def rhs(time, y):
            try:
                a = f(time, *y)
            except (ValueError, ZeroDivisionError, OverflowError):
                return [math.nan] * (2 * n)
            return _derivative(y, a, n)

        if horizon is None:
            horizon = _horizon(rhs, y0, n)
        events = []
        for i, u in enumerate(self.coordinates):
            lo = {"positive": 0.0, "nonnegative": 0.0}.get(u.domain.kind, u.domain.lo)
            hi = u.domain.hi
            for bound, outwards in ((lo, -1), (hi, 1)):
                if math.isfinite(bound):
                    def leave(time, y, i=i, bound=bound):
                        return y[2 * i] - bound
                    leave.terminal = True
                    # Only leaving counts: a start on the bound moving inwards (θ = 0 of a string
                    # winding on a post, θ ≥ 0) ended the run at t = 0.
                    leave.direction = outwards
                    events.append(leave)

        def blow_up(time, y):
            return 1e12 - max(abs(v) for v in y)
        blow_up.terminal = True
        events.append(blow_up)
        self.solution = solve_ivp(rhs, (0.0, horizon), y0, method="DOP853", rtol=1e-12, atol=1e-14,
                                  dense_output=True, events=events)
        self.t_end = float(self.solution.t[-1])
        self.y0 = y0
        if self.t_end <= 0:
            raise SceneError(evaluator.scene.source, "", "the equations of motion cannot be integrated "
                                                         "numerically from [initial] to confirm a closed form")

    def state(self, time: float) -> dict:
        values = self.solution.sol(time)
        return {s: float(values[i]) for i, s in enumerate(self.symbols)}

    def turning_time(self, u) -> float | None:
        """The first time after the start at which u̇ changes sign."""
        index = self.symbols.index(u.dot)
        times = self.solution.t
        values = self.solution.y[index]
        for k in range(1, len(times)):
            if values[k - 1] * values[k] < 0 and times[k - 1] > 0:
                return float(times[k])
        return None

    def time_at(self, u, value: float) -> float | None:
        """The first time u reaches ``value`` (from the dense output), or None."""
        from scipy.optimize import brentq

        index = self.symbols.index(u.symbol)
        times = self.solution.t
        values = self.solution.y[index] - value
        for k in range(1, len(times)):
            if values[k - 1] == 0 and k > 1:
                return float(times[k - 1])
            if values[k - 1] * values[k] < 0:
                return brentq(lambda s: self.solution.sol(s)[index] - value, times[k - 1], times[k], xtol=1e-15,
                              rtol=1e-14)
        return None


def _derivative(y, a, n) -> list[float]:
    """(q̇₁, q̈₁, q̇₂, q̈₂, ...) from the state and the accelerations; nan where they are not real."""
    result = []
    for i in range(n):
        value = a[i]
        result += [y[2 * i + 1], float(value) if not isinstance(value, complex) else math.nan]
    return result


def _horizon(rhs, y0, n) -> float:
    """A few natural times of the motion: 1/√|∂ü/∂q|, √(|q₀|/|ü₀|), |q̇₀|/|ü₀|, |q₀|/|q̇₀| (else 1)."""
    scales = []
    derivative = rhs(0.0, y0)
    for i in range(n):
        q, v, a = abs(y0[2 * i]), abs(y0[2 * i + 1]), abs(derivative[2 * i + 1])
        shifted = list(y0)
        step = 1e-6 * max(q, 1e-3)
        shifted[2 * i] += step
        k = abs(rhs(0.0, shifted)[2 * i + 1] - derivative[2 * i + 1]) / step
        for scale in (1 / math.sqrt(k) if k > 0 else 0, math.sqrt(q / a) if a > 0 else 0, v / a if a > 0 else 0,
                      q / v if v > 0 else 0):
            if math.isfinite(scale) and scale > 0:
                scales.append(scale)
    return 3 * max(scales) if scales else 1.0


def numeric_motion(evaluator, point: dict, horizon: float | None = None) -> _Run:
    """The numerical motion from [initial] at ``point`` (cached per point and horizon)."""
    cache = evaluator.__dict__.setdefault("_motion_cache", {}).setdefault("runs", {})
    key = (tuple(sorted((str(s), v) for s, v in point.items())), horizon)
    if key not in cache:
        with budget.step("integrating the motion numerically"):
            cache[key] = budget.attempt(lambda: _Run(evaluator, point, horizon), _NUMERIC_BUDGET_S,
                                        fallback=lambda: None)
    if cache[key] is None:
        raise SceneError(evaluator.scene.source, "",
                         f"the motion could not be integrated numerically within {_NUMERIC_BUDGET_S:g} s to "
                         "confirm its closed form")
    return cache[key]


def _confirm(evaluator, motion: dict, what: str) -> None:
    """Every closed form in ``motion`` against the numerical motion; SceneError on a disagreement."""
    point = _point(evaluator)
    run = numeric_motion(evaluator, point)
    t = evaluator.scene.time
    # A run that ended early (an event, or the step shrinking to nothing: a string wound up on its post,
    # θ̇ → ∞) is compared short of its end, where the closed form may already be past its own.
    ended = run.solution.status != 0
    times = [run.t_end * (k + 1) / (_SAMPLES + ended) for k in range(_SAMPLES)]
    turns = [run.turning_time(u) for u in run.coordinates]
    turns = [x for x in turns if x is not None]
    for symbol, closed in motion.items():
        numeric = [run.state(s)[symbol] for s in times]
        scale = max(max(abs(v) for v in numeric), 1e-12)
        for s, expected in zip(times, numeric):
            value = _evaluate(closed, {**point, t: s})
            if value is None or abs(value - expected) > _RTOL * max(abs(expected), scale):
                after = ""
                if turns and s > min(turns):
                    after = (f" (after the motion turns back at t ≈ {min(turns):.4g}: the quadrature covers only "
                             "the stretch before)")
                raise SceneError(evaluator.scene.source, "",
                                 f"{what} {symbol.name}(t) = {sympy.sstr(closed)} disagrees with a numerical "
                                 f"integration of the equations of motion at t = {s:.4g}{after}: {value} against "
                                 f"{expected}; refused rather than risk a wrong closed form")


def _readable(expr: sympy.Expr) -> sympy.Expr:
    """r₀ cosh ωt rather than r₀ e^{ωt}/2 + r₀ e^{−ωt}/2."""
    if expr.has(sympy.exp):
        # e^{±x} gathered into cosh x and sinh x first: when that removes every exponential and
        # shortens the form (an undamped motion), the exponential forms are not worth tidying
        # (human_form of them costs half a second each; s(t) of a bead on a turning wire).
        hyperbolic = budget.attempt(lambda: _hyperbolic(expr), 1.0, fallback=lambda: None)
        if (hyperbolic is not None and not hyperbolic.has(sympy.exp)
                and sympy.count_ops(hyperbolic) < sympy.count_ops(expr)):
            return min([hyperbolic, human_form(hyperbolic)], key=lambda e: (sympy.count_ops(e), len(str(e))))
    candidates = [human_form(expr)]
    if expr.has(sympy.exp):
        candidates.append(human_form(exptrigsimp(expr)))
        # exp(ωt) = cosh ωt + sinh ωt; simplify then gathers r₀ (e^{ωt} + e^{−ωt})/2 into r₀ cosh ωt.
        budget.attempt(lambda: candidates.append(sympy.simplify(sympy.expand(expr.rewrite(sympy.cosh)))),
                       1.0, fallback=lambda: None)
        # r₀ cosh ωt + g (sin ωt − sinh ωt)/(2ω²): each e^{±x} as cosh x ± sinh x, gathered by function.
        budget.attempt(lambda: candidates.append(_hyperbolic(expr)), 1.0, fallback=lambda: None)
    return min(candidates, key=lambda e: (sympy.count_ops(e), len(str(e))))


def _hyperbolic(expr: sympy.Expr) -> sympy.Expr:
    """expr with e^{±x} written as cosh x ± sinh x and the terms gathered by cosh and sinh.

    >>> g, w, r0, t = sympy.symbols("g omega r0 t", positive=True)
    >>> _hyperbolic((2*w**2*r0 - g)*sympy.exp(w*t)/(4*w**2) + (2*w**2*r0 + g)*sympy.exp(-w*t)/(4*w**2))
    -g*sinh(omega*t)/(2*omega**2) + r0*cosh(omega*t)
    """
    expanded = sympy.expand(expr.replace(lambda e: isinstance(e, sympy.exp),
                                         lambda e: sympy.cosh(e.args[0]) + sympy.sinh(e.args[0])))
    functions = sorted(expanded.atoms(sympy.cosh, sympy.sinh), key=str)
    gathered = sympy.collect(expanded, functions, evaluate=False)
    return sympy.Add(*[sympy.factor_terms(sympy.cancel(c)) * f for f, c in gathered.items()])
