"""LaTeX -> MathML, on the server, for the subset that problem statements and sympy's ``latex()`` use.

Why on the server and not KaTeX in the browser: the pages must work without JavaScript, the network is
closed (no CDN, and a vendored bundle is a build step that can drift), and every browser we target
renders MathML Core natively. One converter serves statements, reference answers and live previews, so
they look alike, and tests can read the output. It never raises: a command it does not know is shown
as an ``<merror>`` holding the source, and :func:`unsupported` lists such commands so the instructor
sees them while the problem is still a draft.

>>> to_mathml(r"\\frac{1}{2} m \\dot{\\theta}^{2}")[:40]
'<math display="inline"><semantics><mrow>'
"""

from __future__ import annotations

import re
from functools import lru_cache
from html import escape

__all__ = ["to_mathml", "unsupported"]

_GREEK = {
    "alpha": "α", "beta": "β", "gamma": "γ", "delta": "δ", "epsilon": "ϵ", "varepsilon": "ε",
    "zeta": "ζ", "eta": "η", "theta": "θ", "vartheta": "ϑ", "iota": "ι", "kappa": "κ",
    "lambda": "λ", "mu": "μ", "nu": "ν", "xi": "ξ", "omicron": "ο", "pi": "π", "varpi": "ϖ",
    "rho": "ρ", "varrho": "ϱ", "sigma": "σ", "varsigma": "ς", "tau": "τ", "upsilon": "υ",
    "phi": "ϕ", "varphi": "φ", "chi": "χ", "psi": "ψ", "omega": "ω",
    "Gamma": "Γ", "Delta": "Δ", "Theta": "Θ", "Lambda": "Λ", "Xi": "Ξ", "Pi": "Π",
    "Sigma": "Σ", "Upsilon": "Υ", "Phi": "Φ", "Psi": "Ψ", "Omega": "Ω",
    "ell": "ℓ", "hbar": "ℏ", "infty": "∞", "partial": "∂", "nabla": "∇", "emptyset": "∅",
}
# Greek capitals are upright by convention; everything else in _GREEK is an identifier.
_UPRIGHT_IDENTIFIERS = {"Gamma", "Delta", "Theta", "Lambda", "Xi", "Pi", "Sigma", "Upsilon",
                        "Phi", "Psi", "Omega", "infty", "emptyset"}
_OPERATORS = {
    "cdot": "⋅", "times": "×", "div": "÷", "pm": "±", "mp": "∓", "leq": "≤", "le": "≤",
    "geq": "≥", "ge": "≥", "neq": "≠", "ne": "≠", "approx": "≈", "equiv": "≡", "sim": "∼",
    "simeq": "≃", "propto": "∝", "to": "→", "rightarrow": "→", "leftarrow": "←",
    "Rightarrow": "⇒", "Leftrightarrow": "⇔", "mapsto": "↦", "ldots": "…", "cdots": "⋯",
    "dots": "…", "in": "∈", "notin": "∉", "subset": "⊂", "cup": "∪", "cap": "∩", "circ": "∘",
    "mid": "∣", "parallel": "∥", "perp": "⊥", "angle": "∠", "prime": "′", "forall": "∀",
    "exists": "∃", "ll": "≪", "gg": "≫", "lbrace": "{", "rbrace": "}", "langle": "⟨",
    "rangle": "⟩", "vert": "|", "Vert": "‖", "lvert": "|", "rvert": "|", "lVert": "‖",
    "rVert": "‖", "{": "{", "}": "}", "|": "‖", "%": "%", "$": "$", "#": "#", "&": "&", "_": "_",
    "degree": "°",
}
_LARGE_OPERATORS = {"sum": "∑", "prod": "∏", "int": "∫", "iint": "∬", "oint": "∮"}
_FUNCTIONS = {
    "sin", "cos", "tan", "cot", "sec", "csc", "arcsin", "arccos", "arctan", "sinh", "cosh",
    "tanh", "coth", "log", "ln", "exp", "min", "max", "det", "lim", "sgn", "arg", "deg",
}
_ACCENTS = {"dot": "˙", "ddot": "¨", "hat": "^", "widehat": "^", "bar": "¯", "overline": "¯",
            "vec": "→", "tilde": "˜", "widetilde": "˜"}
_SPACES = {",": "0.1667em", ":": "0.2222em", ";": "0.2778em", " ": "0.25em", "quad": "1em",
           "qquad": "2em", "!": "-0.1667em"}
