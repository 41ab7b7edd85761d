"""Simplify an engine result into the form a person would write.

sympy's ``simplify`` returns *a* short form, not always the one on a blackboard: it may leave
``3*g*m*cos(theta) - 2*g*m`` where a physicist writes ``g*m*(3*cos(theta) - 2)``, or turn
``sin(alpha)*cos(alpha)`` into ``sin(2*alpha)/2``. We try a bounded set of rewritings and keep the
one that reads shortest (:func:`_weight`): fewest operations (``count_ops``), a sine of a multiple
angle the input did not have counting one operation more (so ``sin(2x)/2`` replaces
``sin(x)*cos(x)`` only where it is strictly shorter, as in ``2*sin(x)*cos(x)``), a cosine of one
four more (``sin(x)**2`` stays), a negative exponent in print three more, ties broken by printed
length.

The rewritings are sympy's own (``cancel``, ``factor_terms``, ``factor``, ``simplify``, ``trigsimp``)
and six of ours, each applied in turn to the three shortest candidates and kept where it does not
lengthen them: tidier radicands (:func:`tidy_radicands`: expanded, combined or factored, a perfect
square let out where the symbols' signs allow), a denominator in sin² rather than cos²
(:func:`readable_denominator`), each small sum in whichever square is shorter, sums grouped over
a common factor (:func:`grouped`), a denominator spread over the sum it divides
(:func:`spread_denominator`), products of sine and cosine of one argument contracted to the
double angle (:func:`contract_double_angles`, hyperbolic too); then common factors out of every
sum (``factor_terms``). A candidate replaces the input only if it has the input's value
(:func:`_equal`: a numeric check at 30 digits, and a symbolic one where that is cheap).

Two rules more. An expression proved identically zero (:func:`identically_zero`: never nonzero in
ball arithmetic at a few points of the declared domains, then 0 symbolically) is ``0``; one only
numerically zero keeps its form. Half angles are candidates too: sines and cosines of φ and φ/2
written in φ/2 alone (:func:`in_single_angles`), and roots of p(1 ∓ cos x) as √(2p) sin(x/2)
(√(2p) cos(x/2)), with the sign the declared domains (:func:`declared_domains`) give the half
angle, or bars where they give none (:func:`half_angles`).

Examples
--------
>>> import sympy
>>> g, m, theta = sympy.symbols("g m theta", positive=True)
>>> human_form(3*g*m*sympy.cos(theta) - 2*g*m)
g*m*(3*cos(theta) - 2)
>>> quick_form((g*m - g*m*sympy.cos(theta)**2) / (1 - sympy.cos(theta)**2))
g*m
>>> m1, m2, w, t = sympy.symbols("m1 m2 omega t", positive=True)
>>> human_form(g*m1*sympy.cos(theta) + g*m2*sympy.cos(theta) + m1*w**2 + m2*w**2 + m2*g)
g*m2 + (m1 + m2)*(g*cos(theta) + omega**2)
>>> human_form(2*m1*w**2*sympy.sinh(w*t)*sympy.cosh(w*t))
m1*omega**2*sinh(2*omega*t)
"""

from __future__ import annotations

import cmath
import contextlib
import contextvars
import functools
import math
import time

import sympy
from sympy.core.mul import _keep_coeff

__all__ = ["contract_double_angles", "declared_domains", "half_angles", "identically_zero", "in_single_angles", "factored_sums", "gathered_roots", "grouped", "human_form", "inverse_hyperbolic", "pythagorean_roots", "joined_roots",
           "pythagorean_pairs", "quick_form", "readable_denominator", "seen_nonzero", "signs_in_front", "spread_denominator", "tidy_radicands", "tidy_trig"]

_TRIG = (sympy.sin, sympy.cos, sympy.tan, sympy.cot, sympy.sec, sympy.csc)
_HYPERBOLIC = (sympy.sinh, sympy.cosh, sympy.tanh, sympy.coth, sympy.sech, sympy.csch)


def _multiple_angles(expr: sympy.Expr) -> tuple[int, int]:
    """How many sin/sinh calls, and how many other trig or hyperbolic calls, have an argument like
    2*alpha or 2*theta1 - 2*theta2."""
    sines = others = 0
    for f in expr.atoms(*_TRIG, *_HYPERBOLIC):
        coefficients = [term.as_coeff_Mul()[0] for term in sympy.Add.make_args(f.args[0])]
        if any(abs(c) != 1 for c in coefficients if c.is_Rational):
            if isinstance(f, (sympy.sin, sympy.sinh)):
                sines += 1
            else:
                others += 1
    return sines, others


@functools.lru_cache(maxsize=4096)  # candidates meet again across rewritings; printing them is the cost
def _weight(expr: sympy.Expr, allowed_multiples: tuple[int, int], sine_cost: int = 4) -> tuple[int, int]:
    """What a reader pays: operations, multiple angles the input did not have, negative exponents.

    A new multiple angle costs 4 operations more: a physicist writes M + m sin²α, not
    M + m (1 − cos 2α)/2. For an answer (:func:`human_form`) a new sine (or sinh) of a multiple
    angle costs 1: it stands for a product sin x cos x, and wins where it saves an operation, in
    ``2 sin x cos x`` (2 operations more than ``sin 2x``), not in ``sin x cos x`` (as many as
    ``sin(2x)/2``). The tidy-ups of intermediate results keep 4 for it too: their entries are
    reduced further (:mod:`grader.mechanics.reduction`), in single angles.
    """
    sines, others = _multiple_angles(expr)
    extra_sines, extra_others = max(0, sines - allowed_multiples[0]), max(0, others - allowed_multiples[1])
    printed = str(expr)
    negative = 3 if "**(-" in printed else 0  # x**(-3/2): a physicist writes 1/x**(3/2)
    return sympy.count_ops(expr, visual=False) + sine_cost * extra_sines + 4 * extra_others + negative, len(printed)


# Operations past which no readable form is looked for (Cardano's root of a cubic, 459 of them: no
# rewriting makes it readable, and trying spent seconds of a derivation).
TIDY_MAX_OPS = 300


def forget_forms() -> None:
    """Empty the memory of readable forms (:func:`human_form` and its parts), as in a fresh worker.

    A benchmark that derives a scene again must not find the first derivation's forms remembered.
    """
    for remembered in (_remembered_form, _simplified_forms, _tidy_root, _weight, _group, _common_factors, _over,
                       readable_denominator, tidy_trig):
        remembered.cache_clear()


def human_form(expr: sympy.Expr, seconds: float = 0.3) -> sympy.Expr:
    """The most readable of a few equivalent rewritings of ``expr`` (see the module example).

    Remembered per expression: a derivation asks for the same form more than once (an answer and
    the special value built on it), and each asking costs up to the whole budget.

    Cheap rewritings always run; the costly ones (``simplify``, factoring) run under a budget of
    ``seconds`` of CPU time and only on expressions of moderate size, so that tidying never
    dominates a derivation: their result is kept if they finish, skipped if not. Our own
    rewritings (:func:`_rewritten`) run under half that budget. The shortest candidate that has
    the value of ``expr`` (:func:`_equal`) is returned; ``expr`` itself if none has.
    """
    expr = sympy.sympify(expr, strict=True)  # an expression or a number, never text
    if expr.is_Atom:
        return expr
    if sympy.count_ops(expr) > TIDY_MAX_OPS and _nested_roots(expr):
        # Cardano's root of a cubic: no rewriting makes it readable, and the first step, an unbudgeted
        # cancel, spent 10 s a call where a bead's azimuthal rate was taken at the turning point of a
        # magnetic bowl (a cubic in cos θ): the derivation ran out of its 60 s.
        return expr
    bounds, order = _bounds_of(expr.free_symbols), _order_of(expr.free_symbols)
    form = _remembered_form(expr, seconds, bounds, order)
    if not form.has(sympy.Abs):
        return form
    # Again at the end: a rewriting may bring a factor of known sign into the bars (|√(1 − cos φ₀)|
    # as √2 |sin(φ₀/2)|), and what leaves them is tidied with the rest (2|√(1 − cos²θ₀)|/(7 cos θ₀)
    # is 2 sin θ₀/(7 cos θ₀), and that is 2 tan θ₀/7).
    signed = signed_abs(form, bounds, order)
    return signed if signed == form or signed.has(sympy.Abs) else _remembered_form(signed, seconds, bounds, order)


def _nested_roots(expr: sympy.Expr) -> bool:
    """Whether a root (not a whole power) of ``expr`` has another root inside it, as Cardano's ∛(q + √Δ) has.

    >>> x = sympy.Symbol("x", positive=True)
    >>> _nested_roots(sympy.cbrt(x + sympy.sqrt(x**3 + 1))), _nested_roots(sympy.sqrt(x) + sympy.cbrt(x + 1))
    (True, False)
    """
    roots = [p for p in expr.atoms(sympy.Pow) if p.exp.is_Rational and not p.exp.is_Integer]
    return any(inner != root and root.base.has(inner) for root in roots for inner in roots)


