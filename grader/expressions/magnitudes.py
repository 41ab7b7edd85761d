"""Building sympy arithmetic without letting text make numbers explode.

sympy evaluates exact powers eagerly: ``Integer(9)**387420489`` would compute a
370-million-digit integer.  Every power and product the parser builds goes
through here, and sizes are estimated from bit lengths *before* sympy is asked
to compute anything.
"""

from __future__ import annotations

import math

import sympy

from .errors import ExpressionError

__all__ = ["MAX_DIGITS", "MAX_EXPONENT", "digits", "guarded_pow", "checked", "not_real", "node_count"]

#: Largest number of decimal digits any exact number may have.
MAX_DIGITS = 1000
#: Largest |exponent| of an exact numeric power (x^1000 is already more than any answer needs).
MAX_EXPONENT = 1000
#: Largest denominator of a rational exponent; larger ones only make sympy hunt for roots.
MAX_EXPONENT_DENOMINATOR = 10 ** 6

_UNDEFINED = (sympy.zoo, sympy.nan, sympy.oo, -sympy.oo)
# These four are singletons (sympy turns Float("inf") into oo itself), so identity is equality; testing
# ``id`` skips sympy's ``__eq__``, which sympifies its argument, on every node the parser builds.
_UNDEFINED_IDS = frozenset(map(id, _UNDEFINED))
_I = sympy.I
_SMALL = 10 ** 300


def node_count(expr: sympy.Expr, limit: int) -> int:
    """Nodes of ``expr``, counted up to just past ``limit`` (so that a huge expression costs no more than
    ``limit`` steps to be found too large).

    >>> x = sympy.Symbol("x")
    >>> node_count(x + 1, 10), node_count(sum(x**k for k in range(50)), 10)
    (3, 11)
    """
    count, stack = 0, [expr]
    while stack and count <= limit:
        count += 1
        stack.extend(stack.pop().args)
    return count


def digits(number: sympy.Rational) -> float:
    """Decimal digits (log10) of the larger of numerator and denominator.

    Examples
    --------
    >>> digits(sympy.Integer(10) ** 20), digits(sympy.Rational(1, 1000))
    (20.0, 3.0)
    """
    largest = max(abs(int(number.p)), int(number.q))
    return math.log10(largest) if largest > 1 else 0.0


def _size(expr: sympy.Expr) -> float:
    """Digits of the largest exact number inside ``expr`` (at least a little, so size * exponent bounds growth)."""
    if expr.is_Rational:
        return digits(expr)
    return max([digits(r) for r in expr.atoms(sympy.Rational)] + [0.5])


def _too_large(position: int | None, what: str = "number too large") -> ExpressionError:
    return ExpressionError(what, position, "too_large", "no answer here needs numbers that size")


def guarded_pow(base: sympy.Expr, exponent: sympy.Expr, position: int | None) -> sympy.Expr:
    """``base ** exponent``, refused when the exact result would be huge.

    Examples
    --------
    >>> guarded_pow(sympy.Integer(2), sympy.Integer(10), 0)
    1024
    >>> guarded_pow(sympy.Integer(9), sympy.Integer(387420489), 1)
    Traceback (most recent call last):
    ...
    grader.expressions.errors.ExpressionError: exponent too large at character 2; no answer here needs numbers that size
    """
    if exponent.is_Rational:
        # |p/q| > MAX_EXPONENT in integers (q > 0): sympy's own comparison sympifies and is slower.
        if abs(exponent.p) > MAX_EXPONENT * exponent.q:
            raise _too_large(position, "exponent too large")
        if exponent.q > MAX_EXPONENT_DENOMINATOR:
            # x^0.666666666666667 pasted from a calculator: small, but too many digits to be exact
            raise ExpressionError("exponent with too many digits", position, "too_large",
                                  "write it as a fraction, as in x^(2/3), or with at most 6 decimals")
        # In floats: float * Rational would make a sympy Float, rounded the same way but slower.
        if not base.free_symbols and _size(base) * (abs(exponent.p) / exponent.q) > MAX_DIGITS:
            raise _too_large(position)
    elif exponent.is_number and _size(exponent) > 6:
        raise _too_large(position, "exponent too large")
    return checked(sympy.Pow(base, exponent), position)


def not_real(position: int | None) -> ExpressionError:
    """Answers are real: sqrt(-1) or asin(2) is a mistake, not an imaginary unit."""
    return ExpressionError("this is not a real number (a square root or logarithm of a negative number?)",
                           position, "syntax", "check the sign of what is under the root or logarithm, "
                           "and that asin/acos get a number in [-1, 1]")


def checked(expr: sympy.Expr, position: int | None) -> sympy.Expr:
    """Refuse a freshly built result that is undefined (1/0, log(0)) or holds a huge number.

    Only the node and its direct arguments are inspected: deeper ones were
    checked when they were built.

    Examples
    --------
    >>> checked(sympy.Integer(1) / 0, 4)
    Traceback (most recent call last):
    ...
    grader.expressions.errors.ExpressionError: this is undefined (a division by zero?) at character 5; check what divides by zero here
    """
    for node in (expr, *expr.args):
        if id(node) in _UNDEFINED_IDS:
            raise ExpressionError("this is undefined (a division by zero?)", position, "syntax",
                                  "check what divides by zero here")
        if node is _I:
            raise not_real(position)
        # digits() only for numbers that could have that many (both parts below 10**300 cannot)
        if node.is_Rational and (abs(node.p) > _SMALL or node.q > _SMALL) and digits(node) > MAX_DIGITS:
            raise _too_large(position)
    return expr
