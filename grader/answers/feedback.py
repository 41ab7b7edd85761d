"""Feedback for a wrong answer: instructor messages for known wrong answers, then common slips.

Every message is earned by an equivalence check, never by pattern matching on the text: an
instructor's ``[[answers.feedback]]`` entry matches when the student's answer is equivalent to its
``expr``; "check the sign" appears only when the answer is equivalent to minus the reference; and
so on for a constant factor, 2π (radians for cycles), a magnitude, sin <-> cos, a missing term,
an extra term and one term's sign.
Feedback runs only when the answer is not equivalent, and stops when the time budget runs low.

Feedback never gives the reference away. By default (``detail="kind"``) a message names the kind of
slip ("off by a constant factor", "check the sign", "a term is missing") but no value: a student
who read "3/2 times the correct one", or a relative difference at a point the counterexample shows,
could compute the reference from their own answer (the slips that are one exact operation away, the sign,
sin for cos, 2π for radians against cycles, say what they are: naming the slip is the feedback). An
instructor may opt in per problem
(``[feedback] detail = "full"`` in the scene file) to messages that also state the factor and the
relative difference.
"""

from __future__ import annotations

import time
from fractions import Fraction
from functools import lru_cache
from typing import Callable, Iterator, Sequence

import sympy

from grader.answers.equivalence import SYMBOLIC_MAX_TERMS, expansion_terms, instance_test
from grader.expressions.magnitudes import node_count

__all__ = ["diagnose", "factor_message", "counts_cycles", "MAGNITUDE_MESSAGE", "TWO_PI_MESSAGE"]

MAX_TERMS = 6


def factor_message(q: Fraction, detail: str = "kind") -> str:
    """What to tell a student whose answer is ``q`` times the correct one.

    With ``detail="kind"`` the factor itself is never said (it would give the reference away).

    >>> factor_message(Fraction(3, 2))
    'Your answer is off by a constant factor: check the numerical factors.'
    >>> factor_message(Fraction(-1)), factor_message(Fraction(1, 2), detail="full")
    ('Check the sign: your answer is the negative of the correct one.', 'Your answer is half the correct one: check for a missing or extra factor of 2.')
    """
    if q == -1:
        return "Check the sign: your answer is the negative of the correct one."
    if detail != "full":
        if q < 0:
            return "Check the sign and the numerical factors: your answer is off by a negative constant factor."
        return "Your answer is off by a constant factor: check the numerical factors."
    sign = "" if q > 0 else "Check the sign, and: "
    q = abs(q)
    if q == 2:
        text = "Your answer is twice the correct one: check for a missing or extra factor of 2."
    elif q == Fraction(1, 2):
        text = "Your answer is half the correct one: check for a missing or extra factor of 2."
    else:
        text = f"Your answer is {q} times the correct one: check the constant factors."
    return sign + (text[0].lower() + text[1:] if sign else text)


def counts_cycles(dimension) -> bool:
    """Whether a quantity of this dimension (exponents of mass, length and time) may be off by 2π from
    radians for cycles: a frequency, an angular velocity, a period or an angle, none of mass or length.

    >>> from grader.expressions.dimensions import Dimension
    >>> counts_cycles(Dimension(0, 0, -1)), counts_cycles(Dimension(0, 0, 1)), counts_cycles(Dimension(1, 1, -2))
    (True, True, False)
    """
    return dimension is not None and dimension.mass == 0 and dimension.length == 0


def _simple_ratio(value: float) -> Fraction | None:
    if not value or value != value or abs(value) > 1e3:
        return None
    # Most ratios are not within 1e-9 of any p/d with d <= 12: say so without exact fractions. When
    # one is, p = round(value*d) for it, so the looser float test below lets it through.
    if not any(abs(round(value * d) / d - value) <= 2e-9 * abs(value) for d in range(1, 13)):
        return None
    q = Fraction(value).limit_denominator(12)
    if q == 1 or q == 0 or abs(float(q) - value) > 1e-9 * abs(value):
        return None
    return q