@functools.lru_cache(maxsize=512)
def _remembered_form(expr: sympy.Expr, seconds: float, bounds: tuple = (), order: tuple = ()) -> sympy.Expr:
    from grader.mechanics.budget import attempt

    if expr.has(sympy.Abs):
        expr = signed_abs(expr, bounds, order)
    if expr.has(sympy.atan, sympy.asin, sympy.acos):
        expr = inverses_undone(expr, bounds)
    allowed = _multiple_angles(expr)
    cancelled = sympy.cancel(expr)
    if cancelled == 0 or identically_zero(expr, bounds, seconds):
        return sympy.S.Zero
    candidates = [expr, cancelled, sympy.factor_terms(cancelled)]
    if _mixed_angles(expr):
        attempt(lambda: candidates.append(in_single_angles(expr)), seconds / 2, fallback=lambda: None)
    numerator, denominator = sympy.fraction(cancelled)
    if cancelled.has(*_TRIG):
        candidates.append(sympy.factor_terms(tidy_trig(numerator)) / readable_denominator(denominator))

    # simplify() rarely beats the cheap forms on a short expression, and costs the most there.
    if 12 < min(sympy.count_ops(c) for c in candidates) and sympy.count_ops(cancelled) < 120:
        # Half the budget: over the 75 scenes of the tests, simplify and its variants gave the form
        # kept 29 times in 426, once after 0.15 s; past that they mostly ran out (0.3 s for nothing
        # on each of a hoop's four forces).
        candidates.extend(_simplified_forms(cancelled, seconds / 2))
    if expr.has(sympy.Pow):
        candidates = list(dict.fromkeys(candidates))  # simplify often returns a cheap form again
        candidates.extend([gathered_roots(c) for c in candidates])
    if expr.has(sympy.log):
        candidates.append(inverse_hyperbolic(expr))
    if expr.has(sympy.sin) and expr.has(sympy.cos):
        # sin x/cos x as tan x: the least friction coefficient (2/7) tan θ₀, not 2 sin θ₀/(7 cos θ₀)
        from sympy.simplify.fu import TR2i

        candidates.extend([TR2i(c) for c in candidates[:3]])
    if expr.has(sympy.cos) and any(p.exp.is_Rational and p.exp.q == 2 for p in expr.atoms(sympy.Pow)):
        halves = dict.fromkeys(half_angles(c, bounds) for c in candidates)
        candidates.extend(sympy.factor_terms(h) for h in halves if h not in candidates)

    weights: dict = {}

    def weight(e):
        if e not in weights:
            weights[e] = _weight(e, allowed, sine_cost=1)
        return weights[e]

    candidates = sorted(dict.fromkeys(signs_in_front(c) for c in candidates), key=weight)
    if sympy.count_ops(candidates[0]) <= 4:
        candidates = candidates[:1]  # g*m*sin(alpha)/3: nothing left to shorten
    # The few shortest candidates through our rewritings; a partial pass (the budget ran out)
    # keeps what it found.
    rewritten = []
    # The shortest always, within the whole budget: cut at half of it, a long equation (a pendulum
    # hung from a ring on a parabola) printed in 113 operations or in 57 as the machine was busy.
    # The others in what is left of the half.
    started = time.process_time()
    attempt(lambda: rewritten.append(_rewritten(candidates[0], weight)), seconds, fallback=lambda: None)
    left = seconds / 2 - (time.process_time() - started)
    if rewritten and left > 0:
        attempt(lambda: rewritten.extend(_rewritten(c, weight) for c in candidates[1:_REWRITTEN]), left,
                fallback=lambda: None)
    # Never longer than the input, whatever the penalties: a form with a negative exponent in
    # print is not replaced by one with more operations.
    limit = sympy.count_ops(expr)
    for candidate in sorted(dict.fromkeys(candidates + rewritten), key=weight):
        if candidate == expr or (sympy.count_ops(candidate) <= limit and _equal(candidate, expr)):
            return _positive_sums(candidate, bounds, order, weight)
    return _positive_sums(expr, bounds, order, weight)


def _positive_sums(expr: sympy.Expr, bounds: tuple, order: tuple, weight) -> sympy.Expr:
    """``expr`` with the sums it multiplies or divides by that are ≤ 0 on the declared domains written
    negated, where that reads no longer: g m/(4 − 3 sin²θ₀), not −g m/(3 sin²θ₀ − 4). Exact: only signs move.

    >>> g, m = sympy.symbols("g m", positive=True)
    >>> th0 = sympy.Symbol("theta0", real=True)
    >>> e = -g*m/(3*sympy.sin(th0)**2 - 4)
    >>> size = lambda x: (sympy.count_ops(x), len(str(x)))
    >>> _positive_sums(e, (), (), size)
    g*m/(4 - 3*sin(theta0)**2)
    >>> _positive_sums(g*(1 - 2*m*sympy.cos(th0))/(3*sympy.sin(th0)**2 - 4), (), (), size)
    g*(2*m*cos(theta0) - 1)/(4 - 3*sin(theta0)**2)
    >>> _positive_sums(m*(1 - 2*g)/(2*g*(3*sympy.sin(th0)**2 - 4)), (), (), size)
    m*(2*g - 1)/(2*g*(4 - 3*sin(theta0)**2))
    """
    numerator, denominator = sympy.fraction(expr)
    forms = []
    for content in (False, True):  # 8 − 6 sin²θ as it is, or as 2(4 − 3 sin²θ)
        forms += _negated_where_negative(numerator, denominator, bounds, order, content)
    if not forms:
        return expr
    flipped = min(forms, key=weight)
    return flipped if weight(flipped) <= weight(expr) else expr


def _negated_where_negative(numerator: sympy.Expr, denominator: sympy.Expr, bounds: tuple, order: tuple,
                            content: bool) -> list[sympy.Expr]:
    """numerator/denominator with each sum factor ≤ 0 on the domains negated, the sign in front or in a
    sum of the numerator; ``content``: with the numbers of each negated sum taken out in front. [] if none."""
    # Numbers apart from the factors, multiplied in front at the end: sympy multiplies a number into a
    # sum it stands alone with, and 2(4 − 3 sin²θ) would print as 8 − 6 sin²θ.
    coefficient, changed, parts = sympy.S.One, False, []
    for which, part in enumerate((numerator, denominator)):
        factors = []
        for factor in sympy.Mul.make_args(part):
            if factor.is_Number:
                coefficient = coefficient * factor if which == 0 else coefficient / factor
                continue
            base, exp = factor.as_base_exp()
            if base.is_Add and exp.is_Integer and _factor_sign(base, bounds, order) == -1:
                number, base = sympy.factor_terms(-base).as_coeff_Mul() if content else (sympy.S.One, -base)
                number = number ** int(exp if which == 0 else -exp)
                coefficient, changed = coefficient * number * (-1) ** int(exp), True
            factors.append(base ** exp if which == 0 else base ** -exp)
        parts.append(factors)
    if not changed:
        return []
    factors = parts[0] + parts[1]
    forms = [sympy.Mul(coefficient, *factors)]
    if coefficient < 0:  # the minus into a sum of the numerator instead: 3(l θ̇² sin θ − 2g)/(l(4 − 3 sin²θ))
        forms += [sympy.Mul(-coefficient, *factors[:i], -f, *factors[i + 1:])
                  for i, f in enumerate(parts[0]) if f.is_Add]
    return forms


_REWRITTEN = 3  # how many of the shortest candidates go through our rewritings
_SIGNS = ("positive", "negative", "nonnegative", "nonpositive", "nonzero", "real")


@functools.lru_cache(maxsize=512)
def _simplified_forms(cancelled: sympy.Expr, seconds: float) -> tuple[sympy.Expr, ...]:
    """The costly candidates of :func:`human_form`: ``simplify`` and factored and trigonometric
    variants of its result, as many as ``seconds`` of CPU time allow.

    Remembered per cancelled form: expressions that differ only in how they are written (a motion
    in time as solved, and the readable form of it that an answer then reads) cancel to the same
    one, and running out of the budget on it once is enough.
    """
    from grader.mechanics.budget import attempt

    found: list = []

    # simplify's own trigonometric pass (futrig) is most of its cost on an expression in sines and
    # cosines, several times more with hyperbolic functions as well (it factors over the Gaussian
    # rationals), and what it finds in mechanics our rewritings find too: the Pythagorean identity
    # either way (below, and :func:`_squares_in_sums`), sums of products into a sine or cosine of a
    # sum (:func:`tidy_trig`), double angles (:func:`contract_double_angles`). So simplify sees each
    # sine, cosine, ... as a symbol (with its sign, where known) and does the rest: cancelling,
    # common factors, powers, exponentials; trigsimp runs on its own only where there are multiple
    # angles to expand.
    masks = {f: sympy.Dummy(**{a: True for a in _SIGNS if getattr(f, f"is_{a}")})
             for f in sorted(cancelled.atoms(*_TRIG, *_HYPERBOLIC), key=sympy.default_sort_key)}
    unmask = {d: f for f, d in masks.items()}

    def costly():
        simplified = sympy.simplify(cancelled.xreplace(masks)).xreplace(unmask)
        found.extend([simplified, sympy.factor(simplified)])
        if simplified.has(*_TRIG):
            expanded = sympy.expand_trig(simplified)
            if expanded != simplified:
                found.append(sympy.factor(sympy.cancel(expanded)))
                if sympy.count_ops(expanded) <= _TRIGSIMP_MAX_OPS:
                    found.append(sympy.factor(sympy.trigsimp(expanded)))
            # On the simplified form only: over the 100 scenes of the tests, the Pythagorean forms
            # of the expanded one never gave the form kept, and were half of this pass's cost.
            found.extend([sympy.factor(sympy.cancel(_pythagorean(simplified, square)))
                          for square in (sympy.sin, sympy.cos)])

    # A partial pass (the budget ran out) keeps what it found.
    attempt(costly, seconds, fallback=lambda: None)
    return tuple(found)


# The longest expanded form trigsimp is tried on. Over the 100 scenes of the tests it finished
# within the budget on 10 of the 11 forms up to 36 operations (0.1 s at most), and on none
# of the 16 longer: there it spent the rest of the budget (0.1 s each), and the Pythagorean forms
# after it were never tried (a rod with both ends on a circle printed its end forces in 41
# operations instead of 19).
_TRIGSIMP_MAX_OPS = 36


def _rewritten(expr: sympy.Expr, weight) -> sympy.Expr:
    """``expr`` through each of our rewritings in turn, each kept where it does not lengthen it."""
    best = expr
    for rewrite in (tidy_radicands, _readable_fraction, _squares_in_sums, grouped, pythagorean_pairs, spread_denominator,
                    contract_double_angles, sympy.factor_terms):
        candidate = rewrite(best)
        if candidate != best and weight(candidate) <= weight(best):
            best = candidate
    return signs_in_front(best)


def _readable_fraction(expr: sympy.Expr) -> sympy.Expr:
    """The denominator in sin² rather than cos² where shorter (:func:`readable_denominator`).

    >>> M, m, a = sympy.symbols("M m alpha", positive=True)
    >>> _readable_fraction(1/(M + m - m*sympy.cos(a)**2))
    1/(M + m*sin(alpha)**2)
    """
    numerator, denominator = sympy.fraction(expr)
    squares = [p for p in denominator.atoms(sympy.Pow) if isinstance(p.base, sympy.cos) and p.exp.is_even]
    if not squares or sympy.count_ops(denominator) > 40:
        return expr  # no cos² to write as 1 − sin²
    return numerator / readable_denominator(denominator)


