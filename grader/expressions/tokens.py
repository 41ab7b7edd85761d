"""Tokenizer: expression text -> tokens, with every token's position in the original text.

The text is never rewritten before tokenizing (no Unicode normalization, no
LaTeX pre-substitution), so every position in an error points at what the
student actually typed.  Token kinds:

``number``   exact sympy ``Integer``/``Rational`` (decimals are exact: 0.5 is 1/2)
``name``     identifier with Greek spelled out and subscripts flattened (``θ₁`` -> ``theta_1``);
             ``order`` counts derivative marks (``θ̇``, ``theta'``)
``op``       ``+ - * / ^ = , ;`` (``**`` -> ``^``, ``==`` -> ``=``, ``·`` -> ``*``, ``−`` -> ``-``)
``open`` / ``close``  ``( [ {`` and ``) ] }`` (``\\left(`` too)
``sup``      a run of superscript characters, ``²`` or ``⁻¹``, as an int (superscript letters, ``e⁻ᵃᵇ``, are
             refused with the power to type, ``e^(-a b)``)
``root``     ``√`` (2), ``∛`` (3), ``∜`` (4)
``command``  LaTeX structure: ``frac``, ``sqrt``, ``dot``, ``ddot``
``prime``    a prime not directly after a name (an error if the parser reaches it)
``newline``  line break (separates equations in a system, blank otherwise)
``bad``      a character the parser reports when it gets there (``!``, ``.``, ``:``)
``end``      end of text

The parser then turns each Leibniz derivative (``dθ/dt``, ``\\frac{d^2x}{dt^2}``) into one
``derivative`` token spanning it (:mod:`.leibniz`): namespace-aware, so not done here.
"""

from __future__ import annotations

import re
import string
import unicodedata
from dataclasses import dataclass

import sympy

from .errors import ExpressionError
from .functions import FUNCTIONS
from .latex_input import WRAPPER_COMMANDS, classify_command, subscript_text, wrapped_text
from .magnitudes import MAX_DIGITS
from .names import WRITE_INSTEAD
from .unicode_input import (COMBINING_DOTS, DOTTED_LETTERS, FULLWIDTH_SYMBOLS, GREEK_CHARS, MATH_LETTERS,
                            MIDDLE_DOTS, MINUS_SIGNS, OPERATOR_CHARS, PRIME_CHARS, VARIATION_SELECTORS,
                            ROOT_CHARS, SUBSCRIPT_DIGITS, SUBSCRIPT_LETTERS, SUPERSCRIPT_CHARS, SUPERSCRIPT_OTHERS,
                            VULGAR_FRACTIONS,
                            bad_character,
                            is_space)

__all__ = ["Token", "tokenize", "check_brackets", "MAX_NESTING"]

#: Deepest bracket nesting accepted; real answers need a handful.
MAX_NESTING = 50

_PAIRS = {"(": ")", "[": "]", "{": "}"}
# A degree sign in LaTeX: 30^\circ, 30^{\circ}, 30^{\circ }
_DEGREES = re.compile(r"\^\s*(?:\\circ(?![A-Za-z])|\{\s*\\circ\s*\})")
_OPENERS = {v: k for k, v in _PAIRS.items()}

# The characters most text is made of, tested first (see _Tokenizer.step).
_DIGITS = frozenset("0123456789")
_ASCII_ALNUM = frozenset(string.ascii_letters) | _DIGITS
_ASCII_NAME_START = (_ASCII_ALNUM - _DIGITS) | {"_"}
_ASCII_ALNUM_RUN = re.compile("[A-Za-z0-9]+")
_COMMAND_NAME = re.compile(r"\\[A-Za-z]+")
# A superscript typed before the subscript, m^2_1 or \frac{v^{2}_{0}}{2g}: each one token, as TeX takes
# them (a bare one-character subscript only where nothing that could continue it follows: m^2_total
# is left alone).
_SUPERSCRIPT_FIRST = re.compile(r"(?<=[A-Za-z0-9}])(\s*\^(?:\{[^{}]*\}|\\[A-Za-z]+|[A-Za-z0-9]))"
                                r"(_(?:\{[^{}]*\}|\\[A-Za-z]+|[A-Za-z0-9](?![A-Za-z0-9])))")
_FULLWIDTH = re.compile("[" + "".join(map(chr, FULLWIDTH_SYMBOLS)) + "]")
# What can continue a name or mark its derivative (see _Tokenizer.identifier and finish_name):
# a plain ASCII name followed by none of these is emitted as it is.
_NAME_GOES_ON = frozenset(_ASCII_ALNUM | {"_"} | set(GREEK_CHARS) | set(MATH_LETTERS) | set(SUBSCRIPT_DIGITS)
                          | set(SUBSCRIPT_LETTERS)
                          | set(COMBINING_DOTS) | set(PRIME_CHARS))


@dataclass(slots=True)  # slots: quicker to build and to read, and every answer makes many
class Token:
    """One token; ``text`` is the slice of the original input it came from."""

    kind: str
    value: object
    pos: int
    end: int
    text: str
    space_before: bool = False
    order: int = 0
    forced_function: bool = False
    decimal: bool = False
    glued: bool = False  # a later part of a split name (mg -> m, g): belongs with the part before
    error: ExpressionError | None = None


def _is_name_start(ch: str) -> bool:
    return (ch.isascii() and (ch.isalpha() or ch == "_")) or ch in GREEK_CHARS or ch in MATH_LETTERS


def _is_digit(ch: str) -> bool:
    return "0" <= ch <= "9"


# Spellings of "not equal" in other languages and graders ('!=' has its own branch, '≠' and \ne theirs).
_NOT_EQUAL = re.compile(r"=/=|/=|<>|=\\=")

# The combining dots above, which on a space are the spacing dots ˙ and ¨.
_COMBINING_ACCENTS = frozenset("\u0307\u0308")

# Invisible characters that change nothing before or after a formula. Not the direction overrides and isolates
# (U+202A-202E, U+2066-2069) nor the right-to-left mark: at the start they would show the formula otherwise than it
# reads, so they stay refused, named.
_EDGE_INVISIBLE = frozenset("\u200b\u200c\u200d\u2060\ufeff\u00ad\u200e\u2061\u2062\u2063")


def _invisible_or_blank(ch: str) -> bool:
    return ch.isspace() or ch in _EDGE_INVISIBLE


def _without_invisible_edges(text: str) -> str:
    """The text with the invisible format characters before and after the formula made spaces (a byte order mark
    at the start, a zero-width space or a direction mark a web page or an RTL text pastes at an end): they join or
    split nothing there, and the student cannot see them to delete. Inside the formula they stay refused."""
    start, end = 0, len(text)
    while start < end and _invisible_or_blank(text[start]):
        start += 1
    while end > start and _invisible_or_blank(text[end - 1]):
        end -= 1
    edges = text[:start] + text[end:]
    if all(ch.isspace() for ch in edges):
        return text
    blank = lambda part: "".join(ch if ch.isspace() else " " for ch in part)  # noqa: E731 (line breaks stay)
    return blank(text[:start]) + text[start:end] + blank(text[end:])


# A caption before a line's formula: words that name an answer (a ratio mg : l must not lose its mg, so only these)
# and a colon, then a space: Answer:, Final answer:, Tension:, Eq1:, Equation of motion:, Respuesta:.
_CAPTION_WORDS = ("answer|ans|final|my|the|solution|result|tension|normal|force|reaction|acceleration|equations?|eqn?s?"
                  "|eom|of|motion|lagrangian|respuesta|resposta|risposta|r[ée]ponse|antwort|l[öo]e?sung|ergebnis")
_CAPTION = re.compile(rf"^[ \t]*(?:\*\*)?(?i:{_CAPTION_WORDS})\d{{0,2}}(?:[ \t]+(?i:{_CAPTION_WORDS})\d{{0,2}}){{0,3}}"
                      r"[ \t]*:(?:\*\*)?[ \t]+(?=\S)", re.MULTILINE)

# A list's marker at a line's start, as a chat assistant or a word processor sets equations out: 1. 2) - * •
_LIST_MARKER = re.compile(r"^[ \t]*(?:(\d{1,2})[.)]|([-–*•◦▪‣⁃]))[ \t]+(?=\S)", re.MULTILINE)
_BULLETS = frozenset("*•◦▪‣⁃")


def _without_list_markers(text: str) -> str:
    """The text with a list's markers made spaces (so that positions stay): every line numbered 1., 2., … (or 1),
    2), …), or every line after the same bullet (•, *, ◦, ▪: on one line too, where nothing else starts with one).
    Every line after '- ' (a Markdown list, or each equation's minus sign?) is refused naming both."""
    found = list(_LIST_MARKER.finditer(text))
    if not found:
        return text
    lines = sum(1 for line in text.split("\n") if line.strip())
    numbers, bullets = [m.group(1) for m in found], {m.group(2) for m in found}
    if len(found) != lines:
        return text
    if lines >= 2 and all(numbers) and [int(n) for n in numbers] == list(range(1, lines + 1)):
        pass  # 1. … 2. …: a numbered list
    elif len(bullets) == 1 and bullets <= _BULLETS:
        pass  # • … • …
    elif lines >= 2 and bullets <= {"-", "–"} and not any(numbers):
        first = found[0].start(2)
        raise ExpressionError(f"every line starts with '{text[first]} ': a list's bullets, or a minus sign before each "
                              "equation?", first, "ambiguous",
                              "delete the bullets (one equation a line, or separated by ';'), or write each minus sign "
                              "against its term, as in -k x = m ẍ")
    else:
        return text
    for marker in reversed(found):
        text = text[:marker.start()] + " " * (marker.end() - marker.start()) + text[marker.end():]
    return text


# Markdown's bold around the whole answer: **…**, nothing but spaces outside (and the sentence's full stop or
# comma after it, read as after any answer), no ** inside.
_MARKDOWN_BOLD = re.compile(r"\s*(\*\*)(?=\S)(?:(?!\*\*).)+?(?<=[^\s*])(\*\*)[.,;。]?\s*", re.DOTALL)

# A double quote after a name (θ", or θ” as a phone's smart punctuation makes it), and the quotation marks whose
# presence before it makes it a quotation's end.
_DOUBLE_QUOTES = frozenset('"”')
_QUOTE_BEFORE = re.compile('["“”„‟«»]')

# A MathML or HTML tag (<math>, <mi>, </mrow>, <mo stretchy="false">, <sup>, <span ...>) at a '<'.
_MARKUP_TAG = re.compile(r"</?(math|mi|mn|mo|ms|mrow|msup|msub|msubsup|mfrac|msqrt|mroot|mover|munder|munderover"
                         r"|mtext|mspace|mstyle|mfenced|mtable|mtr|mtd|semantics|annotation|annotation-xml|mathml"
                         r"|sup|sub|span|div|p|i|b|em|strong|br)\b[^<>]{0,200}/?>", re.IGNORECASE)

# A subscript between a braced name and its primes ({x}_{1}^{\prime}): the name inside carries it already.
_SUBSCRIPT_GAP = re.compile(r"\s*_\s*(?:\{[^{}]{1,40}\}|[A-Za-z0-9])\s*")

