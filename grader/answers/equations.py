"""Equivalence of equations and of systems of equations.

An equation of motion is right when it is the reference multiplied by a nonzero factor free of the
state: ``thetaddot + g/l*sin(theta) = 0``, ``l*thetaddot = -g*sin(theta)`` and
``m*l**2*thetaddot + m*g*l*sin(theta) = 0`` are one equation. A system is right when it spans the
same equations: the student's residuals are ``M @`` the reference's residuals for a matrix ``M``
that is invertible and free of the state, or, for equations of motion, ``A(state) @`` them for a
mixing matrix that depends on the state and is provably invertible on the whole declared domain
(the unsolved Euler-Lagrange equations ``M(q) qddot = F(q, qdot)`` against the solved reference
``qddot = M(q)**-1 F``): see `state_dependent_mixing`. A factor (or mixing) free of the state must
still be nonzero (invertible) for every value of the parameters: ``(omega**2 R - g)(...) = 0`` says
nothing when ``omega**2 R = g`` (`_vanishing_multiple`, `_parameter_factor`).

Numerically: fix the parameters at a sample point, take ``k + 2`` states (``k`` equations), solve
``M`` from the first ``k`` states and check, in ball arithmetic, that the others satisfy
``S = M R`` and that ``det M != 0``. A state where ``S - M R`` provably excludes zero proves the
equations different; agreement at every parameter point to the required digits is the numeric
verdict.
"""

from __future__ import annotations

import collections
import contextvars
import itertools
import math
import random
import time

import flint
import mpmath
import numpy as np
import sympy

from grader.answers.evaluate import (SCALE, ArbBackend, FloatBackend, MpmathBackend, Undefined, Unresolved,
                                     Unsupported, _log2_mag, compile_expr)
from grader.answers.equivalence import (
    CONFIRM_BITS,
    LOG2_10,
    MAX_PATTERNS,
    Comparison,
    Compiled,
    Options,
    _kink_arguments,
    _breakpoints,
    _PointsSampler,
    _float_at,
    _range_bits,
    _sign_pattern,
    _span,
    as_float,
    kink_region_states,
    off_grid,
    resonant,
    _where_defined,
)
from grader.answers.sampling import GivenPoints, Sampler
from grader.mechanics import budget

__all__ = ["compare_equations", "state_dependent_mixing", "state_symbols", "unknown_symbols"]

STATE_KINDS = {"coordinate", "velocity", "acceleration", "multiplier", "force", "time", "answer"}


def state_symbols(variables: dict[str, dict], symbols: dict[str, sympy.Symbol], state: list[str] | None = None) -> set:
    """The variables a factor of an equation may not depend on.

    Taken from ``state`` when given (with the accelerations, always), else from each variable's ``kind``;
    else by name: names ending in ``dot``/``ddot`` and any name ``q`` for which ``qdot`` exists. With no state at all,
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
        # The accelerations are the equations' unknowns whatever the list names: a state of coordinates and
        # velocities, as the API describes it, must not turn them into parameters (that turned off every
        # check of a factor or a mixing of the equations).
        chosen = {symbols[n] for n in state if n in symbols} | set(_declared_accelerations(variables, symbols))
    else:
        chosen = {symbols[n] for n, spec in variables.items() if n in symbols and (spec or {}).get("kind") in STATE_KINDS}
        if not chosen and not any((spec or {}).get("kind") for spec in variables.values()):
            names = set(symbols)
            for n in names:
                if n.endswith("dot") or f"{n}dot" in names:
                    chosen.add(symbols[n])
    return chosen or set(symbols.values())


def unknown_symbols(variables: dict[str, dict], symbols: dict[str, sympy.Symbol],
                    state: list[str] | None = None) -> tuple:
    """The accelerations: what equations of motion are solved for (sorted by name).

    Taken from each variable's ``kind`` ("acceleration"); with no kinds at all, from names ending
    in ``ddot``. With accelerations, the multipliers and constraint forces (kinds "multiplier" and
    "force") too: the Lagrange equations with multipliers are one linear system in both. They are
    state variables whatever ``state`` lists (`state_symbols`).

    Examples
    --------
    >>> import sympy
    >>> names = ["m", "theta", "thetadot", "thetaddot", "xddot"]
    >>> syms = {n: sympy.Symbol(n) for n in names}
    >>> [s.name for s in unknown_symbols({n: {} for n in names}, syms)]
    ['thetaddot', 'xddot']
    >>> [s.name for s in unknown_symbols({n: {} for n in names}, syms, state=["theta", "thetadot"])]
    ['thetaddot', 'xddot']
    """
    states = state_symbols(variables, symbols, state)
    accelerations = set(_declared_accelerations(variables, symbols)) & states
    if accelerations:
        # Multipliers and constraint forces are solved for together with the accelerations (m ẍ = λ x/l with
        # the constraint's second derivative: one linear system in ẍ, ÿ, λ): unknowns too, so that a row
        # combination that depends on the state (λ solved out, a row times r²) is looked for.
        accelerations |= {symbols[n] for n, spec in variables.items()
                          if n in symbols and (spec or {}).get("kind") in UNKNOWN_KINDS} & states
    return tuple(sorted(accelerations, key=lambda s: s.name))


# Kinds solved for with the accelerations in a system of equations of motion.
UNKNOWN_KINDS = {"multiplier", "force"}


def _declared_accelerations(variables: dict[str, dict], symbols: dict[str, sympy.Symbol]) -> list:
    """The variables of kind "acceleration"; with no kinds at all, the names ending in ``ddot``."""
    if any((spec or {}).get("kind") for spec in variables.values()):
        return [symbols[n] for n, spec in variables.items() if n in symbols and (spec or {}).get("kind") == "acceleration"]
    return [s for n, s in symbols.items() if n.endswith("ddot")]


# Systems of more equations than unknowns compared by their subsets, at most this many subsets.
MAX_SUBSETS = 10
# States at which the equations left out must hold on the reference's solution.
IMPLIED_POINTS = 4


def _with_implied_extras(reference, answer, parameters, states, options, deadline, compiled_reference,
                         answer_conditions, unknowns) -> Comparison | None:
    """An answer with more equations than the reference whose others follow from k of them: those k are
    the reference's system, and at the accelerations they give the others hold too (a cart's two
    Euler–Lagrange equations and their combination solved for ẍ), else None.

    The others are checked at the reference's solution at a few states: each residual evaluated there
    is zero to the working digits."""
    k = len(reference)
    for n, chosen in enumerate(itertools.combinations(range(len(answer)), k)):
        if n >= MAX_SUBSETS or _past(deadline):
            return None
        subset = [answer[i] for i in chosen]
        result = compare_equations(reference, subset, parameters, states, options, deadline, compiled_reference,
                                   answer_conditions, unknowns)
        if not result.equivalent:
            continue
        others = [answer[i] for i in range(len(answer)) if i not in chosen]
        if _hold_at_the_solutions(reference, others, unknowns, parameters, states):
            result.reason = (f"{result.reason} (the other equation{'s' * (len(others) > 1)} follow"
                             f"{'s' * (len(others) == 1)} from these: {'they hold' if len(others) > 1 else 'it holds'} "
                             f"wherever they do, at {IMPLIED_POINTS} states)")
            return result
    return None


def _hold_at_the_solutions(reference: list[sympy.Expr], others: list[sympy.Expr], unknowns: tuple,
                           parameters: Sampler, states: Sampler) -> bool:
    """Whether each of ``others`` is zero where the reference's system (linear in the unknowns) holds, at a
    few parameter points and states: in ball arithmetic at `CONFIRM_BITS`, the unknowns solved there as
    balls, each residual's ball must contain zero and be narrow. Fixed digits let a slightly false
    equation pass (``+ 1e-30 g/l``, ``+ e^-200 g/l``), as `grader.answers.equivalence._below_the_digits`
    found for expressions."""
    if len(unknowns) != len(reference) or any(other.is_number for other in others):
        return False
    split = _linear_in(reference, unknowns)
    if split is None:
        return False
    matrix, rest = split
    k = len(unknowns)
    try:
        compiled = [Compiled(e, ArbBackend()) for e in (*matrix, *rest)]
        checks = [Compiled(other, ArbBackend()) for other in others]
    except Unsupported:
        return False
    for i in range(IMPLIED_POINTS):
        point = {s: v for s, v in states.joint(parameters.point(i), states.point(i)).items() if s not in unknowns}
        try:
            values = [c.at(point, CONFIRM_BITS)[0] for c in compiled]
            with flint.ctx.workprec(CONFIRM_BITS):
                a = flint.arb_mat(k, k, values[:k * k])
                det = a.det()
                if not det.is_finite() or det.contains(0):
                    return False
                solution = a.solve(flint.arb_mat(k, 1, [-v for v in values[k * k:]]))
            at = {**point, **{u: solution[j, 0] for j, u in enumerate(unknowns)}}
            for check in checks:
                value, scale = check.at(at, CONFIRM_BITS)
                # a wide ball contains zero without saying anything: it must be narrow next to the terms
                if not value.contains(0) or _log2_mag(value.rad()) > scale - CONFIRM_BITS // 2:
                    return False
        except (Undefined, Unresolved, ZeroDivisionError, ValueError):
            return False
    return True


def _without_repeats(residuals: list[sympy.Expr]) -> list[sympy.Expr]:
    """``residuals`` without those that another one implies: X = f Y with f finite everywhere
    (a number, a parameter, sin θ, θ̇): wherever Y = 0, X = 0 too, so X adds no condition, whether or
    not f can vanish.

    >>> x, y = sympy.symbols("x y", real=True)
    >>> _without_repeats([x - y, 2*y - 2*x, x*(x - y), x + y])
    [x - y, x + y]
    >>> _without_repeats([x*(x - y), x - y])  # the second implies the first
    [x - y]
    """
    kept: list[sympy.Expr] = []
    for residual in residuals:
        if any(_implied_by(residual, other) for other in kept):
            continue
        kept = [other for other in kept if not _implied_by(other, residual)] + [residual]
    return kept


def _implied_by(a: sympy.Expr, b: sympy.Expr) -> bool:
    """Whether ``a`` is ``b`` times a factor finite on the whole domain (decided exactly by sympy's
    assumptions, for residuals of moderate size)."""
    if a == 0 or b == 0:
        return False  # 0 = 0 is no equation of the system (θ̇ = θ̇ beside the answer): not dropped
    if a == b or a == -b:
        return True
    if _nodes(a) > FACTOR_MAX_NODES or _nodes(b) > FACTOR_MAX_NODES:
        return False
    try:
        factor = sympy.cancel(sympy.together(a / b))
    except (sympy.PolynomialError, ValueError, TypeError, ZeroDivisionError):
        return False
    return factor.is_finite is True


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
    unknowns: tuple = (),
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
    unknowns : tuple of sympy.Symbol
        The accelerations (`unknown_symbols`). A system of as many equations, linear in them, may
        also be a combination of the reference with coefficients that depend on the state
        (`state_dependent_mixing`).

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
    >>> compare_equations(ref, [thdd + g / l * sympy.cos(th)], P, S, unknowns=(thdd,)).certainty
    'proved'
    """
    # The declared orders (x below L) for the proofs that a factor is nonzero (`_nonzero_on`).
    token = _ORDER.set({**parameters.below, **states.below, **parameters.across, **states.across})
    try:
        if answer_conditions:
            # a typed real domain that is the whole domain (exp(log(2 + cos θ))) loses no state: no condition
            domains = {**parameters.domains, **states.domains}
            answer_conditions = tuple(c for c in answer_conditions if not _defined_everywhere(c, domains))
        return _compare_equations(reference, answer, parameters, states, options, deadline, compiled_reference,
                                  answer_conditions, unknowns)
    finally:
        _ORDER.reset(token)


