"""``check``: one student answer against one reference, start to finish.

1. Read the reference and the answer with our whitelist parser (``grader.expressions``); the
   reference's preparation (namespace, parse, dimension, sample points, compiled evaluator,
   instructor feedback) is cached, so a file of answers to one question is cheap.
2. Dimensions: an answer that adds a force to a length, or has the wrong dimension, is
   ``not_equivalent`` with a message in words.
3. Equivalence: `grader.answers.equivalence` (expressions) or `grader.answers.equations`.
4. Feedback for wrong answers: `grader.answers.feedback`.

``check`` never raises: any input gives a `Verdict`. It has a cooperative time budget; the
hard limits (a killed process) are `grader.answers.sandbox`'s job.
"""

from __future__ import annotations

import json
import math
import time
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any, Mapping, Sequence

import sympy

from grader.answers.equations import compare_equations, state_symbols, unknown_symbols
from grader.answers.equivalence import Comparison, Compiled, Options, compare_expressions
from grader.answers.evaluate import ArbBackend, Undefined, Unresolved, Unsupported
from grader.answers.feedback import CLOSE, counts_cycles, diagnose
from grader.answers.reference import DETAILS, KINDS
from grader.answers.sampling import Sampler, UnorderedPoint, seed_for
from grader.answers.verdict import Verdict
from grader.expressions.dimensions import Dimension
from grader.expressions import (
    DimensionError,
    ExpressionError,
    Namespace,
    dimension_of,
    parse_expression,
    parse_system,
)

__all__ = ["check", "check_request", "DEFAULT_OPTIONS"]

DEFAULT_OPTIONS = Options()
FEEDBACK_OPTIONS = Options(points=4, symbolic=False, factors=False)
SYSTEM_FEEDBACK_OPTIONS = Options(points=4, symbolic=False)
# Share of the budget the mathematics may use; the rest is for the reply (and, in the sandbox,
# is the margin before the hard kill).
BUDGET_SHARE = 0.8
_UNDEFINED = (sympy.zoo, sympy.nan, sympy.oo, -sympy.oo)
_CANONICAL_JSON = json.JSONEncoder(sort_keys=True)  # what json.dumps(x, sort_keys=True) builds per call
# All singletons, so a node is one of them exactly when it is identical to it.
_SUSPICIOUS_IDS = frozenset(map(id, (*_UNDEFINED, sympy.I)))


class _RequestError(ValueError):
    """The request itself is wrong (not the student's answer): becomes an ``invalid`` verdict."""


@dataclass
class _Reference:
    """Everything about a reference that does not depend on the answer."""

    namespace: Namespace
    kind: str
    exprs: list[sympy.Expr]  # one expression, or the residuals of the equations
    dims: dict
    dimension: Any  # the reference's Dimension, or None when it cannot be trusted
    sampler: Sampler | None = None
    parameters: Sampler | None = None
    states: Sampler | None = None
    instructor: list[tuple[Any, str]] = field(default_factory=list)
    compiled: dict = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)
    conditions: tuple = ()  # the reference's real domain as typed (Parsed.conditions)
    unknowns: tuple = ()  # equations: the accelerations they are solved for (unknown_symbols)
    # Values of reference-side feedback candidates (the reference less a term, ...) at the first
    # sample point, for the one-point screen: every wrong answer to this reference tries the same ones.
    screen: dict = field(default_factory=dict)
    _free_symbols: frozenset | None = None

    def free_symbols(self) -> frozenset:
        """The symbols of the reference's expressions (sympy walks them afresh on every ``free_symbols``)."""
        if self._free_symbols is None:
            self._free_symbols = frozenset().union(*(e.free_symbols for e in self.exprs))
        return self._free_symbols

    def compiled_for(self, options: Options):
        backend = options.backend()
        if backend.name not in self.compiled:
            self.compiled[backend.name] = [Compiled(e, backend, self.conditions) for e in self.exprs]
        return self.compiled[backend.name]


def _namespace(variables: Mapping) -> Namespace:
    if not isinstance(variables, Mapping):
        raise _RequestError("'variables' must be an object {name: {dimension, domain}}")
    for name, spec in variables.items():
        if not isinstance(spec, Mapping):
            raise _RequestError(f"variable {name!r} must be an object {{dimension, domain}}")
    try:
        return Namespace.from_spec(variables)
    except (ValueError, TypeError, KeyError) as error:
        raise _RequestError(f"bad variables: {error}") from None


