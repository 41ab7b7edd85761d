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

__all__ = ["gathered_roots", "human_form", "inverse_hyperbolic", "quick_form", "readable_denominator", "signs_in_front", "tidy_trig"]

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


def human_form(expr: sympy.Expr, seconds: float = 0.3) -> sympy.Expr:
    """The most readable of a few equivalent rewritings of ``expr`` (see the module example).

    Cheap rewritings always run; the costly ones (``simplify``, factoring) run under a budget of
    ``seconds`` and only on expressions of moderate size, so that tidying never dominates a
    derivation: their result is kept if they finish, skipped if not.
    """
    from grader.mechanics.budget import attempt

    expr = sympy.sympify(expr, strict=True)  # an expression or a number, never text
    if expr.is_Atom:
        return expr
    allowed = _multiple_angles(expr)
    cancelled = sympy.cancel(expr)
    candidates = [expr, cancelled, sympy.factor_terms(cancelled)]
    numerator, denominator = sympy.fraction(cancelled)
    if cancelled.has(*_TRIG):
        candidates.append(sympy.factor_terms(tidy_trig(numerator)) / readable_denominator(denominator))

    def costly():
        simplified = sympy.simplify(cancelled)
        candidates.extend([simplified, sympy.factor(simplified)])
        if simplified.has(*_TRIG):
            expanded = sympy.expand_trig(simplified)
            candidates.extend([sympy.factor(sympy.cancel(expanded)), sympy.factor(sympy.trigsimp(expanded))])
            candidates.extend([sympy.factor(sympy.cancel(_pythagorean(c, square))) for c in (expanded, simplified)
                               for square in (sympy.sin, sympy.cos)])

    # simplify() rarely beats the cheap forms on a short expression, and costs the most there.
    if 12 < min(sympy.count_ops(c) for c in candidates) and sympy.count_ops(cancelled) < 120:
        attempt(costly, seconds, fallback=lambda: None)
    if expr.has(sympy.Pow):
        candidates.extend([gathered_roots(c) for c in candidates])
    if expr.has(sympy.log):
        candidates.append(inverse_hyperbolic(expr))
    return min((signs_in_front(c) for c in candidates), key=lambda e: _weight(e, allowed))


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
    return min(candidates, key=lambda e: _weight(e, 0))


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
    return min(candidates, key=lambda e: _weight(e, 0))


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
    expr = TR10i(expr)
    candidates = [expr] + [sympy.expand(_pythagorean(expr, square)) for square in (sympy.sin, sympy.cos)]
    return sympy.factor_terms(min(candidates, key=lambda e: _weight(e, 0)))
