"""Equivalence of two expressions over the variables' domains: symbolic when cheap, else numeric.

The numeric judge evaluates both expressions at sample points in ball arithmetic (python-flint
``arb``) and raises the working precision until each point is decided:

- the ball of ``answer - reference`` excludes zero: the expressions provably differ there, and the
  point is a counterexample (a proof of non-equivalence);
- the ball contains zero and its radius is below ``10**-digits`` times the scale of the
  computation (the largest term it added): the expressions agree there to ``digits`` digits.

After agreement, the points are also drawn where the expressions' own constants say to look
(``abs(x - 10)``) and in every sign pattern of an abs/sign argument that sampling meets
(``abs(abs(x) + y)`` and ``abs(x) + y`` differ only where y < -|x|).

Balls make float64's failure modes harmless: ``1 - cos(theta)`` at ``theta = 1e-8`` is computed
with more bits until the answer is certain, instead of cancelling to zero. The ``float64`` and
``mpmath`` methods (fixed precision and a tolerance, no error bound) exist for the benchmark.
"""

from __future__ import annotations

import itertools
import math
import time
from fractions import Fraction
from dataclasses import dataclass, field, replace
from functools import lru_cache
from typing import Any, Callable

import flint
import mpmath
import numpy as np
import sympy

from grader.answers.evaluate import (
    SCALE,
    ArbBackend,
    FloatBackend,
    MpmathBackend,
    Undefined,
    Unresolved,
    Unsupported,
    _log2_mag,
    compile_expr,
)
from grader.answers.sampling import GivenPoints, Sampler
from grader.expressions.functions import REGISTRY
from grader.expressions.magnitudes import node_count

__all__ = ["Options", "Comparison", "Compiled", "PointResult", "compare_expressions", "expansion_terms",
           "symbolic_zero", "SYMBOLIC_MAX_TERMS"]

LOG2_10 = math.log2(10)


@dataclass(frozen=True)
class Options:
    """How hard the numeric judge works.

    Attributes
    ----------
    points : int
        Sample points that must agree before answering ``equivalent``.
    method : str
        ``"arb"`` (ball arithmetic, adaptive precision: the default and the only rigorous one),
        ``"mpmath"`` (fixed ``digits`` of precision) or ``"float64"``.
    digits : int
        ``arb``: digits of agreement required at each point; ``mpmath``: working digits.
    tolerance : float
        Relative tolerance of the ``float64`` and ``mpmath`` methods.
    max_bits : int
        Highest working precision tried by ``arb`` before a point is called unresolved.
    symbolic : bool
        Try a cheap symbolic proof (expansion) first.
    factors : bool
        Equations: accept the reference times a state-dependent factor that is provably nonzero
        on the domain (`grader.answers.equations.state_dependent_factor`, a symbolic step). Off
        for feedback candidates, which are many and only need to be screened.
    fast : bool
        The faster paths (a term's scale from its float midpoint, the answer's values remembered
        between the one-point screen and the full comparison, no expansion of a difference with a
        sum in a denominator, which expansion cannot cancel). False is the older path, kept so that
        ``grader bench check`` shows before/after with identical verdicts.
    """

    points: int = 8
    method: str = "arb"
    digits: int = 30
    tolerance: float = 1e-9
    max_bits: int = 4096
    symbolic: bool = True
    factors: bool = True
    fast: bool = True

    def backend(self):
        if self.method == "arb":
            return ArbBackend(self.fast)
        return {"mpmath": MpmathBackend, "float64": FloatBackend}[self.method]()

    def describe(self) -> str:
        if self.method == "arb":
            return "ball arithmetic"
        if self.method == "mpmath":
            return f"mpmath at {self.digits} digits, relative tolerance {self.tolerance:g}"
        return f"float64, relative tolerance {self.tolerance:g}"


@dataclass
class Comparison:
    """The outcome of comparing two expressions (or equations).

    ``equivalent`` is True, False, or None when undecided (budget spent, or no usable point).
    ``certainty`` is ``"proved"`` (symbolic identity, or a counterexample certified in ball
    arithmetic), ``"numeric"`` (agreement at ``evidence["points"]`` points to
    ``evidence["digits"]`` digits) or ``"none"``.
    """

    equivalent: bool | None
    certainty: str
    reason: str
    evidence: dict = field(default_factory=dict)
    counterexample: dict | None = None
    budget_exceeded: bool = False
    # values at the counterexample, for feedback (answer, reference) as floats
    values: tuple[float, float] | None = None


@dataclass
class PointResult:
    kind: str  # agree | differ | answer_undefined | reference_undefined | unresolved | budget
    answer: Any = None
    reference: Any = None
    digits: float = 0.0
    reason: str = ""


class Compiled:
    """An expression compiled for one backend, with a cache of values at keyed points.

    The cache is what makes a file of answers to the same reference cheap: the reference is
    evaluated once per sample point and precision.

    Examples
    --------
    >>> import sympy
    >>> x = sympy.Symbol("x", positive=True)
    >>> c = Compiled(x**2, ArbBackend())
    >>> value, scale = c.at({x: 3.0}, prec=64, key=0)
    >>> value == 9
    True
    """

    def __init__(self, expr: sympy.Expr, backend, conditions: tuple = ()):
        self.expr = expr
        self.backend = backend
        self.f: Callable = _with_conditions(compile_expr(expr, backend), conditions, backend)
        self._cache: dict = {}

    def at(self, point: dict, prec: int, key=None):
        """Value and scale (log2 of the largest term added) at ``point``; may raise."""
        if key is not None and (key, prec) in self._cache:
            cached = self._cache[key, prec]
            if isinstance(cached, Exception):
                raise cached
            return cached
        try:
            result = self._evaluate(point, prec)
        except (Undefined, Unresolved) as error:
            if key is not None:
                self._cache[key, prec] = error
            raise
        if key is not None:
            self._cache[key, prec] = result
        return result

    def _evaluate(self, point: dict, prec: int):
        backend = self.backend
        if backend.name == "arb":
            # flint.ctx.workprec(prec) by hand: the context manager costs more than a small
            # evaluation, and this runs for every point, precision and candidate.
            ctx = flint.ctx
            outer = ctx.prec
            ctx.prec = prec
            try:
                env = {s: flint.arb(v) for s, v in point.items()}
                env[SCALE] = -math.inf
                value = self.f(env)
                if not value.is_finite():
                    raise Unresolved
                return value, env[SCALE]
            finally:
                ctx.prec = outer
        if backend.name == "mpmath":
            with mpmath.workprec(prec):
                env = {s: mpmath.mpf(v) for s, v in point.items()}
                env[SCALE] = -math.inf
                value = self.f(env)
                if not mpmath.isfinite(value):
                    raise Undefined("not a finite number")
                return value, env[SCALE]
        env = {s: float(v) for s, v in point.items()}
        env[SCALE] = -math.inf
        try:
            value = self.f(env)
        except (OverflowError, ZeroDivisionError) as error:
            raise Undefined("overflow in float64") from error
        if isinstance(value, complex) or not math.isfinite(value):
            raise Undefined("overflow in float64")
        return value, env[SCALE]


def _with_conditions(f: Callable, conditions: tuple, backend) -> Callable:
    """``f``, undefined wherever one of ``conditions`` is (the typed text's real domain, see
    `grader.expressions.Parsed.conditions`): ``sqrt(x)**2`` typed is ``x`` but only for x >= 0."""
    checks = []
    for condition in conditions:
        try:
            checks.append(compile_expr(condition, backend))
        except Unsupported:
            continue  # nothing the evaluator can test: the expression itself still decides
    if not checks:
        return f

    def checked(env):
        scale = env[SCALE]
        for check in checks:
            check(env)  # raises Undefined outside the domain
        env[SCALE] = scale  # the conditions are not terms of the value
        return f(env)

    return checked


def as_float(x) -> float | str:
    """A JSON-friendly number: a float when it is one, else a decimal string."""
    if isinstance(x, flint.arb):
        mid = x.mid()
        f = float(mid)
        if math.isfinite(f) and (f != 0 or mid.is_zero()):
            return f
        return mid.str(15, radius=False)
    try:
        f = float(x)
    except (TypeError, ValueError, OverflowError):
        return str(x)
    return f if math.isfinite(f) else str(x)


def compare_at(ref: Compiled, ans: Compiled, point: dict, key, options: Options, deadline: float | None) -> PointResult:
    """Decide whether ``ans`` and ``ref`` agree at one point (see the module docstring)."""
    if options.method != "arb":
        return _compare_fixed(ref, ans, point, key, options)
    target = options.digits * LOG2_10
    prec = int(target) + 32
    while True:
        try:
            r, r_scale = ref.at(point, prec, key)
        except Undefined as error:
            return _where_reference_is_undefined(ans, point, prec, error)
        except Unresolved:
            r = None
        if r is not None:
            try:
                a, a_scale = ans.at(point, prec, key if options.fast else None)
            except Undefined as error:
                return PointResult("answer_undefined", reference=r, reason=error.reason)
            except Unresolved:
                a = None
            if a is not None:
                d = a - r
                if not d.contains(0):
                    return PointResult("differ", answer=a, reference=r)
                if d.rad().is_zero():
                    return PointResult("agree", a, r, digits=math.inf)
                size = max(_log2_mag(a), _log2_mag(r))
                scale = max(r_scale, a_scale, size)
                if math.isinf(scale):  # values beyond any float's range: no precision will tell
                    return PointResult("unresolved")
                noise = _log2_mag(d.rad())
                # Agreement is to the digits of the values themselves: a value that cancels far below
                # its terms (1 - cos θ at θ ~ 1e-10) is worked at more precision, where θ²/2 shows
                # its difference. Only a value that stays below every precision tried (an exact zero
                # reached by cancellation) is taken at the scale of its terms.
                if noise <= size - target:
                    return PointResult("agree", a, r, digits=(size - noise) / LOG2_10)
                if noise <= scale - target and prec * 2 > options.max_bits:
                    return PointResult("agree", a, r, digits=(scale - noise) / LOG2_10)
        prec *= 2
        if prec > options.max_bits:
            return PointResult("unresolved")
        if deadline is not None and time.monotonic() > deadline:
            return PointResult("budget")


