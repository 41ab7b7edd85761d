"""The whitelist of functions and constants a text may use.

Nothing outside these tables can be called: the parser looks a name up here and
builds the sympy object itself, so no text ever reaches sympy's own parser.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import sympy

__all__ = ["Function", "FUNCTIONS", "INVERSES", "CONSTANTS", "function_names"]


@dataclass(frozen=True)
class Function:
    """A callable the grammar allows: its sympy builder and how many arguments it takes."""

    name: str
    build: Callable
    min_args: int = 1
    max_args: int = 1


def _log(x, base=None):
    return sympy.log(x) if base is None else sympy.log(x, base)


_TABLE = [
    Function("sin", sympy.sin), Function("cos", sympy.cos), Function("tan", sympy.tan),
    Function("cot", sympy.cot), Function("sec", sympy.sec), Function("csc", sympy.csc),
    Function("asin", sympy.asin), Function("acos", sympy.acos), Function("atan", sympy.atan),
    Function("atan2", sympy.atan2, 2, 2),
    Function("sinh", sympy.sinh), Function("cosh", sympy.cosh), Function("tanh", sympy.tanh),
    Function("exp", sympy.exp), Function("log", _log, 1, 2),
    Function("sqrt", None), Function("abs", sympy.Abs), Function("sign", sympy.sign),
]

#: name -> Function.  ``sqrt`` has no builder here: the parser routes it through
#: the guarded power so ``sqrt(10^999)`` is size-checked like any power.
FUNCTIONS: dict[str, Function] = {f.name: f for f in _TABLE}

# Other spellings of the same functions; ``Abs`` is how sympy prints abs, so
# ``str(expr)`` reads back.
_ALIASES = {"ln": "log", "Abs": "abs", "arcsin": "asin", "arccos": "acos", "arctan": "atan"}
for _alias, _name in _ALIASES.items():
    FUNCTIONS[_alias] = FUNCTIONS[_name]

#: ``sin^-1(x)`` means the inverse function, not 1/sin(x).
INVERSES = {"sin": "asin", "cos": "acos", "tan": "atan"}

#: Constants by name; a namespace variable of the same name wins.
CONSTANTS = {"pi": sympy.pi, "e": sympy.E, "E": sympy.E}


def function_names() -> list[str]:
    """Names of the allowed functions, for hints.

    Examples
    --------
    >>> "sin" in function_names() and "factorial" not in function_names()
    True
    """
    return sorted(name for name in FUNCTIONS if name not in _ALIASES or name == "ln")