_UNICODEMATH_ROOT = re.compile(r"√\(\s*(\d{1,6})\s*&")
_LINE_BREAKS = frozenset("\n\u2028\u2029\u0085\v\f")

# What may follow a number's digits to start its power of ten, and the exponent's signs.
_EXPONENT_MARKS = frozenset("eEᴇ")
_EXPONENT_PLUSES = frozenset("+＋")

# ASCIIMath's subscript in round brackets, which it does not print: x_(1), theta_(0), v_(max), m_(α).
# Only a plain index (letters or digits, or one Greek letter): x_(1 + n) is left to the grammar.
_ROUND_SUBSCRIPT = re.compile(r"\(\s*([A-Za-z0-9]{1,20}|[" + "".join(GREEK_CHARS) + r"])\s*\)")

# The extra space a line break may take: \\[2pt], \\[1ex], \\[0.5em]
_BREAK_SPACE = re.compile(r"\s*\[\s*-?(?:\d+\.?\d*|\.\d+)\s*(?:pt|ex|em|mm|cm|in|bp|pc|mu|sp|dd|cc)\s*\]")

# Printable ASCII the grammar does not use, and what to tell the student.
_PUNCTUATION = {
    "!": ("factorial (!) is not supported", "unsupported_function", "write the product out, as in 2*3"),
    ":": ("':' is not part of a formula", "syntax", "write a ratio with /, as in a/b"),
    "#": ("'#' starts a comment in Python and Maple", "syntax", "delete the '#' and everything after it"),
    "<": ("inequalities are not supported", "syntax", "give an expression, or an equation with ="),
    ">": ("inequalities are not supported", "syntax", "give an expression, or an equation with ="),
    '"': ("quotes are not part of a formula", "syntax", "delete the quotes"),
    "&": ("'&' (a LaTeX alignment mark) is not part of a formula", "syntax",
          "delete it, and give the equations one per line or separated by ';'"),
    "~": ("'~' reads as 'approximately' or as a LaTeX space", "syntax",
          "write = for an equation, or delete it"),
    "`": ("backquotes are not part of a formula", "syntax", "delete the backquotes"),
    "%": ("'%' (percent, or a comment in MATLAB and LaTeX) is not part of a formula", "syntax",
          "write a percentage as a number, as in 0.3 for 30%; delete a comment and everything after it"),
}


# An equation's number after a wide space, \quad (2), as the last thing of the equation; \tag{2}.
# (and before the next equation set beside it: x = 1 \quad (1) \qquad y = 2 \quad (2))
_LABEL_AFTER_SPACE = re.compile(r"\s*\(\s*\d+[a-z]?\s*\)(?=\s*(?:$|\\\\|;|,|\n|\\end\b|\\q?quad\b))")
_TAG = re.compile(r"\*?\s*\{[^{}]*\}")


# LaTeX environments that only lay equations out (\begin{aligned} ... \end{aligned}), where any '&' aligns.
_LAYOUT_ENVIRONMENTS = {"aligned", "align", "gather", "gathered", "split", "equation", "eqnarray", "multline",
                        "flalign", "alignat", "alignedat"}
# A system in a brace (Mathpix, Word): cases, or \left\{ \begin{array}{l} … \end{array} \right. There an '&'
# also starts a condition (cases) or a column (array): only an '&' beside '=' is read, as alignment.
_SYSTEM_ENVIRONMENTS = {"cases", "dcases", "rcases", "array"}
# The argument after \begin{array} (column layout, {l}) and \begin{alignat} (column count, {2}): not a factor.
_ENVIRONMENT_ARGUMENT = {"array", "alignat", "alignedat"}
_BEGIN = re.compile(r"\s*\\begin\s*\{")
_LETTERS = re.compile("[A-Za-z]+")


# x -> 2 (Mathematica's rule, as Solve prints it) and x → 2: an arrow where an equation's = belongs.
def _arrow_error(position: int, arrow: str) -> ExpressionError:
    return ExpressionError(f"'{arrow}' is an arrow (a rule, or 'tends to'), not an equation", position, "syntax",
                           "write = between the two sides of an equation, as in x = 2")


# Primes as LaTeX writes them: ^\prime, ^{\prime}, ^{\prime\prime}
# (and ^′, as Wolfram|Alpha prints θ′ in a superscript)
# (MathLive writes two primes as ^{\doubleprime})
_LATEX_PRIMES = re.compile(r"\^\s*(?:\{\s*(?:(?:\\(?:prime|doubleprime|dprime)|['′″])\s*)+(?P<power>[0-9]{1,3})?\s*\}"
                           r"|\\(?:prime|doubleprime|dprime)(?![A-Za-z])|[′″]+)")

# After a middle dot between digits: 1·10⁻³, 2·10^3 is a mantissa times a power of ten, not 1.10.
_POWER_OF_TEN = re.compile(r"10(?:\^|[⁰¹²³⁴⁵⁶⁷⁸⁹⁻])")
_DIGIT_RUN = re.compile(r"[0-9]+")
_DECIMAL = re.compile(r"[0-9]+\.[0-9]")  # 5·9.81: a decimal after the dot, so the dot is a product
# The exponent of e-notation right after a bare decimal point (3.e10).
_EXPONENT_AFTER_POINT = re.compile(r"[eE][+-]?[0-9]+")

# What a console prints before a formula: Mathematica's In[1]:= and Out[1]=, MATLAB's >>, Maxima's (%o1)
# Mathematica's named characters (\[Theta]), as its InputForm and "Copy As Plain Text" write θ, ×, −.
_MATHEMATICA_NAMED = re.compile(r"\\\[([A-Za-z]+)\]")
MATHEMATICA_CHARACTERS = {
    **{name.capitalize(): char for char, name in GREEK_CHARS.items() if name.islower() and char.isalpha()
       and unicodedata.name(char, "").startswith("GREEK SMALL LETTER") and "FINAL" not in unicodedata.name(char, "")},
    **{"Capital" + name: char for char, name in GREEK_CHARS.items() if name[:1].isupper()},
    "CurlyTheta": "ϑ", "CurlyPhi": "φ", "CurlyEpsilon": "ε", "CurlyRho": "ϱ", "Ell": "ℓ",
    "Times": "×", "CenterDot": "·", "Minus": "−", "Divide": "÷", "Degree": "°",
}
# Mathematica's Subscript[m, 1], Subscript[\[Theta], 0], Subscript[θ, max]: a subscripted name
_MATHEMATICA_SUBSCRIPT = re.compile(r"Subscript\[\s*(?:([A-Za-z][A-Za-z0-9]{0,30})|\\\[([A-Za-z]+)\]|(["
                                    + "".join(GREEK_CHARS) + r"]))\s*,\s*([A-Za-z0-9]{1,20})\s*\]")
# Mathematica's InputForm of a derivative, Derivative[2][θ], and a name it may hold
_MATHEMATICA_DERIVATIVE = re.compile(r"Derivative\[\s*([1-9])\s*\]\[\s*")
_MATHEMATICA_BASE = re.compile(r"([A-Za-z][A-Za-z0-9]{0,30})|\\\[([A-Za-z]+)\]|([" + "".join(GREEK_CHARS) + "])")
_CONSOLE_PROMPT = re.compile(r"\s*(?:(?:In|Out)\[\d+\]\s*:?=|>>|\(%[io]\d+\))")

# Python modules whose functions students paste with the prefix (np.sin, math.sqrt).
_MODULES = frozenset({"np", "numpy", "math", "cmath", "sp", "sympy", "Math"})  # Math: JavaScript's
_ASCII_WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")

# Maxima's constants, typed after a '%' (STACK's %pi, %e, %i).
_MAXIMA_CONSTANT = re.compile(r"(pi|e|i)(?![A-Za-z0-9_])")


def _sign(ch: str) -> str:
    """'+' or '-' for a plus or minus sign as typed (ASCII or a Unicode minus or dash), else ''."""
    sign = OPERATOR_CHARS.get(ch, ch)
    return sign if ch and sign in ("+", "-") else ""


