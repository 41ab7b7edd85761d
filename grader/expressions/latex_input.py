r"""The subset of LaTeX a student may type (or paste from a previewer).

Supported: ``\frac{a}{b}`` (``\dfrac``, ``\tfrac``), ``\sqrt{x}``, ``\sqrt[n]{x}``,
``\cdot``, ``\times``, ``\left( \right)`` (and the sized ``\bigl( \Bigr)``), ``\sin`` and friends, Greek letters
``\theta``, ``\dot{\theta}``, ``\ddot{\theta}``, ``^{...}``, ``_{...}``, ``{}``
grouping, ``\pi``, spacing commands and ``\mathrm{...}`` around names, degrees after a number
(``30^\circ``, ``30\degree``), and ``$ $``, ``\( \)`` or ``\[ \]`` around it all; equations in
``\begin{aligned}`` … ``\end{aligned}`` (and align, gather, split, equation) with ``&`` and ``\\``
(read by :mod:`.tokens`).
``\frac`` reads an unbraced argument as LaTeX does, one digit, letter or command: ``\frac12``, ``\frac gl``,
``\frac\pi2`` (a command's name ends at its last letter, so that is π/2; elsewhere ``\omega2`` is the name
ω2, as ``ω2`` is).
Time derivatives as ``\frac{d\theta}{dt}``, ``\frac{\mathrm{d}^2x}{\mathrm{d}t^2}``,
``\frac{d}{dt}\theta`` and ``\frac d{dt}\theta`` are read by :mod:`.leibniz`.
``\left.`` and ``\left/`` (no bracket) are refused by name.
Anything else (``\int``, ``\sum``, ``\partial``) is refused by name.
"""

from __future__ import annotations

import re

from .errors import ExpressionError
from .functions import latex_commands
from .names import GREEK_LETTERS

__all__ = ["classify_command", "subscript_text", "GREEK_COMMANDS", "FUNCTION_COMMANDS"]

#: \theta -> theta; the var- forms are the same letters to a grader.
GREEK_COMMANDS = {name: name for name, latex in GREEK_LETTERS.items() if latex.startswith("\\")}
GREEK_COMMANDS.update({"varphi": "phi", "vartheta": "theta", "varepsilon": "epsilon",
                       "varrho": "rho", "varsigma": "sigma", "varpi": "pi",
                       "ell": "l"})  # \ell is how statements write a length l

#: \sin -> sin, \arcsin -> asin (from the function registry).
FUNCTION_COMMANDS = latex_commands()

_OPERATORS = {"cdot": "*", "times": "*", "ast": "*", "div": "/"}
# \big( \Bigm| \bigg): a bracket's size, nothing to a grader; the l and r forms say which side it is.
_SIZES = {f"{size}{side}": "space" if side in ("", "m") else f"big{side}"
          for size in ("big", "Big", "bigg", "Bigg") for side in ("", "l", "r", "m")}
_SPACING = {"quad", "qquad", "displaystyle", "textstyle", "scriptstyle", "limits",
            *(name for name, value in _SIZES.items() if value == "space")}
_STRUCTURE = {"frac": "frac", "dfrac": "frac", "tfrac": "frac", "sqrt": "sqrt",
              "dot": "dot", "ddot": "ddot", "left": "left", "right": "right",
              "lvert": "lvert", "rvert": "rvert", "vert": "vert", "mid": "vert",
              **{name: value for name, value in _SIZES.items() if value != "space"}}
_WRAPPERS = {"mathrm", "text", "mathit", "operatorname", "rm", "mathbf", "textrm"}


def classify_command(name: str, position: int) -> tuple[str, str]:
    r"""What a ``\name`` command is: ``(kind, value)``.

    kind is ``"greek"`` (value: letter name), ``"function"`` (value: function
    name), ``"op"``, ``"space"``, ``"structure"`` (frac, sqrt, dot, ddot, left,
    right) or ``"wrapper"`` (``\mathrm`` and friends, whose braced text is a name).

    Examples
    --------
    >>> classify_command("theta", 0), classify_command("arcsin", 0), classify_command("cdot", 0)
    (('greek', 'theta'), ('function', 'asin'), ('op', '*'))
    """
    if name in GREEK_COMMANDS:
        return "greek", GREEK_COMMANDS[name]
    if name in FUNCTION_COMMANDS:
        return "function", FUNCTION_COMMANDS[name]
    if name in _OPERATORS:
        return "op", _OPERATORS[name]
    if name in _SPACING:
        return "space", ""
    if name in _STRUCTURE:
        return "structure", _STRUCTURE[name]
    if name in _WRAPPERS:
        return "wrapper", name
    raise ExpressionError(f"the LaTeX command \\{name} is not supported", position, "unsupported_function",
                          r"use + - * / ^, \frac, \sqrt and functions such as \sin")


_WRAPPED = re.compile(r"\\(?:mathrm|text|mathit|rm|textrm|mathbf|operatorname)\s*\{([^{}]*)\}")
_COMMAND = re.compile(r"\\([A-Za-z]+)")
_SUBSCRIPT = re.compile(r"^[A-Za-z0-9_]+$")


def subscript_text(content: str, position: int) -> str:
    r"""A braced subscript as name text: ``{1}`` -> ``1``, ``{roll,s}`` -> ``roll_s``.

    Examples
    --------
    >>> subscript_text(r"\mathrm{roll},s", 0), subscript_text(r"\theta", 0)
    ('roll_s', 'theta')
    """
    text = _WRAPPED.sub(r"\1", content)
    text = _COMMAND.sub(lambda m: GREEK_COMMANDS.get(m.group(1), m.group(0)), text)
    text = re.sub(r"\s*,\s*", "_", text.strip())
    if not _SUBSCRIPT.match(text):
        raise ExpressionError(f"cannot read the subscript '{content}'", position, "syntax",
                              "a subscript holds letters and digits, as in m_{1}")
    return text
