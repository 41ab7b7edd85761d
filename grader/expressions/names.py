"""Variable names: how they look in LaTeX and how typed names resolve to them.

Canonical names are plain identifiers: ``theta``, ``thetadot``, ``thetaddot``,
``m1``, ``lambda_surface``, ``Q_roll_s``.  Students may type the same variable
as ``θ``, ``theta_dot``, ``θ̇``, ``theta'``, ``dot(theta)``, ``m_1``, ``m_{1}`` or
glue names together (``mg``); :func:`resolve_name` maps all of these to one
namespace symbol, or explains why it cannot.
"""

from __future__ import annotations

import difflib
import keyword
import re
from dataclasses import dataclass, field
from functools import lru_cache
from typing import TYPE_CHECKING

from .errors import ExpressionError
from .functions import CONSTANTS, FUNCTIONS, function_names
from .unicode_input import GREEK_CHARS

if TYPE_CHECKING:  # pragma: no cover
    from .variables import Namespace

__all__ = ["GREEK_LETTERS", "latex_name", "Resolved", "resolve_name", "derivative_name"]

_GREEK_LOWER = ("alpha beta gamma delta epsilon zeta eta theta iota kappa lambda mu nu xi "
                "omicron pi rho sigma tau upsilon phi chi psi omega").split()
# Capitals that look like Latin letters have no LaTeX command of their own.
_GREEK_UPPER = {
    "Alpha": "A", "Beta": "B", "Gamma": r"\Gamma", "Delta": r"\Delta", "Epsilon": "E",
    "Zeta": "Z", "Eta": "H", "Theta": r"\Theta", "Iota": "I", "Kappa": "K",
    "Lambda": r"\Lambda", "Mu": "M", "Nu": "N", "Xi": r"\Xi", "Omicron": "O", "Pi": r"\Pi",
    "Rho": "P", "Sigma": r"\Sigma", "Tau": "T", "Upsilon": r"\Upsilon", "Phi": r"\Phi",
    "Chi": "X", "Psi": r"\Psi", "Omega": r"\Omega",
}

#: Greek letter name -> LaTeX.
GREEK_LETTERS: dict[str, str] = {name: "\\" + name for name in _GREEK_LOWER}
GREEK_LETTERS["omicron"] = "o"
GREEK_LETTERS.update(_GREEK_UPPER)

_TRAILING_DIGITS = re.compile(r"^(.*?[A-Za-z])(\d+)$")


def _latex_word(word: str) -> str:
    if word in GREEK_LETTERS:
        return GREEK_LETTERS[word]
    if len(word) == 1 or word.isdigit():
        return word
    return r"\mathrm{" + word + "}"


def latex_name(name: str) -> str:
    r"""LaTeX for a canonical variable name.

    A trailing ``dot``/``ddot`` is a time derivative, trailing digits and
    ``_parts`` are subscripts (words upright, several parts comma-separated).

    Examples
    --------
    >>> latex_name("thetadot"), latex_name("m1"), latex_name("Omega")
    ('\\dot{\\theta}', 'm_{1}', '\\Omega')
    >>> latex_name("lambda_surface"), latex_name("Q_roll_s")
    ('\\lambda_{\\mathrm{surface}}', 'Q_{\\mathrm{roll},s}')
    """
    head, *subs = name.split("_")
    subs = [s for s in subs if s]
    order = 0
    if head.endswith("ddot") and len(head) > 4:
        head, order = head[:-4], 2
    elif head.endswith("dot") and len(head) > 3:
        head, order = head[:-3], 1
    match = _TRAILING_DIGITS.match(head)
    if match:
        head = match.group(1)
        subs.insert(0, match.group(2))
    text = GREEK_LETTERS.get(head, head)
    if order:
        text = ("\\dot{" if order == 1 else "\\ddot{") + text + "}"
    if subs:
        text += "_{" + ",".join(_latex_word(s) for s in subs) + "}"
    return text


def derivative_name(base: str, order: int) -> str:
    """Canonical name of the ``order``-th time derivative of ``base``.

    Examples
    --------
    >>> derivative_name("theta", 1), derivative_name("thetadot", 1), derivative_name("x", 2)
    ('thetadot', 'thetaddot', 'xddot')
    """
    if base.endswith("ddot"):
        base, order = base[:-4], order + 2
    elif base.endswith("dot"):
        base, order = base[:-3], order + 1
    return base + {0: "", 1: "dot", 2: "ddot"}.get(order, "d" * order + "ot")