class _Tokenizer:
    def __init__(self, text: str) -> None:
        # full-width ＋（２） is +(2), one for one; x^2_1 is x_1^2, as TeX sets both on x (same length)
        # (each step only where it can change something: translate looks every character up in a dict,
        # raising inside for each one it lacks, and the pattern has a ^ and a _)
        if _FULLWIDTH.search(text):
            text = text.translate(FULLWIDTH_SYMBOLS)
        if text and (_invisible_or_blank(text[0]) or _invisible_or_blank(text[-1])):
            text = _without_invisible_edges(text)
        if "**" in text and (bold := _MARKDOWN_BOLD.fullmatch(text)):
            # **T = m g cos θ**: Markdown's bold, as a chat assistant's copy button gives its final answer (never
            # Python's power: nothing comes before the first ** to raise); spaces, so that positions stay
            text = text[:bold.start(1)] + "  " + text[bold.end(1):bold.start(2)] + "  " + text[bold.end(2):]
        if "\n" in text or text.lstrip()[:1] in _BULLETS:
            text = _without_list_markers(text)
        if ":" in text:
            # Answer: …, Tension: …, **Final answer:** …, r: … on each line: a caption, as \text{Answer: } is
            # (a colon has no other meaning here); spaces, so that positions stay
            text = _CAPTION.sub(lambda caption: " " * len(caption.group()), text)
        self.text = _SUPERSCRIPT_FIRST.sub(r"\2\1", text) if "^" in text and "_" in text else text
        self.n = len(text)
        self.i = 0
        self.tokens: list[Token] = []
        self.space = False
        self.environments: list[str] = []  # the \begin{…} environments open here, innermost last
        self.system_braces = 0  # \left\{ before a \begin{aligned}, closed by \right.
        self.transparent_closes: dict[int, bool] = {}  # where the '}' of a \boxed{…} is: a bracket's or none

    def emit(self, kind: str, value, start: int, end: int, **extra) -> Token:
        token = Token(kind, value, start, end, self.text[start:end], self.space, **extra)
        self.tokens.append(token)
        self.space = False
        self.i = end
        return token

    def braced_name(self, start: int) -> int:
        """How many pairs of braces hold one name right before ``start`` (``{\\theta}`` in MathType's
        ``{\\theta }^{\\prime }``, ``{x}_{1}`` and ``{{x}_{1}}`` of ``x_1''``), 0 for none or when the
        braces are a command's argument (``\\dot{x}``, the ``{b}`` of ``\\frac{a}{b}``, an exponent's ``^{x}``)."""
        tokens = self.tokens
        depth = 0
        while depth < 3 and len(tokens) > depth and tokens[-1 - depth].kind == "close" \
                and tokens[-1 - depth].value == "}":
            depth += 1
        at = len(tokens) - 1 - depth  # the name
        if not depth or at - depth < 0 or tokens[at].kind != "name" \
                or any(not (t.kind == "open" and t.value == "{") for t in tokens[at - depth:at]):
            return 0
        gap = self.text[tokens[-1].end:start]
        if gap.strip() and not ("_" in tokens[at].value and _SUBSCRIPT_GAP.fullmatch(gap)):
            return 0  # only {x}_{1}'s subscript, which the name inside already carries, may come between
        before = tokens[at - depth - 1] if at - depth > 0 else None
        ok = before is None or before.kind in ("name", "number", "open") \
            or (before.kind == "op" and before.value not in ("^", "_"))
        return depth if ok else 0

    def unbrace_name(self) -> Token:
        """Drop the braces of `braced_name`; the name then spans them, as typed."""
        depth = self.braced_name(self.i)
        closer = self.tokens[-1]
        name = self.tokens[-1 - depth]
        opener = self.tokens[-1 - 2 * depth]
        del self.tokens[-1 - 2 * depth:]
        name.pos, name.end = opener.pos, closer.end
        name.text = self.text[name.pos:name.end]
        name.space_before = opener.space_before
        self.tokens.append(name)
        return name

    def peek(self, offset: int = 0) -> str:
        j = self.i + offset
        return self.text[j] if j < self.n else ""

    def run(self) -> list[Token]:
        while self.i < self.n:
            self.step()
        self.tokens.append(Token("end", None, self.n, self.n, "", self.space))
        if any(t.kind == "bar" for t in self.tokens):
            self.tokens = _absolute_values(self.tokens)
        if any(t.kind == "open" and t.value == "(" for t in self.tokens):
            _equation_numbers(self.tokens)
        return self.tokens

    def step(self) -> None:
        ch, start = self.text[self.i], self.i
        if not self.tokens and _CONSOLE_PROMPT.match(self.text, start):
            prompt = _CONSOLE_PROMPT.match(self.text, start).group().strip()
            self.emit("bad", prompt, start, _CONSOLE_PROMPT.match(self.text, start).end(),
                      error=ExpressionError(f"'{prompt}' is a console prompt or output label, not part of the "
                                            "answer", start, "syntax", "delete it and keep the formula after it"))
            return
        # Letters, digits, spaces, ASCII operators and brackets first. Each class matches only one
        # branch of the chain, so the order only decides how soon it is found: before the Unicode
        # lookup of is_space.
        if ch == "S" and (subscript := _MATHEMATICA_SUBSCRIPT.match(self.text, start)):
            self.mathematica_subscript(start, subscript)
        elif ch == "D" and (derivative := _MATHEMATICA_DERIVATIVE.match(self.text, start)) \
                and self.mathematica_derivative(start, derivative):
            pass
        elif ch in _ASCII_NAME_START:
            run = _ASCII_ALNUM_RUN.match(self.text, start) if ch != "_" else None
            end = run.end() if run else start
            if run and (end == self.n or self.text[end] not in _NAME_GOES_ON):
                self.emit("name", run.group(), start, end)  # what identifier() makes of it, directly
            else:
                self.identifier(start, "", start)
                if ch == "_":
                    self.attach_subscript()
        elif ch in _DIGITS:
            self.number()
        elif ch == " ":
            if start + 1 < self.n and self.text[start + 1] in _COMBINING_ACCENTS and self.dot_on_space(start):
                return
            self.space = True
            self.i += 1
        elif ch == "*" and self.peek(1) == "*":
            self.emit("op", "^", start, start + 2)
        elif ch == "=" and self.peek(1) == "=":
            self.emit("op", "=", start, start + 2)
        elif ch == "|" or ch == "∣":  # ∣ (DIVIDES) is the bar some editors and PDFs give
            self.emit("bar", None, start, start + 1)
        elif ch == "^" and self.tokens and ((self.tokens[-1].kind == "name"
                                             and not self.text[self.tokens[-1].end:start].strip())
                                            or self.braced_name(start)) and _LATEX_PRIMES.match(self.text, start):
            if self.tokens[-1].kind != "name":
                self.unbrace_name()
            # (\theta ^{\prime}: LaTeX ignores the space)
            # x^{\prime}, \theta^\prime, x^{\prime\prime}: LaTeX's own spelling of x', θ', x''; and
            # \theta^{\prime 2}, θ' squared (the prime and the power share one superscript)
            marks = _LATEX_PRIMES.match(self.text, start)
            name = self.tokens[-1]
            typed = marks.group()
            name.order += (typed.count("\\prime") + typed.count("′") + typed.count("'")
                           + 2 * (typed.count("″") + typed.count("\\doubleprime") + typed.count("\\dprime")))
            name.end, self.i = marks.end(), marks.end()
            name.text = self.text[name.pos:name.end]
            if marks.group("power"):
                name.end = marks.start("power")
                name.text = self.text[name.pos:name.end]
                self.emit("sup", int(marks.group("power")), name.end, marks.end())
        elif ch == "^" and _DEGREES.match(self.text, start):
            self.degrees(start, _DEGREES.match(self.text, start).end())
        elif _sign(ch) and (_sign(self.peek(1)) == "+-".replace(_sign(ch), "")
                            or (_sign(ch) == "+" and self.peek(1) == "/" and _sign(self.peek(2)) == "-")):
            # +- (or +/-, -+) typed together is the ASCII spelling of ± (∓): a silent reading as
            # +(-b) turned "-b +- sqrt(D)" and "x = +-2" into one sign
            typed = self.text[start:start + (3 if self.peek(1) == "/" else 2)]
            sign, words = ("∓", "minus or plus") if _sign(ch) == "-" else ("±", "plus or minus")
            self.emit("bad", typed, start, start + len(typed),
                      error=ExpressionError(f"'{typed}' reads as {sign} ({words})", start, "syntax",
                                            "give one sign (the answer with + or the one with -); for a plus "
                                            "then a negative number, write + (-2)"))
        elif ch == "-" and self.peek(1) == ">":
            self.emit("bad", "->", start, start + 2, error=_arrow_error(start, "->"))
        elif _sign(ch) == "-" and self.peek(1) == ":":  # ASCIIMath's ÷
            self.emit("op", "/", start, start + 2)
        elif ch == "/" and self.peek(1) == "/":
            self.emit("bad", "//", start, start + 2, error=ExpressionError(
                "'//' is floor division in Python, a postfix function in Mathematica, a slash in ASCIIMath and "
                "'in parallel' in French (R1 // R2)", start, "ambiguous",
                "write / for a quotient, or a*b/(a + b) for a and b in parallel"))
        elif ch in "=/<" and _NOT_EQUAL.match(self.text, start):  # (the first characters of its spellings)
            # =/= (KAS), /= (Fortran, Haskell), <> (BASIC, SQL), =\= (Prolog): "not equal", named as such
            # rather than as a stray '/', a second '=' or an inequality
            typed = _NOT_EQUAL.match(self.text, start).group()
            self.emit("bad", typed, start, start + len(typed),
                      error=ExpressionError(f"'{typed}' (not equal) is not part of an answer", start, "syntax",
                                            "give an expression, or an equation with ="))
        elif ch in "+-*/^=,;":
            self.emit("op", ch, start, start + 1)
        elif ch == "{" and _STYLE_GROUP.match(self.text, start) and self.whole_group(start):
            # {\displaystyle T = m g …}: the LaTeX Wikipedia's formulas copy as, around the whole answer
            self.transparent_closes[self.matching_brace(start)] = False
            self.space = True
            self.i += 1
        elif ch in _PAIRS:
            self.emit("open", ch, start, start + 1)
        elif ch == "}" and start in self.transparent_closes:  # the end of \boxed{…}
            if self.transparent_closes[start]:
                self.emit("close", ")", start, start + 1)
            else:
                self.space = True
                self.i += 1
        elif ch in _OPENERS:
            self.emit("close", ch, start, start + 1)
        elif ch in _LINE_BREAKS:  # and the line and paragraph separators Word, PDFs and web pages paste
            self.emit("newline", "\n", start, start + 1)
        elif is_space(ch) or ch == "$":  # $...$ around pasted LaTeX is only decoration
            if ch == "\u00a0" and self.peek(1) in _COMBINING_ACCENTS and self.dot_on_space(start):
                return
            self.space = True
            self.i += 1
        elif _is_digit(ch) or (ch == "." and _is_digit(self.peek(1))):
            self.number()
        elif _is_name_start(ch):
            self.identifier(start, "", start)
        elif ch == "〖":
            # Word's linear format groups with 〖…〗, which it never shows: 〖cos〗^2⁡θ is cos²θ (a function
            # name alone inside), 〖θ + φ〗 and 〖(m g)〗^2 are a bracket
            close = self.text.find("〗", start + 1)
            word = self.text[start + 1:close] if close > 0 else ""
            if word in FUNCTIONS or word.lower() in FUNCTIONS:
                self.emit("name", word, start + 1, close)
                self.i = close + 1
            else:
                self.emit("open", "(", start, start + 1)
        elif ch == "〗":
            self.emit("close", ")", start, start + 1)
        elif ch == "\u2061":  # FUNCTION APPLICATION, which Word's equations put in sin⁡θ: a space
            self.space = True
            self.i += 1
        elif ch == "\u2062":  # INVISIBLE TIMES (MathML, Word): the product it stands for
            self.emit("op", "*", start, start + 1)
        elif ch in DOTTED_LETTERS:
            letter, order = DOTTED_LETTERS[ch]
            suffix, end = self.subscript_after_accent(start + 1)
            self.finish_name(start, letter + suffix, end, order)
        elif ch == "\\":
            self.command()
        elif ch in MIDDLE_DOTS and self.tokens and self.tokens[-1].kind == "number" and self.tokens[-1].end == start \
                and self.tokens[-1].text.isdigit() and _is_digit(self.peek(1)) \
                and not _POWER_OF_TEN.match(self.text, start + 1) and not _DECIMAL.match(self.text, start + 1):
            # 2·5: the raised decimal point of British print (2.5), or a product (10); after 1.2 or before 9.81 it
            # is a product
            number = _DIGIT_RUN.match(self.text, start + 1).group()
            before = self.tokens[-1].text
            self.emit("bad", ch, start, start + 1,
                      error=ExpressionError(f"'{before}{ch}{number}' reads as the decimal {before}.{number} or as the "
                                            f"product {before}×{number}", start, "ambiguous",
                                            f"write {before}.{number} for the decimal, or {before}*{number} "
                                            "for the product"))
        elif ch in "⇒⟹∴⇔⟺":
            self.implication(start, start + 1, ch)
        elif ch in "→⟶↦":
            self.emit("bad", ch, start, start + 1, error=_arrow_error(start, ch))
        elif ch in OPERATOR_CHARS:
            end = start + 1
            if end < self.n and self.text[end] in VARIATION_SELECTORS:  # ✖️, ➕️: the emoji's style, as typed
                end += 1
            self.emit("op", OPERATOR_CHARS[ch], start, end)
        elif ch in SUPERSCRIPT_CHARS or ch in SUPERSCRIPT_OTHERS:
            self.superscript()
        elif ch == "√" and (indexed := _UNICODEMATH_ROOT.match(self.text, start)):
            # UnicodeMath's n-th root, √(n&x) (what Word's \root n\of x gives in linear format)
            index = int(indexed[1])
            if not 2 <= index <= 1000:
                raise ExpressionError(f"cannot read the root of index {index} in '{indexed.group()}…'", start, "syntax",
                                      "the index of a root is a whole number from 2 on, as in √(3&x)")
            self.emit("root", index, start, start + 1)
            self.emit("open", "(", start + 1, indexed.end())
        elif ch in ROOT_CHARS:
            self.emit("root", ROOT_CHARS[ch], start, start + 1)
        elif ch in VULGAR_FRACTIONS:
            self.vulgar_fraction(start)
        elif ch == "°" and self.tokens and self.tokens[-1].kind == "number":
            self.degrees(start, start + 1)
        elif ch in PRIME_CHARS and self.braced_name(start):
            # {\theta}'' (MathType braces a base): the primes of the name in the braces
            name = self.unbrace_name()
            end = start
            while end < self.n and self.text[end] in PRIME_CHARS:
                name.order += PRIME_CHARS[self.text[end]]
                end += 1
            name.end, self.i = end, end
            name.text = self.text[name.pos:name.end]
        elif ch == "'" and self.text.startswith("diff(", start + 1):
            # Maxima's noun form 'diff(y, t), as STACK asks for a derivative in an equation: the diff itself
            self.space = True
            self.i += 1
        elif ch in PRIME_CHARS:
            self.emit("prime", PRIME_CHARS[ch], start, start + 1)
        elif ch == "." and self.peek(1) in ("*", "/", "^") and self.tokens \
                and self.tokens[-1].kind in ("name", "close", "number", "sup", "prime"):
            # MATLAB's element-wise .* ./ .^ are *, / and ^ on numbers (2.*3 is 6 either way).
            self.i += 1
        elif ch == "." and self.tokens and self.tokens[-1].kind == "name" and self.tokens[-1].end == start \
                and self.tokens[-1].text in _MODULES and _ASCII_WORD.match(self.text, start + 1):
            self.module_attribute(start)
        elif ch == ".":
            previous = self.tokens[-1].kind if self.tokens else None
            message = ("'.' (attribute access) is not allowed" if previous in ("name", "close")
                       else "a decimal point must be followed by digits, as in 0.5")
            code = "unsupported_function" if previous in ("name", "close") else "syntax"
            hint = "use * for a product" if previous in ("name", "close") else "write 0.5, not .5. or 5."
            exponent = _EXPONENT_AFTER_POINT.match(self.text, start + 1)
            if previous == "number" and self.tokens[-1].end == start and exponent:
                # 3.e10, as C and calculators print it: say how to write that number
                mantissa = self.tokens[-1].text
                hint = f"write {mantissa}{exponent.group()} or {mantissa}.0{exponent.group()} for the number"
            self.emit("bad", ".", start, start + 1, error=ExpressionError(message, start, code, hint))
        elif ch == "%" and _MAXIMA_CONSTANT.match(self.text, start + 1):
            # Maxima's (STACK's) %pi, %e, %i: name the constant to type instead.
            word = _MAXIMA_CONSTANT.match(self.text, start + 1).group(0)
            hint = {"pi": "write pi (or π)", "e": "write e, or exp(x) for e^x"}.get(
                word, "complex numbers are not part of these answers")
            self.emit("bad", ch, start, start + 1 + len(word),
                      error=ExpressionError(f"'%{word}' is Maxima's notation", start, "syntax", hint))
        elif ch == "!" and self.peek(1) == "=":  # a programmer's "not equal", not a factorial
            self.emit("bad", ch, start, start + 2,
                      error=ExpressionError("'!=' (not equal) is not part of an answer", start, "syntax",
                                            "give an expression, or an equation with ="))
        elif ch == ":" and self.peek(1) == "=":
            error = ExpressionError("':=' (a definition) is not part of a formula", start, "syntax",
                                    "write an equation with =, or the label's = (T = …), or the expression alone")
            self.emit("bad", ch, start, start + 2, error=error)
        elif ch == "&" and ((self.environments and self.environments[-1] in _LAYOUT_ENVIRONMENTS)
                            or self.beside_equals(start)):
            # an alignment point (of \begin{aligned}, or '&=' of a line copied out of one): nothing to a grader
            self.space = True
            self.i += 1
        elif ch == "~" and "\\" in self.text \
                and not (start > 0 and self.text[start - 1] == " " and self.peek(1) == " "):
            # LaTeX's non-breaking space (Mathpix: g~\sin\theta); set apart, x ~ \frac{l}{2} means 'about' 
            self.space = True
            self.i += 1
        elif ch == "<" and (tag := _MARKUP_TAG.match(self.text, start)):
            # MathML (or HTML) pasted from Word, an editor or a web page: a tag, not 'less than'
            self.emit("bad", ch, start, tag.end(), error=ExpressionError(
                f"'{tag.group(0)}' is {'MathML' if tag.group(1).lower().startswith('m') else 'HTML'} markup, "
                "not a formula", start, "syntax",
                "paste the formula as plain text or LaTeX (in Word: Equation, then Convert to Linear or "
                "copy as LaTeX), or type it, as in m*g*sin(theta)"))
        elif ch in _DOUBLE_QUOTES and self.tokens and self.tokens[-1].kind == "name" \
                and self.tokens[-1].end == start and not _QUOTE_BEFORE.search(self.text, 0, start):
            # θ" (the ″ of a keyboard without one), which a phone's smart punctuation makes θ”: a double prime,
            # or the end of a quotation whose start is not there? Neither is taken.
            name = self.tokens[-1].text
            self.emit("bad", ch, start, start + 1, error=ExpressionError(
                f"'{name}{ch}' reads as {name}″ (a double prime: the second derivative) or as a closing quotation "
                "mark", start, "ambiguous", f"for the second derivative write {name}'' (two apostrophes) or a dotted "
                "letter such as θ̈; otherwise delete the quotation mark"))
        elif ch == "@" and self.tokens and self.tokens[-1].kind == "name" and self.tokens[-1].value == "D" \
                and self.tokens[-1].end == start:
            # Maple's (D@@2)(θ)(t): named where the D is, which the parser meets first (as an unknown name)
            d = self.tokens.pop()
            self.space = d.space_before
            self.emit("bad", "D@", d.pos, start + 1, error=ExpressionError(
                "'@' (composition, as in Maple's D@@2) is not part of a formula", start, "syntax",
                "write a second time derivative as θ̈, D(D(θ))(t) or diff(θ(t), t, 2)"))
        elif ch in _PUNCTUATION:
            message, code, hint = _PUNCTUATION[ch]
            self.emit("bad", ch, start, start + 1, error=ExpressionError(message, start, code, hint))
        elif ch.isascii() and ch.isprintable():
            self.emit("bad", ch, start, start + 1,
                      error=ExpressionError(f"'{ch}' is not allowed in a formula", start, "syntax",
                                            "use letters, digits, + - * / ^ and brackets"))
        else:
            raise bad_character(ch, start)

    def dot_on_space(self, start: int) -> bool:
        """θ ̇: a combining dot on a space (or a no-break space) is Unicode's spacing dot (˙), as Word's linear format
        writes 〖𝜃 ̇〗: the dot of the name right before it, as θ˙ is. Whether it was one (and is read)."""
        name = self.tokens[-1] if self.tokens else None
        if name is None or name.kind != "name" or name.end != start or name.forced_function:
            return False
        end = start + 1
        while end < self.n and self.text[end] in _COMBINING_ACCENTS:
            name.order += COMBINING_DOTS[self.text[end]]
            end += 1
        name.end, self.i = end, end
        name.text = self.text[name.pos:end]
        return True

    def module_attribute(self, dot: int) -> None:
        """``np.sin``, ``math.sqrt``, ``numpy.pi``, ``Math.PI``: a function or π pasted from Python (or JavaScript) with its module
        prefix, one name token spanning both (the prefix carries no meaning of its own). Anything
        else after the prefix (``np.linspace``, ``math.e`` beside a variable e) is refused by name."""
        module = self.tokens.pop()
        word = _ASCII_WORD.match(self.text, dot + 1)
        name = word.group()
        self.space = module.space_before
        if name in FUNCTIONS or name in ("pi", "PI"):  # JavaScript's Math.PI
            self.emit("name", name.lower() if name == "PI" else name, module.pos, word.end())
            return
        self.emit("bad", module.text, module.pos, word.end(),
                  error=ExpressionError(f"'{module.text}.{name}' is not a function or constant of this grammar",
                                        module.pos, "unsupported_function",
                                        WRITE_INSTEAD.get(name.lower(),
                                                          f"write the formula without the '{module.text}.' prefix, "
                                                          "with functions such as sin, sqrt, exp, atan2 and the "
                                                          "constants pi and e")))

    # -- numbers ------------------------------------------------------------
    def degrees(self, start: int, end: int) -> None:
        r"""``30°``, ``30^\circ``, ``30^{\circ}``, ``30\degree``: the number 30·π/180, one token so that
        cos 30° is cos(30°). After a number only: θ° would turn a variable in radians into degrees."""
        if not (self.tokens and self.tokens[-1].kind == "number"):
            raise ExpressionError(f"'{self.text[start:end]}' (degrees) does not follow a number", start,
                                  "bad_character", "angles are in radians: degrees only follow a number, as in 30°")
        number = self.tokens.pop()
        self.space = number.space_before
        self.emit("number", number.value * sympy.pi / 180, number.pos, end, decimal=number.decimal)

    def vulgar_fraction(self, start: int) -> None:
        """``½`` is the number 1/2; ``1½`` (a mixed number, or 1·½?) is refused rather than guessed."""
        if self.tokens and self.tokens[-1].kind == "number" and not self.text[self.tokens[-1].end:start].strip():
            # 1 ½ with a space is the mixed number as often as 1½ ('missing operator' named neither)
            raise ExpressionError(f"'{self.text[self.tokens[-1].pos:start + 1]}' mixes a number and a fraction",
                                  start, "syntax", "write 3/2 or 1 + 1/2, with the operator you mean")
        num, den = VULGAR_FRACTIONS[self.text[start]]
        self.emit("number", sympy.Rational(num, den), start, start + 1)

    def number(self) -> None:
        text, start = self.text, self.i
        j = start
        while j < self.n and _is_digit(text[j]):
            j += 1
        int_part, frac_part, exponent, decimal = text[start:j], "", 0, False
        # 0{,}5: the decimal comma as LaTeX must write it (a bare comma would be followed by a space)
        point = 1 if j < self.n and text[j] == "." else 3 if text.startswith("{,}", j) else 0
        if point and j + point < self.n and _is_digit(text[j + point]):
            k = j + point
            while k < self.n and _is_digit(text[k]):
                k += 1
            frac_part, j, decimal = text[j + point:k], k, True
        # 1.5e-3, and as calculators write it, 1.5ᴇ-3 (TI, NumWorks). The exponent's sign may be any minus a
        # word processor or PDF makes of '-' (1.5e−3 was 1.5·e − 3, Euler's number), and after ᴇ TI's raised ⁻.
        if j < self.n and text[j] in _EXPONENT_MARKS:
            k = j + 1
            negative = k < self.n and (text[k] in MINUS_SIGNS or (text[k] == "⁻" and text[j] == "ᴇ"))
            if k < self.n and (negative or text[k] in _EXPONENT_PLUSES):
                k += 1
            if k < self.n and _is_digit(text[k]):
                m = k
                while m < self.n and _is_digit(text[m]):
                    m += 1
                # Check the exponent's size before building 10**exponent.
                if m - k > 5:
                    raise ExpressionError("number too large", start, "too_large",
                                          "no answer here needs numbers that size")
                exponent, j, decimal = (-1 if negative else 1) * int(text[k:m]), m, True
        mantissa = (int_part + frac_part).lstrip("0") or "0"
        scale = exponent - len(frac_part)
        if len(mantissa) > MAX_DIGITS or (mantissa != "0" and len(mantissa) + scale > MAX_DIGITS) \
                or (mantissa != "0" and -scale > MAX_DIGITS):
            raise ExpressionError("number too large (more than 1000 digits)", start, "too_large",
                                  "no answer here needs numbers that size")
        value = sympy.Integer(int(mantissa))
        if mantissa != "0" and scale:
            value = value * 10 ** scale if scale > 0 else sympy.Rational(int(mantissa), 10 ** -scale)
        self.emit("number", value, start, j, decimal=decimal)  # an Integer or a Rational already

    # -- names ----------------------------------------------------------------
    def identifier(self, start: int, prefix: str, i: int) -> None:
        text, parts, after_subscript_digit = self.text, [prefix], False
        order = 0
        while i < self.n:
            c = text[i]
            if c in _ASCII_ALNUM:  # the common case, as the isalnum branch below, a whole run at once
                run = _ASCII_ALNUM_RUN.match(text, i)
                parts.append(run.group())
                i = run.end()
                after_subscript_digit = False
                continue
            subscript_digit = False
            after = self.after_spaces(i + 1) if c == "_" else i  # m_ {1}, m _ { 1 }: LaTeX ignores the spaces
            if c == "_" and after < self.n and text[after] == "{":
                close = self.matching_brace(after)
                parts.append("_" + subscript_text(text[after + 1:close], after + 1))
                i = close + 1
                break  # LaTeX's subscript closes the symbol: m_{1}x'' is m₁·x'', not (m₁x)''
            elif c == "_" and after < self.n and text[after] == "\\":
                j = after + 1
                while j < self.n and text[j].isascii() and text[j].isalpha():
                    j += 1
                if text[after + 1:j] in WRAPPER_COMMANDS and j < self.n and text[j] == "{":
                    j = self.matching_brace(j) + 1  # v_\text{max}: the font's braces are the subscript's
                parts.append("_" + subscript_text(text[after:j], after))
                i = j
                break
            elif c == "_" and (index := _ROUND_SUBSCRIPT.match(text, after)):
                # ASCIIMath's x_(1) is x₁: read as the product x·1 (or MATLAB's index) it gave 2x for x_(2)
                parts.append("_" + GREEK_CHARS.get(index[1], index[1]))
                i = index.end()
                break
            elif c == "_" and after > i + 1 and after < self.n and text[after] in _ASCII_ALNUM:
                parts.append("_" + text[after])  # m _ 1: one character, as LaTeX takes a bare subscript
                i = after + 1
            elif c.isascii() and (c.isalnum() or c == "_"):
                parts.append(c)
                i += 1
            elif c in GREEK_CHARS:
                parts.append(GREEK_CHARS[c])
                i += 1
            elif c in MATH_LETTERS:  # 𝑚, 𝜃: a styled letter is the letter
                parts.append(MATH_LETTERS[c])
                i += 1
            elif c in SUBSCRIPT_DIGITS:
                parts.append(("" if after_subscript_digit else "_") + SUBSCRIPT_DIGITS[c])
                subscript_digit = True
                i += 1
            elif c in SUBSCRIPT_LETTERS:  # vₓ, θₘₐₓ: one subscript of the letters typed together
                j = i
                while j < self.n and text[j] in SUBSCRIPT_LETTERS:
                    j += 1
                parts.append("_" + "".join(SUBSCRIPT_LETTERS[ch] for ch in text[i:j]))
                i = j
            elif c in COMBINING_DOTS:
                # An accent ends the name: θ̇ is the derivative of everything typed so far, and of
                # the subscript that may follow it (θ̇₁ is θ₁̇).
                while i < self.n and text[i] in COMBINING_DOTS:
                    order += COMBINING_DOTS[text[i]]
                    i += 1
                suffix, i = self.subscript_after_accent(i)
                parts.append(suffix)
                break
            else:
                break
            after_subscript_digit = subscript_digit
        self.finish_name(start, "".join(parts), i, order)

    def after_spaces(self, i: int) -> int:
        """The index of the first character at or after ``i`` that is not a space."""
        while i < self.n and is_space(self.text[i]):
            i += 1
        return i

    def attach_subscript(self) -> None:
        r"""A subscript token (``_1``) just emitted, set apart from its name as LaTeX allows: ``m _ { 1 }``
        (OCR's spacing), ``{m}_{1}``, ``{\theta}_1``, ``{\dot{\theta}}_{1}`` (Word's grouping), ``\dot{\theta} _1``.
        The subscript joins the name before it (inside the group), as LaTeX prints it."""
        sub = self.tokens[-1]
        if len(self.tokens) < 2 or sub.order or len(sub.value) < 2 or self.text[self.tokens[-2].end:sub.pos].strip():
            return
        before = self.tokens[-2]
        if before.kind == "name" and not before.order and not before.forced_function \
                and not before.value.startswith("_"):
            self.tokens[-2:] = [Token("name", before.value + sub.value, before.pos, sub.end,
                                      self.text[before.pos:sub.end], before.space_before)]
            return
        if not (before.kind == "close" and before.value == "}"):
            return
        k = self.group_start(len(self.tokens) - 2)
        group = self.tokens[k + 1:-2]
        ahead = self.tokens[k - 1] if k > 0 else None
        if ahead is not None and ahead.kind == "close" and ahead.value == "}":
            # {m_1}{m}_2 is a product; \frac{a}{m}_1 is the fraction's second argument
            first = self.group_start(k - 1)
            ahead = self.tokens[first - 1] if first > 0 else None
        if k < 0 or (ahead is not None and ahead.kind == "command" and ahead.value not in ("dot", "ddot")):
            return  # \frac{a}{m}_1, \sqrt{m}_1: not a name's subscript
        if len(group) == 1 and group[0].kind == "name" and not group[0].order and not group[0].forced_function:
            target = group[0]
        elif len(group) == 4 and group[0].kind == "command" and group[0].value in ("dot", "ddot") \
                and group[1].kind == "open" and group[2].kind == "name" and not group[2].order \
                and not group[2].forced_function and group[3].kind == "close":
            target = group[2]
        else:
            return
        target.value += sub.value
        self.tokens.pop()

    def group_start(self, close: int) -> int:
        """The index of the token that opens the group the token at ``close`` closes (-1 if none)."""
        depth, k = 0, close
        while k >= 0:
            depth += {"close": 1, "open": -1}.get(self.tokens[k].kind, 0)
            if depth == 0:
                return k
            k -= 1
        return -1

    def subscript_after_accent(self, i: int) -> tuple[str, int]:
        """A subscript typed after a derivative mark (``θ̇₁``, ``ẍ_2``, ``ẍ_{2}``, ``ẋ2``): its name text.

        Only subscripts: letters after the mark start a new name (``ẋy`` is ẋ·y).
        """
        text, n = self.text, self.n
        if i < n and text[i] in SUBSCRIPT_DIGITS:
            j = i
            while j < n and text[j] in SUBSCRIPT_DIGITS:
                j += 1
            return "_" + "".join(SUBSCRIPT_DIGITS[c] for c in text[i:j]), j
        if i < n and _is_digit(text[i]):
            j = i
            while j < n and _is_digit(text[j]):
                j += 1
            return "_" + text[i:j], j
        if i + 1 < n and text[i] == "_" and text[i + 1] == "{":
            close = self.matching_brace(i + 1)
            return "_" + subscript_text(text[i + 2:close], i + 2), close + 1
        if i + 1 < n and text[i] == "_" and text[i + 1] in _ASCII_ALNUM:
            run = _ASCII_ALNUM_RUN.match(text, i + 1)
            return "_" + run.group(), run.end()
        if i + 1 < n and text[i] == "_" and (index := _ROUND_SUBSCRIPT.match(text, i + 1)):  # θ̇_(1), θ'_(1)
            return "_" + GREEK_CHARS.get(index[1], index[1]), index.end()
        return "", i

    def finish_name(self, start: int, name: str, i: int, order: int, **extra) -> None:
        primed = i < self.n and self.text[i] in PRIME_CHARS
        while i < self.n and self.text[i] in PRIME_CHARS:
            order += PRIME_CHARS[self.text[i]]
            i += 1
        if primed and not extra.get("forced_function") and i < self.n \
                and (self.text[i] in SUBSCRIPT_DIGITS or self.text[i] == "_"):
            # θ''₁, theta''_1, x'_{2}: the subscript typed after the primes (not x'2: a product); a
            # function's (\sin''_{1}) is not joined to its name, which would name no function
            suffix, i = self.subscript_after_accent(i)
            name += suffix
        self.emit("name", name, start, i, order=order, **extra)

    def matching_brace(self, open_at: int) -> int:
        depth = 0
        for j in range(open_at, self.n):
            if self.text[j] == "{":
                depth += 1
            elif self.text[j] == "}":
                depth -= 1
                if depth == 0:
                    return j
        raise ExpressionError("'{' is never closed", open_at, "unbalanced", "add a '}'")

    # -- LaTeX ----------------------------------------------------------------
    def command(self) -> None:
        text, start = self.text, self.i
        j = start + 1
        while j < self.n and text[j].isascii() and text[j].isalpha():
            j += 1
        if j == start + 1:
            self.command_symbol(start)
            return
        if text[start + 1:j] == "degree":
            self.degrees(start, j)
            return
        if text[start + 1:j] in ("begin", "end"):
            self.environment(start, j, text[start + 1:j])
            return
        if text[start + 1:j] == "newline":  # LaTeX's other line break, as \\ is
            self.emit("newline", "\n", start, j)
            return
        label = _LABEL_AFTER_SPACE.match(text, j) if text[start + 1:j] in ("quad", "qquad") else None
        if text[start + 1:j] in ("tag", "label"):  # \label{eq:1} names the equation, as \tag{1} numbers it
            label = _TAG.match(text, j)
        if label is not None:
            # \quad (2), \tag{2}: an equation's number, never a factor 2 of it
            self.space = True
            self.i = label.end()
            return
        if text[start + 1:j] in ("overset", "stackrel"):
            self.overset(start, j)
            return
        if text[start + 1:j] in _TRANSPARENT or text[start + 1:j] in _SKIPPED:
            self.transparent(start, j, text[start + 1:j])
            return
        kind, value = classify_command(text[start + 1:j], start)
        # A subscript on a function, spaced or not (latex2sympy's \log _{a}x, OCR's \log _ { b } x): the
        # logarithm's base, never the function's argument (read so, \log _{b} x was log(b)·x)
        k = j
        while kind == "function" and k < self.n and is_space(text[k]):
            k += 1
        subscript = kind == "function" and k < self.n and text[k] == "_"
        if subscript and text[start + 1:j] == "log":
            self.logarithm_base(start, k)
        elif subscript:
            raise ExpressionError(f"cannot read the subscript on {text[start:j]}: only \\log takes one (its base)",
                                  k, "syntax", f"write {text[start:j]}(x); for a logarithm to base b, \\log_{{b}} x")
        elif kind == "greek":
            self.identifier(start, value, j)
        elif kind == "function":
            self.finish_name(start, value, j, 0, forced_function=True)
        elif kind == "op":
            self.emit("op", value, start, j)
        elif kind == "space" and text[start + 1:j] in ("quad", "qquad") and self.numbered_line():
            # (1) \quad x = 1: the equation's number before it, never a factor
            del self.tokens[-3:]
            self.space = True
            self.i = j
        elif kind == "space" and text[start + 1:j] in ("quad", "qquad") and self.between_equations(j):
            # x = 1 \qquad y = 2: two equations set side by side, as on separate lines
            self.emit("newline", "\n", start, j)
        elif kind == "space":
            self.space = True
            self.i = j
        elif kind == "wrapper":
            self.wrapper(start, j, value)
        elif kind == "letter":  # \exponentialE, \differentialD: e and d, as typed
            self.identifier(start, value, j)
        elif kind == "implication":
            self.implication(start, j, text[start:j])
        elif value in ("lbrace", "lbrack", "lparen", "rbrace", "rbrack", "rparen", "lgroup", "rgroup"):
            self.emit("open" if value[0] == "l" else "close", _BRACKET_COMMANDS[value], start, j)
        elif value in ("left", "right"):
            self.delimiter(start, j, value)
        elif value in ("bigl", "bigr"):  # \bigl( \Bigr]: a sized bracket, which side as \left \right say
            self.delimiter(start, j, "left" if value == "bigl" else "right", text[start:j])
        elif value in ("lvert", "rvert", "vert"):
            self.emit("bar", {"lvert": "open", "rvert": "close"}.get(value), start, j)
        else:
            self.emit("command", value, start, j)

    def wrapper(self, start: int, j: int, command: str) -> None:
        r"""``\mathrm{m}``, ``\text{cos}``, ``\boldsymbol{\theta}``: a name in another font. What else a
        student's editor puts in one is read by `wrapped_text`: spacing (``\text{ }``), a full stop or
        comma, ``\text{and}`` between two equations; a unit or words are refused by name."""
        text, k = self.text, j
        if command == "operatorname" and k < self.n and text[k] == "*":
            k += 1  # \operatorname*{sin}: the star only moves limits, which a name has none of
        while k < self.n and is_space(text[k]):
            k += 1
        if k < self.n and text[k] == "{":
            close = self.matching_brace(k)
            inside, after = k + 1, close + 1
        else:
            # \mathrm dt, \mathrm d\theta, \boldsymbol\omega: without braces TeX takes one character or one
            # command, as \mathrm{d}t and \boldsymbol{\omega}
            word = re.match(r"\\[A-Za-z]+|[A-Za-z0-9]", text[k:]) if k < self.n else None
            if word is None:
                raise ExpressionError(f"\\{command} needs braces, as in \\{command}{{x}}", start, "syntax")
            close, inside, after = k + word.end(), k, k + word.end()
        if text[inside:close].strip().endswith(":") and all(token.kind == "newline" for token in self.tokens):
            # \text{Answer: } before the whole answer: a caption, as a label T = is
            self.space = True
            self.i = after
            return
        kind, value = wrapped_text(text[start:after], text[inside:close], inside)
        if kind == "space":
            self.space = True
            self.i = after
        elif kind == "number":  # \mathrm{2}: the number (\mathrm 12, as TeX shows it, 12)
            self.i = inside + text[inside:close].index(value)
            self.number()
            self.i = max(self.i, after)
        elif kind == "punctuation":  # \text{.}, \text{,}: read as the mark itself
            self.i = inside + text[inside:close].index(value)
            self.step()
            self.i = after
        elif kind == "and":  # eq1 \text{ and } eq2: two equations, as with ';'
            self.emit("op", ";", start, after)
        else:
            self.identifier(start, value, after)

    def transparent(self, start: int, j: int, name: str) -> None:
        r"""``\boxed{…}`` (a final answer in a box), ``\displaylines{… \\ …}``, ``\textcolor{red}{…}``: only
        how the formula inside looks, read as if typed alone; ``\color{red}``, ``\hspace{1cm}``, ``\phantom{x}``
        show nothing of the answer and are skipped."""
        k = self.after_spaces(j)
        if k >= self.n or self.text[k] != "{":
            raise ExpressionError(f"\\{name} needs braces, as in \\{name}{{…}}", start, "syntax")
        close = self.matching_brace(k)
        if name in ("textcolor", "colorbox"):  # the colour, then what is coloured
            k = self.after_spaces(close + 1)
            if k >= self.n or self.text[k] != "{":
                raise ExpressionError("\\textcolor needs the text to colour, as in \\textcolor{red}{x}", start,
                                      "syntax")
            close = self.matching_brace(k)
        elif name in _SKIPPED:
            self.space = True
            self.i = close + 1
            return
        # Around the whole answer, or a whole side of it, the box is no bracket (\boxed{T = m g} is an
        # equation); around a part, it groups that part, as its braces do (m \boxed{g + a} is m (g + a)).
        whole = self.whole_group(k)
        self.transparent_closes[close] = not whole
        if whole:
            self.space = True
            self.i = k + 1
        else:
            self.emit("open", "(", start, k + 1)

    def whole_group(self, brace: int) -> bool:
        """Whether the group opened at ``brace`` is a whole answer, line or side of an equation: nothing of
        the formula before it on its line but '=', and nothing after it but the end, '=' or punctuation."""
        last = self.tokens[-1] if self.tokens else None
        return (last is None or last.kind == "newline" or (last.kind == "op" and last.value in "=,;")) \
            and _SIDE_ENDS.match(self.text, self.matching_brace(brace) + 1) is not None

    def overset(self, start: int, j: int) -> None:
        r"""``\overset{\cdot}{\theta}``, ``\overset{..}{x}``, ``\stackrel{.}{x}``: the dots Word's and some
        OCR's LaTeX put over a letter, read as ``\dot`` and ``\ddot``; anything else over a letter is refused."""
        text, k = self.text, j
        while k < self.n and is_space(text[k]):
            k += 1
        if k >= self.n or text[k] != "{":
            raise ExpressionError(f"{text[start:j]} needs braces, as in \\overset{{\\cdot}}{{x}}", start, "syntax")
        close = self.matching_brace(k)
        mark = _DOT_MARKS.sub(".", text[k + 1:close]).replace("¨", "..")
        mark = "".join(c for c in mark if not is_space(c))
        if mark not in (".", ".."):
            raise ExpressionError(f"{text[start:close + 1]}{{…}} (a mark over a letter) is not supported", start,
                                  "unsupported_function", "write \\dot{x} or \\ddot{x} for a time derivative")
        self.emit("command", "dot" if mark == "." else "ddot", start, close + 1)

    def implication(self, start: int, end: int, shown: str) -> None:
        r"""``⇒``, ``\Rightarrow``, ``\implies``, ``∴``: at the very start of the answer (the last line of a
        derivation, copied) it only says "so"; after anything else the answer is a derivation, whose
        steps are not graded (is the line before it part of the answer?), and it is refused, naming the
        arrow. Where no '=' comes before it on its line, it stands for the '=' (a solver's rule)."""
        if all(token.kind == "newline" for token in self.tokens):
            self.space = True
            self.i = end
            return
        line = []  # the tokens of this line so far
        for token in reversed(self.tokens):
            if token.kind == "newline" or (token.kind == "op" and token.value in ",;"):
                break
            line.append(token)
        if not re.sub(r"\s|\$|\\[\])]", "", self.text[end:]):  # T = m g ⇒ (nothing follows)
            self.emit("bad", shown, start, end,
                      error=ExpressionError(f"'{shown}' at the end leads to nothing", start, "syntax",
                                            f"delete the '{shown}'"))
            return
        if line and not any(token.kind == "op" and token.value == "=" for token in line):
            # θ̈ ⇒ −(g/l) sin θ: the arrow stands where the equation's = belongs (a solver's rule)
            self.emit("bad", shown, start, end, error=_arrow_error(start, shown))
            return
        self.emit("bad", shown, start, end,
                  error=ExpressionError(f"'{shown}' joins two steps of a derivation", start, "syntax",
                                        f"give only the final result: delete '{shown}' and what comes before it"))

    def numbered_line(self) -> bool:
        """Whether this line so far is only an equation's number in brackets, as ``(1)``."""
        line = []
        for token in reversed(self.tokens):
            if token.kind == "newline" or (token.kind == "op" and token.value == ";"):
                break
            line.append(token)
        return len(line) == 3 and line[2].kind == "open" and line[2].value == "(" and line[1].kind == "number" \
            and line[1].text.isdigit() and line[0].kind == "close" and line[0].value == ")"

    def between_equations(self, at: int) -> bool:
        """Whether a wide space ending at ``at`` stands between two equations: this line so far holds a
        whole one (an '=' outside brackets) and the rest of the line another '='."""
        depth, equals = 0, False
        for token in reversed(self.tokens):
            if token.kind == "newline" or (token.kind == "op" and token.value == ";"):
                break
            depth += {"open": -1, "close": 1}.get(token.kind, 0)
            equals = equals or (token.kind == "op" and token.value == "=" and depth == 0)
        rest = re.split(r"\\\\|\n|;", self.text[at:], maxsplit=1)[0]
        return equals and depth == 0 and "=" in rest

    def beside_equals(self, at: int) -> bool:
        """Whether the character at ``at`` (an '&') has '=' just before or after it, spaces apart."""
        before, after = at - 1, at + 1
        while before >= 0 and is_space(self.text[before]):
            before -= 1
        while after < self.n and is_space(self.text[after]):
            after += 1
        return (before >= 0 and self.text[before] == "=") or (after < self.n and self.text[after] == "=")

    def environment(self, start: int, j: int, which: str) -> None:
        r"""``\begin{aligned}`` … ``\end{aligned}`` (and align, gather, split, equation, eqnarray) around
        equations pasted from a LaTeX document: only layout, with ``&`` alignment points and ``\\``
        between the equations (read as new lines). Any other environment is refused by name."""
        k = j
        while k < self.n and is_space(self.text[k]):
            k += 1
        close = self.matching_brace(k) if k < self.n and self.text[k] == "{" else -1
        name = self.text[k + 1:close].strip() if close > k else ""
        shown = self.text[start:close + 1] if close > k else self.text[start:j]
        name = name.rstrip("*")
        # MathType and WIRIS set a system in a brace as \left\{ \begin{matrix} … \end{matrix} \right.
        braced_matrix = name == "matrix" and (self.system_braces if which == "begin" else self.environments[-1:] == [name])
        if name not in _LAYOUT_ENVIRONMENTS and name not in _SYSTEM_ENVIRONMENTS and not braced_matrix:
            raise ExpressionError(f"the LaTeX environment {shown} is not supported", start, "unsupported_function",
                                  "type the equations one per line, or separated by ';', without \\begin and "
                                  "\\end (\\begin{aligned} … \\end{aligned} is read)")
        end = close + 1
        if which == "begin":
            self.environments.append(name)
            k = end
            while k < self.n and is_space(self.text[k]):
                k += 1
            if name in _ENVIRONMENT_ARGUMENT and k < self.n and self.text[k] == "{":
                end = self.matching_brace(k) + 1  # alignat's {2}: the layout, not a factor
        elif self.environments:
            self.environments.pop()
        self.space = True
        self.i = end

    def logarithm_base(self, start: int, j: int) -> None:  # j: the index of "_"
        r"""``\log_{10}``, ``\log_2``: a name ``log_10`` that `resolve_name` reads as a logarithm to a base."""
        k = j + 1
        while k < self.n and is_space(self.text[k]):
            k += 1
        command = _COMMAND_NAME.match(self.text, k)
        if k < self.n and self.text[k] == "{":
            close = self.matching_brace(k)
            base, end = subscript_text(self.text[k + 1:close], k + 1), close + 1
        elif command is not None:  # \log_\theta x: the base is the one command, as LaTeX reads it
            base, end = subscript_text(command.group(), k), command.end()
        else:
            run = _ASCII_ALNUM_RUN.match(self.text, k)
            if run is None:
                raise ExpressionError(r"\log_ needs a base, as in \log_{10} x", j, "syntax")
            base, end = run.group()[:1], k + 1  # \log_2x: one character, as LaTeX reads a subscript
        self.emit("name", f"log_{base}", start, end)

    def command_symbol(self, start: int) -> None:
        ch = self.text[start + 1] if start + 1 < self.n else ""
        named = _MATHEMATICA_NAMED.match(self.text, start) if ch == "[" else None
        if named is not None and named.group(1) in MATHEMATICA_CHARACTERS:
            self.mathematica_character(start, named.end(), MATHEMATICA_CHARACTERS[named.group(1)])
        elif named is not None and named.group(1)[:1].isupper():
            raise ExpressionError(f"'{named.group()}' is a Mathematica character that is not read here", start,
                                  "syntax", "type the character itself (θ, ω, ×) or its name (theta, omega, *)")
        elif ch in (",", ";", ":", "!", " ", ">", "(", ")", "[", "]"):  # \( \) \[ \]: math delimiters, as $
            self.space = True
            self.i = start + 2
        elif ch in ("{", "}"):
            self.emit("open" if ch == "{" else "close", ch, start, start + 2)
        elif ch == "\\":
            # \\[2pt]: the line break's extra space, nothing to read
            space = _BREAK_SPACE.match(self.text, start + 2)
            self.emit("newline", "\n", start, space.end() if space else start + 2)
        elif ch == "|":  # \|x\|: a norm
            raise ExpressionError("'‖…‖' (a norm) is not supported", start, "unsupported_function",
                                  "write |x| for the absolute value of a number")
        elif ch == "%":  # LaTeX's escaped percent sign (CortexJS, MathLive), not a stray backslash
            raise ExpressionError("'\\%' (a percent sign) is not part of a formula", start, "syntax",
                                  "write a percentage as a number, as in 0.3 for 30%")
        else:
            raise ExpressionError("'\\' must start a LaTeX command such as \\frac", start, "syntax",
                                  "delete the backslash, or write a command such as \\frac{a}{b}")

    def mathematica_derivative(self, start: int, found: re.Match) -> bool:
        """Mathematica's InputForm of θ'[t], ``Derivative[1][θ][t]`` (and of θ₁'', ``Derivative[2][Subscript[θ, 1]]``):
        the name with that many dots; the ``[t]`` after it is read as θ'[t]'s is. False (nothing emitted) when
        the bracket after ``Derivative[n]`` holds no name."""
        order, at = int(found[1]), found.end()
        subscript = _MATHEMATICA_SUBSCRIPT.match(self.text, at)
        plain = _MATHEMATICA_BASE.match(self.text, at) if subscript is None else None
        closing = re.compile(r"\s*\]").match(self.text, (subscript or plain).end()) if (subscript or plain) else None
        if closing is None:
            return False
        if subscript is not None:
            ascii_name, named, letter, index = subscript.groups()
        else:
            (ascii_name, named, letter), index = plain.groups(), None
        base = ascii_name or GREEK_CHARS.get(MATHEMATICA_CHARACTERS.get(named, ""), "") or GREEK_CHARS.get(letter, "")
        if not base:
            return False
        self.emit("name", f"{base}_{index}" if index else base, start, closing.end(), order=order)
        return True

    def mathematica_subscript(self, start: int, found: re.Match) -> None:
        """Mathematica's ``Subscript[θ, 0]`` (what "Copy As Plain Text" gives for θ₀): the name θ_0, with the
        primes after it (``Subscript[θ, 1]'[t]``). It was refused as an unknown name 'Subscript'."""
        ascii_name, named, letter, index = found.groups()
        base = ascii_name or GREEK_CHARS.get(MATHEMATICA_CHARACTERS.get(named, ""), "") or GREEK_CHARS.get(letter, "")
        if not base:
            self.emit("bad", found.group(), start, found.end(),
                      error=ExpressionError(f"cannot read '{found.group()}'", start, "syntax",
                                            "write the subscripted name as x_1"))
            return
        self.finish_name(start, f"{base}_{index}", found.end(), 0)

    def mathematica_character(self, start: int, end: int, character: str) -> None:
        """Mathematica's ``\\[Theta]`` (what its InputForm and "Copy As Plain Text" give for θ), read as
        the character it names: a letter starts a name there (``\\[Theta]'[t]``, ``\\[Omega]0``)."""
        if character in GREEK_CHARS:
            self.identifier(start, GREEK_CHARS[character], end)
        elif character == "°":
            self.degrees(start, end)
        else:
            self.emit("op", OPERATOR_CHARS[character], start, end)

    def delimiter(self, start: int, j: int, which: str, command: str = "") -> None:
        while j < self.n and is_space(self.text[j]):
            j += 1
        ch = self.text[j] if j < self.n else ""
        if ch == "\\" and j + 1 < self.n and self.text[j + 1] in "{}":
            ch, j = self.text[j + 1], j + 1
        elif ch == "\\":  # \left\lvert, \right\rbrace: the bracket a command names
            word = _LETTERS.match(self.text, j + 1)
            if word is not None and word.group() in _BRACKET_COMMANDS:
                ch, j = _BRACKET_COMMANDS[word.group()], word.end() - 1
            elif self.text[j + 1:j + 2] == "|" or (word is not None and word.group() in ("Vert", "lVert", "rVert")):
                raise ExpressionError("'‖…‖' (a norm) is not supported", start, "unsupported_function",
                                      "write |x| for the absolute value of a number")
        if which == "left" and ch == "{" and _BEGIN.match(self.text, j + 1):
            # \left\{ \begin{aligned} … \end{aligned} \right.: the brace that groups a system, nothing to read
            self.system_braces += 1
            self.space = True
            self.i = j + 1
            return
        if which == "right" and ch == "." and self.system_braces and not self.environments:
            self.system_braces -= 1
            self.space = True
            self.i = j + 1
            return
        if ch in "([{" and ch and which == "left":
            self.emit("open", ch, start, j + 1)
        elif ch in ")]}" and ch and which == "right":
            self.emit("close", ch, start, j + 1)
        elif ch == "|":  # \left| x \right|: an absolute value whose bars say which side they are
            self.emit("bar", "open" if which == "left" else "close", start, j + 1)
        else:
            command = command or "\\" + which
            if ch == "\\":  # \left\langle, \right\rangle: name the whole command
                k = j + 1
                while k < self.n and self.text[k].isascii() and self.text[k].isalpha():
                    k += 1
                ch = self.text[j:k] if k > j + 1 else ch
            shown = ch or "end of text"
            hint = "use \\left( ... \\right), or \\left| ... \\right| for |x|"
            if ch == ".":  # \left. x \right| (evaluated at), \left/ … \right.: an invisible delimiter
                message = f"'{command}.' (an invisible delimiter) is not supported"
                hint = (f"delete '{command}.' and the \\left or \\right it pairs with; "
                        "write plain brackets ( ) where needed")
            elif ch == "/":
                message = f"'{command}/' (a slash sized as a delimiter) is not supported"
                hint = f"write / for division, without {command}, as in a/b or \\frac{{a}}{{b}}"
            else:
                message = f"{command} followed by '{shown}' is not supported"
            raise ExpressionError(message, start, "unsupported_function", hint)

    def superscript(self) -> None:
        start, j = self.i, self.i
        while j < self.n and (self.text[j] in SUPERSCRIPT_CHARS or self.text[j] in SUPERSCRIPT_OTHERS):
            j += 1
        last = self.tokens[-1] if self.tokens else None
        if self.text[start:j] == "⁻" and (last is None or last.kind in ("op", "open", "newline")) \
                and j < self.n and not is_space(self.text[j]):
            # =⁻g: a TI calculator's raised negation sign (its (-) key), where no power can be (nothing to raise)
            self.emit("op", "-", start, j)
            return
        if any(c in SUPERSCRIPT_OTHERS for c in self.text[start:j]):
            self.superscript_letters(start, j)
        digits = "".join(SUPERSCRIPT_CHARS[c] for c in self.text[start:j])
        body = digits.lstrip("+-")
        if not body or not body.isdigit() or len(digits) - len(body) > 1:
            raise ExpressionError(f"cannot read the superscript '{self.text[start:j]}'", start, "syntax",
                                  "write the power with ^, as in x^-1")
        if len(body) > 4:
            raise ExpressionError("exponent too large", start, "too_large", "no answer here needs powers that high")
        last = self.tokens[-4:]
        bracketed = (len(last) == 4 and [t.kind for t in last] == ["op", "open", "number", "close"]
                     and last[0].value == "^" and last[1].value in "({")
        if bracketed or (len(self.tokens) >= 2 and self.tokens[-1].kind == "number"
                         and self.tokens[-2].kind == "op" and self.tokens[-2].value == "^"):
            # θ̇^2² (or x^(2)², x^{2}²): the square typed twice (a keyboard made the second one raised),
            # or the power 2²?
            caret, number = (last[0], last[2]) if bracketed else (self.tokens[-2], self.tokens[-1])
            power = number.text
            raise ExpressionError(f"'^{power} {self.text[start:j]}' gives the power twice", caret.pos,
                                  "ambiguous", f"write it once: ^{power} (or ^({power}^{digits}) for a power of "
                                               "the power)")
        if j < self.n and self.text[j] == "√" and digits.isdigit() and int(digits) >= 2:
            # ³√(x): a calculator's (TI's) root of index 3, as ∛ is. Glued to what comes before (2³√x) it
            # could as well raise that: neither reading is taken. It was read as the power (2 ³√k was 8√k).
            last = self.tokens[-1] if self.tokens else None
            if last is not None and last.end == start and last.kind in ("name", "number", "close", "sup"):
                typed = self.text[last.pos:j + 1]
                raise ExpressionError(f"'{typed}…' reads as {last.text}^{digits}·√… or as {last.text}·(root of "
                                      f"index {digits})", last.pos, "ambiguous",
                                      f"write {last.text}^{digits}*sqrt(…) for the power, or {last.text}*"
                                      f"{'cbrt' if digits == '3' else 'surd'}(…{'' if digits == '3' else ', ' + digits}) "
                                      "for the root")
            self.emit("root", int(digits), start, j + 1)
            return
        self.emit("sup", int(digits), start, j)

    def superscript_letters(self, start: int, j: int) -> None:
        """``e⁻ᵃᵇ``, ``xⁿ``, ``e⁽ᵏᵗ⁾``: refused, naming the characters and giving the text to type.

        Superscript letters are not read: the few fonts that have them are pasted from chat and
        word processors, and which letters multiply which is not written down.
        """
        run = self.text[start:j]
        if run == "ʳ":  # sin(0.5ʳ): a TI calculator's radian mark, or a power r?
            raise ExpressionError("'ʳ' is a TI calculator's radian mark, or a power r", start, "ambiguous",
                                  "angles are in radians here: delete the 'ʳ' (or write ^r for a power)")
        letters = [c for c in run if c in SUPERSCRIPT_OTHERS]
        shown = [f"'{c}' ({unicodedata.name(c, 'U+%04X' % ord(c))})" for c in dict.fromkeys(letters)]
        names, many = ", ".join(shown[:3]) + (", …" if len(shown) > 3 else ""), len(shown) > 1
        inner, previous = "", ""
        for c in run:
            plain = SUPERSCRIPT_OTHERS.get(c) or SUPERSCRIPT_CHARS[c]
            if plain.isalpha() and previous.isalpha():
                inner += " "  # ᵃᵇ is a·b: written a b
            inner += plain
            previous = plain
        last = self.tokens[-1] if self.tokens else None
        base = last.text if last is not None and last.end == start and last.kind in ("name", "number") \
            and len(last.text) <= 20 else "x"
        power = inner if len(inner) == 1 or inner.isdigit() or (inner.startswith("(") and inner.endswith(")")) \
            else f"({inner})"
        if len(run) > 20:  # a pasted wall of them: the message names them, not all of it again
            run, power, base = run[:20] + "…", "(-a b)", "e"
        raise ExpressionError(f"cannot read the superscript '{run}': {names} {'are' if many else 'is'} not read "
                              "as a power", start, "bad_character",
                              f"write the power with ^ and ordinary letters, as in {base}^{power}")


