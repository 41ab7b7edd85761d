"""Whitelist parser: text -> sympy, built node by node (never eval/sympify/parse_expr).

A Pratt parser over the tokens of :mod:`.tokens`.  Binding powers, loosest first::

    =            equations only (parse_equation / parse_system)
    + -          10, left   (a sum is built as one Add)
    * / implicit 20, left   (2 m g, 2(a+b), (a)(b), g(1 - x) with g a variable; one Mul)
    unary - +    prefix     (-a*b is -(a*b) and -x^2 is -(x^2), but 2^-x*y is 2^(-x)*y)
    ^ ** ²       30, right  (2^3^2 is 2^9)

Implicit multiplication binds like ``*``: ``1/2 m`` is m/2 and ``g/2l`` is
(g/2)·l (a note says so).  Sums and products are collected and built in one
step, the way sympy's printer writes them, so ``str(expr)`` reads back to the
same tree.

Functions are whitelisted (:mod:`.functions`) and take ``(args)`` or, for a
single argument, one following factor: ``cos theta``, ``sin 2x`` (= sin(2x)),
``cos theta^2`` (= cos(theta^2)).  ``sin^2 x`` is sin(x)^2 and ``sin^-1 x`` is
asin(x).  Names resolve only through the :class:`~.variables.Namespace`
(:mod:`.names`).  Numbers are exact: ``0.5*m == m/2``.  Time derivatives in
Leibniz notation (``dθ/dt``, ``\\frac{d^2x}{dt^2}``, ``d/dt(θ)``) become one token
each before parsing (:mod:`.leibniz`) and read as ``θ̇``, ``ẍ`` do; ``d/dt(m r² φ̇)`` is the bracket
differentiated by the chain rule.

What other tools print reads as it means there: Mathematica's ``Sin[θ]^2`` (a call, squared),
``θ''[t]``, ``D[θ[t], t]`` and ``Pi``; ``diff(θ(t), t)`` of Maple, SymPy and Maxima (Maple's ``diff(θ(t), t$2)``,
SymPy's printed ``Derivative(θ(t), (t, 2))``); Python's
``np.sin``; MATLAB's ``.*``. Where the same text means different things in different tools
(``ArcTan[x, y]``, capital ``ATAN2`` and ``LOG``, ``2·5``), the refusal names both readings.
"""

from __future__ import annotations

from collections.abc import Mapping
import re
import threading
from collections import OrderedDict
from dataclasses import dataclass, field, replace

import sympy

from .printing import to_latex, to_text

from .dimensions import dimension_of, parse_dimension
from .errors import DimensionError, ExpressionError
from .functions import FUNCTIONS, INVERSES
from .leibniz import dotted, read_leibniz, time_derivative
from .magnitudes import MAX_DIGITS, checked, guarded_pow, not_real
from .names import GREEK_LETTERS, INVERSE_INSTEAD, WRITE_INSTEAD, derivative_name, resolve_name
from .tokens import Token, check_brackets, tokenize
from .variables import Namespace

__all__ = ["Parsed", "ParsedEquation", "parse_expression", "parse_equation", "parse_system",
           "MAX_LENGTH"]

#: Longest text accepted, checked before anything else is done with it.
MAX_LENGTH = 2000
#: Deepest recursion of the parser (prefix-operator chains, powers of powers).
MAX_RECURSION = 200

_ADD, _MUL, _POW = 10, 20, 30
#: Largest index of a root typed as sqrt[n]{x}.
MAX_ROOT_INDEX = 1000
# Functions whose argument may have a dimension (√(g l), |v|); every other one needs a dimensionless one.
_ANY_DIMENSION = {"√", "sqrt", "cbrt", "abs", "sign", "sgn", "Abs"}
#: Roots read by `_Parser.function_argument`, by their index (√ and ∛ carry theirs in the token).
_ROOT_INDEX = {"√": None, "sqrt": 2, "cbrt": 3}

# cos ω t: at most this many factors after an argument with a dimension are taken into it.
_MOST_FACTORS_TAKEN = 2
_TIME = parse_dimension("time")
# The exponent letter of a number in e-notation (2E+3, 1.5e-2), which may also be a declared variable; the
# exponent signed with any minus tokens.number takes.
_EXPONENT_LETTER = re.compile(r"^[0-9.]+([eE])[-+−–—‒‐‑﹣－＋]?[0-9]+$")
_MINUSES = str.maketrans({ch: "-" for ch in "−–—‒‐‑﹣－"} | {"＋": "+"})
# \pi2, \omega12, \pi2x: a LaTeX command with digits (and letters) after it, which the tokenizer reads
# as one name (see latex_argument).
_UNBRACED_FRAC_DIGITS = re.compile(r"\\[dt]?frac\s*(\d)\s*(\d)\s*$")
_COMMAND_THEN_DIGITS = re.compile(r"^\\([A-Za-z]+)\d[A-Za-z0-9]*$")
_I = sympy.I
_OPERATOR_POWER = {"+": _ADD, "-": _ADD, "*": _MUL, "/": _MUL, "^": _POW}
# Spreadsheet functions in capitals whose meaning differs from the same word here: (message, hint).
_SPREADSHEET_CAPITALS = {
    "ATAN2": ("'ATAN2' in capitals is the spreadsheet function, whose arguments are in the reverse order "
              "(Excel's ATAN2(x, y) is atan2(y, x) here)",
              "write atan2(y, x) in small letters for the angle of the point (x, y), or atan(y/x)"),
    "LOG": ("'LOG' in capitals is the spreadsheet's (and a calculator's) logarithm to base 10, but log here "
            "is the natural logarithm ln", "write ln(x) for the natural logarithm, or log10(x) for base 10"),
}
# Calls that differentiate (Maple's, SymPy's and Maxima's diff, Mathematica's D), with their bracket.
# The periodic functions, whose value at x needs x reduced modulo π to as many digits as x has.
_PERIODIC = frozenset({"sin", "cos", "tan", "cot", "sec", "csc"})
_PERIODIC_LIMIT = sympy.Integer(10) ** MAX_DIGITS


def _beyond(number: sympy.Expr, bound: sympy.Integer) -> bool:
    """Whether the number (built by the parser) is larger than ``bound`` in absolute value; found at 15 digits,
    which an exponential of any size costs no more than its exponent's."""
    value = number.evalf(15)
    return value.is_comparable and abs(value) > bound


# Blank text, or LaTeX's spacing commands (MathQuill writes a typed space as '\ '): \sin 2\ \theta is \sin 2 \theta.
_SPACING_ONLY = re.compile(r"(?:\s|~|\\[ ,;:!>]|\\(?:quad|qquad|thinspace|medspace|thickspace|enspace)(?![A-Za-z]))*")

# SymPy prints a derivative as Derivative(θ(t), t) and Derivative(θ(t), (t, 2)).
_DIFF_CALLS = {"diff": "(", "D": "[", "Derivative": "("}
_PAIRS_CLOSE = {"(": ")", "[": "]", "{": "}"}
# What to type instead of a two-argument call in square brackets (see Parser.call_arguments).
_BRACKET_PAIR_HINTS = {
    "atan": "write atan2(y, x) for the angle of the point (x, y), or atan(y/x)",
    "log": "write log(x, b) for the logarithm of x to base b",
}
_ATOM_STARTS = ("number", "name", "open", "root", "command", "derivative", "time_derivative")
# Left binding power of the tokens that are not operators: a superscript is a power, an atom
# starts an implicit product, a prime binds tightest (so the parser reaches it and complains).
_KIND_POWER = {"sup": _POW, "prime": _POW + 10, **{kind: _MUL for kind in _ATOM_STARTS}}


# SI prefixes edX's calculator reads after a number (5k is 5000), with their powers of ten
_SI_SUFFIXES = {"T": 12, "G": 9, "M": 6, "k": 3, "c": -2, "m": -3, "u": -6, "n": -9, "p": -12}


@dataclass(frozen=True)
class Parsed:
    """A parsed expression.

    Attributes
    ----------
    expr : sympy.Expr
    text : str
        Canonical text (sympy's ``str`` with our variable names); it parses back to ``expr``.
    latex : str
        LaTeX with the namespace's variable LaTeX (``\\dot{\\theta}``).
    notes : list of str
        How ambiguous input was read ("read 'mg' as m·g").
    conditions : tuple of sympy.Expr
        The real domain of the text as typed, where sympy's simplification lost it: expressions that
        must be defined wherever the text is (``sqrt(x)`` for ``sqrt(x)^2``, whose ``expr`` is ``x``).
    """

    expr: sympy.Expr
    text: str
    latex: str
    notes: list[str] = field(default_factory=list)
    conditions: tuple = ()


@dataclass(frozen=True)
class ParsedEquation:
    """A parsed equation ``lhs = rhs``; attributes as in :class:`Parsed`."""

    lhs: sympy.Expr
    rhs: sympy.Expr
    text: str
    latex: str
    notes: list[str] = field(default_factory=list)
    conditions: tuple = ()

    @property
    def residual(self) -> sympy.Expr:
        """``lhs - rhs``, zero exactly when the equation holds."""
        return self.lhs - self.rhs

    @property
    def equation(self) -> sympy.Equality:
        return sympy.Eq(self.lhs, self.rhs, evaluate=False)


# Functions with a restricted real domain, whose argument the typed expression constrains even when
# sympy simplifies the call away (exp(log(x)) is x).
_RESTRICTED = frozenset({"log", "asin", "acos", "acosh", "atanh"})


def _real_domain(expr: sympy.Expr, nodes: list[tuple[sympy.Expr, sympy.Expr]]) -> tuple[sympy.Expr, ...]:
    """The conditions of ``expr``'s real domain that sympy's simplifications dropped.

    Each is an expression that must be defined (real) where ``expr`` is: ``sqrt(x)`` for a
    ``sqrt(x)**2`` typed, ``log(x)`` for ``exp(log(x))``. A node that is still in ``expr``, or whose
    base is nonnegative by its symbols' assumptions, needs no condition.
    """
    if not nodes:
        return ()
    present = set(sympy.preorder_traversal(expr))
    conditions = []
    for node, condition in nodes:
        if node in present or condition in conditions:
            continue
        if condition.is_Pow and condition.base.is_nonnegative:
            continue
        if isinstance(condition, sympy.log) and condition.args[0].is_positive:
            continue
        conditions.append(condition)
    return tuple(conditions)


def _empty_group_before_power(tokens: list[Token]) -> list[Token]:
    """The tokens without each empty group ``{}`` between an operand and its power: editors (Word's
    LaTeX, Mathpix's ``{ }^{2}``, MathType) write ``x{}^{2}`` and ``\\dot{\\theta}{}^{2}`` for x² and θ̇², the
    group only carrying the superscript. One with nothing before it (``{}^{2}x``, a prescript) is kept,
    and refused as empty brackets."""
    keep: list[Token] | None = None
    for i in range(1, len(tokens) - 2):
        opener, closer, power = tokens[i], tokens[i + 1], tokens[i + 2]
        if (opener.kind == "open" and opener.value == "{" and closer.kind == "close" and closer.value == "}"
                and power.kind == "op" and power.value == "^"
                and tokens[i - 1].kind in ("name", "number", "close", "derivative")):
            if keep is None:
                keep = list(tokens)
            keep[i] = keep[i + 1] = None
    return tokens if keep is None else [t for t in keep if t is not None]


# Functions whose powers are written before the argument (sin²x): sin x² could mean that, and is noted
_SQUARED_BEFORE = frozenset({"sin", "cos", "tan", "cot", "sec", "csc", "sinh", "cosh", "tanh", "coth", "sech", "csch"})

# Two-argument functions whose Mathematica form takes its arguments in our order (Power[x, y], Surd[x, n])
_SAME_ORDER_IN_MATHEMATICA = frozenset({"pow", "surd"})
_ARGUMENT_NAMES = {"pow": "x, y", "surd": "x, n"}  # what a refusal shows as their arguments (atan2's are y, x)