@dataclass
class Resolved:
    """What a typed name means.

    ``kind`` is ``"symbol"`` / ``"constant"`` (``value`` is a sympy object),
    ``"function"`` (``value`` is the whitelisted name) or ``"split"`` (``value``
    lists the known names the text is made of, e.g. ``["m", "g"]``).
    """

    kind: str
    value: object
    notes: list[str] = field(default_factory=list)


_PYTHON_WORDS = set(keyword.kwlist) | {"eval", "exec", "open", "compile", "getattr", "globals",
                                       "locals", "os", "sys", "subprocess", "print", "input"}


def resolve_name(raw: str, ns: "Namespace", *, order: int = 0, typed: str | None = None,
                 position: int = 0, called: bool = False, before_power: bool = False) -> Resolved:
    """Resolve a typed identifier to a namespace symbol, constant, function or split.

    Parameters
    ----------
    raw : str
        The identifier with Greek letters spelled out (``θ`` -> ``theta``) and
        subscript braces removed (``m_{1}`` -> ``m_1``).
    ns : Namespace
        The variables the text may use.
    order : int
        Time-derivative order added by primes or accents (``θ̇`` -> 1).
    typed : str
        The identifier as typed, for messages.
    position : int
        Where it starts in the text, for errors.
    called : bool
        Whether ``(`` follows directly; an unknown called name is reported as
        an unsupported function.
    before_power : bool
        Whether ``^`` follows: ``ye^x`` is then y·e^x when y is declared and e is not (see
        :func:`_before_euler`).

    Examples
    --------
    >>> from grader.expressions import Namespace, Variable
    >>> ns = Namespace([Variable("theta", "angle", "real"), Variable("thetadot", "1/s", "real"),
    ...                 Variable("m", "mass", "positive"), Variable("g", "acceleration", "positive")])
    >>> resolve_name("theta_dot", ns).value
    thetadot
    >>> resolve_name("theta", ns, order=1).value
    thetadot
    >>> r = resolve_name("mg", ns); r.kind, r.value, r.notes
    ('split', ['m', 'g'], ["read 'mg' as m·g"])
    >>> r = resolve_name("me", ns, before_power=True); r.kind, r.value, r.notes
    ('split', ['m', 'e'], ["read 'me' as m·e"])
    """
    typed = typed if typed is not None else raw
    if len(typed) > 40:  # a 2000-letter "name" should not come back in full in the message
        typed = typed[:40] + "…"
    if order:
        try:
            return _resolve_derivative(raw, ns, order, typed, position)
        except ExpressionError:
            # mθ̇ is m·θ̇: a glued name whose last part carries the accent.
            parts = _split(raw, ns, typed, position)
            if not parts or parts[-1] in FUNCTIONS or parts[-1].isdigit():
                # m₁x'' (Word, Google Docs) is m₁·x'' when only x'' is declared, not x
                parts = _split_before_derivative(raw, ns, order, typed, position)
                if not parts:
                    raise
                return Resolved("split", parts, [f"read '{typed}' as {_reading(parts)}"])
            parts[-1] = _resolve_derivative(parts[-1], ns, order, typed, position).value.name
            return Resolved("split", parts, [f"read '{typed}' as {_reading(parts)}"])
    symbol = _lookup(raw, ns)
    if symbol is not None:
        return Resolved("symbol", symbol)
    logarithm = _logarithm(raw, typed, position, called)
    if logarithm is not None:
        return logarithm
    if raw in _PRODUCT_FIRST:
        parts = _variables_only(raw, ns)
        if parts:  # √(lg) with a length l and g declared is √(l·g), not √(log₁₀ g)
            return Resolved("split", parts, [f"read '{typed}' as {_reading(parts)}"])
        name = FUNCTIONS[raw].name
        return Resolved("function", name, [f"read '{typed}' as {_PRODUCT_FIRST[raw]}"])
    if raw in FUNCTIONS or raw.lower() in FUNCTIONS:
        return Resolved("function", FUNCTIONS[raw if raw in FUNCTIONS else raw.lower()].name)
    if raw == "Pi" and typed == "Pi":  # Mathematica's and Maple's π; a declared variable Pi (capital Π) was found above
        return Resolved("constant", CONSTANTS["pi"], [f"read '{typed}' as π"])
    if raw in CONSTANTS:
        notes = []
        if raw in ("e", "E"):
            notes.append(f"read '{typed}' as Euler's number e ≈ 2.718")
        return Resolved("constant", CONSTANTS[raw], notes)
    if raw.startswith("_"):
        raise ExpressionError(f"'{typed}' is not allowed in an expression", position,
                              "unsupported_function", "write a formula, not program code")
    if raw in WRITE_INSTEAD:
        # acot(k) or acot k with a variable a declared is the inverse cotangent the student meant, refused with
        # how to write it, not a·cot(k)
        _raise_unknown(raw, ns, typed, position, called)
    parts = _split(raw, ns, typed, position)
    if parts:
        return Resolved("split", parts, [f"read '{typed}' as {_reading(parts)}"])
    parts = _before_euler(raw, ns, typed, position) if before_power else None
    if parts:
        return Resolved("split", parts, [f"read '{typed}' as {_reading(parts)}"])
    if raw in _PYTHON_WORDS:
        raise ExpressionError(f"'{typed}' is not allowed in an expression", position,
                              "unsupported_function", "write a formula, not program code")
    _raise_unknown(raw, ns, typed, position, called)