# Commands around the formula that only change its look (\boxed{…}, a student's final answer), and commands
# with an argument that shows nothing of the answer (\color{red}, \hspace{1cm}, \phantom{x}).
_TRANSPARENT = {"boxed", "fbox", "displaylines", "textcolor", "colorbox", "underline"}
_SKIPPED = {"color", "hspace", "vspace", "phantom", "hphantom", "vphantom"}
# {\displaystyle …}, {\begin{aligned} … \end{aligned}}: a group that only sets the style of what is in it.
_STYLE_GROUP = re.compile(r"\{\s*(?:\\(?:displaystyle|textstyle)(?![A-Za-z])|\\begin\s*\{)")
# What may follow a box around a whole side: the end, '=', the next line, punctuation, closing math.
_SIDE_ENDS = re.compile(r"\s*(?:$|=|\n|\\\\|[.,;$}]|\\(?:end|\]|\)|quad|qquad|tag|label|text)(?![A-Za-z]))")

# \left\lvert x \right\rvert, \left\lbrace: the bracket character each command stands for.
_BRACKET_COMMANDS = {"lvert": "|", "rvert": "|", "vert": "|", "lbrace": "{", "rbrace": "}", "lbrack": "[",
                     "rbrack": "]", "lparen": "(", "rparen": ")", "lgroup": "(", "rgroup": ")"}