# ASCIIMath's operators spelled as words (MathJax, Moodle, WeBWorK, Canvas: a xx b, a cdot b, a times b, a div b)
_OPERATOR_WORDS = {"xx": "*", "cdot": "*", "times": "*", "div": "/"}
_OPERAND_ENDS = ("name", "number", "close", "sup", "derivative")


def _operator_words(tokens: list[Token], ns: Namespace) -> list[Token]:
    """The tokens with each ASCIIMath operator word between two operands made its operator: ``m xx g`` is
    m·g, ``a div b`` is a/b. A word the problem declares stays its variable; one its variables spell glued
    (``xx`` where x is a variable: it was read as x·x silently, ``x xx k`` gave k x³) is refused naming both."""
    found = [k for k, t in enumerate(tokens) if t.kind == "name" and t.value in _OPERATOR_WORDS
             and not t.order and t.text == t.value and t.value not in ns.names]
    if not found:
        return tokens
    tokens = list(tokens)
    for k in found:
        word = tokens[k]
        before, after = tokens[k - 1] if k else None, tokens[k + 1]
        if before is None or before.kind not in _OPERAND_ENDS or after.kind not in _ATOM_STARTS:
            continue
        try:  # glued, the word may name the problem's variables: xx is x·x where x is one
            glued = resolve_name(word.value, ns)
        except ExpressionError:
            glued = None
        if glued is not None and glued.kind in ("symbol", "split"):
            parts = glued.value if glued.kind == "split" else [str(glued.value)]
            shown, sign = "·".join(parts), {"*": "×", "/": "÷"}[_OPERATOR_WORDS[word.value]]
            raise ExpressionError(f"'{word.text}' is ASCIIMath's {sign}, or {shown} typed without spaces", word.pos,
                                  "ambiguous", f"write {_OPERATOR_WORDS[word.value]} for the operator, or "
                                               f"{'*'.join(parts)} for the product of the variables")
        tokens[k] = Token("op", _OPERATOR_WORDS[word.value], word.pos, word.end, word.text, word.space_before)
    return tokens


