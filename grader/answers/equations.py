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

from grader.answers.evaluate import Undefined, Unresolved, _log2_mag
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
        reason = ("your equation is not the reference multiplied by a factor free of the state: the ratio "
                  "changes between two states (see the counterexample)")
        example = {"values": _named(points[j]), "answer": as_float(S[j][0]), "reference": as_float(R[j][0]),
                   "other_state": _named(points[0]), "answer_there": as_float(S[0][0]),
                   "reference_there": as_float(R[0][0])}
    else:
        reason = ("your equations are not combinations of the reference equations with coefficients "
                  f"free of the state (equation {i + 1} fails at the counterexample)")
        example = {"values": _named(points[j]), "answer": [as_float(v) for v in S[j]],
                   "reference": [as_float(v) for v in R[j]]}
    return reason, example


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