# Dots set over a letter (\overset{\cdot}{x}): each is one dot.
_DOT_MARKS = re.compile(r"\\(?:cdot|bullet|ldotp|centerdot)(?![A-Za-z])|[˙·•∙⋅]")


def _lone_number(tokens: list[Token], k: int) -> bool:
    """Whether tokens k, k+1, k+2 are '(', a whole number, ')' (as an equation's number is written)."""
    return k >= 0 and k + 2 < len(tokens) and tokens[k].kind == "open" and tokens[k].value == "(" \
        and tokens[k + 1].kind == "number" and tokens[k + 1].text.isdigit() \
        and tokens[k + 2].kind == "close" and tokens[k + 2].value == ")"


def _function_name(token: Token) -> bool:
    """Whether ``token`` names a function: ``sin (2)`` and ``\\sin \\left( 2 \\right)`` are its call."""
    return token.kind == "name" and str(token.value).lstrip("\\").lower() in FUNCTIONS


_DEPTH_CHANGE = {"open": 1, "close": -1}


def _equation_numbers(tokens: list[Token]) -> None:  # changes tokens in place
    r"""``(2) y = l`` and ``x + y = l (2)``: a whole number in brackets set apart by a space at the start or
    the end of a line reads as the equation's number or as a factor 2; it is refused, naming both (read
    as a factor it would silently change the equation). ``\quad (2)`` and ``\tag{2}`` are numbers, read
    as such by the tokenizer; ``2(x + y)`` and ``(2)(3)`` are products."""
    breaks, depth = [], 0  # where lines and equations end: new lines, and ';' or ',' outside brackets
    for n, t in enumerate(tokens):
        depth += _DEPTH_CHANGE.get(t.kind, 0)
        if t.kind in ("newline", "end") or (t.kind == "op" and t.value in ";," and depth == 0):
            breaks.append(n)
    starts, ends = [0] + [n + 1 for n in breaks], breaks
    found = None
    for k in starts:  # (2) y = l
        if _lone_number(tokens, k) and k + 3 < len(tokens) and tokens[k + 3].space_before \
                and tokens[k + 3].kind in ("name", "number", "open", "command", "root", "derivative"):
            found = k
            break
    if found is None:
        for end in ends:  # x + y = l (2)
            k = end - 3
            if _lone_number(tokens, k) and tokens[k].space_before and k > 0 \
                    and tokens[k - 1].kind in ("name", "number", "close") and not _function_name(tokens[k - 1]):
                found = k
                break
    if found is not None:
        opener, number, closer = tokens[found:found + 3]
        shown = f"({number.text})"
        tokens[found:found + 3] = [Token("bad", shown, opener.pos, closer.end, shown, opener.space_before,
                                         error=ExpressionError(f"'{shown}' reads as the equation's number or as a "
                                                               f"factor {number.text}", opener.pos, "ambiguous",
                                                               f"delete the equation's number, or write "
                                                               f"{number.text}* for the factor"))]


