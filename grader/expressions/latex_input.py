r"""The subset of LaTeX a student may type (or paste from a previewer).

Supported: ``\frac{a}{b}`` (``\dfrac``, ``\tfrac``, ``\cfrac``), ``\sqrt{x}``, ``\sqrt[n]{x}``,
``\cdot``, ``\times``, ``\bullet``, ``\left( \right)`` (MathLive's ``\mleft( \mright)``, the sized
``\bigl( \Bigr)``, ``\left\lvert``, ``\lbrace``), ``\sin`` and friends (``\operatorname{sen}``, ``\operatorname{tg}``),
Greek letters ``\theta`` (``\uptheta``), ``\dot{\theta}``, ``\ddot{\theta}`` (``\overset{\cdot}{\theta}``),
``^{...}``, ``_{...}``, ``{}`` grouping, ``\pi``, ``\exponentialE``, spacing commands and ``~``, and
``\mathrm{...}`` (``\boldsymbol``, ``\mathbf``, ``\text`` …) around names, degrees after a number
(``30^\circ``, ``30\degree``), and ``$ $``, ``\( \)`` or ``\[ \]`` around it all; equations in
``\begin{aligned}`` … ``\end{aligned}`` (and align, gather, split, equation, alignat) with ``&`` and ``\\``,
``&=`` anywhere, and ``\Rightarrow`` (``\implies``, ``\therefore``, ``⇒``) before the answer
(read by :mod:`.tokens`). What editors put in a wrapper besides a name is read by `wrapped_text`:
``\text{.}`` ends the sentence, ``\text{ and }`` joins two equations, a unit (``\mathrm{~N}``) or
words are refused by name.
``\frac`` reads an unbraced argument as LaTeX does, one digit, letter or command: ``\frac12``, ``\frac gl``,
``\frac\pi2`` (a command's name ends at its last letter, so that is π/2; elsewhere ``\omega2`` is the name
ω2, as ``ω2`` is).
Time derivatives as ``\frac{d\theta}{dt}``, ``\frac{\mathrm{d}^2x}{\mathrm{d}t^2}``,
``\frac{d}{dt}\theta`` and ``\frac d{dt}\theta`` are read by :mod:`.leibniz`.
``\left.`` and ``\left/`` (no bracket) are refused by name, as are relations that are no equation
(``\approx``, ``\equiv``, ``\leq``), MathLive's empty ``\placeholder{}``, norms and vectors.
Anything else (``\int``, ``\sum``, ``\partial``) is refused by name.
"""

from __future__ import annotations

import re

from .errors import ExpressionError
from .functions import latex_commands
from .names import GREEK_LETTERS, UNIT_SYMBOLS

__all__ = ["classify_command", "subscript_text", "wrapped_text", "GREEK_COMMANDS", "FUNCTION_COMMANDS",
           "WRAPPER_COMMANDS"]

#: \theta -> theta; the var- forms are the same letters to a grader.
GREEK_COMMANDS = {name: name for name, latex in GREEK_LETTERS.items() if latex.startswith("\\")}
GREEK_COMMANDS.update({"varphi": "phi", "vartheta": "theta", "varepsilon": "epsilon",
                       "varrho": "rho", "varsigma": "sigma", "varpi": "pi",
                       "ell": "l"})  # \ell is how statements write a length l
# upgreek's upright letters (\uppi, \uptheta): the same letters
GREEK_COMMANDS.update({f"up{name}": letter for name, letter in list(GREEK_COMMANDS.items()) if name.islower()})

#: \sin -> sin, \arcsin -> asin (from the function registry).
FUNCTION_COMMANDS = latex_commands()

# \bullet: the dot some editors and OCR put for a product, as • and ∙ are read in Unicode
_OPERATORS = {"cdot": "*", "times": "*", "ast": "*", "bullet": "*", "div": "/"}
# \big( \Bigm| \bigg): a bracket's size, nothing to a grader; the l and r forms say which side it is.
_SIZES = {f"{size}{side}": "space" if side in ("", "m") else f"big{side}"
          for size in ("big", "Big", "bigg", "Bigg") for side in ("", "l", "r", "m")}