class _Parser:
    def __init__(self, tokens: list[Token], namespace: Namespace, text: str) -> None:
        # dθ/dt, \frac{d^2x}{dt^2}, d/dt(θ): one derivative token each (see leibniz.py).
        if "{" in text and "^" in text:
            tokens = _empty_group_before_power(tokens)
        self.tokens = _operator_words(read_leibniz(tokens, namespace, text), namespace)
        self.ns = namespace
        self.text = text
        # LaTeX (a command or a brace in it): a superscript is one token there, as editors show it
        self.latex = "\\" in text or "{" in text
        self.i = 0
        self.depth = 0
        self.notes: list[str] = []
        # The last product built and its factors, so a/(b*c) can divide factor by factor.
        self.last_product: tuple[sympy.Expr, list[sympy.Expr]] | None = None
        # (node as built, what must be defined for it to be): see _real_domain.
        self.domain_nodes: list[tuple[sympy.Expr, sympy.Expr]] = []

    # -- token access -----------------------------------------------------
    def peek(self, offset: int = 0) -> Token:
        i = self.i + offset
        tokens = self.tokens
        return tokens[i] if i < len(tokens) else tokens[-1]

    def advance(self) -> Token:
        # Stops at the end token, so self.i is always a valid index (peek() need not clamp it).
        i = self.i
        token = self.tokens[i]
        if i + 1 < len(self.tokens):
            self.i = i + 1
        return token

    def refuse_si_suffix(self, token: Token, raw: str, unknown: ExpressionError) -> None:
        """5k, 1.2m, 5n with no such variable: edX's calculator reads an SI prefix glued to a number as its power
        of ten (5k is 5000); say so, with the power of ten to write ('5n' was "did you mean 'ln'?")."""
        previous = self.before(token)
        if (unknown.code != "unknown_name" or raw not in _SI_SUFFIXES or token.order or previous is None
                or previous.kind != "number" or previous.end != token.pos):
            return
        unit = "; if it is the unit, delete it: units are not part of the answer" if raw in ("m", "T") else ""
        raise ExpressionError(f"unknown name '{token.text}' after the number {previous.text}: this problem has no "
                              f"variable {token.text}", token.pos, "unknown_name",
                              f"if {token.text} is the SI prefix (as some calculators read it), write the power of "
                              f"ten: {previous.text}e{_SI_SUFFIXES[raw]}{unit}")

    def before(self, token: Token) -> Token | None:
        """The token just before ``token`` (for "'+' needs something after it")."""
        for index, candidate in enumerate(self.tokens):
            if candidate is token:
                return self.tokens[index - 1] if index else None
        return None

    def bracket_depth(self, token: Token) -> int:
        """How many brackets are open at ``token``."""
        depth = 0
        for candidate in self.tokens:
            if candidate is token:
                break
            depth += {"open": 1, "close": -1}.get(candidate.kind, 0)
        return depth

    def note(self, text: str) -> None:
        if text not in self.notes:
            self.notes.append(text)

    def unexpected(self, token: Token) -> ExpressionError:
        if token.kind == "bad":
            return token.error
        before = self.before(token)
        if token.kind == "end":
            if before is not None and before.kind == "op":
                return ExpressionError(f"'{before.text}' needs something after it", before.pos, "syntax",
                                       f"finish the expression after '{before.text}', or delete it")
            return ExpressionError("the expression ends too early", token.pos, "syntax", "finish the expression")
        if token.kind == "close":
            if before is not None and before.kind == "op":
                return ExpressionError(f"'{before.text}' needs something after it", before.pos, "syntax",
                                       f"write something between '{before.text}' and '{token.text}'")
            if before is not None and before.kind == "open":
                return ExpressionError("empty brackets", before.pos, "syntax", "put an expression inside, or delete them")
        if token.kind == "op" and token.value == "=":
            if self.bracket_depth(token) > 0:
                # {x = 2} from Maple's solve, [x = 2] from a list: the equation is inside brackets
                return ExpressionError("an equation cannot be inside brackets", token.pos, "syntax",
                                       "delete the brackets around the equation, as in x = 2")
            return ExpressionError("'=' is only allowed once, between the two sides of an equation",
                                   token.pos, "syntax", "separate several equations with ';'")
        if token.kind == "op" and token.value == ",":
            decimals = re.match(r"[0-9]+", self.text[token.end:])
            if before is not None and before.kind == "number" and before.end == token.pos and decimals:
                # 0,5: a decimal comma, as most of Europe writes it
                digits = decimals.group()
                return ExpressionError(f"'{before.text},{digits}' has a decimal comma; a comma can only separate "
                                       "function arguments here", token.pos, "syntax",
                                       f"write a decimal point, as in {before.text}.{digits}")
            return ExpressionError("a comma can only separate function arguments, as in atan2(y, x)",
                                   token.pos, "syntax")
        if token.kind == "op" and token.value == ";":
            typed = token.text.strip()  # ';', or the \text{ and } that joins two equations as ';' does
            if not self.text[token.end:].strip():  # m*g/3; as MATLAB's statements end
                return ExpressionError(f"a '{typed}' at the end is not part of a formula", token.pos, "syntax",
                                       f"delete the '{typed}'")
            return ExpressionError(f"'{typed}' cannot be used in a single expression", token.pos,
                                   "unsupported_function", "write one expression")
        if token.kind == "prime":
            return ExpressionError("a prime (') can only follow a variable name, as in theta'",
                                   token.pos, "syntax")
        if token.kind == "sup":
            return ExpressionError(f"superscript '{token.text}' has nothing to raise", token.pos, "syntax",
                                   "put it right after what it raises, as in x²")
        return ExpressionError(f"unexpected '{token.text}'", token.pos, "syntax",
                               f"delete '{token.text}' or put an operator before it")

    def expect_close(self, opener: Token) -> Token:
        token = self.advance()
        if token.kind != "close":
            raise self.unexpected(token)
        return token

    # -- Pratt core ---------------------------------------------------------
    def expression(self, rbp: int = 0) -> sympy.Expr:
        self.depth += 1
        if self.depth > MAX_RECURSION:
            raise ExpressionError("the expression is nested too deeply", self.peek().pos, "too_deep",
                                  "simplify the expression first")
        start = self.peek()
        left = self.nud(self.advance(), rbp)
        # Factors of a product are collected and multiplied once, as sympy's printer
        # assumes: 33*(E - 4)*f is Mul(33, E - 4, f), while building it pairwise would
        # distribute 33 over (E - 4) first and str(expr) would not read back.
        factors: list[sympy.Expr] | None = None
        terms: list[sympy.Expr] | None = None  # likewise for sums: one Add, not n pairwise ones
        previous_op = None
        tokens = self.tokens
        while True:
            token = tokens[self.i]  # self.peek(), inlined (see advance)
            lbp = self.left_power(token)
            if lbp <= rbp:
                break
            if lbp == _MUL and terms is None:
                factors = factors if factors is not None else [left]
                op = self.product_factor(token, factors)
                if op == "implicit" and previous_op == "/":
                    end = self.tokens[self.i - 1].end
                    self.note(f"read '{self.text[start.pos:end]}' as "
                              f"({self.text[start.pos:token.pos].strip()})·{self.text[token.pos:end]}")
            elif lbp == _ADD:
                if factors is not None:
                    left, factors = self.product(factors, token.pos), None
                terms = terms if terms is not None else [left]
                self.advance()
                right = self.expression(_ADD)
                terms.append(right if token.value == "+" else checked(-right, token.pos))
                op = token.value
            else:
                if factors is not None:
                    left, factors = self.product(factors, token.pos), None
                if terms is not None:
                    left, terms = checked(sympy.Add(*terms), token.pos), None
                left, op = self.led(token, left)
            previous_op = op
        if factors is not None:
            left = self.product(factors, start.pos)
        if terms is not None:
            left = checked(sympy.Add(*terms), start.pos)
        self.depth -= 1
        return left

    def product(self, factors: list[sympy.Expr], position: int) -> sympy.Expr:
        result = checked(sympy.Mul(*factors), position)
        self.last_product = (result, factors)
        return result

    def product_factor(self, token: Token, factors: list[sympy.Expr]) -> str:
        """Parse the next factor of a product (after ``*``, ``/`` or side by side) into ``factors``."""
        if token.kind == "op":
            self.advance()
            right = self.expression(_MUL)
            if token.value == "*":
                factors.append(right)
                return "*"
            # a/(b*c) divides by each factor, so 1/(8*(m - 2)) is not first distributed to 1/(8*m - 16).
            product, parts = self.last_product or (None, None)
            for part in (parts if product is right and parts else [right]):
                factors.append(guarded_pow(part, sympy.Integer(-1), token.pos))
            return "/"
        if token.kind == "number":
            unbraced = _UNBRACED_FRAC_DIGITS.search(self.text[:token.pos])
            if unbraced:
                # \frac1234 is ½·34 to TeX (one digit per argument) and 12/34 to whoever typed it
                a, b = unbraced.group(1), unbraced.group(2)
                raise ExpressionError(f"'{self.text[unbraced.start():token.end]}' is \\frac{{{a}}}{{{b}}}·{token.text} to LaTeX, "
                                      "which takes one digit for each argument without braces", unbraced.start(),
                                      "ambiguous", f"write \\frac{{{a}{b}}}{{{token.text}}} or \\frac{{{a}}}{{{b}{token.text}}} "
                                      "with braces, or put * before the number")
            before = next((t for t in reversed(self.tokens[:self.i]) if t.pos < token.pos), None)
            if before is not None and before.kind == "number" and before.text.isdigit() and len(before.text) <= 3 \
                    and len(token.text) == 3 and token.text.isdigit() and len(self.text[before.end:token.pos]) == 1:
                # 1 000, 12 500: a number's thousands set apart by a space, as many countries print them
                raise ExpressionError(f"missing operator before '{token.text}'", token.pos, "syntax",
                                      f"for the number {before.text}{token.text}, write it without the space (a "
                                      f"thousands separator); for a product, write {before.text}*{token.text}")
            raise ExpressionError(f"missing operator before '{token.text}'", token.pos, "syntax",
                                  "write * (or another operator) before the number")
        factors.append(self.expression(_MUL))
        return "implicit"

    def left_power(self, token: Token) -> int:
        if token.kind == "op":
            return _OPERATOR_POWER.get(token.value, 0)
        return _KIND_POWER.get(token.kind, 0)

    def led(self, token: Token, left: sympy.Expr) -> tuple[sympy.Expr, str]:
        """Powers: ``^`` (right-associative) and superscripts."""
        if token.kind == "op" and token.value == "^":
            base = self.tokens[self.i - 1]
            self.advance()
            if self.peek().kind == "sup" and not self.peek().space_before:
                # x^², θ̇^⁻¹: a caret, then the power as a superscript (a phone's keyboard makes 2 into ²)
                return guarded_pow(left, sympy.Integer(self.advance().value), token.pos), "^"
            bracketed = self.peek().kind == "open"
            exponent = self.expression(_POW - 1)
            after = self.peek()
            if (exponent in (1, -1) and self.tokens[self.i - 1].text == "1" and after.kind == "op"
                    and after.value == "/"):
                # x^1/2 is x/2 and x^-1/2 is 1/(2x) by precedence, the classic slips for √x and 1/√x
                divisor, power = self.peek(1).text, "1" if exponent == 1 else "-1"
                self.note(f"read '^{power}/{divisor}' as the power {power}, then divided by {divisor}: write "
                          f"^({power}/{divisor}) for the power {power}/{divisor}")
            if left is sympy.E and base.kind == "name":
                # e^-kt, e^2x: the factors typed glued to the exponent stay in it, as nobody means
                # e^(-k)·t (x^2y stays x²·y: only the exponential's exponent is read so). Not in LaTeX,
                # where e^2x is e²·x, as MathQuill and MathLive show what the student typed (read as
                # e^(2x), an answer e^(2x) was accepted for e²x).
                if not (self.latex and not bracketed):
                    exponent = self.glued_factors(exponent, base.pos, "e^")
                if not bracketed:  # e^(-k) t: the student closed the exponent
                    exponent = self.dimensionless_argument(exponent, base.pos, "e^")
            return self.power(left, exponent, token.pos), "^"
        if token.kind == "sup":
            self.advance()
            return guarded_pow(left, sympy.Integer(token.value), token.pos), "^"
        raise self.unexpected(token)

    def power(self, base: sympy.Expr, exponent: sympy.Expr, position: int) -> sympy.Expr:
        """``base ** exponent``, remembering that a fractional power needs ``base >= 0`` over the reals.

        sympy combines powers by laws that hold for complex numbers (``sqrt(x)**2`` is ``x``), so
        the typed expression's real domain is kept aside, before any law is applied.
        """
        value = guarded_pow(base, exponent, position)
        if not exponent.is_Integer and not base.is_number:
            self.domain_nodes.append((value, sympy.Pow(base, sympy.S.Half, evaluate=False)))
        return value

    def root(self, arg: sympy.Expr, index: int, position: int) -> sympy.Expr:
        """The ``index``-th root a radical sign means: ``√x`` needs x >= 0, but an odd root is real
        for every x (``∛(-8)`` and ``\\sqrt[3]{-8}`` are -2), as ``cbrt`` is; a power ``x^(1/3)`` keeps
        the reals' rule for fractional powers (x >= 0)."""
        if index % 2 == 0:
            return self.power(arg, sympy.Rational(1, index), position)
        return checked(sympy.sign(arg) * guarded_pow(sympy.Abs(arg), sympy.Rational(1, index), position), position)

    def nud(self, token: Token, rbp: int = 0) -> sympy.Expr:
        kind = token.kind
        if kind == "number":
            letter = _EXPONENT_LETTER.search(token.text)
            if letter and letter.group(1) in self.ns.names:
                # 2E+3 with a variable E (an energy, a Young's modulus): 2·10³ or 2E + 3.
                e = letter.group(1)
                mantissa, rest = token.text[:letter.start(1)], token.text[letter.end(1):].translate(_MINUSES)
                raise ExpressionError(f"'{token.text}' could be {mantissa}×10^{rest.lstrip('+')} or "
                                      f"{mantissa}·{e} {rest[0] if rest[0] in '+-' else '·'} {rest.lstrip('+-')}, "
                                      f"and {e} is a variable here", token.pos, "ambiguous",
                                      f"write {mantissa}*10^{rest.lstrip('+')} for the number, or "
                                      f"{mantissa}*{e}{' ' + rest[0] + ' ' if rest[0] in '+-' else '*'}"
                                      f"{rest.lstrip('+-')} for the variable")
            if token.decimal:
                self.note(f"decimals are read as exact fractions ({token.text} = {token.value})")
            return token.value
        if kind == "name":
            return self.name(token, rbp)
        if kind == "op" and token.value in "+-":
            # -a*b is -(a*b) (one product, as sympy prints it), but 2^-x*y is 2^(-x)*y.
            operand = self.expression(max(rbp, _ADD))
            return checked(-operand, token.pos) if token.value == "-" else operand
        if kind == "open":
            if self.peek().kind == "close":
                raise ExpressionError("empty brackets", token.pos, "syntax", "put an expression inside, or delete them")
            inner = self.expression(0)
            self.expect_close(token)
            return inner
        if kind == "root":
            bracketed = self.peek().kind == "open"
            if bracketed and self.raised_after_bracket():
                # √(x)² is the square of √(x), as sqrt(x)² is: the bracket closes the radicand
                opener = self.advance()
                radicand = self.expression(0)
                self.expect_close(opener)
                return self.root(radicand, token.value, token.pos)
            value = self.root(self.function_argument(token, "√"), token.value, token.pos)
            after = self.peek()
            if not bracketed and after.kind == "op" and after.value in "+-" and not value.is_number:
                # √x²+y² is √(x²) + y² by precedence; the sum under the root needs its brackets
                self.note(f"read '{self.text[token.pos:after.pos].strip()}' as the root of that alone, then "
                          f"'{after.value}' what follows: write {token.text}(…) around everything the root covers")
            return value
        if kind == "command":
            return self.latex_command(token)
        if kind == "derivative":  # Leibniz notation, already resolved (or refused) by read_leibniz
            if token.error is not None:
                raise token.error
            self.note(f"read '{token.text}' as {dotted(token.value.name)}")
            return token.value
        if kind == "time_derivative":  # d/dt(…) of an expression: the bracket, differentiated
            return self.time_derivative(token)
        raise self.unexpected(token)

    def raised_after_bracket(self) -> bool:
        """Whether the bracket that opens at the next token is followed, once closed, by a power."""
        depth = 0
        for n in range(self.i, len(self.tokens)):
            kind = self.tokens[n].kind
            depth += {"open": 1, "close": -1}.get(kind, 0)
            if depth == 0:
                after = self.tokens[n + 1] if n + 1 < len(self.tokens) else None
                return after is not None and (after.kind == "sup" or (after.kind == "op" and after.value == "^"))
        return False

    def time_derivative(self, token: Token) -> sympy.Expr:
        """``d/dt(m r² φ̇)``: the bracket after the operator, differentiated by the chain rule through the
        declared derivatives (`leibniz.time_derivative`); a power right after the bracket is refused as
        ambiguous (the derivative of the square, or the square of the derivative?)."""
        opener = self.advance()
        inner = self.expression(0)
        self.expect_close(opener)
        following = self.peek()
        if following.kind == "sup" or (following.kind == "op" and following.value == "^"):
            last = following if following.kind == "sup" else self.tokens[min(self.i + 1, len(self.tokens) - 1)]
            shown = self.text[token.pos:last.end]
            raise ExpressionError(f"'{shown}' is ambiguous: it is not clear what {token.text} applies to",
                                  token.pos, "ambiguous",
                                  f"write ({self.text[token.pos:self.tokens[self.i - 1].end]})^2 for the square "
                                  "of the derivative, or differentiate the whole yourself")
        value = checked(time_derivative(inner, token.value, self.ns, token.text, token.pos), token.pos)
        # d(m l² θ̇)/dt was put in operator form (leibniz._operator_first): the token spans the typed /dt too
        end = max(token.end, self.tokens[self.i - 1].end)
        self.note(f"read '{self.text[token.pos:end]}' as {value}")
        return value

    def diff_call(self, token: Token) -> sympy.Expr:
        """``diff(θ(t), t)``, ``diff(x, t, t)``, ``diff(x, t, 2)`` (Maple, SymPy, Maxima) and Mathematica's
        ``D[θ[t], t]``, ``D[x[t], {t, 2}]``: the time derivative of the first argument, which every one
        of these systems means (differentiating by anything but the time t is refused by name)."""
        opener = self.advance()
        if self.peek().kind == "close":
            raise ExpressionError(f"{token.text}() needs an expression and the time, as in {token.text}(θ(t), t)",
                                  opener.pos, "syntax")
        inner = self.expression(0)
        order = 0
        while self.peek().kind == "op" and self.peek().value == ",":
            self.advance()
            order += self.diff_order(token)
        self.expect_close(opener)
        shown = self.text[token.pos:self.tokens[self.i - 1].end]
        if order == 0:
            raise ExpressionError(f"'{shown}' does not say what to differentiate by", token.pos, "syntax",
                                  f"write {token.text}{opener.value}θ(t), t{_PAIRS_CLOSE[opener.value]} for the "
                                  "time derivative, or θ̇ (thetadot)")
        if order > 4:
            raise ExpressionError(f"'{shown}' is a derivative of order {order}", token.pos, "syntax",
                                  "answers here need at most the second time derivative, as in θ̈")
        if isinstance(inner, sympy.Symbol):
            # θ's second derivative is the declared θ̈ even when θ̇ is not declared (as d²θ/dt² is)
            try:
                value = resolve_name(inner.name, self.ns, order=order, typed=shown, position=token.pos)
            except ExpressionError:
                value = None
            if value is not None and value.kind == "symbol":
                self.note(f"read '{shown}' as {dotted(value.value.name)}")
                return value.value
        value = checked(time_derivative(inner, order, self.ns, shown, token.pos), token.pos)
        self.note(f"read '{shown}' as {value}")
        return value

    def diff_order(self, token: Token) -> int:
        """How many times one more argument of `diff_call` differentiates: ``t`` once, ``t, 2`` (a
        number after t) that often, Mathematica's ``{t, 2}``, SymPy's ``(t, 2)`` and Maple's ``t$2`` likewise."""
        start = self.peek()
        braced = start.kind == "open" and start.value in "{("
        if braced:
            self.advance()
        variable = self.advance()
        if not (variable.kind == "name" and variable.value == "t" and not variable.order
                and ("t" not in self.ns.names or self.ns["t"].kind == "time" or self.ns["t"].dimension == _TIME)):
            raise ExpressionError(f"'{token.text}' differentiates by '{variable.text}' here; only time derivatives "
                                  "(by t) are part of these answers", variable.pos, "syntax",
                                  "write the time derivative as θ̇ (thetadot), or as diff(θ(t), t)")
        count = 1
        after = self.peek()
        following = self.tokens[self.i + 1] if self.i + 1 < len(self.tokens) else after
        sequence = after.kind == "number" and self.text[variable.end:after.pos].strip() == "$"  # Maple's t$2
        if sequence or (after.kind == "op" and after.value == "," and following.kind == "number"):
            if not sequence:
                self.advance()
            number = self.advance()
            if not (number.value.is_Integer and 1 <= number.value <= 4):
                raise ExpressionError(f"'{number.text}' is not an order of derivative", number.pos, "syntax",
                                      "give 1 or 2, as in diff(x(t), t, 2)")
            count = int(number.value)
        if braced:
            closer = self.advance()
            if not (closer.kind == "close" and closer.value == _PAIRS_CLOSE[start.value]):
                example = "D[x[t], {t, 2}]" if start.value == "{" else "Derivative(x(t), (t, 2))"
                raise ExpressionError(f"expected '{_PAIRS_CLOSE[start.value]}' after the order, as in {example}",
                                      closer.pos, "syntax")
        return count

    # -- names and functions ------------------------------------------------
    def name(self, token: Token, rbp: int = 0) -> sympy.Expr:
        raw = token.value
        following = self.peek()
        called = following.kind == "open" and following.value == "("
        if token.forced_function:
            return self.function(token.value, token)
        if raw in ("dot", "ddot") and raw not in self.ns and following.kind == "open":
            return self.derivative_call(token, 1 if raw == "dot" else 2)
        if raw in ("dot", "ddot") and raw not in self.ns.names and not token.order and following.kind == "name" \
                and not following.order and not following.forced_function \
                and following.value.lower() not in FUNCTIONS and (raw == "ddot" or not self.after_operand()):
            # ASCIIMath's accents without brackets (Canvas, Moodle, WeBWorK): ddot theta is θ̈, and dot theta is θ̇
            # where nothing comes before it (after an operand, Typst's l dot θ is a product: refused naming both)
            inner = self.advance()
            value = self.derivative_of(inner, 1 if raw == "dot" else 2)
            self.note(f"read '{self.text[token.pos:inner.end]}' as {dotted(value.name)}")
            return value
        if raw in ("frac", "root") and raw not in self.ns.names and not token.order and called:
            two = self.asciimath_pair(token)
            if two is not None:
                return two
        if raw == "D" and not token.order and raw not in self.ns.names and called and following.pos == token.end:
            return self.maple_d(token)
        if (raw in _DIFF_CALLS and not token.order and raw not in self.ns.names and following.kind == "open"
                and following.value == _DIFF_CALLS[raw] and following.pos == token.end):
            return self.diff_call(token)
        if (following.kind == "open" and following.value == "[" and following.pos == token.end and not token.order
                and raw.lower() not in FUNCTIONS):  # sin[x] is a call, as Mathematica writes it
            indexed = None if self.time_bracket(raw) else self.indexed_name(token)
            if indexed is not None:
                return indexed
        if called and following.pos == token.end and not token.order and raw not in self.ns.names:
            self.refuse_round_index(token)
        if not token.order and raw in self.ns.names:
            value = self.ns.symbol(raw)  # what resolve_name answers for a declared name (no notes)
        else:
            try:
                resolved = resolve_name(raw, self.ns, order=token.order, typed=token.text,
                                        position=token.pos, called=called,
                                        before_power=following.kind == "op" and following.value == "^")
            except ExpressionError as unknown:
                self.refuse_superscript_index(token, following, unknown)
                self.refuse_si_suffix(token, raw, unknown)
                if unknown.code == "unknown_name" and following.kind == "bad" and following.text == ":=":
                    # T := m g (Maple, Maxima, a Python walrus): the definition is what to fix, not the name T
                    raise following.error from None
                raise
            for text in resolved.notes:
                self.note(text)
            if resolved.kind == "function":
                return self.function(resolved.value, token)
            if resolved.kind == "split":
                self.splice(token, resolved.value)
                return self.nud(self.advance(), rbp)
            value = resolved.value
        if following.kind == "open" and following.value in "([" and self.time_argument(token, value):
            return value
        if called and following.pos == token.end:
            self.refuse_value_at_time(token, value)
        if called and not following.space_before and not token.order:
            self.note(f"read '{token.text}(…)' as {token.text}·(…): {token.text} is a variable, not a function")
        return value

    def asciimath_pair(self, token: Token) -> sympy.Expr | None:
        """ASCIIMath's ``frac(a)(b)`` (a/b) and ``root(n)(x)`` (the n-th root of x), as MathJax, Moodle,
        WeBWorK and Canvas write them: two bracketed arguments side by side. None when only one bracket
        follows (Typst's ``frac(a, b)``, STACK's ``root(x, n)``: refused with the form to type)."""
        first = self.i
        depth, k = 0, first
        while True:  # the bracket that closes the first argument (the brackets are balanced already)
            depth += {"open": 1, "close": -1}.get(self.tokens[k].kind, 0)
            if depth == 0:
                break
            k += 1
        second = self.tokens[k + 1]
        if second.kind != "open" or any(t.kind == "op" and t.value == "," for t in self.tokens[first:k]):
            return None
        self.advance()
        head = self.expression(0)
        self.expect_close(self.tokens[first])
        opener = self.advance()
        if self.peek().kind == "close":
            raise ExpressionError("empty brackets", opener.pos, "syntax", "put an expression inside, or delete them")
        tail = self.expression(0)
        self.expect_close(opener)
        typed = self.text[token.pos:self.tokens[self.i - 1].end]
        if token.value == "frac":
            self.note(f"read '{typed}' as ASCIIMath's fraction ({head})/({tail})")
            return checked(sympy.Mul(head, guarded_pow(tail, sympy.Integer(-1), token.pos)), token.pos)
        if not (head.is_Integer and 2 <= head <= MAX_ROOT_INDEX):
            raise ExpressionError(f"cannot read the root of index {head} in '{typed}'", token.pos, "syntax",
                                  "the index of a root is a whole number from 2 on, as in root(3)(x); "
                                  "write x^(1/n) for a power")
        self.note(f"read '{typed}' as ASCIIMath's root of index {head}")
        return self.root(tail, int(head), token.pos)

    def indexed_name(self, token: Token) -> sympy.Expr | None:
        """``m[1]``, ``epsilon[0]``, ``x[i]``: a name with an index in square brackets right after it,
        which Maxima (STACK) and programming languages read as a subscript. It is the declared
        ``m_1`` (or ``m1``) when there is one; otherwise it is refused, never read as the product
        m·1 (``epsilon[0]`` would be 0). None when the brackets hold more than one number or name
        (``m[g - a]``: brackets as grouping, a product)."""
        inner, closer = self.tokens[self.i + 1:self.i + 3]
        simple = (inner.kind == "number" and inner.text.isdigit()) or (inner.kind == "name" and not inner.order)
        if not (simple and closer.kind == "close" and closer.value == "]"):
            return None
        typed = self.text[token.pos:closer.end]
        index = inner.text
        for candidate in (f"{token.value}_{index}", f"{token.value}{index}"):
            if candidate in self.ns.names:
                self.i += 3
                self.note(f"read '{typed}' as {candidate}")
                return self.ns.symbol(candidate)
        if token.value.lower() in WRITE_INSTEAD:  # Mathematica's Derivative[1][θ][t]: a function we lack
            raise ExpressionError(f"'{token.text}' is not a function you can use here", token.pos,
                                  "unsupported_function", WRITE_INSTEAD[token.value.lower()])
        raise ExpressionError(f"'{typed}' reads as a subscript in some systems, and there is no variable "
                              f"{token.value}_{index}", token.pos, "syntax",
                              f"write {token.value}_{index} for a subscript, or {token.value}*({index}) for a product")

    def refuse_round_index(self, token: Token) -> None:
        """``m(1)`` with no variable m but a declared m1 (or m_1): MATLAB's index in round brackets. In
        mathematics it is a function m at 1, which does not exist here, so neither reading is taken:
        the refusal names the variable to type."""
        inner, closer = self.tokens[self.i + 1:self.i + 3]
        if not (inner.kind == "number" and inner.text.isdigit() and closer.kind == "close" and closer.value == ")"):
            return
        for candidate in (f"{token.value}{inner.text}", f"{token.value}_{inner.text}"):
            if candidate in self.ns.names:
                typed = self.text[token.pos:closer.end]
                raise ExpressionError(f"'{typed}' is an index in MATLAB, and there is no function {token.text} here",
                                      token.pos, "syntax", f"write {candidate} for the variable {candidate}")

    def time_argument(self, token: Token, value: sympy.Expr) -> bool:
        """Skip a ``(t)`` typed right after a variable (``θ(t)``, ``θ̈(t)``, ``\\ddot{\\theta}(t)``) when no
        variable t is declared, or t is the declared time and the variable moves (a coordinate or one of
        its derivatives: the driven pendulum's ``l θ̈(t) = -g sin θ(t) + …``): the variable as a function
        of time, which it is. A parameter's ``l(t)`` with t declared stays the product. True when skipped."""
        opener = self.peek()
        if not (isinstance(value, sympy.Symbol) and opener.kind == "open" and opener.value in "(["
                and opener.pos == token.end and ("t" not in self.ns.names or self.moves_in_time(value.name))):
            return False
        inner, closer = self.tokens[self.i + 1:self.i + 3]
        if not (inner.kind == "name" and inner.value == "t" and inner.order == 0
                and closer.kind == "close" and closer.value == {"(": ")", "[": "]"}[opener.value]):
            return False
        self.i += 3
        self.note(f"read '{self.text[token.pos:closer.end]}' as {token.text}, a function of time")
        return True

    def refuse_value_at_time(self, token: Token, value: sympy.Expr) -> None:
        """``θ(0)``, ``ẋ(2)``: a coordinate (or its rate) with a number in brackets right after it is its
        value at that time to whoever wrote it, and was read as θ·0 = 0. Neither reading is taken: refused
        naming both."""
        name = getattr(value, "name", None)
        if not (isinstance(value, sympy.Symbol) and name in self.ns.names
                and self.ns[name].kind in ("coordinate", "velocity", "acceleration")):
            return
        inner, closer = self.tokens[self.i + 1:self.i + 3]
        if not (inner.kind == "number" and closer.kind == "close" and closer.value == ")"):
            return
        typed = self.text[token.pos:closer.end]
        own = (f"write {name}0 for the value at t = 0" if inner.value == 0 and f"{name}0" in self.ns.names
               else "write the value at that time by its own name")
        raise ExpressionError(f"'{typed}' reads as {token.text} at t = {inner.text} or as {token.text}·{inner.text}",
                              token.pos, "ambiguous", f"{own}, or {token.text}*{inner.text} for the product")

    def time_bracket(self, raw: str) -> bool:
        """Whether a declared variable ``raw`` is followed by ``[t]`` that `time_argument` reads as
        Mathematica's function of time (``θ[t]``), not as an index. A subscript typed apart (``θ₁[t]``,
        ``Subscript[θ, 1][t]``) is the declared theta1's."""
        if raw not in self.ns.names:
            try:
                resolved = resolve_name(raw, self.ns)
            except ExpressionError:
                return False
            if resolved.kind != "symbol" or resolved.value.name not in self.ns.names:
                return False
            raw = resolved.value.name
        inner, closer = self.tokens[self.i + 1:self.i + 3]
        return (inner.kind == "name" and inner.value == "t" and not inner.order
                and closer.kind == "close" and closer.value == "]"
                and ("t" not in self.ns.names or self.moves_in_time(raw)))

    def moves_in_time(self, name: str) -> bool:
        """With a variable t declared as the time: whether ``name`` is a coordinate or a derivative of one
        (by kind, or by a declared derivative when no kind is given)."""
        time = self.ns["t"]
        if not (time.kind == "time" or time.dimension == _TIME) or name not in self.ns.names:
            return False
        if self.ns[name].kind in ("coordinate", "velocity", "acceleration"):
            return True
        return self.ns[name].kind == "parameter" and (name.endswith("dot") or derivative_name(name, 1) in self.ns.names)

    def splice(self, token: Token, parts: list[str]) -> None:
        """Replace a glued name (``mg``, ``sin2x``) by one token per part, then parse on.

        A part keeps its own position when it can be found in the typed text;
        otherwise (``ωt`` typed, ``omega`` meant) each part spans the whole name.
        """
        pieces, cursor = [], 0
        for n, part in enumerate(parts):
            found = token.text.find(part, cursor)
            if found >= 0 and token.order == 0:
                start, end = token.pos + found, token.pos + found + len(part)
                cursor = found + len(part)
            else:
                start, end = token.pos, token.end
            if part.isdigit():
                piece = Token("number", sympy.Integer(int(part)), start, end, part)
            else:
                piece = Token("name", part, start, end, part)
            piece.space_before = token.space_before if n == 0 else False
            piece.glued = n > 0
            pieces.append(piece)
        self.i -= 1
        self.tokens[self.i:self.i + 1] = pieces

    def function(self, name: str, token: Token) -> sympy.Expr:
        power = None
        following = self.peek()
        if (token.text.lstrip("\\").startswith("log_") and following.kind == "number"
                and following.pos == token.end and following.text.startswith(".")):
            # log_2.5x: KAS's logarithm to base 2.5, not log₂(0.5x) as the tokens alone would say
            base = token.text.split("_", 1)[1].strip("{}") + following.text
            raise ExpressionError(f"cannot read '{token.text}{following.text}': a logarithm to base {base}?",
                                  token.pos, "ambiguous", f"write log(x, {base}) for the logarithm of x to base {base}")
        if following.kind == "sup" or (following.kind == "op" and following.value == "^"):
            self.advance()
            exponent = sympy.Integer(following.value) if following.kind == "sup" else self.expression(_POW - 1)
            if exponent == -1 and name in INVERSES:
                self.note(f"read '{token.text}^-1' as the inverse function {INVERSES[name]}, not 1/{name}")
                name = INVERSES[name]
            elif exponent.is_Integer and 0 < exponent <= 1000:
                power = exponent
            elif exponent == -1:
                # sec^-1 x is the inverse secant in most books and 1/sec x in some: the grammar has no
                # asec, so both readings are spelt out instead of a hint about powers
                inverse = INVERSE_INSTEAD.get(name) or WRITE_INSTEAD.get("a" + name)
                question = f": the inverse function of {name} or 1/{name}?" if inverse else ""
                raise ExpressionError(f"cannot read '{token.text}^-1'{question}", following.pos, "ambiguous",
                                      (f"{inverse}; " if inverse else "") + f"write 1/{name}(x) for the reciprocal")
            else:
                raise ExpressionError(f"cannot read '{token.text}^{exponent}'", following.pos, "syntax",
                                      f"write ({name}(x))^n for a power of {name}")
        if token.text in _SPREADSHEET_CAPITALS:
            # Excel's and Google Sheets' ATAN2(x, y) is atan2(y, x) here, and their LOG is to base 10:
            # the same letters, another meaning
            message, hint = _SPREADSHEET_CAPITALS[token.text]
            raise ExpressionError(message, token.pos, "ambiguous", hint)
        spec = FUNCTIONS[name]
        following = self.peek()
        # Sin[x]^2 is Mathematica's call sin(x)^2, as sin(x)^2 is: read as grouping, the square went
        # inside (sin(x²)) and a right sin²x was proved wrong.
        if following.kind == "open" and following.value in "({[":
            if (following.text == "{" and token.text.startswith("\\") and spec.min_args == 1
                    and name not in _ROOT_INDEX and name not in _ANY_DIMENSION):
                self.refuse_a_power_after_braces(token, name)
            args = self.call_arguments(token, spec)
            if name == "sqrt" and following.value == "[":
                index_root = self.bracket_index_root(token, args[0])
                if index_root is not None:
                    return index_root
        elif spec.min_args > 1:
            raise ExpressionError(f"{token.text} takes {spec.min_args} arguments in parentheses, "
                                  f"as in {name}({_ARGUMENT_NAMES.get(name, 'y, x')})", token.pos, "syntax")
        elif following.kind in _ATOM_STARTS or (following.kind == "op" and following.value == "-"):
            args = [self.function_argument(token, name)]
        else:
            raise ExpressionError(f"{token.text} needs an argument, as in {name}(x)", token.pos, "syntax")
        if name == "sqrt":
            value = self.power(args[0], sympy.Rational(1, 2), token.pos)
        elif name == "pow":
            value = self.power(args[0], args[1], token.pos)
        elif name == "surd":
            index = args[1]
            if not (index.is_Integer and 2 <= index <= MAX_ROOT_INDEX):
                raise ExpressionError(f"cannot read the root of index {index} in {token.text}(x, n)", token.pos,
                                      "syntax", "the index of a root is a whole number from 2 on, as in "
                                      f"{token.text}(x, 3); write x^(1/n) for a power")
            value = self.root(args[0], int(index), token.pos)
        else:
            if spec.name in _PERIODIC and args[0].is_number and _beyond(args[0], _PERIODIC_LIMIT):
                # sin(exp(99999999)): its sign (asked for in log(sin(…))) needs the angle to millions of digits,
                # and the parse did not end; no answer takes the sine of a number with more digits than a number may have
                raise ExpressionError(f"{token.text} of a number with more than {MAX_DIGITS} digits", token.pos,
                                      "too_large", "no answer here needs numbers that size")
            try:
                value = checked(spec.build(*args), token.pos)
            except (TypeError, AttributeError):  # sympy's own failure on a huge argument: asin(sin(1e400))
                raise ExpressionError(f"cannot work out {token.text} of this exactly", token.pos, "too_large",
                                      "no answer here needs numbers that size") from None
            if spec.name in _RESTRICTED:
                self.domain_nodes.append((value, spec.sympy_func(args[0], evaluate=False)))
            # asin(3/2), acosh(1/2), log(-2): a number with no real value, which is a slip.
            if value.is_number and all(a.is_number for a in args) and value.is_extended_real is False:
                raise not_real(token.pos)
        if token.text.lower() in ("log", "\\log"):
            self.note("log is the natural logarithm (ln)")
        return guarded_pow(value, power, token.pos) if power is not None else value

    def refuse_a_power_after_braces(self, token: Token, name: str) -> None:
        """``\\sin{\\theta}^2``: TeX shows sin θ², and some readers (CortexJS) take the braces as a group,
        sin(θ²); others take them as the call's brackets, sin(θ)², as ``\\frac{1}{2}\\sin{x}^2`` in answer
        keys means. Refused naming both, unless the braces hold one bracket (``\\sin{\\left(x\\right)}^2``
        shows sin(x)², the power of the sine as sin(x)^2 is)."""
        depth, n = 0, self.i
        for n in range(self.i, len(self.tokens)):
            depth += {"open": 1, "close": -1}.get(self.tokens[n].kind, 0)
            if depth == 0:
                break
        after = self.tokens[n + 1] if n + 1 < len(self.tokens) else None
        if depth != 0 or after is None or not (after.kind == "sup" or (after.kind == "op" and after.value == "^")):
            return
        inner = self.tokens[self.i + 1:n]
        if any(t.kind == "op" and t.value == "," for t in inner):
            return  # \\log{x, 2}: arguments, not a group
        if inner and inner[0].kind == "open":
            level = 0
            for m, t in enumerate(inner):
                level += {"open": 1, "close": -1}.get(t.kind, 0)
                if level == 0:
                    break
            if m == len(inner) - 1:
                return  # \sin{(x)}^2: the bracket inside says it is the call's
        power = after.text if after.kind == "sup" else "^…"
        shown = self.text[token.pos:self.tokens[n].end] + power
        argument = self.text[self.tokens[self.i].end:self.tokens[n].pos].strip()
        raise ExpressionError(f"'{shown}' could be {name} of the power (TeX shows the power on {argument}) or the power "
                              f"of {name}", token.pos, "ambiguous",
                              f"write {token.text}^2 {argument} or {token.text}({argument})^2 for the power of {name}, or "
                              f"put the power inside the braces ({token.text}{{{argument}^2}}) for {name} of the power")

    def bracket_index_root(self, token: Token, index: sympy.Expr) -> sympy.Expr | None:
        """``sqrt[3]{x}``: LaTeX's n-th root typed without the backslash (as KAS and MathQuill's
        plain text write it) is that root, not √3·x; ``sqrt[3](x)`` and ``sqrt[3] x`` could be either
        (Mathematica's ``Sqrt[3] x`` is √3·x), so they are refused with both readings. None when
        nothing follows the brackets that could be a radicand (``sqrt[2] + 1`` is √2 + 1)."""
        following = self.peek()
        braced = following.kind == "open" and following.value == "{"
        capital = token.text[:1] == "S"  # Mathematica's Sqrt[3] x: a product, as there
        if not braced and (capital or following.kind not in _ATOM_STARTS):
            return None
        typed = self.text[token.pos:following.end]
        if not braced:
            root = {2: "sqrt(x)", 3: "cbrt(x)"}.get(index, f"x^(1/{index})")
            raise ExpressionError(f"'{typed}…' could be the root of index {index} or sqrt({index}) times what follows",
                                  token.pos, "ambiguous",
                                  f"write {root} for the root, or sqrt({index})*x for the product")
        if not (index.is_Integer and 2 <= index <= MAX_ROOT_INDEX):
            raise ExpressionError(f"cannot read the root of index {index} in '{typed}'", token.pos, "syntax",
                                  "the index of a root is a whole number from 2 on; write x^(1/n) for a power")
        opener = self.advance()
        if self.peek().kind == "close":
            raise ExpressionError("empty brackets", opener.pos, "syntax", "put the radicand inside, as in sqrt[3]{x}")
        radicand = self.expression(0)
        self.expect_close(opener)
        self.note(f"read 'sqrt[{index}]{{…}}' as the root of index {index}, as LaTeX's \\sqrt[{index}]{{…}}")
        return self.root(radicand, int(index), token.pos)

    def call_arguments(self, token: Token, spec) -> list[sympy.Expr]:
        opener = self.advance()
        if self.peek().kind == "close":
            raise ExpressionError(f"{token.text}() needs an argument", opener.pos, "syntax",
                                  f"write {spec.name}(x)")
        args = [self.expression(0)]
        if (opener.value == "[" and (spec.max_args > 1 or spec.name in _BRACKET_PAIR_HINTS)
                and spec.name not in _SAME_ORDER_IN_MATHEMATICA and self.peek().kind == "op" and self.peek().value == ","):
            # Mathematica's ArcTan[x, y] is atan2(y, x) and its Log[b, x] is the logarithm of x to
            # base b: the reverse of atan2(y, x) and log(x, b) here, so neither order is guessed.
            raise ExpressionError(f"'{token.text}[…, …]' has its arguments in a different order in different "
                                  f"systems (Mathematica's ArcTan[x, y] is atan2(y, x), its Log[b, x] is "
                                  f"log(x, b))", self.peek().pos, "ambiguous",
                                  _BRACKET_PAIR_HINTS.get(spec.name, f"write {spec.name}(…) with round brackets"))
        while self.peek().kind == "op" and self.peek().value == "," and (
                opener.value == "(" or spec.name in _SAME_ORDER_IN_MATHEMATICA):
            self.advance()
            args.append(self.expression(0))
        closer = self.expect_close(opener)
        if opener.value == "[" and spec.name == "log" and self.peek().kind in _ATOM_STARTS:
            # Maple's log[10](x) is the logarithm of x to base 10, Mathematica's Log[10] (x) the product
            # log(10)·x: read as the product, an answer x log 10 was accepted for Maple's. (Sin[θ] (a + b)
            # is a product in both.)
            index = self.text[opener.end:closer.pos].strip()
            raise ExpressionError(f"cannot read '{token.text}[{index}]' before an argument: Maple's log[{index}](x) is "
                                  f"the logarithm of x to base {index}, Mathematica's Log[{index}] x the product",
                                  opener.pos, "ambiguous",
                                  f"write log(…, {index}) for the logarithm to base {index}, or log({index})*(…) for "
                                  "the product")
        if not spec.min_args <= len(args) <= spec.max_args:
            wanted = (f"{spec.min_args}" if spec.min_args == spec.max_args
                      else f"{spec.min_args} or {spec.max_args}")
            shown = ", ".join("yxz"[:spec.min_args] if spec.min_args > 1 else "x")
            example = f"{spec.name}({_ARGUMENT_NAMES.get(spec.name, shown)})"
            hint = f"write it as {example}"
            if spec.name in ("log10", "log2") and len(args) == 2:  # STACK's lg(x, b): a base given
                hint = "write log(x, b) for the logarithm of x to base b"
            if spec.name == "atan" and len(args) == 2:  # Maple's arctan(y, x), MATLAB's habit
                hint = "write atan2(y, x) for the angle of the point (x, y), or atan(y/x)"
            raise ExpressionError(f"{token.text} takes {wanted} argument{'s' if spec.max_args > 1 else ''}, "
                                  f"got {len(args)}", token.pos, "syntax", hint)
        return args

    def function_argument(self, token: Token, name: str) -> sympy.Expr:
        """The argument of a function written without parentheses: one factor and its power.

        Factors typed glued together stay together: ``sin 2x`` (and ``sin 2 x``) is sin(2x) and
        ``cos ωt`` is cos(ω·t), because nobody means sin(2)·x.
        """
        begin = self.i
        arg = self.glued_factors(self.expression(_MUL), token.pos, name)
        if name not in _ANY_DIMENSION:
            arg = self.dimensionless_argument(arg, token.pos, name)
        raised = next((t for t in self.tokens[begin:self.i] if t.kind == "sup" or (t.kind == "op" and t.value == "^")),
                      None)
        if raised is not None and name in _ROOT_INDEX and self.tokens[begin].kind != "open":
            self.unbracketed_root_of_a_power(token, name, begin, arg)
        if raised is not None and name in _SQUARED_BEFORE and self.tokens[begin].kind != "open":
            # sin α² is sin(α²), as convention has it; sin²α, the square of the sine, is often what was meant
            shown = self.text[token.pos:self.tokens[self.i - 1].end]
            self.note(f"read '{shown}' as {name}({arg}): write {name}^2(…) or {name}(…)^2 for a power of {name}")
        following = self.peek()
        if following.kind == "name" and following.value.lower() not in FUNCTIONS \
                and not following.forced_function:
            self.note(f"read '{self.text[token.pos:following.end]}' as {name}({arg})·{following.text}")
        elif following.kind == "op" and following.value in "*/" and name != "√" \
                and self.peek(1).kind in _ATOM_STARTS:
            # cos 2*x, sin θ/2: the function takes the factor before the operator, as precedence says
            # and some readers do not; said, since the other reading is as common
            shown = self.text[token.pos:self.peek(1).end]
            self.note(f"read '{shown}' as {name}({arg}){following.value}{self.peek(1).text}: write "
                      f"{name}(…) around everything the {name} covers")
        return arg

    def unbracketed_root_of_a_power(self, token: Token, name: str, begin: int, arg: sympy.Expr) -> None:
        """``sqrt x^2``, ``√x²``, ``cbrt x^3``: a root without brackets before a power. Precedence (and
        sin x² = sin(x²)) says the root of the power, √(x²) = |x|; ASCIIMath, whose unary functions take
        the next simple term, and TeX's ``\\sqrt x^2`` say the power of the root, (√x)² = x. Where the
        two differ (x real, or glued factors as in ``sqrt 2x^2``) it is refused naming both; where they
        are the same (x > 0, a number) it is read with a note."""
        depth, raised = 0, None
        for t in self.tokens[begin:self.i]:
            depth += {"open": 1, "close": -1}.get(t.kind, 0)
            if depth == 0 and (t.kind == "sup" or (t.kind == "op" and t.value == "^")):
                raised = t
                break
        if raised is None:
            return  # sqrt 2(x^2): the power is inside brackets
        index = token.value if token.kind == "root" else _ROOT_INDEX[name]
        # The readings differ only by an even root of an even power of what may be negative: an odd root
        # or power keeps the sign, and a fractional power needs its base >= 0 in both.
        same = arg.is_number or (isinstance(arg, sympy.Pow) and (
            index % 2 == 1 or not (arg.exp.is_Integer and arg.exp.is_even) or arg.base.is_nonnegative))
        end = self.tokens[self.i - 1].end
        shown, radicand = self.text[token.pos:end], self.text[self.tokens[begin].pos:end]
        base, exponent = self.text[self.tokens[begin].pos:raised.pos].strip(), self.text[raised.pos:end].strip()
        written = token.text if token.kind == "root" else name
        of_power, of_root = f"{written}({radicand})", f"{written}({base}){exponent}"
        if same:
            self.note(f"read '{shown}' as {of_power}, which is {of_root} here")
            return
        raise ExpressionError(f"'{shown}' could be the root of the power, {of_power}, or the power of the root, "
                              f"{of_root}", token.pos, "ambiguous",
                              f"write {of_power} or {of_root}")

    def dimensionless_argument(self, arg: sympy.Expr, start: int, name: str) -> sympy.Expr:
        """``arg`` times the factors that follow it while it has a dimension and they make it dimensionless:
        ``cos ω t`` is cos(ω·t) and ``e^-k t`` is e^(−k·t), since the cosine of an angular velocity
        times a time means nothing. Said in a note; left as it is when no such factors follow (the
        dimension check then names the slip) or the variables have no dimensions.
        """
        dims = self.ns.dimensions()
        try:
            if dimension_of(arg, dims).is_dimensionless:
                return arg
        except DimensionError:
            return arg
        saved = (self.i, list(self.notes), len(self.domain_nodes), self.last_product)
        candidate = arg
        for _ in range(_MOST_FACTORS_TAKEN):
            following = self.peek()
            if not (following.kind == "name" and following.value.lower() not in FUNCTIONS
                    and not following.forced_function):
                break
            candidate = checked(sympy.Mul(candidate, self.expression(_MUL)), following.pos)
            try:
                if dimension_of(candidate, dims).is_dimensionless:
                    shown = f"e^({candidate})" if name == "e^" else f"{name}({candidate})"
                    self.note(f"read '{self.text[start:self.tokens[self.i - 1].end]}' as {shown}: the argument "
                              "must be dimensionless")
                    return candidate
            except DimensionError:
                break
        self.i, self.notes, self.last_product = saved[0], saved[1], saved[3]
        del self.domain_nodes[saved[2]:]
        return arg

    def glued_factors(self, arg: sympy.Expr, start: int, name: str) -> sympy.Expr:
        """``arg`` times the factors typed glued to it: the rest of a split name (``ωt``), a name right
        after a number (``2x``; in LaTeX, where spaces mean nothing, also ``\\sin 2 \\theta``), or a name
        after the space that ends a LaTeX command (``\\omega t``, which LaTeX reads as ωt). A function's
        argument without brackets, an exponential's exponent."""
        glued = False  # glued by us (2 then x), not by a split name, which has its own note
        latex_function = self.text[start:start + 1] == "\\"
        while True:
            following, last = self.peek(), self.tokens[self.i - 1]
            split_part = following.glued
            # A number then a name is a function's argument, spaced or not: sin 2 θ is sin(2θ) as sin 2θ is
            # (and as LaTeX, which ignores spaces, prints \sin 2 \theta); nobody means sin(2)·θ. An exponent
            # ends at a typed space (e^2 x is e²·x), except in LaTeX.
            spaced = name != "e^" or latex_function or following.text[:1] == "\\"
            typed_glued = last.kind == "number" and (
                (following.pos == last.end and not following.space_before)
                or (spaced and _SPACING_ONLY.fullmatch(self.text, last.end, following.pos) is not None))
            latex_word = (last.kind == "name" and last.text[:1] == "\\" and last.text[-1:].isalpha()
                          and not self.text[last.end:following.pos].strip())
            # sin 2(x + 1) is sin(2(x + 1)), as sin 2x is sin(2x); an exponent's e^2(x + 1) is left as it was
            glued_bracket = (following.kind == "open" and following.value == "(" and name != "e^"
                             and last.kind == "number" and following.pos == last.end)
            if not glued_bracket and not (following.kind == "name" and (split_part or typed_glued or latex_word)
                                          and following.value.lower() not in FUNCTIONS
                                          and not following.forced_function):
                break
            arg = checked(sympy.Mul(arg, self.expression(_MUL)), following.pos)
            glued = glued or not split_part or name == "e^"  # a split name's note does not say e^(...)
        if glued:
            shown = f"{name}({arg})" if name != "e^" else f"e^({arg})"
            self.note(f"read '{self.text[start:self.tokens[self.i - 1].end]}' as {shown}")
        return arg

    def derivative_call(self, token: Token, order: int) -> sympy.Expr:
        opener = self.advance()
        inner = self.advance()
        if inner.kind != "name":
            raise ExpressionError(f"{token.text}(…) takes a variable name, as in {token.text}(theta)",
                                  inner.pos, "syntax")
        self.expect_close(opener)
        return self.derivative_of(inner, order)

    def after_operand(self) -> bool:
        """Whether the token before the one just read ends an operand (so that the one just read is a factor of a
        product): ``l dot θ``, not ``dot θ`` or ``(dot θ)``."""
        before = self.tokens[self.i - 2] if self.i >= 2 else None
        return before is not None and before.kind in _OPERAND_ENDS

    def refuse_superscript_index(self, token: Token, following: Token, unknown: ExpressionError) -> None:
        """m² where the problem has m2 and no m: a raised digit typed for the index (a phone's long-pressed 2 gives
        ², never ₂). Refused naming both: m squared, or the variable m2."""
        if unknown.code != "unknown_name" or following.kind != "sup" or following.pos != token.end \
                or following.value < 0 or token.order:
            return
        indexed = f"{token.value}{following.value}"
        if indexed in self.ns.names or f"{token.value}_{following.value}" in self.ns.names:
            shown = self.text[token.pos:following.end]
            name = indexed if indexed in self.ns.names else f"{token.value}_{following.value}"
            raise ExpressionError(f"'{shown}' is {token.text} to the power {following.value}, and this problem has "
                                  f"no {token.text} but a variable {name}", token.pos, "unknown_name",
                                  f"for the variable, type {token.text}{following.value} or {token.text}_"
                                  f"{following.value} (a subscript, not a raised digit)")

    def maple_d(self, token: Token) -> sympy.Expr:
        """Maple's derivative operator, as Maple and Möbius print it: ``D(θ)(t)`` is θ̇, ``D(D(θ))(t)`` is θ̈."""
        openers = [self.advance()]
        while self.peek().kind == "name" and self.peek().value == "D" and not self.peek().order \
                and self.tokens[self.i + 1].kind == "open" and self.tokens[self.i + 1].value == "(":
            self.advance()
            openers.append(self.advance())
        inner = self.advance()
        if inner.kind != "name":
            raise ExpressionError("Maple's D(…) takes a variable name, as in D(theta)(t)", inner.pos, "syntax",
                                  "write the time derivative as θ̇ (thetadot), or as diff(θ(t), t)")
        for opener in reversed(openers):
            self.expect_close(opener)
        shown = self.text[token.pos:self.tokens[self.i - 1].end]
        value = self.derivative_of(inner, len(openers))
        self.note(f"read '{shown}' as {dotted(value.name)}")
        return value

    def derivative_of(self, inner: Token, order: int) -> sympy.Expr:
        following = self.peek()
        if following.kind == "name" and following.value.startswith("_") and not following.space_before:
            # dot{θ}_1, \dot{\theta}_1, \ddot{x}_{2}: the subscript belongs to the variable.
            self.advance()
            inner = Token("name", inner.value + following.value, inner.pos, following.end,
                          self.text[inner.pos:following.end], order=inner.order + following.order)
        resolved = resolve_name(inner.value, self.ns, order=order + inner.order, typed=inner.text,
                                position=inner.pos)
        if resolved.kind != "symbol":
            raise ExpressionError(f"'{inner.text}' is not a variable that has a time derivative",
                                  inner.pos, "unknown_name")
        self.time_argument(self.tokens[self.i - 1], resolved.value)
        return resolved.value

    # -- LaTeX structures ----------------------------------------------------
    def braced(self, command: Token) -> sympy.Expr:
        if self.peek().kind != "open" or self.peek().value != "{":
            return self.latex_argument(command)
        opener = self.advance()
        if self.peek().kind == "close":
            raise ExpressionError("empty braces", opener.pos, "syntax", "put an expression inside the braces")
        inner = self.expression(0)
        self.expect_close(opener)
        return inner

    def latex_argument(self, command: Token) -> sympy.Expr:
        """An unbraced argument, read as LaTeX does: one character or one command, so ``\\frac12`` is
        1/2, ``\\frac gl`` is g/l and ``\\frac\\pi2`` is π/2 (the tokenizer's name ``\\pi2`` is cut where
        the command's letters end)."""
        token = self.peek()
        glued = _COMMAND_THEN_DIGITS.match(token.text) if token.kind == "name" and not token.order else None
        if glued is not None and not token.forced_function:
            # \frac\pi2: a command name ends at its last letter, as in TeX, so the argument is \pi
            # and the 2 is what follows it (alone, \omega2 is the name ω2, as ω2 is: see tokens.py).
            cut = glued.end(1)
            rest = token.text[cut:]
            pieces = [replace(token, value=token.value[:-len(rest)], text=token.text[:cut], end=token.pos + cut)]
            for piece in tokenize(rest)[:-1]:  # 2, or 2 then x: plain ASCII, so tokenized alike
                pieces.append(replace(piece, pos=piece.pos + token.pos + cut, end=piece.end + token.pos + cut))
            self.tokens[self.i:self.i + 1] = pieces
            token = pieces[0]
        plain = token.text.isascii() and token.text.isalnum() and token.order == 0
        if token.kind in ("number", "name") and plain and len(token.text) > 1:
            first, rest = token.text[0], token.text[1:]
            if token.text.isdigit() or token.text.isalpha():
                pieces = [replace(token, value=sympy.Integer(int(part)) if part.isdigit() else part, text=part,
                                  pos=token.pos + k, end=token.pos + k + len(part),
                                  space_before=token.space_before if k == 0 else False)
                          for k, part in ((0, first), (1, rest))]
            else:
                # letters and digits glued (\frac x2, \frac 1x2, \frac a2b): TeX too takes the first
                # character, and what follows is read afresh (x/2, (1/x)·2, (a/2)·b)
                pieces = [replace(token, value=sympy.Integer(int(first)) if first.isdigit() else first, text=first,
                                  end=token.pos + 1, decimal=False)]
                for piece in tokenize(rest)[:-1]:  # plain ASCII letters and digits
                    pieces.append(replace(piece, pos=piece.pos + token.pos + 1, end=piece.end + token.pos + 1))
            self.tokens[self.i:self.i + 1] = pieces
            token = pieces[0]
        single = plain and len(token.text) == 1
        latex_name = token.kind == "name" and token.text[:1] == "\\" and not token.forced_function
        if not ((token.kind in ("number", "name") and single) or latex_name):
            raise ExpressionError(f"{command.text} needs braces, as in {_BRACED_EXAMPLE.get(command.value, '')}",
                                      token.pos, "syntax")
        self.advance()
        return self.nud(token, _POW)

    def latex_command(self, token: Token) -> sympy.Expr:
        if token.value == "frac":
            # 3{\frac{1}{2}} and {3}\frac{1}{2}: TeX's braces print nothing, so these are 3½ all the same
            # (the last tokens only: braces nest at most 50 deep, and a text of many fractions stays linear)
            earlier = [t for t in self.tokens[max(0, self.i - 128):self.i] if t.pos < token.pos]
            opened = closed = 0
            while earlier and earlier[-1].kind == "open" and earlier[-1].text == "{":
                opened += bool(earlier.pop())
            while not opened and earlier and earlier[-1].kind == "close" and earlier[-1].text == "}":
                closed += bool(earlier.pop())
            braced = opened or closed
            before = earlier.pop() if earlier else None
            while closed and earlier and earlier[-1].kind == "open" and earlier[-1].text == "{":
                closed -= bool(earlier.pop())
            if braced and (closed or earlier and (earlier[-1].kind not in ("op", "open") or earlier[-1].value == "^")):
                before = None  # \frac{1}{2}\frac{1}{2}, 3^{2}\frac{1}{2}: a command's argument or an exponent
            if self.i >= 3 and self.tokens[self.i - 3].kind == "op" and self.tokens[self.i - 3].value == "^":
                before = None  # x^2\frac{1}{2}: the 2 is an exponent
            numerator = self.braced(token)
            denominator = self.braced(token)
            if (before is not None and before.kind == "number" and not before.decimal and before.value.is_Integer
                    and numerator.is_Integer and denominator.is_Integer):
                # 2\frac{1}{2} prints 2½: the mixed number 5/2 at school, 2·½ to KAS; refused as ½ after a
                # number is (tokens.vulgar_fraction), never guessed
                start = before.pos
                while start and self.text[start - 1] == "{":
                    start -= 1
                shown = self.text[start:self.tokens[self.i - 1].end] + "}" * opened
                raise ExpressionError(f"'{shown}' mixes a number and a fraction", before.pos, "ambiguous",
                                      f"write {before.value} + {numerator}/{denominator} for the mixed number, or "
                                      f"{before.value}*{numerator}/{denominator} for the product")
            return checked(sympy.Mul(numerator, guarded_pow(denominator, sympy.Integer(-1), token.pos)),
                           token.pos)
        if token.value == "sqrt":
            index = sympy.Integer(2)
            if self.peek().kind == "open" and self.peek().value == "[":
                opener = self.advance()
                index = self.expression(0)
                self.expect_close(opener)
                if not (index.is_Integer and 2 <= index <= 1000):
                    raise ExpressionError("the root index must be a whole number from 2 up, as in \\sqrt[3]{x}",
                                          opener.pos, "syntax")
            following = self.peek()
            if following.kind == "open" and following.value == "{":
                arg = self.braced(token)
            elif following.kind in ("open", "command", "root") or following.forced_function:
                # \sqrt(x), \sqrt\left(x\right), \sqrt\frac{g}{l}, \sqrt|x|, \sqrt\sin x
                arg = self.function_argument(token, "sqrt")
            else:
                # TeX takes one character or command: \sqrt2 g and \sqrt g l print √2 g and √g l. Two glued
                # (\sqrt12, \sqrt gl print √1 2 and √g l) are refused: what was meant under the root?
                glued = following.text if following.kind in ("number", "name") and not following.order \
                    and following.text.isascii() and following.text.isalnum() and len(following.text) > 1 else ""
                if glued:
                    raise ExpressionError(f"'{token.text}{self.text[token.end:following.pos]}{glued}' puts only "
                                          f"'{glued[0]}' under the root, as LaTeX prints it", following.pos,
                                          "ambiguous", f"write {token.text}{{{glued}}} for the root of {glued}, or "
                                          f"{token.text}{{{glued[0]}}}\\,{glued[1:]}")
                arg = self.latex_argument(token)
            return self.root(arg, int(index), token.pos)
        # \dot{x}, \ddot{x}, \dot x
        order = 1 if token.value == "dot" else 2
        following = self.peek()
        if following.kind == "open" and following.value == "{":
            opener = self.advance()
            inner = self.advance()
            if inner.kind == "command" and inner.value in ("dot", "ddot"):
                raise ExpressionError("nested \\dot is not supported; write \\ddot{x}", inner.pos, "syntax")
            if inner.kind != "name":
                raise ExpressionError(f"{token.text}{{…}} takes a variable name", inner.pos, "syntax",
                                      f"write {token.text}{{x}} with a variable x")
            self.expect_close(opener)
            return self.derivative_of(inner, order)
        inner = self.peek()
        if inner.kind == "name" and not inner.order and inner.text.isascii() and inner.text.isalpha() \
                and len(inner.text) > 1 and inner.value not in self.ns.names and inner.value not in GREEK_LETTERS:
            # \dot xy: TeX dots one character, so it prints ẋy (x·ẏ, the glued name's reading, it is not)
            first, rest = inner.text[0], inner.text[1:]
            self.tokens[self.i:self.i + 1] = [replace(inner, value=first, text=first, end=inner.pos + 1),
                                              replace(inner, value=rest, text=rest, pos=inner.pos + 1,
                                                      space_before=False)]
        inner = self.advance()
        if inner.kind != "name":
            raise ExpressionError(f"{token.text} takes a variable name, as in {token.text}{{\\theta}}",
                                  inner.pos, "syntax")
        return self.derivative_of(inner, order)