#: Spellings of other traditions (tg for tan, lg for log₁₀) that are also products of one-letter
#: variables common in mechanics (t·g, l·g): a function only when the letters are not all declared.
_PRODUCT_FIRST = {"tg": "tan", "ctg": "cot", "cotg": "cot", "arctg": "arctan", "lg": "the logarithm to base 10",
                  "sen": "sin", "senh": "sinh"}  # sen: Spanish and Portuguese sine

_LOG_BASE = re.compile(r"^log_(\w+)$")


def _logarithm(raw: str, typed: str, position: int, called: bool) -> Resolved | None:
    """``log_2``, ``log_{10}``, ``log2(…)``: a logarithm to a base, or None for any other name.

    ``log2`` is the base-2 logarithm only when called directly (``log2(x)``, as in most
    programming languages); alone, ``τ log2`` is τ·log(2), as physics texts write ln 2.
    """
    if raw == "log2":
        if called:
            return Resolved("function", "log2", [f"read '{typed}(…)' as the logarithm to base 2"])
        return Resolved("split", ["log", "2"], [f"read '{typed}' as log(2)"])
    match = _LOG_BASE.match(raw)
    if match is None:
        return None
    base = match.group(1)
    named = {"2": "log2", "10": "log10", "e": "log"}
    if base in named:
        return Resolved("function", named[base], [f"read '{typed}' as the logarithm to base {base}"])
    raise ExpressionError(f"'{typed}' is a logarithm to base {base}, which is not built in", position,
                          "unsupported_function", f"write log(x)/log({base}) for the logarithm of x to base {base}")


def _before_euler(raw: str, ns: "Namespace", typed: str, position: int) -> list[str] | None:
    """``ye``, ``ae``, ``m_1e``, ``θe`` typed before ``^``: the declared names and then Euler's e, or None.

    Read only when the split is unambiguous: no variable ``e`` is declared (one that is keeps its
    meaning, and the ordinary glued-name split already reads y·e with it), the part before the
    ``e`` is one declared name, ``pi`` or an unambiguous glued run of declared names (no function:
    ``sine^x`` is not sin(e^x)), and the ``e`` is not a subscript (``x_e^2`` is the square of x_e).
    """
    if len(raw) < 2 or raw[-1] != "e" or raw[-2] == "_" or _lookup("e", ns) is not None:
        return None
    head = raw[:-1]
    symbol = _lookup(head, ns)
    if symbol is not None:
        return [symbol.name, "e"]
    if head == "pi":
        return ["pi", "e"]
    try:
        parts = _split(head, ns, typed, position)
    except ExpressionError:  # the head is ambiguous: the unknown name is reported as typed
        return None
    if not parts or any(part in FUNCTIONS or part.isdigit() for part in parts):
        return None
    return [*parts, "e"]


def _variables_only(raw: str, ns: "Namespace") -> list[str] | None:
    """A reading of the short word ``raw`` as declared variables alone (longest names first), or None."""
    words, _ = _split_words(ns)
    variables = {k: v for k, v in words.items() if v in ns.names}

    def read(start: int) -> list[str] | None:
        if start == len(raw):
            return []
        for end in range(len(raw), start, -1):
            if raw[start:end] in variables:
                rest = read(end)
                if rest is not None:
                    return [variables[raw[start:end]], *rest]
        return None

    parts = read(0)
    return parts if parts and len(parts) > 1 else None