# After these a bar opens an absolute value (an operand is expected); after anything else it closes one.
_OPERAND_EXPECTED = frozenset({"op", "open", "root", "command", "newline"})


def _parallel_bars(pair: tuple[Token, Token]) -> ExpressionError:
    return ExpressionError(f"'{pair[0].text}{pair[1].text}' after an operand reads as the parallel operator "
                           "(a||b = a b/(a + b)) or as a double bar", pair[0].pos, "ambiguous",
                           "write a*b/(a + b) or 1/(1/a + 1/b) for a and b in parallel, "
                           "or a*|b| for a product with an absolute value")


def _absolute_values(tokens: list[Token]) -> list[Token]:
    r"""``|x|`` -> ``abs ( x )``: each bar becomes the opening or the closing of an absolute value.

    A bar opens where an operand is expected (at the start, after an operator, a bracket or
    another opening bar) and closes the innermost open one elsewhere; with none open it opens a
    factor of a product (``2|x|``, ``|a|b|c|`` is |a|·b·|c|). ``\left|`` and ``\right|`` say
    which they are.
    """
    out: list[Token] = []
    open_bars: list[Token] = []
    pair = None  # a || after an operand, with no bar open: the parallel operator, unless it closes apart
    for n, token in enumerate(tokens):
        if token.kind != "bar":
            out.append(token)
            continue
        previous = out[-1] if out else None
        if (not open_bars and token.value is None and previous is not None and previous.kind not in _OPERAND_EXPECTED
                and tokens[n + 1].kind == "bar" and tokens[n + 1].pos == token.end):
            # a||b is edX's parallel operator (a b/(a + b)) and 'or' in code; read as a·‖b‖ it made
            # R1||R2||R3 the product R1·R2·R3. Refused unless the two bars close apart (2||x| - 1|, nested).
            pair = (token, tokens[n + 1])
        last = tokens[n + 1].kind in ("end", "close") and open_bars  # nothing can follow an opening here
        opens = token.value == "open" or (token.value is None and not last and (
            previous is None or previous.kind in _OPERAND_EXPECTED or not open_bars))
        if opens:
            out.append(Token("name", "abs", token.pos, token.end, token.text, token.space_before,
                             forced_function=True))
            out.append(Token("open", "(", token.pos, token.end, token.text))
            open_bars.append(token)
            continue
        if not open_bars:
            raise ExpressionError(f"'{token.text}' closes an absolute value that was never opened", token.pos,
                                  "unbalanced", "write |x| with a bar on each side")
        if previous is not None and previous.kind == "open" and previous.text == open_bars[-1].text \
                and previous.pos == open_bars[-1].pos:
            raise ExpressionError("empty absolute value bars", open_bars[-1].pos, "syntax", "put an expression between them")
        if pair is not None and open_bars[-1] is pair[1] and tokens[n + 1].kind == "bar" \
                and tokens[n + 1].pos == token.end:
            raise _parallel_bars(pair)  # a||b||c: the pair closes as a pair, ‖b‖
        if pair is not None and open_bars[-1] is pair[0]:
            pair = None  # 2||x| - 1|: nested absolute values
        out.append(Token("close", ")", token.pos, token.end, token.text))
        open_bars.pop()
    if open_bars and pair is not None:
        raise _parallel_bars(pair)
    if open_bars:
        raise ExpressionError(f"'{open_bars[-1].text}' opens an absolute value that is never closed",
                              open_bars[-1].pos, "unbalanced", "close it with a second bar")
    return out