# -- entry points -------------------------------------------------------------

# How each LaTeX structure's argument is braced, for the message when it is not.
_BRACED_EXAMPLE = {"frac": "\\frac{a}{b}", "sqrt": "\\sqrt{x}"}


def _namespace(namespace) -> Namespace:
    if isinstance(namespace, Namespace):
        return namespace
    if isinstance(namespace, Mapping):  # {name: {"dimension", "domain"}} as the checker receives it
        return Namespace.from_spec(namespace)
    raise TypeError(f"expected a Namespace, got {type(namespace).__name__}")


def _prepare(text: str, limit: int = MAX_LENGTH) -> list[Token]:
    if not isinstance(text, str):
        raise ExpressionError(f"expected text, got {type(text).__name__}", None, "syntax")
    # Length first: nothing below runs on a megabyte of input.
    if len(text) > limit:
        raise ExpressionError(f"the text is too long ({len(text)} characters, at most {limit})",
                              limit, "too_long", "simplify the expression")
    if not text.strip():
        raise ExpressionError("the answer is empty", 0, "empty", "type an expression")
    tokens = tokenize(text)
    check_brackets(tokens)
    return tokens


def _without_newlines(tokens: list[Token]) -> list[Token]:
    kept: list[Token] = []
    space = False
    for token in tokens:
        if token.kind == "newline":
            space = True
            continue
        if space:
            token.space_before = True
            space = False
        kept.append(token)
    return kept