def _reading(parts: list[str]) -> str:
    """How a split reads, the way the parser will take it: ['m', 'g', 'sin', '2', 'x'] -> m·g·sin(2·x).

    A function takes the glued parts after it up to the next function.
    """
    words, open_call = [], False
    for part in parts:
        if part in FUNCTIONS:
            if open_call:
                words[-1] += ")"
            words.append(part + "(")
            open_call = True
        elif words and words[-1].endswith("("):
            words[-1] += part
        else:
            words.append(part)
    text = "·".join(words).replace("(·", "(")
    return text + (")" if open_call and not text.endswith("(") else "")


def _lookup(raw: str, ns: "Namespace"):
    if raw in ns.names:
        return ns.symbol(raw)
    # Underscores are only separators to a student: m_1 is m1, theta_dot is thetadot.
    matches = ns.names_by_key.get(raw.replace("_", ""), ())
    if len(matches) == 1:
        return ns.symbol(matches[0])
    # thetaddot_1, thetadot2: the dots typed before the index, for theta1ddot, theta2dot
    moved = _DOTS_BEFORE_INDEX.match(raw)
    if moved is not None:
        matches = ns.names_by_key.get(moved.group(1).replace("_", "") + moved.group(3) + moved.group(2), ())
        if len(matches) == 1:
            return ns.symbol(matches[0])
    return None


_DOTS_BEFORE_INDEX = re.compile(r"^([A-Za-z_]*?[A-Za-z])_?(d?dot)_?(\d+)$")


def is_constant(symbol, ns: "Namespace") -> bool:
    """Whether a declared variable is constant in time: a parameter (the default kind) that is no derivative and
    has no declared rate, as `leibniz.time_derivative` takes it (d/dt(m l² θ̇) is m l² θ̈)."""
    if symbol is None or ns[symbol.name].kind != "parameter" or symbol.name.endswith("dot"):
        return False
    return all(_lookup(derivative_name(symbol.name, k), ns) is None for k in (1, 2))


def constant_derivative_error(name: str, typed: str, position: int) -> ExpressionError:
    """The refusal of a time derivative of a constant on its own (ġ, d/dt(g), diff(g, t)): not "this problem has
    no variable gdot", but why, since the student may have meant something else (θ under a stray dot)."""
    shown = "" if typed == name else f" ('{typed}')"
    return ExpressionError(f"{name} is a constant of this problem, so its time derivative{shown} is 0", position,
                           "unknown_name", f"leave the term out or write 0, or write {name} without the derivative "
                           "if that is what you meant")


def _resolve_derivative(raw: str, ns: "Namespace", order: int, typed: str, position: int) -> Resolved:
    base_symbol = _lookup(raw, ns)
    base = base_symbol.name if base_symbol is not None else raw.replace("_", "")
    if order + (2 if base.endswith("ddot") else 1 if base.endswith("dot") else 0) > 2:
        raise ExpressionError(f"'{typed}' is a third or higher time derivative, which no answer here uses",
                              position, "unknown_name", "write at most two dots or primes")
    name = derivative_name(base, order)
    symbol = _lookup(name, ns)
    if symbol is None and is_constant(base_symbol, ns):
        raise constant_derivative_error(base, typed, position)
    if symbol is None:
        hint = _suggestion(name, ns)
        flattened = _DOT_THEN_DIGITS.search(typed)
        if flattened is not None:
            # θ˙2 copied out of a web page's MathML: its θ̇² or θ̇₂ lost the raise or drop
            hint = (f"digits after a dot read as a subscript; write a power with ^, as in "
                    f"{typed[:flattened.start(1)]}^2" + (f"; or {hint}" if hint else ""))
        raise ExpressionError(f"'{typed}' means {name}, the time derivative of {base}, "
                              f"but this problem has no variable {name}", position, "unknown_name", hint)
    return Resolved("symbol", symbol)


def _split_before_derivative(raw: str, ns: "Namespace", order: int, typed: str, position: int) -> list[str] | None:
    """``m1x`` with two primes: declared names, then the one whose derivative is declared (m1, xddot).

    The primes or dots belong to the last letters typed, as they are written after them; every cut
    that reads is tried, and two readings are no reading (None), as in `_split`.
    """
    found = []
    for cut in range(1, len(raw)):
        head, tail = raw[:cut].rstrip("_"), raw[cut:]
        if not head or tail.startswith("_"):
            continue
        try:
            derivative = _resolve_derivative(tail, ns, order, typed, position).value.name
            declared = _lookup(head, ns)
            head_parts = [declared.name] if declared is not None else _split(head, ns, typed, position)
        except ExpressionError:
            continue
        if head_parts and not any(part in FUNCTIONS or part.isdigit() for part in head_parts):
            found.append([*head_parts, derivative])
    return found[0] if len(found) == 1 else None