def _below(variables: Mapping, symbols: Mapping[str, sympy.Symbol], dims: Mapping,
           domains: Mapping) -> dict[sympy.Symbol, sympy.Symbol]:
    """{a: R} for each variable declared ``"below": "R"``: a < R wherever the answers are compared, as
    the scene says (a mass at d < R from a hoop's centre); both variables of one dimension."""
    below = {}
    for name, spec in variables.items():
        other = spec.get("below")
        if other is None:
            continue
        if not isinstance(other, str) or other not in symbols or other == name:
            raise _RequestError(f"variable {name!r}: 'below' must name another variable, got {other!r}")
        if dims[symbols[name]] != dims[symbols[other]]:
            raise _RequestError(f"variable {name!r}: 'below' compares it with {other!r}, of another dimension")
        low, high = _bounds(domains[symbols[name]])[0], _bounds(domains[symbols[other]])[1]
        if not low < high:
            raise _RequestError(f"variable {name!r}: no values of its domain are below those of {other!r}")
        below[symbols[name]] = symbols[other]
    return below


def _bounds(domain) -> tuple[float, float]:
    """The least and greatest values of a variable's domain."""
    if domain.kind == "interval":
        return domain.lo, domain.hi
    return (0.0 if domain.kind in ("positive", "nonnegative") else -math.inf), math.inf


def _read(text: str, namespace: Namespace, kind: str, printed: bool = True):
    """(exprs, parsed-json, conditions) of a text: one expression, or the residuals of its equations,
    and the text's real domain as typed (`grader.expressions.Parsed.conditions`).

    ``printed=False`` skips the text and LaTeX, for texts nobody sees (the reference, the
    instructor's feedback expressions).
    """
    if kind == "expression":
        p = parse_expression(text, namespace, printed=printed)
        return [p.expr], {"text": p.text, "latex": p.latex, "notes": list(p.notes)}, p.conditions
    try:
        equations = parse_system(text, namespace, printed=printed)
    except ExpressionError as error:
        if "needs '='" not in error.message:
            raise
        p = parse_expression(text, namespace, printed=printed)  # an expression alone is read as "... = 0"
        return [p.expr], {"text": f"{p.text} = 0", "latex": f"{p.latex} = 0",
                          "notes": list(p.notes) + ["read as an equation '... = 0'"]}, p.conditions
    notes = [n for eq in equations for n in eq.notes]
    return [eq.residual for eq in equations], {
        "text": "; ".join(eq.text for eq in equations),
        "latex": r" \\ ".join(eq.latex for eq in equations),
        "notes": notes,
    }, tuple(c for eq in equations for c in eq.conditions)


@lru_cache(maxsize=256)
def _prepare(reference: str, kind: str, variables_json: str, state_json: str, feedback_json: str) -> _Reference:
    variables = json.loads(variables_json)
    namespace = _namespace(variables)
    try:
        exprs, _, conditions = _read(reference, namespace, kind, printed=False)
    except ExpressionError as error:
        raise _RequestError(f"the reference does not parse: {error}") from None
    if any(e.has(*_UNDEFINED) for e in exprs):
        raise _RequestError("the reference is undefined (division by zero)")
    dims = namespace.dimensions()
    notes = []
    dimension = None
    try:
        for e in exprs:
            dimension = dimension_of(e, dims)
    except DimensionError as error:
        dimension = None  # never blame the student for the reference's dimensions
        notes.append(f"dimensions not checked: the reference {error}")
    symbols = {v.name: v.symbol for v in namespace.variables}
    domains = {v.symbol: v.domain for v in namespace.variables}
    below = _below(variables, symbols, dims, domains)
    seed = seed_for(reference, kind, variables_json)
    ref = _Reference(namespace, kind, exprs, dims, dimension, notes=notes, conditions=conditions)
    if kind == "expression":
        ref.sampler = Sampler(domains, seed, below=below)
    else:
        state = state_symbols(variables, symbols, json.loads(state_json))
        ref.unknowns = unknown_symbols(variables, symbols, json.loads(state_json))
        ref.parameters = Sampler({s: d for s, d in domains.items() if s not in state}, seed, below=below)
        ref.states = Sampler({s: d for s, d in domains.items() if s in state}, seed + 1, below=below)
    for entry in json.loads(feedback_json):
        try:
            expr_text, message = entry["expr"], entry["message"]
            entry_exprs, _, _ = _read(expr_text, namespace, kind, printed=False)
        except (ExpressionError, KeyError, TypeError) as error:
            ref.notes.append(f"instructor feedback entry skipped: {error}")
            continue
        ref.instructor.append((entry_exprs if kind == "equation" else entry_exprs[0], str(message)))
    return ref


def _contains(expr: sympy.Basic, ids: frozenset) -> bool:
    """Whether a node of ``expr`` is one of the objects whose ``id`` is in ``ids`` (``has`` for
    singletons, without its pattern set-up)."""
    stack = [expr]
    while stack:
        node = stack.pop()
        if id(node) in ids:
            return True
        stack.extend(node.args)
    return False