_STYLES = {"mathrm": "normal", "mathbf": "bold", "boldsymbol": "bold", "bm": "bold",
           "mathit": "italic", "mathcal": "script", "mathsf": "sans-serif", "mathtt": "monospace"}
_TEXT = {"text", "textrm", "mbox", "textit", "textbf", "operatorname"}
_FRACTIONS = {"frac", "dfrac", "tfrac"}
_IGNORED = {"displaystyle", "textstyle", "limits", "nolimits", "left", "right", "big", "Big",
            "bigg", "Bigg", "bigl", "bigr", "Bigl", "Bigr"}
_ENVIRONMENTS = {"matrix": None, "pmatrix": ("(", ")"), "bmatrix": ("[", "]"),
                 "vmatrix": ("|", "|"), "Bmatrix": ("{", "}"), "cases": ("{", None),
                 "aligned": None, "align": None, "align*": None, "array": None, "smallmatrix": None}

_LETTER = re.compile(r"[A-Za-z]")
_WORD = re.compile(r"([A-Za-z]{2,})")
_ROMAN_WORD = re.compile(r"\\(?:mathrm|text|textrm)\s*\{\s*([A-Za-z]{2,})\s*\}")
_TOKEN = re.compile(r"\\([A-Za-z]+\*?|.)|(\d+(?:\.\d+)?|\.\d+)|(\s+)|(.)", re.S)


def _tokens(tex: str) -> tuple[list[tuple[str, str]], list[int]]:
    """Tokens (kind, value) and where each starts in ``tex``; white space is dropped."""
    tokens, starts = [], []
    for match in _TOKEN.finditer(tex):
        command, number, space, char = match.groups()
        if space:
            continue
        tokens.append(("cmd", command) if command else ("num", number) if number else ("chr", char))
        starts.append(match.start())
    return tokens, starts