# A dot accent (combining or spacing) then digits at the end of a name: ẋ2, θ˙2.
_DOT_THEN_DIGITS = re.compile("[\u0307\u0308\u02d9\u00a8]([0-9]+)$")


@lru_cache(maxsize=64)
def _split_words(ns: "Namespace") -> tuple[dict[str, str], int]:
    """The names a glued name may be made of (``{spelling: name}``) and the longest spelling.

    A namespace never changes, and every glued name typed against it needs the same table.
    """
    words = {k: names[0] for k, names in ns.names_by_key.items() if len(names) == 1}
    words.setdefault("pi", "pi")
    for name in FUNCTIONS:
        words.setdefault(name, name)
    return words, max(map(len, words))


def _split(raw: str, ns: "Namespace", typed: str, position: int) -> list[str] | None:
    """The unique way to read ``raw`` as several known names glued together.

    Parts are variable names (underscores ignored, so ``m_1g`` is m1·g), ``pi``
    and function names; digits may follow a function only (``sin2x`` is
    sin(2x), while ``m2g`` needs a variable ``m2``).  Longest match first with
    backtracking; two different readings are an error, since guessing would
    grade the wrong expression.
    """
    key = raw.replace("_", "")
    words, longest = _split_words(ns)
    found: list[list[str]] = []

    # Iterative search so a long run of letters cannot exhaust the Python stack;
    # stop at two readings, which is all the ambiguity check needs.
    stack: list[tuple[int, list[str]]] = [(0, [])]
    steps = 0
    while stack and len(found) < 2 and steps < 20000:
        steps += 1
        start, parts = stack.pop()
        if start == len(key):
            if len(parts) > 1:
                found.append(parts)
            continue
        candidates = []
        if parts and parts[-1] in FUNCTIONS and key[start].isdigit():
            end = start
            while end < len(key) and key[end].isdigit():
                end += 1
            candidates.append((end, key[start:end]))
        for end in range(start + 1, min(len(key), start + longest) + 1):
            if key[start:end] in words:
                candidates.append((end, words[key[start:end]]))
        # Push shortest first so the longest match is tried first.
        for end, part in sorted(candidates):
            stack.append((end, parts + [part]))
    if len(found) > 1:
        readings = " or ".join(_reading(p) for p in found)
        raise ExpressionError(f"'{typed}' is ambiguous: it could be {readings}", position, "ambiguous",
                              "put * or spaces between the names you mean")
    return found[0] if found else None


def _suggestion(name: str, ns: "Namespace", functions_only: bool = False) -> str | None:
    vocabulary = sorted(set(function_names()) if functions_only else set(ns.names) | set(function_names()) | {"pi"})
    close = difflib.get_close_matches(name, vocabulary, n=3, cutoff=0.6)
    if close:
        return "did you mean " + " or ".join(f"'{c}'" for c in close) + "?"
    if functions_only:
        return "allowed functions: " + ", ".join(function_names())
    if ns.names:
        return "the variables here are " + ", ".join(sorted(ns.names))
    return None