def _squares_in_sums(expr: sympy.Expr) -> sympy.Expr:
    """Each small sum with sin² or cos² in it, written with the other square where shorter:
    M g l² (sin²θ − 1) as −M g l² cos²θ, 1 − cos²θ as sin²θ."""
    def shorter(total):
        if sympy.count_ops(total) > 30:
            return total
        forms = [total] + [sympy.expand(_pythagorean(total, square)) for square in (sympy.sin, sympy.cos)]
        return min(forms, key=lambda e: (sympy.count_ops(e), len(str(e))))

    return expr.replace(lambda e: e.is_Add and any(p.exp == 2 for p in e.atoms(sympy.Pow)
                                                   if isinstance(p.base, (sympy.sin, sympy.cos))), shorter)


def pythagorean_pairs(expr: sympy.Expr) -> sympy.Expr:
    """In each sum, a term k sin²x beside −k as −k cos²x, and k cos²x beside −k as −k sin²x; k sin²x
    beside k cos²x as k; the rest of the sum as it is.

    :func:`_squares_in_sums` writes every square of a sum the other way or none; a denominator
    M + m − m sin²θ needs only one of its terms rewritten, and sums such as it are often built by
    our own rewritings (:func:`grouped`) after that ran.

    >>> M, m, m1, m2, th = sympy.symbols("M m m1 m2 theta", positive=True)
    >>> pythagorean_pairs(M + m - m*sympy.sin(th)**2)
    M + m*cos(theta)**2
    >>> pythagorean_pairs(m1*sympy.cos(th)**2 - m2*sympy.cos(th)**2 + m2)
    m1*cos(theta)**2 + m2*sin(theta)**2
    >>> pythagorean_pairs(12*m1**2*sympy.sin(th)**2 + 12*m1**2*sympy.cos(th)**2 - 9*m1*m2*sympy.cos(th))
    12*m1**2 - 9*m1*m2*cos(theta)
    """
    def paired(total):
        terms = list(sympy.Add.make_args(total))
        changed = False
        for square, other in ((sympy.sin, sympy.cos), (sympy.cos, sympy.sin)):
            for power in [p for p in total.atoms(sympy.Pow) if isinstance(p.base, square) and p.exp == 2]:
                i = 0
                while i < len(terms):
                    k = terms[i] / power  # terms[i] = k·sin²x exactly, whatever k is
                    partner = k * other(power.base.args[0]) ** 2
                    if terms[i].has(power) and partner in terms[:i] + terms[i + 1:]:
                        terms.remove(partner)  # k sin²x + k cos²x = k
                        terms[terms.index(k * power)] = k
                        changed = True
                        i = 0
                    elif terms[i].has(power) and -k in terms[:i] + terms[i + 1:]:
                        j = terms.index(-k, i + 1) if -k in terms[i + 1:] else terms.index(-k)
                        terms[i] = -k * other(power.base.args[0]) ** 2  # k sin²x − k = −k cos²x
                        del terms[j]
                        changed = True
                        i = 0 if j < i else i + 1
                    else:
                        i += 1
        return sympy.Add(*terms) if changed else total

    return expr.replace(lambda e: e.is_Add and any(p.exp == 2 for p in e.atoms(sympy.Pow)
                                                   if isinstance(p.base, (sympy.sin, sympy.cos))), paired)


def factored_sums(expr: sympy.Expr) -> sympy.Expr:
    """Each small polynomial sum in ``expr`` factored, where that takes fewer operations.

    ``cancel`` and ``together`` multiply out the products of sums they meet, and factoring the
    whole does not bring back one that sits in a sum of its own, as in a governor's
    g²(M + m)² − l²m²ω⁴ (which factors, but into two longer sums).

    >>> M, m, g, l, w = sympy.symbols("M m g l omega", positive=True)
    >>> factored_sums(g**2*(M**2 + 2*M*m + m**2) - l**2*m**2*w**4)
    g**2*(M + m)**2 - l**2*m**2*omega**4
    >>> factored_sums(M**2 - m**2)  # (M - m)*(M + m) takes as many
    M**2 - m**2
    """
    def factored(total):
        # A function is one more variable here: cos²kx − 2 cos kx + 1 is (cos kx − 1)² (a hill's normal force).
        functions = {f: sympy.Dummy() for f in total.atoms(sympy.Function)}
        masked = total.xreplace(functions)
        if len(total.args) > _FACTORED_TERMS or not masked.is_polynomial() or total.has(sympy.Float):
            return total  # (factored, 0.3 M² + 0.6 M m + 0.3 m² would read 0.3 (1.0 M + 1.0 m)²)
        candidate = sympy.factor(masked).xreplace({d: f for f, d in functions.items()})
        return candidate if sympy.count_ops(candidate) < sympy.count_ops(total) else total

    return expr.replace(lambda e: e.is_Add, factored)


_FACTORED_TERMS = 6  # the largest sum factored_sums tries


def spread_denominator(expr: sympy.Expr) -> sympy.Expr:
    """A fraction over one sum as that sum's terms each over the denominator, cancelled.

    Inside a loop the normal force is m (v₀² + R g (3 cos φ − 2))/R as one fraction and
    m (v₀²/R + g (3 cos φ − 2)) in a textbook: only the term that keeps the R keeps the fraction.

    >>> m, v, R, g, phi = sympy.symbols("m v0 R g phi", positive=True)
    >>> spread_denominator(m*(v**2 + R*g*(3*sympy.cos(phi) - 2))/R)
    m*(g*(3*cos(phi) - 2) + v0**2/R)
    """
    numerator, denominator = sympy.fraction(expr)
    sums = [f for f in sympy.Mul.make_args(numerator) if f.is_Add]
    if denominator.is_number or len(sums) != 1:
        return expr  # a number under a sum (g (7 cos φ − 4 cos φ₀)/3) is shortest left whole
    rest = sympy.Mul(*[f for f in sympy.Mul.make_args(numerator) if f is not sums[0]])
    return rest * sympy.Add(*[_over(term, denominator) for term in sums[0].args])


@functools.lru_cache(maxsize=8192)  # the candidates of a form share their terms and denominator
def _over(term: sympy.Expr, denominator: sympy.Expr) -> sympy.Expr:
    """One term of :func:`spread_denominator` over the denominator, cancelled."""
    return sympy.factor_terms(sympy.cancel(term / denominator))


def contract_double_angles(expr: sympy.Expr) -> sympy.Expr:
    """sin x cos x as sin(2x)/2 and sinh x cosh x as sinh(2x)/2, in every product.

    A motor's torque on a bead on a rod, 2 m ω² r₀² sinh ωt cosh ωt, is m ω² r₀² sinh 2ωt in a
    textbook. The rewriting is exact; :func:`human_form` keeps it only where it is shorter.

    >>> x, m = sympy.symbols("x m", positive=True)
    >>> contract_double_angles(2*m*sympy.sinh(x)*sympy.cosh(x))
    m*sinh(2*x)
    >>> contract_double_angles(sympy.sin(x)**3*sympy.cos(x))
    sin(x)**2*sin(2*x)/2
    """
    pairs = ((sympy.sin, sympy.cos), (sympy.sinh, sympy.cosh))

    def contract(product):
        powers = product.as_powers_dict()
        factor = sympy.S.One
        for sine, cosine in pairs:
            for f in [f for f in powers if isinstance(f, sine)]:
                c = cosine(f.args[0])
                a, b = powers[f], powers.get(c, sympy.S.Zero)
                if not (a.is_Integer and b.is_Integer and a > 0 and b > 0):
                    continue
                k = min(a, b)
                powers[f], powers[c] = a - k, b - k
                factor *= (sine(2 * f.args[0]) / 2) ** k
        if factor == 1:
            return product
        return factor * sympy.Mul(*[base ** exp for base, exp in powers.items()])

    return expr.replace(lambda e: e.is_Mul, contract)


def grouped(expr: sympy.Expr) -> sympy.Expr:
    """Sums with their terms grouped over a common factor, as in (m₁ + m₂)(g cos θ₁ + l₁ θ̇₁²) + ….

    Terms are grouped by their coefficient in one or two of the symbols (the masses, say): the
    terms whose coefficients are equal, or opposite, share it as a factor. Every choice of one or
    two symbols is tried on every sum of three to sixteen terms; the shortest grouping is kept.

    >>> m1, m2, g, l, w = sympy.symbols("m1 m2 g l omega", positive=True)
    >>> grouped(g*m1 + g*m2 + l*m1*w**2 + l*m2*w**2 + l*m2*g)
    g*l*m2 + (g + l*omega**2)*(m1 + m2)
    >>> a, th = sympy.symbols("a theta", positive=True)
    >>> grouped(a*w**2*sympy.cos(th) + a*w**2*sympy.cos(sympy.Rational(3, 10)) - 2*g)
    a*omega**2*(cos(theta) + cos(3/10)) - 2*g
    """
    return expr.replace(lambda e: e.is_Add, _group)


@functools.lru_cache(maxsize=4096)  # the candidates of a form, and the forms built on an answer, share sums
def _group(total: sympy.Add) -> sympy.Expr:
    """One sum of :func:`grouped`."""
    terms = sympy.Add.make_args(sympy.expand(total))
    if not 3 <= len(terms) <= 16:
        return total
    # Only a symbol in two terms or more can be part of a shared coefficient; the seven in the
    # most terms are tried (28 pairs), which bounds the cost on a large sum.
    counts = {s: sum(t.has(s) for t in terms) for s in total.free_symbols}
    shared = sorted((s for s in counts if counts[s] > 1), key=lambda s: (-counts[s], str(s)))[:7]
    best, best_ops = total, sympy.count_ops(total)
    for chosen in [(s,) for s in shared] + [(s, t) for i, s in enumerate(shared) for t in shared[i + 1:]]:
        candidate = _grouped_by(terms, chosen)
        if candidate is not None and (ops := sympy.count_ops(candidate)) < best_ops:
            best, best_ops = candidate, ops
    return best


