"""Equivalence of equations and of systems of equations.

An equation of motion is right when it is the reference multiplied by a nonzero factor free of the
state: ``thetaddot + g/l*sin(theta) = 0``, ``l*thetaddot = -g*sin(theta)`` and
``m*l**2*thetaddot + m*g*l*sin(theta) = 0`` are one equation. A system is right when it spans the
same equations: the student's residuals are ``M @`` the reference's residuals for a matrix ``M``
that is invertible and free of the state.

Numerically: fix the parameters at a sample point, take ``k + 2`` states (``k`` equations), solve
``M`` from the first ``k`` states and check, in ball arithmetic, that the others satisfy
``S = M R`` and that ``det M != 0``. A state where ``S - M R`` provably excludes zero proves the
equations different; agreement at every parameter point to the required digits is the numeric
verdict.
"""

from __future__ import annotations

import math
import time

import flint
import sympy

from grader.answers.evaluate import SCALE, ArbBackend, Undefined, Unresolved, Unsupported, _log2_mag, compile_expr
from grader.answers.equivalence import (
    LOG2_10,
    Comparison,
    Compiled,
    Options,
    as_float,
)
from grader.answers.sampling import Sampler

__all__ = ["compare_equations", "state_symbols"]

STATE_KINDS = {"coordinate", "velocity", "acceleration", "multiplier", "force", "time", "answer"}


def state_symbols(variables: dict[str, dict], symbols: dict[str, sympy.Symbol], state: list[str] | None = None) -> set:
    """The variables a factor of an equation may not depend on.

    Taken from ``state`` when given, else from each variable's ``kind``; else by name: names
    ending in ``dot``/``ddot`` and any name ``q`` for which ``qdot`` exists. With no state at all,
    every variable counts, so that only constant factors are accepted (never too lenient).

    Examples
    --------
    >>> import sympy
    >>> names = ["m", "g", "l", "theta", "thetadot", "thetaddot"]
    >>> syms = {n: sympy.Symbol(n) for n in names}
    >>> sorted(s.name for s in state_symbols({n: {} for n in names}, syms))
    ['theta', 'thetaddot', 'thetadot']
    """
    if state:
        chosen = {symbols[n] for n in state if n in symbols}
    else:
        chosen = {symbols[n] for n, spec in variables.items() if n in symbols and (spec or {}).get("kind") in STATE_KINDS}
        if not chosen and not any((spec or {}).get("kind") for spec in variables.values()):
            names = set(symbols)
            for n in names:
                if n.endswith("dot") or f"{n}dot" in names:
                    chosen.add(symbols[n])
    return chosen or set(symbols.values())


def _residuals_equal_symbolically(ref: list[sympy.Expr], ans: list[sympy.Expr]) -> bool:
    if len(ref) != 1 or len(ans) != 1:
        return False
    # sympy's automatic canonical form only: expanding residuals costs more than the numeric check
    return ans[0] - ref[0] == 0 or ans[0] + ref[0] == 0