_is_sin_or_cos = instance_test((sympy.sin, sympy.cos))


def _has_sin_or_cos(expr: sympy.Expr) -> bool:
    """``expr.has(sympy.sin, sympy.cos)``: the same nodes, without sympy's generator and its isinstance with
    each function class at each node (see `instance_test`)."""
    stack = [expr]
    while stack:
        node = stack.pop()
        if _is_sin_or_cos(node):
            return True
        stack.extend(node.args)
    return False


def _swap_sin_cos(expr: sympy.Expr) -> sympy.Expr:
    """``expr`` with every sin written as cos and every cos as sin."""
    if not expr.args:
        return expr
    args = [_swap_sin_cos(a) for a in expr.args]
    if expr.func is sympy.sin:
        return sympy.cos(*args)
    if expr.func is sympy.cos:
        return sympy.sin(*args)
    if all(new is old for new, old in zip(args, expr.args)):
        return expr  # no sin or cos below: rebuilding would only give the same expression back
    return expr.func(*args)


def _splits(factor: sympy.Expr) -> bool:
    """Whether ``expand`` may turn this factor of a product into a sum (so the product into several
    terms): a sum, a logarithm, and a power above 1 (or to a symbol) of anything but a symbol or a
    number, ((a + b)c)^(3/2) becoming (a + b)^(3/2) c^(3/2) and then a sum. Everything else expands
    to one term: a power at most 1 is a product of such powers, a sum in a denominator or in a
    function's argument stays there (trig=False), a power to a sum is a product (power_exp)."""
    if factor.is_Add:
        return True
    if factor.is_Pow:
        base, exp = factor.args
        return not (base.is_Symbol or base.is_Number) and not (exp.is_Rational and exp <= 1)
    return factor.func is sympy.log


# Products distributed by hand at most this far; beyond, expand (rare: several nested sums).
MAX_DISTRIBUTED = 64
# Largest expression (in nodes) worth expanding for its terms.
EXPAND_MAX_NODES = 400


def _terms_without_expanding(expr: sympy.Expr) -> tuple[sympy.Expr, ...] | None:
    """The terms of ``expand(expr)``, up to the form of each, for a product: ``()`` when it is one
    term as it stands, else its sums distributed by hand (c·(t₁ + t₂) is c·t₁ and c·t₂, nested sums
    in turn, like terms then combined); None when a factor needs expand itself (a power of a sum,
    a logarithm) or the terms would be too many.

    sympy's expand rebuilds and re-derives every factor of a fresh product (most of a wrong answer's
    feedback time); here the terms are only candidates that an equivalence check then tests, so a
    term's form does not matter (c·t/(r³(M + m)) where expand writes c·t/(M r³ + m r³)), only its value.

    >>> m, g, M, a = sympy.symbols("m g M alpha", positive=True)
    >>> _terms_without_expanding(M*m*g*sympy.cos(a)/(M + m*sympy.sin(a)**2))
    ()
    >>> _terms_without_expanding(m*(g - a**2)/(M + m))
    (g*m/(M + m), -alpha**2*m/(M + m))
    >>> _terms_without_expanding(m*(g + a*(M - m)))
    (g*m, -alpha*m**2, M*alpha*m)
    >>> _terms_without_expanding(m*(g + a)**2) is None  # a power of a sum: expand
    True
    """
    if not any(_splits(f) for f in sympy.Mul.make_args(expr)):
        return ()
    terms = _distributed(expr, [])
    if terms is None:
        return None
    first = next(f for f in sympy.Mul.make_args(expr) if _splits(f))
    if len(terms) == len(first.args):
        return tuple(terms)  # one sum of unlike terms times the same factors: still unlike
    return sympy.Add.make_args(sympy.Add(*terms))