def _grouped_by(terms, symbols) -> sympy.Expr | None:
    """The terms as Σ c·(Σ monomials), c their coefficients in ``symbols``; None if nothing groups."""
    by_rest: dict = {}
    for term in terms:
        rest, coefficient = term.as_independent(*symbols, as_Add=False)
        number, rest = rest.as_coeff_Mul()
        by_rest[rest] = by_rest.get(rest, 0) + number * coefficient
    by_coefficient: dict = {}
    for rest, coefficient in by_rest.items():
        coefficient = sympy.expand(coefficient)
        if coefficient == 0:
            continue
        sign = 1
        if coefficient.could_extract_minus_sign():
            coefficient, sign = -coefficient, -1
        number, coefficient = (1, coefficient) if coefficient.is_Add else coefficient.as_coeff_Mul()
        by_coefficient.setdefault(coefficient, []).append(sign * number * rest)
    if len(by_coefficient) == len(terms):
        return None  # every term on its own: nothing is shared
    def tidy(total):
        return _common_factors(total) if total.is_Add else total

    return sympy.Add(*[tidy(coefficient) * tidy(sympy.Add(*rests)) for coefficient, rests in by_coefficient.items()])


@functools.lru_cache(maxsize=8192)  # the same inner sums come back for every choice of symbols and form
def _common_factors(total: sympy.Add) -> sympy.Expr:
    return sympy.factor_terms(total)


def tidy_radicands(expr: sympy.Expr) -> sympy.Expr:
    """Every root over the shortest of its radicand's own, expanded, combined and factored forms.

    A root found by ``solve`` often has a radicand that cancels when expanded (√(1 − (1 − x)(1 + x))
    is x), or one with a square in it that the symbols' assumptions let out: √((x + 1)² y) is
    (x + 1) √y for x, y > 0, and factoring shows it. The ladder's cos θ* = √(1 − u²), with
    u = (√(sin²θ₀ + 18) + sin θ₀)/6, is kept: expanded it is longer.

    >>> x, y = sympy.symbols("x y", positive=True)
    >>> tidy_radicands(sympy.sqrt(1 - (1 - x)*(1 + x)))
    x
    >>> tidy_radicands(sympy.sqrt(x**2*y + 2*x*y + y))
    sqrt(y)*(x + 1)
    >>> tidy_radicands(sympy.sqrt(1 - (x + y)**2/36))
    sqrt(1 - (x + y)**2/36)
    """
    return expr.replace(lambda e: e.is_Pow and e.exp.is_Rational and not e.exp.is_Integer and e.base.has(sympy.Add),
                        _tidy_root)


def pythagorean_roots(expr: sympy.Expr) -> sympy.Expr:
    """Each root whose radicand sin² + cos² = 1 shortens over that radicand, with the bars of an even
    root taken off where the declared domains and orders (:func:`declared_domains`) fix the sign.

    A constraint in Cartesian coordinates with √(x² + y²) in it, mapped onto a surface of revolution,
    leaves √((a + b cos θ)² sin²φ + (a + b cos θ)² cos²φ) in every force and acceleration: left so,
    the tidy-ups after it expanded the powers and took seconds a matrix entry (a torus: 7 s in all).

    >>> a, b = sympy.symbols("a b", positive=True)
    >>> th, ph = sympy.symbols("theta phi", real=True)
    >>> ring = (a + b*sympy.cos(th))**2
    >>> pythagorean_roots(sympy.sqrt(ring*sympy.sin(ph)**2 + ring*sympy.cos(ph)**2))
    Abs(a + b*cos(theta))
    >>> with declared_domains({}, {b: a}):
    ...     pythagorean_roots(sympy.sqrt(ring*sympy.sin(ph)**2 + ring*sympy.cos(ph)**2))
    a + b*cos(theta)
    """
    roots = [e for e in expr.atoms(sympy.Pow)
             if e.exp.is_Rational and not e.exp.is_Integer and e.base.has(sympy.sin, sympy.cos)]
    if not roots:
        return expr
    symbols = set().union(*(r.free_symbols for r in roots))
    bounds, order = _bounds_of(symbols), _order_of(symbols)
    return expr.xreplace({r: _pythagorean_root(r, bounds, order) for r in roots})


_PYTHAGOREAN_ROOT_LIMIT = 60  # operations in a radicand; the mapped √(x² + y²) of a torus has 20


@functools.lru_cache(maxsize=1024)
def _pythagorean_root(root: sympy.Pow, bounds: tuple, order: tuple) -> sympy.Expr:
    """One root of :func:`pythagorean_roots`, remembered with the domains it was taken under."""
    if sympy.count_ops(root.base) > _PYTHAGOREAN_ROOT_LIMIT:
        return root
    base = sympy.factor(tidy_trig(root.base))
    if sympy.count_ops(base) >= sympy.count_ops(root.base):
        return root
    return signed_abs(base ** root.exp, bounds, order)


@functools.lru_cache(maxsize=1024)
def _tidy_root(root: sympy.Pow) -> sympy.Expr:
    """One root of :func:`tidy_radicands` (remembered: the candidates of one form, and the forms of
    an answer and of what is built on it, share their roots)."""
    base = root.base
    forms = [base, sympy.together(sympy.expand(base)), sympy.cancel(base)]
    forms.append(sympy.factor_terms(forms[1]))
    if sympy.count_ops(base) < 40:
        forms += [sympy.factor(base), _readable_fraction(forms[1])]
    functions = sorted(base.atoms(*_TRIG), key=sympy.default_sort_key)
    if functions and sympy.count_ops(base) < 80:
        # Gathered by powers of its sines, cosines, tangents with factored coefficients: a
        # dumbbell's −2m₁m₂(tan²β − 1) + (m₁² + m₂²)(tan²β + 1) is (m₁ − m₂)² tan²β + (m₁ + m₂)².
        numerator, denominator = sympy.fraction(forms[1])
        forms.append(sympy.collect(sympy.expand(numerator), functions, sympy.factor) / denominator)
    return min((f ** root.exp for f in forms), key=lambda e: (sympy.count_ops(e), len(str(e))))


def _points(symbols, count: int, seed: int = 1):
    """Reproducible points for a numeric check: what the engine derives must not vary by run.

    Positive symbols take values in [0.3, 1.3]; other real ones either sign, so that a rewriting
    exact only for positive values (√a·√b = √(ab)) is caught for a symbol that may be negative.
    """
    import random

    rng = random.Random(seed)
    for _ in range(count):
        point = {}
        for s in symbols:
            value = 0.3 + rng.random()
            if not (s.is_positive or s.is_nonnegative) and rng.random() < 0.5:
                value = -value
            point[s] = sympy.Float(value, 30)
        yield point


def _equal(a: sympy.Expr, b: sympy.Expr, digits: int = 30) -> bool:
    """Whether ``a`` and ``b`` have the same value: at three points to 30 digits, and symbolically
    where that is cheap (rational functions, and polynomials in sines and cosines).

    ``simplify(a - b) == 0`` decides more but can take seconds; a rewriting that changes the
    value changes it at almost every point, so three points at 30 digits are a sharp test. Points
    where ``a`` is undefined are skipped; two at least must remain.

    >>> x = sympy.Symbol("x", positive=True)
    >>> _equal(sympy.sin(2*x)/2, sympy.sin(x)*sympy.cos(x)), _equal(sympy.sin(2*x), sympy.sin(x)*sympy.cos(x))
    (True, False)
    """
    symbols = sorted(a.free_symbols | b.free_symbols, key=str)
    compared = 0
    for point in _points(symbols, 3):
        try:
            x = complex(a.xreplace(point).evalf(digits))
        except (TypeError, ValueError, ZeroDivisionError):
            continue
        if x != x or abs(x) == float("inf"):
            continue
        try:
            y = complex(b.xreplace(point).evalf(digits))
        except (TypeError, ValueError, ZeroDivisionError):
            return False
        if not abs(x - y) <= 1e-20 * max(1.0, abs(x)):
            return False
        compared += 1
    return compared >= 2 and _symbolically_equal(a, b) is not False


def _symbolically_equal(a: sympy.Expr, b: sympy.Expr, limit: int = 80) -> bool | None:
    """True or False where cheap to decide, None where not.

    A rational function of the symbols is zero exactly when ``cancel`` makes it 0. With sines and
    cosines (or sinh and cosh) of rational multiples of symbols (φ and φ/2: each symbol is first
    scaled so that all its multiples are whole, :func:`_angle_scales`), after ``expand_trig``, the
    numerator is zero if it reduces to 0 modulo s² + c² − 1 (c² − s² − 1) for each argument; a
    nonzero remainder proves nothing (sin x and sin(x/2) are not independent), so that case
    returns None, as do roots, logarithms, differences of more than ``limit`` operations and the
    like.
    """
    difference = a - b
    if sympy.count_ops(difference) > limit:
        return None
    if any(not p.exp.is_Integer for p in difference.atoms(sympy.Pow)):
        return None
    if not difference.atoms(sympy.Function):
        return sympy.cancel(difference) == 0
    scales = _angle_scales(difference)
    if scales is None:
        return None
    # x → L·x is a bijection of the reals (and keeps x's sign): zero before exactly when after.
    difference = difference.xreplace({x: scale * x for x, scale in scales.items() if scale != 1})
    expanded = sympy.expand_trig(difference)
    circular, hyperbolic = (sympy.sin, sympy.cos), (sympy.sinh, sympy.cosh)
    functions = expanded.atoms(sympy.Function)
    if not all(isinstance(f, circular + hyperbolic) and not f.args[0].is_Add and f.args[0].as_coeff_Mul()[0] == 1
               for f in functions):
        return None
    replacement, relations = {}, []
    families = ((circular, lambda s, c: s ** 2 + c ** 2 - 1), (hyperbolic, lambda s, c: c ** 2 - s ** 2 - 1))
    for family, relation in families:
        for x in {f.args[0] for f in functions if isinstance(f, family)}:
            s, c = sympy.Dummy(), sympy.Dummy()
            replacement.update({family[0](x): s, family[1](x): c})
            relations.append(relation(s, c))
    numerator = sympy.expand(sympy.numer(sympy.together(expanded.xreplace(replacement))))
    if numerator == 0:
        return True
    dummies = sorted(replacement.values(), key=str)
    generators = dummies + sorted(numerator.free_symbols - set(dummies), key=str)
    _, remainder = sympy.reduced(numerator, relations, *generators)
    return True if remainder == 0 else None