_SPACING = {"quad", "qquad", "displaystyle", "textstyle", "scriptstyle", "limits", "nonumber", "notag",
            "enspace", "thinspace", "medspace", "thickspace", "negthinspace", "negmedspace", "negthickspace",
            "strut", "mathstrut", "nolimits", "allowbreak", "nobreak",
            *(name for name, value in _SIZES.items() if value == "space")}
# \cfrac (Mathpix's continued-fraction form) is a fraction; MathLive writes \mleft( \mright) for \left( \right).
_STRUCTURE = {"frac": "frac", "dfrac": "frac", "tfrac": "frac", "cfrac": "frac", "sqrt": "sqrt",
              "dot": "dot", "ddot": "ddot", "left": "left", "right": "right", "mleft": "left", "mright": "right",
              "lvert": "lvert", "rvert": "rvert", "vert": "vert", "mid": "vert",
              "lbrace": "lbrace", "rbrace": "rbrace", "lbrack": "lbrack", "rbrack": "rbrack",
              "lparen": "lparen", "rparen": "rparen",  # MathLive's \lparen \rparen
              "lgroup": "lgroup", "rgroup": "rgroup",  # TeX's \lgroup x \rgroup: round brackets
              **{name: value for name, value in _SIZES.items() if value != "space"}}
# Commands whose braced text is a name in another font: \boldsymbol{\theta} is θ, as \mathbf{m} is m.
_WRAPPERS = {"mathrm", "text", "mathit", "operatorname", "rm", "mathbf", "textrm", "boldsymbol", "bm",
             "mathsf", "mathnormal", "textit", "textbf", "textnormal", "mathup", "symbf", "symit", "symup",
             "pmb", "mbox"}
#: The fonts and boxes around a name (\mathrm{max}, \text{N}): what they hold is the name.
WRAPPER_COMMANDS = frozenset(_WRAPPERS)
#: MathLive's \exponentialE and \differentialD are the letters e and d (\frac{\differentialD x}{\differentialD t}).
LETTER_COMMANDS = {"exponentialE": "e", "differentialD": "d"}
# How a derivation's last line starts: "⇒ θ̈ = …"; dropped at the start of the answer (see tokens.py).
IMPLICATIONS = {"Rightarrow", "implies", "Longrightarrow", "therefore", "Leftrightarrow", "iff",
                "Longleftrightarrow"}

_EQUALS = "write = between the two sides of an equation"


def _relation(name: str, meaning: str) -> tuple[str, str]:
    return f"'\\{name}' ({meaning}) is not an equation", _EQUALS


#: Commands refused with what they are and what to write instead.
_REFUSED = {
    **{name: _relation(name, "approximately equal") for name in ("approx", "simeq", "thickapprox")},
    "sim": _relation("sim", "of the order of"),
    "cong": _relation("cong", "congruent"),
    "propto": _relation("propto", "proportional to"),
    "equiv": _relation("equiv", "identical to, or defined as"),
    "coloneqq": _relation("coloneqq", "defined as"),
    **{name: (f"'\\{name}' (not equal) is not an equation", "give an expression, or an equation with =")
       for name in ("neq", "ne")},
    **{name: (f"'\\{name}' is an inequality: inequalities are not supported",
              "give an expression, or an equation with =")
       for name in ("le", "leq", "leqslant", "ge", "geq", "geqslant", "lt", "gt", "ll", "gg")},
    **{name: (f"'\\{name}' is an arrow (a rule, or 'tends to'), not an equation", _EQUALS + ", as in x = 2")
       for name in ("to", "rightarrow", "longrightarrow", "mapsto", "longmapsto")},
    # MathLive's empty box, left where the student did not type the exponent, numerator, ...
    "placeholder": ("an empty box (\\placeholder) is left in the answer", "fill the box in, or delete it"),
    **{name: (f"'\\{name}' (an ellipsis) is not part of a formula", "write the whole formula, without '…'")
       for name in ("cdots", "ldots", "dots", "dotsb", "dotsm", "dotsc")},
    "prime": ("'\\prime' can only follow a variable name", "write \\theta^{\\prime}, or \\ddot{\\theta} for θ̈"),
    "over": ("'\\over' (TeX's fraction) is not supported", "write \\frac{a}{b}, or a/b"),
    "imaginaryI": ("complex numbers are not part of these answers", "write the answer with real quantities"),
    **{name: ("'‖…‖' (a norm) is not supported", "write |x| for the absolute value of a number")
       for name in ("Vert", "lVert", "rVert")},
    **{name: (f"'\\{name}{{…}}' (a vector) is not supported",
              "write the component or the magnitude as a plain symbol, as in T or F_x")
       for name in ("vec", "overrightarrow")},
}