# Functions other systems (Maxima/STACK, calculators) know that the grammar leaves out, and how to
# write each with the ones it has (an inverse cotangent's value for negative x differs between
# conventions, so it is spelt out rather than guessed).
_ACOT = "write pi/2 - atan(x) or atan(1/x), the one you mean (they differ for x < 0)"
WRITE_INSTEAD = {
    # Maple's root(x, n): x^(1/n) has no value for x < 0, where surd (nthroot) gives the real root
    "root": "write surd(x, n) for the real n-th root of x (x^(1/n) for x >= 0), or sqrt(x)",
    "logbase": "write log(x, b) for the logarithm of x to base b",
    "acot": _ACOT,
    "arccot": _ACOT,
    "arcctg": _ACOT,
    "asec": "write acos(1/x) for the inverse secant",
    "arcsec": "write acos(1/x) for the inverse secant",
    "acsc": "write asin(1/x) for the inverse cosecant",
    "arccsc": "write asin(1/x) for the inverse cosecant",
    "arccosec": "write asin(1/x) for the inverse cosecant",
    # the reciprocal hyperbolic functions' inverses (math-expressions and Maxima know them)
    "asech": "write acosh(1/x) for the inverse hyperbolic secant",
    "arsech": "write acosh(1/x) for the inverse hyperbolic secant",
    "arcsech": "write acosh(1/x) for the inverse hyperbolic secant",
    "acsch": "write asinh(1/x) for the inverse hyperbolic cosecant",
    "arcsch": "write asinh(1/x) for the inverse hyperbolic cosecant",
    "arccsch": "write asinh(1/x) for the inverse hyperbolic cosecant",
    "acoth": "write atanh(1/x) for the inverse hyperbolic cotangent",
    "arcoth": "write atanh(1/x) for the inverse hyperbolic cotangent",
    "arccoth": "write atanh(1/x) for the inverse hyperbolic cotangent",
    "binomial": "write the binomial coefficient out with products",
    "factorial": "write the product out, as in 2*3",
    "fact": "write the product out, as in 2*3 for fact(3)",  # edX's and qtype_formulas' fact(n) is n!
    # SymPy's derivative object (diff(θ(t), t) itself is read as the time derivative)
    "derivative": "write the time derivative as θ̇ (thetadot), or as diff(θ(t), t)",
    "hypot": "write sqrt(x^2 + y^2)",
    "pi": "write pi (or π) without brackets",  # a spreadsheet's PI()
    "eq": "write the equation with =, as in x = y",  # SymPy's Eq(x, y)
    "frac": "write a/b for a fraction (or \\frac{a}{b})",  # Typst's frac(a, b)
    # the functions' names spelt out, as dictation gives them ('cosine' was "did you mean 'cosec' or 'sin' or 'cos'?")
    "sine": "write sin, as in sin(θ)", "cosine": "write cos, as in cos(θ)", "tangent": "write tan, as in tan(θ)",
    # French and Russian names of the hyperbolic functions (ch x is cosh x); \ch, \sh, \th are read in LaTeX
    "ch": "write cosh(x) for the hyperbolic cosine (ch in French and Russian notation)",
    "sh": "write sinh(x) for the hyperbolic sine (sh in French and Russian notation)",
    **dict.fromkeys(("th", "tgh"), "write tanh(x) for the hyperbolic tangent (th in French and Russian notation)"),
    **dict.fromkeys(("cth", "ctgh"), "write coth(x) for the hyperbolic cotangent (cth in Russian notation)"),
}

#: How to write the inverse of a function that has no inverse in the grammar, for ``f^-1``
#: (the reciprocal functions' inverses are under their names in WRITE_INSTEAD).
INVERSE_INSTEAD = {
    "log": "write exp(x) for the inverse function of log",
    "exp": "write log(x) for the inverse function of exp",
    "sqrt": "write x^2 (for x >= 0) for the inverse function of sqrt",
}