def _dimension_verdict(ref: _Reference, exprs: list[sympy.Expr], kind: str) -> tuple[str, str] | None:
    """(reason, feedback message) when the answer's dimensions are wrong, else None."""
    if ref.dimension is None:
        return None
    try:
        answer_dims = [dimension_of(e, ref.dims) for e in exprs]
    except DimensionError as error:
        side = "Your equation " if kind == "equation" else "Your answer "
        text = f"{side}{error.message if hasattr(error, 'message') else error}"
        return text, text + "."
    if kind == "equation" or (len(exprs) == 1 and exprs[0] == 0):
        return None  # an equation may be scaled by anything; zero has every dimension
    got = answer_dims[0]
    if got != ref.dimension:
        text = (f"Your answer is {_phrase(got)}, but the answer should be {_phrase(ref.dimension)}.")
        return text, text
    return None


# m·9.81 for m g: "Your answer is a mass" is true, and leaves the student wondering what is wrong with g's value.
G_VALUE_MESSAGE = ("Your answer has a number where the problem's symbol g belongs (its value in m/s²): write g. "
                   "Answers are checked as formulas in the problem's symbols, not as numbers.")
_G = 9.80665
_ACCELERATION = Dimension(0, 1, -2)
_G_MULTIPLES = (1, 2, sympy.Rational(1, 2))  # g, 2g (√(2gh) typed √(19.62 h)) and g/2 (4.9 t²)


def _g_as_its_value(ref: _Reference, exprs: list[sympy.Expr], kind: str) -> bool:
    """Whether the answer, of the wrong dimension, has the right one once a number within 0.5 % of g's value
    (or twice or half of it, or the root of one of these) is read as that multiple of the problem's g (an
    acceleration named g), or its root."""
    g = next((s for s, d in ref.dims.items() if s.name == "g" and d == _ACCELERATION), None)
    if g is None:
        return False
    # k g itself, or its root (√(19.62 h) is read as (3/10)·√218·√h: the number is a product's coefficient)
    forms = [(float(k) * _G, k * g) for k in _G_MULTIPLES] + [(float(k * _G) ** 0.5, sympy.sqrt(k * g))
                                                              for k in _G_MULTIPLES]
    found = []

    def as_g(number: sympy.Expr) -> sympy.Expr | None:
        value = abs(float(number))
        form = next((f for v, f in forms if abs(value / v - 1) < 0.005), None)
        return None if form is None else (form if number > 0 else -form)

    def swapped(e: sympy.Expr) -> sympy.Expr:
        if e.is_number and not e.is_Integer and e.is_real:
            form = as_g(e)
            if form is not None:
                found.append(e)
                return form
            return e
        if e.is_Mul and e.free_symbols:
            coeff, rest = e.as_independent(*e.free_symbols)
            if coeff != 1 and coeff.is_real and (form := as_g(coeff)) is not None:
                found.append(coeff)
                return form * swapped(rest)
        return e.func(*[swapped(a) for a in e.args]) if e.args else e

    try:
        candidates = [swapped(e) for e in exprs]
        if not found:
            return False
        dims = [dimension_of(e, ref.dims) for e in candidates]
    except (DimensionError, TypeError, ValueError, OverflowError):
        return False
    return kind == "equation" or dims[0] == ref.dimension


def _phrase(dim) -> str:
    return "a dimensionless number" if dim.is_dimensionless else dim.describe()


def _filter_values(example: dict | None, symbols: set) -> dict | None:
    if example is None:
        return None
    names = {s.name for s in symbols}
    for key in ("values", "other_state"):
        if key in example:
            example[key] = {k: v for k, v in example[key].items() if k in names}
    return example


def _compare(ref: _Reference, exprs: list[sympy.Expr], options: Options, deadline: float,
             conditions: tuple = ()) -> Comparison:
    compiled = ref.compiled_for(options)
    if ref.kind == "expression":
        return compare_expressions(ref.exprs[0], exprs[0], ref.sampler, options, deadline, compiled[0],
                                   conditions, ref.conditions)
    return compare_equations(ref.exprs, exprs, ref.parameters, ref.states, options, deadline, compiled,
                             conditions, ref.unknowns)


SCREEN_PREC = 64
# Reference-side screen values kept per reference; the candidates are few (terms, small factors),
# the bound only guards against a pathological stream of different factors.
SCREEN_CACHE_SIZE = 256


class _SinCosSwapped(ArbBackend):
    """Ball arithmetic with sin and cos exchanged: compiling an expression with it evaluates the
    expression with every sin written as cos and every cos as sin, without building that expression
    in sympy (which costs far more than the one-point screen it is for)."""

    _SWAP = {"sin": "cos", "cos": "sin"}

    def function(self, name: str, fs):
        return super().function(self._SWAP.get(name, name), fs)