class _Parser:
    def __init__(self, tex: str):
        self.tex = tex
        self.tokens, self.starts = _tokens(tex)
        self.i = 0
        self.unknown: list[str] = []

    # -- helpers ---------------------------------------------------------------------------------
    def peek(self) -> tuple[str, str] | None:
        return self.tokens[self.i] if self.i < len(self.tokens) else None

    def take(self) -> tuple[str, str] | None:
        token = self.peek()
        self.i += token is not None
        return token

    def raw_group(self) -> str:
        """The source text of a ``{...}`` group (or of one token), for ``\\text`` and ``\\begin``."""
        if self.peek() != ("chr", "{"):
            token = self.take()
            return "" if token is None else token[1]
        begin = self.starts[self.i] + 1  # just after the "{"
        self.take()
        depth = 1
        while (token := self.take()) is not None:
            depth += (token == ("chr", "{")) - (token == ("chr", "}"))
            if depth == 0:
                return self.tex[begin:self.starts[self.i - 1]]
        return self.tex[begin:]

    def argument(self) -> str:
        """One argument: a braced group or a single token, as MathML."""
        token = self.peek()
        if token == ("chr", "{"):
            self.take()
            return _row(self.row(stop=frozenset("}")))
        if token is not None and token[0] == "num" and len(token[1]) > 1:
            # TeX takes one digit as an argument: \tfrac12 is 1/2, not 12/...
            self.tokens[self.i] = ("num", token[1][1:])
            self.starts[self.i] += 1
            return f"<mn>{token[1][0]}</mn>"
        atom = self.atom()
        return atom if atom is not None else "<mrow></mrow>"

    def word(self) -> str | None:
        """A subscript that is a word (``_{surface}``, ``_{\\mathrm{surface}}``, or bare ``_surface`` as
        authors write it) as one upright ``<mtext>``: a label, not a product of italic letters."""
        token = self.peek()
        if token is None:
            return None
        if token == ("chr", "{"):
            start, end = self.starts[self.i] + 1, self._closing(self.i)
            if end is None:
                return None
            inner = self.tex[start:self.starts[end]].strip()
            found = _WORD.fullmatch(inner) or _ROMAN_WORD.fullmatch(inner)
            if found is None:
                return None
            self.i = end + 1
            return f"<mtext>{escape(found.group(1))}</mtext>"
        if token[0] != "chr" or not _LETTER.fullmatch(token[1]):
            return None
        # Letters typed together right after "_": contiguous in the source, so "x_a b" stays x_a b.
        j, letters = self.i, ""
        while (j < len(self.tokens) and self.tokens[j][0] == "chr" and _LETTER.fullmatch(self.tokens[j][1])
               and self.starts[j] == self.starts[self.i] + len(letters)):
            letters += self.tokens[j][1]
            j += 1
        if len(letters) < 2:
            return None
        self.i = j
        return f"<mtext>{escape(letters)}</mtext>"

    def _closing(self, i: int) -> int | None:
        """The index of the token closing the ``{`` at token ``i``."""
        depth = 0
        for j in range(i, len(self.tokens)):
            depth += (self.tokens[j] == ("chr", "{")) - (self.tokens[j] == ("chr", "}"))
            if depth == 0:
                return j
        return None

    def optional(self) -> str | None:
        if self.peek() != ("chr", "["):
            return None
        self.take()
        return _row(self.row(stop=frozenset("]")))

    # -- grammar ---------------------------------------------------------------------------------
    def row(self, stop: frozenset[str] = frozenset(), table: bool = False) -> list[str]:
        """Atoms up to a closing token (consumed), with scripts attached to their base.

        In a table (``table=True``) a row also ends at ``&``, ``\\\\`` and ``\\end``; what ended it
        is left in ``self.ended``.
        """
        items: list[str] = []
        self.ended = "eof"
        while (token := self.peek()) is not None:
            kind, value = token
            if kind == "chr" and value in stop:
                self.take()
                self.ended = value
                return items
            if kind == "cmd" and value == "right" and "right" in stop:
                self.take()
                items.append(self.delimiter())
                return items
            if table and (token == ("chr", "&") or token == ("cmd", "\\")):
                self.take()
                self.ended = value
                return items
            if table and token == ("cmd", "end"):
                self.take()
                self.raw_group()
                self.ended = "end"
                return items
            if kind == "chr" and value in "^_":
                base = items.pop() if items else "<mrow></mrow>"
                items.append(self.scripts(base))
                continue
            function = kind == "cmd" and value in _FUNCTIONS
            atom = self.atom()
            if atom is None:
                continue
            if function and self.peek() in (("chr", "^"), ("chr", "_")):
                atom = self.scripts(atom)
            items.append(atom)
            if function:
                items.append("<mo>\u2061</mo>")  # function application: sin x, not sin·x
        return items

    def scripts(self, base: str) -> str:
        sub = sup = None
        while (token := self.peek()) in (("chr", "^"), ("chr", "_")):
            self.take()
            if token[1] == "^":
                sup = self.argument()
            else:
                sub = self.word() or self.argument()
        large = base.startswith("<mo largeop")
        under, over, both = ("munder", "mover", "munderover") if large else ("msub", "msup", "msubsup")
        if sub is not None and sup is not None:
            return f"<{both}>{base}{sub}{sup}</{both}>"
        if sup is not None:
            return f"<{over}>{base}{sup}</{over}>"
        return f"<{under}>{base}{sub}</{under}>"

    def delimiter(self) -> str:
        token = self.take()
        if token is None or token == ("chr", "."):
            return ""
        value = _OPERATORS.get(token[1], token[1]) if token[0] == "cmd" else token[1]
        return f'<mo stretchy="true">{escape(value)}</mo>'

    def atom(self) -> str | None:
        token = self.take()
        if token is None:
            return None
        kind, value = token
        if kind == "num":
            return f"<mn>{value}</mn>"
        if kind == "chr":
            if value == "{":
                return _row(self.row(stop=frozenset("}")))
            if value.isalpha():
                return f"<mi>{escape(value)}</mi>"
            if value == "~":
                return '<mspace width="0.25em"></mspace>'
            if value in "}&":
                return None  # unbalanced: dropped rather than shown
            if value == "'":
                return "<mo>′</mo>"
            if value == "-":
                return "<mo>−</mo>"  # a real minus sign, not a hyphen
            return f"<mo>{escape(value)}</mo>"
        return self.command(value)

    def command(self, name: str) -> str | None:
        if name in _GREEK:
            variant = ' mathvariant="normal"' if name in _UPRIGHT_IDENTIFIERS else ""
            return f"<mi{variant}>{_GREEK[name]}</mi>"
        if name in _OPERATORS:
            return f"<mo>{escape(_OPERATORS[name])}</mo>"
        if name in _LARGE_OPERATORS:
            return f'<mo largeop="true">{_LARGE_OPERATORS[name]}</mo>'
        if name in _FUNCTIONS:
            return f"<mi>{name}</mi>"
        if name in _FRACTIONS:
            return f"<mfrac>{self.argument()}{self.argument()}</mfrac>"
        if name == "sqrt":
            index = self.optional()
            body = self.argument()
            return f"<mroot>{body}{index}</mroot>" if index else f"<msqrt>{body}</msqrt>"
        if name in _ACCENTS:
            return f'<mover accent="true">{self.argument()}<mo>{_ACCENTS[name]}</mo></mover>'
        if name in _SPACES:
            return f'<mspace width="{_SPACES[name]}"></mspace>'
        if name in _STYLES:
            if name == "mathrm" and self.peek() == ("chr", "{"):
                end = self._closing(self.i)
                inner = self.tex[self.starts[self.i] + 1:self.starts[end]].strip() if end is not None else ""
                if _WORD.fullmatch(inner):  # an upright word is text: "surface", not s·u·r·f·a·c·e
                    self.i = end + 1
                    return f"<mtext>{escape(inner)}</mtext>"
            body = self.argument()
            # A class, not style="": the Content-Security-Policy allows no inline style (lagrade.css has it).
            style = ' class="bold"' if _STYLES[name] == "bold" else ""
            return f'<mstyle mathvariant="{_STYLES[name]}"{style}>{body}</mstyle>'
        if name in _TEXT:
            text = re.sub(r"^\s+|\s+$", "\u00a0", self.raw_group())  # keep edge spaces
            tag = "mi" if name == "operatorname" else "mtext"
            return f"<{tag}>{escape(text)}</{tag}>"
        if name == "left":
            opening = self.delimiter()
            inner = self.row(stop=frozenset({"right"}))
            return _row([opening, *inner])
        if name == "begin":
            return self.environment(self.raw_group())
        if name in _IGNORED or name == "\\":
            return None
        self.unknown.append("\\" + name)
        return f"<merror><mtext>\\{escape(name)}</mtext></merror>"

    def environment(self, name: str) -> str:
        if name not in _ENVIRONMENTS:
            self.unknown.append(f"\\begin{{{name}}}")
        if name == "array" and self.peek() == ("chr", "{"):
            self.raw_group()  # column spec: alignment is not worth honouring here
        rows: list[list[str]] = [[]]
        while True:
            cell = _row(self.row(table=True))
            rows[-1].append(cell)
            if self.ended == "&":
                continue
            if self.ended == "\\":
                rows.append([])
                continue
            break
        if len(rows) > 1 and rows[-1] == ["<mrow></mrow>"]:
            rows.pop()  # a trailing \\ before \end
        table = "<mtable>" + "".join(
            "<mtr>" + "".join(f"<mtd>{c}</mtd>" for c in r) + "</mtr>" for r in rows) + "</mtable>"
        fences = _ENVIRONMENTS.get(name)
        if not fences:
            return table
        left, right = fences
        left_mo = f'<mo stretchy="true">{escape(left)}</mo>' if left else ""
        right_mo = f'<mo stretchy="true">{escape(right)}</mo>' if right else ""
        return _row([left_mo, table, right_mo])