def classify_command(name: str, position: int) -> tuple[str, str]:
    r"""What a ``\name`` command is: ``(kind, value)``.

    kind is ``"greek"`` (value: letter name), ``"function"`` (value: function
    name), ``"op"``, ``"space"``, ``"structure"`` (frac, sqrt, dot, ddot, left,
    right, ...), ``"wrapper"`` (``\mathrm`` and friends, whose braced text is a name),
    ``"letter"`` (MathLive's ``\exponentialE``, ``\differentialD``) or ``"implication"``
    (``\Rightarrow``). Relations (``\approx``), ``\placeholder`` and other commands are
    refused, naming them.

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
    if name in LETTER_COMMANDS:
        return "letter", LETTER_COMMANDS[name]
    if name in IMPLICATIONS:
        return "implication", name
    if name in _REFUSED:
        message, hint = _REFUSED[name]
        raise ExpressionError(message, position, "unsupported_function" if name != "placeholder" else "syntax", hint)
    glued = _glued_commands(name)
    if glued is not None:  # \cdotg, \costheta, \thetam, \thetadot: a command with the next letters glued on
        raise ExpressionError(f"the LaTeX command \\{name} is not supported: LaTeX reads every letter after a "
                              "backslash as one name", position, "unsupported_function", glued)
    raise ExpressionError(f"the LaTeX command \\{name} is not supported", position, "unsupported_function",
                          r"use + - * / ^, \frac, \sqrt and functions such as \sin")


def _glued_commands(name: str) -> str | None:
    r"""What to write for a product, a function or a Greek letter with letters glued on (``\cdotg``: ``\cdot g``;
    ``\costheta``: ``\cos\theta``; ``\thetadot``: ``\dot{\theta}``), or None when ``name`` is not one: the rest
    must be a Greek letter or one or two letters (a variable), so that ``\leftarrow`` or ``\bigcirc`` get no such
    reading, and a function then h is a hyperbolic one (``\sech``), not sec·h."""
    for marks in ("ddot", "dot"):
        if name.endswith(marks) and name[:-len(marks)] in GREEK_COMMANDS:
            return f"write \\{marks}{{\\{name[:-len(marks)]}}} for its time derivative"
    for k in range(len(name) - 1, 1, -1):
        known, rest = name[:k], name[k:]
        if not (known in _OPERATORS or known in FUNCTION_COMMANDS or known in GREEK_COMMANDS):
            continue
        if rest in GREEK_COMMANDS:
            return f"write \\{known}\\{rest}"
        if len(rest) <= 2 and not (known in FUNCTION_COMMANDS and rest == "h"):
            return f"write \\{known} {rest}, with a space after \\{known}"
        return None
    return None


_WRAPPED = re.compile(r"\\(?:" + "|".join(sorted(_WRAPPERS, key=len, reverse=True)) + r")\s*\{([^{}]*)\}")
_COMMAND = re.compile(r"\\([A-Za-z]+)")
_SUBSCRIPT = re.compile(r"^[A-Za-z0-9_]+$")


def subscript_text(content: str, position: int) -> str:
    r"""A braced subscript as name text: ``{1}`` -> ``1``, ``{roll,s}`` -> ``roll_s``.

    Examples
    --------
    >>> subscript_text(r"\mathrm{roll},s", 0), subscript_text(r"\theta", 0)
    ('roll_s', 'theta')
    """
    if "\\placeholder" in content:  # m_{\placeholder{}}: MathLive's empty box
        message, hint = _REFUSED["placeholder"]
        raise ExpressionError(message, position, "syntax", hint)
    if not content.strip():  # MathQuill leaves _{} where a subscript box was opened and not filled
        raise ExpressionError("the subscript is empty", position, "syntax",
                              "type the subscript inside the braces, as in m_{1}, or delete the '_{}'")
    text = _WRAPPED.sub(r"\1", content)
    # \theta -> theta, and \mathrm{\cos} (Word) -> cos
    text = _COMMAND.sub(lambda m: GREEK_COMMANDS.get(m.group(1), FUNCTION_COMMANDS.get(m.group(1), m.group(0))), text)
    text = re.sub(r"\s*,\s*", "_", text.strip())
    if not _SUBSCRIPT.match(text):
        raise ExpressionError(f"cannot read the subscript '{content}'", position, "syntax",
                              "a subscript holds letters and digits, as in m_{1}")
    return text


# Spacing inside a wrapper: \mathrm{~N} (Mathpix), \text{ N}, \mathrm{kg\,m}.
_WRAPPED_SPACE = re.compile(r"~|\\[,;:! ]|\\q?quad(?![A-Za-z])")


def _is_unit(text: str) -> bool:
    """Whether a wrapper's text is only unit symbols, with / ^ - . digits, brackets and products between
    them: ``N``, ``m/s^2``, ``(N)``, ``kg\\cdot m\\cdot s^{-2}``."""
    if not set(_COMMAND.findall(text)) <= {"cdot", "times", "mathrm", "text"}:
        return False
    plain = _COMMAND.sub(" ", text).strip("()[] ")
    words = re.findall(r"[A-Za-z]+", plain)
    return bool(words) and all(word in UNIT_SYMBOLS for word in words) \
        and not re.search(r"[^A-Za-z0-9/^{}\-.\s]", plain)


def wrapped_text(shown: str, content: str, position: int) -> tuple[str, str]:
    r"""What a wrapper's braced text is: ``(kind, value)``.

    ``("name", text)`` for a name (``\mathrm{m}``, ``\text{cos}``, ``\boldsymbol{\theta}``, what
    `subscript_text` reads); ``("space", "")`` for nothing but spacing (``\text{ }``);
    ``("punctuation", ".")`` for a full stop, comma or semicolon alone (``\text{.}``); ``("number", "2")``
    for digits (``\mathrm{2}``); ``("and", "")`` for the word and between two equations. A unit
    (``\mathrm{rad/s^2}``, ``\mathrm{~m}``) or words (``\text{(equation of motion)}``) are refused, naming them.

    Examples
    --------
    >>> wrapped_text(r"\mathrm{m}", "m", 0), wrapped_text(r"\text{ .}", " .", 0)
    (('name', 'm'), ('punctuation', '.'))
    >>> wrapped_text(r"\mathrm{~m}", "~m", 0)
    Traceback (most recent call last):
    ...
    grader.expressions.errors.ExpressionError: '\mathrm{~m}' reads as a unit: units are not part of the answer ...
    """
    spaced = _WRAPPED_SPACE.sub(" ", content)
    plain = spaced.strip()
    if not plain:
        return "space", ""
    if plain in (".", ",", ";"):
        return "punctuation", plain
    if plain.isascii() and plain.isdigit():  # \mathrm{2}: upright digits, as some editors set every symbol
        return "number", plain
    if plain.lower() == "and":
        return "and", ""
    unit = _is_unit(plain)
    # \mathrm{~m}, \text{ kg}: the space a unit is set off with (Mathpix), so never the variable m
    spaced_unit = unit and spaced[:1].isspace()
    if (_SUBSCRIPT.match(plain) or plain.startswith("\\")) and not spaced_unit:
        return "name", subscript_text(plain, position)
    if unit:
        raise ExpressionError(f"'{shown}' reads as a unit: units are not part of the answer", position,
                              "unknown_name", f"write the answer in the problem's symbols and delete '{shown}'")
    raise ExpressionError(f"'{shown}' is text, not part of a formula", position, "syntax",
                          "delete it, and give only the formula")