def _screen_value(expr: sympy.Expr, point: dict, cache: dict | None):
    """``expr`` at ``point`` in 64-bit balls, or the exception that stopped it; remembered in ``cache``."""
    if cache is not None and expr in cache:
        return cache[expr]
    try:
        value, _ = Compiled(expr, ArbBackend()).at(point, SCREEN_PREC)
    except (Undefined, Unresolved, Unsupported) as error:
        value = error
    if cache is not None and len(cache) < SCREEN_CACHE_SIZE:
        cache[expr] = value
    return value


# The points a "close" answer must be close at besides the counterexample (ordinary ones: not the
# stress points 3, 7, where variables take extreme scales).
_ORDINARY_POINTS = (0, 1, 2, 4, 5, 6)


def _relative_difference(r: sympy.Expr, a: sympy.Expr, point: dict) -> float:
    """|a − r| at ``point`` relative to the reference's size there, or to its largest term where it cancels
    (a rounded coefficient is close near a zero of the reference too); infinite where either is not a
    number there."""
    try:
        rv, r_scale = Compiled(r, ArbBackend()).at(point, SCREEN_PREC)
        av, _ = Compiled(a, ArbBackend()).at(point, SCREEN_PREC)
        reference, answer = float(rv.mid()), float(av.mid())
    except (Undefined, Unresolved, Unsupported, TypeError, ValueError, OverflowError):
        return math.inf
    size = max(abs(reference), 2.0 ** r_scale if math.isfinite(r_scale) else 0.0)
    return abs(answer - reference) / size if size else math.inf


def _could_be_same(r: sympy.Expr, a: sympy.Expr, point: dict, r_cache: dict | None = None,
                   a_cache: dict | None = None) -> bool:
    """A one-point screen for feedback candidates (most fail it): False only when proved different.

    ``r_cache`` and ``a_cache`` remember values of the two sides at this point between calls.
    """
    ra = _screen_value(r, point, r_cache)
    if isinstance(ra, Exception):
        return True
    aa = _screen_value(a, point, a_cache)
    if isinstance(aa, Exception):
        return True
    return (aa - ra).contains(0)


def _feedback(ref: _Reference, exprs: list[sympy.Expr], comparison: Comparison, deadline: float,
              detail: str) -> list[dict]:
    if ref.kind == "expression":
        answer_values: dict = {}  # the answer itself is the right side of most candidates

        def same(r, a):
            if r == a:  # what compare_expressions says first ("symbolically identical"), and the screen agrees
                return True
            if not _could_be_same(r, a, ref.sampler.point(0), ref.screen, answer_values):
                return False
            return compare_expressions(r, a, ref.sampler, FEEDBACK_OPTIONS, deadline).equivalent is True

        def swap_could_match():
            # _could_be_same(reference, answer with sin and cos swapped), the swap done in the evaluator
            point = ref.sampler.point(0)
            r = _screen_value(ref.exprs[0], point, ref.screen)
            if isinstance(r, Exception):
                return True
            try:
                a, _ = Compiled(exprs[0], _SinCosSwapped()).at(point, SCREEN_PREC)
            except (Undefined, Unresolved, Unsupported):
                return True
            return (a - r).contains(0)

        ratio = None
        if comparison.values is not None:
            a, r = comparison.values
            ratio = a / r if r else None
        rel = (comparison.counterexample or {}).get("relative_difference")
        if rel is not None and rel < CLOSE:
            # Close at the ordinary points too, not only at the counterexample: r0 cosh ωt + (v0/ω) cosh ωt
            # is 6e-6 from r0 cosh ωt + (v0/ω) sinh ωt at ωt = 6, and a third off at t = 0 (a swap, not a
            # rounded number).
            worst = max(_relative_difference(ref.exprs[0], exprs[0], ref.sampler.point(i)) for i in _ORDINARY_POINTS)
            rel = rel if worst < CLOSE else worst  # (the difference stated is the counterexample's)
        return diagnose(ref.exprs[0], exprs[0], same, ref.instructor, ratio, rel, deadline,
                        swap_could_match=swap_could_match, detail=detail, cycles=counts_cycles(ref.dimension))

    def same_equation(r, a, options=FEEDBACK_OPTIONS, unknowns=()):
        r_list = r if isinstance(r, list) else [r]
        a_list = a if isinstance(a, list) else [a]
        return compare_equations(r_list, a_list, ref.parameters, ref.states, options, deadline,
                                 unknowns=unknowns).equivalent is True

    # An instructor's wrong system is recognised in every form the reference itself would be (its
    # unsolved Lagrange form too): such entries are few, unlike the slip candidates below.
    system = (SYSTEM_FEEDBACK_OPTIONS, ref.unknowns) if len(exprs) > 1 else ()
    found = [{"code": "instructor", "message": m} for e, m in ref.instructor if same_equation(e, exprs, *system)][:1]
    if found:
        return found
    bare = _without_acceleration(ref, exprs)
    if len(exprs) != 1 or len(ref.exprs) != 1:
        return bare
    return diagnose(ref.exprs[0], exprs[0], same_equation, (), None, None, deadline, equation=True,
                    detail=detail) or bare