def tokenize(text: str) -> list[Token]:
    """Split text into tokens; raises ``ExpressionError`` on characters it refuses.

    Examples
    --------
    >>> [(t.kind, t.value) for t in tokenize("2θ̇ ·x²")]
    [('number', 2), ('name', 'theta'), ('op', '*'), ('name', 'x'), ('sup', 2), ('end', None)]
    >>> tokenize("2θ̇")[1].order
    1
    """
    return _Tokenizer(text).run()


def check_brackets(tokens: list[Token]) -> None:
    """Raise for an unmatched or mismatched bracket, pointing at it, or nesting beyond :data:`MAX_NESTING`.

    Checked before parsing so ``((((...`` is refused without recursing into it.

    Examples
    --------
    >>> try:
    ...     check_brackets(tokenize("(a + b"))
    ... except ExpressionError as err:
    ...     print(err.code, err.position)
    unbalanced 0
    """
    stack: list[Token] = []
    for token in tokens:
        if token.kind == "open":
            stack.append(token)
            if len(stack) > MAX_NESTING:
                raise ExpressionError(f"brackets nested more than {MAX_NESTING} deep", token.pos, "too_deep",
                                      "simplify the expression first")
        elif token.kind == "close":
            opener = _OPENERS[token.value]
            if not stack:
                raise ExpressionError(f"'{token.value}' has no matching '{opener}'", token.pos, "unbalanced",
                                      f"add a '{opener}' or delete this '{token.value}'")
            top = stack.pop()
            if top.value != opener:
                raise ExpressionError(f"'{token.value}' does not match the '{top.value}' at character "
                                      f"{top.pos + 1}", token.pos, "unbalanced", f"close it with '{_PAIRS[top.value]}'")
    if stack:
        top = stack[-1]
        raise ExpressionError(f"'{top.value}' is never closed", top.pos, "unbalanced",
                              f"add a '{_PAIRS[top.value]}'")