def _distributed(expr: sympy.Expr, out: list) -> list | None:
    """``out`` extended by the terms of ``expr`` with every sum of a product distributed, or None."""
    factors = sympy.Mul.make_args(expr)
    total = next((f for f in factors if _splits(f)), None)
    if total is None:
        out.append(expr)
        return out
    if not total.is_Add:
        return None
    others = [f for f in factors if f is not total]
    for t in total.args:
        if _distributed(sympy.Mul(*others, t), out) is None or len(out) > MAX_DISTRIBUTED:
            return None
    return out


def _terms(expr: sympy.Expr) -> tuple[sympy.Expr, ...]:
    terms = sympy.Add.make_args(expr)
    if len(terms) < 2:
        terms = _terms_without_expanding(expr)
        if terms is None:
            # powers of sums that multiply out to thousands of terms are not expanded (no feedback by terms),
            # nor a page of nested quotients (a triple pendulum's solved row: minutes in expand)
            small = expansion_terms(expr) <= SYMBOLIC_MAX_TERMS and node_count(expr, EXPAND_MAX_NODES) <= EXPAND_MAX_NODES
            terms = sympy.Add.make_args(sympy.expand(expr)) if small else ()
    return terms if 2 <= len(terms) <= MAX_TERMS else ()


@lru_cache(maxsize=256)
def _reference_candidates(reference: sympy.Expr) -> tuple[tuple[sympy.Expr, ...], tuple[sympy.Expr, ...]]:
    """The reference without each of its terms, and with each term's sign flipped.

    They depend on the reference alone, and every wrong answer to a question tries them, so they
    are built (and the reference expanded) once per reference.
    """
    terms = _terms(reference)
    return tuple(reference - t for t in terms), tuple(reference - 2 * t for t in terms)


# The relative difference below which a wrong answer is "close" (rounded numbers, a tiny extra term).
CLOSE = 1e-3
# 2π or 1/(2π) times the correct answer: radians for cycles, the commonest slip in oscillations (ω for f,
# a period 2π/ω for 1/ω), which "off by a constant factor" does not name (2π is no ratio of small integers).
# |N| where the reference N is signed (a normal force that turns negative where the contact would pull): the
# verdict is right, and without a word the student could not tell their magnitude from a wrong formula.
MAGNITUDE_MESSAGE = ("Your answer is the magnitude of the correct one, which is negative for some values here: "
                     "give it with its sign (the sign says the direction).")
TWO_PI_MESSAGE = ("Your answer is off by a factor of 2π: check radians against cycles (the angular frequency ω "
                  "against the frequency f = ω/2π, a period 2π/ω against 1/ω).")


