r"""Leibniz notation for time derivatives: ``dθ/dt``, ``d²x/dt²``, ``\frac{d\theta}{dt}``, ``d/dt(θ)``,
``\frac d{dt}\theta`` (an unbraced ``\frac`` argument is one letter, as in TeX; ``\frac{d}dt`` is refused: TeX
reads it as d/d times t).

A pass over the tokens, before the parser, that replaces each run of tokens spelling the time
derivative of one coordinate by a single ``derivative`` token spanning the typed text (so every
position still points at what the student typed). The parser reads that token as the namespace's
velocity or acceleration variable, exactly as it reads ``θ̇`` or ``\ddot{x}``, and notes the reading.

The reading only ever replaces text that is an error today: it applies when

* the ``d`` words mean nothing in the namespace (no variable ``d``, ``dt``, ``dtheta``, and no
  glued reading such as d·θ), so with variables ``d`` and ``t`` declared ``d x/d t`` stays the
  quotient of products;
* the denominator is ``dt`` (or ``d t``) for the time ``t``, which may be undeclared or declared
  as a time;
* the coordinate, or one of its time derivatives, is declared (``dq/dt`` with no q at all stays
  an unknown name).

``d/dt`` of a bracketed expression (``d/dt(m r² φ̇)``, ``\frac{d}{dt}\left(m l^2\dot\theta\right)``)
becomes a ``time_derivative`` token: the parser reads the bracket and differentiates it by the chain
rule through the declared derivatives (`time_derivative`), parameters constant.

A missing derivative variable (also one the chain rule needs: ``d/dt(m ẍ)``), orders that disagree
(``d²θ/dt``), a ``t`` that is not a time, and a power right after ``d/dt(…)`` are refused with the text
and the fix.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import sympy

from .dimensions import parse_dimension
from .errors import ExpressionError
from .magnitudes import node_count
from .names import derivative_name, resolve_name
# The parser's own lookups of a declared name and of a coordinate's derivative, so a Leibniz
# derivative resolves (and fails) exactly as θ̇ does; resolve_name would also try glued readings.
from .names import _lookup, _resolve_derivative, is_constant
from .tokens import Token

__all__ = ["read_leibniz", "dotted", "time_derivative"]

_TIME = parse_dimension("time")
_OPEN_OPERAND = {"(": ")", "[": "]", "{": "}"}
_ATOMS = ("number", "name", "open", "root", "command", "derivative", "time_derivative")
# ``\mathrm{d}x``, ``\operatorname{d}x``, ``\mathrm dx`` (TeX's one-letter argument, which needs the space):
# the wrapper the tokenizer read into the name ``dx``.
_WRAPPED_D = re.compile(r"^\\[A-Za-z]+(?:\s*\{d\}|\s+d)")
# The d of Word's equations, a mathematical italic 𝑑 (read as the letter d), typed first.
_ITALIC_D = "\U0001d451"
# UnicodeMath's differential d (Word's \dd), DOUBLE-STRUCK ITALIC SMALL D, also read as the letter d.
_DIFFERENTIAL_D = "\u2146"
_TYPED_DS = ("d", _ITALIC_D, _DIFFERENTIAL_D)


def _typed_d(text: str) -> str | None:
    """What follows the typed d of a name (``dθ`` -> ``θ``, ``𝑑𝜃`` -> ``𝜃``, ``\\mathrm{d}x`` -> ``x``), or
    None when its d is not typed as one (``\\delta``)."""
    if text[:1] in _TYPED_DS:
        return text[1:]
    wrapped = _WRAPPED_D.match(text)
    return text[wrapped.end():] if wrapped else None
_GREEK_CHAR = {"alpha": "α", "beta": "β", "gamma": "γ", "delta": "δ", "epsilon": "ε", "zeta": "ζ",
               "eta": "η", "theta": "θ", "iota": "ι", "kappa": "κ", "lambda": "λ", "mu": "μ", "nu": "ν",
               "xi": "ξ", "pi": "π", "rho": "ρ", "sigma": "σ", "tau": "τ", "upsilon": "υ", "phi": "φ",
               "chi": "χ", "psi": "ψ", "omega": "ω", "Gamma": "Γ", "Delta": "Δ", "Theta": "Θ",
               "Lambda": "Λ", "Xi": "Ξ", "Pi": "Π", "Sigma": "Σ", "Phi": "Φ", "Psi": "Ψ", "Omega": "Ω"}
_SUBSCRIPT = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")
_SUPERSCRIPT = {1: "", 2: "²", 3: "³"}


def dotted(name: str) -> str:
    """How a canonical derivative name looks with dots, for notes: ``thetadot`` -> ``θ̇``.

    Examples
    --------
    >>> print(dotted("thetadot"), dotted("xddot"), dotted("theta1dot"), dotted("x_2ddot"))
    θ̇ ẍ θ̇₁ ẍ₂
    """
    order = 0
    if name.endswith("ddot"):
        name, order = name[:-4], 2
    elif name.endswith("dot"):
        name, order = name[:-3], 1
    match = re.match(r"([A-Za-z]+?)(_?\d+)?$", name)
    if match is None:  # lambda_surface and the like: no tidier spelling than the name
        return name + "\u0307" * order
    head, digits = match.group(1), match.group(2) or ""
    mark = {0: "", 1: "\u0307", 2: "\u0308"}[order]
    return _GREEK_CHAR.get(head, head) + mark + digits.lstrip("_").translate(_SUBSCRIPT)


def _at(tokens: list[Token], j: int) -> Token:
    return tokens[j] if j < len(tokens) else tokens[-1]  # the list ends with the end token


def _is(token: Token, kind: str, value=None) -> bool:
    return token.kind == kind and (value is None or token.value == value)


def _plain_name(token: Token) -> bool:
    return token.kind == "name" and not token.forced_function and not token.glued


def _order_mark(tokens: list[Token], j: int) -> tuple[int | None, int]:
    """The power after a ``d`` or ``dt``: ``²``, ``^2``, ``^{2}``, or none (1). None if malformed."""
    token = _at(tokens, j)
    if token.kind == "sup":
        return (token.value, j + 1) if token.value >= 1 else (None, j)
    if _is(token, "op", "^"):
        following = _at(tokens, j + 1)
        if following.kind == "number" and not following.decimal and following.value.is_Integer:
            return int(following.value), j + 2
        if _is(following, "open", "{") and _at(tokens, j + 2).kind == "number" \
                and _is(_at(tokens, j + 3), "close", "}") and _at(tokens, j + 2).value.is_Integer:
            return int(_at(tokens, j + 2).value), j + 4
        return None, j
    return 1, j


@dataclass(frozen=True, slots=True)
class _Numerator:
    """``d``, ``d²``, ``dθ``, ``d θ``, ``d(θ)``, ``d²θ``, ``\\mathrm{d}\\theta``, ``d\\dot\\theta``: what was matched.

    ``coordinate`` is None for the operator ``d/dt``; ``raw`` is its name text (``theta_1``),
    ``typed`` as typed (``θ₁``), and ``end`` the index of the token after the numerator.
    """

    order: int
    words: list[Token]
    coordinate: Token | None
    raw: str | None
    typed: str | None
    end: int
    dots: int = 0  # the \dot (1) or \ddot (2) over the coordinate: \frac{d\dot\theta}{dt} is θ̈


def _numerator(tokens: list[Token], i: int) -> _Numerator | None:
    token = tokens[i]
    if not _plain_name(token):
        return None
    if token.value == "d" and not token.order:
        order, j = _order_mark(tokens, i + 1)
        if order is None:
            return None
        following = _at(tokens, j)
        if _plain_name(following):
            return _Numerator(order, [token], following, following.value, following.text, j + 1)
        inner = _at(tokens, j + 1)
        if _is(following, "open", "(") and _plain_name(inner) and _is(_at(tokens, j + 2), "close", ")"):
            return _Numerator(order, [token], inner, inner.value, inner.text, j + 3)  # d(θ)/dt
        if following.kind == "command" and following.value in ("dot", "ddot"):
            # d\dot\theta, d\dot{\theta}: LaTeX's dθ̇, as the dotted letter typed is read
            dotted_name, raw, total, end = _operand(tokens, j)
            if dotted_name is not None:
                typed = f"\\{following.value}{{{dotted_name.text}}}"
                return _Numerator(order, [token], dotted_name, raw, typed, end, total - dotted_name.order)
        return _Numerator(order, [token], None, None, None, j)
    value, text = token.value, token.text
    if len(value) > 1 and value[0] == "d" and value[1] != "_":
        typed = _typed_d(text)
        if typed is None:  # \delta: a Greek letter, not d
            return None
        return _Numerator(1, [token], token, value[1:], typed, i + 1)
    return None


def _denominator(tokens: list[Token], i: int) -> tuple[int, list[Token], Token, int] | None:
    """``dt``, ``d t``, ``dt²``, ``dt^2``, ``\\mathrm{d}t``: (order, d words, the t, end) or None."""
    token = _at(tokens, i)
    if not _plain_name(token) or token.order:
        return None
    if token.value == "dt" and _typed_d(token.text) is not None:
        words, time, j = [token], token, i + 1
    elif token.value == "d":
        time = _at(tokens, i + 1)
        if not (_plain_name(time) and time.value == "t" and not time.order):
            return None
        words, j = [token], i + 2
    else:
        return None
    order, j = _order_mark(tokens, j)
    return (order, words, time, j) if order is not None else None


def _known_coordinate(raw: str, ns) -> bool:
    """A coordinate the namespace knows: declared, or with a declared time derivative."""
    if _lookup(raw, ns) is not None:
        return True
    base = raw.replace("_", "")
    return any(_lookup(derivative_name(base, order), ns) is not None for order in (1, 2))


def _means_something(words: list[Token], ns, memo: dict) -> bool:
    """Whether the typed ``d`` words already read as names here (d, dt, dtheta, or a glued d·θ).

    ``memo`` keeps the answers for one text: an unknown name costs a search for suggestions, and a
    text may repeat the same dθ/dt hundreds of times.
    """
    for word in words:
        key = (word.value, word.order)
        if key not in memo:
            try:
                resolve_name(word.value, ns, order=word.order, typed=word.text, position=word.pos)
                memo[key] = True
            except ExpressionError:
                memo[key] = False
        if memo[key]:
            return True
    return False


def _time_error(time: Token, ns, shown: str) -> ExpressionError | None:
    """None when ``t`` is the time (undeclared, or declared with the dimension of time)."""
    if "t" not in ns.names or ns["t"].dimension == _TIME:
        return None
    return ExpressionError(f"'{shown}' reads as a time derivative, but t here is "
                           f"{ns['t'].dimension.describe()}, not the time", time.pos, "syntax",
                           "write the time derivative with a dot, as in θ̇ or thetadot")


def _derivative(start: Token, end: Token, text: str, raw: str, order: int, ns,
                error: ExpressionError | None = None) -> Token:
    """The token that stands for the whole typed derivative; an error is raised when parsed."""
    shown = text[start.pos:end.end]
    value = None
    if error is None:
        try:
            value = _resolve_derivative(raw, ns, order, shown, start.pos).value
        except ExpressionError as err:
            error = err
    return Token("derivative", value, start.pos, end.end, shown, start.space_before, order, error=error)


def _mismatch(start: Token, end: Token, text: str, top: int, below: int, typed: str) -> ExpressionError:
    shown = text[start.pos:end.end]
    typed = typed or ""
    return ExpressionError(
        f"'{shown}' has d{_SUPERSCRIPT.get(top, f'^{top}')} on top but dt{_SUPERSCRIPT.get(below, f'^{below}')} "
        "below", start.pos, "syntax",
        f"the powers must agree: write d{typed}/dt for the first derivative, d²{typed}/dt² for the second, "
        f"or (d{typed}/dt)² for the square of the first")


def _operand(tokens: list[Token], k: int) -> tuple[Token | None, str | None, int, int]:
    """What ``d/dt`` is applied to: (token, raw name, extra order, end), token None if not one name.

    A name (``θ``, ``θ̇``), one bracketed (``(θ)``, ``\\left(θ\\right)``) or a ``\\dot`` of one.
    """
    token = _at(tokens, k)
    if _plain_name(token):
        return token, token.value, token.order, k + 1
    if token.kind == "open" and _plain_name(_at(tokens, k + 1)) \
            and _is(_at(tokens, k + 2), "close", _OPEN_OPERAND[token.value]):
        inner = _at(tokens, k + 1)
        return inner, inner.value, inner.order, k + 3
    if token.kind == "command" and token.value in ("dot", "ddot"):
        extra = 1 if token.value == "dot" else 2
        if _plain_name(_at(tokens, k + 1)):
            inner = _at(tokens, k + 1)
            return inner, inner.value, inner.order + extra, k + 2
        if _is(_at(tokens, k + 1), "open", "{") and _plain_name(_at(tokens, k + 2)) \
                and _is(_at(tokens, k + 3), "close", "}"):
            inner = _at(tokens, k + 2)
            return inner, inner.value, inner.order + extra, k + 4
    return None, None, 0, k


def _exponent_end(tokens: list[Token], j: int) -> Token:
    """The last token of the exponent starting at ``tokens[j]`` (for showing ``θ^{2}`` whole)."""
    token = _at(tokens, j)
    if token.kind != "open":
        return token
    depth = 0
    for k in range(j, len(tokens)):
        depth += {"open": 1, "close": -1}.get(tokens[k].kind, 0)
        if depth == 0:
            return tokens[k]
    return tokens[-1]


def _nested(tokens: list[Token], k: int, ns, text: str, memo: dict) -> tuple[Token, int] | None:
    """A bracketed Leibniz derivative after ``d/dt``, as in ``d/dt(dθ/dt)``: (its token, end) or None."""
    opener, first = _at(tokens, k), _at(tokens, k + 1)
    if opener.kind != "open" or not ((first.kind == "name" and first.value[:1] == "d")
                                     or _is(first, "command", "frac")):
        return None
    found = _match(tokens, k + 1, ns, text, memo)
    if found is None or not _is(_at(tokens, found[1]), "close", _OPEN_OPERAND[opener.value]):
        return None
    return found[0], found[1] + 1


def _operator_in_brackets(tokens: list[Token], i: int):
    """(numerator, denominator) of ``(d/dt)`` opened at ``tokens[i]`` and applied to a bracket, or None."""
    top = _numerator(tokens, i + 1)
    if top is None or top.coordinate is not None or not _is(_at(tokens, top.end), "op", "/"):
        return None
    below = _denominator(tokens, top.end + 1)
    if below is None or not _is(_at(tokens, below[3]), "close", ")") or _at(tokens, below[3] + 1).kind != "open":
        return None
    return top, below


def _match(tokens: list[Token], i: int, ns, text: str, memo: dict) -> tuple[Token, int] | None:
    """The derivative token for a Leibniz derivative starting at ``tokens[i]`` and where it ends."""
    start = tokens[i]
    # ASCIIMath's frac(d^2 theta)(dt^2) is \frac{d^2\theta}{dt^2} with round brackets
    ascii_frac = start.kind == "name" and start.value == "frac" and "frac" not in ns.names
    framed = start.kind == "command" or ascii_frac
    opening, closing = ("(", ")") if ascii_frac else ("{", "}")
    if framed:  # \frac{d…}{dt…}, or \frac d{dt…} (an unbraced argument is one letter, as in TeX)
        first = _at(tokens, i + 1)
        if _plain_name(first) and first.text == "d" and not first.order and not ascii_frac:
            top, after = _Numerator(1, [first], None, None, None, i + 2), i + 2
        elif _is(first, "open", opening):
            top = _numerator(tokens, i + 2)
            if top is None or not _is(_at(tokens, top.end), "close", closing):
                return None
            after = top.end + 1
        else:
            return None
        if ascii_frac and not _is(_at(tokens, after), "open", opening):
            return None
        if not _is(_at(tokens, after), "open", opening):
            bare = _at(tokens, after)  # \frac{d}dt: LaTeX reads d/d, then t
            if top.coordinate is None and _plain_name(bare) and bare.value == "dt" and bare.text == "dt" \
                    and not _means_something(top.words + [bare], ns, memo):
                shown = text[start.pos:bare.end]
                error = ExpressionError(f"'{shown}' needs braces around dt: LaTeX reads it as d/d times t",
                                        start.pos, "syntax", "write \\frac{d}{dt}, with dt in braces")
                return _derivative(start, bare, text, "", 0, ns, error), after + 1
            return None
        below = _denominator(tokens, after + 1)
        if below is None or not _is(_at(tokens, below[3]), "close", closing):
            return None
        k = below[3] + 1
    elif start.kind == "open" and _operator_in_brackets(tokens, i):  # (d/dt)(m l² θ̇)
        top, below = _operator_in_brackets(tokens, i)
        k = below[3] + 1
    elif start.kind == "open":  # (d²θ)/(dt²) and (d²θ)/dt²: Word's linear form of the fraction
        top = _numerator(tokens, i + 1)
        if top is None or top.coordinate is None or not _is(_at(tokens, top.end), "close", ")") \
                or not _is(_at(tokens, top.end + 1), "op", "/"):
            return None
        bracketed = _is(_at(tokens, top.end + 2), "open", "(")
        below = _denominator(tokens, top.end + (3 if bracketed else 2))
        if below is None or (bracketed and not _is(_at(tokens, below[3]), "close", ")")):
            return None
        k = below[3] + (1 if bracketed else 0)
    else:  # d…/dt…
        top = _numerator(tokens, i)
        if top is None or not _is(_at(tokens, top.end), "op", "/"):
            return None
        below = _denominator(tokens, top.end + 1)
        if below is None:
            return None
        k = below[3]
    order, words, time, _ = below
    if _means_something(top.words + words, ns, memo):
        return None  # d, dt or dθ is a name here: the text keeps its ordinary meaning
    last = tokens[k - 1]
    if top.coordinate is not None:  # the quotient dθ/dt
        if not _known_coordinate(top.raw, ns):
            return None
        shown = text[start.pos:last.end]
        error = _time_error(time, ns, shown)
        if error is None and top.order != order:
            error = _mismatch(start, last, text, top.order, order, top.typed)
        return _derivative(start, last, text, top.raw, top.order + top.coordinate.order + top.dots, ns, error), k
    # the operator d/dt, applied to what follows
    operator = text[start.pos:last.end]
    error = _time_error(time, ns, operator)
    if error is None and top.order != order:
        error = ExpressionError(f"'{operator}' has d{_SUPERSCRIPT.get(top.order, '')} on top but "
                                f"dt{_SUPERSCRIPT.get(order, '')} below", start.pos, "syntax",
                                "the powers must agree: write d/dt or d²/dt²")
    operand, raw, extra, end = _operand(tokens, k)
    nested = _nested(tokens, k, ns, text, memo) if operand is None else None
    if nested is not None:  # d/dt(dθ/dt): the derivative of a derivative
        operand, end = nested
        raw, extra = (operand.value.name if operand.value is not None else ""), 0
        error = error or operand.error
    if error is None and (operand is None or not _known_coordinate(raw, ns)):
        where = _at(tokens, k)
        if operand is None and nested is None and where.kind == "open":
            # d/dt(m r² φ̇): the parser reads the bracket and differentiates it (time_derivative)
            return Token("time_derivative", order, start.pos, last.end, operator, start.space_before), k
        error = ExpressionError(f"'{operator}' can only be applied to one coordinate here, as in {operator}(θ)",
                                where.pos, "syntax",
                                "differentiate it yourself and write the derivatives with dots, as in θ̇ or ẍ")
        return _derivative(start, last, text, "", 0, ns, error), k
    following = _at(tokens, end)
    bare = _at(tokens, k) is operand
    powered = following.kind == "sup" or _is(following, "op", "^")
    if error is None and (powered or (bare and following.kind in _ATOMS)):
        # d/dt θ² and d/dt θ x: the derivative of θ² (of θ·x), or its square (product)? Either is typed.
        last = _exponent_end(tokens, end + 1) if _is(following, "op", "^") else following
        shown = text[start.pos:last.end]
        whole = text[start.pos:tokens[end - 1].end] if nested else f"d{operand.text}/dt"
        fix = (f"write ({whole})^2 for the square of the derivative" if powered
               else f"write ({whole})·{following.text} for a product with the derivative")
        error = ExpressionError(f"'{shown}' is ambiguous: it is not clear what {operator} applies to",
                                start.pos, "ambiguous", fix + ", or differentiate the whole yourself")
    return _derivative(start, tokens[end - 1], text, raw or "", order + extra, ns, error), end


def _closing(tokens: list[Token], j: int) -> int | None:
    """The index of the bracket that closes the one opened at ``tokens[j]``, or None."""
    depth = 0
    for k in range(j, len(tokens)):
        kind = tokens[k].kind
        depth += 1 if kind == "open" else -1 if kind == "close" else 0
        if depth == 0:
            return k
    return None


def _operator_first(tokens: list[Token], ns, memo: dict) -> list[Token]:
    """The tokens with each derivative of a bracket written as a quotient put in operator form, for
    `_match` to read: ``d(m l² θ̇)/dt`` and ``d[…]/dt`` as ``d/dt(…)``, ``\frac{d(…)}{dt}`` as
    ``\frac{d}{dt}(…)``, and ``(d/dt)(…)`` as ``d/dt(…)``; ``tokens`` itself when there is none.

    The tokens keep their positions, so what is shown of the derivative spans the text as typed. As
    for ``dθ/dt``, only where the ``d`` words mean nothing in the namespace.
    """
    out: list[Token] = []
    i, n, changed = 0, len(tokens), False
    while i < n:
        token = tokens[i]
        moved = None
        if _plain_name(token) and token.value == "d" and not token.order:  # d(…)/dt
            order, j = _order_mark(tokens, i + 1)
            moved = order is not None and _bracket_over_dt(tokens, i, j, None, ns, memo)
        elif _is(token, "command", "frac") and _is(_at(tokens, i + 1), "open", "{"):  # \frac{d(…)}{dt}
            d = _at(tokens, i + 2)
            if _plain_name(d) and d.value == "d" and not d.order:
                order, j = _order_mark(tokens, i + 3)
                moved = order is not None and _bracket_over_dt(tokens, i + 2, j, "}", ns, memo)
        if moved:
            reordered, i = moved
            out.extend(reordered)
            changed = True
            continue
        out.append(token)
        i += 1
    return out if changed else tokens


def _bracket_over_dt(tokens: list[Token], d: int, j: int, brace: str | None, ns, memo: dict):
    """(the tokens of ``d/dt(…)``, end) for ``d(…)/dt`` with the ``d`` (and its order mark) at
    ``tokens[d:j]``, inside ``\frac{…}{…}`` when ``brace`` is ``"}"``; False when not one."""
    opener = _at(tokens, j)
    close = _closing(tokens, j) if opener.kind == "open" else None
    if close is None or (close == j + 2 and _plain_name(tokens[j + 1])):
        return False  # no bracket, or d(θ)/dt: one coordinate, which _match reads as dθ/dt
    if brace is None:
        if not _is(_at(tokens, close + 1), "op", "/"):
            return False
        below = _denominator(tokens, close + 2)
        if below is None or _means_something([tokens[d]] + below[1], ns, memo):
            return False
        return tokens[d:j] + [tokens[close + 1]] + tokens[close + 2:below[3]] + tokens[j:close + 1], below[3]
    if not (_is(_at(tokens, close + 1), "close", "}") and _is(_at(tokens, close + 2), "open", "{")):
        return False
    below = _denominator(tokens, close + 3)
    if below is None or not _is(_at(tokens, below[3]), "close", "}") or _means_something([tokens[d]] + below[1], ns, memo):
        return False
    # \frac { d … } { dt … } ( … )
    return (tokens[d - 2:j] + [tokens[close + 1], tokens[close + 2]] + tokens[close + 3:below[3] + 1]
            + tokens[j:close + 1], below[3] + 1)


def read_leibniz(tokens: list[Token], ns, text: str) -> list[Token]:
    """The tokens with each Leibniz time derivative replaced by one ``derivative`` token.

    Parameters
    ----------
    tokens : list of Token
        From :func:`.tokens.tokenize`, ending with the end token; not modified.
    ns : Namespace
        Decides whether ``d``, ``t`` and the coordinate mean something else here.
    text : str
        The text the tokens' positions point into.

    Returns
    -------
    list of Token
        ``tokens`` itself when there is nothing to replace (the common case).

    Examples
    --------
    >>> from grader.expressions import Namespace, Variable
    >>> from grader.expressions.tokens import tokenize
    >>> ns = Namespace([Variable("theta", "angle"), Variable("thetadot", "angular_velocity")])
    >>> text = "2 dθ/dt"
    >>> [(t.kind, t.text, t.value) for t in read_leibniz(tokenize(text), ns, text)][:2]
    [('number', '2', 2), ('derivative', 'dθ/dt', thetadot)]
    >>> ns = Namespace([Variable("d", "length"), Variable("t", "time"), Variable("x", "length")])
    >>> text = "d x/d t"
    >>> [t.kind for t in read_leibniz(tokenize(text), ns, text)]
    ['name', 'name', 'op', 'name', 'name', 'end']
    """
    if "d" not in text and _ITALIC_D not in text and _DIFFERENTIAL_D not in text:  # most answers: nothing to look at
        return tokens
    memo: dict = {}
    typed = tokens
    tokens = _operator_first(_unbraced_powers(tokens), ns, memo)
    out: list[Token] | None = None
    i, n = 0, len(tokens)
    while i < n:
        token = tokens[i]
        found = None
        if (token.kind == "name" and token.value[:1] == "d") or (token.kind in ("command", "name")
                                                                 and token.value == "frac") \
                or (token.kind == "open" and token.value == "(" and i + 1 < n and tokens[i + 1].kind == "name"
                    and tokens[i + 1].value[:1] == "d"):
            found = _match(tokens, i, ns, text, memo)
        if found is None:
            if out is not None:
                out.append(token)
            i += 1
            continue
        if out is None:
            out = tokens[:i]
        out.append(found[0])
        i = found[1]
        if found[0].error is not None:
            # The parser stops at this token (or at an error before it): nothing after it is read.
            out.extend(tokens[i:])
            break
    return out if out is not None else typed


def _unbraced_powers(tokens: list[Token]) -> list[Token]:
    """The tokens with the braces WIRIS and MathType put around a base before its power dropped
    (``\\frac{{d}^{2}\\theta}{d{t}^{2}}``: ``{d}^{2}`` is ``d^{2}``), for `read_leibniz` to match;
    ``tokens`` itself when there are none. Only a brace opened at the start, after a bracket, an
    operator or a ``d``, so a command's argument (``\\sqrt{x}^{2}``, ``\\dot{t}^2``, ``\\frac{a}{b}^2``) is kept.
    """
    out: list[Token] | None = None
    n = len(tokens)
    for i, token in enumerate(tokens):
        if (_is(token, "open", "{") and i + 3 < n and _plain_name(tokens[i + 1]) and _is(tokens[i + 2], "close", "}")
                and (tokens[i + 3].kind == "sup" or _is(tokens[i + 3], "op", "^"))):
            before = tokens[i - 1] if i else None
            if (before is None or before.kind == "open" or (before.kind == "op" and before.value not in ("^", "_"))
                    or (_plain_name(before) and before.value == "d" and not before.order)):
                if out is None:
                    out = list(tokens)
                out[i] = out[i + 2] = None
    return [t for t in out if t is not None] if out is not None else tokens


# Largest operand (in nodes) of d/dt (first order) and d²/dt² (second order): the Lagrangian's
# momenta and energies students differentiate are a few dozen nodes.
_MAX_OPERAND = {1: 150, 2: 60}


def _rate(symbol: sympy.Symbol, ns, shown: str, position: int) -> sympy.Expr:
    """``d symbol/dt`` in the namespace: the declared derivative (θ -> θ̇, θ̇ -> θ̈), 1 for the time,
    0 for a parameter; an error for a quantity of the motion whose derivative is not declared."""
    name = symbol.name
    variable = ns[name] if name in ns.names else None
    if variable is not None and (variable.kind == "time" or (name == "t" and variable.dimension == _TIME)):
        return sympy.S.One
    wanted = derivative_name(name, 1)
    found = _lookup(wanted, ns) if not name.endswith("ddot") else None
    if found is not None:
        return found
    if variable is not None and is_constant(symbol, ns):
        return sympy.S.Zero  # a parameter: constant in time
    raise ExpressionError(f"'{shown}' needs the time derivative of {name}, which this problem has no "
                          "variable for", position, "unknown_name",
                          "differentiate it yourself and write the derivatives with dots, as in θ̇ or ẍ")


def time_derivative(expr: sympy.Expr, order: int, ns, shown: str, position: int) -> sympy.Expr:
    """The total time derivative of ``expr`` (``d/dt(m r² φ̇)`` = 2 m r ṙ φ̇ + m r² φ̈), by the chain rule
    through the namespace's declared derivatives; parameters are constant.

    Examples
    --------
    >>> from grader.expressions import Namespace, Variable
    >>> ns = Namespace([Variable("m", "mass", "positive"), Variable("r", "length", "positive", "coordinate"),
    ...                 Variable("rdot", "velocity", "real", "velocity"),
    ...                 Variable("phidot", "angular_velocity", "real", "velocity"),
    ...                 Variable("phiddot", "angular_acceleration", "real", "acceleration")])
    >>> r, rdot, phidot, phiddot, m = (ns.symbol(n) for n in ("r", "rdot", "phidot", "phiddot", "m"))
    >>> time_derivative(m*r**2*phidot, 1, ns, "d/dt", 0) == 2*m*r*rdot*phidot + m*r**2*phiddot
    True
    """
    limit = _MAX_OPERAND.get(order, _MAX_OPERAND[2])
    if node_count(expr, limit) > limit:
        # the product rule multiplies a product's size by its length, at each order: a 500-character
        # product of 80 factors would take a minute to differentiate twice
        raise ExpressionError(f"'{shown}' is applied to an expression too long to differentiate here", position,
                              "too_large", "differentiate it yourself and write the derivatives with dots, as in θ̇ or ẍ")
    for _ in range(order):
        rates = {s: _rate(s, ns, shown, position) for s in sorted(expr.free_symbols, key=lambda s: s.name)}
        expr = sympy.Add(*(expr.diff(s) * rate for s, rate in rates.items() if rate != 0))
    if expr.has(sympy.DiracDelta, sympy.Heaviside, sympy.Derivative, sympy.Subs):
        # sign(x), Abs(x)'s derivative at 0, atan2 across its cut: no derivative everywhere
        raise ExpressionError(f"'{shown}' is applied to something with no derivative everywhere (a jump, as "
                              "in sign)", position, "syntax",
                              "differentiate it yourself and write the derivatives with dots, as in θ̇ or ẍ")
    return expr