def _angle_scales(expr: sympy.Expr) -> dict | None:
    """For each symbol in the arguments of the (hyperbolic) sines and cosines of ``expr``, the
    least common denominator of its coefficients there: 2 for φ in sin φ and cos(φ/2). None where
    an argument is not a sum of rational multiples of symbols and numbers (a symbol's multiples
    must be whole to expand them into one angle)."""
    scales: dict = {}
    for f in expr.atoms(*_TRIG, *_HYPERBOLIC):
        for term in sympy.Add.make_args(f.args[0]):
            coefficient, rest = term.as_coeff_Mul()
            if not coefficient.is_Rational:
                return None
            if rest.is_Symbol:
                scales[rest] = sympy.ilcm(scales.get(rest, 1), coefficient.q)
            elif rest != 1 and coefficient.q != 1:
                return None
    return scales


def _mixed_angles(expr: sympy.Expr) -> bool:
    """Whether a symbol appears in sines or cosines both as φ (or 3φ/2) and as φ/2."""
    scales = _angle_scales(expr)
    return bool(scales) and any(scale != 1 for scale in scales.values()) and any(
        term.as_coeff_Mul()[0].is_Integer and term.as_coeff_Mul()[1] in scales
        for f in expr.atoms(sympy.sin, sympy.cos) for term in sympy.Add.make_args(f.args[0]))


def in_single_angles(expr: sympy.Expr) -> sympy.Expr:
    """``expr`` with the sines and cosines of φ, 3φ/2, … written in those of the one angle φ/2
    their multiples share, reduced with sin² + cos² = 1 and cancelled.

    A force on a cycloid along the normal (−sin(φ/2), cos(φ/2)) comes in sin φ and cos φ from the
    multipliers and in φ/2 from the direction; in φ/2 alone it is m cos(φ/2)(g + a φ̇²).

    >>> m, g, a, phi = sympy.symbols("m g a phi", positive=True)
    >>> in_single_angles(m*(g*sympy.sin(phi)*sympy.sin(phi/2) + g*(1 + sympy.cos(phi))*sympy.cos(phi/2))/2)
    g*m*cos(phi/2)
    """
    scales = _angle_scales(expr)
    if not scales or all(scale == 1 for scale in scales.values()):
        return expr
    angles = {x: sympy.Dummy(real=True) for x, scale in scales.items() if scale != 1}
    expanded = sympy.expand_trig(expr.xreplace({x: scales[x] * u for x, u in angles.items()}))
    back, relations, replacement = {}, [], {}
    for x, u in angles.items():
        s, c = sympy.Dummy(), sympy.Dummy()
        replacement.update({sympy.sin(u): s, sympy.cos(u): c})
        back.update({s: sympy.sin(x / scales[x]), c: sympy.cos(x / scales[x])})
        relations.append(s ** 2 + c ** 2 - 1)
    rest = set(expanded.xreplace(replacement).atoms(sympy.Dummy)) - set(replacement.values())
    if rest & set(angles.values()):
        return expr  # an angle left outside a sine or cosine (or in tan): not ours to rewrite
    # Other functions (cos φ₀ beside φ and φ/2) are symbols to the reduction.
    masked = {f: sympy.Dummy() for f in expanded.xreplace(replacement).atoms(sympy.Function)}
    back.update({d: f for f, d in masked.items()})
    numerator, denominator = sympy.fraction(sympy.together(expanded.xreplace(replacement).xreplace(masked)))
    forms = []
    for order in (list(replacement.values()), list(reversed(list(replacement.values())))):
        generators = order + sorted((numerator.free_symbols | denominator.free_symbols) - set(order), key=str)
        try:
            reduced = [sympy.reduced(sympy.expand(part), relations, *generators)[1] for part in (numerator, denominator)]
        except sympy.PolynomialError:  # √g beside g: not a polynomial in the generators, not ours to rewrite
            return expr
        forms.append(sympy.factor_terms(sympy.cancel(reduced[0] / reduced[1])))
    best = min(forms, key=lambda e: (sympy.count_ops(e), len(str(e))))
    return best.xreplace(back)


def half_angles(expr: sympy.Expr, bounds: tuple = ()) -> sympy.Expr:
    """Square roots of p(1 − cos x) and p(1 + cos x) as √(2p)·sin(x/2) and √(2p)·cos(x/2).

    p(1 − cos x) = 2p sin²(x/2) and p(1 + cos x) = 2p cos²(x/2) hold everywhere; the root of the
    square is |sin(x/2)| (|cos(x/2)|), written without the bars (or with a minus sign) only where
    the declared domains (``bounds``, :func:`declared_domains`) and the symbols' signs put x/2
    where it has one sign, and kept with them otherwise.

    >>> th = sympy.Symbol("theta0", positive=True)
    >>> half_angles(sympy.sqrt(2 - 2*sympy.cos(th)), ((th, 0.05, 3.0),))
    2*sin(theta0/2)
    >>> half_angles(sympy.sqrt(2 - 2*sympy.cos(th)))
    2*Abs(sin(theta0/2))
    """
    def rewrite(root):
        found = _half_angle_square(root.base)
        if found is None:
            return root
        p, half = found
        sign = _sign(half, bounds)
        signed = sympy.Abs(half) if sign is None else sign * half
        return (2 * p) ** root.exp * signed ** (2 * root.exp)

    return expr.replace(lambda e: e.is_Pow and e.exp.is_Rational and e.exp.q == 2, rewrite)


def _half_angle_square(base: sympy.Expr):
    """(p, sin(x/2)) for base = p(1 − cos x), (p, cos(x/2)) for base = p(1 + cos x), else None."""
    cosines = base.atoms(sympy.cos)
    if len(cosines) != 1:
        return None
    (cosine,) = cosines
    if not any(_maybe_zero(base.xreplace({cosine: end})) for end in (sympy.S.One, sympy.S.NegativeOne)):
        return None  # p(1 ∓ cos x) vanishes at cos x = ±1: seen at once by value, before expanding
    c = sympy.Dummy()
    linear = sympy.expand(base.xreplace({cosine: c}))
    q = linear.coeff(c, 1)
    p = sympy.expand(linear - q * c)
    if q == 0 or p.has(c) or q.has(c):
        return None
    half = cosine.args[0] / 2
    if sympy.cancel(p + q) == 0:
        return sympy.factor_terms(p), sympy.sin(half)
    if sympy.cancel(p - q) == 0:
        return sympy.factor_terms(p), sympy.cos(half)
    return None


def _maybe_zero(expr: sympy.Expr) -> bool:
    """False where ``expr`` is shown nonzero by its value at one rational point of its symbols (a
    sum that is identically zero has value 0 there, to the 50 digits evaluated); True otherwise."""
    point = {s: sympy.Rational(7 + 3 * i, 11) for i, s in enumerate(sorted(expr.free_symbols, key=str))}
    try:
        value = complex(expr.xreplace(point).evalf(50))
    except (TypeError, ValueError, ZeroDivisionError):
        return True
    return not (cmath.isfinite(value) and abs(value) > 1e-30)


def signed_abs(expr: sympy.Expr, bounds: tuple = (), order: tuple = ()) -> sympy.Expr:
    """Each |a b …| with the factors whose sign the declared domains (``bounds``, as for
    :func:`half_angles`) and the symbols' signs fix taken out with that sign: |a b| = |a| |b| and
    |a| = ±a where a has one sign.

    A spring along a cone's generator has length ρ/|sin α|; with α declared in [0.05, 1.5] it is
    ρ/sin α.

    >>> rho, a = sympy.symbols("rho alpha", positive=True)
    >>> signed_abs(rho / sympy.Abs(sympy.sin(a)), ((a, 0.05, 1.5),))
    rho/sin(alpha)
    >>> signed_abs(rho / sympy.Abs(sympy.sin(a)))  # α not bounded: its sine may have either sign
    rho/Abs(sin(alpha))
    >>> R, d = sympy.symbols("R d", positive=True)
    >>> signed_abs(sympy.Abs(d - R) * sympy.Abs(2*R - 2*d), order=((d, R),))  # d declared below R
    (R - d)*(2*R - 2*d)
    """
    def rewrite(absolute):
        known, unknown = sympy.Integer(1), []
        for factor in sympy.Mul.make_args(absolute.args[0]):
            sign = _factor_sign(factor, bounds, order)
            if sign is None:
                unknown.append(factor)
            else:
                known *= sign * factor
        return known * sympy.Abs(sympy.Mul(*unknown)) if unknown else known

    return expr.replace(lambda e: isinstance(e, sympy.Abs), rewrite)


def _factor_sign(f: sympy.Expr, bounds: tuple, order: tuple = ()) -> int | None:
    """+1 where ``f`` ≥ 0 and −1 where ``f`` ≤ 0 on the declared domains and order (``(a, R)``: a < R);
    None where that is not shown."""
    if f.is_nonnegative:
        return 1
    if f.is_nonpositive:
        return -1
    if isinstance(f, (sympy.sin, sympy.cos)):
        return _sign(f, bounds)
    if f.is_Pow and f.exp.is_Rational:
        base = _factor_sign(f.base, bounds, order)
        if f.exp.is_Integer:
            return None if base is None else base ** int(f.exp % 2 + 2)  # an even power: +1
        return 1 if base == 1 else None  # a root of what is ≥ 0
    if f.is_Symbol or f.is_Add:
        interval = _interval(f, {s: (lo, hi) for s, lo, hi in bounds})
        if interval is not None and interval[0] >= 0:
            return 1
        if interval is not None and interval[1] <= 0:
            return -1
    if f.is_Mul:
        signs = [_factor_sign(factor, bounds, order) for factor in f.args]
        return None if None in signs else math.prod(signs)
    if f.is_Add:
        for a, b in order:  # a multiple of R − a, of either sign
            ratio = sympy.cancel(f / (b - a))
            if ratio.is_number and ratio.is_nonzero:
                return 1 if ratio.is_positive else -1
        bounded = _trig_bounds(f)
        if bounded is not None:
            lower, upper = bounded
            if _factor_sign(lower, bounds, order) == 1:
                return 1
            if _factor_sign(-upper, bounds, order) == 1:  # upper ≤ 0 (cos θ₀ − 1: upper 0, which is ≥ 0 too)
                return -1
        return _definite_quadratic(f)
    return None