def _real_and_flat(expr: sympy.Expr, position: int) -> sympy.Expr:
    """Refuse a non-real result and rebuild any Mul inside a Mul (or Add inside an Add) that sympy
    left unflattened, in one walk over the tree.

    checked() sees I where it is built; sympy can also create it deeper in one step (atan2 of a
    complex). ``sqrt(-theta*l^4)`` evaluates to ``Mul(l**2, sqrt(-theta))`` built with
    evaluate=False, and multiplying that by more factors can leave it nested; its ``str`` would
    then read back as a different (flat) tree.
    """
    if expr is _I:
        raise not_real(position)
    args = expr.args
    if not args:
        return expr
    flat = None  # the arguments, copied once one of them is rebuilt (most trees need nothing rebuilt)
    for k, arg in enumerate(args):
        if arg.args:
            new = _real_and_flat(arg, position)
            if new is not arg and flat is None:
                flat = list(args[:k])
            arg = new
        elif arg is _I:
            raise not_real(position)
        if flat is not None:
            flat.append(arg)
    func = expr.func
    if flat is not None:
        return func(*flat)
    if expr.is_Mul or expr.is_Add:
        for arg in args:
            if arg.func is func:
                return func(*args)  # nested: rebuilt flat
    return expr


def _finish(parser: _Parser, expr: sympy.Expr, printed: bool = True) -> Parsed:
    expr = _real_and_flat(expr, 0)
    conditions = _real_domain(expr, parser.domain_nodes)
    if not printed:
        return Parsed(expr, "", "", list(parser.notes), conditions)
    latex = to_latex(expr, parser.ns.latex_names())
    return Parsed(expr, to_text(expr), latex, list(parser.notes), conditions)