def _without_acceleration(ref: _Reference, exprs: list[sympy.Expr]) -> list[dict]:
    """A note for equations of motion of which some has no acceleration (2 m r ṙ φ̇ = 0, d/dt(m r² φ̇) written
    out and the φ̈ terms cancelled): "not a multiple of the reference" is all the verdict can say, and the student
    is better told why it cannot be one. Only where every reference equation has an acceleration."""
    unknowns = set(ref.unknowns)
    if not unknowns or not all(e.free_symbols & unknowns for e in ref.exprs):
        return []
    bare = [n for n, e in enumerate(exprs, 1) if not e.free_symbols & unknowns]
    if not bare:
        return []
    which = "Your equation has" if len(exprs) == 1 else f"Your equation {', '.join(map(str, bare))} has"
    return [{"code": "no_acceleration", "message": f"{which} no acceleration in it: an equation of motion gives the "
             "accelerations, and one that relates positions and velocities only cannot be one."}]


def check(
    reference: str,
    answer: str,
    variables: Mapping[str, Mapping],
    kind: str = "expression",
    feedback: Sequence[Mapping] | None = None,
    budget_s: float = 2.0,
    state: Sequence[str] | None = None,
    options: Options = DEFAULT_OPTIONS,
    feedback_detail: str = "kind",
    alternatives: Sequence[str] | None = None,
    values: Mapping[str, float] | None = None,
    unit: str = "",
    tolerance: Mapping[str, Any] | None = None,
    dimension: str | None = None,
    implicit: Mapping[str, Any] | None = None,
) -> Verdict:
    """Check a student's answer against a reference answer (or any of its accepted alternatives).

    Parameters
    ----------
    reference : str
        The reference answer, in the same grammar as the student's (an equation, or several
        separated by ``;``, when ``kind="equation"``).
    answer : str
        What the student typed.
    variables : mapping
        ``{name: {"dimension": str, "domain": "positive" | "nonnegative" | "real" | [lo, hi],
        "kind"?: "parameter" | "coordinate" | ...}}``: the names the texts may use.
    kind : {"expression", "equation", "numeric"}
    feedback : list of {"expr", "message"}, optional
        Known wrong answers and what to tell a student who gives one.
    budget_s : float
        Wall-clock budget; when it runs out the verdict says so (``budget_exceeded``).
    state : list of str, optional
        For equations: the variables an equation's factor may not depend on (default: from each
        variable's ``kind``, else from names ending in ``dot``/``ddot``).
    options : Options
        How hard the numeric judge works (the benchmark varies this).
    feedback_detail : {"kind", "full"}
        ``"kind"``: slip messages name the kind of slip and no value that would reveal the
        reference; ``"full"``: they also state the factor or difference (an instructor's opt-in).
    alternatives : list of str, optional
        Other references that are also right (the mirror equilibrium -theta*, the other sign
        convention), in the reference's grammar. An answer matching one is ``equivalent``, and
        ``evidence["matched"]`` says which: 0 for ``reference``, i for the i-th alternative.
    values, unit, tolerance, dimension, implicit
        For ``kind="numeric"`` (`grader.answers.numeric`): the student's parameter values at which
        the reference is evaluated (each in its variable's domain), the answer's unit text (``""``:
        the reference's dimension, in any unit of it; `grader.answers.numeric.asked_unit`),
        ``{relative?, absolute?, sig_figs?}``, the answer's dimension, and for a reference without a
        closed form the root its unknown is at (`grader.expressions.implicit.Implicit` as JSON).

    Returns
    -------
    Verdict

    Examples
    --------
    >>> v = check("m*g*(3*cos(theta) - 2)", "3mg cos θ - 2mg",
    ...           {"m": {"dimension": "mass", "domain": "positive"},
    ...            "g": {"dimension": "acceleration", "domain": "positive"},
    ...            "theta": {"dimension": "angle", "domain": "real"}})
    >>> v.verdict, v.certainty
    ('equivalent', 'proved')
    >>> v = check("m*g/3", "m*g + 1", {"m": {"dimension": "mass", "domain": "positive"},
    ...                                 "g": {"dimension": "acceleration", "domain": "positive"}})
    >>> v.verdict, v.feedback[0]["code"]
    ('not_equivalent', 'dimension')
    """
    started = time.monotonic()
    text = answer if isinstance(answer, str) else ""
    try:
        if kind == "numeric":
            return _numeric(reference, answer, variables, values, unit, tolerance, dimension, feedback, started,
                            alternatives, implicit)
        verdict = _check(reference, answer, variables, kind, feedback, budget_s, state, options, started,
                         feedback_detail)
        _partial_credit(verdict, feedback)
        if alternatives is not None:
            verdict = _alternatives(verdict, reference, alternatives, answer, variables, kind, feedback, budget_s,
                                    state, options, started, feedback_detail)
    except (_RequestError, UnorderedPoint) as error:
        verdict = Verdict.invalid(str(error), text)
    except RecursionError:
        verdict = Verdict.invalid("the answer is nested too deeply", text)
    except MemoryError:
        raise  # the sandbox turns this into a verdict and a fresh process
    except Exception as error:  # a checker bug must not crash the caller; say so plainly
        # Only the type: a library's message may quote the reference.
        verdict = Verdict.invalid(f"internal error while checking ({type(error).__name__})", text)
    verdict.ms = (time.monotonic() - started) * 1000
    return verdict