def compare_equations(
    reference: list[sympy.Expr],
    answer: list[sympy.Expr],
    parameters: Sampler,
    states: Sampler,
    options: Options = Options(),
    deadline: float | None = None,
    compiled_reference: list[Compiled] | None = None,
    answer_conditions: tuple = (),
) -> Comparison:
    """Compare systems of equations given as residuals (``lhs - rhs``).

    Parameters
    ----------
    reference, answer : list of sympy.Expr
        Residuals; each equation is ``residual = 0``.
    parameters, states : Sampler
        Points for the parameters and, separately, for the state variables.
    options : Options
        ``options.points`` parameter points are used, each with ``k + 2`` states.
    answer_conditions : tuple of sympy.Expr
        The answer's real domain as typed (`grader.expressions.Parsed.conditions`).

    Examples
    --------
    >>> import sympy
    >>> from grader.expressions import parse_domain
    >>> positive = parse_domain("positive")
    >>> g, l, m = sympy.symbols("g l m", positive=True)
    >>> th, thdd = sympy.symbols("theta thetaddot", real=True)
    >>> P = Sampler({g: positive, l: positive, m: positive}, seed=1)
    >>> S = Sampler({th: positive, thdd: positive}, seed=2)
    >>> ref = [thdd + g / l * sympy.sin(th)]
    >>> compare_equations(ref, [m*l**2*thdd + m*g*l*sympy.sin(th)], P, S).equivalent
    True
    >>> compare_equations(ref, [thdd + g / l * sympy.cos(th)], P, S).certainty
    'proved'
    """
    k = len(reference)
    if len(answer) != k:
        return Comparison(
            False,
            "proved",
            f"expected {k} equation{'s' * (k != 1)}, got {len(answer)}",
            evidence={"method": "count"},
        )
    if options.symbolic and not answer_conditions and _residuals_equal_symbolically(reference, answer):
        return Comparison(True, "proved", "the same equation, rearranged", evidence={"method": "symbolic"})
    if options.method != "arb":
        # the benchmark's fixed-precision methods only apply to single equations: compare the ratio
        return _compare_fixed_ratio(reference, answer, parameters, states, options)
    backend = options.backend()
    refs = compiled_reference or [Compiled(r, backend) for r in reference]
    anss = [Compiled(a, backend, answer_conditions) for a in answer]
    target = options.digits * LOG2_10
    agreed, digits_seen = 0, math.inf
    # each parameter point checks k + 2 states, so half as many parameter points as expression points
    needed = max(3, options.points // 2)
    for p in range(needed * 2):
        outcome = _one_parameter_point(refs, anss, parameters, states, p, target, options, deadline)
        kind = outcome[0]
        if kind == "agree":
            agreed += 1
            digits_seen = min(digits_seen, outcome[1])
            if agreed >= needed:
                break
        elif kind == "differ":
            if k == 1 and options.factors and outcome[1].startswith(_NOT_A_MULTIPLE):
                # Not a constant multiple; it may still be the reference times a factor that depends
                # on the state and is nonzero on the whole domain (r**2 with r > 0, 1 + x**2).
                factor = state_dependent_factor(reference[0], answer[0], {**parameters.domains, **states.domains},
                                                (parameters, states), deadline)
                if factor is not None:
                    return factor
            return Comparison(
                False,
                outcome[3] if len(outcome) > 3 else "proved",
                outcome[1],
                evidence={"method": "ball arithmetic", "points": agreed + 1},
                counterexample=outcome[2],
            )
        elif kind == "budget":
            return Comparison(None, "none", "the time budget ran out while comparing", budget_exceeded=True)
    if agreed >= min(needed, 3):
        digits = options.digits if math.isinf(digits_seen) else int(digits_seen)
        return Comparison(
            True,
            "numeric",
            f"a state-independent multiple of the reference at {agreed} parameter points, "
            f"to at least {digits} digits (ball arithmetic)",
            evidence={"method": "ball arithmetic", "points": agreed, "digits": digits},
        )
    return Comparison(None, "none", "could not decide: the equations could not be evaluated reliably")


def _values(compiled: list[Compiled], point: dict, prec: int, key):
    values, scale = [], -math.inf
    for i, c in enumerate(compiled):
        v, s = c.at(point, prec, None if key is None else (key, i))
        values.append(v)
        scale = max(scale, s, _log2_mag(v))
    return values, scale


def _one_parameter_point(refs, anss, parameters, states, p, target, options, deadline):
    """At parameter point p: ("agree", digits) | ("differ", reason, counterexample) | ("skip",) | ("budget",)."""
    k = len(refs)
    params = parameters.point(p)
    prec = int(target) + 32
    while True:
        outcome = _try_precision(refs, anss, params, states, p, k, prec, target)
        if outcome is not None:
            return outcome
        prec *= 2
        if prec > options.max_bits:
            return ("skip",)
        if deadline is not None and time.monotonic() > deadline:
            return ("budget",)


def _try_precision(refs, anss, params, states, p, k, prec, target):
    n_states = k + 2
    R, S, points, scale = [], [], [], -math.inf
    for j in range(n_states):
        point = {**params, **states.point(p * n_states + j)}
        try:
            r, rs = _values(refs, point, prec, (p, j))
        except Undefined:
            return ("skip",)
        except Unresolved:
            return None
        try:
            s, ss = _values(anss, point, prec, None)
        except Undefined as error:
            example = {"values": _named(point), "answer": "undefined", "reference": [as_float(v) for v in r]}
            return ("differ", f"your equation is undefined at a state where the reference is not ({error.reason})", example)
        except Unresolved:
            return None
        R.append(r)
        S.append(s)
        points.append(point)
        scale = max(scale, rs, ss)
    with flint.ctx.workprec(prec):
        Rk = flint.arb_mat([[R[j][i] for j in range(k)] for i in range(k)])
        Sk = flint.arb_mat([[S[j][i] for j in range(k)] for i in range(k)])
        det_r = Rk.det()
        if not det_r.is_finite() or det_r.contains(0):
            return None  # reference residuals degenerate at these states: more bits (or skip at the cap)
        M = Sk * Rk.inv()
        noise = -math.inf
        for j in range(k, n_states):
            r = flint.arb_mat([[x] for x in R[j]])
            s = flint.arb_mat([[x] for x in S[j]])
            d = s - M * r
            for i in range(k):
                if not d[i, 0].contains(0):
                    return ("differ", *_not_a_multiple(k, points, R, S, j, i))
                noise = max(noise, _log2_mag(d[i, 0].rad()))
        if noise > scale - target:
            return None
        if not M.det().contains(0):
            return ("agree", (scale - noise) / LOG2_10)
        if k > 1:
            m_scale = max(_log2_mag(M[i, j]) for i in range(k) for j in range(k))
            if _log2_mag(M.det()) <= k * m_scale - target:
                example = {"values": _named(points[0]), "answer": [as_float(v) for v in S[0]],
                           "reference": [as_float(v) for v in R[0]]}
                return ("differ", "your equations are not independent: together they say less than the "
                        "reference equations", example, "numeric")
        if k == 1 and S[0][0].contains(0) and _log2_mag(S[0][0]) <= scale - target:
            example = {"values": _named(points[0]), "answer": as_float(S[0][0]), "reference": as_float(R[0][0])}
            return ("differ", "your equation holds where the reference does not (both sides are equal at the counterexample)", example, "numeric")
        return None


def _not_a_multiple(k, points, R, S, j, i):
    if k == 1:
        # No ratio in the reason: with the student's own equation it would give the reference's values.
        reason = (f"{_NOT_A_MULTIPLE}: the ratio changes between two states (see the counterexample)")
        example = {"values": _named(points[j]), "answer": as_float(S[j][0]), "reference": as_float(R[j][0]),
                   "other_state": _named(points[0]), "answer_there": as_float(S[0][0]),
                   "reference_there": as_float(R[0][0])}
    else:
        reason = ("your equations are not combinations of the reference equations with coefficients "
                  f"free of the state (equation {i + 1} fails at the counterexample)")
        example = {"values": _named(points[j]), "answer": [as_float(v) for v in S[j]],
                   "reference": [as_float(v) for v in R[j]]}
    return reason, example


_NOT_A_MULTIPLE = "your equation is not the reference multiplied by a factor free of the state"
# Largest residuals (in nodes) whose ratio is worth a symbolic cancellation.
FACTOR_MAX_NODES = 200
# Highest integer power worth cancelling symbolically.
FACTOR_MAX_POWER = 8
# Boxes the ball-arithmetic proof may split a bounded domain into.
FACTOR_MAX_BOXES = 256


def state_dependent_factor(reference: sympy.Expr, answer: sympy.Expr, domains: dict,
                           samplers: tuple[Sampler, Sampler] | None = None,
                           deadline: float | None = None) -> Comparison | None:
    """Is ``answer`` the ``reference`` residual times a factor that is nonzero on the whole domain?

    The ratio ``answer/reference`` is cancelled to ``n/d`` in lowest terms. When ``d`` is provably
    nonzero on the declared domain, the answer is a multiple of the reference, and it is right
    exactly when ``n`` is provably nonzero too (``r**2`` with r > 0, ``1 + x**2``, ``cos(theta)`` on
    [-1.5, 1.5]); a factor that can vanish (``thetadot``, ``cos(theta)`` on (-pi, pi)) leaves an
    equation that no longer determines the motion where it vanishes. A proof uses the symbols'
    assumptions or ball arithmetic over the whole of bounded domains.

    Returns a verdict, or None when the answer is not a multiple of that kind (the caller keeps
    its own counterexample). ``samplers`` (parameters, states) give the states where a factor that
    can vanish is shown to change sign.

    Examples
    --------
    >>> import sympy
    >>> from grader.expressions import parse_domain
    >>> r = sympy.Symbol("r", positive=True)
    >>> rddot, thetadot = sympy.symbols("rddot thetadot", real=True)
    >>> ref = rddot - r*thetadot**2
    >>> domains = {r: parse_domain("positive"), rddot: parse_domain("real"), thetadot: parse_domain("real")}
    >>> state_dependent_factor(ref, r**2*ref, domains).equivalent
    True
    >>> state_dependent_factor(ref, thetadot*ref, domains).equivalent
    False
    """
    # A high power of a nonzero factor ((1 + theta**2)**400) changes no solution: set it aside
    # rather than make cancel expand it.
    kept = []
    for factor in sympy.Mul.make_args(answer):
        if factor.is_Pow and factor.exp.is_Integer and abs(int(factor.exp)) > FACTOR_MAX_POWER \
                and _nonzero_on(factor.base, domains) is True:
            continue
        kept.append(factor)
    answer = sympy.Mul(*kept)
    if not (_nodes(reference) <= FACTOR_MAX_NODES and _nodes(answer) <= FACTOR_MAX_NODES):
        return None
    try:
        ratio = sympy.cancel(sympy.together(answer / reference))
    except (sympy.PolynomialError, ValueError, TypeError, ZeroDivisionError):
        return None
    numerator, denominator = sympy.fraction(ratio)
    if deadline is not None and time.monotonic() > deadline:
        return None
    if _nonzero_on(denominator, domains) is not True:
        return None  # not a multiple of the reference at all
    if _nonzero_on(numerator, domains) is True:
        return Comparison(True, "proved", "the reference multiplied by a factor that depends on the state "
                          "and is nonzero on the whole declared domain", evidence={"method": "symbolic"})
    example = _sign_change(numerator, *samplers) if samplers is not None else None
    if example is not None:
        return Comparison(False, "proved", "your equation is the reference multiplied by a factor that depends "
                          "on the state and is zero somewhere in the declared domain (it changes sign between "
                          "the two states in the counterexample): there your equation no longer determines "
                          "the motion", evidence={"method": "ball arithmetic"}, counterexample=example)
    return Comparison(False, "numeric", "your equation is the reference multiplied by a factor that depends on "
                      "the state and could not be shown to be nonzero on the whole declared domain",
                      evidence={"method": "symbolic"})


def _nodes(expr: sympy.Expr) -> int:
    """Nodes of ``expr`` (past the limit when a high power makes cancelling it costly: x**1000)."""
    count, stack = 0, [expr]
    while stack and count <= FACTOR_MAX_NODES:
        node = stack.pop()
        count += 1
        if node.is_Pow and node.exp.is_Integer and abs(int(node.exp)) > FACTOR_MAX_POWER:
            return FACTOR_MAX_NODES + 1
        stack.extend(node.args)
    return count


def _nonzero_on(expr: sympy.Expr, domains: dict) -> bool | None:
    """True when ``expr`` is provably nonzero (and finite) on the whole declared domain, else None."""
    for factor in sympy.Mul.make_args(sympy.factor_terms(expr)):
        if factor.is_Pow and factor.exp.is_Integer:
            factor = factor.base  # a power vanishes where its base does (and has poles where it has zeros)
        if factor.is_number:
            if factor.is_zero is False and factor.is_finite:
                continue
            return None
        if factor.is_positive or factor.is_negative:
            continue
        if _nonzero_in_balls(factor, domains) is not True:
            return None
    return True


def _nonzero_in_balls(expr: sympy.Expr, domains: dict) -> bool | None:
    """Ball arithmetic over the whole box of bounded domains: True if ``expr`` provably excludes 0."""
    symbols = sorted(expr.free_symbols, key=lambda s: s.name)
    boxes = []
    for s in symbols:
        domain = domains.get(s)
        lo, hi = getattr(domain, "lo", -math.inf), getattr(domain, "hi", math.inf)
        if domain is None or not (math.isfinite(lo) and math.isfinite(hi)):
            return None
        boxes.append((lo, hi))
    try:
        f = compile_expr(expr, ArbBackend())
    except Unsupported:
        return None
    pending, tried = [boxes], 0
    with flint.ctx.workprec(64):
        while pending:
            box = pending.pop()
            tried += 1
            if tried > FACTOR_MAX_BOXES:
                return None
            env = {s: flint.arb((lo + hi) / 2, (hi - lo) / 2) for s, (lo, hi) in zip(symbols, box)}
            env[SCALE] = -math.inf
            try:
                value = f(env)
                if value.is_finite() and not value.contains(0):
                    continue
                if value.is_finite() and value == 0:
                    return None
            except Undefined:
                return None
            except Unresolved:
                pass
            widest = max(range(len(box)), key=lambda i: box[i][1] - box[i][0])
            lo, hi = box[widest]
            middle = (lo + hi) / 2
            pending.append(box[:widest] + [(lo, middle)] + box[widest + 1:])
            pending.append(box[:widest] + [(middle, hi)] + box[widest + 1:])
    return True


def _sign_change(expr: sympy.Expr, parameters: Sampler, states: Sampler) -> dict | None:
    """Two sampled states where ``expr`` provably has opposite signs (so it vanishes in between)."""
    try:
        f = compile_expr(expr, ArbBackend())
    except Unsupported:
        return None
    seen = {}
    fixed = parameters.point(0)
    points = [{**fixed, **states.point(i)} for i in range(12)] + [{**fixed, **states.wide_point(i)} for i in range(12)]
    with flint.ctx.workprec(64):
        for point in points:
            env = {s: flint.arb(v) for s, v in point.items()}
            env[SCALE] = -math.inf
            try:
                value = f(env)
            except (Undefined, Unresolved, KeyError):
                continue
            sign = 1 if value > 0 else -1 if value < 0 else 0 if value == 0 else None
            if sign is None or sign in seen:
                continue
            if sign == 0:
                return {"values": _named(point)}
            seen[sign] = point
            if len(seen) == 2:
                return {"values": _named(seen[1]), "other_state": _named(seen[-1])}
    return None


def _named(point: dict) -> dict:
    return {s.name: v for s, v in point.items()}


def _compare_fixed_ratio(reference, answer, parameters, states, options) -> Comparison:
    """float64 / mpmath rule for the benchmark: the ratio answer/reference is the same at two states."""
    backend = options.backend()
    prec = 53 if options.method == "float64" else int(options.digits * LOG2_10) + 1
    refs = [Compiled(r, backend) for r in reference]
    anss = [Compiled(a, backend) for a in answer]
    if len(refs) != 1:
        return Comparison(None, "none", "fixed-precision methods compare single equations only")
    agreed = 0
    for p in range(options.points * 2):
        ratios = []
        for j in range(2):
            point = {**parameters.point(p), **states.point(2 * p + j)}
            try:
                r, _ = refs[0].at(point, prec)
            except (Undefined, Unresolved):
                break
            try:
                a, _ = anss[0].at(point, prec)
            except (Undefined, Unresolved):
                return Comparison(False, "numeric", "your equation is undefined at a sample point")
            if r == 0:
                break
            ratios.append(a / r)
        if len(ratios) < 2:
            continue
        q0, q1 = ratios
        size = max(abs(q0), abs(q1))
        if size < 1e-14 or abs(q0 - q1) > options.tolerance * size:
            return Comparison(False, "numeric", "the ratio to the reference depends on the state")
        agreed += 1
        if agreed >= options.points:
            break
    if agreed:
        return Comparison(True, "numeric", f"ratio constant at {agreed} points ({options.describe()})",
                          evidence={"method": options.describe(), "points": agreed})
    return Comparison(None, "none", "could not decide")