#: Texts remembered per namespace: a class types the same few forms, and the grading worker checks
#: every submission of a question against the same namespace. Parsed results are immutable (their
#: notes are handed out as copies), and the namespace object itself is part of the key.
PARSE_MEMORY = 2048
_remembered: OrderedDict = OrderedDict()
_memory_lock = threading.Lock()  # the web app parses previews on several threads


def forget_parses() -> None:
    """Empty the memory of parsed texts (for benchmarks that must parse every text afresh)."""
    with _memory_lock:
        _remembered.clear()


def _recall(key):
    with _memory_lock:
        found = _remembered.get(key)
        if found is not None:
            _remembered.move_to_end(key)
        return found


def _remember(key, value) -> None:
    with _memory_lock:
        _remembered[key] = value
        if len(_remembered) > PARSE_MEMORY:
            _remembered.popitem(last=False)


def _without_closing_semicolons(tokens: list[Token]) -> tuple[list[Token], list[str]]:
    """``m*g/3;`` and ``θ̈ = -g/l sin θ;``: the ';' (one or more, new lines between) that ends the answer,
    as MATLAB's and Maxima's statements end, is ignored with a note, in an expression, an equation and a
    system alike, as a full stop is. A ';' between two expressions is still refused."""
    n, found = len(tokens) - 1, False  # tokens[-1] is the end token
    while n > 0 and (tokens[n - 1].kind == "newline"
                     or (tokens[n - 1].kind == "op" and tokens[n - 1].value == ";" and tokens[n - 1].text.strip() == ";")):
        found = found or tokens[n - 1].kind == "op"
        n -= 1
    if not found or n == 0:  # nothing to drop, or nothing but ';'
        return tokens, []
    return tokens[:n] + tokens[-1:], ["ignored the ';' at the end"]