def _numeric(reference, answer, variables, values, unit, tolerance, dimension, feedback, started,
             alternatives=None, implicit=None) -> Verdict:
    from grader.answers.numeric import NumericRequestError, check_numeric

    text = answer if isinstance(answer, str) else ""
    if not isinstance(reference, str) or not reference.strip():
        verdict = Verdict.invalid("'reference' must be a non-empty string", text)
    elif not isinstance(variables, Mapping) or (values is not None and not isinstance(values, Mapping)):
        verdict = Verdict.invalid("'variables' and 'values' must be objects", text)
    elif feedback is not None and not isinstance(feedback, (list, tuple)):
        verdict = Verdict.invalid("'feedback' must be a list of {expr, message}", text)
    elif implicit is not None and not isinstance(implicit, Mapping):
        verdict = Verdict.invalid("'implicit' must be an object {condition, unknown, interval, root}", text)
    else:
        entries = [f for f in feedback or () if isinstance(f, Mapping)]
        unit = unit if unit is not None else ""
        try:
            verdict = check_numeric(reference, text, variables, values, unit, tolerance, dimension, entries,
                                    implicit)
            # Another accepted value (the mirror equilibrium) counts too; a wrong unit stays wrong.
            others = alternatives if isinstance(alternatives, (list, tuple)) else ()
            if verdict.verdict == "not_equivalent" and verdict.evidence.get("method") == "numeric_value":
                misses = []
                for index, other in enumerate(o for o in others if isinstance(o, str)):
                    try:
                        matched = check_numeric(other, text, variables, values, unit, tolerance, dimension,
                                                implicit=implicit)
                    except NumericRequestError:
                        # (an accepted value that does not exist at these numbers, the hoop's ±acos(g/ω²R)
                        # with ω²R < g: the others still count, and the verdict on the main one stands)
                        continue
                    if matched.verdict == "equivalent":
                        matched.evidence = {**matched.evidence, "matched": index + 1}
                        verdict = matched
                        break
                    misses.append((index + 1, matched))
                else:
                    _nearest_slip(verdict, misses)
        except NumericRequestError as error:
            verdict = Verdict.invalid(str(error), text)
    verdict.ms = (time.monotonic() - started) * 1000
    return verdict


def _partial_credit(verdict: Verdict, feedback) -> None:
    """A wrong answer that matched an instructor's entry with a ``score`` earns that score."""
    if verdict.verdict != "not_equivalent" or not feedback:
        return
    scores = {}
    for entry in feedback:
        score = entry.get("score") if isinstance(entry, Mapping) else None
        if isinstance(score, (int, float)) and not isinstance(score, bool) and 0 <= score <= 1:
            scores[entry.get("message")] = max(float(score), scores.get(entry.get("message"), 0.0))
    for item in verdict.feedback:
        if item.get("code") == "instructor" and item.get("message") in scores:
            item["score"] = scores[item["message"]]
            verdict.score = max(item["score"], verdict.score or 0.0)


