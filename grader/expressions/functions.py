"""The one registry of functions and constants a text may use.

Each :class:`Function` says everything any part of the grader needs to know about it: the names
people type (``name`` and ``aliases``), how many arguments it takes, how to build it in sympy,
how to evaluate it in ball arithmetic (python-flint ``arb``) and in floats (``math``/``mpmath``),
how to print it (text and LaTeX), which LaTeX commands denote it, and its dimension rule. The
parser, the printers, the LaTeX input, the dimension checker and the numeric evaluator all read
this table, so a function added here is added everywhere at once.

Nothing outside the table can be called: the parser looks a name up here and builds the sympy
object itself, so no text ever reaches sympy's own parser.

Evaluation is over the reals: a point where a function has no real value raises `Undefined` (with
the reason in words); a ball too wide to tell raises `Unresolved`, and the caller retries with
more bits.

Examples
--------
>>> FUNCTIONS["arctan2"].name, FUNCTIONS["cosec"].name, FUNCTIONS["sgn"].name
('atan2', 'csc', 'sign')
>>> import flint
>>> float(BY_SYMPY[sympy.asinh].arb(flint.arb(0)).mid())
0.0
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import flint
import sympy

__all__ = ["Function", "FUNCTIONS", "REGISTRY", "BY_SYMPY", "INVERSES", "CONSTANTS", "Undefined",
           "Unresolved", "function_names", "latex_commands"]


class Undefined(ArithmeticError):
    """The expression has no real value at this point; ``reason`` says why, in words."""

    def __init__(self, reason: str):
        super().__init__(reason)
        self.reason = reason


class Unresolved(ArithmeticError):
    """The working precision is too low to tell whether the expression is defined here."""


@dataclass(frozen=True)
class Function:
    """A function the grammar allows.

    Attributes
    ----------
    name : str
        The canonical name (what the hint lists).
    build : callable or None
        Builds the sympy expression from sympy arguments; None for ``sqrt``, which the parser
        builds as a size-checked power.
    min_args, max_args : int
        Arity; a call with another number of arguments is a parse error naming both.
    aliases : tuple of str
        Other spellings (``arcsin``, ``cosec``, ``sgn``, ``Abs`` which is how sympy prints abs).
    sympy_func : sympy function class or None
        The class ``build`` makes, which the evaluator and the dimension checker recognise (None
        when ``build`` makes something else: ``log10(x)`` is ``log(x)/log(10)``).
    text : str
        The name in canonical text (sympy's ``str``), which parses back.
    latex : str
        LaTeX of the function's name (``\\sin``, ``\\operatorname{asinh}``).
    commands : tuple of str
        LaTeX commands a student may type for it (``\\arcsin``); other names work through
        ``\\operatorname{...}``.
    dimension : str
        ``"dimensionless"`` (argument and result dimensionless), ``"same"`` (result has the
        argument's dimension: abs), ``"any"`` (any argument, dimensionless result: sign) or
        ``"same_args"`` (arguments of one dimension, dimensionless result: atan2).
    arb : callable or None
        Ball-arithmetic evaluator on ``flint.arb`` arguments.
    real : callable or None
        Float evaluator ``real(lib, *args)`` with ``lib`` the ``math`` or ``mpmath`` module.
    """

    name: str
    build: Callable | None
    min_args: int = 1
    max_args: int = 1
    aliases: tuple[str, ...] = ()
    sympy_func: object = None
    text: str = ""
    latex: str = ""
    commands: tuple[str, ...] = ()
    dimension: str = "dimensionless"
    arb: Callable | None = None
    real: Callable | None = None


# -- ball arithmetic: every branch decides certainly, or asks for more bits -------------------------
def _inverse(x, reason):
    if x == 0:
        raise Undefined(reason)
    if x.contains(0):
        raise Unresolved
    return 1 / x


def _arb_log(x):
    if x > 0:
        return x.log()
    if x <= 0:
        raise Undefined("the logarithm of a number that is not positive")
    raise Unresolved


def _arb_unit(x, name):
    if x.abs_upper() <= 1:
        return x
    if x.abs_lower() > 1:
        raise Undefined(f"{name} of a number outside [-1, 1]")
    raise Unresolved


def _arb_acosh(x):
    if x >= 1:
        return x.acosh()
    if x < 1:
        raise Undefined("acosh of a number below 1")
    raise Unresolved


def _arb_atanh(x):
    if x.abs_upper() < 1:
        return x.atanh()
    if x.abs_lower() >= 1:
        raise Undefined("atanh of a number outside (-1, 1)")
    raise Unresolved


def _arb_sign(x):
    if x > 0:
        return flint.arb(1)
    if x < 0:
        return flint.arb(-1)
    if x == 0:
        return flint.arb(0)
    raise Unresolved


def _arb_atan2(y, x):
    if x > 0 or y > 0 or y < 0:
        return flint.arb.atan2(y, x)
    if x == 0 and y == 0:
        raise Undefined("atan2(0, 0)")
    raise Unresolved


# -- floats (math or mpmath): the same domain rules without error bounds ------------------------------
def _real_inverse(x, reason):
    if x == 0:
        raise Undefined(reason)
    return 1 / x


def _real_log(lib, x):
    if x <= 0:
        raise Undefined("the logarithm of a number that is not positive")
    return lib.log(x)


def _real_unit(x, name):
    if abs(x) > 1:
        raise Undefined(f"{name} of a number outside [-1, 1]")
    return x


def _real_acosh(lib, x):
    if x < 1:
        raise Undefined("acosh of a number below 1")
    return lib.acosh(x)


def _real_atanh(lib, x):
    if abs(x) >= 1:
        raise Undefined("atanh of a number outside (-1, 1)")
    return lib.atanh(x)


def _real_atan2(lib, y, x):
    if x == 0 and y == 0:
        raise Undefined("atan2(0, 0)")
    return lib.atan2(y, x)


def _log(x, base=None):
    return sympy.log(x) if base is None else sympy.log(x, base)


def _op(name):
    return rf"\operatorname{{{name}}}"


_HALF_PI = "an odd multiple of pi/2"
_TABLE = [
    # sen: sine in Spanish and Portuguese (Mathpix writes \operatorname{sen}, babel-spanish has \sen)
    Function("sin", sympy.sin, aliases=("sen",), sympy_func=sympy.sin, latex=r"\sin", commands=("sin", "sen"),
             arb=lambda x: x.sin(), real=lambda lib, x: lib.sin(x)),
    Function("cos", sympy.cos, sympy_func=sympy.cos, latex=r"\cos", commands=("cos",),
             arb=lambda x: x.cos(), real=lambda lib, x: lib.cos(x)),
    Function("tan", sympy.tan, aliases=("tg",), sympy_func=sympy.tan, latex=r"\tan", commands=("tan", "tg"),
             arb=lambda x: x.sin() * _inverse(x.cos(), f"tan at {_HALF_PI}"),
             real=lambda lib, x: lib.sin(x) * _real_inverse(lib.cos(x), f"tan at {_HALF_PI}")),
    Function("cot", sympy.cot, aliases=("ctg", "cotg", "cotan"), sympy_func=sympy.cot, latex=r"\cot",
             commands=("cot", "ctg", "cotg"),
             arb=lambda x: x.cos() * _inverse(x.sin(), "cot at a multiple of pi"),
             real=lambda lib, x: lib.cos(x) * _real_inverse(lib.sin(x), "cot at a multiple of pi")),
    Function("sec", sympy.sec, sympy_func=sympy.sec, latex=r"\sec", commands=("sec",),
             arb=lambda x: _inverse(x.cos(), f"sec at {_HALF_PI}"),
             real=lambda lib, x: _real_inverse(lib.cos(x), f"sec at {_HALF_PI}")),
    Function("csc", sympy.csc, aliases=("cosec",), sympy_func=sympy.csc, latex=r"\csc", commands=("csc",),
             arb=lambda x: _inverse(x.sin(), "csc at a multiple of pi"),
             real=lambda lib, x: _real_inverse(lib.sin(x), "csc at a multiple of pi")),
    Function("asin", sympy.asin, aliases=("arcsin", "arcsen"), sympy_func=sympy.asin, latex=_op("asin"),
             commands=("arcsin",), arb=lambda x: _arb_unit(x, "asin").asin(),
             real=lambda lib, x: lib.asin(_real_unit(x, "asin"))),
    Function("acos", sympy.acos, aliases=("arccos",), sympy_func=sympy.acos, latex=_op("acos"),
             commands=("arccos",), arb=lambda x: _arb_unit(x, "acos").acos(),
             real=lambda lib, x: lib.acos(_real_unit(x, "acos"))),
    Function("atan", sympy.atan, aliases=("arctan", "arctg"), sympy_func=sympy.atan, latex=_op("atan"),
             commands=("arctan", "arctg"), arb=lambda x: x.atan(), real=lambda lib, x: lib.atan(x)),
    Function("atan2", sympy.atan2, 2, 2, aliases=("arctan2",), sympy_func=sympy.atan2,
             latex=r"\operatorname{atan_{2}}", dimension="same_args", arb=_arb_atan2, real=_real_atan2),
    Function("sinh", sympy.sinh, aliases=("senh",), sympy_func=sympy.sinh, latex=r"\sinh", commands=("sinh", "sh"),
             arb=lambda x: x.sinh(), real=lambda lib, x: lib.sinh(x)),
    Function("cosh", sympy.cosh, sympy_func=sympy.cosh, latex=r"\cosh", commands=("cosh", "ch"),
             arb=lambda x: x.cosh(), real=lambda lib, x: lib.cosh(x)),
    Function("tanh", sympy.tanh, sympy_func=sympy.tanh, latex=r"\tanh", commands=("tanh", "th"),
             arb=lambda x: x.tanh(), real=lambda lib, x: lib.tanh(x)),
    Function("coth", sympy.coth, sympy_func=sympy.coth, latex=r"\coth", commands=("coth",),
             arb=lambda x: x.cosh() * _inverse(x.sinh(), "coth at 0"),
             real=lambda lib, x: lib.cosh(x) * _real_inverse(lib.sinh(x), "coth at 0")),
    Function("sech", sympy.sech, sympy_func=sympy.sech, latex=_op("sech"),
             arb=lambda x: 1 / x.cosh(), real=lambda lib, x: 1 / lib.cosh(x)),
    Function("csch", sympy.csch, aliases=("cosech",), sympy_func=sympy.csch, latex=_op("csch"),
             arb=lambda x: _inverse(x.sinh(), "csch at 0"),
             real=lambda lib, x: _real_inverse(lib.sinh(x), "csch at 0")),
    Function("asinh", sympy.asinh, aliases=("arsinh", "arcsinh"), sympy_func=sympy.asinh, latex=_op("asinh"),
             arb=lambda x: x.asinh(), real=lambda lib, x: lib.asinh(x)),
    Function("acosh", sympy.acosh, aliases=("arcosh", "arccosh"), sympy_func=sympy.acosh, latex=_op("acosh"),
             arb=_arb_acosh, real=_real_acosh),
    Function("atanh", sympy.atanh, aliases=("artanh", "arctanh"), sympy_func=sympy.atanh, latex=_op("atanh"),
             arb=_arb_atanh, real=_real_atanh),
    Function("exp", sympy.exp, sympy_func=sympy.exp, latex=r"\exp", commands=("exp",),
             arb=lambda x: x.exp(), real=lambda lib, x: lib.exp(x)),
    Function("log", _log, 1, 2, aliases=("ln",), sympy_func=sympy.log, latex=r"\log", commands=("log", "ln"),
             arb=_arb_log, real=_real_log),
    # log10(x) is log(x)/log(10) in sympy: no function class of its own, nothing to evaluate.
    Function("log10", lambda x: sympy.log(x, 10), aliases=("lg",), commands=("lg",)),  # KaTeX's \lg, ISO's lg
    Function("log2", lambda x: sympy.log(x, 2), commands=("lb",)),  # ISO 80000-2's lb, KaTeX's \lb
    Function("sqrt", None),
    # The real cube root, defined for negative numbers too (x**(1/3) is not, over the reals); built
    # from sign and abs, so the evaluators and the dimension rule of a power apply as they are.
    Function("cbrt", lambda x: sympy.sign(x) * sympy.Abs(x) ** sympy.Rational(1, 3),
             aliases=("cuberoot",)),  # Mathematica's CubeRoot[x]
    # pow(x, y) (Python, C, JavaScript's Math.pow, Excel's POWER, Mathematica's Power[x, y]) is x^y, and
    # surd(x, n) (Maple, Mathematica's Surd[x, n], GeoGebra's nroot(x, n), MATLAB's nthroot(x, n)) the real
    # n-th root: the parser builds both, as it builds sqrt, so that the power is size-checked and its real
    # domain kept.
    Function("pow", None, 2, 2, aliases=("power",)),
    Function("surd", None, 2, 2, aliases=("nroot", "nthroot")),
    Function("abs", sympy.Abs, aliases=("Abs",), sympy_func=sympy.Abs, text="Abs", dimension="same",
             arb=lambda x: abs(x), real=lambda lib, x: abs(x)),
    Function("sign", sympy.sign, aliases=("sgn",), sympy_func=sympy.sign, latex=_op("sgn"), dimension="any",
             arb=_arb_sign, real=lambda lib, x: float((x > 0) - (x < 0))),
]

#: Canonical name -> Function, in the order above.
REGISTRY: dict[str, Function] = {
    f.name: Function(**{**f.__dict__, "text": f.text or f.name}) for f in _TABLE
}

#: Every spelling (name or alias) -> Function.  ``sqrt`` has no builder: the parser routes it
#: through the guarded power so ``sqrt(10^999)`` is size-checked like any power.
FUNCTIONS: dict[str, Function] = {}
for _function in REGISTRY.values():
    for _spelling in (_function.name, *_function.aliases):
        FUNCTIONS[_spelling] = _function

#: sympy function class -> Function (what the evaluator and the dimension checker look up).
BY_SYMPY: dict[object, Function] = {f.sympy_func: f for f in REGISTRY.values() if f.sympy_func is not None}

#: ``sin^-1(x)`` means the inverse function, not 1/sin(x).
INVERSES = {"sin": "asin", "cos": "acos", "tan": "atan", "sinh": "asinh", "cosh": "acosh", "tanh": "atanh"}

#: Constants by name; a namespace variable of the same name wins.
CONSTANTS = {"pi": sympy.pi, "e": sympy.E, "E": sympy.E}

# Aliases worth listing in a hint (the ones people type); the others only clutter it.
_LISTED_ALIASES = {"ln", "arcsin", "arccos", "arctan", "sgn", "cosec", "tg", "ctg", "arctg"}


def function_names() -> list[str]:
    """Names of the allowed functions, for hints.

    Examples
    --------
    >>> "sin" in function_names() and "asinh" in function_names() and "factorial" not in function_names()
    True
    """
    names = set(REGISTRY) | _LISTED_ALIASES
    return sorted(names)


def latex_commands() -> dict[str, str]:
    r"""LaTeX command -> canonical function name (``arcsin`` -> ``asin``), for the LaTeX input.

    Examples
    --------
    >>> latex_commands()["arcsin"], latex_commands()["ln"]
    ('asin', 'log')
    """
    return {command: f.name for f in REGISTRY.values() for command in f.commands}