def _answer_only(tokens: list[Token], text: str) -> tuple[list[Token], list[str]]:
    """The tokens of the answer itself, without the label or the full stop a student may add.

    ``T = m g (3 cos θ - 2)`` and ``N(θ) = …`` name what the answer is, as on paper: the label is a
    single name (with, at most, its arguments in brackets) that the right side does not use, so
    ``x = 2x - 1``, an equation, is still refused. A full stop (or a comma) at the very end ends a sentence.
    """
    notes: list[str] = []
    while True:  # the marks that end a statement or a sentence, in any order (x;. as x.;)
        tokens, said = _without_closing_semicolons(tokens)
        stop, comma = "ignored the full stop at the end", "ignored the comma at the end"
        if len(tokens) > 2 and tokens[-2].kind == "bad" and tokens[-2].text == "." and stop not in notes:
            tokens = tokens[:-2] + tokens[-1:]
            said.append(stop)
        elif len(tokens) > 2 and tokens[-2].kind == "op" and tokens[-2].value == "," and comma not in notes:
            # a formula set inside a sentence ends with its comma (Mathpix: "… \text {, }"), as with a full stop
            tokens = tokens[:-2] + tokens[-1:]
            said.append(comma)
        notes += [note for note in said if note not in notes]
        if not said:
            break
    equals = [n for n, t in enumerate(tokens) if t.kind == "op" and t.value == "="]
    if len(equals) > 1 and tokens[0].kind == "name" and (equals[0] == 1 or tokens[1].kind == "open"):
        # T = m(g cos θ + l θ̇²) = m g cos θ + …: the work shown on paper, several answers for one
        second = tokens[equals[1]]
        raise ExpressionError("a chain of '=' after a label gives more than one answer", second.pos, "syntax",
                              "give one answer: the label and the last expression (T = …), or that expression alone")
    if len(equals) != 1 or tokens[0].kind != "name" or tokens[equals[0] + 1].kind == "end":
        return tokens, notes
    split = equals[0]
    label = tokens[:split]
    arguments = label[1:]
    if arguments and not (arguments[0].kind == "open" and arguments[-1].kind == "close"
                          and all(t.kind == "name" or (t.kind == "op" and t.value == ",") for t in arguments[1:-1])):
        return tokens, notes
    name = label[0]
    if any(t.kind == "name" and t.value == name.value and t.order == name.order for t in tokens[split + 1:]):
        return tokens, notes  # x = 2x - 1 is an equation, not a label
    if arguments and name.value.lower() in FUNCTIONS:
        # cos(θ) = g/(ω²a) states the cosine of an angle, not a name for the answer: dropped as a label, its
        # right side was graded as the angle itself, and sin(θ) = … was accepted where cos θ* is asked.
        said = text[name.pos:tokens[split - 1].end].strip()
        inverse = INVERSES.get(FUNCTIONS[name.value.lower()].name)
        example = f"; an angle whose {name.value} is c is {inverse}(c)" if inverse else ""
        raise ExpressionError(f"'{said} = …' gives the value of {said}, not the answer itself: '=' after a "
                              "function is not a label", name.pos, "syntax",
                              f"give the quantity asked for alone, without '{said} ='{example}")
    notes.append(f"read '{text[name.pos:tokens[split].end].strip()} …' as the expression after '='")
    return tokens[split + 1:], notes