def _trig_bounds(f: sympy.Expr) -> tuple[sympy.Expr, sympy.Expr] | None:
    """Lower and upper bounds of a sum of terms free of sines and cosines and terms c·P with P a
    product of powers of sines and cosines (in [−1, 1], or [0, 1] with even powers only) and c of
    known sign, each P at its worst end; None where no term has a sine or cosine or a c's sign is
    unknown. The tube's distance from a torus's axis, a + b cos θ, lies in [a − b, a + b], so it is
    positive where b is declared below a.

    >>> a, b, th = sympy.symbols("a b theta", positive=True)
    >>> _trig_bounds(a + b*sympy.cos(th) - a*sympy.sin(th)**2)
    (-b, a + b)
    """
    lower, upper, trigonometric = [], [], False
    for term in sympy.Add.make_args(f):
        coefficient, product = sympy.S.One, sympy.S.One
        for factor in sympy.Mul.make_args(term):
            base, exp = factor.as_base_exp()
            if isinstance(base, (sympy.sin, sympy.cos)) and exp.is_Integer and exp > 0:
                product *= factor
            else:
                coefficient *= factor
        if product == 1:
            lower.append(term)
            upper.append(term)
            continue
        if coefficient.has(sympy.sin, sympy.cos) or coefficient.is_extended_real is not True:
            return None
        low = 0 if all(e.is_even for _, e in (x.as_base_exp() for x in sympy.Mul.make_args(product))) else -1
        if coefficient.is_nonnegative:
            lower.append(low * coefficient)
            upper.append(coefficient)
        elif coefficient.is_nonpositive:
            lower.append(coefficient)
            upper.append(low * coefficient)
        else:
            return None
        trigonometric = True
    return (sympy.Add(*lower), sympy.Add(*upper)) if trigonometric else None


def _definite_quadratic(f: sympy.Expr) -> int | None:
    """±1 where ``f`` is a quadratic a s² + b s + c in one of its symbols with a of that sign and
    b² − 4ac ≤ 0 (by the symbols' signs), so that f has a's sign or is 0: a hoop's moment of inertia
    about its contact point, R²(2M + m) − 2Rdm + d²m, has discriminant −8Md²m in R."""
    for s in sorted(f.free_symbols, key=str):
        try:
            poly = sympy.Poly(f, s)
        except sympy.PolynomialError:
            continue
        if poly.degree() != 2:
            continue
        a, b, c = poly.all_coeffs()
        if sympy.expand(b ** 2 - 4 * a * c).is_nonpositive:  # ≥ 0 (or ≤ 0) is all the bars need
            if a.is_positive:
                return 1
            if a.is_negative:
                return -1
    return None


def _sign(f: sympy.Expr, bounds: tuple) -> int | None:
    """+1 or −1 where the sine or cosine ``f`` has that sign (or is 0) wherever its argument's
    symbols are in their declared domains (``bounds``) and signs; None where that is not shown."""
    interval = _interval(f.args[0], {s: (lo, hi) for s, lo, hi in bounds})
    if interval is None:
        return None
    lo, hi = interval
    shift = 0.0 if isinstance(f, sympy.sin) else math.pi / 2  # cos y = sin(y + π/2)
    if not (math.isfinite(lo) and math.isfinite(hi)):
        return 1 if isinstance(f, sympy.sin) and 0 <= lo and hi <= math.pi else None
    turns = math.floor((lo + shift) / (2 * math.pi))  # sin has period 2π: lo in [0, 2π)
    lo, hi = lo + shift - 2 * math.pi * turns, hi + shift - 2 * math.pi * turns
    if hi <= math.pi:
        return 1
    if math.pi <= lo and hi <= 2 * math.pi:
        return -1
    return None


def _interval(expr: sympy.Expr, bounds: dict) -> tuple[float, float] | None:
    """Bounds of a sum of rational multiples of symbols (and a number) over the symbols' bounds."""
    lo = hi = 0.0
    for term in sympy.Add.make_args(expr):
        coefficient, rest = term.as_coeff_Mul()
        if rest == 1:
            lo, hi = lo + float(coefficient), hi + float(coefficient)
            continue
        if not (coefficient.is_Rational and rest.is_Symbol):
            return None
        if rest in bounds:
            a, b = bounds[rest]
        elif rest.is_nonnegative:
            a, b = 0.0, math.inf
        elif rest.is_nonpositive:
            a, b = -math.inf, 0.0
        else:
            return None
        a, b = sorted((float(coefficient) * a, float(coefficient) * b)) if coefficient else (0.0, 0.0)
        lo, hi = lo + a, hi + b
    return lo, hi


def identically_zero(expr: sympy.Expr, bounds: tuple = (), seconds: float = 0.3) -> bool:
    """Whether ``expr`` is proved 0: it is never shown nonzero at a few points (:func:`_nonzero_at_a_point`)
    and then reduces to 0 symbolically (:func:`_symbolically_equal`) within ``seconds``.

    Only a proof makes an answer 0; an expression that is 0 only to the precision of the points
    stays as it is.

    >>> phi, m, g = sympy.symbols("phi m g", positive=True)
    >>> identically_zero(m*g*(sympy.sin(phi)*sympy.cos(phi/2) - (1 + sympy.cos(phi))*sympy.sin(phi/2)))
    True
    >>> identically_zero(m*g*(sympy.sin(phi)*sympy.cos(phi/2) - sympy.cos(phi)*sympy.sin(phi/2)))
    False
    """
    from grader.mechanics.budget import attempt

    if _nonzero_at_a_point(expr, bounds):
        return False
    proved: list = []
    attempt(lambda: proved.append(_symbolically_equal(expr, sympy.S.Zero, limit=400)), seconds,
            fallback=lambda: None)
    return proved == [True]


def seen_nonzero(expr: sympy.Expr) -> bool:
    """Whether ``expr`` is seen nonzero at a point its symbols' signs allow (:func:`_nonzero_at_a_point`):
    then it is not identically zero, and no ``simplify`` need look (0.1-0.25 s on a nonzero
    acceleration). False, proving nothing, where a symbol is negative or an integer: the points
    do not keep to those.

    >>> x = sympy.Symbol("x", positive=True)
    >>> seen_nonzero(sympy.sin(x)**2 + sympy.cos(x)**2 - 1), seen_nonzero(sympy.sin(x) - x)
    (False, True)
    """
    if any(s.is_negative or s.is_nonpositive or s.is_integer for s in expr.free_symbols):
        return False
    return _nonzero_at_a_point(expr, ())


def _nonzero_at_a_point(expr: sympy.Expr, bounds: tuple, count: int = 4, seed: int = 7) -> bool:
    """Whether ``expr`` is seen nonzero at one of ``count`` seeded rational points in the declared
    domains (``bounds``; the symbols' signs elsewhere), by ``evalf`` at 20 digits.

    Only a screen that spares the symbolic proof most answers: either mistake is harmless (a zero
    seen nonzero keeps its form, a nonzero one fails the proof), so the engine's own ``evalf``
    serves and the checker's ball arithmetic (a later package) is not needed here.
    """
    import random

    within = {s: (lo, hi) for s, lo, hi in bounds}
    symbols = sorted(expr.free_symbols, key=str)
    rng = random.Random(seed)
    for _ in range(count):
        point = {}
        for s in symbols:
            r = rng.random()
            if s in within:
                lo, hi = within[s]
                value = lo + (0.05 + 0.9 * r) * (hi - lo)
            else:
                value = 0.3 + 1.5 * r
                if not (s.is_positive or s.is_nonnegative) and rng.random() < 0.5:
                    value = -value
            point[s] = sympy.Rational(round(value * 1000), 1000)
        try:
            value = complex(expr.xreplace(point).evalf(20))
        except (TypeError, ValueError, ZeroDivisionError, OverflowError):
            continue
        if math.isfinite(abs(value)) and abs(value) > 1e-12:
            return True
    return False


_DOMAINS: contextvars.ContextVar[dict] = contextvars.ContextVar("declared domains", default={})


_BELOW: contextvars.ContextVar[dict] = contextvars.ContextVar("declared order", default={})


@contextlib.contextmanager
def declared_domains(bounds: dict, below: dict | None = None):
    """Within: the symbols of ``bounds`` ({symbol: (lo, hi)}, a scene's declared intervals) are
    known to stay in them, for the signs :func:`human_form` may rely on (√(2 − 2 cos θ₀) is
    2 sin(θ₀/2) for 0 ≤ θ₀ ≤ 2π) and the points where it looks for a nonzero value; and each
    ``a`` of ``below`` ({a: R}, parameters declared ``below``) stays below its ``R`` (R − a > 0)."""
    token = _DOMAINS.set(dict(bounds))
    order = _BELOW.set(dict(below or {}))
    try:
        yield
    finally:
        _DOMAINS.reset(token)
        _BELOW.reset(order)


def _order_of(symbols) -> tuple:
    """The declared ``(a, R)`` pairs (a < R) among ``symbols``, in a fixed order (part of the memory)."""
    below = _BELOW.get()
    return tuple(sorted(((a, b) for a, b in below.items() if a in symbols and b in symbols), key=str))


def _bounds_of(symbols) -> tuple:
    """The declared bounds of ``symbols``, in a fixed order (part of :func:`human_form`'s memory)."""
    domains = _DOMAINS.get()
    return tuple(sorted(((s, *domains[s]) for s in symbols if s in domains), key=lambda b: str(b[0])))


# Where each inverse undoes its function: the argument's declared range inside its principal branch.
_BRANCHES = {sympy.atan: (sympy.tan, -math.pi / 2, math.pi / 2, False),
             sympy.asin: (sympy.sin, -math.pi / 2, math.pi / 2, True),
             sympy.acos: (sympy.cos, 0.0, math.pi, True)}


def inverses_undone(expr: sympy.Expr, bounds: tuple = ()) -> sympy.Expr:
    """``expr`` with atan(tan u), asin(sin u) and acos(cos u) written u where u's declared range lies in the
    inverse's principal branch (an incline's angle α on [0.05, 1.5]: −atan(tan α) is −α).

    >>> a = sympy.Symbol("alpha", positive=True)
    >>> inverses_undone(-sympy.atan(sympy.tan(a)), ((a, 0.05, 1.5),))
    -alpha
    >>> inverses_undone(sympy.acos(sympy.cos(a)), ((a, 0.05, 4.0),))
    acos(cos(alpha))
    """
    ranges = {s: (lo, hi) for s, lo, hi in bounds}

    def undone(node):
        function, lo, hi, closed = _BRANCHES[type(node)]
        inner = node.args[0]
        if not isinstance(inner, function):
            return node
        interval = _interval(inner.args[0], ranges)
        if interval is None:
            return node
        inside = (lo <= interval[0] and interval[1] <= hi) if closed else (lo < interval[0] and interval[1] < hi)
        return inner.args[0] if inside else node

    return expr.replace(lambda n: isinstance(n, tuple(_BRANCHES)), undone)