def _alternatives(verdict: Verdict, reference, alternatives, answer, variables, kind, feedback, budget_s, state,
                  options, started, detail) -> Verdict:
    """The first accepted reference the answer matches, or the verdict against the main one."""
    if not isinstance(alternatives, (list, tuple)) or not all(isinstance(a, str) for a in alternatives):
        raise _RequestError("'alternatives' must be a list of reference texts")
    if kind == "equation" and "=" in reference:
        # A student's bare expression is read as "... = 0"; an instructor's bare alternative to an equation is
        # most likely its right-hand side ("g*sin(theta)" for "thetaddot = g*sin(theta)"), and "= 0" would
        # make a wrong reference of it.
        for index, alternative in enumerate(alternatives, 2):
            if "=" not in alternative:
                raise _RequestError(f"accepted answer {index} ({alternative[:60]!r}) is not an equation: write it "
                                    "whole, with its '=', as the reference is written")
    if verdict.verdict == "not_equivalent":
        misses = []
        for index, alternative in enumerate(alternatives, 1):
            other = _check(alternative, answer, variables, kind, feedback, budget_s, state, options, started,
                           detail)
            if other.verdict == "equivalent":
                other.evidence = {**other.evidence, "matched": index}
                other.reason = f"{other.reason} (matches accepted answer {index + 1} of {len(alternatives) + 1})"
                return other
            misses.append((index, other))
        _nearest_slip(verdict, misses)
    if verdict.verdict == "equivalent":
        verdict.evidence = {**verdict.evidence, "matched": 0}
    return verdict


# Feedback codes that name a slip against one reference (a sign, a factor, a term, sin for cos, a power of
# ten): each is true of the answer compared with that reference only.
_SLIP_CODES = frozenset({"sign", "factor", "two_pi", "magnitude", "sin_cos", "missing_term", "term_sign", "extra_term", "close",
                         "power_of_ten"})


def _says_sign(item: Mapping) -> bool:
    """Whether a slip message tells the student their sign is wrong ("check the sign", a negative factor)."""
    return item["code"] == "sign" or (item["code"] in ("factor", "power_of_ten") and "sign" in item["message"])


def _nearest_slip(verdict: Verdict, misses: Sequence[tuple[int, Verdict]]) -> None:
    """A wrong answer's slip is named against the accepted answer it is nearest to, not the first one only.

    With the other sign convention accepted (a reaction force's ``alternatives = ["-N"]``), "check the
    sign" against the main reference is false: the student's sign is an accepted one. So when the main
    reference's feedback is only slips and speaks of the sign, or names no slip at all, the first accepted
    answer whose diagnosis names a slip without the sign gives the feedback (``evidence["feedback_from"]``
    says which, 1 for the first alternative); failing that, when the main one names nothing, the first
    alternative's slip that does. An instructor's message or a dimension stays as it is.
    """
    main = verdict.feedback
    if any(item.get("code") not in _SLIP_CODES for item in main):
        return
    if main and not any(_says_sign(item) for item in main):
        return
    candidates = [(index, other) for index, other in misses if other.verdict == "not_equivalent" and other.feedback
                  and all(item.get("code") in _SLIP_CODES for item in other.feedback)]
    chosen = next(((i, o) for i, o in candidates if not any(_says_sign(item) for item in o.feedback)), None)
    if chosen is None and not main and candidates:
        chosen = candidates[0]
    if chosen is not None:
        verdict.feedback = list(chosen[1].feedback)
        verdict.evidence = {**verdict.evidence, "feedback_from": chosen[0]}


