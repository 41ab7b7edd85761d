"""Fast text and LaTeX for the expressions our grammar builds.

sympy's printers are general and slow (most of their time goes into ordering terms); on the
checker's hot path they cost more than parsing and checking together. These printers cover the
trees :mod:`grader.expressions.parser` builds (sums, products, powers, the whitelisted functions,
symbols, integers, rationals, floats, pi and E) and fall back to sympy for anything else. The text
is in sympy's ``str`` syntax, so our parser reads it back to the same expression.

Examples
--------
>>> import sympy
>>> m, g, theta = sympy.symbols("m g theta", positive=True)
>>> e = m*g*(3*sympy.cos(theta) - 2)
>>> to_text(e)
'g*m*(3*cos(theta) - 2)'
>>> to_latex(e, {theta: r"\\theta"})
'g m \\\\left(3 \\\\cos{\\\\left(\\\\theta \\\\right)} - 2\\\\right)'
"""

from __future__ import annotations

from fractions import Fraction
from functools import lru_cache

import sympy
from sympy.core.function import AppliedUndef

from .functions import BY_SYMPY

__all__ = ["to_latex", "to_text"]

# Precedence: higher binds tighter.
_ADD, _MUL, _POW, _ATOM = 10, 20, 30, 40

# sympy function class name -> LaTeX of the function's name, from the one registry.
_LATEX_FUNCTIONS = {f.sympy_func.__name__: f.latex for f in BY_SYMPY.values() if f.latex}


def _minus(expr: sympy.Expr) -> bool:
    """``expr.could_extract_minus_sign()``, without building ``-expr`` for a product.

    sympy's product version negates the whole product first, only to catch ``-3*zoo`` (which equals
    its negative); apart from that case the sign of the leading number decides, as it does there.
    """
    if expr.is_Mul:
        args = expr.args
        if len(args) > 1 and args[1] is not sympy.S.ComplexInfinity:
            return _negative_number(args[0])
    return expr.could_extract_minus_sign()


def _negative_number(expr: sympy.Expr) -> bool:
    # A rational's sign is that of its numerator: no need to go through sympy's assumptions system,
    # which works out every other fact about a number the first time it is asked one.
    if expr.is_Rational:
        return expr.p < 0
    return bool(expr.is_Number and expr.is_extended_negative)


def _sorted_terms(expr: sympy.Add) -> list[tuple[sympy.Expr, bool]]:
    """(term, whether it is written with a minus) pairs of a sum.

    Positive terms first, in sympy's canonical argument order: stable, and reads naturally.
    """
    return sorted(((t, _minus(t)) for t in expr.args), key=lambda pair: pair[1])


# The text and the LaTeX of an answer are printed one after the other, and both need the
# negation of each negative term and the split of each product; so do answers sharing terms with
# the reference. Both are pure functions of an immutable expression: remember the recent ones.
@lru_cache(maxsize=1024)
def _negated(expr: sympy.Expr) -> sympy.Expr:
    return -expr


@lru_cache(maxsize=1024)
def _split_fraction(expr: sympy.Mul) -> tuple[sympy.Expr, tuple, tuple]:
    """(numeric coefficient, numerator factors, denominator factors) of a product."""
    args = expr.args
    if len(args) > 2 and args[0].is_Number:
        # What as_coeff_Mul and make_args give here, without building the product of the rest.
        coefficient, factors = args[0], args[1:]
    else:
        coefficient, rest = expr.as_coeff_Mul()
        factors = sympy.Mul.make_args(rest)
    numerator, denominator = [], []
    for factor in factors:
        if factor.is_Pow and factor.exp.is_Rational and factor.exp.is_negative:
            denominator.append(factor.base if _equals(factor.exp, -1, 1) else sympy.Pow(factor.base, -factor.exp))
        else:
            numerator.append(factor)
    return coefficient, tuple(numerator), tuple(denominator)


def _printing_order(factors: list) -> list:
    """Factors in the order sympy's str prints them: by ``sort_key`` (Mul stores another order).

    For symbols and rational powers of symbols, the commonest factors, that order is by name and
    then exponent, which is quick to compare; ``sort_key`` itself is slow to build for a new factor.
    """
    if all(f.is_Symbol or (f.is_Pow and f.base.is_Symbol and f.exp.is_Rational) for f in factors):
        return sorted(factors, key=_symbol_power_key)
    return sorted(factors, key=_sort_key)


def _symbol_power_key(factor: sympy.Expr) -> tuple:
    if factor.is_Symbol:
        return factor.name, 1
    return factor.base.name, Fraction(int(factor.exp.p), int(factor.exp.q))


def _sort_key(expr: sympy.Basic):
    return _SortKey(expr)