def inverse_hyperbolic(expr: sympy.Expr) -> sympy.Expr:
    """log(y + √(y² − 1)) as acosh(y), log(y + √(y² + 1)) as asinh(y), as a textbook writes them.

    ``solve`` gives the time a bead reaches the end of a rotating rod, r₀ cosh ωt = L, as
    log((L + √(L² − r₀²))/r₀)/ω; for u = y + √(y² ∓ 1), (u ± 1/u)/2 = y, and the rewriting is kept
    where the two forms agree at generic points.

    >>> L, r0, w = sympy.symbols("L r0 omega", positive=True)
    >>> inverse_hyperbolic(sympy.log((L + sympy.sqrt(L**2 - r0**2))/r0)/w)
    acosh(L/r0)/omega
    """
    def rewrite(e):
        u = e.args[0]
        for function, sign in ((sympy.acosh, 1), (sympy.asinh, -1)):
            y = sympy.cancel(sympy.radsimp((u + sign / u) / 2))
            if sympy.count_ops(y) < sympy.count_ops(u) and _agree(e, function(y)):
                return function(y)
        return e

    return expr.replace(lambda e: isinstance(e, sympy.log), rewrite)


def _is_root(factor: sympy.Expr) -> bool:
    return factor.is_Pow and factor.exp in (sympy.S.Half, -sympy.S.Half)


def gathered_roots(expr: sympy.Expr) -> sympy.Expr:
    """Square roots gathered into one, over a radicand with common factors taken out of its sums.

    sympy splits √(2d/(g sin α)) into √2·√d·√(1/sin α)/√g and multiplies 3 into 3R − 3r; on a
    blackboard both are written once: √(2d/(g sin α)), √(2g/(3(R − r))). Gathering √a·√b into
    √(ab) is exact wherever the answer is real, which is where it is an answer. The root is kept
    unevaluated, else sympy splits it again.

    >>> d, g, a, R, r = sympy.symbols("d g alpha R r", positive=True)
    >>> gathered_roots(sympy.sqrt(2)*sympy.sqrt(d)*sympy.sqrt(1/sympy.sin(a))/sympy.sqrt(g))
    sqrt(2*d/(g*sin(alpha)))
    >>> gathered_roots(sympy.sqrt(2*g/(3*R - 3*r)))
    sqrt(2*g/(3*(R - r)))
    >>> x, y = sympy.symbols("x y", real=True)
    >>> gathered_roots(sympy.sqrt(x + 2)*sympy.sqrt(y + 3))
    sqrt((x + 2)*(y + 3))
    >>> gathered_roots(sympy.sqrt(x - 2)*sympy.sqrt(y - 3))  # -sqrt((x - 2)*(y - 3)) for x < 2, y < 3
    sqrt(x - 2)*sqrt(y - 3)
    """
    if expr.is_Add:
        return sympy.Add(*[gathered_roots(a) for a in expr.args])
    factors = sympy.Mul.make_args(expr)
    roots = [f for f in factors if _is_root(f)]
    if not roots or (len(roots) == 1 and roots[0].exp < 0):
        return expr
    rest = [gathered_roots(f) if f.is_Add else f for f in factors if not _is_root(f)]
    radicand = sympy.Mul(*[f.base ** (2 * f.exp) for f in roots])
    gathered = sympy.Mul(*rest) * sympy.Pow(_tidy_radicand(radicand), sympy.S.Half, evaluate=False)
    # √a·√b = −√(ab) when a and b are both negative: keep the split form unless the two agree
    # at generic points.
    return gathered if _agree(expr, gathered) else expr


def joined_roots(expr: sympy.Expr) -> sympy.Expr:
    """Each product's square roots written as one root, as on a blackboard: √(2gR/3), not
    √6·√R·√g/3; 2π√(l cos θ₀/g); cos(t√(k/m)).

    sympy splits the root of a product of positive factors, and splits a joined root again in
    every product it is multiplied into, so the joined form is built unevaluated and only for the
    printed answer (:meth:`AnswerEvaluator.evaluate`), once nothing more is computed with it.

    √a·√b = √(ab) holds where a ≥ 0 (whatever b's sign) and 1/√b = √(1/b) where b > 0, so a
    product is joined only where the declared domains and order (:func:`declared_domains`) show
    every radicand nonnegative, but for at most one in the numerator. Numbers go inside the root as
    far as they leave whole numbers outside (2√7/7 is 2√(1/7)), pairs of factors that are negative
    on the domains are written positive ((a − R)(cos θ₀ − 1) as (R − a)(1 − cos θ₀) for a < R), and
    a root with only a number over it is written 1/√(…), never √(1/(…)).

    >>> l, g, R, m, M = sympy.symbols("l g R m M", positive=True)
    >>> joined_roots(sympy.sqrt(6) * sympy.sqrt(R) * sympy.sqrt(g) / 3)
    sqrt(2*R*g/3)
    >>> joined_roots(2 * m / (sympy.sqrt(M) * sympy.sqrt(3*M + 2*m)))
    2*m/sqrt(M*(3*M + 2*m))
    >>> x = sympy.Symbol("x", real=True)
    >>> joined_roots(sympy.sqrt(g) / sympy.sqrt(x))  # x may be negative: 1/√x is not √(1/x)
    sqrt(g)/sqrt(x)
    """
    bounds, order = _bounds_of(expr.free_symbols), _order_of(expr.free_symbols)
    joined = _join_roots(expr, bounds, order)
    if joined is expr or sympy.count_ops(joined) > sympy.count_ops(expr) or not _agree(joined, expr):
        return expr
    return joined


def _join_roots(expr: sympy.Expr, bounds: tuple, order: tuple, in_product: bool = False) -> sympy.Expr:
    """:func:`joined_roots` of every product (and every root standing alone) in ``expr``, from the leaves up."""
    if not expr.args or expr.is_Atom:
        return expr
    args = [_join_roots(a, bounds, order, in_product=expr.is_Mul) for a in expr.args]
    if expr.is_Mul or (_is_root(expr) and not in_product):  # a root in a product: the product's to join
        joined = _joined_product(args if expr.is_Mul else [expr.func(*args, evaluate=False)], bounds, order)
        if joined is not None:
            return joined
    if all(new is old for new, old in zip(args, expr.args)):
        return expr
    if expr.is_Add or expr.is_Mul or expr.is_Pow:
        return expr.func(*args, evaluate=False)  # evaluated, sympy would split the joined roots again
    return expr.func(*args)


def _joined_product(factors: list, bounds: tuple, order: tuple) -> sympy.Expr | None:
    """The product of ``factors`` with its square roots joined into one and the radicand tidied (numbers
    and signs), or None where that is not shown exact or changes nothing."""
    roots = [f for f in factors if _is_root(f)]
    symbolic_roots = [r for r in roots if not r.base.is_Rational]
    if not symbolic_roots:
        return None
    unknown = 0
    for root in symbolic_roots:
        sign = _factor_sign(root.base, bounds, order)
        if sign == -1 or (sign is None and root.exp < 0):
            return None
        unknown += sign is None
    if unknown > 1:
        return None
    coefficient = sympy.Mul(*[f for f in factors if f.is_Rational])
    others = [f for f in factors if not _is_root(f) and not f.is_Rational]
    # factor_terms for the numbers of a sum (2r²/3 − 2r₀²/3 is 2/3 times r² − r₀²), which sympy multiplies out
    inside, symbolic = sympy.factor_terms(
        _tidy_radicand(sympy.Mul(*[r.base ** (2 * r.exp) for r in symbolic_roots]))).as_coeff_Mul()
    numbers = sympy.Mul(*[r.base ** (2 * r.exp) for r in roots if r.base.is_Rational]) * coefficient ** 2 * inside
    if not numbers.is_Rational or numbers == 0:
        return None
    if numbers < 0:
        # −d(M + 2m)/(g(m₁ sin β − m₂)) under a root: the minus into a sum, d(M + 2m)/(g(m₂ − m₁ sin β))
        negated = _one_sum_negated(symbolic)
        symbolic, numbers = (negated if negated is not None else -symbolic), -numbers
    # Whole numbers outside, the rest of the numbers inside: 4√3/3 is 4√(1/3), 2√2 stays 2√2.
    whole = _square_part(numbers.p) / _square_part(numbers.q)
    radicand = _keep_coeff(numbers / whole ** 2, _negative_pairs_flipped(symbolic, bounds, order))
    if len(roots) == 1 and roots[0].exp > 0 and radicand == roots[0].base and whole == abs(coefficient):
        return None  # nothing to tidy: keep the product as sympy built it
    numerator, denominator = sympy.fraction(radicand)
    if numerator.is_number and numerator.is_positive:
        root = sympy.Pow(denominator / numerator, -sympy.S.Half, evaluate=False)
    else:
        root = sympy.Pow(radicand, sympy.S.Half, evaluate=False)
    product = [whole] if whole != 1 else []
    product = sympy.Mul(*product, *others, root, evaluate=False) if product or others else root
    # A minus sign as a factor of its own: sympy splits a negative number into −1 and the rest in an
    # unevaluated product, and its printer then multiplies the rest out, splitting the joined root
    # again (−√(2gl/3)/3 printed as −√6·√g·√l/3/3).
    return sympy.Mul(sympy.S.NegativeOne, product, evaluate=False) if coefficient < 0 else product


def _one_sum_negated(expr: sympy.Expr) -> sympy.Expr | None:
    """``-expr`` written by negating the one of its sums with the largest share of negative terms (m₁ sin β
    − m₂ becomes m₂ − m₁ sin β), or None if no sum has a negative term (R + r stays as it is)."""
    numerator, denominator = sympy.fraction(expr)
    candidates = []
    for which, part in enumerate((numerator, denominator)):
        for i, f in enumerate(sympy.Mul.make_args(part)):
            if f.is_Add:
                negative = sum(t.could_extract_minus_sign() for t in f.args)
                if negative:
                    candidates.append((negative / len(f.args), which, i))
    if not candidates:
        return None
    _, which, i = max(candidates)
    parts = [list(sympy.Mul.make_args(numerator)), list(sympy.Mul.make_args(denominator))]
    parts[which][i] = -parts[which][i]
    return sympy.Mul(*parts[0]) / sympy.Mul(*parts[1])