def _where_reference_is_undefined(ans: Compiled, point: dict, prec: int, error: Undefined) -> PointResult:
    """A point of the declared domain where the reference is undefined: skipped when the answer is
    undefined too, a difference when it is defined (``x`` is not ``(x**3)**(1/3)`` for real x: a
    power law that holds only for nonnegative bases must not make them equal)."""
    try:
        a, _ = ans.at(point, prec)
    except (Undefined, Unresolved):
        return PointResult("reference_undefined", reason=error.reason)
    return PointResult("answer_defined", answer=a, reason=error.reason)


def _compare_fixed(ref: Compiled, ans: Compiled, point: dict, key, options: Options) -> PointResult:
    """float64 / mpmath: agreement within a relative tolerance (WeBWorK's rule)."""
    prec = 53 if options.method == "float64" else int(options.digits * LOG2_10) + 1
    try:
        r, _ = ref.at(point, prec, key)
    except (Undefined, Unresolved) as error:
        return PointResult("reference_undefined", reason=getattr(error, "reason", ""))
    try:
        a, _ = ans.at(point, prec)
    except (Undefined, Unresolved) as error:
        return PointResult("answer_undefined", reference=r, reason=getattr(error, "reason", ""))
    diff, size = abs(a - r), max(abs(a), abs(r))
    # WeBWorK: relative tolerance, except near zero (zeroLevel 1e-14) where 1e-12 is absolute
    ok = diff <= 1e-12 if size < 1e-14 else diff <= options.tolerance * size
    if ok:
        digits = math.inf if diff == 0 else -math.log10(max(diff / size, 1e-300)) if size else 0.0
        return PointResult("agree", a, r, digits=digits)
    return PointResult("differ", answer=a, reference=r)


def counterexample(point: dict, result: PointResult) -> dict:
    """The counterexample record of a verdict: values, both results, and their difference."""
    # (a value off the floats' grid, an exact fraction, as the JSON number nearest it)
    values = {s.name: float(v) if isinstance(v, flint.fmpq) else v for s, v in point.items()}
    record = {"values": values, "answer": None, "reference": as_float(result.reference)}
    if result.kind == "answer_defined":
        record["reference"] = "undefined"
        record["answer"] = as_float(result.answer)
        return record
    if result.kind == "answer_undefined":
        record["answer"] = "undefined"
        record["note"] = f"your answer is undefined here ({result.reason})"
        return record
    record["answer"] = as_float(result.answer)
    try:
        a, r = float(result.answer.mid() if hasattr(result.answer, "mid") else result.answer), float(
            result.reference.mid() if hasattr(result.reference, "mid") else result.reference
        )
        if r != 0 and math.isfinite(a) and math.isfinite(r):
            record["relative_difference"] = abs(a - r) / abs(r)
    except (TypeError, ValueError, OverflowError):
        pass
    return record


def round_values(point: dict, domains: dict) -> list[dict]:
    """Points near ``point`` with round values (2, 0.5, -1...) inside each variable's domain, the
    roundest first: a counterexample a student can check by hand reads "at θ = 0.5", not 0.4871.

    >>> import sympy
    >>> class Half:                                   # a stand-in for grader.expressions.Domain
    ...     def contains(self, x): return x > 0
    >>> x, y = sympy.symbols("x y")
    >>> [list(p.values()) for p in round_values({x: 1.8994, y: 0.0421}, {x: Half(), y: Half()})]
    [[2.0, 0.5], [2.0, 0.04]]
    >>> [list(p.values()) for p in round_values({x: 12345.6, y: 3.3}, {x: Half(), y: Half()})]
    [[10000.0, 3.0]]
    """
    def roundest(v: float) -> float:
        # A small whole number or a half near v's size (never 0: a zero hides most differences); a
        # stress point's 12345.6 becomes 10000, not 12346.
        if abs(v) >= 10:
            return float(f"{v:.0e}")
        if abs(v) >= 0.75:
            return float(math.copysign(round(abs(v)), v))
        return math.copysign(0.5, v)

    def one_figure(v: float) -> float:
        return float(f"{v:.1g}") if v else v

    found: list[dict] = []
    for rounding in (roundest, one_figure):
        candidate = {}
        for symbol, value in point.items():
            nice = rounding(value) if isinstance(value, float) and math.isfinite(value) else value
            domain = domains.get(symbol)
            candidate[symbol] = nice if domain is None or domain.contains(nice) else value
        if candidate != point and candidate not in found:
            found.append(candidate)
    return found


def _rounder_witness(ref: Compiled, ans: Compiled, sampler: Sampler, point: dict, result: PointResult,
                     options: Options, deadline: float | None) -> tuple[dict, PointResult]:
    """The same kind of difference at a rounder point when one shows it, else the point found."""
    for candidate in round_values(point, sampler.domains):
        if deadline is not None and time.monotonic() > deadline:
            break
        # No cache key: the cache is keyed by sample index, and this point is none of them.
        there = compare_at(ref, ans, candidate, None, options, deadline)
        if there.kind == result.kind:
            return candidate, there
    return point, result


# How far the neighbours of a point where only one side is undefined lie (relative to each value).
NEIGHBOUR_STEP = 1e-6


def _isolated(ref: Compiled, ans: Compiled, sampler: Sampler, point: dict, options: Options,
              deadline: float | None) -> bool:
    """Whether a point where only one of the two is undefined is isolated: at two neighbouring
    points (every variable moved by a relative 1e-6, one way and the other) both are defined.

    Such a point is a removable one, ``x = 2`` of ``|x² − 4|/(|x − 2||x + 2|)`` against 1, or
    ``d = 0`` of ``d x/(d t)`` against ``x/t``: the two are the same function wherever both are
    defined, and the set where only one is has no extent, so it is no counterexample (a sample
    point lands on it only when it is a round value). A region where one side is undefined, ``x <
    0`` of ``(x³)^(1/3)`` against ``x``, has its neighbours in it too, and stays a counterexample.
    """
    for sign in (1, -1):
        neighbour = {}
        for symbol, value in point.items():
            moved = value
            if isinstance(value, float) and math.isfinite(value):
                moved = value + sign * NEIGHBOUR_STEP * max(abs(value), 1.0)
                domain = sampler.domains.get(symbol)
                if domain is not None and not domain.contains(moved):
                    moved = value - sign * NEIGHBOUR_STEP * max(abs(value), 1.0)
                    if not domain.contains(moved):
                        return False
            neighbour[symbol] = moved
        there = compare_at(ref, ans, neighbour, None, options, deadline)
        if there.kind not in ("agree", "differ"):
            return False
    return True


def _points_evidence(options: Options, agreed: int, digits: float, unresolved: int) -> dict:
    evidence = {"method": options.describe(), "points": agreed}
    if options.method == "arb":
        evidence["digits"] = options.digits if math.isinf(digits) else int(min(digits, 1e6))
    if unresolved:
        evidence["unresolved_points"] = unresolved
    return evidence


def compare_numeric(
    ref: Compiled,
    ans: Compiled,
    sampler: Sampler,
    options: Options,
    deadline: float | None = None,
) -> Comparison:
    """Compare two compiled expressions at the sampler's points.

    Points where both are undefined are skipped (as WeBWorK does); a point where only one of them
    is undefined is a counterexample, unless it is isolated (`_isolated`: a removable point). Once the reference is undefined somewhere, every other point
    is drawn across the domains' whole scale (`Sampler.wide_point`), so that an expression defined
    only for x >= 5 is still decided, and more points are tried.
    """
    needed = options.points
    agreed, unresolved, ref_undefined = 0, 0, 0
    digits = math.inf
    proved = options.method == "arb"
    regular = wide = attempt = 0
    while attempt < (needed * 3 if not ref_undefined else needed * 6):
        if ref_undefined and attempt % 2:
            point, key = sampler.wide_point(wide), ("wide", wide)
            wide += 1
        else:
            point, key = sampler.point(regular), regular
            regular += 1
        attempt += 1
        result = compare_at(ref, ans, point, key, options, deadline)
        if result.kind == "agree":
            agreed += 1
            digits = min(digits, result.digits)
            if agreed >= needed:
                break
        elif result.kind in ("answer_undefined", "answer_defined") and _isolated(ref, ans, sampler, point, options,
                                                                                 deadline):
            continue  # a removable point: see _isolated
        elif result.kind in ("differ", "answer_undefined", "answer_defined"):
            point, result = _rounder_witness(ref, ans, sampler, point, result, options, deadline)
            example = counterexample(point, result)
            if result.kind == "differ":
                reason = "your answer and the correct one differ at the point in the counterexample"
                values = (_to_float(result.answer), _to_float(result.reference))
            elif result.kind == "answer_defined":
                reason = "your answer is defined at a point of the domain where the correct one is not"
                values = None
            else:
                reason = f"your answer is undefined at a point where the correct one is defined ({result.reason})"
                values = None
            return Comparison(
                False,
                "proved" if proved else "numeric",
                reason,
                evidence={"method": options.describe(), "points": agreed + 1},
                counterexample=example,
                values=values,
            )
        elif result.kind == "reference_undefined":
            ref_undefined += 1
        elif result.kind == "unresolved":
            unresolved += 1
        else:  # budget
            return Comparison(
                None,
                "none",
                "the time budget ran out while comparing",
                evidence=_points_evidence(options, agreed, digits, unresolved),
                budget_exceeded=True,
            )
    if agreed >= min(needed, 3) or (agreed and agreed >= needed):
        evidence = _points_evidence(options, agreed, digits, unresolved)
        how = f"agree at {agreed} sample points"
        if options.method == "arb":
            how += f" to at least {evidence['digits']} digits (ball arithmetic)"
        else:
            how += f" ({options.describe()})"
        return Comparison(True, "numeric", how, evidence=evidence)
    if agreed == 0 and ref_undefined and not unresolved:
        return Comparison(None, "none", f"{_UNDEFINED_EVERYWHERE} {ref_undefined} sample points "
                          "tried, across the whole scale of the declared domains (magnitudes 1e-3 to 1e6): "
                          "check the reference and the variables' domains", evidence={"points": 0})
    return Comparison(
        None,
        "none",
        "could not decide: the expressions could not be evaluated reliably at enough points",
        evidence=_points_evidence(options, agreed, digits, unresolved),
    )