class _SortKey:
    """``expr.sort_key()`` (what default_sort_key returns for a sympy object), compared lazily.

    A sort key starts with the ``class_key`` of the factor (of its base, for a power), which is
    cheap; the rest (for a sum, its terms in printed order) is slow to build for a new factor. Two
    keys whose class keys differ compare as those do, as tuples compare by their first differing
    item; only factors of one class (two sums, two cosines) need the whole key.
    """

    __slots__ = ("expr", "head", "key")

    def __init__(self, expr: sympy.Basic):
        self.expr = expr
        self.head = _class_key_head(expr)
        self.key = None

    def full(self):
        if self.key is None:
            self.key = self.expr.sort_key()
        return self.key

    def __lt__(self, other: "_SortKey") -> bool:
        if self.head is not None and other.head is not None and self.head != other.head:
            return self.head < other.head
        return self.full() < other.full()


def _class_key_head(expr: sympy.Basic):
    """The first item of ``expr.sort_key()`` without the rest, or None where it is not known cheaply."""
    method = type(expr).sort_key
    if method is _EXPR_SORT_KEY:
        # as Expr.sort_key: the class of the factor without its coefficient and, for a power, of its base
        _, rest = expr.as_coeff_Mul()
        if rest.is_Pow:
            rest, _ = rest.as_base_exp()
            if rest is sympy.S.Exp1:
                return None  # sorted as the function exp
        return _class_key(type(rest))
    if method in _CLASS_FIRST_SORT_KEYS:
        return _class_key(type(expr))
    return None


_EXPR_SORT_KEY = sympy.Expr.sort_key
# sort_key methods whose key starts with the object's own class_key.
_CLASS_FIRST_SORT_KEYS = (sympy.Atom.sort_key, sympy.Symbol.sort_key, sympy.Number.sort_key)


@lru_cache(maxsize=None)
def _class_key(cls: type) -> tuple:
    return cls.class_key()


def _equals(number: sympy.Expr, p: int, q: int) -> bool:
    """``number == Rational(p, q)``, without sympy's comparison, which sympifies both sides first: for a
    rational from its numerator and denominator, for anything else (a float 0.5) as sympy compares."""
    if number.is_Rational:
        return number.p == p and number.q == q
    return number == sympy.Rational(p, q)


def _precedence(expr: sympy.Expr) -> int:
    if expr.is_Add:
        return _ADD
    if expr.is_Mul or (expr.is_Rational and not expr.is_Integer):
        return _MUL
    if expr.is_Pow:
        return _POW
    if expr.is_Number and (expr.p < 0 if expr.is_Rational else expr.is_negative):
        return _ADD
    return _ATOM


# -- text ----------------------------------------------------------------------------------------
def to_text(expr: sympy.Expr) -> str:
    """sympy-``str``-compatible text of an expression (see the module example)."""
    try:
        return _text(expr)
    except _Unsupported:
        return sympy.sstr(expr)


class _Unsupported(Exception):
    pass


def _text_wrapped(expr: sympy.Expr, level: int) -> str:
    text = _text(expr)
    return f"({text})" if _precedence(expr) < level else text


def _text(expr: sympy.Expr) -> str:
    if expr.is_Symbol:
        return expr.name
    if expr.is_Integer:
        return str(int(expr))
    if expr.is_Rational:
        return f"{expr.p}/{expr.q}"
    if expr.is_Float:
        return sympy.sstr(expr)
    if expr is sympy.pi:
        return "pi"
    if expr is sympy.E:
        return "E"
    if expr.is_Add:
        out = ""
        for i, (term, negative) in enumerate(_sorted_terms(expr)):
            if negative:
                body = _text_wrapped(_negated(term), _MUL)
                out += f" - {body}" if i else f"-{body}"
            else:
                out += f" + {_text(term)}" if i else _text(term)
        return out
    if expr.is_Mul:
        if _minus(expr):
            return "-" + _text_wrapped(_negated(expr), _MUL)
        coefficient, numerator, denominator = _split_fraction(expr)
        numerator, denominator = list(numerator), list(denominator)
        parts = [] if _equals(coefficient, 1, 1) else [str(coefficient.p)] if coefficient.q == 1 else None
        if parts is None:
            numerator = [sympy.Integer(coefficient.p)] + numerator if coefficient.p != 1 else numerator
            denominator = [sympy.Integer(coefficient.q)] + denominator
            parts = []
        ordered = _printing_order(numerator) if len(numerator) > 1 else numerator
        parts += [_text_wrapped(f, _MUL) for f in ordered if not (f.is_Integer and f.p == 1 and numerator)]
        top = "*".join(parts) or "1"
        if not denominator:
            return top
        bottom = [_text_wrapped(f, _MUL) for f in denominator]
        bottom_text = bottom[0] if len(bottom) == 1 else "(" + "*".join(bottom) + ")"
        return f"{top}/{bottom_text}"
    if expr.is_Pow:
        base, exp = expr.args
        if _equals(exp, 1, 2):
            return f"sqrt({_text(base)})"
        if _equals(exp, -1, 2):
            return f"1/sqrt({_text(base)})"
        if exp.is_Rational and exp.is_negative:
            return f"1/{_text_wrapped(sympy.Pow(base, -exp), _POW)}"
        exp_text = _text(exp) if exp.is_Symbol or (exp.is_Integer and exp.p >= 0) else f"({_text(exp)})"
        return f"{_text_wrapped(base, _POW + 1)}**{exp_text}"
    if isinstance(expr, sympy.Function) and not isinstance(expr, AppliedUndef):
        spec = BY_SYMPY.get(expr.func)
        name = spec.text if spec is not None else expr.func.__name__
        return f"{name}({', '.join(_text(a) for a in expr.args)})"
    raise _Unsupported


