"""Simplify an engine result into the form a person would write.

sympy's ``simplify`` returns *a* short form, not always the one on a blackboard: it may leave
``3*g*m*cos(theta) - 2*g*m`` where a physicist writes ``g*m*(3*cos(theta) - 2)``, or turn
``sin(alpha)*cos(alpha)`` into ``sin(2*alpha)/2``. We try a few rewritings and keep the one that
reads shortest: fewest operations, with multiple angles the input did not have counted as extra
work for the reader, ties broken by length.

Examples
--------
>>> import sympy
>>> g, m, theta = sympy.symbols("g m theta", positive=True)
>>> human_form(3*g*m*sympy.cos(theta) - 2*g*m)
g*m*(3*cos(theta) - 2)
>>> quick_form((g*m - g*m*sympy.cos(theta)**2) / (1 - sympy.cos(theta)**2))
g*m
"""

from __future__ import annotations

import sympy

__all__ = ["human_form", "quick_form"]

_TRIG = (sympy.sin, sympy.cos, sympy.tan, sympy.cot, sympy.sec, sympy.csc)


def _multiple_angles(expr: sympy.Expr) -> int:
    """How many trig calls have an argument like 2*alpha or 2*theta1 - 2*theta2."""
    count = 0
    for f in expr.atoms(*_TRIG):
        coefficients = [term.as_coeff_Mul()[0] for term in sympy.Add.make_args(f.args[0])]
        if any(abs(c) != 1 for c in coefficients if c.is_Rational):
            count += 1
    return count


def _weight(expr: sympy.Expr, allowed_multiples: int) -> tuple[int, int]:
    extra = max(0, _multiple_angles(expr) - allowed_multiples)
    return sympy.count_ops(expr, visual=False) + 4 * extra, len(str(expr))


def human_form(expr: sympy.Expr) -> sympy.Expr:
    """The most readable of a few equivalent rewritings of ``expr`` (see the module example)."""
    expr = sympy.sympify(expr)
    if expr.is_Atom:
        return expr
    allowed = _multiple_angles(expr)
    cancelled = sympy.cancel(expr)
    simplified = sympy.simplify(cancelled)
    candidates = [expr, cancelled, simplified, sympy.factor(simplified)]
    if simplified.has(*_TRIG):
        expanded = sympy.expand_trig(simplified)
        candidates += [sympy.factor(sympy.cancel(expanded)), sympy.factor(sympy.trigsimp(expanded))]
        candidates += [sympy.factor(sympy.cancel(_pythagorean(c, square))) for c in (expanded, simplified)
                       for square in (sympy.sin, sympy.cos)]
    return min(candidates, key=lambda e: _weight(e, allowed))


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


def quick_form(expr: sympy.Expr) -> sympy.Expr:
    """A cheap tidy-up for large intermediate results: cancel and factor, trigsimp when small."""
    expr = sympy.cancel(sympy.sympify(expr))
    candidates = [expr, sympy.factor(expr)]
    if expr.has(*_TRIG) and sympy.count_ops(expr) < 80:
        candidates.append(sympy.factor(sympy.trigsimp(expr)))
    return min(candidates, key=lambda e: _weight(e, 0))