_UNDEFINED_EVERYWHERE = "the reference is undefined at all"
# Shares of a region between two boundaries (or of its distance from the one boundary of an unbounded one) at
# which points of a reference defined only there are drawn.
REGION_SHARES = (0.02, 0.1, 0.25, 0.38, 0.5, 0.62, 0.75, 0.9, 0.98)
OUTER_SHARES = (0.01, 0.1, 0.38, 1.0, 3.0, 10.0, 100.0, 1000.0)
MAX_DEFINED_POINTS = 48


class _PointsSampler:
    """A `Sampler` whose ordinary and wide points are the given ones, in turn (its domains and orders kept)."""

    def __init__(self, sampler, points: list[dict], domains: dict | None = None):
        self._sampler, self._points = sampler, list(points)
        if domains is not None:  # a sampler over more variables than the one given (parameters and states)
            self.domains = domains

    def __getattr__(self, name):
        return getattr(self._sampler, name)

    def point(self, i: int) -> dict:
        return self._points[i % len(self._points)]

    def wide_point(self, i: int) -> dict:
        return self._points[(i + len(self._points) // 2) % len(self._points)]


def _where_defined(ref: Compiled, exprs, sampler, deadline: float | None) -> list[dict]:
    """Points where ``ref`` is defined, drawn in each region between the boundaries of the restricted arguments of
    ``exprs`` (a root's base, a log's argument, asin's ...: `_boundaries`) along each variable, the other
    variables as at the first few sample points; at most `MAX_DEFINED_POINTS`. For a reference defined only
    past the sampled magnitudes: sqrt(x − 10⁷) on x ≥ 10⁷."""
    boundaries = _boundaries(exprs)
    base = sampler.point(0)
    symbols = sorted({s for u, _ in boundaries for s in u.free_symbols if s in sampler.domains and s in base},
                     key=lambda s: s.name)[:MAX_SCANNED]
    below = {**sampler.below, **sampler.across}
    found: list[dict] = []
    for symbol in symbols:
        domain, span = sampler.domains[symbol], _span(sampler.domains[symbol])
        if span is None:
            continue
        breaks = sorted({t for u, values in boundaries if symbol in u.free_symbols
                         for t in _breakpoints(u, values, symbol, base, span)})
        edges = [span[0], *breaks, span[1]]
        values = []
        for a, b in zip(edges, edges[1:]):
            if math.isinf(a) and math.isinf(b):
                continue
            if math.isinf(b):
                values += [a + max(1.0, abs(a)) * share for share in OUTER_SHARES]
            elif math.isinf(a):
                values += [b - max(1.0, abs(b)) * share for share in OUTER_SHARES]
            else:
                values += [a + (b - a) * share for share in REGION_SHARES]
        for t in values:
            if deadline is not None and time.monotonic() > deadline or len(found) >= MAX_DEFINED_POINTS:
                return found
            if not domain.contains(t):
                continue
            for i in range(4):
                point = {**sampler.point(i), symbol: t}
                if not all(point[a] < point[b] for a, b in below.items() if a in point and b in point):
                    continue
                try:
                    ref.at(point, 64)
                except Undefined:
                    continue
                except Unresolved:
                    pass
                found.append(point)
    return found[:MAX_DEFINED_POINTS]


def _to_float(x) -> float:
    try:
        return float(x.mid()) if isinstance(x, flint.arb) else float(x)
    except (TypeError, ValueError, OverflowError):
        return math.nan


# -- symbolic --------------------------------------------------------------------------------

SYMBOLIC_MAX_NODES = 80
SYMBOLIC_MAX_POWER = 6


SYMBOLIC_MAX_TERMS = 500


def _small(expr: sympy.Expr) -> bool:
    # A plain stack walk (the order of the nodes does not matter here), quicker than
    # sympy.preorder_traversal's nested generators.
    nodes = 0
    stack = [expr]
    while stack:
        node = stack.pop()
        nodes += 1
        if nodes > SYMBOLIC_MAX_NODES:
            return False
        if node.is_Pow and node.exp.is_Integer and abs(int(node.exp)) > SYMBOLIC_MAX_POWER:
            return False
        stack.extend(node.args)
    return expansion_terms(expr) <= SYMBOLIC_MAX_TERMS


def expansion_terms(expr: sympy.Expr) -> int:
    """An upper bound on the terms ``expand`` makes of ``expr`` (of a power of a sum inside a function
    or a denominator too), past ``SYMBOLIC_MAX_TERMS`` only as far as it takes to know: powers of sums
    of powers of sums, each small, multiply out to tens of thousands of terms ((s⁵ + u⁵)⁴ with s a sum
    of three: 27,405), which took minutes to expand.

    >>> a, b, c = sympy.symbols("a b c")
    >>> expansion_terms((a + b)**2 * c), expansion_terms(((a + b + c)**2 + a)**3)
    (3, 84)
    """
    def terms(node) -> int:
        if node.is_Add:
            return min(sum(terms(a) for a in node.args), SYMBOLIC_MAX_TERMS + 1)
        if node.is_Mul:
            return min(math.prod(terms(a) for a in node.args), SYMBOLIC_MAX_TERMS + 1)
        if node.is_Pow and node.exp.is_Integer:
            k, n = terms(node.base), abs(int(node.exp))
            count = min(math.comb(k + n - 1, n), SYMBOLIC_MAX_TERMS + 1)  # monomials of degree n in k terms
            if node.exp < 0:  # expanded in the denominator: one term here, if it can be expanded at all
                return 1 if count <= SYMBOLIC_MAX_TERMS else SYMBOLIC_MAX_TERMS + 1
            return count
        inner = max((terms(a) for a in node.args), default=1)  # expanded inside a function
        return 1 if inner <= SYMBOLIC_MAX_TERMS else SYMBOLIC_MAX_TERMS + 1

    return terms(expr)


def symbolic_zero(diff: sympy.Expr) -> bool:
    """A cheap proof that ``diff`` is identically zero: sympy's automatic simplification plus
    ``expand`` on small expressions. False means "not proved", not "nonzero".

    Examples
    --------
    >>> import sympy
    >>> m, g, t = sympy.symbols("m g theta", positive=True)
    >>> symbolic_zero(m*g*(3*sympy.cos(t) - 2) - (3*m*g*sympy.cos(t) - 2*m*g))
    True
    >>> symbolic_zero(sympy.sin(t)**2 + sympy.cos(t)**2 - 1)  # true, but not proved cheaply
    False
    """
    if diff == 0:
        return True
    if not _small(diff):
        return False
    return sympy.expand(diff) == 0


def compare_expressions(
    reference: sympy.Expr,
    answer: sympy.Expr,
    sampler: Sampler,
    options: Options = Options(),
    deadline: float | None = None,
    compiled_reference: Compiled | None = None,
    answer_conditions: tuple = (),
    reference_conditions: tuple = (),
) -> Comparison:
    """Are ``answer`` and ``reference`` the same function on the sampler's domains?

    Parameters
    ----------
    reference, answer : sympy.Expr
        Built over the same symbols (with the domains' assumptions).
    sampler : Sampler
        Points inside the variables' domains.
    options : Options
    deadline : float, optional
        ``time.monotonic()`` after which the judge gives up (``budget_exceeded``).
    compiled_reference : Compiled, optional
        The reference compiled for ``options.backend()``, to reuse its cached values.
    answer_conditions, reference_conditions : tuple of sympy.Expr
        The texts' real domains as typed (`grader.expressions.Parsed.conditions`).

    Examples
    --------
    >>> import sympy
    >>> from grader.expressions import parse_domain
    >>> positive = parse_domain("positive")
    >>> m1, m2, g = sympy.symbols("m1 m2 g", positive=True)
    >>> s = Sampler({m1: positive, m2: positive, g: positive}, seed=3)
    >>> a = m2 * g / (m1 + m2)
    >>> c = compare_expressions(m1*m2*g/(m1 + m2), m2*(g - a), s, Options(symbolic=False))
    >>> c.equivalent, c.certainty
    (True, 'numeric')
    >>> c = compare_expressions(m1*m2*g/(m1 + m2), m1*m2*g/(m1 + m2)*(1 + sympy.Rational(1, 10**9)), s)
    >>> c.equivalent, c.certainty
    (False, 'proved')
    """
    diff = answer - reference
    if diff == 0 and not answer_conditions and not reference_conditions:
        return Comparison(True, "proved", "symbolically identical", evidence={"method": "symbolic"})
    if diff.is_Rational and diff != 0 and answer.is_number and reference.is_number:
        # (a zero difference with conditions, 2 asin(1) against pi, is decided by the points below,
        # which check the typed text's real domain)
        # Two constants that differ, however little: exact arithmetic decides. (x + 1 against x
        # also differs by a rational, but has variables: the points below give its counterexample.)
        example = {"values": {}, "answer": as_float(answer), "reference": as_float(reference)}
        relative = _to_float(abs(diff / reference)) if reference != 0 else math.nan
        if math.isfinite(relative):
            example["relative_difference"] = relative
        # The reason never states the difference: with the answer, it would give the reference away.
        return Comparison(False, "proved", "your answer differs from the correct one by a constant",
                          evidence={"method": "exact"}, counterexample=example,
                          values=(_to_float(answer), _to_float(reference)))
    backend = options.backend()
    try:
        ref = compiled_reference if compiled_reference is not None else Compiled(reference, backend,
                                                                                  reference_conditions)
        ans = Compiled(answer, backend, answer_conditions)
    except Unsupported as error:
        return Comparison(None, "none", f"the checker cannot evaluate {error}")
    if options.symbolic:
        # One point first: most wrong answers differ there, and then expanding would be wasted.
        first = compare_numeric(ref, ans, sampler, _one_point(options), deadline)
        if first.equivalent is False or first.budget_exceeded:
            return first
        if not answer_conditions and not reference_conditions and not (options.fast and _sum_denominator(diff)) \
                and symbolic_zero(diff):
            return Comparison(True, "proved", "symbolically identical", evidence={"method": "symbolic"})
    result = compare_numeric(ref, ans, sampler, options, deadline)
    if result.equivalent is None and not result.budget_exceeded and options.method == "arb" \
            and resonant((reference, answer)):
        # sin(2^60 π x) is a zero every float makes exact, which no precision resolves: off the floats' grid it
        # is not (both compiled afresh: these are not their cached points)
        ref, ans = Compiled(reference, backend, reference_conditions), Compiled(answer, backend, answer_conditions)
        sampler = _OffGridSampler(sampler)
        result = compare_numeric(ref, ans, sampler, options, deadline)
    if result.equivalent is None and not result.budget_exceeded and options.method == "arb":
        # sqrt(x - 1e7), log(x - 1e12), sqrt(1e-9 - x): defined only past the sampled magnitudes (1e-3 .. 1e6), or
        # asin(x - 10) on [9, 11] only, met once by chance; the boundaries of its own arguments say where (both
        # compiled afresh: these are not their cached points)
        fresh = Compiled(reference, backend, reference_conditions)
        points = _where_defined(fresh, (reference, *reference_conditions), sampler, deadline)
        if points:
            ref, ans = fresh, Compiled(answer, backend, answer_conditions)
            sampler = _PointsSampler(sampler, points)
            result = compare_numeric(ref, ans, sampler, options, deadline)
    if result.equivalent and options.method == "arb":
        return (_hidden_difference(diff, answer, reference, ref, ans, sampler, options)
                or _below_the_digits(ref, ans, sampler, options)
                or _off_the_grid(ref, ans, sampler, (reference, answer), options, deadline)
                or _at_landmarks(ref, ans, sampler, (reference, answer), options, deadline)
                or _past_the_branches(ref, ans, sampler, (reference, answer), options, deadline)
                or _in_sign_regions(ref, ans, sampler, (reference, answer), options, deadline)
                or _across_the_kinks(ref, ans, sampler, (reference, answer), options, deadline)
                or _outside_one_domain(ref, ans, sampler, (reference, *reference_conditions),
                                       (answer, *answer_conditions), options, deadline) or result)
    return result


def _hidden_difference(diff: sympy.Expr, answer: sympy.Expr, reference: sympy.Expr, ref: Compiled, ans: Compiled,
                       sampler: Sampler, options: Options) -> Comparison | None:
    """A difference below the judge's digits that sympy's exact arithmetic isolates, or None.

    ``x(1 + 10⁻⁴⁰)`` and ``x`` agree to 40 digits at every point, but their difference, built by
    sympy, is ``x/10⁴⁰``: evaluated by itself its ball excludes zero, a proof that they differ.
    Only a difference in which sympy combined terms is evaluated (otherwise it is ``answer -
    reference`` again, which the points already compared).
    """
    terms = len(sympy.Add.make_args(diff))
    if diff == 0 or terms >= len(sympy.Add.make_args(answer)) + len(sympy.Add.make_args(reference)):
        return None
    point = sampler.point(0)
    prec = int(options.digits * LOG2_10) + 32
    try:
        d, _ = Compiled(diff, options.backend()).at(point, prec)
        if d.contains(0):
            return None
        a, _ = ans.at(point, prec, 0)
        r, _ = ref.at(point, prec, 0)
    except (Undefined, Unresolved, Unsupported):
        return None
    return _differ_below_the_digits(point, a, r, options, "their difference alone is not zero there")


def _differ_below_the_digits(point: dict, a, r, options: Options, how: str) -> Comparison:
    """The verdict where answer ``a`` and reference ``r`` differ at ``point`` by less than the judge's digits."""
    result = PointResult("differ", answer=a, reference=r)
    return Comparison(False, "proved", "your answer and the correct one differ at the point in the counterexample "
                      f"(by less than the judge's digits: {how})", evidence={"method": options.describe(), "points": 1},
                      counterexample=counterexample(point, result), values=(_to_float(a), _to_float(r)))


# Working precision of the one confirming evaluation (about 300 digits): 8 points agreeing to 30
# digits do not tell m g from m g tanh(100), which differ by 3e-87 relative.
CONFIRM_BITS = 1024


def _below_the_digits(ref: Compiled, ans: Compiled, sampler: Sampler, options: Options) -> Comparison | None:
    """A difference below the judge's digits that more precision at one point shows, or None.

    ``m g cos(10⁻²⁰)``, ``m g tanh(100)`` and ``m g`` agree to 30 digits at every point; at
    `CONFIRM_BITS` the ball of their difference at the first point excludes zero, a proof that they
    differ. The reference's value at that precision is cached with its other values.
    """
    point = sampler.point(0)
    try:
        a, _ = ans.at(point, CONFIRM_BITS, 0 if options.fast else None)
        r, _ = ref.at(point, CONFIRM_BITS, 0)
    except (Undefined, Unresolved):
        return None
    if (a - r).contains(0):
        bits = _range_bits((ref.expr, ans.expr), point)
        if bits <= CONFIRM_BITS:
            return None
        try:  # keyed by the precision, which depends only on the texts at the first point
            a, _ = ans.at(point, bits, 0 if options.fast else None)
            r, _ = ref.at(point, bits, 0)
        except (Undefined, Unresolved):
            return None
        if (a - r).contains(0):
            return None
    return _differ_below_the_digits(point, a, r, options, "at more precision they differ there")


# The most bits a confirmation at the expressions' own range is carried to (about 20,000 digits).
MAX_CONFIRM_BITS = 1 << 16
# A constant, point value or integer power past 2^±RANGE_TRIGGER, or a function that saturates, asks for
# the range to be measured; below it, CONFIRM_BITS covers any difference the expression can hide.
RANGE_TRIGGER = 60
# Functions within e^-|u| of a limit for large |u| (tanh 2000 is 1 - 2e-1737), or within 1/|u| (atan 1e400).
_SATURATING = frozenset({"exp", "sinh", "cosh", "tanh", "coth", "sech", "csch"})
_RECIPROCAL = frozenset({"atan", "acot", "asinh", "acosh", "atanh", "acoth", "asec", "acsc", "log", "asin", "acos",
                         "atan2"})


def _range_bits(exprs, point: dict) -> int:
    """The working precision at which a difference that ``exprs`` can hide at ``point`` shows: twice the widest
    magnitude (log2) of a constant, an integer power or a function's argument, and about 3|u| bits for a function
    that nears its limit as e^-|u| (``x (1 + e^-1000)``, ``x tanh(2000)``, ``cos(10^-200)``, ``atan(10^400)`` all
    agree with ``x``, ``1`` or ``π/2`` to 1024 bits). Measured by one 64-bit evaluation, only where a constant,
    a value of the point or an integer power is past 2^±`RANGE_TRIGGER` or a saturating function is present;
    0 otherwise. At most `MAX_CONFIRM_BITS`."""
    measure = any(v and abs(math.log2(abs(v))) > RANGE_TRIGGER for v in point.values()
                  if isinstance(v, float) and math.isfinite(v))
    bits = 0.0
    for expr in exprs:
        constant_bits, asks, _ = _structure(expr)
        bits, measure = max(bits, constant_bits), measure or asks
    if measure:
        bits = max(bits, _measured_range(exprs, point))
    return min(int(bits) + 64, MAX_CONFIRM_BITS) if bits > CONFIRM_BITS - 64 else 0


def _constant_magnitude(node: sympy.Number) -> int:
    """|log2| of a nonzero rational or float constant, to a bit or two; 0 for zero and the infinities."""
    if node.is_Rational:
        return abs(int(node.p).bit_length() - int(node.q).bit_length())
    if node.is_Float:
        _, mantissa, exponent, _ = node._mpf_
        return abs(int(mantissa).bit_length() + exponent) if mantissa else 0
    return 0


def _range_name(node) -> str:
    return type(node).__name__.lower()


class _RangeBackend(ArbBackend):
    """Ball arithmetic that records under ``RANGE`` the bits `_range_bits` asks for: of each function's
    arguments, integer power's base and real power's base and exponent."""

    def function(self, name: str, fs):
        spec = REGISTRY.get(name)
        if spec is None or spec.arb is None:
            raise Unsupported(name)
        evaluate, saturating = spec.arb, name in _SATURATING

        def recorded(env):
            args = [f(env) for f in fs]
            for u in args:
                _note(env, u, saturating)
            return evaluate(*args)

        return recorded

    def pow_int(self, f, n: int):
        power = super().pow_int(lambda env: env[_BASE], n)

        def recorded(env):
            x = f(env)
            _note(env, x, False, abs(n))
            env[_BASE] = x
            return power(env)

        return recorded

    def pow_real(self, f, g):
        def recorded(env):
            x, y = f(env), g(env)
            _note(env, x, False)
            _note(env, y, True)
            env[_BASE], env[_EXPONENT] = x, y
            return power(env)

        power = super().pow_real(lambda env: env[_BASE], lambda env: env[_EXPONENT])
        return recorded


RANGE, _BASE, _EXPONENT = "__range__", "__base__", "__exponent__"


def _note(env: dict, u, saturating: bool, times: int = 1) -> None:
    if not u.is_finite() or u.contains(0):
        return
    magnitude = _log2_mag(u)
    bits = 2 * abs(magnitude) * times
    if saturating and magnitude > 0:
        bits = max(bits, 3 * 2.0 ** min(magnitude, 20))  # e^-|u| is 1.44|u| bits below the limit, twice over
    env[RANGE] = max(env[RANGE], bits)


def _measured_range(exprs, point: dict) -> float:
    backend = _RangeBackend()
    ctx = flint.ctx
    outer = ctx.prec
    ctx.prec = 64
    bits = 0.0
    try:
        for expr in exprs:
            env = {s: flint.arb(v) for s, v in point.items()}
            env[SCALE], env[RANGE] = -math.inf, 0.0
            try:
                compile_expr(expr, backend)(env)
            except (Undefined, Unresolved, Unsupported, ValueError, ZeroDivisionError):
                pass
            bits = max(bits, env.get(RANGE, 0.0))
    finally:
        ctx.prec = outer
    return bits


# A periodic function whose argument has a constant at least 2^GRID_RESONANCE can fit its period to the floats'
# grid: sin(2^60 π x) is 0 at every float x above 2^-7 (x 2^60 is an integer there), so x + sin(2^60 π x)
# agrees with x at every sample point. Such texts are compared once more at a point off that grid.
GRID_RESONANCE = 20
_PERIODIC = (sympy.sin, sympy.cos, sympy.tan, sympy.cot, sympy.sec, sympy.csc)
# The off-grid point: each value times (1 - 3^-24) (or 1 + 3^-24 at a domain's end), an exact fraction with a
# power of 3 below, which no power of 2 times an integer meets.
_OFF_GRID = 3**24


def resonant(exprs) -> bool:
    """Whether a periodic function in ``exprs`` has a constant of at least 2^`GRID_RESONANCE` in its argument."""
    return any(_structure(expr)[2] for expr in exprs)


@lru_cache(maxsize=4096)
def _structure(expr: sympy.Expr) -> tuple[float, bool, bool]:
    """What `_range_bits` and `resonant` read from a text, in one walk (a reference's, once for all its answers):
    twice the widest magnitude (log2) of its constants; whether a constant or integer power past
    2^±`RANGE_TRIGGER` or a saturating or inverse function asks for its range to be measured; whether a periodic
    function's argument has a constant of at least 2^`GRID_RESONANCE`."""
    bits, measure, resonance = 0.0, False, False
    for node in sympy.preorder_traversal(expr):
        if node.is_Number:
            magnitude = _constant_magnitude(node)
            bits = max(bits, 2.0 * magnitude)
            measure = measure or magnitude > RANGE_TRIGGER
        elif node.is_Pow:
            measure = measure or (node.exp.is_Integer and abs(node.exp) > RANGE_TRIGGER)
        elif isinstance(node, sympy.Function):
            measure = measure or _range_name(node) in _SATURATING | _RECIPROCAL
            resonance = resonance or isinstance(node, _PERIODIC) and any(
                abs(c) > 1 and _constant_magnitude(c) >= GRID_RESONANCE for c in node.args[0].atoms(sympy.Number))
    return bits, measure, resonance


def off_grid(point: dict, domains: dict) -> dict:
    """``point`` moved off the floats' grid: each nonzero float ``v`` as the exact fraction ``v (1 - 3^-24)``, or
    ``v (1 + 3^-24)`` where the first leaves its domain (python-flint ``fmpq``, rounded at each evaluation's
    precision)."""
    moved = {}
    for s, v in point.items():
        if not isinstance(v, float) or v == 0 or not math.isfinite(v):
            moved[s] = v
            continue
        exact = Fraction(v)
        w = exact * Fraction(_OFF_GRID - 1, _OFF_GRID)
        if s in domains and not domains[s].contains(float(w)):
            w = exact * Fraction(_OFF_GRID + 1, _OFF_GRID)
        moved[s] = flint.fmpq(w.numerator, w.denominator)
    return moved


class _OffGridSampler:
    """A `Sampler` whose points (ordinary and wide) are moved off the floats' grid (`off_grid`)."""

    def __init__(self, sampler: Sampler):
        self._sampler = sampler

    def __getattr__(self, name):
        return getattr(self._sampler, name)

    def point(self, i: int) -> dict:
        return off_grid(self._sampler.point(i), self._sampler.domains)

    def wide_point(self, i: int) -> dict:
        return off_grid(self._sampler.wide_point(i), self._sampler.domains)


def _off_the_grid(ref: Compiled, ans: Compiled, sampler: Sampler, exprs, options: Options,
                  deadline: float | None) -> Comparison | None:
    """A counterexample at a point off the floats' grid, where a periodic function's large constant may have fit
    its period to every sample point (`resonant`), or None."""
    if not resonant(exprs):
        return None
    point = off_grid(sampler.point(0), sampler.domains)
    result = compare_at(ref, ans, point, ("off the grid",), options, deadline)
    found = _proved_there(ref, ans, sampler, point, result, options, deadline, rounder=False)
    if found is not None and found.counterexample:
        found.counterexample["values"] = {name: float(v) for name, v in found.counterexample["values"].items()}
        found.counterexample["exact_values"] = {s.name: f"{v.p}/{v.q}" if isinstance(v, flint.fmpq) else v
                                                for s, v in point.items()}
        found.reason += (" (a point off the floats' grid: a constant in a periodic function of your answer fits "
                         "its period to every float)")
    return found


# Constants outside the ordinary samples' scale (0.5 .. 3) say where else to look: abs(x - 10)
# and 10 - x agree for every x <= 10.
LANDMARK_SCALE = (0.3, 3.0)
MAX_LANDMARKS = 4


def _at_landmarks(ref: Compiled, ans: Compiled, sampler: Sampler, exprs, options: Options,
                  deadline: float | None) -> Comparison | None:
    """A counterexample at the scale of the expressions' own constants, or None.

    Each unbounded variable (real line or positive) is set to twice and half of each constant
    outside the ordinary samples' scale, with both signs where the domain allows, the other
    variables as at the first sample point.
    """
    values = set()
    stack = list(exprs)
    while stack:
        node = stack.pop()
        if node.is_Rational:
            c = abs(float(node))
            if c and not LANDMARK_SCALE[0] <= c <= LANDMARK_SCALE[1]:
                values.add(c)
        elif node.is_Pow:
            stack.append(node.base)  # an exponent is no scale of the variables
        else:
            stack.extend(node.args)
    if not values:
        return None
    free = [s for s, d in sampler.domains.items()
            if getattr(d, "kind", None) in ("real", "positive", "nonnegative")]
    if not free:
        return None
    base = sampler.point(0)
    for n, c in enumerate(sorted(values)[:MAX_LANDMARKS]):
        for j, v in enumerate((2 * c, c / 2, -2 * c, -c / 2)):
            if v < 0 and any(sampler.domains[s].kind != "real" for s in free):
                continue
            point = {**base, **{s: v for s in free}}
            # keyed by the value itself: the reference's cache is shared by every answer to it
            result = compare_at(ref, ans, point, ("landmark", v), options, deadline)
            found = _proved_there(ref, ans, sampler, point, result, options, deadline, rounder=False)
            if found is not None:
                return found
    return None


_DIFFERENCES = {
    "differ": "your answer and the correct one differ at the point in the counterexample",
    "answer_undefined": "your answer is undefined at a point where the correct one is defined",
    "answer_defined": "your answer is defined at a point of the domain where the correct one is not",
}


def _proved_there(ref: Compiled, ans: Compiled, sampler: Sampler, point: dict, result: PointResult, options: Options,
                  deadline: float | None, rounder: bool = True) -> Comparison | None:
    """The verdict that ``result`` at ``point`` proves (a difference, one side undefined), or None where
    it proves nothing (agreement; a removable point, see `_isolated`). ``rounder``: stated at a rounder
    point showing the same, where one does (`_rounder_witness`)."""
    if result.kind not in _DIFFERENCES:
        return None
    if result.kind != "differ" and _isolated(ref, ans, sampler, point, options, deadline):
        return None
    if rounder:
        point, result = _rounder_witness(ref, ans, sampler, point, result, options, deadline)
    differ = result.kind == "differ"
    return Comparison(False, "proved", _DIFFERENCES[result.kind], evidence={"method": options.describe(), "points": 1},
                      counterexample=counterexample(point, result),
                      values=(_to_float(result.answer), _to_float(result.reference)) if differ else None)


# Points drawn beyond the compared ones to meet the other sign patterns of abs/sign arguments, and
# the most arguments followed (the patterns of more would not be met by so few points anyway).
SIGN_REGION_DRAWS = 200
MAX_KINKS = 8
MAX_PATTERNS = 16


def _kink_arguments(exprs) -> list[sympy.Expr]:
    """The arguments of abs and sign in ``exprs`` that depend on the variables, each once."""
    found: list[sympy.Expr] = []
    for node in _branch_nodes(exprs):
        if isinstance(node, (sympy.Abs, sympy.sign)) and node.args[0].free_symbols and node.args[0] not in found:
            found.append(node.args[0])
    return found[:MAX_KINKS]


# Functions whose formula changes somewhere along their argument (see `_boundaries`).
_BRANCH_FUNCTIONS = frozenset({sympy.Abs, sympy.sign, sympy.log, sympy.coth, sympy.csch, sympy.asin, sympy.acos,
                               sympy.atanh, sympy.acosh, sympy.atan2, sympy.tan, sympy.sec, sympy.cot, sympy.csc})
_last_walk: tuple = ((), [])  # the expressions last walked by `_branch_nodes`, and what it found


def _branch_nodes(exprs) -> list[sympy.Expr]:
    """The nodes of ``exprs`` (in preorder, as sympy.preorder_traversal, without its generator's cost) that are a
    kink or a branch: a function of `_BRANCH_FUNCTIONS`, or a non-integer power of an expression in the variables.
    One walk serves every search after agreement (the last expressions' nodes are remembered)."""
    global _last_walk
    key = tuple(exprs)
    walked, found = _last_walk  # one read: another thread may replace it
    if key and len(walked) == len(key) and all(a is b for a, b in zip(walked, key)):
        return found
    found = []
    for expr in key:
        stack = [expr]
        while stack:
            node = stack.pop()
            args = node.args
            if not args:
                continue
            if node.func in _BRANCH_FUNCTIONS or (node.is_Pow and not args[1].is_Integer and args[0].free_symbols):
                found.append(node)
            stack.extend(reversed(args))
    _last_walk = (key, found)
    return found


def _sign_pattern(kinks: list[Compiled], point: dict) -> tuple | None:
    """The signs of the compiled arguments at ``point`` (0 where a ball straddles zero), or None."""
    signs = []
    for kink in kinks:
        try:
            value, _ = kink.at(point, 64)
        except (Undefined, Unresolved):
            return None
        v = _to_float(value)
        if not math.isfinite(v):
            return None
        signs.append((v > 0) - (v < 0))
    return tuple(signs)


def _in_sign_regions(ref: Compiled, ans: Compiled, sampler: Sampler, exprs, options: Options,
                     deadline: float | None) -> Comparison | None:
    """A counterexample in a sign region of an abs/sign argument the compared points missed, or None.

    ``abs(abs(x) + y)`` and ``abs(x) + y`` agree wherever y > -|x|, three quarters of the plane: the
    few points compared can all lie there. The sampler's points are drawn on, and the two are
    compared at every point whose pattern of signs of the arguments (of both texts) is new.
    """
    arguments = _kink_arguments(exprs)
    if not arguments:
        return None
    try:
        kinks = [Compiled(argument, options.backend()) for argument in arguments]
    except Unsupported:
        return None

    def new_patterns():
        seen: set = set()
        for i in range(options.points + SIGN_REGION_DRAWS):
            point = sampler.point(i)
            pattern = _sign_pattern(kinks, point)
            if pattern is None or pattern in seen:
                continue
            seen.add(pattern)
            if len(seen) > MAX_PATTERNS:
                return
            yield point, i

    return _first_difference(ref, ans, sampler, new_patterns(), options, deadline)


# Points drawn beyond the compared ones to find where an argument that only one text restricts is
# out of its range (a region an eighth of the domain is missed by 64 with odds of 1 in 5000; each
# draw costs a few microseconds), and the most such points compared.
DOMAIN_DRAWS = 64
MAX_DOMAIN_CHECKS = 4


def instance_test(classes: tuple) -> Callable[[Any], bool]:
    """``isinstance(node, classes)``, remembered per type of node.

    isinstance with a sympy function class goes through its metaclass and costs some 150 ns a class: 2 µs a
    node for `_BRANCHES`, most of a walk over an answer. For these classes it depends on the node's type alone
    (none has an ``__instancecheck__`` of its own, as ``exp`` has: E**x is an exp to isinstance).
    """
    if not all(type(c).__instancecheck__ is type.__instancecheck__ for c in classes):
        raise TypeError(f"isinstance with {classes} depends on more than the type")
    memo: dict = {}

    def test(node) -> bool:
        kind = type(node)
        found = memo.get(kind)
        if found is None:
            found = memo[kind] = isinstance(node, classes)
        return found

    return test


_is_log, _is_acosh = instance_test((sympy.log,)), instance_test((sympy.acosh,))
_is_unit_bounded = instance_test((sympy.asin, sympy.acos, sympy.atanh))


def _restricted_arguments(exprs) -> list[sympy.Expr]:
    """What must be nonnegative for ``exprs`` (an expression and its typed conditions) to be real: the u
    of log u (positive), the base of a fractional power (√u), 1 - u² of asin u, acos u and atanh u, u - 1 of
    acosh u; each once, only those in the variables whose sign sympy does not know."""
    found: list[sympy.Expr] = []
    stack = list(exprs)
    while stack:
        node = stack.pop()
        args = node.args
        if not args:
            continue
        stack.extend(args)
        if _is_log(node):
            argument = args[0]
        elif node.is_Pow and not args[1].is_Integer:
            argument = args[0]
        elif _is_unit_bounded(node):
            argument = 1 - args[0] ** 2
        elif _is_acosh(node):
            argument = args[0] - 1
        else:
            continue
        if argument.free_symbols and argument not in found and not argument.is_nonnegative:
            found.append(argument)
    return found


def _outside_one_domain(ref: Compiled, ans: Compiled, sampler: Sampler, reference: tuple, answer: tuple,
                        options: Options, deadline: float | None) -> Comparison | None:
    """A counterexample where an argument that only one of the texts restricts is out of range, or None.

    ``exp(2 log(a + x))`` is ``(a + x)²`` only where a + x > 0: with a > 0 and x on [-2, 3] that is most of
    the plane, and the compared points can all lie in it. The sampler's points are drawn on, each such
    argument evaluated in float64 (cheap), and the texts are compared where one is negative. Only when the
    two texts restrict different arguments (``√(2gl(1 - cos θ))`` in both restricts nothing new).
    """
    ours, theirs = _restricted_arguments(answer), _restricted_arguments(reference)
    one_sided = [u for u in ours if u not in theirs] + [u for u in theirs if u not in ours]
    if not one_sided:
        return None
    try:
        arguments = [Compiled(u, FloatBackend()) for u in one_sided[:MAX_KINKS]]
    except Unsupported:
        return None
    def outside():  # the drawn points where one of the arguments is negative
        for i in range(options.points, options.points + DOMAIN_DRAWS):
            if deadline is not None and time.monotonic() > deadline:
                return
            point = sampler.point(i)
            if any(_negative_at(argument, point) for argument in arguments):
                yield point, i

    return _first_difference(ref, ans, sampler, itertools.islice(outside(), MAX_DOMAIN_CHECKS), options, deadline)


def _negative_at(argument: Compiled, point) -> bool:
    try:
        value, _ = argument.at(point, 53)
    except (Undefined, Unresolved):
        return False
    return value < 0


def _first_difference(ref: Compiled, ans: Compiled, sampler: Sampler, points, options: Options,
                      deadline: float | None) -> Comparison | None:
    """The verdict at the first of ``points`` (pairs of a point and its cache key) where a difference is
    proved (`_proved_there`), or None (also when the budget runs out)."""
    for point, key in points:
        result = compare_at(ref, ans, point, key, options, deadline)
        if result.kind == "budget":
            return None
        found = _proved_there(ref, ans, sampler, point, result, options, deadline)
        if found is not None:
            return found
    return None


# Points compared, in all, where an expression has a branch or a pole and a variable ranges over a
# finite interval: the ordinary first eight reach only two of the interval's avoided bands (points
# 3 and 7; `Sampler`), so √(1 − sin²x) passed for cos x on [0.1, 1.75], and asin(sin x) for x on
# [−1.5, 2], wrong only past π/2 at the far end. Sixteen take every band once (points 3, 7, 11, 15).
BRANCH_POINTS = 16
# Then each such variable just inside each end of its interval (this share of its width from it),
# the others as at the first point: acos(cos x) and |x| differ on [−3.14, 3.15] only past π. Not
# nearer: an end written to four or five digits means its round value (α in [0, 1.5708] is an
# incline up to π/2, where √(1 − sin²α) is cos α, not the 4·10⁻⁶ past it).
END_OFFSET = 1e-3
_BRANCHES = (sympy.asin, sympy.acos, sympy.atan, sympy.acot, sympy.asec, sympy.acsc, sympy.atan2, sympy.Abs,
             sympy.sign, sympy.tan, sympy.cot, sympy.sec, sympy.csc, sympy.log, sympy.floor, sympy.ceiling)


_is_branch = instance_test(_BRANCHES)


def _has_branch(exprs) -> bool:
    """Whether an expression has a function that is one formula on part of its argument's range only (an
    inverse trigonometric function, abs, sign, a root of a variable, a pole, a logarithm)."""
    stack = list(exprs)
    while stack:
        node = stack.pop()
        if _is_branch(node) or (node.is_Pow and not node.exp.is_Integer and node.base.free_symbols):
            return True
        stack.extend(node.args)
    return False


def _past_the_branches(ref: Compiled, ans: Compiled, sampler: Sampler, exprs, options: Options,
                       deadline: float | None) -> Comparison | None:
    """A counterexample among the first `BRANCH_POINTS` points (those past ``options.points``) and at the
    ends of the intervals, where the expressions have a branch and a variable of theirs ranges over a
    finite interval, or None."""
    # The cheap tests first (no banded variable, no branch: most answers stop there); free_symbols walks
    # the whole answer, and sympy does not remember it.
    if not sampler.banded or not _has_branch(exprs):
        return None
    symbols = set().union(*(e.free_symbols for e in exprs))
    if not sampler.banded & symbols:
        return None
    points = [(sampler.point(i), i) for i in range(options.points, BRANCH_POINTS)]
    for symbol in sorted(sampler.banded & symbols, key=str):
        domain = sampler.domains[symbol]
        step = END_OFFSET * (domain.hi - domain.lo)
        points += [({**sampler.point(0), symbol: end}, None) for end in (domain.lo + step, domain.hi - step)]
    return _first_difference(ref, ans, sampler, points, options, deadline)


# -- regions between the points where a kink or a branch changes formula ------------------------------
#
# The points compared lie at a variable's ordinary scale (|v| in 0.5 .. 3, and a few stress points): √((1 +
# cos θ)/2) passed for cos(θ/2) with θ real, |(x − 3)(x − 4)| for (x − 3)(x − 4) with x > 0, and x sign((x −
# 40)(x − 41)) for x on [0, 100], each wrong only between two points no sample came near. Along each variable
# (the others as at the first point) the places where the argument of a kink or branch crosses its boundary,
# or touches it (an extremum), are located, and the two expressions compared once inside each region between
# them and past the outermost: a region where they differ proves them different.

# Where each function changes formula, as the values of its argument (or of cos/sin of it) at the boundary.
_KINK_ZERO = (sympy.Abs, sympy.sign, sympy.log, sympy.coth, sympy.csch)
_KINK_UNIT = (sympy.asin, sympy.acos, sympy.atanh)
# The most kink arguments followed, variables scanned, breakpoints kept along one variable, and points compared.
MAX_BOUNDARIES = 8
MAX_SCANNED = 6
MAX_BREAKS = 24
MAX_REGION_POINTS = 48
# Kink arguments larger than this (in nodes) are not scanned.
BOUNDARY_MAX_NODES = 120
# The scan along an unbounded variable: a linear grid over several periods of the argument's own scale (4π
# times the largest of its constants, their inverses, and the other variables' values, at most `SCAN_REACH`),
# and magnitudes 10⁻³ .. 10⁶ a quarter decade apart.
SCAN_POINTS = 256
SCAN_REACH = 1e4
SCAN_DECADES = (-3.0, 6.0, 0.25)
# Where inside a region it is compared: off its middle, where special values (cos θ = 0 at 3π/2) sit.
REGION_SHARE = (3 - math.sqrt(5)) / 2
_FLOAT = None


def _boundaries(exprs) -> list[tuple[sympy.Expr, tuple]]:
    """The arguments ``u`` at which a kink or branch of ``exprs`` changes formula, each with the values of ``u``
    where it does: 0 for abs, sign, log and a root (a non-integer power); ±1 for asin, acos, atanh; 1 for acosh;
    each argument of atan2 at 0; cos u (tan, sec) or sin u (cot, csc) at 0. An argument whose sign sympy's
    assumptions decide (the root of 2 g h with g, h > 0) is left out: its formula never changes."""
    found: dict = {}

    def add(u, values):
        if not u.free_symbols or node_count(u, BOUNDARY_MAX_NODES) > BOUNDARY_MAX_NODES:
            return
        if values == (0,) and (u.is_positive or u.is_negative):
            return
        found[u] = tuple(sorted(set(found.get(u, ())) | set(values)))

    for node in _branch_nodes(exprs):
        if isinstance(node, _KINK_ZERO):
            add(node.args[0], (0,))
        elif node.is_Pow and not node.exp.is_Integer and node.base.free_symbols:
            add(node.base, (0,))
        elif isinstance(node, _KINK_UNIT):
            add(node.args[0], (-1, 1))
        elif isinstance(node, sympy.acosh):
            add(node.args[0], (1,))
        elif isinstance(node, sympy.atan2):
            add(node.args[0], (0,))
            add(node.args[1], (0,))
        elif isinstance(node, (sympy.tan, sympy.sec)):
            add(sympy.cos(node.args[0]), (0,))
        elif isinstance(node, (sympy.cot, sympy.csc)):
            add(sympy.sin(node.args[0]), (0,))
        if len(found) >= MAX_BOUNDARIES:
            break
    return list(found.items())


def _span(domain) -> tuple[float, float] | None:
    kind = getattr(domain, "kind", None)
    if kind == "interval":
        return float(domain.lo), float(domain.hi)
    if kind in ("positive", "nonnegative"):
        return 0.0, math.inf
    if kind == "real":
        return -math.inf, math.inf
    return None


def _reach(u: sympy.Expr, base: dict) -> float:
    """4π times the scale of ``u``'s constants (and their inverses, a frequency's period) and of the values of
    its other variables, at least 1 and at most `SCAN_REACH`: several periods of a trigonometric argument."""
    scale = 1.0
    stack = [u]
    while stack:
        node = stack.pop()
        if node.is_Number and node != 0 and node.is_finite:
            c = abs(float(node))
            scale = max(scale, c, 1 / c)
        elif node.is_Symbol and isinstance(base.get(node), float) and base[node]:
            c = abs(base[node])
            scale = max(scale, c, 1 / c)
        else:
            stack.extend(node.args)
    return 4 * math.pi * min(scale, SCAN_REACH)


def _scan_grid(lo: float, hi: float, reach: float) -> list[float]:
    """Values along a variable on (lo, hi): linear across the reach (or the interval), and log-spaced magnitudes."""
    a, b = max(lo, -reach), min(hi, reach)
    grid = {a + (b - a) * i / SCAN_POINTS for i in range(SCAN_POINTS + 1)} if b > a else set()
    first, last, step = SCAN_DECADES
    for n in range(int(round((last - first) / step)) + 1):
        m = 10.0 ** (first + n * step)
        grid.update(v for v in (m, -m) if lo < v < hi)
    return sorted(v for v in grid if lo <= v <= hi and math.isfinite(v))


def _float_at(f, env: dict, symbol, t: float) -> float | None:
    env[symbol] = t
    env[SCALE] = -math.inf
    try:
        value = f(env)
    except (Undefined, Unresolved, ValueError, OverflowError, ZeroDivisionError, TypeError):
        return None
    if isinstance(value, complex) or not math.isfinite(value):
        return None
    return value


def _bisect(f, env: dict, symbol, a: float, b: float, fa: float) -> float:
    """A point where ``f`` (of sign ``fa`` at ``a``) changes sign between ``a`` and ``b`` (or stops being defined)."""
    for _ in range(60):
        m = (a + b) / 2
        if not a < m < b or b - a <= 1e-12 * max(1.0, abs(m)):
            break
        fm = _float_at(f, env, symbol, m)
        if fm is not None and (fm > 0) == (fa > 0) and fm != 0:
            a = m
        else:
            b = m
    return (a + b) / 2


def _crossings(values: list, grid: list, f, env: dict, symbol) -> list[float]:
    """Where the grid's values change sign (or definedness), refined by bisection."""
    found = []
    for (t0, v0), (t1, v1) in zip(zip(grid, values), zip(grid[1:], values[1:])):
        if v0 is None and v1 is None:
            continue
        if v0 is None or v1 is None:
            found.append(_bisect(_defined(f), env, symbol, t0, t1, 1.0 if v0 is not None else -1.0))
        elif v0 == 0:
            found.append(t0)
        elif (v0 > 0) != (v1 > 0) and v1 != 0:
            found.append(_bisect(f, env, symbol, t0, t1, v0))
    return found


def _defined(f):
    def indicator(env):
        try:
            f(env)
        except Exception:
            return -1.0
        return 1.0
    return indicator


def _breakpoints(u: sympy.Expr, values: tuple, symbol, base: dict, span: tuple[float, float]) -> list[float]:
    """Where along ``symbol`` (the others as in ``base``) ``u`` crosses or touches one of ``values``: the sign
    changes of ``u - c`` on a grid, and the extrema of ``u`` (the zeros of its derivative), between which ``u``
    is monotonic, so that a narrow dip past a value between two grid points is found too; exactly, for a
    polynomial in ``symbol``."""
    global _FLOAT
    _FLOAT = _FLOAT or FloatBackend()
    try:
        f = compile_expr(u, _FLOAT)
    except Unsupported:
        return []
    lo, hi = span
    grid = _scan_grid(lo, hi, _reach(u, base))
    env = {s: float(v) for s, v in base.items()}
    found = _polynomial_roots(u, values, symbol, base, span)
    try:
        derivative = compile_expr(sympy.diff(u, symbol), _FLOAT)
    except (Unsupported, ValueError, TypeError):
        derivative = None
    if derivative is not None:
        slopes = [_float_at(derivative, env, symbol, t) for t in grid]
        extrema = [t for t in _crossings(slopes, grid, derivative, env, symbol) if lo < t < hi]
        found += extrema
        grid = sorted(set(grid) | set(extrema))
    at = [_float_at(f, env, symbol, t) for t in grid]
    for c in values:
        found += _crossings([None if v is None else v - c for v in at], grid,
                            (lambda e, c=c: f(e) - c), env, symbol)
    return sorted(t for t in found if lo < t < hi and math.isfinite(t))


POLYNOMIAL_MAX_DEGREE = 12


def _polynomial_roots(u, values, symbol, base, span) -> list[float]:
    """The real roots of ``u - c`` and of its derivative, where ``u`` is a polynomial in ``symbol`` of degree 1 to
    `POLYNOMIAL_MAX_DEGREE` (numpy's companion-matrix roots, a double root's tiny imaginary part allowed)."""
    if not u.is_polynomial(symbol):
        return []
    try:
        poly = sympy.Poly(u, symbol)
        if not 1 <= poly.degree() <= POLYNOMIAL_MAX_DEGREE:
            return []
        point = {s: sympy.Float(v) for s, v in base.items() if s != symbol}
        coefficients = [complex(c.xreplace(point).evalf()) for c in poly.all_coeffs()]
    except (sympy.PolynomialError, TypeError, ValueError):
        return []
    if not all(math.isfinite(c.real) and math.isfinite(c.imag) for c in coefficients) or coefficients[0] == 0:
        return []
    roots = []
    derivative = list(np.polyder(np.array(coefficients)))
    for polynomial in [coefficients[:-1] + [coefficients[-1] - c] for c in values] + [derivative]:
        try:
            found = np.roots(np.array(polynomial))
        except (np.linalg.LinAlgError, ValueError):
            continue
        roots += [float(r.real) for r in found if abs(r.imag) <= 1e-6 * max(1.0, abs(r.real))]
    return roots


def _test_values(breaks: list[float], span: tuple[float, float], near: float) -> list[float]:
    """One value inside each region between consecutive breakpoints and past the outermost (the regions at an
    interval's ends narrower than `END_OFFSET` of it left out where that end has decimals: 1.5708 written to a
    few digits means its round value π/2; a whole end, 0 or 1, is exact, and |x - 0.0005| is not x - 0.0005 on
    [0, 1]); of many breakpoints, the `MAX_BREAKS` nearest ``near``."""
    lo, hi = span
    margin = END_OFFSET * (hi - lo) if math.isfinite(hi - lo) else 0.0
    low_margin, high_margin = (0.0 if math.isfinite(end) and end == int(end) else margin for end in (lo, hi))
    kept: list[float] = []
    for b in sorted(breaks):
        if not kept or b - kept[-1] > 1e-9 * max(1.0, abs(b)):
            kept.append(b)
    if len(kept) > MAX_BREAKS:  # those nearest the ordinary values (a periodic argument's near periods)
        kept = sorted(sorted(kept, key=lambda b: abs(b - near))[:MAX_BREAKS])
    values = []
    edges = [lo] + kept + [hi]
    for a, b in zip(edges, edges[1:]):
        if math.isinf(a) and math.isinf(b):
            continue
        if math.isinf(a):
            t = b - max(1.0, abs(b)) * REGION_SHARE
        elif math.isinf(b):
            t = a + max(1.0, abs(a)) * REGION_SHARE
        else:
            if (a == lo and b - a <= low_margin) or (b == hi and b - a <= high_margin):
                continue
            t = a + (b - a) * REGION_SHARE
        if lo + low_margin < t < hi - high_margin:
            values.append(t)
    return values


def kink_region_points(exprs, domains: dict, base: dict, below: dict | None = None,
                       deadline: float | None = None) -> list[dict]:
    """Points that meet every region between the places where a kink or branch of ``exprs`` changes formula,
    along each variable in turn (the others as in ``base``), at most `MAX_REGION_POINTS`; none where there is no
    kink or branch. Only points inside the domains that keep the declared orders (``below``: a < R); those found
    so far once ``deadline`` passes."""
    boundaries = _boundaries(exprs)
    if not boundaries:
        return []
    symbols = sorted({s for u, _ in boundaries for s in u.free_symbols if s in domains and s in base},
                     key=lambda s: s.name)[:MAX_SCANNED]
    points: list[dict] = []
    seen = set()
    for symbol in symbols:
        span = _span(domains[symbol])
        if span is None:
            continue
        breaks: list[float] = []
        for u, values in boundaries:
            if deadline is not None and time.monotonic() > deadline:
                return points[:MAX_REGION_POINTS]
            if symbol in u.free_symbols:
                breaks += _breakpoints(u, values, symbol, base, span)
        for t in _test_values(breaks, span, base[symbol]):
            if (symbol, t) in seen or not domains[symbol].contains(t):
                continue
            seen.add((symbol, t))
            point = {**base, symbol: t}
            if all(point[a] < point[b] for a, b in (below or {}).items() if a in point and b in point):
                points.append(point)
    if len(points) < MAX_REGION_POINTS:
        points += _descended_points(boundaries, domains, base, below or {}, deadline, points)
    return points[:MAX_REGION_POINTS]


# Rounds of the walk along one variable at a time toward a boundary that no single variable reaches, and the
# least share of the distance left that a round must close for the walk to go on (a coupled valley,
# (x - a)² + (y - a)² + (x - y)², closes half of it a round).
DESCENT_ROUNDS = 32
DESCENT_PROGRESS = 0.05


def _descended_points(boundaries, domains: dict, base: dict, below: dict, deadline: float | None,
                      met: list[dict] = ()) -> list[dict]:
    """Points past a boundary that moving one variable from ``base`` never crosses: sign((x - 10⁴)² + (y - 10⁴)²
    - 1) is -1 only within 1 of (10⁴, 10⁴), which both variables must leave the ordinary scale to reach. From
    ``base``, each argument of two or more variables that none of the points ``met`` puts past its boundary is
    taken, one variable at a time, to its value nearest the other side along that variable (on the scan's grid
    and at its extrema there), for up to `DESCENT_ROUNDS` rounds while each round brings it `DESCENT_PROGRESS`
    nearer; the point reached, where it is past the boundary, is returned."""
    global _FLOAT
    _FLOAT = _FLOAT or FloatBackend()
    found: list[dict] = []
    for u, values in boundaries:
        symbols = sorted((s for s in u.free_symbols if s in domains and s in base and _span(domains[s])),
                         key=lambda s: s.name)[:MAX_SCANNED]
        if len(symbols) < 2:
            continue
        try:
            f = compile_expr(u, _FLOAT)
            slopes = {s: compile_expr(sympy.diff(u, s), _FLOAT) for s in symbols}
        except (Unsupported, ValueError, TypeError):
            continue
        grids = {s: _scan_grid(*_span(domains[s]), _reach(u, base)) for s in symbols}
        for c in values:
            start = _float_at(f, {k: float(v) for k, v in base.items()}, symbols[0], float(base[symbols[0]]))
            if start is None or start == c:
                continue
            side = 1.0 if start > c else -1.0
            if any((v := _float_at(f, {k: float(x) for k, x in p.items()}, symbols[0], float(p[symbols[0]])))
                   is not None and side * (v - c) < 0 for p in met):
                continue  # the regions past this boundary are met already
            point = {k: float(v) for k, v in base.items()}
            best_value = side * (start - c)
            for _ in range(DESCENT_ROUNDS):
                before = best_value
                for symbol in symbols:
                    if deadline is not None and time.monotonic() > deadline:
                        return found
                    point[symbol], best_value = _nearest_side(f, slopes[symbol], point, symbol, grids[symbol],
                                                              c, side, domains[symbol], below)
                    if best_value < 0:
                        break
                if best_value < 0:
                    found.append(point)
                    break
                if best_value > before - DESCENT_PROGRESS * before:
                    break  # settled on this side: the walk no longer nears the boundary
    return found


def _nearest_side(f, slope, point: dict, symbol, grid: list[float], c: float, side: float, domain,
                  below: dict) -> tuple[float, float]:
    """The value of ``symbol`` (the others as in ``point``), among ``grid`` and the extrema of ``f`` between its
    values, where ``side * (f - c)`` is least, and that least value (from the present value on)."""
    env = dict(point)
    steep = [_float_at(slope, env, symbol, t) for t in grid]
    here = _float_at(f, env, symbol, point[symbol])
    best, best_value = point[symbol], math.inf if here is None else side * (here - c)
    for t in grid + _crossings(steep, grid, slope, env, symbol):
        trial = {**point, symbol: t}
        if not domain.contains(t) or not all(trial[a] < trial[b] for a, b in below.items()
                                             if a in trial and b in trial):
            continue
        v = _float_at(f, env, symbol, t)
        if v is not None and side * (v - c) < best_value:
            best, best_value = t, side * (v - c)
    return best, best_value


def _across_the_kinks(ref: Compiled, ans: Compiled, sampler: Sampler, exprs, options: Options,
                      deadline: float | None) -> Comparison | None:
    """A counterexample in a region between the boundaries of a kink or branch that the points compared missed
    (`kink_region_points`), or None."""
    points = kink_region_points(exprs, sampler.domains, sampler.point(0), {**sampler.below, **sampler.across},
                                deadline)
    # keyed by the point's values: the reference's cache is shared by every answer to it
    keyed = ((p, ("region", tuple(sorted((s.name, v) for s, v in p.items())))) for p in points)
    return _first_difference(ref, ans, sampler, keyed, options, deadline)


def kink_region_states(exprs, parameters: Sampler, states: Sampler, n_states: int, deadline: float | None = None):
    """For equations: pairs (parameters, states) of `GivenPoints`, one per point of `kink_region_points` (over
    both samplers' variables, from their first joint point), whose states are the ordinary first ``n_states -
    1`` and that point's as the last: a multiple fixed by the first is checked in the region."""
    domains = {**parameters.domains, **states.domains}
    base = states.joint(parameters.point(0), states.point(0))
    below = {**parameters.below, **states.below, **parameters.across, **states.across}
    for point in kink_region_points(exprs, domains, base, below, deadline):
        params = {s: v for s, v in point.items() if s in parameters.domains}
        state = {s: v for s, v in point.items() if s in states.domains}
        yield (GivenPoints(parameters, [params]),
               GivenPoints(states, [states.point(j) for j in range(n_states - 1)] + [state]))


def _sum_denominator(expr: sympy.Expr) -> bool:
    """Whether a sum is raised to a negative power somewhere in ``expr`` (then ``expand`` leaves
    the terms over different denominators and proves nothing: the numeric judge decides)."""
    stack = [expr]
    while stack:
        node = stack.pop()
        if node.is_Pow and node.base.is_Add and node.exp.is_negative:
            return True
        stack.extend(node.args)
    return False


@lru_cache(maxsize=64)
def _one_point(options: Options) -> Options:
    return replace(options, points=1)  # the same few Options every time: build each copy once


def with_points(options: Options, points: int) -> Options:
    """A copy of ``options`` with another number of points."""
    return replace(options, points=points)