def _check(reference, answer, variables, kind, feedback, budget_s, state, options, started, detail) -> Verdict:
    if not isinstance(reference, str) or not reference.strip():
        raise _RequestError("'reference' must be a non-empty string")
    if not isinstance(answer, str):
        raise _RequestError("'answer' must be a string")
    if kind not in KINDS:
        raise _RequestError(f"'kind' must be one of {', '.join(KINDS)}")
    if state is not None and (not isinstance(state, (list, tuple)) or not all(isinstance(s, str) for s in state)):
        raise _RequestError("'state' must be a list of variable names")
    if feedback is not None and not isinstance(feedback, (list, tuple)):
        raise _RequestError("'feedback' must be a list of {expr, message}")
    if detail not in DETAILS:
        raise _RequestError(f"'feedback_detail' must be one of {', '.join(DETAILS)}")
    try:
        budget = float(budget_s)
    except (TypeError, ValueError):
        raise _RequestError("'budget_s' must be a number") from None
    deadline = started + max(budget, 0.01) * BUDGET_SHARE
    try:
        key = (
            _CANONICAL_JSON.encode(variables),
            json.dumps(sorted(state)) if state else "[]",  # "[]" is what json.dumps([]) gives
            _CANONICAL_JSON.encode([dict(e) if isinstance(e, Mapping) else e for e in feedback]) if feedback else "[]",
        )
    except (TypeError, ValueError):
        raise _RequestError("'variables' and 'feedback' must be JSON data") from None
    ref = _prepare(reference, kind, *key)

    try:
        exprs, parsed, conditions = _read(answer, ref.namespace, kind)
    except ExpressionError as error:
        evidence = {"error": {"code": error.code, "position": error.position, "hint": error.hint}}
        return Verdict("invalid", "none", str(error), parsed={"text": answer, "latex": "", "notes": []},
                       evidence=evidence)
    except OverflowError:
        # sympy, simplifying while the text is read, tests a huge exact number for a perfect power in floats:
        # sqrt(cos(atan(1e-200))) is (1 + 10^-400)^(-1/4)
        return Verdict("invalid", "none", "a number in your answer is too large or too small to work with exactly; "
                       "write it with fewer digits or a smaller exponent",
                       parsed={"text": answer, "latex": "", "notes": []},
                       evidence={"error": {"code": "too_large", "position": None, "hint": None}})
    # One quick walk over the answer for both checks below; it almost never finds anything.
    suspicious = any(_contains(e, _SUSPICIOUS_IDS) for e in exprs)
    if suspicious and any(e.has(*_UNDEFINED) for e in exprs):
        return Verdict("invalid", "none", "your answer is undefined (it divides by zero)", parsed=parsed)
    parsed["notes"] = parsed["notes"] + ref.notes
    if suspicious and any(e.has(sympy.I) for e in exprs):
        return Verdict("not_equivalent", "proved", "your answer is not a real number (it contains the square "
                       "root or logarithm of a negative number)", parsed=parsed, evidence={"method": "exact"},
                       feedback=[{"code": "not_real", "message": "Your answer is not a real number: check "
                                  "square roots and logarithms of negative quantities."}])

    wrong_dimension = _dimension_verdict(ref, exprs, kind)
    if wrong_dimension is not None:
        reason, message = wrong_dimension
        items = [{"code": "dimension", "message": message}]
        if _g_as_its_value(ref, exprs, kind):
            items.append({"code": "g_value", "message": G_VALUE_MESSAGE})
        return Verdict("not_equivalent", "proved", reason, parsed=parsed, feedback=items,
                       evidence={"method": "dimensions"})

    try:
        comparison = _compare(ref, exprs, options, deadline, conditions)
    except Unsupported as error:
        return Verdict("invalid", "none", f"the checker cannot evaluate {error}", parsed=parsed)
    example = None
    if comparison.counterexample is not None:  # the symbols are only needed to trim its values
        symbols = ref.free_symbols() | set().union(*(e.free_symbols for e in exprs))
        example = _filter_values(comparison.counterexample, symbols)
    if comparison.equivalent is None:
        reason = comparison.reason
        if comparison.budget_exceeded:
            reason = f"budget exceeded: {reason}"
        return Verdict("invalid", "none", reason, parsed=parsed, evidence=comparison.evidence,
                       budget_exceeded=comparison.budget_exceeded)
    if comparison.equivalent:
        return Verdict("equivalent", comparison.certainty, comparison.reason, parsed=parsed,
                       evidence=comparison.evidence)
    items = _feedback(ref, exprs, comparison, deadline, detail)
    return Verdict("not_equivalent", comparison.certainty, comparison.reason, parsed=parsed,
                   counterexample=example, feedback=items, evidence=comparison.evidence)


def check_request(request: Any) -> dict:
    """`check` for one decoded JSON request; returns the verdict's JSON (never raises).

    The request is ``{"reference", "answer", "variables", "kind"?, "feedback"?, "state"?,
    "budget_s"?, "feedback_detail"?, "alternatives"?}``, and for ``kind="numeric"`` also
    ``"values"``, ``"unit"``, ``"tolerance"``, ``"dimension"``, ``"implicit"``?, as read by
    ``grader check --jsonl`` and sent by the grading worker.

    Examples
    --------
    >>> check_request({"reference": "m*g", "answer": "g m",
    ...                "variables": {"m": {"dimension": "mass", "domain": "positive"},
    ...                              "g": {"dimension": "acceleration", "domain": "positive"}}})["verdict"]
    'equivalent'
    >>> check_request("not an object")["verdict"]
    'invalid'
    """
    started = time.monotonic()
    if not isinstance(request, Mapping):
        verdict = Verdict.invalid("malformed request: expected a JSON object")
    else:
        missing = [k for k in ("reference", "answer", "variables") if k not in request]
        if missing:
            verdict = Verdict.invalid(f"malformed request: missing {', '.join(missing)}",
                                      request.get("answer") if isinstance(request.get("answer"), str) else "")
        else:
            verdict = check(
                request["reference"],
                request["answer"],
                request["variables"],
                kind=request.get("kind", "expression"),
                feedback=request.get("feedback"),
                budget_s=request.get("budget_s", 2.0),
                state=request.get("state"),
                feedback_detail=request.get("feedback_detail", "kind"),
                alternatives=request.get("alternatives"),
                values=request.get("values"),
                unit=request.get("unit", ""),
                tolerance=request.get("tolerance"),
                dimension=request.get("dimension"),
                implicit=request.get("implicit"),
            )
    verdict.ms = (time.monotonic() - started) * 1000
    return verdict.to_json()