# -- LaTeX ---------------------------------------------------------------------------------------
def to_latex(expr: sympy.Expr, names: dict | None = None) -> str:
    """LaTeX of an expression; ``names`` maps symbols to their LaTeX (see the module example)."""
    try:
        return _Latex(names or {}).print(expr)
    except _Unsupported:
        return sympy.latex(expr, symbol_names=names or {})


class _Latex:
    def __init__(self, names: dict):
        self.names = names

    def wrapped(self, expr: sympy.Expr, level: int) -> str:
        text = self.print(expr)
        return rf"\left({text}\right)" if _precedence(expr) < level else text

    def factors(self, factors: list, bare: bool) -> str:
        # Inside \frac a lone sum needs no parentheses: the bar groups it.
        if bare and len(factors) == 1:
            return self.print(factors[0])
        return " ".join(self.wrapped(f, _MUL) for f in factors)

    def print(self, expr: sympy.Expr) -> str:
        if expr.is_Symbol:
            return self.names.get(expr, expr.name)
        if expr.is_Integer:
            return str(int(expr))
        if expr.is_Rational:
            sign = "-" if expr.p < 0 else ""
            return rf"{sign}\frac{{{abs(expr.p)}}}{{{expr.q}}}"
        if expr.is_Float:
            return sympy.latex(expr)
        if expr is sympy.pi:
            return r"\pi"
        if expr is sympy.E:
            return "e"
        if expr.is_Add:
            out = ""
            for i, (term, negative) in enumerate(_sorted_terms(expr)):
                if negative:
                    body = self.wrapped(_negated(term), _MUL)
                    out += f" - {body}" if i else f"- {body}"
                else:
                    out += f" + {self.print(term)}" if i else self.print(term)
            return out
        if expr.is_Mul:
            if _minus(expr):
                return "- " + self.wrapped(_negated(expr), _MUL)
            coefficient, numerator, denominator = _split_fraction(expr)
            numerator, denominator = list(numerator), list(denominator)
            if coefficient.q != 1:
                denominator = [sympy.Integer(coefficient.q)] + denominator
            if coefficient.p != 1:
                numerator = [sympy.Integer(coefficient.p)] + numerator
            top = self.factors(numerator, bare=bool(denominator)) or "1"
            if not denominator:
                return top
            bottom = self.factors(denominator, bare=True)
            return rf"\frac{{{top}}}{{{bottom}}}"
        if expr.is_Pow:
            base, exp = expr.args
            if _equals(exp, 1, 2):
                return rf"\sqrt{{{self.print(base)}}}"
            if exp.is_Rational and exp.is_negative:
                return rf"\frac{{1}}{{{self.print(sympy.Pow(base, -exp))}}}"
            if isinstance(base, sympy.Function) and not isinstance(base, AppliedUndef) and exp.is_Integer \
                    and base.func.__name__ in _LATEX_FUNCTIONS and len(base.args) == 1:
                # sin^2(theta), as people write it
                return rf"{_LATEX_FUNCTIONS[base.func.__name__]}^{{{int(exp)}}}{{\left({self.print(base.args[0])} \right)}}"
            return f"{self.wrapped(base, _POW + 1)}^{{{self.print(exp)}}}"
        if isinstance(expr, sympy.Function) and not isinstance(expr, AppliedUndef):
            name = expr.func.__name__
            if expr.func is sympy.Abs:
                return rf"\left|{self.print(expr.args[0])}\right|"
            if name in _LATEX_FUNCTIONS:
                args = ", ".join(self.print(a) for a in expr.args)
                return rf"{_LATEX_FUNCTIONS[name]}{{\left({args} \right)}}"
        raise _Unsupported