def _raise_unknown(raw: str, ns: "Namespace", typed: str, position: int, called: bool):
    # arcsec x, arccot x: a function other systems know, typed without brackets, is still that
    # function (not a misspelt variable), and its refusal says how to write it here; exact spelling
    # only, as the capital letter Π (raw "Pi") is a name, not the spreadsheet's PI()
    if called or (raw in WRITE_INSTEAD and raw != "pi"):
        suggestion = _suggestion(raw, ns, functions_only=True)
        instead = WRITE_INSTEAD.get(raw.lower())
        if instead:
            suggestion = f"{instead}; or {suggestion}" if suggestion else instead
        raise ExpressionError(f"'{typed}' is not a function you can use here", position,
                              "unsupported_function",
                              suggestion or "allowed functions: " + ", ".join(function_names()))
    if raw in _UNIT_WORDS or raw.lower() in _UNIT_WORDS or (raw in _UPRIGHT_UNITS and typed.startswith("\\")):  # \mathrm{s}: upright, as units are
        raise ExpressionError(f"unknown name '{typed}': units are not part of the answer", position, "unknown_name",
                              f"write the answer in the problem's symbols and delete '{typed}'")
    if raw.lower() in ("deg", "degs", "degree", "degrees"):  # sin(30 deg): the degree sign is read, the word is not
        raise ExpressionError(f"unknown name '{typed}': degrees are written with the degree sign", position,
                              "unknown_name", "write 30° (a number then °) for 30 degrees, or the angle in radians (π/6)")
    if raw in ("dot", "ddot"):  # Typst's "theta dot", or "dot theta" without brackets: which name is dotted?
        marked = "θ̇, thetadot" if raw == "dot" else "θ̈, thetaddot"
        product = "; for a product (Typst's m dot g) write m*g" if raw == "dot" else ""
        raise ExpressionError(f"'{typed}' alone is not a variable", position, "unknown_name",
                              f"write the time derivative as {marked} or {raw}(theta){product}")
    euler = _before_euler(raw, ns, typed, position)
    if euler is not None:  # ye alone (no ^ after it): y·e, or a misspelt name? Say both.
        product = "*".join(euler)
        suggestion = _suggestion(raw, ns)
        raise ExpressionError(f"unknown name '{typed}'", position, "unknown_name",
                              f"write {product} for {_reading(euler)} with e Euler's number"
                              + (f"; or {suggestion}" if suggestion and suggestion.startswith("did") else ""))
    latex = _LATEX_DIGITS.match(typed)
    if latex is not None:  # \pi2, \omega2 with no variable omega2: a command then digits
        command, digits = latex.groups()
        subscript = "" if command == "\\pi" else f", or {command}_{{{digits}}} for a variable with subscript {digits}"
        raise ExpressionError(f"unknown name '{typed}'", position, "unknown_name",
                              f"write {digits}{command} for the product{subscript}")
    latin = _latin_lookalike(raw, typed, ns)
    if latin is not None:  # ν0 for v0: a Greek letter that looks like the Latin one the problem uses
        greek, letter, name = latin
        raise ExpressionError(f"unknown name '{typed}': '{greek}' is the Greek letter {GREEK_CHARS[greek]}, "
                              f"which looks like the Latin '{letter}'", position, "unknown_name",
                              f"type {name} with the Latin '{letter}' if that is what you meant")
    if raw.lower() in ("inf", "infinity", "nan", "oo"):  # edX's and mathjs' inf, NaN: 'nan' was "did you mean 'tan'?"
        raise ExpressionError(f"unknown name '{typed}': infinity and not-a-number are not values of an answer",
                              position, "unknown_name", "give a formula with a finite value")
    if raw in ("i", "I", "j"):  # edX's i and j, Wolfram's and Maple's I: 'i' was "did you mean 'pi'?"
        raise ExpressionError(f"unknown name '{typed}': this problem has no variable {raw}, and complex numbers "
                              "(i, the imaginary unit) are not part of these answers", position, "unknown_name",
                              "write the answer with real quantities"
                              + (f"; the variables here are {', '.join(sorted(ns.names))}" if ns.names else ""))
    if raw.lower() == "tau" and "tau" not in ns.names:  # mathjs' tau is 2π; 'tau' was "did you mean 'tan'?"
        raise ExpressionError(f"unknown name '{typed}': this problem has no variable τ", position, "unknown_name",
                              "write 2*pi for the constant τ = 2π of some calculators"
                              + (f"; the variables here are {', '.join(sorted(ns.names))}" if ns.names else ""))
    spoken = _SPOKEN_WORDS.get(raw.lower())
    if spoken is not None:  # m l θ̇ squared: a phone's dictation, or the formula read aloud
        raise ExpressionError(f"unknown name '{typed}': it is a word, not a symbol", position, "unknown_name", spoken)
    greek, letter = _LATIN_FOR_GREEK.get(raw, (None, None))
    if greek is not None and greek in ns.names:  # sin a for sin α: a keyboard without Greek letters
        raise ExpressionError(f"unknown name '{typed}': the problem has {letter} ({greek}), which '{typed}' may "
                              "stand for", position, "unknown_name", f"type {greek} or {letter} for the Greek letter")
    lowered = _capitalised_start(raw, ns, position)
    if lowered is not None:  # Mg cos θ: a phone capitalises the first letter of what is typed
        shown = typed[0].lower() + typed[1:] if typed[:1] == raw[:1] else lowered
        raise ExpressionError(f"unknown name '{typed}'", position, "unknown_name",
                              f"did you mean '{shown}', with a lowercase '{raw[0].lower()}'? (a phone or editor may "
                              "have capitalised the first letter of the answer)")
    suggestion = _suggestion(raw, ns) or "this answer uses no variables: write a number"
    if raw in ("x", "X") and not any(name[:1] == raw for name in ns.names):  # m x g: a keyboard without ×
        suggestion += "; if 'x' stands for times, type * (or ×)"
    if re.fullmatch(r"[xX]10", raw) and not any(name[:1] == raw[0] for name in ns.names):
        # 3x10^-1: a calculator's (or a phone's) times ten to the, with the letter x
        suggestion = "for a number times a power of ten, write 3*10^-1 or 3e-1 (not x, a letter)"
    if raw in _UPRIGHT_UNITS:  # √(5gR) m/s: 's' may be a variable the problem lacks, or a unit
        suggestion += f"; if '{typed}' is a unit, delete it: units are not part of the answer"
    raise ExpressionError(f"unknown name '{typed}'", position, "unknown_name", suggestion)