def _square_part(n: int) -> sympy.Integer:
    """The largest whole number whose square divides ``n`` (√12 = 2√3: 2)."""
    return sympy.Mul(*[f for f in sympy.Mul.make_args(sympy.sqrt(n)) if f.is_Integer])


def _negative_pairs_flipped(radicand: sympy.Expr, bounds: tuple, order: tuple) -> sympy.Expr:
    """``radicand`` with its sums that are ≤ 0 on the domains negated, two at a time; one such sum alone
    with the one sum of unknown sign: a nonnegative radicand makes that one ≤ 0 too (negating both
    changes nothing anyway), √((sin θ₀ − sin θ)/(4 − 3 sin²θ)), not √((sin θ − sin θ₀)/(3 sin²θ − 4)).

    >>> th, th0 = sympy.symbols("theta theta0", real=True)
    >>> _negative_pairs_flipped((sympy.sin(th) - sympy.sin(th0))/(3*sympy.sin(th)**2 - 4), (), ())
    (-sin(theta) + sin(theta0))/(4 - 3*sin(theta)**2)
    """
    numerator, denominator = sympy.fraction(radicand)
    factors = [*sympy.Mul.make_args(numerator), *(1 / f for f in sympy.Mul.make_args(denominator))]
    odd_sums = [f for f in factors if f.is_Add or (f.is_Pow and f.base.is_Add and f.exp.is_odd)]
    signs = [_factor_sign(f, bounds, order) for f in odd_sums]
    negative = [f for f, sign in zip(odd_sums, signs) if sign == -1]
    unknown = [f for f, sign in zip(odd_sums, signs) if sign is None]
    if len(negative) % 2 and len(unknown) == 1:
        negative.append(unknown[0])
    if len(negative) < 2:
        return radicand
    flipped = negative[: len(negative) // 2 * 2]
    rest = [f for f in factors if f not in flipped] if len(set(flipped)) == len(flipped) else None
    if rest is None:
        return radicand
    return sympy.Mul(*rest, *[sympy.Pow(-f.base, f.exp) if f.is_Pow else -f for f in flipped])


def _agree(a: sympy.Expr, b: sympy.Expr) -> bool:
    symbols = sorted(a.free_symbols | b.free_symbols, key=str)
    for shift in (0.0, 0.61):
        point = {s: sympy.Float(0.7 + 0.13 * k + shift * (k % 2), 20) for k, s in enumerate(symbols)}
        try:
            x, y = complex(a.xreplace(point).evalf(20)), complex(b.xreplace(point).evalf(20))
        except (TypeError, ValueError):
            return False
        if not abs(x - y) <= 1e-12 * max(1.0, abs(x)):
            return False
    return True


def _tidy_radicand(expr: sympy.Expr) -> sympy.Expr:
    """A fraction with the common factors of numerator and denominator sums taken out."""
    # cancel() removes common factors but multiplies out products of sums; together() keeps them.
    return min((_fraction_in_front(f(expr)) for f in (sympy.together, sympy.cancel)),
               key=lambda e: (sympy.count_ops(e), len(str(e))))


def _fraction_in_front(expr: sympy.Expr) -> sympy.Expr:
    numerator, denominator = sympy.fraction(expr)
    (a, numerator), (b, denominator) = (sympy.factor_terms(part).as_coeff_Mul() for part in (numerator, denominator))
    # Signs and numbers in front as a whole: 2g/(3(R − r)), not −2g/(3(r − R)) or 2g/(3R − 3r)
    # (sympy distributes a number over a sum it multiplies, so the two are kept apart).
    for part in (numerator, denominator):
        if part.is_Add and part.could_extract_minus_sign():
            a = -a
    numerator = -numerator if numerator.is_Add and numerator.could_extract_minus_sign() else numerator
    denominator = -denominator if denominator.is_Add and denominator.could_extract_minus_sign() else denominator
    return sympy.Mul(a / b, numerator, sympy.Pow(denominator, -1))


def signs_in_front(expr: sympy.Expr) -> sympy.Expr:
    """-a/(b + c) rather than a/(-b - c), and (r - r0)(…) rather than -(-r + r0)(…).

    A minus sign belongs in front of the whole, not inside a denominator or a factor.

    >>> r, r0, a = sympy.symbols("r r0 a", positive=True)
    >>> signs_in_front(-(-r + r0)*(a - r)/(-a - r))
    -(a - r)*(r - r0)/(a + r)
    """
    numerator, denominator = sympy.fraction(expr)
    sign = 1
    parts = []
    for part in (numerator, denominator):
        factors = []
        for f in sympy.Mul.make_args(part):
            base, exp = f.as_base_exp()
            if base.is_Add and base.could_extract_minus_sign() and exp.is_Integer:
                base = -base
                sign *= (-1) ** int(exp)
            factors.append(base ** exp)
        parts.append(sympy.Mul(*factors))
    result = sign * parts[0] / parts[1]
    return result if sympy.count_ops(result) <= sympy.count_ops(expr) else expr


def _pythagorean(expr: sympy.Expr, square) -> sympy.Expr:
    """Rewrite even powers of cos as 1 - sin² (square=sin) or of sin as 1 - cos² (square=cos).

    simplify() picks neither: M + m sin²α reads better than M + m - m cos²α, and only one of the
    two rewritings shows it.
    """
    other = sympy.cos if square is sympy.sin else sympy.sin

    def rewrite(e):
        return (1 - square(e.base.args[0]) ** 2) ** (e.exp // 2)

    return expr.replace(
        lambda e: e.is_Pow and isinstance(e.base, other) and e.exp.is_Integer and e.exp > 0 and e.exp % 2 == 0,
        rewrite,
    )


def quick_form(expr: sympy.Expr, seconds: float = 0.1) -> sympy.Expr:
    """A cheap tidy-up for large intermediate results: cancel and factor, trigsimp when small.

    Factoring a large multivariate polynomial takes anywhere from a second to minutes (the
    algorithm is randomised), so it runs under a budget of ``seconds`` and is skipped past it.
    """
    from grader.mechanics.budget import attempt

    expr = sympy.cancel(sympy.sympify(expr, strict=True))
    candidates = [expr, sympy.factor_terms(expr)]

    def costly():
        candidates.append(sympy.factor(expr))
        if expr.has(*_TRIG):
            numerator, denominator = sympy.fraction(expr)
            candidates.append(sympy.factor(tidy_trig(numerator)) / readable_denominator(denominator))

    if sympy.count_ops(expr) < 60:
        attempt(costly, seconds, fallback=lambda: None)
    return min(candidates, key=lambda e: _weight(e, (0, 0)))


@functools.lru_cache(maxsize=1024)  # the answers of a scene share their determinant, and the solve has it too
def readable_denominator(expr: sympy.Expr) -> sympy.Expr:
    """A determinant as people write it: factored, with m₂ sin²(θ₁ − θ₂) rather than m₂ − m₂ cos²(…).

    >>> m1, m2, a = sympy.symbols("m1 m2 a", positive=True)
    >>> readable_denominator(m1*m2 + m2**2 - m2**2*sympy.cos(a)**2)
    m2*(m1 + m2*sin(a)**2)
    """
    expr = sympy.factor(sympy.expand(expr))
    candidates = [expr]
    if expr.has(*_TRIG):
        candidates += [sympy.factor(sympy.expand(_pythagorean(expr, square))) for square in (sympy.sin, sympy.cos)]
        if len({f.args[0] for f in expr.atoms(sympy.sin, sympy.cos)}) > 1 and sympy.count_ops(expr) <= 200:
            # A 2 × 2 determinant over two angles: sin(β − φ) cos(β + φ) + sin(β + φ) cos(β − φ) is
            # sin 2β. (Not on a long one: TR10i took 1.5 s on a sum of 1,154 operations.)
            candidates.append(sympy.factor(tidy_trig(expr)))
    return min(candidates, key=lambda e: _weight(e, (0, 0)))


def _angle_count(expr: sympy.Expr) -> int:
    return len({f.args[0] for f in expr.atoms(sympy.sin, sympy.cos)})


@functools.lru_cache(maxsize=4096)  # the matrix entries, their solution and its answers meet the same sums
def tidy_trig(expr: sympy.Expr) -> sympy.Expr:
    """A fast trigonometric tidy-up for small entries: combine and use sin² + cos² = 1.

    ``trigsimp`` finds the same on such entries but takes ~100 times longer; this does the two
    things that matter for mechanics: products of sines and cosines of single angles into the
    sine or cosine of a difference (fu's TR10i), and the Pythagorean identity in whichever
    direction is shorter.

    >>> a, b, l = sympy.symbols("a b l")
    >>> tidy_trig(l*sympy.cos(a)*sympy.cos(b) + l*sympy.sin(a)*sympy.sin(b))
    l*cos(a - b)
    >>> tidy_trig(l**2*sympy.sin(a)**2 + l**2*sympy.cos(a)**2)
    l**2
    """
    from sympy.simplify.fu import TR10i

    expr = sympy.expand(expr)
    if not expr.has(*_TRIG):
        return sympy.factor_terms(expr)
    if _angle_count(expr) > 1:
        # Sums of products into the sine or cosine of a sum need two angles; with one, TR10i
        # changed nothing in 1,127 calls over the test scenes and cost a second of them. Where
        # sin² + cos² = 1 removes an angle (the azimuth of a Cartesian constraint mapped onto a
        # surface of revolution, in sin⁴φ + 2 sin²φ cos²φ + cos⁴φ), that form goes on instead:
        # TR10i on the expanded sum it came from took 4.7 s an entry of a torus's multiplier.
        fewer = [e for e in (sympy.expand(_pythagorean(expr, square)) for square in (sympy.sin, sympy.cos))
                 if _angle_count(e) < _angle_count(expr)]
        expr = min(fewer, key=lambda e: _weight(e, (0, 0))) if fewer else TR10i(expr)
    candidates = [expr] + [sympy.expand(_pythagorean(expr, square)) for square in (sympy.sin, sympy.cos)]
    return sympy.factor_terms(min(candidates, key=lambda e: _weight(e, (0, 0))))