def _compare_equations(reference, answer, parameters, states, options, deadline, compiled_reference,
                       answer_conditions, unknowns) -> Comparison:
    k = len(reference)
    determined = set().union(*(r.free_symbols for r in reference)) & set(states.domains)
    if k > len(determined):
        return _over_determined(reference, determined, parameters)
    if len(answer) > k:
        distinct = _without_repeats(answer)
        if len(distinct) < len(answer):
            # An equation that another implies (the same one pasted twice, or it times a factor)
            # adds no condition: the system is the one without it.
            result = compare_equations(reference, distinct, parameters, states, options, deadline,
                                       compiled_reference, answer_conditions, unknowns)
            if result.equivalent:
                result.reason = f"{result.reason} (an equation that another one implies, such as the same equation again, adds nothing)"
            return result
    if len(answer) > k and unknowns:
        implied = _with_implied_extras(reference, answer, parameters, states, options, deadline, compiled_reference,
                                       answer_conditions, unknowns)
        if implied is not None:
            return implied
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
    agreed, digits_seen, mixing = 0, math.inf, None
    signs = {}  # the sign of det M at the agreeing parameter points -> one such point
    # each parameter point checks k + 2 states, so half as many parameter points as expression points
    needed = max(3, options.points // 2)

    def differ(outcome) -> Comparison:
        """The verdict where the answer is not the state-free multiple the other points found."""
        # An equation of motion whose typed real domain (-k√x√x, exp(log(x/L)): sympy simplified the root or
        # logarithm away, its condition stays) excludes a state where the reference holds has lost that state's
        # motion: the factor searches below see only the simplified residual, and found the factor 1.
        lost = bool(unknowns and answer_conditions and outcome[1].startswith(_UNDEFINED_WHERE))
        if k == 1 and not unknowns and answer_conditions and outcome[1].startswith(_UNDEFINED_WHERE):
            # A relation between state variables (y = exp(log x) against y = x, x real) whose typed real domain
            # leaves out states where the reference holds has lost those solutions; one undefined only where
            # the reference has none either (θ = acos(...) against the energy equation) goes on below.
            lost_state = _undefined_where_the_reference_holds(reference[0], anss[0], outcome[2], parameters, states)
            if lost_state is not None:
                return Comparison(False, "numeric", f"{_UNDEFINED_WHERE}, at a state where the reference holds (see "
                                  "the counterexample): your equation leaves out solutions of the reference",
                                  evidence={"method": "root search", "points": agreed + 1},
                                  counterexample={"values": _named(lost_state), "answer": "undefined",
                                                  "reference": 0.0})
        if k == 1 and options.factors and outcome[1].startswith((_NOT_A_MULTIPLE, _UNDEFINED_WHERE)) and not lost:
            # Not a constant multiple; it may still be the reference times a factor that depends
            # on the state and is nonzero on the whole domain (r**2 with r > 0, 1 + x**2).
            factor = state_dependent_factor(reference[0], answer[0], {**parameters.domains, **states.domains},
                                            (parameters, states), deadline)
            if factor is not None and factor.equivalent:
                return factor
            # exp(x) = exp(y), x^3 = y^3: the same solutions as x = y, but the ratio of the residuals is
            # no factor that cancels; either equation may be the one written so (|x| = |y| against x^2 = y^2)
            domains = {**parameters.domains, **states.domains}
            inner = None if answer_conditions else (_injective_sides(answer[0], domains)
                                                    or _logs_exponentiated(answer[0]))
            inner_reference = _injective_sides(reference[0], domains) or _logs_exponentiated(reference[0])
            # θ = atan(X) and tan θ = X, where θ stays in atan's range (an equilibrium angle)
            inverse = None if answer_conditions else _inverse_applied(answer[0], domains)
            inverse_reference = _inverse_applied(reference[0], domains)
            # |v| = √(2gh) and v² = 2gh: squared, whatever the answer's own domain (where 2gh < 0 neither holds)
            squared, squared_reference = _nonnegative_sides_squared(answer[0]), _nonnegative_sides_squared(reference[0])
            for ref_form, answer_form in ((reference[0], inner), (inner_reference, answer[0]),
                                          (inner_reference, inner), (inverse_reference, answer[0]),
                                          (reference[0], inverse), (inverse_reference, inner),
                                          (inner_reference, inverse), (reference[0], squared),
                                          (squared_reference, answer[0]), (squared_reference, squared)):
                if ref_form is None or answer_form is None or _past(deadline) or _PEELED.get() >= MAX_PEELED:
                    continue
                token = _PEELED.set(_PEELED.get() + 1)
                try:
                    again = compare_equations([ref_form], [answer_form], parameters, states, options, deadline,
                                              compiled_reference if ref_form is reference[0] else None,
                                              answer_conditions if answer_form is answer[0] else (), unknowns)
                finally:
                    _PEELED.reset(token)
                if again.equivalent:
                    again.reason = ("the same solutions as the reference: f(A) = f(B), with f taking each value "
                                    "once (an odd power, exp, atan, log of positive quantities, a sine or tangent "
                                    "where its argument stays in one branch; an even power on |A|), holds exactly "
                                    f"where A = B, and that equation is {again.reason}")
                    return again
            if not unknowns and not answer_conditions:
                # an equilibrium condition in one coordinate on an interval (tan θ = a/g, θ = atan(a/g),
                # sin θ = a/√(a² + g²)): its solutions, found on the interval, decide
                roots = _same_roots_on_the_interval(reference[0], answer[0], parameters, states, deadline)
                if roots is not None and roots.equivalent:
                    return roots  # (a difference is left to the reasons below)
            if factor is not None:
                return factor
            if _nodes(reference[0]) > FACTOR_MAX_NODES or _nodes(answer[0]) > FACTOR_MAX_NODES:
                if unknowns and not answer_conditions:
                    # Linear in the acceleration, the factor is the ratio of its coefficients: no cancelling
                    # of the whole residuals (`state_dependent_mixing` with one equation, in the one
                    # acceleration it is solved for where the system declares several).
                    present = tuple(u for u in unknowns if u in reference[0].free_symbols)
                    mixed = state_dependent_mixing(reference, answer, present if len(present) == 1 else unknowns,
                                                   {**parameters.domains, **states.domains},
                                                   (parameters, states), options, deadline)
                    if mixed is not None:
                        return mixed
                # No factor free of the state, proved; one that depends on it was never looked for.
                return Comparison(False, "numeric", f"{outcome[1]}; it may still be the reference times a factor "
                                  "that depends on the state, but your equation is too large for that factor to be "
                                  "analysed (simplify it and submit again)",
                                  evidence={"method": "ball arithmetic", "points": agreed + 1,
                                            "factor": "not analysed (too large)"},
                                  counterexample=outcome[2])
        if k > 1 and options.factors and outcome[1].startswith(_NOT_A_COMBINATION) and not answer_conditions \
                and _same_polynomial_ideal(reference, answer, set(states.domains), with_parameters=not unknowns,
                                           domains={**parameters.domains, **states.domains}):
            return Comparison(True, "proved", "the same solutions as the reference: with repeated factors and "
                              "factors that cannot vanish set aside, your equations and the reference's generate "
                              "the same polynomial equations (equal reduced Gröbner bases)",
                              evidence={"method": "Gröbner basis"})
        if k > 1 and options.factors and unknowns and outcome[1].startswith(_NOT_A_COMBINATION) \
                and not answer_conditions:
            # Not a state-free combination; it may still be A(state) times the reference with
            # A invertible on the whole domain (the unsolved Euler-Lagrange equations).
            mixed = state_dependent_mixing(reference, answer, unknowns, {**parameters.domains, **states.domains},
                                           (parameters, states), options, deadline)
            if mixed is not None:
                return mixed
        if k > 1 and options.factors and outcome[1].startswith(_NOT_A_COMBINATION) and not answer_conditions:
            # T³ = (m₁m₂g/(m₁ + m₂))³ as one equation of a system: each row f(A) = f(B) with f one-to-one is read as
            # A = B, as a single equation's is above, and the systems compared again
            peeled = _rows_peeled(reference, answer, {**parameters.domains, **states.domains}, parameters, states,
                                  options, deadline, compiled_reference, unknowns)
            if peeled is not None:
                return peeled
        certainty = outcome[3] if len(outcome) > 3 else "proved"
        if k == 1 and not unknowns and outcome[1].startswith((_NOT_A_MULTIPLE, _UNDEFINED_WHERE)):
            # A relation between state variables with the reference's solutions need be no multiple of it
            # (|v| = √(2gh) against v² = 2gh): a changing ratio proves no difference of solutions.
            certainty = "numeric"
        return Comparison(
            False,
            certainty,
            outcome[1],
            evidence={"method": "ball arithmetic", "points": agreed + 1},
            counterexample=outcome[2],
        )

    examined = 0  # parameter points looked at
    for p in range(needed * 2):
        outcome = _one_parameter_point(refs, anss, parameters, states, p, target, options, deadline)
        examined = p + 1
        kind = outcome[0]
        if kind == "agree":
            agreed += 1
            digits_seen = min(digits_seen, outcome[1])
            signs.setdefault(outcome[2], parameters.point(p))
            mixing = outcome[3]
            if len(signs) == 2 and unknowns:
                return _vanishing_multiple(k, signs)
            if agreed >= needed:
                break
        elif kind == "differ":
            return differ(outcome)
        elif kind == "budget":
            return Comparison(None, "none", "the time budget ran out while comparing", budget_exceeded=True)
    if agreed >= min(needed, 3):
        # |x| + y = z and ||x| + y| = z agree wherever y > -|x|: the points may all lie there.
        for p in _sign_region_points(reference + answer, parameters, states, examined, k + 2, backend):
            outcome = _one_parameter_point(refs, anss, parameters, states, p, target, options, deadline)
            if outcome[0] == "differ":
                return differ(outcome)
        # and in each region between the boundaries of a kink or branch (sign((x - 5y)(x - 6y)), θ past π)
        fresh = None  # the reference compiled again: these points are not the shared cache's (p, j)
        # (with the answer's typed real domain: y = exp(log(x + 10)) - 5 is y = x + 5 only where x > -10)
        regions = kink_region_states(reference + answer + list(answer_conditions), parameters, states, k + 2,
                                     deadline)
        for n, (given, at) in enumerate(regions):
            fresh = fresh or [Compiled(r, backend) for r in reference]
            outcome = _one_parameter_point(fresh, anss, given, at, n, target, options, deadline)
            if outcome[0] == "differ":
                return differ(outcome)
    if agreed >= min(needed, 3) and unknowns:
        # Equations of motion, whose reference determines the accelerations for every parameter value:
        # a factor (a mixing) free of the state must then be nonzero (invertible) for every one too. An
        # equation in an answer X may be degenerate itself ((k - m w^2) X = F0 at resonance, where
        # X = F0/(k - m w^2) is undefined: no solution either way), so it is not screened so.
        if k == 1 and signs:
            signs = _multiple_signs(refs[0], anss[0], parameters, states, needed * 2, target, signs)
        elif signs and len(_paired_rows(mixing, k)) < k:
            # rows that combine reference equations (a row each multiple of one is screened by its factor)
            signs = _mixing_signs(refs, anss, parameters, states, needed * 2, target, signs, options.max_bits)
        if len(signs) == 2:
            return _vanishing_multiple(k, signs)
        factor = _parameter_factor(reference, answer, parameters, states)
        if factor is not None:
            return factor
        if k > 1 and mixing is not None and len(_paired_rows(mixing, k)) < k:
            # rows that combine reference equations: one sign of the determinant at the parameter points says
            # nothing of one that touches zero (cos² α) or is negative only in a narrow band of them
            mixed = _parameter_mixing(reference, answer, unknowns, parameters, set(states.domains), deadline)
            if mixed is not None:
                return mixed
    if agreed >= min(needed, 3) and not unknowns and parameters.domains:
        # An equilibrium or a statics system must hold for every parameter value too; only an
        # equation degenerate there itself is spared (`_degenerate_there`).
        found = _parameter_dependence(reference, answer, refs, anss, parameters, states, needed * 2, target,
                                      signs, mixing, options)
        if found is not None:
            return found
    if agreed >= min(needed, 3):
        digits = options.digits if math.isinf(digits_seen) else int(digits_seen)
        for i, j in _paired_rows(mixing, k):
            hidden = _hidden_difference([reference[j]], [answer[i]], unknowns, parameters, states, options)
            if hidden is not None:
                if k > 1:
                    hidden.reason = f"equation {i + 1}: {hidden.reason}"
                return hidden
        if k == 1:
            special = _multiple_at_special_points(reference[0], answer[0], parameters, states, unknowns)
            if special is not None:
                return special
        confirmed = _try_precision(refs, anss, parameters.point(0), states, 0, k, CONFIRM_BITS + 64, CONFIRM_BITS)
        how = "by less than the judge's digits: at more precision the ratio is not constant"
        if confirmed is None or confirmed[0] != "differ":
            # a difference behind a function near its limit or a constant far from 1 (θ̈ = −(g/l) sin θ tanh 2000):
            # once more at the range the texts span (`_range_bits`), where that is past CONFIRM_BITS
            bits = _range_bits(reference + answer, states.joint(parameters.point(0), states.point(0)))
            if bits > CONFIRM_BITS:
                confirmed = _try_precision(refs, anss, parameters.point(0), states, 0, k, bits + 64, bits)
        if (confirmed is None or confirmed[0] != "differ") and resonant(reference + answer):
            # a period fitted to every float (θ̈ = −(g/l) sin θ + (g/l) sin(2^60 π θ)): states off the floats' grid,
            # with the reference compiled afresh (these are not the shared cache's (p, j) points)
            off = GivenPoints(states, [off_grid(states.point(j), states.domains) for j in range(k + 2)])
            confirmed = _try_precision([Compiled(r, backend) for r in reference], anss,
                                       off_grid(parameters.point(0), parameters.domains), off, 0, k,
                                       CONFIRM_BITS + 64, CONFIRM_BITS)
            if confirmed is not None and confirmed[0] == "differ":
                for key in ("values", "other_state"):  # the exact fractions, as the JSON numbers nearest them
                    if key in confirmed[2]:
                        confirmed[2][key] = {n: float(v) for n, v in confirmed[2][key].items()}
                how = ("at states off the floats' grid: a constant in a periodic function of your equation fits its "
                       "period to every float")
        if confirmed is not None and confirmed[0] == "differ":
            # θ̈ = −(g/l) sin(θ(1 + 10⁻⁴⁰)) is a multiple of the reference to 40 digits, not at 300
            # (through `differ`: a factor constant at the ordinary states may still be nonzero and depend on the
            # state, 2 + cos(2^60 π θ))
            return differ(("differ", f"{confirmed[1]} ({how})", confirmed[2]))
        return Comparison(
            True,
            "numeric",
            f"a state-independent multiple of the reference at {agreed} parameter points, "
            f"to at least {digits} digits (ball arithmetic)",
            evidence={"method": "ball arithmetic", "points": agreed, "digits": digits},
        )
    if agreed < min(needed, 3) and not isinstance(parameters, _PointsSampler) and not _past(deadline):
        # y = sqrt(x − 1e7), m ẍ = −k sqrt(x² − 1e8 L²): the reference is defined only past the sampled magnitudes;
        # the boundaries of its own arguments say where (`_where_defined`), and the equations are compared there
        # (compiled afresh: these are not the shared cache's points)
        # (from the first parameter point alone: a state found for other parameters need not be one for these)
        every = {**parameters.domains, **states.domains}
        first = states.joint(parameters.point(0), states.point(0))
        defined = _where_defined(_AllRows([Compiled(r, backend) for r in reference]), tuple(reference),
                                 _PointsSampler(states, [first], every), deadline)
        if defined:
            result = _compare_equations(
                reference, answer,
                _PointsSampler(parameters, [{s: v for s, v in p.items() if s in parameters.domains} for p in defined]),
                _PointsSampler(states, [{s: v for s, v in p.items() if s in states.domains} for p in defined]),
                options, deadline, None, answer_conditions, unknowns)
            if result.equivalent:
                result.reason = (f"{result.reason}, all at the first parameter point, with states drawn where the "
                                 "reference is defined (past the sampled magnitudes)")
            return result
    return Comparison(None, "none", "could not decide: the equations could not be evaluated reliably")


def _over_determined(reference: list[sympy.Expr], determined: set, parameters: Sampler) -> Comparison:
    """The request error of a reference with more equations than state variables in it: its equations
    then also fix parameters (``x + y = 1; x - y = 0`` with y untagged), and a factor (mixing) free of
    the state can carry any answer onto it at each parameter point, so no answer can be graded."""
    untagged = sorted(s.name for s in set().union(*(r.free_symbols for r in reference)) & set(parameters.domains))
    names = ", ".join(sorted(s.name for s in determined)) or "none"
    return Comparison(None, "none", f"the reference has {len(reference)} equations but only {len(determined)} "
                      f"variable{'s' * (len(determined) != 1)} to solve for ({names}): its equations also fix "
                      f"parameters, and it cannot be graded as equations. Give the variables the equations determine "
                      f"a kind (coordinate, force, answer, ...); the reference's variables read as parameters are: "
                      f"{', '.join(untagged) or 'none'}", evidence={"method": "request"})


# Parameter points drawn beyond the compared ones, each with its states, to meet the other sign
# patterns of the abs/sign arguments (see `grader.answers.equivalence._in_sign_regions`).
SIGN_REGION_PARAMETER_POINTS = 60


def _sign_region_points(exprs, parameters: Sampler, states: Sampler, start: int, n_states: int, backend):
    """Parameter-point indices from ``start`` on whose states meet a sign pattern of an abs/sign argument
    that no earlier point met (at most `MAX_PATTERNS` patterns)."""
    arguments = _kink_arguments(exprs)
    if not arguments:
        return
    try:
        kinks = [Compiled(argument, backend) for argument in arguments]
    except Unsupported:
        return
    seen: set = set()
    for p in range(start + SIGN_REGION_PARAMETER_POINTS):
        new = False
        for j in range(n_states):
            pattern = _sign_pattern(kinks, states.joint(parameters.point(p), states.point(p * n_states + j)))
            if pattern is not None and pattern not in seen:
                seen.add(pattern)
                new = True
        if len(seen) > MAX_PATTERNS:
            return
        if new and p >= start:
            yield p

# Further parameter points (ordinary and wide) at which a single equation's multiple is screened for
# a sign change, one state each.
SIGN_POINTS = 6


def _multiple_signs(ref: Compiled, ans: Compiled, parameters: Sampler, states: Sampler, start: int, target: float,
                    signs: dict) -> dict:
    """``signs`` with the sign of answer/reference at further parameter points, up to two signs.

    Either sign change proves the answer wrong: at those parameters the answer is the reference
    times a factor of the other sign, or no multiple of it at all."""
    prec = int(target) + 32
    points = [parameters.point(start + i) for i in range(SIGN_POINTS)]
    points += [parameters.wide_point(i) for i in range(SIGN_POINTS)]
    for i, params in enumerate(points):
        point = states.joint(params, states.point(i))
        try:
            r, _ = ref.at(point, prec)
            a, _ = ans.at(point, prec)
        except (Undefined, Unresolved):
            continue
        if r.contains(0) or a.contains(0) or not (r.is_finite() and a.is_finite()):
            continue
        signs.setdefault(1 if (r > 0) == (a > 0) else -1, params)
        if len(signs) == 2:
            break
    return signs


# Further parameter points (ordinary and wide) at which a system's mixing matrix is screened, k + 2 states each.
MIXING_SIGN_POINTS = 2


def _mixing_signs(refs: list[Compiled], anss: list[Compiled], parameters: Sampler, states: Sampler, start: int,
                  target: float, signs: dict, max_bits: int) -> dict:
    """`_multiple_signs` for a system: the sign of det M at further parameter points (a point where the
    answer is no combination at all is left to the points already compared)."""
    k, prec = len(refs), int(target) + 32
    points = [(start + i, parameters.point(start + i)) for i in range(MIXING_SIGN_POINTS)]
    points += [(start + MIXING_SIGN_POINTS + i, parameters.wide_point(i)) for i in range(MIXING_SIGN_POINTS)]
    for p, params in points:
        outcome, bits = None, prec
        while outcome is None and bits <= max_bits:  # more bits where a wide point's scales need them
            outcome = _try_precision(refs, anss, params, states, p, k, bits, target)
            bits *= 2
        if outcome is not None and outcome[0] == "agree":
            signs.setdefault(outcome[2], params)
            if len(signs) == 2:
                break
    return signs


def _parameter_dependence(reference, answer, refs, anss, parameters: Sampler, states: Sampler, start: int,
                          target: float, signs: dict, mixing, options: Options) -> Comparison | None:
    """For equations without accelerations: a refusal when the answer is the reference times a factor
    (a mixing matrix) of the parameters that vanishes (is singular) for some of their values, unless
    both equations have no solution there anyway (`_degenerate_there`); else None.

    Symbolically where the factor can be had (the ratio of single equations, the determinant of
    systems linear in the state); else by a sign change between parameter points."""
    k, state = len(reference), set(states.domains)

    def degenerate(base):
        return _degenerate_there(base, reference, answer, state, parameters.domains)

    ratio = _state_free_ratio(reference[0], answer[0], state) if k == 1 else None
    factor = _parameter_factor(reference, answer, parameters, states, exempt=degenerate, ratio=ratio)
    if factor is not None:
        return factor
    if k == 1:
        if ratio is not None:
            return None  # the whole ratio was analysed: a sign change is a degenerate equation's pole
        signs = _multiple_signs(refs[0], anss[0], parameters, states, start, target, signs)
        return _vanishing_multiple(k, signs) if len(signs) == 2 else None
    determinant = _state_free_determinant(reference, answer, state)
    if determinant is not None:
        for part in sympy.fraction(determinant):
            for base in _bases(part):
                if _nonzero_on(base, parameters.domains) is not True and not degenerate(base):
                    decided = _zero_or_nonzero(base, parameters.domains, [parameters.point(0), parameters.point(1)])
                    if decided is True:
                        continue
                    if isinstance(decided, dict):
                        return Comparison(False, "numeric", f"your equations are combinations of the reference "
                                          f"equations by a matrix whose determinant has the factor {base}, which "
                                          "depends on the parameters and is zero (or undefined) at the values in the "
                                          "counterexample: there your equations say less than the reference",
                                          evidence={"method": "root search"}, counterexample={"values": decided})
                    return Comparison(None, "none", f"your equations are combinations of the reference equations by "
                                      f"a matrix whose determinant has the factor {base}, which depends on the "
                                      "parameters and which the checker could neither prove nonzero for all their "
                                      "values nor find zero for any: it cannot decide whether your equations are "
                                      "right", evidence={"method": "symbolic"})
        return None
    if signs and len(_paired_rows(mixing, k)) < k:
        signs = _mixing_signs(refs, anss, parameters, states, start, target, signs, options.max_bits)
    return _vanishing_multiple(k, signs) if len(signs) == 2 else None


def _state_free_determinant(reference: list[sympy.Expr], answer: list[sympy.Expr], state: set):
    """det(answer's matrix)/det(reference's), factored, for systems linear in as many state variables
    as equations (the mixing matrix is then their quotient), else None."""
    present = sorted(set().union(*(r.free_symbols for r in reference + answer)) & state, key=lambda s: s.name)
    if len(present) != len(reference) or any(_nodes(r) > FACTOR_MAX_NODES for r in reference + answer):
        return None
    split_r, split_s = _linear_in(reference, tuple(present)), _linear_in(answer, tuple(present))
    if split_r is None or split_s is None:
        return None
    try:
        quotient = _factored(sympy.cancel(sympy.together(split_s[0].det(method="berkowitz")
                                                         / split_r[0].det(method="berkowitz"))))
    except (sympy.PolynomialError, ValueError, TypeError, ZeroDivisionError):
        return None
    return None if quotient.free_symbols & state else quotient


def _degenerate_there(base: sympy.Expr, reference: list[sympy.Expr], answer: list[sympy.Expr], state: set,
                      domains: dict) -> bool:
    """Whether neither system has a solution where ``base`` (of the parameters) vanishes: at resonance
    ``(k - m w^2) X = F0`` says ``-F0 = 0`` and ``X = F0/(k - m w^2)`` is undefined, so the factor
    ``k - m w^2`` between them changes no solution. Each system needs an equation undefined there
    (``base`` divides its denominator) or one that is a nonzero constant there (``base = 0`` solved
    for a parameter it is linear in)."""
    where = _zero_of(base)
    if where is None:
        return False

    def no_solution(system):
        for row in system:
            try:
                numerator, denominator = sympy.fraction(sympy.together(row))
                if not sympy.gcd(base, denominator).is_number:
                    return True
                there = sympy.cancel(numerator.xreplace(where))
            except (sympy.PolynomialError, ValueError, TypeError, ZeroDivisionError):
                continue
            if there != 0 and not there.free_symbols & state and _nonzero_on(there, domains) is True:
                return True
        return False

    return no_solution(reference) and no_solution(answer)


def _zero_of(base: sympy.Expr) -> dict | None:
    """``{p: value}`` with ``base`` zero at ``p = value``, for a parameter ``p`` it is linear in with a
    numeric coefficient, else None."""
    if _nodes(base) > FACTOR_MAX_NODES:
        return None
    for p in sorted(base.free_symbols, key=lambda s: s.name):
        slope = base.diff(p)
        if slope.is_number and slope != 0:
            return {p: sympy.expand(-base.xreplace({p: 0}) / slope)}
    return None


def _parameter_factor(reference: list[sympy.Expr], answer: list[sympy.Expr], parameters: Sampler,
                      states: Sampler, exempt=None, ratio: sympy.Expr | None = None) -> Comparison | None:
    """A refusal when an equation of the answer is multiplied (or divided) by a factor free of the
    state that cannot be shown nonzero for every value of the parameters, else None.

    A square does not change sign, so the parameter points cannot see ``(omega**2 - g/R)**2`` vanish;
    its base is then proved nonzero on the parameters' domains (`_nonzero_on`) or the answer refused.
    Only the factors the reference's own equation does not have are asked about."""
    state = set(states.domains)
    for i, row in enumerate(answer):
        own = set(sympy.Mul.make_args(reference[i])) if i < len(reference) else set()
        for factor in _common_factors(row):
            base = factor.base if factor.is_Pow and factor.exp.is_Integer else factor
            if base.is_number or base in own or factor in own or base.free_symbols & state \
                    or base.is_positive or base.is_negative:
                continue
            if _cancels_inside(row, factor, base):
                continue  # (g - c)*(l*thetaddot/(g - c) + ...): it cancels, as tan(x)*cos(x) does
            if _nonzero_on(base, parameters.domains) is not True and not (exempt and exempt(base)):
                verdict = _factor_may_vanish(base, f" {i + 1}" if len(answer) > 1 else "", parameters)
                if verdict is not None:
                    return verdict
    if len(answer) == 1 and len(reference) == 1:
        # The factor as a whole, not only as typed: (m1 - m2)^2 xddot = (m1 - m2)^3 g/(m1 + m2) has none in
        # common, and a square never changes sign between the parameter points.
        ratio = ratio if ratio is not None else _state_free_ratio(reference[0], answer[0], state)
        for part in sympy.fraction(ratio) if ratio is not None else ():
            if not part.is_number and _nonzero_on(part, parameters.domains) is not True and not (
                    exempt and all(_nonzero_on(base, parameters.domains) is True or exempt(base)
                                   for base in _bases(part))):
                verdict = _factor_may_vanish(ratio, "", parameters, part)
                if verdict is not None:
                    return verdict
    return None


def _parameter_mixing(reference: list[sympy.Expr], answer: list[sympy.Expr], unknowns: tuple, parameters: Sampler,
                      state: set, deadline: float | None = None) -> Comparison | None:
    """A refusal (or no verdict) for equations of motion mixed by a matrix free of the state whose determinant
    (det M_answer / det M_reference, their matrices in the accelerations) is not shown nonzero for every value of the
    parameters: [[1, sin α], [sin α, 1]] is singular at α = ±π/2. None where it is, or where the determinant
    cannot be had symbolically (too large, not linear in the accelerations, or depending on the state)."""
    present = tuple(u for u in unknowns if any(u in r.free_symbols for r in reference))
    if len(present) != len(reference) or any(_nodes(e) > FACTOR_MAX_NODES for e in (*reference, *answer)):
        return None
    split_r, split_s = _linear_in(reference, present), _linear_in(answer, present)
    if split_r is None or split_s is None:
        return None
    det_r, det_s = _determinant(split_r[0]), _determinant(split_s[0])
    if det_r is None or det_s is None or det_r == 0:
        return None
    try:
        ratio = _factored(sympy.cancel(sympy.together(det_s / det_r)))
    except (sympy.PolynomialError, ValueError, TypeError, ZeroDivisionError):
        return None
    if ratio.free_symbols & state:
        return None
    for base in (b for part in sympy.fraction(ratio) for b in _bases(part)):
        if _nonzero_on(base, parameters.domains) is True:
            continue
        decided = _zero_or_nonzero(base, parameters.domains, [parameters.point(0), parameters.point(1)], deadline)
        if decided is True:
            continue
        if isinstance(decided, dict):
            return Comparison(False, "numeric", "your equations are combinations of the reference equations by a "
                              f"matrix of the parameters whose determinant has the factor {base}, which is zero (or "
                              "undefined) at the values in the counterexample: there your equations no longer give "
                              "the motion", evidence={"method": "root search"}, counterexample={"values": decided})
        return Comparison(None, "none", "your equations are combinations of the reference equations by a matrix of the "
                          f"parameters whose determinant has the factor {base}, which the checker could neither prove "
                          "nonzero for all their values nor find zero for any: it cannot decide whether your "
                          "equations are right", evidence={"method": "symbolic"})
    return None


def _bases(product: sympy.Expr) -> list:
    """The factors of ``product`` that are not numbers, each without its integer power."""
    return [f.base if f.is_Pow and f.exp.is_Integer else f for f in sympy.Mul.make_args(product) if not f.is_number]


def _factor_may_vanish(factor: sympy.Expr, which: str, parameters: Sampler,
                       part: sympy.Expr | None = None) -> Comparison | None:
    """The verdict on an equation multiplied by ``factor`` (of the parameters; ``part``, its numerator or
    denominator, the one the first proof did not show nonzero): refused where it is found zero (a sign change or a
    zero it touches, `_zero_witness`), None where a proof with more boxes shows it nonzero after all (1.4143 − cos α
    − sin α), undecided otherwise: never refused on a guess."""
    part = factor if part is None else part
    decided = _zero_or_nonzero(part, parameters.domains, [parameters.point(0), parameters.point(1)])
    if isinstance(decided, dict):
        return Comparison(False, "numeric", f"your equation{which} is multiplied by {factor}, which depends on the "
                          "parameters and is zero (or undefined) at the values in the counterexample: there your "
                          "equation no longer gives the motion", evidence={"method": "root search"},
                          counterexample={"values": decided})
    if decided is True:
        return None
    return Comparison(None, "none", f"your equation{which} is multiplied by {factor}, which depends on the parameters "
                      "and which the checker could neither prove nonzero (and finite) for all their values nor find "
                      "zero for any: it cannot decide whether your equation is right", evidence={"method": "symbolic"})


def _state_free_ratio(reference: sympy.Expr, answer: sympy.Expr, state: set) -> sympy.Expr | None:
    """answer/reference cancelled, when it is free of the state and both are small enough, else None."""
    if _nodes(reference) > FACTOR_MAX_NODES or _nodes(answer) > FACTOR_MAX_NODES:
        return None
    try:
        ratio = sympy.cancel(sympy.together(_quotients_written_out(answer) / _quotients_written_out(reference)))
        if ratio.free_symbols & state:
            return None
        return _factored(ratio)  # (m1 - m2)**2, as the student wrote it, rather than multiplied out
    except (sympy.PolynomialError, ValueError, TypeError, ZeroDivisionError):
        return None


def _common_factors(expr: sympy.Expr) -> set:
    """The factors of ``expr`` as typed, or those every term of a sum has (``a**2*x - a**2*y``: ``a**2``);
    the intersection of the terms' factors is cheaper than `sympy.factor_terms`, and finds what was typed."""
    if not expr.is_Add:
        return set(sympy.Mul.make_args(expr))
    terms = iter(expr.args)
    common = set(sympy.Mul.make_args(next(terms)))
    for term in terms:
        common &= set(sympy.Mul.make_args(term))
        if not common:
            break
    return common


def _common_factor_kept(total: sympy.Add, domains: dict) -> sympy.Expr:
    """``total`` as a sum F·(c₁ + c₂ + …) is F alone, where F is the sum most of its terms multiply and the
    cofactor is nonzero on the whole domain (the same solutions); else ``total`` itself. Terms without F
    are divided by it, where that leaves no state in a denominator: sympy multiplies out (x − y)/2.

    >>> x, y = sympy.symbols("x y", real=True)
    >>> from grader.expressions import parse_domain
    >>> domains = {x: parse_domain("real"), y: parse_domain("real")}
    >>> _common_factor_kept((x - y)/2 + (x - y)*x**2 + (x - y)*y**2, domains)
    x - y
    >>> _common_factor_kept((x - y)/2 - (x - y)*x**2 + (x - y)*y**2, domains)  # 1/2 − x² + y² vanishes
    -x**2*(x - y) + x/2 + y**2*(x - y) - y/2
    """
    terms = total.args
    sums = collections.Counter(f for term in terms for f in sympy.Mul.make_args(term) if f.is_Add)
    if not sums:
        return total
    factor, count = sums.most_common(1)[0]
    if 2 * count < len(terms):
        return total
    with_factor = [t for t in terms if factor in sympy.Mul.make_args(t)]
    cofactor = [sympy.Mul(*[f for f in sympy.Mul.make_args(t) if f != factor]) for t in with_factor]
    rest = [t for t in terms if factor not in sympy.Mul.make_args(t)]
    # Only where the pieces are small (the factor is then compared with the reference under the same limit): a
    # triple pendulum's row times (2 + cos θ₁) has a thousand-node sum as its factor or its cofactor, and
    # cancelling or bounding that took minutes.
    sizes = [_nodes(e) for e in (factor, *cofactor, *rest)]
    if max(sizes) > FACTOR_MAX_NODES or sum(sizes) > 2 * FACTOR_MAX_NODES:
        return total
    if rest:
        try:
            quotient = budget.attempt(lambda: sympy.cancel(sympy.Add(*rest) / factor), FACTOR_BUDGET_S,
                                      fallback=lambda: None)
        except (sympy.PolynomialError, ValueError, TypeError, ZeroDivisionError):
            return total
        if quotient is None:
            return total
        positive = {s for s, d in domains.items() if getattr(d, "kind", None) == "positive"}
        if sympy.fraction(quotient)[1].free_symbols - positive:
            return total  # F does not divide them: no such product
        cofactor.append(quotient)
    return factor if _nonzero_on(sympy.Add(*cofactor), domains) is True else total


def _cancels_inside(row: sympy.Expr, factor: sympy.Expr, base: sympy.Expr) -> bool:
    """Whether the rest of ``row`` divides by ``base`` where ``factor`` multiplies by it (or the other way):
    then the product is defined and the same where ``base`` vanishes (a removable point), no factor."""
    try:
        numerator, denominator = sympy.fraction(sympy.together(row / factor))
    except (sympy.PolynomialError, ValueError, TypeError, ZeroDivisionError):
        return False
    divides = factor.is_Pow and factor.exp.is_negative
    return (numerator if divides else denominator).has(base)


def _vanishing_multiple(k: int, signs: dict) -> Comparison:
    """The answer is the reference times a factor (``k = 1``) or a mixing matrix free of the state whose
    determinant has opposite signs at two parameter points: on the connected parameter domain it
    vanishes (or has a pole) in between, and for those parameters the answer says nothing or is undefined:
    ``(omega**2 - g/R)*(thetaddot - ...) = 0``, ``xddot/(m1 - m2) = g/(m1 + m2)``."""
    what = ("your equation is the reference multiplied by a factor" if k == 1 else
            "your equations are combinations of the reference equations by a matrix")
    why = ("zero or undefined" if k == 1 else "singular or undefined")
    return Comparison(False, "numeric", f"{what} that depends on the parameters and changes sign between the two "
                      f"parameter values in the counterexample: it is {why} for some parameters in between, where "
                      "your answer no longer gives the motion", evidence={"method": "ball arithmetic"},
                      counterexample={"values": _named(signs[1]), "other_parameters": _named(signs[-1])})


def _hidden_difference(reference: list[sympy.Expr], answer: list[sympy.Expr], unknowns: tuple, parameters: Sampler,
                       states: Sampler, options: Options) -> Comparison | None:
    """A difference below the judge's digits between an equation and the reference, or None.

    ``θ̈ = −(g/l) sin θ (1 + 10⁻⁴⁰)`` is a multiple of the reference to 40 digits at every point.
    Both solved for an acceleration that appears linearly (each residual divided by its
    coefficient, products distributed), sympy's exact arithmetic leaves their difference,
    ``−g sin θ/(10⁴⁰ l)``: its ball excluding zero at a sample point proves the equations differ.
    Only a difference in which sympy combined terms is evaluated.
    """
    r, a = reference[0], answer[0]
    if _too_big(r) or _too_big(a):
        return None  # its expansion is not worth a check's budget: the points' verdict stands
    for u in unknowns or tuple(states.domains):
        if not r.has(u):
            continue
        a_u, r_u = a.diff(u), r.diff(u)
        if a_u == 0 or r_u == 0 or a_u.has(u) or r_u.has(u):
            return None  # not linear in u: nothing to solve for
        solved_a, solved_r = sympy.expand_mul(a / a_u), sympy.expand_mul(r / r_u)
        d = solved_a - solved_r
        if d == 0 or len(sympy.Add.make_args(d)) >= len(sympy.Add.make_args(solved_a)) + len(
                sympy.Add.make_args(solved_r)):
            return None
        point = states.joint(parameters.point(0), states.point(0))
        try:
            value, _ = Compiled(d, options.backend()).at(point, int(options.digits * LOG2_10) + 32)
        except (Undefined, Unresolved, Unsupported):
            return None
        if value.contains(0):
            return None
        return Comparison(False, "proved", f"solved for {u.name}, your equation and the reference differ at the "
                          "counterexample (by less than the judge's digits)",
                          evidence={"method": "ball arithmetic", "points": 1},
                          counterexample={"values": _named(point), "difference": as_float(value)})
    return None


def _paired_rows(mixing, k: int) -> list[tuple[int, int]]:
    """``(i, j)``: the answer's equation i is a multiple of the reference's equation j alone (row i of the
    mixing matrix has one entry that excludes zero, the others contain it); every equation when k = 1.
    Only such a pair may be compared by `_hidden_difference`: a combination of several reference
    equations, solved for an acceleration, differs from each of them."""
    if k == 1:
        return [(0, 0)]
    if mixing is None:
        return []
    pairs = []
    for i in range(k):
        nonzero = [j for j in range(k) if not mixing[i, j].contains(0)]
        if len(nonzero) == 1:
            pairs.append((i, nonzero[0]))
    return pairs


def _too_big(expr: sympy.Expr) -> bool:
    """More than FACTOR_MAX_NODES nodes (a stack walk that stops there)."""
    stack, nodes = [expr], 0
    while stack:
        nodes += 1
        if nodes > FACTOR_MAX_NODES:
            return True
        stack.extend(stack.pop().args)
    return False


def _values(compiled: list[Compiled], point: dict, prec: int, key):
    values, scale = [], -math.inf
    for i, c in enumerate(compiled):
        v, s = c.at(point, prec, None if key is None else (key, i))
        values.append(v)
        scale = max(scale, s, _log2_mag(v))
    return values, scale


def _one_parameter_point(refs, anss, parameters, states, p, target, options, deadline):
    """At parameter point p: ("agree", digits, sign of det M, M) | ("differ", reason, counterexample) | ("skip",)
    | ("budget",)."""
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
        point = states.joint(params, states.point(p * n_states + j))
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
            return ("differ", f"{_UNDEFINED_WHERE} ({error.reason})", example)
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
        det_m = M.det()
        if not det_m.contains(0):
            return ("agree", (scale - noise) / LOG2_10, 1 if det_m > 0 else -1, M)
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
        reason = f"{_NOT_A_COMBINATION} (equation {i + 1} fails at the counterexample)"
        example = {"values": _named(points[j]), "answer": [as_float(v) for v in S[j]],
                   "reference": [as_float(v) for v in R[j]]}
    return reason, example


class _AllRows:
    """The rows of a system, compiled, as one `Compiled` for `_where_defined`: defined where every row is."""

    def __init__(self, rows: list[Compiled]):
        self._rows = rows

    def at(self, point: dict, prec: int, key=None):
        return [row.at(point, prec) for row in self._rows][0]  # each row raises where it is undefined


def _rows_peeled(reference, answer, domains, parameters, states, options, deadline, compiled_reference,
                 unknowns) -> Comparison | None:
    """The verdict of the systems with each row ``f(A) = f(B)`` (``f`` one-to-one: an odd power, exp, atan, a log
    of positive quantities; `_injective_sides`, `_logs_exponentiated`) read as ``A = B``, on the answer's side,
    the reference's or both, where that makes them the same; else None."""
    def peel(rows):
        return [_injective_sides(r, domains) or _logs_exponentiated(r) or r for r in rows]

    peeled, peeled_reference = peel(answer), peel(reference)
    for ref_form, answer_form in ((reference, peeled), (peeled_reference, answer), (peeled_reference, peeled)):
        if (ref_form == reference and answer_form == answer) or _past(deadline) or _PEELED.get() >= MAX_PEELED:
            continue
        token = _PEELED.set(_PEELED.get() + 1)
        try:
            again = compare_equations(ref_form, answer_form, parameters, states, options, deadline,
                                      compiled_reference if ref_form is reference else None, (), unknowns)
        finally:
            _PEELED.reset(token)
        if again.equivalent:
            again.reason = ("the same solutions as the reference: an equation f(A) = f(B), with f taking each value "
                            "once (an odd power, exp, atan, log of positive quantities), holds exactly where A = B, "
                            f"and with such equations so read, {again.reason}")
            return again
    return None


def _undefined_where_the_reference_holds(reference: sympy.Expr, answer: Compiled, example: dict,
                                        parameters: Sampler, states: Sampler) -> dict | None:
    """A state where the reference equation ``reference = 0`` holds and the compiled ``answer`` (with its typed
    real domain) is undefined, or None: the roots of the reference along each state variable from the state
    of ``example`` (a counterexample where the answer is undefined), the other variables kept, found as the
    kink search finds an argument's zeros (`_breakpoints`), each inside its domain and the declared orders."""
    domains = {**parameters.domains, **states.domains}
    named = example.get("values") or {}
    base = {s: float(named[s.name]) for s in domains if s.name in named}
    below = {**parameters.below, **states.below, **parameters.across, **states.across}
    try:
        residual = compile_expr(reference, FloatBackend())
    except Unsupported:
        return None
    for symbol in sorted(reference.free_symbols & set(states.domains), key=lambda s: s.name):
        span = _span(domains[symbol])
        if span is None or symbol not in base:
            continue
        for t in _breakpoints(reference, (0,), symbol, base, span)[:MAX_LOST_ROOTS]:
            point = {**base, symbol: t}
            if not domains[symbol].contains(t) or not all(
                    point[a] < point[b] for a, b in below.items() if a in point and b in point):
                continue
            # a root, not one of the extrema _breakpoints also returns: the residual changes sign across it
            step = 1e-9 * max(1.0, abs(t))
            env = {s: float(v) for s, v in base.items()}
            left, right = (_float_at(residual, env, symbol, t + d) for d in (-step, step))
            if left is None or right is None or (left > 0) == (right > 0) or left == 0 or right == 0:
                continue
            try:
                answer.at(point, CONFIRM_BITS)
            except Undefined:
                return point
            except Unresolved:
                continue
    return None


# Roots of the reference looked at along each state variable for a state the answer's domain leaves out.
MAX_LOST_ROOTS = 16
_NOT_A_MULTIPLE = "your equation is not the reference multiplied by a factor free of the state"
_UNDEFINED_WHERE = "your equation is undefined at a state where the reference is not"
_NOT_A_COMBINATION = ("your equations are not combinations of the reference equations with coefficients free of "
                      "the state")
# Largest residuals (in nodes) whose ratio is worth a symbolic cancellation.
FACTOR_MAX_NODES = 200
# Highest integer power worth cancelling symbolically.
FACTOR_MAX_POWER = 8
# Boxes the ball-arithmetic proof may split a bounded domain into.
FACTOR_MAX_BOXES = 256
# Boxes of the second proof, tried only for a factor the first neither proved nonzero nor saw change sign.
FACTOR_MORE_BOXES = 8192
# Working digits of the search for a zero such a factor touches, and the size (relative to the factor's value where
# the search starts) below which a value found there counts as zero.
WITNESS_DPS = 40
WITNESS_ZERO = mpmath.mpf(10) ** -30
WITNESS_STEPS = 10
# mnewton for a zero touched without a sign change; the secant method where mnewton leaves the domain (−cot θ from
# θ = 0.76 jumps to −7π/2, not to π/2)
WITNESS_SOLVERS = ("mnewton", "secant")
# Points of the scan along each variable's domain, and how many of the least values found there start a search.
WITNESS_SCAN_POINTS = 64
WITNESS_SCAN_STARTS = 2


def state_dependent_factor(reference: sympy.Expr, answer: sympy.Expr, domains: dict,
                           samplers: tuple[Sampler, Sampler] | None = None,
                           deadline: float | None = None) -> Comparison | None:
    """`_state_dependent_factor`, tried again with every positive variable under a root written as
    the square of a new positive variable when the first try finds no nonzero factor: ``T = 2 pi
    sqrt(L/g)`` against ``g = 4 pi^2 L/T^2`` (all positive) is a multiple that sympy cancels only once
    ``sqrt(L/g)`` is ``l/k`` with ``L = l^2``, ``g = k^2`` (a bijection of the positive reals, so a
    factor nonzero in the new variables is nonzero in the old)."""
    found = _state_dependent_factor(reference, answer, domains, samplers, deadline)
    if found is not None and found.equivalent:
        return found
    squares = _positive_roots_as_squares(reference, answer, domains)
    if squares is not None and not (deadline is not None and time.monotonic() > deadline):
        again = _state_dependent_factor(*squares, samplers=None, deadline=deadline)
        if again is not None and again.equivalent:
            return again
    # l(M + m - m cos²θ) θ̈ = … is the reference times l(M + m sin²θ): cancel takes sin θ and cos θ for
    # unrelated symbols, so the factor cancels only once every cos² is written 1 - sin² on both sides, products
    # multiplied out first (m cos θ (l θ̈ cos θ - …)); the same values, so a factor found nonzero there is
    # nonzero here.
    # sin 2θ and cos 2θ likewise: the factor of θ̈ (2 + sin θ cos θ) = −(g/l) sin θ (2 + sin 2θ/2) cancels only
    # once the double angle is written with θ's own sine and cosine.
    pythagorean = tuple(_pythagorean(sympy.expand(_in_single_angles(e), trig=False)
                                     if _nodes(e) <= FACTOR_MAX_NODES else e)
                        for e in (reference, answer))
    if pythagorean != (reference, answer) and not (deadline is not None and time.monotonic() > deadline):
        again = _state_dependent_factor(*pythagorean, domains, samplers, deadline)
        if again is not None and (again.equivalent or found is None):
            return again  # (or a multiple by a factor that vanishes: a truer reason than "not a multiple")
    return found


_SQUARE_AS_ONE_LESS = {sympy.cos: (sympy.sin, -1), sympy.cosh: (sympy.sinh, 1)}
# Largest whole multiple of an angle written out with the angle's own sine and cosine (sin 12θ has 7 terms).
MAX_MULTIPLE_ANGLE = 12


def _in_single_angles(expr: sympy.Expr) -> sympy.Expr:
    """``expr`` with the sine and cosine of each small whole multiple of an argument (sin 2θ, cos 3φ) written
    with the argument's own sine and cosine: the same values, one form.

    >>> t = sympy.Symbol("theta")
    >>> _in_single_angles(2 + sympy.sin(2*t)/2)
    sin(theta)*cos(theta) + 2
    """
    def multiple(f) -> bool:
        factor = f.args[0].as_coeff_Mul()[0]
        return factor.is_Integer and 2 <= abs(factor) <= MAX_MULTIPLE_ANGLE

    multiples = {f: sympy.expand_trig(f) for f in expr.atoms(sympy.sin, sympy.cos) if multiple(f)}
    return expr.xreplace(multiples) if multiples else expr


def _pythagorean(expr: sympy.Expr) -> sympy.Expr:
    """``expr`` with every power cos(u)ⁿ (|n| ≥ 2) written with (1 - sin(u)²) for each cos(u)², and cosh(u)ⁿ
    with (1 + sinh(u)²): one form for the values sin² + cos² = 1 makes equal.

    >>> t = sympy.Symbol("theta")
    >>> _pythagorean(2 + sympy.cos(t)**3)
    (1 - sin(theta)**2)*cos(theta) + 2
    """
    def rewritten(power: sympy.Pow) -> sympy.Expr:
        other, sign = _SQUARE_AS_ONE_LESS[power.base.func]
        n = int(power.exp)
        form = power.base ** (abs(n) % 2) * (1 + sign * other(*power.base.args) ** 2) ** (abs(n) // 2)
        return form if n > 0 else 1 / form

    return expr.replace(lambda e: e.is_Pow and e.base.func in _SQUARE_AS_ONE_LESS and e.exp.is_Integer
                        and abs(e.exp) >= 2, rewritten)


def _positive_roots_as_squares(reference: sympy.Expr, answer: sympy.Expr, domains: dict):
    """(reference, answer, domains) with each positive variable that appears under a fractional power
    replaced by the square of a new positive variable, or None when there is none."""
    under_roots = set()
    for expr in (reference, answer):
        for power in expr.atoms(sympy.Pow):
            if power.exp.is_Rational and not power.exp.is_Integer:
                under_roots |= {s for s in power.base.free_symbols
                                if getattr(domains.get(s), "kind", None) == "positive"}
    if not under_roots:
        return None
    squares = {s: sympy.Dummy(s.name, positive=True) for s in under_roots}
    replacement = {s: t**2 for s, t in squares.items()}
    new_domains = {squares.get(s, s): d for s, d in domains.items()}
    return reference.xreplace(replacement), answer.xreplace(replacement), new_domains


def _state_dependent_factor(reference: sympy.Expr, answer: sympy.Expr, domains: dict,
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
    # A factor nonzero on the whole domain ((1 + theta**2)**400, (2 + cos(theta))**4 (3 + sin(theta))**4)
    # changes no solution: set it aside rather than make cancel multiply it out (past the size limits,
    # where the product of nonzero factors could be shown nonzero by no rule). Also one every term has.
    set_aside = [f for f in _common_factors(answer) if not f.is_number
                 and _nonzero_on(f.base if f.is_Pow and f.exp.is_Integer else f, domains) is True]
    if set_aside:
        if answer.is_Add:
            answer = sympy.Add(*[sympy.Mul(*[g for g in sympy.Mul.make_args(t) if g not in set_aside])
                                 for t in answer.args])
        else:
            answer = sympy.Mul(*[g for g in sympy.Mul.make_args(answer) if g not in set_aside])
    if answer.is_Add and _nodes(answer) > FACTOR_MAX_NODES:
        # The reference multiplied into every term of a sum that is nonzero on the domain ((l θ̈/g + sin θ) cos^k θ/(k + 2)
        # over k = 0…11): too large to cancel as typed, the reference once the sum is shown nonzero.
        answer = _common_factor_kept(answer, domains)
    if not (_nodes(reference) <= FACTOR_MAX_NODES and _nodes(answer) <= FACTOR_MAX_NODES):
        return None
    # a = g tan(theta) is a*cos(theta) = g*sin(theta) over cos(theta): only as a quotient does the factor cancel
    reference, answer = _quotients_written_out(reference), _quotients_written_out(answer)
    try:
        ratio = sympy.together(answer / reference)
        # a root of a number (sqrt(2 g h) = sqrt(2) sqrt(g) sqrt(h)) cancels only in its extension
        roots = any(p.base.is_Rational and not p.exp.is_Integer for p in ratio.atoms(sympy.Pow))
        ratio = sympy.cancel(ratio, extension=True) if roots else sympy.cancel(ratio)
    except (sympy.PolynomialError, ValueError, TypeError, ZeroDivisionError, NotImplementedError):
        return None
    numerator, denominator = sympy.fraction(ratio)
    if deadline is not None and time.monotonic() > deadline:
        return None
    # A denominator that vanishes only where the answer does (x = 1 against (x - 1)**3 = 0: the ratio
    # is 1/(x - 1)**2) removes no solution either.
    rest_of_denominator = _without_powers_of(denominator, answer)
    if _nonzero_on(rest_of_denominator, domains) is not True:
        return None  # not a multiple of the reference at all
    rest = _without_powers_of(numerator, reference)
    if _nonzero_on(rest, domains) is True:
        if rest == numerator and rest_of_denominator == denominator:
            return Comparison(True, "proved", "the reference multiplied by a factor that depends on the state "
                              "and is nonzero on the whole declared domain", evidence={"method": "symbolic"})
        return Comparison(True, "proved", "the same solutions as the reference: your equation is the reference "
                          "multiplied by a factor that is zero or undefined only where both equations hold",
                          evidence={"method": "symbolic"})
    numerator = rest
    example = _sign_change(numerator, *samplers) if samplers is not None else None
    undefined = _where_the_reference_is_undefined(numerator, [reference], domains)
    if undefined:
        # sin(theta) against phiddot = -2 thetadot phidot cos(theta)/sin(theta): zero only where the reference is
        # undefined; "there your equation no longer determines the motion" would be false
        return Comparison(False, "proved" if example is not None else "numeric",
                          "your equation is the reference multiplied by a factor that is zero only where the "
                          f"reference itself is undefined (where {' or '.join(f'{sympy.sstr(f)} = 0' for f in undefined)}"
                          f", which {'the declared domain includes' if example is not None else 'could not be excluded from the declared domain'}"
                          "): everywhere else they are the same equation, but there yours still says something "
                          "where the reference says nothing, so it is not accepted as the reference's on the "
                          "declared domain", evidence={"method": "symbolic"}, counterexample=example)
    if example is not None:
        return Comparison(False, "proved", "your equation is the reference multiplied by a factor that depends "
                          "on the state and is zero somewhere in the declared domain (it changes sign between "
                          "the two states in the counterexample): there your equation no longer determines "
                          "the motion", evidence={"method": "ball arithmetic"}, counterexample=example)
    # Neither proved nonzero nor seen to change sign: a factor that touches zero (1 + cos θ at θ = π, θ̇², l θ̇² +
    # g(1 − cos θ) at rest at the bottom) is found where it vanishes; one that stays off zero by less than the first
    # proof's boxes resolve (1.4143 − cos θ − sin θ ≥ 8.6e-5) is proved with more. Either way never a guess.
    start = _first_state(*samplers) if samplers is not None else _domain_point(numerator, domains)
    decided = _zero_or_nonzero(numerator, domains, [start], deadline)
    if isinstance(decided, dict):
        return Comparison(False, "numeric", "your equation is the reference multiplied by a factor that depends on "
                          "the state and is zero (or undefined) at the state in the counterexample (to 30 digits): "
                          "there your equation no longer determines the motion",
                          evidence={"method": "root search"}, counterexample={"values": decided})
    if decided is True:
        return Comparison(True, "proved", "the reference multiplied by a factor that depends on the state and is "
                          "nonzero on the whole declared domain", evidence={"method": "ball arithmetic"})
    return Comparison(None, "none", "your equation is the reference multiplied by a factor that depends on the state, "
                      "which the checker could neither prove nonzero on the whole declared domain nor find zero "
                      "anywhere in it: it cannot decide whether your equation is right", evidence={"method": "symbolic"})


_QUOTIENTS = {sympy.tan: lambda u: sympy.sin(u) / sympy.cos(u), sympy.cot: lambda u: sympy.cos(u) / sympy.sin(u),
              sympy.sec: lambda u: 1 / sympy.cos(u), sympy.csc: lambda u: 1 / sympy.sin(u),
              sympy.tanh: lambda u: sympy.sinh(u) / sympy.cosh(u), sympy.coth: lambda u: sympy.cosh(u) / sympy.sinh(u),
              sympy.sech: lambda u: 1 / sympy.cosh(u), sympy.csch: lambda u: 1 / sympy.sinh(u)}


def _quotients_written_out(expr: sympy.Expr) -> sympy.Expr:
    """``expr`` with tan, cot, sec, csc and their hyperbolic kin written as quotients of sin and cos (sinh
    and cosh): the same function, defined at the same points."""
    found = expr.atoms(*_QUOTIENTS)
    if not found:
        return expr
    return expr.xreplace({f: _QUOTIENTS[type(f)](f.args[0]) for f in found})


def _without_powers_of(numerator: sympy.Expr, reference: sympy.Expr) -> sympy.Expr:
    """``numerator`` with every factor it shares with the reference's own numerator divided out, as
    often as it goes (their greatest common divisor, so a part of the reference counts too).

    A factor that vanishes only where the reference does adds no solution: ``(l*thetaddot + g*sin(theta))**2 = 0``
    holds exactly where the reference does, and ``(x - 1)*(x + 3) = 0`` where ``(x - 1)**2*(x + 3) = 0``
    does, so only the rest of the factor must be nonzero."""
    try:
        own = sympy.fraction(sympy.together(reference))[0]
        if own.is_number:
            return numerator
        for _ in range(FACTOR_MAX_POWER):
            common = sympy.gcd(numerator, own)
            if common.is_number:
                break
            numerator = sympy.cancel(numerator / common)
    except (sympy.polys.polyerrors.BasePolynomialError, ValueError, TypeError, ZeroDivisionError):
        pass
    return numerator


# Largest system whose mixing matrix is worth symbolic determinants.
MIXING_MAX_EQUATIONS = 4
# Largest residual (in nodes) worth splitting into coefficients of the accelerations.
MIXING_MAX_NODES = 600
# Largest identity row (in nodes) worth the symbolic proof.
IDENTITY_MAX_NODES = 1000
# Parameter points and states per parameter point of the numeric screen of the combination.
MIXING_POINTS, MIXING_STATES = 3, 3


def state_dependent_mixing(reference: list[sympy.Expr], answer: list[sympy.Expr], unknowns: tuple, domains: dict,
                           samplers: tuple[Sampler, Sampler], options: Options = Options(),
                           deadline: float | None = None) -> Comparison | None:
    """Are the answer's equations ``A(state) @`` the reference's, with ``A`` invertible on the whole domain?

    Equations of motion are linear in the accelerations ``a`` (``unknowns``): ``R = M_r a + c_r``
    and ``S = M_s a + c_s``. Then ``S = A R`` for a matrix ``A`` free of the accelerations exactly
    when ``A = M_s M_r**-1`` and ``c_s = A c_r``; the equations are the same equations wherever
    ``det A = det M_s / det M_r`` is nonzero. So the solved reference ``thetaddot1 = f1,
    thetaddot2 = f2`` and the student's unsolved Lagrange form ``M(q) qddot + ... = 0`` are one
    system, because the mass matrix is invertible everywhere; a row multiplied by ``thetadot`` (or
    by ``cos(theta)`` on (-pi, pi)) is not, because there the system says less.

    ``c_s = A c_r`` is screened in ball arithmetic at sample points, then proved symbolically
    (rational functions, and sines and cosines of sums of the variables reduced with
    ``sin**2 + cos**2 = 1``); both determinants are proved nonzero (and the coefficients finite)
    on the whole declared domain with `_nonzero_on`. Only a proof accepts.

    Returns a verdict (for a system that is no such combination, with the accelerations each system
    gives at the counterexample), or None when this does not apply (not linear in the accelerations,
    not as many accelerations as equations, a reference whose own matrix may be singular) or cannot
    show more than the caller's own counterexample.

    Examples
    --------
    >>> import sympy
    >>> from grader.answers.sampling import Sampler
    >>> from grader.expressions import parse_domain
    >>> k, m, r = sympy.symbols("k m r", positive=True)
    >>> rdot, thetadot, rddot, thetaddot = sympy.symbols("rdot thetadot rddot thetaddot", real=True)
    >>> real, positive = parse_domain("real"), parse_domain("positive")
    >>> P = Sampler({k: positive, m: positive}, seed=1)
    >>> S = Sampler({r: positive, rdot: real, thetadot: real, rddot: real, thetaddot: real}, seed=2)
    >>> solved = [rddot - r*thetadot**2 + k/(m*r**2), thetaddot + 2*rdot*thetadot/r]
    >>> lagrange = [m*solved[0], m*r**2*thetaddot + 2*m*r*rdot*thetadot]   # d/dt(m r^2 thetadot) = 0
    >>> domains = {**P.domains, **S.domains}
    >>> state_dependent_mixing(solved, lagrange, (rddot, thetaddot), domains, (P, S)).certainty
    'proved'
    >>> v = state_dependent_mixing(solved, [thetadot*solved[0], solved[1]], (rddot, thetaddot), domains, (P, S))
    >>> v.equivalent, v.certainty, "singular somewhere" in v.reason
    (False, 'proved', True)
    """
    k = len(reference)
    if not (1 <= k and len(answer) == k and len(unknowns) == k):
        return None
    if k > MIXING_MAX_EQUATIONS or not all(_nodes(e, MIXING_MAX_NODES) <= MIXING_MAX_NODES
                                           for e in (*reference, *answer)):
        return _mixing_at_points(reference, answer, unknowns, domains, samplers, options, deadline)
    split_r, split_s = _linear_in(reference, unknowns), _linear_in(answer, unknowns)
    if split_r is None or split_s is None:
        return None
    (m_r, c_r), (m_s, c_s) = split_r, split_s
    try:
        det_r = sympy.cancel(sympy.together(m_r.det(method="berkowitz")))
    except (sympy.PolynomialError, ValueError, TypeError, ZeroDivisionError):
        return None
    # The reference's own matrix must be invertible everywhere, with finite coefficients, for A to exist.
    if not (_finite_on(m_r, domains) and _nonzero_on(det_r, domains) is True):
        return None
    screened = _combination_at_points(m_r, c_r, m_s, c_s, unknowns, samplers, options, deadline)
    if isinstance(screened, dict) and screened:
        return _other_accelerations(screened)
    if _past(deadline):
        return _out_of_time()  # not a wrong answer for want of time: the Lagrange form takes this path
    if screened != "agree":
        return None
    det_s = _determinant(m_s)
    if det_s is None:
        return None
    if det_s == 0:
        return _not_independent()
    if not _finite_on(m_s, domains):
        return Comparison(False, "numeric", "your equations are combinations of the reference equations with "
                          "coefficients that could not be shown finite on the whole declared domain",
                          evidence={"method": "symbolic"})
    numerator = _factored(sympy.fraction(det_s)[0])
    if _nonzero_on(numerator, domains) is not True:
        example = _vanishing_factor(numerator, domains, samplers)
        undefined = _where_the_reference_is_undefined(numerator, [*m_r, *c_r], domains)
        if undefined:
            # sin(theta)**2 against phiddot = -2 thetadot phidot cos(theta)/sin(theta): singular only where the
            # reference says nothing either; "there your equations no longer determine the motion" would be false
            return Comparison(False, "proved" if example is not None else "numeric",
                              "your equations are combinations of the reference equations whose mixing matrix is "
                              "singular only where the reference itself is undefined (where "
                              f"{' or '.join(f'{sympy.sstr(f)} = 0' for f in undefined)}, which "
                              f"{'the declared domain includes' if example is not None else 'could not be excluded from the declared domain'}"
                              "): everywhere else they are the same equations, but there they still say "
                              "something where the reference says nothing, so they are not accepted as the "
                              "reference's on the declared domain", evidence={"method": "symbolic"},
                              counterexample=example)
        if example is not None:
            return Comparison(False, "proved", _SINGULAR_MIXING, evidence={"method": "ball arithmetic"},
                              counterexample=example)
        decided = _zero_or_nonzero(numerator, domains, [_first_state(*samplers)], deadline)
        if isinstance(decided, dict):
            return Comparison(False, "numeric", "your equations are combinations of the reference equations whose "
                              "mixing matrix depends on the state and is singular at the state in the counterexample "
                              "(its determinant is zero or undefined there, to 30 digits): there your equations no "
                              "longer determine the motion",
                              evidence={"method": "root search"}, counterexample={"values": decided})
        if decided is not True:
            return Comparison(None, "none", "your equations are combinations of the reference equations whose mixing "
                              "matrix depends on the state, and which the checker could neither prove invertible on "
                              "the whole declared domain nor find singular anywhere in it: it cannot decide whether "
                              "your equations are right", evidence={"method": "symbolic"})
    proved = _combination_proved(m_r, c_r, m_s, c_s, deadline)
    if proved is None:
        return _out_of_time()
    if not proved:
        return Comparison(False, "numeric", "your equations agree with combinations of the reference equations "
                          "with state-dependent coefficients at every sample point, but that could not be proved",
                          evidence={"method": "ball arithmetic"})
    return Comparison(True, "proved", "combinations of the reference equations with coefficients that depend on "
                      "the state, whose mixing matrix is invertible on the whole declared domain",
                      evidence={"method": "symbolic"})


# Largest residual (in nodes) whose coefficients are worth evaluating at points when it is too large for the proof.
MIXING_NUMERIC_MAX_NODES = 20000


def _other_accelerations(example: dict) -> Comparison:
    """The verdict where the answer's rows, solved for the unknowns at a point, give other accelerations."""
    return Comparison(False, "proved", "your equations are not combinations of the reference equations, not "
                      "even with coefficients that depend on the state: they give other accelerations (see "
                      "the counterexample)", evidence={"method": "ball arithmetic"}, counterexample=example)


def _mixing_at_points(reference: list[sympy.Expr], answer: list[sympy.Expr], unknowns: tuple, domains: dict,
                      samplers: tuple[Sampler, Sampler], options: Options, deadline: float | None) -> Comparison:
    """`state_dependent_mixing` for systems too large for its symbolic proof (a triple pendulum's solved
    accelerations against its Lagrange form ``M(q) a = F``, a thousand nodes a row): both linear in the
    unknowns, the answer's rows solved for them at sample points must give the reference's (in ball
    arithmetic, confirmed at `CONFIRM_BITS` at one point), and the mixing matrix must be invertible: its
    determinant ``det M_s / det M_r`` proved nonzero on the whole domain when both matrices are small enough
    (the mass matrix of the Lagrange form, the identity of the solved form), else nonzero and of one sign at
    the sample points. Never a proof of equivalence: accepted with certainty "numeric"; a point where
    the accelerations differ proves the systems different; anything else is an honest "numeric"
    refusal that names the size."""
    too_large = Comparison(False, "numeric", "your equations are not combinations of the reference equations "
                           "with coefficients free of the state; they may still be combinations with coefficients "
                           "that depend on the state, but the system is too large to analyse for that (simplify "
                           "it and submit again)", evidence={"method": "ball arithmetic",
                                                              "mixing": "not analysed (too large)"})
    if not all(_nodes(e, MIXING_NUMERIC_MAX_NODES) <= MIXING_NUMERIC_MAX_NODES for e in (*reference, *answer)):
        return too_large
    split_r, split_s = _linear_in(reference, unknowns), _linear_in(answer, unknowns)
    if split_r is None or split_s is None:
        return too_large
    (m_r, c_r), (m_s, c_s) = split_r, split_s
    screened = _combination_at_points(m_r, c_r, m_s, c_s, unknowns, samplers, options, deadline)
    if isinstance(screened, dict) and screened:
        return _other_accelerations(screened)
    if _past(deadline):
        return _out_of_time()
    if screened != "agree":
        return too_large
    k = len(unknowns)
    parameters, states = samplers
    try:
        compiled = [Compiled(e, ArbBackend()) for e in (*m_r, *c_r, *m_s, *c_s)]
        determinants = [Compiled(e, ArbBackend()) for e in m_s]
    except Unsupported:
        return too_large
    # the same check at 1024 bits: a difference below the judge's digits (a coefficient off by 1e-40)
    point = states.joint(parameters.point(0), states.point(0))
    if _combination_at(compiled, k, point, CONFIRM_BITS, 2 * CONFIRM_BITS + 128) != "agree":
        return too_large
    proved = _determinants_nonzero(m_r, m_s, domains, samplers)
    if isinstance(proved, Comparison):
        return proved
    signs = set()
    for p in range(MIXING_POINTS):
        for j in range(MIXING_STATES):
            point = states.joint(parameters.point(p), states.point(p * MIXING_STATES + j))
            try:
                values = [c.at(point, CONFIRM_BITS)[0] for c in determinants]
            except (Undefined, Unresolved):
                continue
            with flint.ctx.workprec(CONFIRM_BITS):
                det = flint.arb_mat(k, k, values).det()
            if not det.is_finite() or det.contains(0):
                return Comparison(False, "numeric", "your equations are combinations of the reference equations "
                                  "whose mixing matrix is singular (or undefined) at a sample point: there they no "
                                  "longer determine the motion", evidence={"method": "ball arithmetic"},
                                  counterexample={"values": _named(point)})
            signs.add(det > 0)
    if len(signs) != 1:
        return Comparison(False, "numeric", "your equations are combinations of the reference equations whose "
                          "mixing matrix's determinant changes sign between sample points: it is singular "
                          "somewhere in the declared domain, where your equations no longer determine the motion",
                          evidence={"method": "ball arithmetic"})
    if proved is not True:
        # One sign at the sample points says nothing of a factor that touches zero without changing sign
        # ((1 + cos θ₁), (θ₁ − θ₂)², (m₁ − m₂)², θ̇₁² + θ̇₂²): look where such factors, or the determinant, vanish.
        base = states.joint(parameters.point(0), states.point(0))
        below = _below_pairs(samplers)
        # each factor of det M_s not proved nonzero, or where there is no symbolic determinant, det M_s itself
        for entries, size in ([([f], 1) for f in proved] if proved else [(list(m_s), k)]):
            try:
                singular = _singular_near(entries, size, base, domains, below, deadline)
            except Unsupported:
                singular = None
            if singular == "out of time":
                return _out_of_time()
            if singular is not None:
                return Comparison(False, "numeric", "your equations are combinations of the reference equations "
                                  "whose mixing matrix is singular at the state in the counterexample (its "
                                  "determinant vanishes there, or comes within a billionth of its size elsewhere, "
                                  "without changing sign): there they no longer determine the motion",
                                  evidence={"method": "ball arithmetic"}, counterexample={"values": _named(singular)})
    where = ("on the whole declared domain (proved)" if proved is True
             else "at those points, and no zero of its determinant was found where its factors could vanish")
    return Comparison(True, "numeric", "combinations of the reference equations with coefficients that depend on "
                      "the state: solved for the accelerations, your equations give the reference's at every sample "
                      f"point ({MIXING_POINTS * MIXING_STATES} states, ball arithmetic, one confirmed at "
                      f"{CONFIRM_BITS} bits), and the mixing matrix is invertible {where}; the system is too large "
                      "for a symbolic proof of the rest", evidence={"method": "ball arithmetic",
                                                                     "mixing": "numeric (too large)"})


# Precision of the search for a singular mixing matrix at special points, and how small against its size
# (`_singular_near`) its determinant must be there to count as zero (a float π leaves 1 + cos π at ~1e-32).
SPECIAL_BITS = 256
SPECIAL_SMALLNESS = 1e-20
# Values a trigonometric argument is set to: where sines, cosines and their sums and differences vanish.
_SPECIAL_ANGLES = (0.0, math.pi / 2, -math.pi / 2, math.pi, -math.pi)


# CPU seconds for factoring a mixing determinant too large for `_factored`.
LARGE_FACTOR_BUDGET_S = 0.3
# CPU seconds for any other factoring: a few milliseconds as a rule, seconds only with coefficients of
# hundreds of digits.
FACTOR_BUDGET_S = 0.1
# How small against its size (`_singular_near`) a determinant found by descent must be to count as zero: a
# touching zero ((cos θ − 1/2)²) is reached to about the square root of float precision.
DESCENT_SMALLNESS = 1e-9
# Starting points and evaluations of each descent.
DESCENT_STARTS, DESCENT_EVALUATIONS = 4, 400


def _singular_near(entries: list, k: int, base: dict, domains: dict, below: dict,
                   deadline: float | None) -> dict | str | None:
    """A point of the domain where the determinant of the k×k matrix of ``entries`` (one entry: a factor)
    vanishes, None if none was found, or "out of time": first at the special points of `_special_points`
    (256 bits), then by a descent in float64 from the ordinary point and the first special points, over the
    variables of the entries within their domains (a zero of (cos(x/l) − 1/2)² is no special point).

    Vanishing is measured against the size of what makes the determinant (the product of the rows' norms;
    a factor's largest term), so that a determinant that only shrinks with the scale of the variables (all
    lengths a thousandth) is not taken for a singular one."""
    balls = [Compiled(e, ArbBackend()) for e in entries]
    # in float64, a factor is measured against its largest term, each term compiled on its own
    floats = [Compiled(e, FloatBackend()) for e in (entries if k > 1 else sympy.Add.make_args(entries[0]))]

    def relative(point, prec=SPECIAL_BITS) -> flint.arb | None:
        """|det| over the rows' norms (a factor: over its largest term), as a ball; 0 where it is 0."""
        try:
            values = [c.at(point, prec) for c in balls]
        except (Undefined, Unresolved):
            return None
        with flint.ctx.workprec(prec):
            if k == 1:
                value, scale = values[0]
                size = 2.0 ** scale if math.isfinite(scale) else 0.0
            else:
                value = flint.arb_mat(k, k, [v for v, _ in values]).det()
                size = _rows_norm([float(v.mid()) for v, _ in values], k)
            if not value.is_finite():
                return None
            return abs(value) / size if size > 0 else flint.arb(0) if value.contains(0) else None

    def float_relative(point) -> float | None:
        try:
            numbers = [c.at(point, 53)[0] for c in floats]
        except (Undefined, Unresolved, OverflowError, ValueError, ZeroDivisionError):
            return None
        if k == 1:
            largest = max(abs(v) for v in numbers)
            return abs(math.fsum(numbers)) / largest if largest > 0 else 0.0
        size = _rows_norm(numbers, k)
        return abs(float(np.linalg.det(np.array(numbers, dtype=float).reshape(k, k)))) / size if size > 0 else 0.0

    at_base = relative(base)
    if at_base is None or at_base.contains(0):
        return None
    specials = []
    for point in _special_points(base, entries, domains, below):
        ratio = relative(point)
        if ratio is not None and (ratio.contains(0) or float(ratio.mid()) < SPECIAL_SMALLNESS):
            return point
        specials.append(point)
        if _past(deadline):
            return "out of time"
    symbols = set().union(*(e.free_symbols for e in entries))
    moving = sorted((s for s in symbols if s in base and s in domains), key=lambda s: s.name)
    for start in [base, *specials[:DESCENT_STARTS - 1]]:
        if _past(deadline):
            return "out of time"
        found = _descent(float_relative, start, moving, domains, below)
        if found is not None:
            return found
    return None


def _rows_norm(values: list, k: int) -> float:
    """The product of the Euclidean norms of the rows of a k×k matrix given row by row (Hadamard's bound on
    its determinant)."""
    return math.prod(math.sqrt(sum(v * v for v in values[i * k:(i + 1) * k])) for i in range(k))


def _descent(relative, start: dict, moving: list, domains: dict, below: dict) -> dict | None:
    """A point where ``relative`` (a function of a point: |det| over its size, or None) is below
    `DESCENT_SMALLNESS`, found by minimizing it over the ``moving`` variables from ``start``, inside their
    domains (bounds a thousandfold around the start for unbounded ones; a value only tending to zero at such
    a bound is no zero), keeping the ``below`` orders; or None."""
    from scipy.optimize import minimize

    if not moving:
        return None
    bounds = [_descent_bounds(domains[s], start[s]) for s in moving]

    def at(values):
        return {**start, **{s: float(v) for s, v in zip(moving, values)}}

    def objective(values):
        ratio = relative(at(values))
        return 1e300 if ratio is None or not math.isfinite(ratio) else ratio

    result = minimize(objective, [start[s] for s in moving], method="Powell", bounds=bounds,
                      options={"maxfev": DESCENT_EVALUATIONS, "xtol": 1e-12, "ftol": 1e-30})
    if not result.fun < DESCENT_SMALLNESS:
        return None
    point = at(result.x)
    interior = not any(_open_end_pushed(domains[s], point[s], lo, hi) for s, (lo, hi) in zip(moving, bounds))
    keeps_order = all(point[a] < point[b] for a, b in below.items() if a in point and b in point)
    return point if interior and keeps_order and all(domains[s].contains(point[s]) for s in moving) else None


def _descent_bounds(domain, value: float) -> tuple[float, float]:
    """Where a descent may move a variable: its interval, or a thousandfold around ``value`` inside an
    unbounded domain."""
    spread = 1000.0 * max(abs(value), 1.0)
    lo, hi = getattr(domain, "lo", None), getattr(domain, "hi", None)
    if domain.kind == "interval":
        return lo, hi
    if domain.kind in ("positive", "nonnegative"):
        low = 0.0 if domain.kind == "nonnegative" else abs(value) / 1000.0
        return low, abs(value) * 1000.0
    return value - spread, value + spread


def _open_end_pushed(domain, value: float, lo: float, hi: float) -> bool:
    """Whether a descent stopped at a bound that only stands for an open or far end (a positive variable's
    thousandth, an unbounded variable's far bound): a determinant that only tends to zero there has no zero."""
    if domain.kind == "interval" or (domain.kind == "nonnegative" and value <= lo == 0.0):
        return False  # a true end of the domain: a zero there is in it
    margin = 1e-3 * abs(lo) if domain.kind in ("positive", "nonnegative") else 1e-6 * (hi - lo)
    return value <= lo + margin or value >= hi - 1e-3 * abs(hi)


def _special_points(base: dict, exprs, domains: dict, below: dict):
    """``base`` with one or two variables moved to where factors of ``exprs`` typically vanish, each inside its
    domain and keeping every ``below`` order: a variable at zero or at an end of its interval, two at zero at
    once (θ̇₁² + θ̇₂²), a variable equal to another, and each trigonometric argument linear in a variable at 0, ±π/2 or ±π (so sin θ,
    1 + cos(x/l), cos(θ₁ − θ₂) and (θ₁ − θ₂)² each vanish at one of them)."""
    arguments = {f.args[0] for e in exprs for f in e.atoms(sympy.sin, sympy.cos, sympy.tan)}
    symbols = sorted(set().union(*(e.free_symbols for e in exprs)) & set(base), key=lambda s: s.name)
    at_base = {x: sympy.Float(v, 30) for x, v in base.items()}
    moves = [{s: 0.0} for s in symbols]
    moves += [{s: end} for s in symbols if getattr(domains.get(s), "kind", None) == "interval"
              for end in (domains[s].lo, domains[s].hi)]
    moves += [{s: 0.0, t: 0.0} for i, s in enumerate(symbols) for t in symbols[i + 1:]]
    moves += [{s: base[t]} for s in symbols for t in symbols if t is not s]
    for argument in sorted(arguments, key=sympy.default_sort_key):
        for s in sorted(argument.free_symbols & set(base), key=lambda s: s.name):
            try:
                # the slope at the base point: x/l is linear in x with slope 1/l
                slope = float(sympy.diff(argument, s).xreplace(at_base))
                value = float(argument.xreplace(at_base))
            except (TypeError, ValueError):
                continue
            if slope == 0 or not math.isfinite(slope) or sympy.diff(argument, s, 2) != 0:
                continue
            moves += [{s: base[s] + (angle - value) / slope} for angle in _SPECIAL_ANGLES]
    seen = set()
    for move in moves:
        key = tuple(sorted((s.name, v) for s, v in move.items()))
        if key in seen or all(base[s] == v for s, v in move.items()) \
                or not all(s in domains and domains[s].contains(v) for s, v in move.items()):
            continue
        seen.add(key)
        point = {**base, **move}
        if all(point[a] < point[b] for a, b in below.items() if a in point and b in point):
            yield point


# Precision of the multiple at special points, and the digits to which it must stay what it is elsewhere.
MULTIPLE_BITS, MULTIPLE_DIGITS_BITS = 192, 120


def _multiple_at_special_points(reference: sympy.Expr, answer: sympy.Expr, parameters: Sampler,
                                states: Sampler, unknowns: tuple) -> Comparison | None:
    """The refusal of an answer the sample points took for ``c × reference`` with ``c`` free of the state, when
    at a special point (`_special_points`: a variable at zero or at an end of its interval, equal to another,
    an angle where a sine or cosine vanishes) the two are no multiple of each other: ``c`` is zero there (the
    answer holds where the reference does not: sign(θ)² is 0 at θ = 0, sin 2α written out at α = 0), or,
    with accelerations, it changes with them (the answer gives another acceleration there: F0 cos ωt sign t
    is 0 at t = 0). A factor that only changes there ((2 + sign(θ)²): 3, and 2 at θ = 0) is no refusal.
    Points where the reference is zero or undefined are passed over; None otherwise."""
    domains = {**parameters.domains, **states.domains}
    base = states.joint(parameters.point(0), states.point(0))
    compiled = [Compiled(e, ArbBackend()) for e in (reference, answer)]

    def multiple(point):
        try:
            r, a = (c.at(point, MULTIPLE_BITS)[0] for c in compiled)
        except (Undefined, Unresolved):
            return None
        with flint.ctx.workprec(MULTIPLE_BITS):
            return None if r.contains(0) or not (a / r).is_finite() else a / r

    def apart(c, d) -> bool:  # two multiples that differ beyond the precision's noise
        with flint.ctx.workprec(MULTIPLE_BITS):
            return not (c - d).contains(0) and _log2_mag(c - d) > _log2_mag(d) - MULTIPLE_DIGITS_BITS

    usual = multiple(base)
    if usual is None or usual.contains(0):
        return None
    for point in _special_points(base, [reference, answer], domains, _below_pairs((parameters, states))):
        c = multiple(point)
        if c is None:
            continue
        with flint.ctx.workprec(MULTIPLE_BITS):
            vanishes = c.contains(0) or _log2_mag(c) < _log2_mag(usual) - MULTIPLE_DIGITS_BITS
        other = [multiple({**point, u: point[u] + 1.0 + abs(point[u])}) for u in unknowns if u in point]
        moves_with_acceleration = any(d is not None and apart(d, c) for d in other)
        if vanishes or moves_with_acceleration:
            return Comparison(False, "proved" if moves_with_acceleration else "numeric",
                              f"{_NOT_A_MULTIPLE} everywhere: it agrees with a multiple of the reference at the "
                              "sample points, but not where a factor or term of it vanishes or jumps (see the "
                              "counterexample)", evidence={"method": "ball arithmetic"},
                              counterexample={"values": _named(point)})
    return None


# Grid of the root search on an interval, the parameter points it is done at, and the relative distance
# within which two roots are one.
ROOT_GRID, ROOT_PARAMETER_POINTS, ROOT_TOLERANCE = 2000, 3, 1e-9
ROOT_SPECIAL_POINTS = 12


def _same_roots_on_the_interval(reference: sympy.Expr, answer: sympy.Expr, parameters: Sampler,
                                states: Sampler, deadline: float | None = None) -> Comparison | None:
    """Whether two equations in one state variable x, declared on an interval, have the same solutions there,
    at a few parameter points: each one's roots are found on a fine grid (sign changes refined by bisection,
    and the grid's local minima of |f| refined for roots that touch zero), a pole or a point where an
    equation is undefined being no root. None where it does not apply (another state variable, an unbounded
    domain, an expression that cannot be evaluated in float64)."""
    variables = (reference.free_symbols | answer.free_symbols) & set(states.domains)
    if len(variables) != 1 or _nodes(reference) > FACTOR_MAX_NODES or _nodes(answer) > FACTOR_MAX_NODES:
        return None  # (tens of thousands of evaluations: only for conditions of a few terms)
    x = variables.pop()
    domain = states.domains[x]
    if getattr(domain, "kind", None) != "interval":
        return None
    try:
        functions = [Compiled(e, FloatBackend()) for e in (reference, answer)]
    except Unsupported:
        return None
    # random parameter points, and special ones (two parameters equal, one at zero or an end): (a − g) times
    # the equation is 0 = 0 at a = g
    base = parameters.point(0)
    special = list(itertools.islice(_special_points(base, [reference, answer], parameters.domains,
                                                    _below_pairs((parameters, states))), ROOT_SPECIAL_POINTS))
    for point in [parameters.point(p) for p in range(ROOT_PARAMETER_POINTS)] + special:
        if _past(deadline):
            return None
        found = [_roots_on(f, x, point, domain.lo, domain.hi) for f in functions]
        if None in found:
            return None
        width = domain.hi - domain.lo
        for mine, theirs, whose in ((found[1], found[0], "your equation"), (found[0], found[1], "the reference")):
            extra = [r for r in mine if all(abs(r - t) > ROOT_TOLERANCE * max(width, abs(r)) for t in theirs)]
            if extra:
                example = {"values": {**_named(point), x.name: extra[0]}}
                return Comparison(False, "numeric", f"{whose} holds at {x.name} = {extra[0]:.6g} on the declared "
                                  f"interval, where {'the reference' if whose == 'your equation' else 'yours'} "
                                  "does not (see the counterexample)", evidence={"method": "roots on the interval"},
                                  counterexample=example)
    return Comparison(True, "numeric", f"the same solutions for {x.name} on its declared interval as the reference, "
                      f"found on a grid of {ROOT_GRID} points at {ROOT_PARAMETER_POINTS} parameter points and where "
                      "parameters are equal, zero or at an end of their intervals",
                      evidence={"method": "roots on the interval"})


def _roots_on(function: Compiled, x, point: dict, lo: float, hi: float) -> list[float] | None:
    """The roots of ``function`` in x over [lo, hi] (the other variables at ``point``), or None where it is
    not a number at most grid points."""
    def value(t):
        try:
            return function.at({**point, x: t}, 53)[0]
        except (Undefined, Unresolved, OverflowError, ValueError, ZeroDivisionError):
            return None

    grid = np.linspace(lo, hi, ROOT_GRID)
    values = [value(t) for t in grid]
    finite = [v for v in values if v is not None and math.isfinite(v)]
    if len(finite) < ROOT_GRID // 2:
        return None
    # The middle magnitude, not np.median: that averages the two middle ones, which overflows when the
    # values are near the largest float (sin(θ)·1.7e308 = 0). (The largest could be beside a pole.)
    scale = sorted(abs(v) for v in finite)[len(finite) // 2] or 1.0
    roots = []
    for i in range(ROOT_GRID - 1):
        a, b = values[i], values[i + 1]
        if a is None or b is None:
            continue
        if a == 0:
            roots.append(float(grid[i]))
        elif a * b < 0 or (0 < i and values[i - 1] is not None and abs(a) <= min(abs(values[i - 1]), abs(b))
                           and abs(a) < 1e-3 * scale):
            root = _refined(value, float(grid[max(i - 1, 0)]), float(grid[i + 1]), a * b < 0, scale)
            if root is not None:
                roots.append(root)
    if values[-1] == 0:
        roots.append(float(grid[-1]))
    merged = []
    for r in sorted(roots):
        if not merged or abs(r - merged[-1]) > ROOT_TOLERANCE * max(hi - lo, abs(r)):
            merged.append(r)
    return merged


def _refined(value, a: float, b: float, sign_change: bool, scale: float) -> float | None:
    """A root in [a, b]: by bisection where the value changes sign, else by a golden-section search of |value|
    (a root that touches zero); None where it is a pole (a sign change with huge values at it) or a minimum
    above zero. ``scale`` is the value's typical size on the interval."""
    if sign_change:
        fa = value(a)
        for _ in range(80):
            m = (a + b) / 2
            fm = value(m)
            if fm is None:
                return None
            if fm == 0:
                return m
            if (fm < 0) == (fa < 0):
                a, fa = m, fm
            else:
                b = m
        m = (a + b) / 2
        fm = value(m)
        return m if fm is not None and abs(fm) <= 1e-8 * scale else None
    ratio = (math.sqrt(5) - 1) / 2
    for _ in range(120):
        c, d = b - ratio * (b - a), a + ratio * (b - a)
        fc, fd = value(c), value(d)
        if fc is None or fd is None:
            return None
        if abs(fc) < abs(fd):
            b = d
        else:
            a = c
    m = (a + b) / 2
    fm = value(m)
    return m if fm is not None and abs(fm) <= 1e-10 * scale else None


def _below_pairs(samplers: tuple[Sampler, Sampler]) -> dict:
    """Every ``below`` order ``{a: R}`` the samplers keep."""
    return {a: b for sampler in samplers for a, b in (*sampler.below.items(), *sampler.across.items())}


def _determinant(matrix: sympy.Matrix) -> sympy.Expr | None:
    """``det(matrix)`` as one cancelled fraction, or None where sympy cannot build it."""
    try:
        return sympy.cancel(sympy.together(matrix.det(method="berkowitz")))
    except (sympy.PolynomialError, ValueError, TypeError, ZeroDivisionError):
        return None


def _not_independent() -> Comparison:
    """The verdict on answer equations whose mixing matrix has a zero determinant."""
    return Comparison(False, "proved", "your equations are not independent: they are combinations of the "
                      "reference equations that together say less than the reference equations",
                      evidence={"method": "symbolic"})


def _determinants_nonzero(m_r: sympy.Matrix, m_s: sympy.Matrix, domains: dict,
                          samplers: tuple[Sampler, Sampler]) -> bool | list | Comparison:
    """True when ``det M_r`` and ``det M_s`` are proved finite and nonzero on the whole domain, a refusal when
    a factor of ``det M_s`` provably changes sign there, else the factors of ``det M_s`` not proved nonzero
    (empty when the matrices are too large or the proof fails elsewhere): the caller then looks for their
    zeros, and checks the determinant at its sample points."""
    if not all(_nodes(e, MIXING_MAX_NODES) <= MIXING_MAX_NODES for e in (*m_r, *m_s)):
        return []
    det_r, det_s = _determinant(m_r), _determinant(m_s)
    if det_r is None or det_s is None:
        return []
    if det_s == 0:
        return _not_independent()
    numerator = _factored(sympy.fraction(det_s)[0])
    if _nonzero_on(numerator, domains) is not True:
        example = _vanishing_factor(numerator, domains, samplers)
        if example is not None:
            return Comparison(False, "proved", _SINGULAR_MIXING, evidence={"method": "ball arithmetic"},
                              counterexample=example)
        if numerator == sympy.fraction(det_s)[0]:
            # too large for `_factored`: a student's factor ((m₁ − 2m₂)²) multiplied into the mass matrix's
            # determinant is found far more surely on its own
            numerator = _factored(numerator, LARGE_FACTOR_BUDGET_S)
        return [base for base in _bases(numerator) if not base.is_number and _nonzero_on(base, domains) is not True]
    return (_finite_on(m_r, domains) and _finite_on(m_s, domains)
            and _nonzero_on(_factored(sympy.fraction(det_r)[0]), domains) is True) or []


def _where_the_reference_is_undefined(numerator: sympy.Expr, reference: list, domains: dict) -> list:
    """The factors of ``numerator`` (a factor's, a mixing determinant's) not proved nonzero, when each of them
    is also a factor of a denominator of the ``reference``'s terms (so the factor vanishes only where the
    reference is undefined); else an empty list."""
    denominators = set()
    for entry in reference:
        denominator = sympy.fraction(sympy.together(entry))[1]
        for factor in sympy.Mul.make_args(_factored(denominator)):
            base = factor.base if factor.is_Pow and factor.exp.is_Integer and factor.exp > 0 else factor
            if not base.is_number:
                denominators |= {base, -base}
    found = []
    for factor in sympy.Mul.make_args(sympy.factor_terms(numerator)):
        base = factor.base if factor.is_Pow and factor.exp.is_Integer and factor.exp > 0 else factor
        if base.is_number or _nonzero_on(base, domains) is True:
            continue
        if base not in denominators:
            return []
        found.append(base)
    return found


def _factored(expr: sympy.Expr, seconds: float | None = None) -> sympy.Expr:
    """``expr`` factored when it is small enough, else ``expr`` itself: cancelling expands a determinant,
    and its factors (``r**2 - r*L + L**2``, ``10*theta**2 + 1``) are what `_nonzero_on` can prove one by one.

    Every factoring here goes through this function: sympy's factoring runs to its end whatever the
    check's deadline, and a coefficient of hundreds of digits (a typed constant) makes it take seconds
    (Wang's algorithm looks for large primes), so it runs under a CPU budget.

    >>> x = sympy.Symbol("x")
    >>> _factored(x**2 - 1)
    (x - 1)*(x + 1)
    """
    if seconds is None:
        if _nodes(expr) > FACTOR_MAX_NODES:
            return expr
        seconds = FACTOR_BUDGET_S
    try:
        return budget.attempt(lambda: sympy.factor(expr), seconds, fallback=lambda: expr)
    except (sympy.PolynomialError, ValueError, TypeError):
        return expr


_SINGULAR_MIXING = ("your equations are combinations of the reference equations whose mixing matrix depends on "
                    "the state and is singular somewhere in the declared domain (a factor of its determinant "
                    "changes sign between the two states in the counterexample): there your equations no longer "
                    "determine the motion")
# Functions continuous wherever their arguments are: a sign change of a product of them has a zero between.
_CONTINUOUS = (sympy.sin, sympy.cos, sympy.exp, sympy.sinh, sympy.cosh, sympy.tanh, sympy.atan, sympy.Abs)


def _vanishing_factor(expr: sympy.Expr, domains: dict, samplers: tuple[Sampler, Sampler]) -> dict | None:
    """Two states between which a continuous factor of ``expr`` changes sign (so ``expr`` vanishes there).

    Factor by factor, because a square (``thetadot**2``) vanishes without changing sign. The states
    differ only in state variables, whose domains are intervals: the segment between them is inside.
    """
    for factor in sympy.Mul.make_args(sympy.factor_terms(expr)):
        base = factor.base if factor.is_Pow and factor.exp.is_Integer and factor.exp > 0 else factor
        if base.is_number or not _continuous(base) or _nonzero_on(base, domains) is True:
            continue
        example = _sign_change(base, *samplers)
        if example is not None:
            return example
    return None


def _continuous(expr: sympy.Expr) -> bool:
    """A polynomial in the variables and in functions of `_CONTINUOUS` (no division, no roots)."""
    for node in sympy.preorder_traversal(expr):
        if node.is_Pow and not (node.exp.is_Integer and node.exp > 0):
            return False
        if isinstance(node, sympy.Function) and not isinstance(node, _CONTINUOUS):
            return False
    return True


def _out_of_time() -> Comparison:
    return Comparison(None, "none", "the time budget ran out while comparing", budget_exceeded=True)


def _past(deadline: float | None) -> bool:
    return deadline is not None and time.monotonic() > deadline


def _linear_in(residuals: list[sympy.Expr], unknowns: tuple):
    """``(M, c)`` with ``residuals == M @ unknowns + c`` and ``M``, ``c`` free of the unknowns, else None."""
    rows, constants = [], []
    zero = {u: sympy.S.Zero for u in unknowns}
    for e in residuals:
        try:
            row = [sympy.diff(e, u) for u in unknowns]
        except (ValueError, TypeError, NotImplementedError):
            return None
        # a gradient free of the unknowns makes e affine in them (e - e(0) is the gradient times a)
        if any(entry.has(*unknowns) for entry in row):
            return None
        constant = e.xreplace(zero)
        if constant.has(sympy.nan, sympy.zoo, sympy.oo, -sympy.oo):
            return None
        rows.append(row)
        constants.append(constant)
    matrix = sympy.Matrix(rows)
    if any(all(entry == 0 for entry in matrix.row(i)) for i in range(matrix.rows)):
        return None  # an equation without accelerations (a constraint): not this path
    return matrix, sympy.Matrix(constants)


def _finite_on(matrix: sympy.Matrix, domains: dict) -> bool:
    """Every entry's denominator is provably nonzero on the domain."""
    for entry in matrix:
        _, denominator = sympy.fraction(sympy.together(entry))
        if not (denominator.is_number and denominator != 0) and _nonzero_on(denominator, domains) is not True:
            return False
    return True


def _combination_at_points(m_r, c_r, m_s, c_s, unknowns, samplers, options, deadline) -> str | dict | None:
    """"agree" when ``c_s = M_s M_r**-1 c_r`` at every sample point (ball arithmetic), a counterexample
    when a point proves otherwise, None when undecided."""
    parameters, states = samplers
    k = len(c_r)
    try:
        compiled = [Compiled(e, ArbBackend()) for e in (*m_r, *c_r, *m_s, *c_s)]
    except Unsupported:
        return None
    target = options.digits * LOG2_10
    agreed = 0
    for p in range(MIXING_POINTS):
        for j in range(MIXING_STATES):
            if _past(deadline):
                return None
            point = states.joint(parameters.point(p), states.point(p * MIXING_STATES + j))
            outcome = _combination_at(compiled, k, point, target, options.max_bits)
            if isinstance(outcome, dict):
                return _acceleration_example(outcome, point, unknowns)
            agreed += outcome == "agree"
    return "agree" if agreed >= MIXING_POINTS * MIXING_STATES // 2 else None


def _combination_at(compiled, k, point, target, max_bits) -> str | dict | None:
    """"agree", None (undecided), or at a point that proves the systems different the accelerations
    each gives ``{"answer": [...], "reference": [...]}`` (empty when the answer's are undetermined)."""
    prec = int(target) + 32
    while prec <= max_bits:
        try:
            values = [c.at(point, prec) for c in compiled]
        except Undefined:
            return None  # outside where the equations are defined: another point decides
        except Unresolved:
            prec *= 2
            continue
        with flint.ctx.workprec(prec):
            numbers = [v for v, _ in values]
            m_r = flint.arb_mat(k, k, numbers[:k * k])
            c_r = flint.arb_mat(k, 1, numbers[k * k:k * k + k])
            m_s = flint.arb_mat(k, k, numbers[k * k + k:2 * k * k + k])
            c_s = flint.arb_mat(k, 1, numbers[2 * k * k + k:])
            det = m_r.det()
            if det.is_finite() and not det.contains(0):
                mixed = m_s * m_r.inv() * c_r
                scale = max([s for _, s in values[k * k + k + k * k:]] + [_log2_mag(mixed[i, 0]) for i in range(k)])
                noise = -math.inf
                for i in range(k):
                    d = c_s[i, 0] - mixed[i, 0]
                    if not d.contains(0):
                        return _accelerations(m_r, c_r, m_s, c_s)
                    noise = max(noise, _log2_mag(d))
                if noise <= scale - target:
                    return "agree"
        prec *= 2
    return None


def _accelerations(m_r, c_r, m_s, c_s) -> dict:
    # c_s != M_s M_r**-1 c_r makes the solutions -M**-1 c differ wherever M_s is invertible
    det = m_s.det()
    if not det.is_finite() or det.contains(0):
        return {}
    a_s, a_r = m_s.solve(c_s), m_r.solve(c_r)
    return {"answer": [-a_s[i, 0] for i in range(a_s.nrows())], "reference": [-a_r[i, 0] for i in range(a_r.nrows())]}


def _acceleration_example(accelerations: dict, point: dict, unknowns: tuple) -> dict:
    """The counterexample of a system that is no combination: where, and the accelerations each system gives."""
    if not accelerations:
        return {}
    names = [u.name for u in unknowns]
    return {"values": {s.name: v for s, v in point.items() if s not in unknowns},
            "answer": dict(zip(names, map(as_float, accelerations["answer"]))),
            "reference": dict(zip(names, map(as_float, accelerations["reference"]))),
            "note": "the accelerations your equations give there"}


def _combination_proved(m_r, c_r, m_s, c_s, deadline) -> bool | None:
    """``det(M_r) c_s == M_s adj(M_r) c_r`` identically (``c_s = M_s M_r**-1 c_r`` without division);
    None when the deadline passed first."""
    try:
        rows = m_r.det(method="berkowitz") * c_s - m_s * m_r.adjugate(method="berkowitz") * c_r
    except (ValueError, TypeError, ZeroDivisionError):
        return False
    for row in rows:
        if _past(deadline):
            return None
        if not _identically_zero(row):
            return False
    return True


def _identically_zero(expr: sympy.Expr) -> bool:
    """A proof that ``expr`` is zero wherever it is defined: as a rational function, or with the sines and
    cosines of sums of variables expanded and reduced modulo ``sin(x)**2 + cos(x)**2 - 1``."""
    if _nodes(expr, IDENTITY_MAX_NODES) > IDENTITY_MAX_NODES:
        return False
    try:
        # sines and cosines of sums need the circle reduction: cancelling first would be wasted time
        compound = any(not f.args[0].is_Symbol for f in expr.atoms(sympy.sin, sympy.cos, sympy.tan))
        if not compound and sympy.cancel(sympy.together(expr)) == 0:
            return True
        return _zero_on_circles(expr)
    except (sympy.PolynomialError, sympy.polys.polyerrors.PolificationFailed, ValueError, TypeError,
            ZeroDivisionError):
        return False


_U = sympy.Wild("u")
# tan, cot, sec, csc as sines and cosines, so that one reduction sees every trigonometric function
_AS_SIN_COS = ((sympy.tan(_U), sympy.sin(_U) / sympy.cos(_U)), (sympy.cot(_U), sympy.cos(_U) / sympy.sin(_U)),
               (sympy.sec(_U), 1 / sympy.cos(_U)), (sympy.csc(_U), 1 / sympy.sin(_U)))


def _zero_on_circles(expr: sympy.Expr) -> bool:
    for pattern, replacement in _AS_SIN_COS:
        expr = expr.replace(pattern, replacement)
    expr = sympy.expand_trig(expr)  # sin(theta1 - theta2) -> products of sin(theta1), cos(theta2), ...
    angles = {f.args[0] for f in expr.atoms(sympy.sin, sympy.cos)}
    if not angles:
        # cot(x)*sin(x) - cos(x) is already 0 once written with sines and cosines
        return sympy.cancel(sympy.together(expr)) == 0
    # sin u and cos u of any argument u (a drive's Omega*t, the angle itself) are new variables on the circle
    # s**2 + c**2 = 1: a zero modulo those relations is a zero for every value of them, so for every u (sound,
    # if not complete: a relation between two arguments, or u also outside sin and cos, is not used).
    replacements, circles, generators = {}, [], []
    for n, angle in enumerate(sorted(angles, key=sympy.default_sort_key)):
        s, c = sympy.Dummy(f"s_{n}"), sympy.Dummy(f"c_{n}")
        replacements[sympy.sin(angle)] = s
        replacements[sympy.cos(angle)] = c
        circles.append(s**2 + c**2 - 1)
        generators += [s, c]
    replaced = expr.xreplace(replacements)
    if replaced.has(*(a for a in angles if a.is_Symbol)):
        return False  # the angle also outside sin and cos (theta*sin(theta)): not this reduction
    if replaced.has(sympy.sin, sympy.cos):
        return False  # a sine inside another function's argument (exp(cos(theta))): not a polynomial in them
    proved = _zero_in_ring(replaced, generators, circles)
    if proved is not None:
        return proved
    numerator, _ = sympy.fraction(sympy.together(replaced))
    numerator = sympy.expand(numerator)
    if numerator == 0:
        return True
    # The circles' leading terms s**2 are coprime, so they are a Groebner basis: the remainder is zero
    # exactly when the numerator vanishes for every real angle.
    _, remainder = sympy.reduced(numerator, circles, *generators)
    return remainder == 0


def _zero_in_ring(expr: sympy.Expr, generators: list, circles: list) -> bool | None:
    """Whether the numerator of ``expr`` (a rational function of its symbols) reduces to 0 modulo
    ``circles``, computed in a sparse polynomial ring: half the time of cancelling and expanding it as
    an expression (a double pendulum's unsolved rows: 30 ms a check). None where ``expr`` is not a
    rational function of its symbols (√g in it), for the expression route to decide."""
    from sympy.polys.fields import sfield
    from sympy.polys.polyerrors import PolynomialError

    symbols = list(generators) + sorted(expr.free_symbols - set(generators), key=str)
    try:
        _, fraction = sfield(expr, *symbols)
        numerator = fraction.numer
        ring = numerator.ring
        if not ring.domain.is_Exact:
            return None
        # The circles' leading terms s**2 are coprime: a Groebner basis, so the remainder is unique.
        return numerator.rem([ring.from_expr(c) for c in circles]) == 0
    except (PolynomialError, ValueError, TypeError, NotImplementedError):
        return None


def _nodes(expr: sympy.Expr, limit: int = FACTOR_MAX_NODES) -> int:
    """Nodes of ``expr``, counted up to past ``limit`` (past it when a high power makes cancelling
    it costly: x**1000)."""
    count, stack = 0, [expr]
    while stack and count <= limit:
        node = stack.pop()
        count += 1
        if node.is_Pow and node.exp.is_Integer and abs(int(node.exp)) > FACTOR_MAX_POWER:
            return limit + 1
        stack.extend(node.args)
    return count


# Functions that take each real value at most once on the whole real line (and are defined there):
# f(P) = f(Q) holds exactly where P = Q. log is left out: log P = log Q is undefined where P = Q <= 0.
_INJECTIVE = (sympy.exp, sympy.sinh, sympy.tanh, sympy.atan, sympy.asinh)
# Those that are odd too: f(-u) = -f(u).
_ODD_INJECTIVE = (sympy.sinh, sympy.tanh, sympy.atan, sympy.asinh)


# Where each of sin, cos and tan takes every value once: its argument in one of these intervals (and
# its shifts by π), the branch of asin, acos and atan.
_BRANCHES = {sympy.sin: (-math.pi / 2, math.pi / 2), sympy.cos: (0.0, math.pi), sympy.tan: (-math.pi / 2, math.pi / 2)}
_INVERSES = {sympy.asin: sympy.sin, sympy.acos: sympy.cos, sympy.atan: sympy.tan}
# How far past a branch's end a declared interval may reach: an end written to four decimals (3.1416 for π,
# 1.5708 for π/2) means the multiple of π it rounds, as the sampler's ends do.
_BRANCH_SLACK = 5e-5


def _range_over(expr: sympy.Expr, domains: dict) -> tuple[float, float] | None:
    """An interval that holds every value of ``expr`` over its variables' declared intervals (ball
    arithmetic over the whole box), or None where a variable's domain is unbounded or it cannot be
    evaluated."""
    box = {}
    for symbol in expr.free_symbols:
        domain = domains.get(symbol)
        lo, hi = getattr(domain, "lo", -math.inf), getattr(domain, "hi", math.inf)
        if domain is None or not (math.isfinite(lo) and math.isfinite(hi)):
            return None
        box[symbol] = flint.arb(lo).union(flint.arb(hi))
    try:
        with flint.ctx.workprec(64):
            value = compile_expr(expr, ArbBackend())({**box, SCALE: -math.inf})
    except (Undefined, Unresolved, Unsupported):
        return None
    if not value.is_finite():
        return None
    return float(value.lower()), float(value.upper())


def _in_one_branch(f, arguments: list[sympy.Expr], domains: dict) -> bool:
    """Whether every one of ``arguments`` stays, over the domains, inside one and the same interval
    where ``f`` (sin, cos or tan) takes each value once (`_BRANCHES` shifted by a multiple of π)."""
    lo, hi = _BRANCHES[f]
    ranges = [_range_over(a, domains) for a in arguments]
    if None in ranges:
        return False
    low, high = min(r[0] for r in ranges), max(r[1] for r in ranges)
    # (the balls' radius, ~1e-9, past an end the declared interval has on it: θ in [0, 1.5] for acos)
    k = math.floor((low - lo) / math.pi + _BRANCH_SLACK)
    if f is sympy.tan:  # undefined at the branch's ends: strictly inside
        return lo + k * math.pi < low and high < hi + k * math.pi
    return lo + k * math.pi - _BRANCH_SLACK <= low and high <= hi + k * math.pi + _BRANCH_SLACK


def _inverse_applied(residual: sympy.Expr, domains: dict) -> sympy.Expr | None:
    """``f(A) - X`` for ``residual`` = c (A - F(X)) with F one of asin, acos, atan and f its inverse, where
    A stays in F's range over the domains: θ = atan(X) holds exactly where tan θ = X when θ stays in
    (−π/2, π/2) (the angle of a conical pendulum or a banked curve, written either way), else None."""
    terms = sympy.Add.make_args(residual)
    if len(terms) != 2:
        return None
    for inverse_term, other in ((terms[0], terms[1]), (terms[1], terms[0])):
        c, call = inverse_term.as_coeff_Mul()
        if type(call) not in _INVERSES or not c.is_Rational or c.is_zero:
            continue
        # c F(X) + other = 0 is F(X) = A with A = -other/c, which holds exactly where f(A) = X when A
        # stays in F's range (f's branch, `_in_one_branch`); outside it F(X) = A has no solution at all
        a = -other / c
        f = _INVERSES[type(call)]
        if _in_one_branch(f, [a], domains):
            return f(a) - call.args[0]
    return None


def _injective_sides(residual: sympy.Expr, domains: dict | None = None) -> sympy.Expr | None:
    """``A - B`` when ``residual = 0`` says ``f(A) = f(B)`` for a function ``f`` that takes each real
    value once (an odd power or root, exp and a power of a positive number, sinh, tanh, atan, asinh;
    a number on one side read as ``f`` of its preimage, 0 too: atan(A) = 0 is A = 0); ``|A| - |B|``
    for an even power. None otherwise.

    >>> x, y, r, w = sympy.symbols("x y r w", real=True)
    >>> _injective_sides(x**3 - y**3)
    x - y
    >>> _injective_sides(2*sympy.exp(x) - 2*sympy.exp(y))  # one sign or the other: a residual
    -x + y
    >>> _injective_sides(x**2 - r**2*w**2)
    Abs(x) - Abs(r*w)
    >>> _injective_sides(2**y - 2**x)  # 2^y = e^(y log 2)
    x*log(2) - y*log(2)
    >>> _injective_sides(sympy.exp(y) * sympy.exp(-x) - 1)
    -x + y
    >>> _injective_sides(sympy.atan(y - x))  # sympy writes it -atan(x - y)
    x - y
    >>> _injective_sides(x**2 + y**2) is None
    True
    """
    residual = _as_exponentials(residual)
    terms = sympy.Add.make_args(residual)
    if len(terms) == 1:
        return _preimage(residual.as_coeff_Mul()[1], sympy.S.Zero)  # c f(A) = 0
    if len(terms) != 2:
        return None
    left, right = terms[0], -terms[1]
    powered = _same_power(left, right)
    if powered is not None:
        return powered
    (c1, a), (c2, b) = left.as_coeff_Mul(), right.as_coeff_Mul()
    if a.is_number or b.is_number:
        # f(A) = number: the number's preimage, where f reaches it (2 e^x = 4: x = log 2)
        (c, a), number = ((c1, a), right) if b.is_number else ((c2, b), left)
        return _preimage(a, number / c)
    in_branch = (domains is not None and type(a) is type(b) and type(a) in _BRANCHES
                 and _in_one_branch(type(a), [a.args[0], b.args[0]], domains))
    if c1 == -c2 and c1 != 0:
        # f(A) = -f(B) for an odd f is f(A) = f(-B): sympy writes atan(-u) as -atan(u)
        if type(a) is type(b) and isinstance(a, _ODD_INJECTIVE):
            return a.args[0] + b.args[0]
        if type(a) is type(b) and type(a) in (sympy.sin, sympy.tan) and domains is not None \
                and _in_one_branch(type(a), [a.args[0], -b.args[0]], domains):
            return a.args[0] + b.args[0]
        roots = _odd_root(a), _odd_root(b)
        if None not in roots and roots[0][1] == roots[1][1]:
            return roots[0][0] + roots[1][0]
        return None
    if c1 != c2:
        return None
    if type(a) is type(b) and isinstance(a, _INJECTIVE) or in_branch:
        # (sin, cos, tan: where both arguments stay in one branch, `_in_one_branch`)
        return a.args[0] - b.args[0]
    roots = _odd_root(a), _odd_root(b)
    if None not in roots and roots[0][1] == roots[1][1]:
        return roots[0][0] - roots[1][0]
    return None


def _logs_exponentiated(residual: sympy.Expr) -> sympy.Expr | None:
    """``prod(P_i**c_i) - exp(-B)`` for ``residual = sum(c_i log(P_i)) + B``, each ``P_i`` positive on the whole
    domain (the symbols' assumptions) and each ``c_i`` rational, else None: log is one-to-one on the positive
    numbers, so ``log(v/v0) = -k t/m`` and ``v/v0 = exp(-k t/m)`` have the same solutions. A log of a number
    is a constant of ``B``: taking it out would undo `_preimage` (x = log 2) and loop."""
    if not residual.has(sympy.log):
        return None
    residual = _log_coefficient_divided(residual)
    powers, rest = [], []
    for term in sympy.Add.make_args(residual):
        c, f = term.as_coeff_Mul()
        if isinstance(f, sympy.log) and c.is_Rational and f.args[0].free_symbols and f.args[0].is_positive:
            powers.append(f.args[0] ** c)
        elif term.has(sympy.log) and term.free_symbols:
            return None  # a log not known to be defined everywhere: log P = log Q is undefined where P = Q <= 0
        else:
            rest.append(term)
    if not powers:
        return None
    return sympy.Mul(*powers) - sympy.exp(-sympy.Add(*rest))


def _nonnegative_sides_squared(residual: sympy.Expr) -> sympy.Expr | None:
    """``P² − Q²`` for ``residual = P − Q`` with both sides nonnegative wherever they are defined (absolute
    values, square roots, even powers, positive symbols, and products of them): P = Q exactly where P² = Q²,
    and where a root's radicand is negative P² = Q² has no real solution either. A product of absolute
    values equal to zero is the product without its bars. None otherwise.

    >>> v, g, h = sympy.symbols("v g h", real=True)
    >>> _nonnegative_sides_squared(sympy.Abs(v) - sympy.sqrt(2*g*h))
    -2*g*h + v**2
    """
    terms = sympy.Add.make_args(residual)
    if len(terms) == 1:
        factors = sympy.Mul.make_args(residual)
        if any(isinstance(f, sympy.Abs) for f in factors) and all(_nonnegative_by_form(f) or f.is_number
                                                                   for f in factors):
            return sympy.Mul(*(f.args[0] if isinstance(f, sympy.Abs) else f for f in factors))
        return None
    if len(terms) != 2:
        return None
    positive = [t for t in terms if not t.could_extract_minus_sign()]
    negative = [-t for t in terms if t.could_extract_minus_sign()]
    if len(positive) != 1 or len(negative) != 1:
        return None
    p, q = positive[0], negative[0]
    if not (_nonnegative_by_form(p) and _nonnegative_by_form(q)) or not (p.has(sympy.Abs) or q.has(sympy.Abs)
                                                                       or p.is_Pow or q.is_Pow):
        return None
    # Where a root is undefined its square is negative: no solution of P² = Q² is gained there only if the
    # other side is defined everywhere (|v| = √(2gh)); √x = √y is not x = y, which also holds at x = y < 0.
    if not (_without_roots(p) or _without_roots(q)):
        return None
    return sympy.expand(p**2 - q**2) if _nodes(p) + _nodes(q) <= FACTOR_MAX_NODES else None


def _without_roots(expr: sympy.Expr) -> bool:
    """Whether no power of ``expr`` has a fractional exponent (so it is defined wherever its variables are)."""
    return not any(power.exp.is_Rational and not power.exp.is_integer for power in expr.atoms(sympy.Pow))


def _nonnegative_by_form(expr: sympy.Expr) -> bool:
    """Whether ``expr`` is nonnegative wherever it is defined, by its form alone."""
    if expr.is_nonnegative:
        return True
    if isinstance(expr, sympy.Abs):
        return True
    if expr.is_Pow and expr.exp.is_Rational and expr.exp > 0 and (expr.exp.q % 2 == 0 or expr.exp.p % 2 == 0):
        return True  # √x, x², x^(3/2)
    if expr.is_Mul:
        return all(_nonnegative_by_form(f) for f in expr.args)
    return False


def _log_coefficient_divided(residual: sympy.Expr) -> sympy.Expr:
    """``residual`` divided by the factor its log terms share, when that factor is nonzero (the symbols'
    assumptions) and each log term is a rational multiple of it: ``t - (m/k) log(v0/v)`` is
    ``log(v0/v) - k t/m`` times ``-m/k``, the same equation, with a log of rational coefficient. Else
    ``residual`` itself."""
    terms = sympy.Add.make_args(residual)
    shares = [term.as_independent(sympy.log, as_Add=False)[0] for term in terms if term.has(sympy.log)]
    common = shares[0]
    if common.is_Rational or common.is_nonzero is not True:
        return residual
    if not all((share / common).is_Rational for share in shares[1:]):
        return residual
    return sympy.Add(*(term / common for term in terms))


def _as_exponentials(residual: sympy.Expr) -> sympy.Expr:
    """``residual`` with every power of a positive number b ≠ 1 written e^(E log b), and products of
    exponentials combined (e^y/e^x is e^(y − x)): both exact, so that 2^y = 2^x and e^y/e^x = 1 are
    seen as e^A = e^B."""
    def positive_base(e):
        return e.is_Pow and e.base.is_number and e.base.is_positive and e.base != 1 and not e.exp.is_number

    rewritten = residual.replace(positive_base, lambda e: sympy.exp(e.exp * sympy.log(e.base)))
    return sympy.powsimp(rewritten, combine="exp") if rewritten.has(sympy.exp) else rewritten


def _preimage(a: sympy.Expr, value: sympy.Expr) -> sympy.Expr | None:
    """``A - f⁻¹(value)`` for ``a = f(A)``, f one-to-one and ``value`` a number in its range; None otherwise."""
    if not value.is_number or not value.is_real:
        return None
    if isinstance(a, sympy.exp):
        return a.args[0] - sympy.log(value) if value.is_positive else None
    if isinstance(a, sympy.sinh):
        return a.args[0] - sympy.asinh(value)
    if isinstance(a, sympy.asinh):
        return a.args[0] - sympy.sinh(value)
    if isinstance(a, sympy.atan):
        return a.args[0] - sympy.tan(value) if (abs(value) < sympy.pi / 2) is sympy.true else None
    if isinstance(a, sympy.tanh):
        return a.args[0] - sympy.atanh(value) if (abs(value) < 1) is sympy.true else None
    if a.is_Pow and a.exp.is_Integer and a.exp > 0 and not a.base.is_number:
        n = int(a.exp)
        if n % 2 == 1:
            return a.base - sympy.real_root(value, n)
        return sympy.Abs(a.base) - value ** sympy.Rational(1, n) if value.is_nonnegative else None
    root = _odd_root(a)
    if root is not None:
        return root[0] - value ** root[1]
    return None


def _odd_root(a: sympy.Expr) -> tuple[sympy.Expr, int] | None:
    """(A, n) for the real n-th root of A with n odd, as the parser writes it: sign(A)·|A|^(1/n)."""
    if not a.is_Mul or len(a.args) != 2:
        return None
    signs = [f for f in a.args if isinstance(f, sympy.sign)]
    powers = [f for f in a.args if f.is_Pow and isinstance(f.base, sympy.Abs)]
    if len(signs) != 1 or len(powers) != 1:
        return None
    inner, exponent = signs[0].args[0], powers[0].exp
    if powers[0].base.args[0] not in (inner, -inner) \
            or not (exponent.is_Rational and exponent.p == 1 and exponent.q % 2 == 1):
        return None
    return inner, int(exponent.q)


def _same_power(left: sympy.Expr, right: sympy.Expr) -> sympy.Expr | None:
    """``A - B`` when ``left = A**n`` and ``right = B**n`` for an odd n (``|A| - |B|`` for an even one),
    each side a product of powers whose exponents n divides (8 x**3 = r**3 w**3: 2x = r w)."""
    exponents = [int(e) for side in (left, right) for base, e in side.as_powers_dict().items()
                 if not base.is_number and e.is_Integer]
    n = math.gcd(*exponents) if exponents else 0
    if n < 2:
        return None
    roots = []
    for side in (left, right):
        root = sympy.Integer(1)
        for base, e in side.as_powers_dict().items():
            if base.is_number and e.is_Integer and base.is_real:
                # the numeric part of the side, rooted as a whole below
                root *= sympy.real_root(base**e, n) if n % 2 == 1 or (base**e).is_nonnegative else sympy.nan
            elif e.is_Integer and int(e) % n == 0:
                root *= base ** (int(e) // n)
            else:
                return None
        if root.has(sympy.nan):
            return None
        roots.append(root)
    if n % 2 == 1:
        return roots[0] - roots[1]
    return sympy.Abs(roots[0]) - sympy.Abs(roots[1])


# Gröbner bases are taken only of small polynomial systems: their cost grows doubly exponentially.
GROEBNER_MAX_UNKNOWNS = 4
GROEBNER_MAX_DEGREE = 4
GROEBNER_MAX_PARAMETERS = 3
GROEBNER_BUDGET_S = 0.25


def _same_polynomial_ideal(reference: list[sympy.Expr], answer: list[sympy.Expr], state: set,
                           with_parameters: bool = True, domains: dict | None = None) -> bool:
    """Whether two systems of polynomial equations in the state generate the same ideal (equal reduced
    Gröbner bases), after each equation ``f(A) = f(B)`` is read as ``A = B`` (`_injective_sides`): then
    they have the same solutions. ``x y = 2, x + y = 3`` and ``x^2 - 3x + 2 = 0, y = 3 - x`` are no
    combination of each other with constant coefficients, but one ideal. Each equation keeps only what
    decides its real zeros (`_real_zeros_only`: (x - y)**2 is x - y, (x**2 + 1)(x - y) is x - y).
    Coefficients may hold parameters (``with_parameters``): they are variables of the polynomial ring
    like the unknowns, so equal ideals there are equal for every value of the parameters (a basis over
    their rational functions divides by them: ``(a - 1) y = (a - 1)(b - x)`` is ``y = b - x`` for all
    ``a`` but 1, where it says nothing). Equations of motion are compared with numbers only.

    >>> x, y = sympy.symbols("x y", real=True)
    >>> _same_polynomial_ideal([x*y - 2, x + y - 3], [x**2 - 3*x + 2, y - 3 + x], {x, y})
    True
    >>> _same_polynomial_ideal([x*y - 2, x + y - 3], [x**2 - 3*x + 2, y - x], {x, y})
    False
    """
    systems = []
    for system in (reference, answer):
        peeled = []
        for residual in system:
            inner = _injective_sides(residual)
            while inner is not None and not inner.has(sympy.Abs):
                residual, inner = inner, _injective_sides(inner)
            peeled.append(residual)
        systems.append(peeled)
    # Cheap refusals first: factoring a page of trigonometric equations of motion only to find that
    # they are no polynomials took a tenth of a second per check.
    unknowns_here = set().union(*(r.free_symbols for system in systems for r in system)) & state
    if not unknowns_here or len(unknowns_here) > GROEBNER_MAX_UNKNOWNS \
            or any(_nodes(r) > FACTOR_MAX_NODES or not r.is_polynomial(*unknowns_here)
                   for system in systems for r in system):
        return False
    systems = [[_real_zeros_only(r, domains or {}) for r in system] for system in systems]
    everything = [r for system in systems for r in system]
    gens = sorted(set().union(*(r.free_symbols for r in everything)) & state, key=lambda s: s.name)
    parameters = set().union(*(r.free_symbols for r in everything)) - set(gens)
    most = GROEBNER_MAX_PARAMETERS if with_parameters else 0
    if not gens or len(gens) > GROEBNER_MAX_UNKNOWNS or len(parameters) > most \
            or any(_nodes(r) > FACTOR_MAX_NODES for r in everything):
        return False
    try:
        polys = [[sympy.Poly(r, *gens) for r in system] for system in systems]
        if any(p.total_degree() > GROEBNER_MAX_DEGREE or p.is_zero for system in polys for p in system):
            return False
        if any(not p.get_domain().is_Exact for system in polys for p in system):
            return False  # a float coefficient: no exact basis
        # A basis can take seconds even at these sizes (degree 3 with one parameter: 13 s), and a
        # wrong system comes here too: the work is cut off in CPU time, the verdict then stays.
        ring = gens + sorted(parameters, key=lambda s: s.name)
        bases = budget.attempt(lambda: [_real_basis([p.as_expr() for p in system], ring, domains or {})
                                        for system in polys], GROEBNER_BUDGET_S, fallback=lambda: None)
    except (sympy.PolynomialError, sympy.polys.polyerrors.CoercionFailed, NotImplementedError, ValueError,
            TypeError):
        return False
    return bases is not None and list(bases[0].exprs) == list(bases[1].exprs) and not bases[0].exprs == [1]


# Rounds of a basis's elements cleaned by `_real_zeros_only` and the basis computed again.
REAL_BASIS_ROUNDS = 4


def _real_basis(polynomials: list[sympy.Expr], ring: list, domains: dict):
    """The reduced Gröbner basis of ``polynomials``, each of its elements then reduced to what decides its real
    zeros on the domain (`_real_zeros_only`) and the basis computed again, until nothing changes: the real
    solutions on the domain stay the same at each step. ``(x - y)(x + y) = 0, x + y = 2L`` has the element
    ``L (L - y)``, and with L > 0 its basis is that of ``x = y, x + y = 2L``; ``x = y, x³ + y³ = 2L³`` has
    ``y³ - L³``, whose factor ``y² + yL + L²`` is nonzero there."""
    basis = sympy.groebner(polynomials, *ring, order="grevlex")
    for _ in range(REAL_BASIS_ROUNDS):
        cleaned = [_real_zeros_only(element, domains) for element in basis.exprs]
        if cleaned == list(basis.exprs):
            break
        basis = sympy.groebner(cleaned, *ring, order="grevlex")
    return basis


def _real_zeros_only(residual: sympy.Expr, domains: dict) -> sympy.Expr:
    """``residual`` with the same real zeros on the declared domain, without repeated factors and
    without factors that are nonzero there (`_nonzero_on`), when it is a polynomial that factors; else
    ``residual`` itself.

    >>> x, y = sympy.symbols("x y", real=True)
    >>> _real_zeros_only(x**2 + y**2 - 2*x*y, {})
    x - y
    """
    if _nodes(residual) > FACTOR_MAX_NODES:
        return residual
    try:
        _, factors = budget.attempt(lambda: sympy.factor_list(residual), FACTOR_BUDGET_S,
                                    fallback=lambda: (1, [(residual, 1)]))
    except (sympy.PolynomialError, NotImplementedError, ValueError, TypeError):
        return residual
    kept = [f for f, _ in factors if not (f.free_symbols and _nonzero_on(f, domains) is True)]
    kept = [f for f in kept if f.free_symbols]
    return sympy.Mul(*kept) if kept else residual


def _positive_quadratic(expr: sympy.Expr, domains: dict | None = None) -> bool:
    """Whether ``expr`` is a quadratic polynomial with numeric coefficients that is positive (or
    negative) on the whole space: a definite Hessian and a minimum of that sign (``x**2 + x*y + y**2 + 1``,
    the factor of ``x**3 + x = y**3 + y`` against ``x = y``, which no box over the real line bounds), or
    a minimum of zero at a point outside the declared ``domains`` (``y**2 + y*L + L**2`` with L > 0, the
    factor of ``y**3 = L**3``)."""
    symbols = sorted(expr.free_symbols, key=lambda s: s.name)
    if not symbols or _nodes(expr) > FACTOR_MAX_NODES:
        return False
    try:
        poly = sympy.Poly(expr, *symbols)
    except sympy.PolynomialError:
        return False
    if poly.total_degree() != 2 or poly.get_domain() not in (sympy.ZZ, sympy.QQ):
        return False
    for sign in (1, -1):
        f = sign * poly.as_expr()
        hessian = sympy.hessian(f, symbols)
        if not all(hessian[:i, :i].det() > 0 for i in range(1, len(symbols) + 1)):
            continue
        gradient = sympy.Matrix([sympy.diff(f, s) for s in symbols])
        at_zero = dict(zip(symbols, [0] * len(symbols)))
        lowest = -hessian.LUsolve(gradient.subs(at_zero))
        minimum = f.subs(dict(zip(symbols, lowest)))
        if minimum == 0 and domains:
            # zero only at the minimum: nonzero wherever that point is not
            return any(s in domains and not domains[s].contains(float(v)) for s, v in zip(symbols, lowest))
        return bool(minimum > 0)
    return False


def _nonzero_on(expr: sympy.Expr, domains: dict, boxes: int = FACTOR_MAX_BOXES) -> bool | None:
    """True when ``expr`` is provably nonzero (and finite) on the whole declared domain, else None.

    Factor by factor: cancelling a ratio multiplies out a product of nonzero factors ((2 + cos θ₁)
    times a double pendulum's 2m₁ + m₂ − m₂ cos 2(θ₁ − θ₂)), and each is shown nonzero by its own rule,
    the sum they multiply out to by none."""
    factored = _factored(expr)
    if factored is expr:  # too large, out of its budget, or irreducible
        factored = sympy.factor_terms(expr)
    for factor in sympy.Mul.make_args(factored):
        if factor.is_Pow and factor.exp.is_Integer:
            factor = factor.base  # a power vanishes where its base does (and has poles where it has zeros)
        if factor.is_number:
            if factor.is_zero is False and factor.is_finite:
                continue
            return None
        if factor.is_positive or factor.is_negative or _signed_as_squares(factor) or _no_real_root(factor, domains) \
                or _no_real_root(_dehomogenised(factor, domains), domains) or _outside_the_range(factor) \
                or _positive_quadratic(factor, domains) or _signed_by_the_order(factor):
            continue
        if _nonzero_in_balls(factor, domains, boxes) is not True:
            return None
    return True


_ORDER: contextvars.ContextVar[dict] = contextvars.ContextVar("declared below", default={})
# One-to-one functions taken off both sides, nested: each undoes one written by the student (exp of a log of
# exp ...), and a bound keeps two rewritings that undo each other from looping.
_PEELED: contextvars.ContextVar[int] = contextvars.ContextVar("one-to-one functions taken off", default=0)
MAX_PEELED = 4


def _signed_by_the_order(expr: sympy.Expr) -> bool:
    """Whether ``expr`` has one sign once each declared ``a below b`` is b = a + s with s > 0: L − x, √(L² − x²)'s
    L² − x² (x > 0), R² + d² − 2Rd cos θ = 4d(d + s) sin²(θ/2) + s² for d below R."""
    order = {a: b for a, b in _ORDER.get().items() if a in expr.free_symbols or b in expr.free_symbols}
    if not order or _nodes(expr) > FACTOR_MAX_NODES:
        return False
    gaps = {b: a + sympy.Dummy(positive=True) for a, b in order.items()}
    shifted = expr.xreplace(gaps)
    for form in (sympy.expand(shifted), _factored(shifted)):
        if form.is_positive or form.is_negative or _signed_as_squares(form):
            return True
    return False


def _no_real_root(expr: sympy.Expr, domains: dict) -> bool:
    """Whether ``expr``, a polynomial in one variable with rational coefficients, has no real root
    in that variable's declared domain (ends included), counted exactly (Sturm): ``x**2 + 2*x + 4``
    on the whole real line, which no box of finite x can bound away from zero."""
    symbols = expr.free_symbols
    if len(symbols) != 1 or _nodes(expr) > FACTOR_MAX_NODES:
        return False
    (symbol,) = symbols
    domain = domains.get(symbol)
    if domain is None:
        return False
    lo, hi = getattr(domain, "lo", -math.inf), getattr(domain, "hi", math.inf)
    if getattr(domain, "kind", None) in ("positive", "nonnegative"):
        lo = 0.0
    try:
        poly = sympy.Poly(expr, symbol)
        if poly.degree() < 1 or poly.get_domain() not in (sympy.ZZ, sympy.QQ):
            return False
        roots = poly.count_roots(None if math.isinf(lo) else sympy.Rational(lo),
                                 None if math.isinf(hi) else sympy.Rational(hi))
    except (sympy.PolynomialError, ValueError, TypeError):
        return False
    return roots == 0


# The values a function defined on the whole real line takes there: (low, high, low end left out, high end left
# out). (asin and acos are left out: a factor undefined somewhere is no factor nonzero everywhere.)
_RANGES = {sympy.atan: (-sympy.pi / 2, sympy.pi / 2, True, True), sympy.tanh: (-1, 1, True, True),
           sympy.exp: (0, sympy.oo, True, True), sympy.cosh: (1, sympy.oo, False, True),
           sympy.sin: (-1, 1, False, False), sympy.cos: (-1, 1, False, False), sympy.sech: (0, 1, True, False)}


def _outside_the_range(expr: sympy.Expr) -> bool:
    """Whether ``expr`` is ``c + a f(u)`` (numbers ``c`` and ``a != 0``) with ``-c/a`` outside the values ``f`` takes
    anywhere on the real line: tanh(x/L) + 1 and atan(x/L) − 1.5708 never vanish, though no box of finite x shows it
    (tanh's values come as near −1 as one likes)."""
    constant, rest = [], []
    for term in sympy.Add.make_args(expr):
        (constant if term.is_number else rest).append(term)
    if len(rest) != 1 or not constant:
        return False
    a, call = rest[0].as_coeff_Mul()
    if type(call) not in _RANGES or not a.is_number or a.is_zero is not False or not call.args[0].is_real:
        return False
    value = -sympy.Add(*constant) / a
    lo, hi, lo_open, hi_open = _RANGES[type(call)]
    try:
        below, above = bool(sympy.Lt(value, lo)), bool(sympy.Gt(value, hi))
        at_lo, at_hi = (value - lo).is_zero, (value - hi).is_zero
    except TypeError:
        return False
    return below or above or (lo_open and at_lo is True) or (hi_open and at_hi is True)


def _dehomogenised(expr: sympy.Expr, domains: dict) -> sympy.Expr:
    """``expr``, a homogeneous polynomial, with a positive variable set to 1 where every other variable's domain
    is a cone (the real line, positive, nonnegative): x⁴ − 2x²L² + 1.000001 L⁴ is L⁴ times t⁴ − 2t² + 1.000001
    at t = x/L, which takes every value of x's domain, so each is nonzero where the other is. ``expr`` itself
    where that does not apply."""
    symbols = sorted(expr.free_symbols, key=lambda s: s.name)
    cones = ("real", "positive", "nonnegative")
    if len(symbols) < 2 or _nodes(expr) > FACTOR_MAX_NODES \
            or any(getattr(domains.get(s), "kind", None) not in cones for s in symbols):
        return expr
    try:
        if not sympy.Poly(expr, *symbols).is_homogeneous:
            return expr
    except (sympy.PolynomialError, ValueError, TypeError):
        return expr
    positive = [s for s in symbols if domains[s].kind == "positive"]
    return expr.xreplace({positive[0]: sympy.Integer(1)}) if positive else expr


_SQUARES = ((sympy.cos(_U)**2, 1 - sympy.sin(_U)**2), (sympy.sin(_U)**2, 1 - sympy.cos(_U)**2),
            (sympy.cos(_U), 1 - 2*sympy.sin(_U / 2)**2))


def _signed_as_squares(expr: sympy.Expr) -> bool:
    """Whether ``expr`` has one sign once a cosine is written with a sine squared: ``m1 + m2 - m2 cos(x)**2``
    is ``m1 + m2 sin(x)**2 > 0``, the determinant of a double pendulum's mass matrix, which ball
    arithmetic cannot bound away from zero over all masses."""
    if not expr.has(sympy.sin, sympy.cos) or _nodes(expr) > FACTOR_MAX_NODES:
        return False
    for pattern, replacement in _SQUARES:
        form = sympy.expand(expr.replace(pattern, replacement))
        if form.is_positive or form.is_negative:
            return True
    return False


def _nonzero_in_balls(expr: sympy.Expr, domains: dict, most_boxes: int = FACTOR_MAX_BOXES) -> bool | None:
    """Ball arithmetic over the whole box of bounded domains: True if ``expr`` provably excludes 0.

    A polynomial in variables over the half-line x > 0 is first brought onto 0 <= t <= 1 (`_compactified`):
    ``1 - x + x**2`` has no zero for x > 0, which no box of finite x can show. A sine or cosine of
    an unbounded variable is first set free in [-1, 1] (`_trig_freed`): ``2 + cos(w*t)`` for every
    real t.
    """
    expr, trig_bounds = _trig_freed(expr, domains)
    half_lines = sorted((s for s in expr.free_symbols if _half_line(domains.get(s))), key=lambda s: s.name)
    bounds = {}
    if half_lines:
        if _nodes(expr) > FACTOR_MAX_NODES:
            return None  # no polynomial to bring onto [0, 1] without expanding it (a page-long row took minutes)
        expr, half_lines = _dehomogenized(expr, half_lines, domains)
        compact = _compactified(expr, half_lines)
        if compact is None:
            return None
        expr, bounds = compact
    bounds.update(trig_bounds)
    symbols = sorted(expr.free_symbols, key=lambda s: s.name)
    boxes = []
    for s in symbols:
        domain = domains.get(s)
        lo, hi = bounds.get(s) or (getattr(domain, "lo", -math.inf), getattr(domain, "hi", math.inf))
        if (domain is None and s not in bounds) or not (math.isfinite(lo) and math.isfinite(hi)):
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
            if tried > most_boxes:
                return None
            # the ball of both ends: a midpoint (lo + hi)/2 rounded in floats can leave out a zero
            # at the box's edge once bisection reaches the last bits of a float
            env = {s: flint.arb(lo).union(flint.arb(hi)) for s, (lo, hi) in zip(symbols, box)}
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
            # widest relative to its whole domain: an angle's 2 pi should not starve a t in [0, 1]
            widest = max(range(len(box)), key=lambda i: (box[i][1] - box[i][0]) / (boxes[i][1] - boxes[i][0] or 1))
            lo, hi = box[widest]
            middle = (lo + hi) / 2
            pending.append(box[:widest] + [(lo, middle)] + box[widest + 1:])
            pending.append(box[:widest] + [(middle, hi)] + box[widest + 1:])
    return True


def _trig_freed(expr: sympy.Expr, domains: dict) -> tuple[sympy.Expr, dict]:
    """``expr`` with each sine and cosine of an argument over an unbounded domain replaced by a free
    variable in [-1, 1], and those bounds.

    The values such a sine takes are a subset of [-1, 1] (and sin and cos of one argument are set
    free of each other), so ``expr`` nonzero over the freed box is nonzero over the domain: a proof
    stays a proof, which no box of a finite t could give for ``2 + cos(w*t)``."""
    def unbounded(symbol):
        domain = domains.get(symbol)
        return domain is not None and not (math.isfinite(getattr(domain, "lo", -math.inf))
                                           and math.isfinite(getattr(domain, "hi", math.inf)))
    freed, bounds = {}, {}
    for f in expr.atoms(sympy.sin, sympy.cos):
        if any(unbounded(s) for s in f.args[0].free_symbols):
            freed[f] = sympy.Dummy(f"{type(f).__name__}_{f.args[0]}", real=True)
            bounds[freed[f]] = (-1.0, 1.0)
    return (expr.xreplace(freed), bounds) if freed else (expr, {})


def _half_line(domain) -> bool:
    return getattr(domain, "kind", None) in ("positive", "nonnegative")


# Most variables on a half-line whose subsets are searched for a homogeneous group.
HOMOGENEOUS_MAX_VARIABLES = 5


def _dehomogenized(expr: sympy.Expr, variables: list, domains: dict) -> tuple[sympy.Expr, list]:
    """``expr`` with one variable of each group in which it is homogeneous set to 1, and the variables left.

    A physical expression is homogeneous in each kind of quantity (``L**2 - L*r + r**2`` in the
    lengths), and then vanishes at the origin of the group, which no closed box avoids. With
    ``g > 0``, ``f(x) = g**d f(x/g)``: ``f`` has a zero exactly when ``f`` with ``g = 1`` has one.
    """
    if len(variables) > HOMOGENEOUS_MAX_VARIABLES:
        return expr, variables
    variables = list(variables)
    for size in range(len(variables), 1, -1):
        for group in itertools.combinations(list(variables), size):
            if not all(v in variables for v in group):
                continue
            pivot = next((v for v in group if getattr(domains.get(v), "kind", None) == "positive"), None)
            if pivot is None:
                continue
            try:
                homogeneous = sympy.Poly(expr, *group).is_homogeneous
            except (sympy.PolynomialError, sympy.polys.polyerrors.GeneratorsError):
                return expr, variables
            if homogeneous:
                expr = expr.xreplace({pivot: sympy.S.One})
                variables.remove(pivot)
    return expr, variables


def _compactified(expr: sympy.Expr, variables: list) -> tuple[sympy.Expr, dict] | None:
    """``expr``, a polynomial of degree ``n_i`` in each ``x_i >= 0``, as ``F(t) = f(x) * prod (1 - t_i)**n_i``
    with ``x_i = t_i/(1 - t_i)``, and the bounds 0 <= t_i <= 1; None when ``expr`` is no such polynomial.

    ``(1 - t)**n > 0`` for t < 1, so ``F`` and ``f`` vanish together, and ``F`` is a polynomial on a closed
    box, where ball arithmetic can show it has no zero; t = 1 stands for x going to infinity.
    """
    try:
        poly = sympy.Poly(expr, *variables)
    except (sympy.PolynomialError, sympy.polys.polyerrors.GeneratorsError):
        return None
    degrees = poly.degree_list()
    if sum(degrees) > FACTOR_MAX_POWER:
        return None
    ts = [sympy.Dummy(f"t_{x.name}") for x in variables]
    terms = []
    for monomial, coefficient in poly.terms():
        term = coefficient
        for t, a, n in zip(ts, monomial, degrees):
            term *= t**a * (1 - t)**(n - a)
        terms.append(term)
    return sympy.Add(*terms), {t: (0.0, 1.0) for t in ts}


def _sign_change(expr: sympy.Expr, parameters: Sampler, states: Sampler) -> dict | None:
    """Two sampled states where ``expr`` provably has opposite signs (so it vanishes in between)."""
    try:
        f = compile_expr(expr, ArbBackend())
    except Unsupported:
        return None
    seen = {}
    fixed = parameters.point(0)
    points = [states.joint(fixed, states.point(i)) for i in range(12)] + [states.joint(fixed, states.wide_point(i))
                                                                           for i in range(12)]
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


_POLES = (sympy.tan, sympy.cot, sympy.sec, sympy.csc, sympy.coth, sympy.csch)


def _zero_or_nonzero(expr: sympy.Expr, domains: dict, sampled: list[dict], deadline: float | None = None):
    """For a factor the first proof (`_nonzero_on`) left open and no sign change showed to vanish: True where a proof
    with more boxes shows it nonzero after all (1.4143 − cos θ − sin θ, at least 8.6e-5), else a point where it is
    zero or has a pole (`_zero_witness` of it or of its reciprocal: 1 + cos θ touches zero at π), else None:
    undecided, which is no refusal."""
    if _nonzero_on(expr, domains, boxes=FACTOR_MORE_BOXES) is True:  # (a tenth of a second at most)
        return True
    touched = _zero_witness(expr, domains, sampled, deadline)
    if touched is None and any(isinstance(n, _POLES) or (n.is_Pow and n.exp.is_negative)
                               for n in sympy.preorder_traversal(expr)):
        touched = _zero_witness(1 / expr, domains, sampled, deadline)  # a pole: tan θ at π/2 is undefined there
    return touched


def _zero_witness(expr: sympy.Expr, domains: dict, sampled: list[dict],
                  deadline: float | None = None) -> dict | None:
    """A point of the declared domains where ``expr`` is zero to 30 digits, found by a root search for multiple
    roots (`mpmath.findroot`'s ``mnewton``) in one variable at a time from the ``sampled`` points, or None.

    For a factor that touches zero without changing sign, which `_sign_change` cannot see: ``1 + cos θ`` at θ = π,
    ``θ̇²``, and ``l θ̇² + g (1 − cos θ)``, zero only where θ = θ̇ = 0 (each search starts also from the sampled
    state with every variable whose domain holds 0 set to 0). A root within 1e-12 of an end of an interval counts
    as inside it: an end typed ``pi/2`` is stored rounded.
    """
    try:
        f = compile_expr(expr, MpmathBackend())
    except Unsupported:
        return None

    def holds_zero(symbol) -> bool:
        domain = domains.get(symbol)
        return getattr(domain, "kind", None) in ("real", "nonnegative") or (
            getattr(domain, "kind", None) == "interval" and domain.lo <= 0 <= domain.hi)

    starts = [{s: (0.0 if holds_zero(s) else v) for s, v in point.items()} for point in sampled] + sampled
    symbols = sorted(expr.free_symbols, key=lambda s: s.name)
    with mpmath.workdps(WITNESS_DPS):
        def value(env):
            try:
                return f({**env, SCALE: -math.inf})
            except (Undefined, Unresolved, ZeroDivisionError, ValueError, TypeError):
                return None

        for start in starts:
            env = {s: mpmath.mpf(v) for s, v in start.items()}
            size = value(env)
            if size is None:
                continue
            for symbol in symbols:
                if symbol not in env or _past(deadline):
                    continue
                domain = domains.get(symbol)
                lo, hi = getattr(domain, "lo", -math.inf), getattr(domain, "hi", math.inf)
                if getattr(domain, "kind", None) in ("positive", "nonnegative"):
                    lo, hi = 0.0, math.inf
                slack = 1e-12 * max([1.0, *(abs(x) for x in (lo, hi) if math.isfinite(x))])
                guesses = [env[symbol]] + [x for x in (lo, hi, 0.0) if math.isfinite(x) and lo <= x <= hi]
                # and the least values along a scan of the whole domain: a local search from the sample alone
                # leaves it (1 + sin Ωt from t = 0.9 goes to t = −π/(2Ω) < 0, not to 3π/(2Ω))
                scanned = []
                for x in _witness_grid(lo, hi, float(env[symbol])):
                    y = value({**env, symbol: mpmath.mpf(x)})
                    if y is not None:
                        scanned.append((abs(y), x))
                guesses += [x for _, x in sorted(scanned)[:WITNESS_SCAN_STARTS]]
                for guess, solver in itertools.product(guesses, WITNESS_SOLVERS):
                    def along(x, symbol=symbol):
                        y = value({**env, symbol: x})
                        if y is None:
                            raise ValueError("undefined")
                        return y
                    try:
                        root = mpmath.findroot(along, mpmath.mpf(guess), solver=solver, maxsteps=WITNESS_STEPS,
                                               tol=mpmath.mpf(10) ** -(2 * WITNESS_DPS // 3), verify=False)
                    except (ValueError, ZeroDivisionError, TypeError, OverflowError):
                        continue
                    if isinstance(root, mpmath.mpc) or not mpmath.isfinite(root) or not lo - slack <= root <= hi + slack \
                            or (getattr(domain, "kind", None) == "positive" and root <= slack):
                        # (positive: open at 0, where a factor l·(…) only tends to zero)
                        continue
                    there = value({**env, symbol: root})
                    if there is not None and abs(there) <= WITNESS_ZERO * max(abs(size), 1):
                        return {s.name: float(v) for s, v in {**env, symbol: root}.items()}
    return None


def _witness_grid(lo: float, hi: float, at: float) -> list[float]:
    """Points across a domain for `_zero_witness`'s scan: evenly over a finite interval, geometrically over a
    half-line or the real line (from a thousandth to ten thousand times the sampled value's scale)."""
    if math.isfinite(lo) and math.isfinite(hi):
        return list(np.linspace(lo, hi, WITNESS_SCAN_POINTS))
    scale = max(abs(at), 1.0)
    magnitudes = list(scale * np.geomspace(1e-3, 1e4, WITNESS_SCAN_POINTS // 2))
    if lo >= 0:
        return [lo + x for x in magnitudes]
    if hi <= 0:
        return [hi - x for x in magnitudes]
    return magnitudes + [-x for x in magnitudes]


_JUMPS = (sympy.sign, sympy.floor, sympy.ceiling, sympy.Heaviside, sympy.Piecewise)


def _defined_everywhere(condition: sympy.Expr, domains: dict) -> bool:
    """Whether a typed domain's condition (``log(u)``, ``u**(p/q)``: u must be positive, or not negative) holds on the
    whole declared domain: ``u`` proved nonzero and finite there (`_nonzero_on`), continuous, and positive at one
    point, so positive everywhere (the domain is a box, connected). False where that is not shown."""
    if isinstance(condition, sympy.log):
        u = condition.args[0]
    elif condition.is_Pow and condition.exp.is_Rational and not condition.exp.is_Integer:
        u = condition.base
    else:
        return False
    if u.is_positive:
        return True
    if u.has(*_JUMPS) or _nodes(u) > FACTOR_MAX_NODES or _nonzero_on(u, domains) is not True:
        return False
    point = {s: _inside(domains[s]) for s in u.free_symbols if s in domains}
    if len(point) != len(u.free_symbols):
        return False
    try:
        value, _ = Compiled(u, ArbBackend()).at(point, 64)
    except (Undefined, Unresolved, Unsupported):
        return False
    return bool(value > 0)


def _inside(domain) -> float:
    """A value inside a declared domain."""
    lo, hi = getattr(domain, "lo", -math.inf), getattr(domain, "hi", math.inf)
    if getattr(domain, "kind", None) in ("positive", "nonnegative"):
        return 1.0
    if math.isfinite(lo) and math.isfinite(hi):
        return (lo + hi) / 2
    return lo + 1.0 if math.isfinite(lo) else hi - 1.0 if math.isfinite(hi) else 1.0


def _first_state(parameters: Sampler, states: Sampler) -> dict:
    """The first sampled state with the first parameter point: where a search for a factor's zero starts."""
    return states.joint(parameters.point(0), states.point(0))


def _domain_point(expr: sympy.Expr, domains: dict) -> dict:
    """A point of the declared domains for ``expr``'s variables (a fixed draw), where a search for a factor's zero
    starts when no sampler is given (the second try of `state_dependent_factor`, in new variables)."""
    rng = random.Random(0)
    return {s: domains[s].sample(rng) for s in sorted(expr.free_symbols, key=lambda s: s.name) if s in domains}


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
            point = states.joint(parameters.point(p), states.point(2 * p + j))
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