# Words for operators and functions, as dictation or a formula read aloud gives them, and what to type instead
# (their near spellings misled: 'squared' was "did you mean 'surd'?", 'cosine' "'cosec' or 'sin' or 'cos'?").
_SPOKEN_WORDS = {
    **dict.fromkeys(("squared", "square"), "write ^2 for a square, as in θ̇^2 (or θ̇²)"),
    **dict.fromkeys(("cubed", "cube"), "write ^3 for a cube, as in x^3"),
    "plus": "write + for plus", "minus": "write - for minus",
    **dict.fromkeys(("over", "divided", "by"), "write / for a quotient, as in g/l"),
    **dict.fromkeys(("equals", "equal", "is"), "write = for an equation"),
    **dict.fromkeys(("prime", "primes"), "write a prime as an apostrophe, as in θ', or a dot, as in θ̇"),
    **{word: f"write the number {n} in digits" for n, word in enumerate(
        "zero one two three four five six seven eight nine ten".split()) if word not in ("one",)},
    "half": "write 1/2 for a half", "quarter": "write 1/4 for a quarter",
    **dict.fromkeys(("of", "the", "and", "times"), "give the formula alone, with + - * / ^ and brackets"),
    **dict.fromkeys(("where", "with", "when", "for", "if", "so", "hence", "thus", "therefore"),
                    "give the formula alone, without the explanation"),
}


def _capitalised_start(raw: str, ns: "Namespace", position: int) -> str | None:
    """The name with its first letter lowercase (``mg`` for ``Mg``) when the name starts the answer, only that
    letter is a capital, and the lowercase reading names declared variables (``m``·``g``); None otherwise."""
    if position != 0 or not raw[:1].isupper() or not raw[:1].isascii() or raw[1:2].isupper():
        return None
    lowered = raw[0].lower() + raw[1:]
    try:
        found = resolve_name(lowered, ns, typed=lowered, position=position)
    except ExpressionError:
        return None
    return lowered if found.kind in ("symbol", "split") else None


# Latin letters typed for the Greek letter they resemble, on a keyboard without Greek: sin a for sin α.
# (q and f are θ and φ in Word's Symbol font, which a copy as plain text leaves as the Latin letters.)
_LATIN_FOR_GREEK = {"a": ("alpha", "α"), "B": ("beta", "β"), "w": ("omega", "ω"), "W": ("Omega", "Ω"),
                    "u": ("mu", "μ"), "v": ("nu", "ν"), "p": ("rho", "ρ"), "t": ("tau", "τ"), "q": ("theta", "θ"),
                    "f": ("phi", "φ"), "y": ("gamma", "γ")}


# Greek letters that look like Latin ones in most fonts, and the Latin letter.
_GREEK_LOOKALIKES = {"ν": "v", "κ": "k", "ρ": "p", "υ": "u", "χ": "x", "ι": "i", "τ": "t", "ω": "w"}


def _latin_lookalike(raw: str, typed: str, ns: "Namespace") -> tuple[str, str, str] | None:
    """``(greek, latin, name)`` when the typed name holds a Greek letter that looks Latin and, with the Latin
    letter instead, names a declared variable (``ν0`` where v0 is declared); None otherwise."""
    for greek, letter in _GREEK_LOOKALIKES.items():
        if greek in typed:
            spelled = GREEK_CHARS[greek]
            candidate = raw.replace(spelled, letter, 1)
            if candidate != raw and candidate in ns.names:
                return greek, letter, candidate
    return None


# A LaTeX command with digits typed after it (\pi2): the name the tokenizer made of both.
_LATEX_DIGITS = re.compile(r"^(\\[A-Za-z]+)(\d+)$")


#: Unit symbols and words: a wrapper holding only these (\mathrm{~m}, \text{ m/s^2}) is a unit.
UNIT_SYMBOLS = frozenset("N kN mN m cm mm km s ms kg g J kJ W kW Pa kPa Hz rad deg K mol A V min h "
                         "newton newtons meter meters metre metres second seconds sec joule joules watt watts "
                         "radian radians".split())

# Unit symbols that are seldom a variable's name: an unknown upright \mathrm{s} is named as a unit.
_UPRIGHT_UNITS = frozenset("s m N kg J W Pa Hz rad ms cm mm km kN".split())

# Units students append to an answer (m g N, 2.5 newtons): undeclared, they are named as units.
_UNIT_WORDS = frozenset("N newton newtons kg J joule joules W watt watts Pa Nm rad radians sec seconds meters "
                        "metres kilograms kilogram metre meter second pascal pascals".split())