def diagnose(
    reference: sympy.Expr,
    answer: sympy.Expr,
    same: Callable[[sympy.Expr, sympy.Expr], bool],
    instructor: Sequence[tuple[sympy.Expr, str]] = (),
    ratio: float | None = None,
    relative_difference: float | None = None,
    deadline: float | None = None,
    equation: bool = False,
    swap_could_match: Callable[[], bool] | None = None,
    detail: str = "kind",
    cycles: bool = True,
) -> list[dict]:
    """Feedback items ``{"code", "message"}`` for an answer known not to be equivalent.

    Parameters
    ----------
    reference, answer : sympy.Expr
        For equations, the residuals ``lhs - rhs``.
    same : callable
        ``same(reference_candidate, answer_candidate)``: the equivalence check to use.
    instructor : sequence of (expr, message)
        Known wrong answers with the instructor's message; the first equivalent one is reported.
    ratio : float, optional
        answer / reference at the counterexample, to spot a constant factor cheaply.
    relative_difference : float, optional
        At the counterexample; a tiny one earns a "close but not equal" note.
    deadline : float, optional
        ``time.monotonic()`` after which no more candidates are tried.
    equation : bool
        The expressions are residuals of equations (no constant-factor slip: any factor is fine).
    swap_could_match : callable, optional
        A cheap test that is False only when the answer with sin and cos swapped is provably not
        the reference (the checker compares values at a point); then that candidate is not built.
    detail : {"kind", "full"}
        ``"kind"`` (the default) names the slip without any value that would reveal the reference;
        ``"full"`` also states the factor and the relative difference (the instructor's choice).
    cycles : bool
        Whether a factor of 2π may be named radians for cycles: the reference is a rate, a time or an
        angle (`counts_cycles`); 2π in a tension is no such slip, and the message would mislead.

    Examples
    --------
    >>> import sympy
    >>> m, g, t = sympy.symbols("m g theta", positive=True)
    >>> same = lambda r, a: sympy.expand(a - r) == 0
    >>> [f["code"] for f in diagnose(m*g*sympy.cos(t), m*g*sympy.sin(t), same)]
    ['sin_cos']
    >>> [f["code"] for f in diagnose(m*g*(3*sympy.cos(t) - 2), 3*m*g*sympy.cos(t), same)]
    ['missing_term']
    """
    found: list[dict] = []

    def out_of_time() -> bool:
        return deadline is not None and time.monotonic() > deadline

    for expr, message in instructor:
        if out_of_time():
            return found
        if same(expr, answer):
            found.append({"code": "instructor", "message": message})
            break

    def slips() -> Iterator[tuple[str, Callable[[], bool], str]]:
        # Generated in order and only as far as needed: the first slip that fits is the one reported,
        # so the answer is not expanded for the extra-term test when an earlier test already fits.
        if ratio is not None and not equation:
            q = _simple_ratio(ratio)
            if q is not None:
                yield ("sign" if q == -1 else "factor",
                       lambda: same(sympy.Rational(q.numerator, q.denominator) * reference, answer),
                       factor_message(q, detail))
        if ratio is not None and not equation and cycles and ratio > 0:
            for factor in (2 * sympy.pi, 1 / (2 * sympy.pi)):
                if abs(ratio / float(factor) - 1) <= 1e-9:
                    yield ("two_pi", lambda f=factor: same(f * reference, answer), TWO_PI_MESSAGE)
        factors = sympy.Mul.make_args(answer)
        if not equation and any(f.func is sympy.Abs for f in factors) and answer.as_coeff_Mul()[0] > 0:
            # |N|, m|g cos θ - R θ̇²| (sympy takes a positive m out of the bars): the bars taken off
            signed = sympy.Mul(*(f.args[0] if f.func is sympy.Abs else f for f in factors))
            yield ("magnitude", lambda: same(reference, signed) or same(reference, -signed), MAGNITUDE_MESSAGE)
        if _has_sin_or_cos(answer):
            yield ("sin_cos",
                   lambda: (swap_could_match is None or swap_could_match())
                   and same(reference, _swap_sin_cos(answer)),
                   "Check sin and cos: with them swapped, your answer would be right.")
        without_term, term_flipped = _reference_candidates(reference)
        for candidate in without_term:
            yield ("missing_term", lambda c=candidate: same(c, answer),
                   "Your answer is missing a term: the rest of it is right.")
        for candidate in term_flipped:
            yield ("term_sign", lambda c=candidate: same(c, answer),
                   "One term of your answer has the wrong sign.")
        for t in _terms(answer):
            yield ("extra_term", lambda t=t: same(reference, answer - t),
                   "Your answer has an extra term: without it, it would be right.")

    for code, test, message in slips():
        if out_of_time():
            break
        if test():
            found.append({"code": code, "message": message})
            break
    if not found and relative_difference is not None and relative_difference < CLOSE:
        how_close = f" (relative difference {relative_difference:.1g} at a test point)" if detail == "full" else ""
        found.append({
            "code": "close",
            "message": f"Your answer is close to the correct one{how_close} but not equal: check for rounded "
                       "numbers or a small extra term.",
        })
    return found