def parse_expression(text: str, namespace: Namespace, *, printed: bool = True) -> Parsed:
    """Parse an expression over the namespace's variables.

    Parameters
    ----------
    text : str
        What an instructor or student typed.
    namespace : Namespace
        The only names the text may use (besides whitelisted functions and pi, e).
    printed : bool
        Compute ``text`` and ``latex`` (the default). Without, they are left empty, for callers
        that only need the expression: printing costs about as much as parsing.

    Returns
    -------
    Parsed
        ``expr`` (sympy), canonical ``text``, ``latex`` and ``notes``.

    Raises
    ------
    ExpressionError
        With a 0-based ``position``, a ``code`` and usually a ``hint``.

    Examples
    --------
    >>> from grader.expressions import Namespace, Variable
    >>> ns = Namespace([Variable("m", "mass", "positive"), Variable("g", "acceleration", "positive"),
    ...                 Variable("theta", "angle", "real")])
    >>> p = parse_expression("mg(1 - cos θ)", ns)
    >>> p.text, p.notes
    ('g*m*(1 - cos(theta))', ["read 'mg' as m·g", "read 'g(…)' as g·(…): g is a variable, not a function"])
    >>> parse_expression("0.5*m", ns).expr == parse_expression("m/2", ns).expr
    True
    """
    namespace = _namespace(namespace)
    key = ("expression", text, namespace, printed) if isinstance(text, str) else None
    found = _recall(key) if key is not None else None
    if found is not None:
        return replace(found, notes=list(found.notes))
    tokens = _without_newlines(_prepare(text))
    tokens, notes = _answer_only(tokens, text)
    parser = _Parser(tokens, namespace, text)
    parser.notes.extend(notes)
    expr = parser.expression(0)
    token = parser.peek()
    if token.kind == "op" and token.value == "=":
        raise ExpressionError("this should be an expression, not an equation", token.pos, "syntax",
                              "remove the '=' and everything on one side of it")
    if token.kind != "end":
        raise parser.unexpected(token)
    parsed = _finish(parser, expr, printed)
    _remember(key, parsed)
    return replace(parsed, notes=list(parsed.notes))


def _equation(parser: _Parser, printed: bool = True) -> ParsedEquation:
    lhs = parser.expression(0)
    token = parser.peek()
    if not (token.kind == "op" and token.value == "="):
        if token.kind == "end":
            raise ExpressionError("an equation needs '='", token.pos, "syntax", "write left side = right side")
        raise parser.unexpected(token)
    parser.advance()
    rhs = parser.expression(0)
    token = parser.peek()
    if token.kind != "end":
        if token.kind == "op" and token.value == "=":
            raise ExpressionError("an equation has exactly one '='", token.pos, "syntax",
                                  "separate several equations with ';'")
        raise parser.unexpected(token)
    lhs, rhs = _real_and_flat(lhs, 0), _real_and_flat(rhs, token.pos)
    conditions = _real_domain(lhs - rhs, parser.domain_nodes)
    if not printed:
        return ParsedEquation(lhs, rhs, "", "", list(parser.notes), conditions)
    names = parser.ns.latex_names()
    # The fast printers, as for expressions: sympy's cost more than parsing the equation.
    return ParsedEquation(lhs, rhs, f"{to_text(lhs)} = {to_text(rhs)}",
                          f"{to_latex(lhs, names)} = {to_latex(rhs, names)}", list(parser.notes), conditions)


def parse_equation(text: str, namespace: Namespace, *, printed: bool = True) -> ParsedEquation:
    """Parse ``lhs = rhs`` (``==`` also accepted) with exactly one top-level ``=``.

    ``printed`` as in `parse_expression`.

    Examples
    --------
    >>> from grader.expressions import Namespace, Variable
    >>> ns = Namespace([Variable("x", "length", "real"), Variable("l", "length", "positive")])
    >>> eq = parse_equation("x^2 == l^2", ns)
    >>> eq.lhs, eq.rhs, eq.text
    (x**2, l**2, 'x**2 = l**2')
    """
    namespace = _namespace(namespace)
    tokens, notes = _without_closing_semicolons(_without_newlines(_prepare(text)))
    parser = _Parser(tokens, namespace, text)
    parser.notes.extend(notes)
    return _equation(parser, printed)


def _joins_equations(tokens: list[Token], i: int, namespace: Namespace, before: list[Token]) -> bool:
    """Whether ``tokens[i]`` is the word ``and`` between two equations (``m ẍ = -k x and m ÿ = -k y``),
    read as ``;`` is, as ``\\text{ and }`` already was: an undeclared name ``and`` at the top level, with
    an ``=`` before it in this equation (or right after a separator, ``, and``) and one after it before the
    next separator."""
    token = tokens[i]
    if token.kind != "name" or token.order or str(token.value).lower() != "and" \
            or str(token.value) in namespace:
        return False
    if before and not any(t.kind == "op" and t.value == "=" for t in before):
        return False
    if not before and (i == 0 or tokens[i - 1].kind not in ("newline", "op")):  # ", and" after an equation
        return False
    depth = 0
    for after in tokens[i + 1:]:
        depth += (after.kind == "open") - (after.kind == "close")
        if depth == 0 and (after.kind in ("newline", "end") or (after.kind == "op" and after.value in ",;")):
            return False
        if depth == 0 and after.kind == "op" and after.value == "=":
            return True
    return False


def _ends_with_operator(chunk: list[Token]) -> bool:
    """Whether the last token typed in ``chunk`` (line breaks aside) is an operator that needs more after it."""
    typed = next((t for t in reversed(chunk) if t.kind != "newline"), None)
    return typed is not None and typed.kind == "op" and typed.value in "+-*/^="


def parse_system(text: str, namespace: Namespace, *, printed: bool = True) -> list[ParsedEquation]:
    """Parse several equations separated by ``;``, ``,`` or new lines (at top level).

    ``printed`` as in `parse_expression`.

    Examples
    --------
    >>> from grader.expressions import Namespace, Variable
    >>> ns = Namespace([Variable("x", "length", "real"), Variable("y", "length", "real"),
    ...                 Variable("l", "length", "positive")])
    >>> [eq.text for eq in parse_system("x = 1; y = atan2(x, l + y)\\n x + y = 0", ns)]
    ['x = 1', 'y = atan2(x, y + l)', 'x + y = 0']
    """
    namespace = _namespace(namespace)
    key = ("system", text, namespace, printed) if isinstance(text, str) else None
    found = _recall(key) if key is not None else None
    if found is not None:
        return [replace(eq, notes=list(eq.notes)) for eq in found]
    tokens, closing = _without_closing_semicolons(_prepare(text, 4 * MAX_LENGTH))
    stop = len(tokens) > 2 and tokens[-2].kind == "bad" and tokens[-2].text == "."
    if stop:  # a sentence's full stop, as after an expression ("= 0." reads the same either way)
        tokens = tokens[:-2] + tokens[-1:]
    chunks: list[list[Token]] = [[]]
    depth = 0
    for i, token in enumerate(tokens[:-1]):
        if token.kind == "open":
            depth += 1
        elif token.kind == "close":
            depth -= 1
        # a line that ends with an operator (x =⏎ -k y, a long right side wrapped) goes on on the next one
        broken = token.kind == "newline" and _ends_with_operator(chunks[-1])
        if depth == 0 and not broken and (token.kind == "newline" or (token.kind == "op" and token.value in ",;")
                                          or token.kind == "name" and _joins_equations(tokens, i, namespace,
                                                                                         chunks[-1])):
            chunks.append([])
        else:
            chunks[-1].append(token)
    equations = []
    for chunk in chunks:
        if not chunk:
            continue
        last = chunk[-1]
        end = Token("end", None, last.end, last.end, "")
        equations.append(_equation(_Parser(_without_newlines(chunk) + [end], namespace, text), printed))
    if not equations:
        raise ExpressionError("no equations found", 0, "empty", "write left side = right side")
    if stop or closing:
        said = closing + (["ignored the full stop at the end"] if stop else [])
        equations[-1] = replace(equations[-1], notes=equations[-1].notes + said)
    _remember(key, tuple(equations))
    return [replace(eq, notes=list(eq.notes)) for eq in equations]