def _row(items: list[str]) -> str:
    items = [item for item in items if item]
    return items[0] if len(items) == 1 else "<mrow>" + "".join(items) + "</mrow>"


@lru_cache(maxsize=4096)
def _convert(tex: str) -> tuple[str, tuple[str, ...]]:
    parser = _Parser(tex)
    items = []
    try:
        while parser.peek() is not None:
            items.extend(parser.row(stop=frozenset("}")))  # a stray "}" ends a row: go on after it
    except RecursionError:  # absurdly deep nesting: show the source rather than fail the page
        return f"<merror><mtext>{escape(tex)}</mtext></merror>", ("nesting too deep",)
    return "<mrow>" + "".join(i for i in items if i) + "</mrow>", tuple(parser.unknown)


def to_mathml(tex: str, display: bool = False) -> str:
    """A ``<math>`` element for ``tex``, with the source kept as an annotation for copying.

    >>> to_mathml("x^{2}")
    '<math display="inline"><semantics><mrow><msup><mi>x</mi><mn>2</mn></msup></mrow><annotation encoding="application/x-tex">x^{2}</annotation></semantics></math>'
    """
    body, _ = _convert(tex.strip())
    mode = "block" if display else "inline"
    return (f'<math display="{mode}"><semantics>{body}'
            f'<annotation encoding="application/x-tex">{escape(tex.strip(), quote=False)}</annotation>'
            f"</semantics></math>")


def unsupported(tex: str) -> list[str]:
    """The commands in ``tex`` that :func:`to_mathml` shows as errors.

    >>> unsupported(r"\\frac{a}{b} + \\foo")
    ['\\\\foo']
    """
    return list(_convert(tex.strip())[1])
