"""What non-ASCII characters mean in typed expressions.

Students paste from phones, Word and PDFs, so ``θ``, ``·``, ``−``, ``²`` and
``√`` are accepted.  Characters that merely *look* like Latin letters (Cyrillic
``а``, Greek omicron ``ο``, full-width ``ｍ``) and invisible ones are refused
with a message naming them: accepting them silently would make ``а`` and ``a``
different variables and grade a correct answer wrong.
"""

from __future__ import annotations

import unicodedata
from fractions import Fraction

from .errors import ExpressionError

__all__ = ["GREEK_CHARS", "MATH_LETTERS", "MIDDLE_DOTS", "MINUS_SIGNS", "OPERATOR_CHARS", "VARIATION_SELECTORS", "FULLWIDTH_SYMBOLS", "SUPERSCRIPT_CHARS",
           "SUPERSCRIPT_OTHERS", "SUBSCRIPT_DIGITS", "SUBSCRIPT_LETTERS", "ROOT_CHARS",
           "COMBINING_DOTS", "DOTTED_LETTERS", "PRIME_CHARS", "VULGAR_FRACTIONS", "is_space", "bad_character"]

_GREEK_NAMES = ("alpha beta gamma delta epsilon zeta eta theta iota kappa lambda mu nu xi "
                "omicron pi rho sigma tau upsilon phi chi psi omega").split()

#: Greek letters accepted in names, spelled out (θ -> theta).  Omicron is left out
#: because it is indistinguishable from Latin o.
GREEK_CHARS: dict[str, str] = {chr(0x3B1 + i): name for i, name in enumerate(_GREEK_NAMES[:17])}
GREEK_CHARS.update({chr(0x3C3 + i): name for i, name in enumerate(_GREEK_NAMES[17:])})
del GREEK_CHARS["ο"]
GREEK_CHARS.update({"ς": "sigma", "ϑ": "theta", "ϕ": "phi", "ϵ": "epsilon", "ϱ": "rho",
                    "µ": "mu",  # MICRO SIGN, what many keyboards type for mu
                    "Γ": "Gamma", "Δ": "Delta", "Θ": "Theta", "Λ": "Lambda", "Ξ": "Xi",
                    "Π": "Pi", "Σ": "Sigma", "Φ": "Phi", "Ψ": "Psi", "Ω": "Omega",
                    # not Greek, but a letter of the same kind: statements write a length as ℓ
                    # (\ell), and nobody means ℓ and l as two different variables.
                    "ℓ": "l",
                    # likewise the script e of some fonts and equation editors for Euler's number
                    "ℯ": "e",
                    # and UnicodeMath's exponential e (Word's \ee), DOUBLE-STRUCK ITALIC SMALL E
                    "ⅇ": "e",
                    # and its differential d (Word's \dd: ⅆθ/ⅆt), DOUBLE-STRUCK ITALIC SMALL D
                    "ⅆ": "d"})

#: Operator look-alikes -> ASCII operator.

def _math_letters() -> dict[str, str]:
    """Styled letters of the Mathematical Alphanumeric Symbols block (𝑚, 𝒈, 𝜃, 𝛼) and ℎ: the plain letter.

    Word's equation editor and many PDFs write every variable in them, so a pasted ``𝑚𝑔 cos 𝜃`` is
    ``mg cos θ``. Only letters whose compatibility form is a Latin letter or a Greek letter we read
    are mapped (a styled capital Alpha, which looks like A, stays refused as the lookalike it is).
    """
    found = {}
    for code in [*range(0x1D400, 0x1D800), 0x210E]:
        ch = chr(code)
        if not unicodedata.category(ch).startswith("L"):
            continue
        plain = unicodedata.normalize("NFKC", ch)
        if len(plain) == 1 and plain.isascii() and plain.isalpha():
            found[ch] = plain
        elif plain in GREEK_CHARS:
            found[ch] = GREEK_CHARS[plain]
    return found


#: 𝑚 -> m, 𝜃 -> theta: styled mathematical letters, read as the letters they are.
MATH_LETTERS = _math_letters()

OPERATOR_CHARS = {"·": "*", "⋅": "*", "×": "*", "∗": "*", "•": "*", "∙": "*", "−": "-", "–": "-",
                  # every other dash a word processor or PDF makes of a typed minus
                  "—": "-", "‒": "-", "‐": "-", "‑": "-", "﹣": "-",
                  "÷": "/", "∕": "/", "⁄": "/",
                  # the middle dots of Japanese and Chinese input methods (m・g), and the hyphenation point
                  # some PDFs give for a middle dot: a product, as · is (between digits, as ambiguous as ·)
                  "・": "*", "･": "*", "‧": "*",
                  # and the long-vowel mark a Japanese input method types for the '-' key in kana mode (m g ー m a)
                  "ー": "-", "ｰ": "-",
                  # a phone's emoji keyboard (➕ ➖ ✖️ ➗), the multiplication X of symbol pickers (✕) and the cross
                  # product sign OCR gives for × (⨯): the operators they are drawn as
                  "➕": "+", "➖": "-", "✖": "*", "➗": "/", "✕": "*", "⨯": "*",
                  # the spacing modifier letters some fonts and a Mac keyboard (Shift-Option-I: ˆ) give for + - ^
                  "˖": "+", "˗": "-", "ˆ": "^"}
#: The middle dots that are a product, or a decimal point between digits (2·5): see `tokens`.
MIDDLE_DOTS = frozenset("·・･‧")
#: What an emoji keyboard puts after ✖ or ➕: its emoji or text style, nothing to a formula after an operator.
VARIATION_SELECTORS = frozenset("\ufe0e\ufe0f")
#: Every character read as a minus sign: the hyphen-minus, the dashes above and the full-width minus. A
#: number's sign and exponent (`grader.answers.numeric`) and a unit's exponent read the same ones.
MINUS_SIGNS = frozenset({"-", "－"} | {ch for ch, op in OPERATOR_CHARS.items() if op == "-"})

#: Full-width digits, operators and brackets (what a CJK input method types: ｍ－（ｎ＋ｍ）) -> ASCII, one
#: character for one, so positions stay. Full-width letters are not here: they stay refused, named
#: (see `bad_character`), as every other letter that merely looks like a Latin one.
FULLWIDTH_SYMBOLS = {ord(chr(c)): chr(c - 0xFEE0) for c in range(0xFF01, 0xFF5F) if not chr(c - 0xFEE0).isalpha()}
# The small and vertical forms of the same input methods (﹙ ﹚ ﹦ ︵), Unicode's own compatibility forms of ASCII
# punctuation, and the Greek question mark a Greek keyboard types for ';' (U+037E, which is ';' to Unicode).
FULLWIDTH_SYMBOLS.update({c: unicodedata.normalize("NFKC", chr(c)) for c in (0x37E, *range(0xFE10, 0xFE20),
                                                                              *range(0xFE30, 0xFE70))
                          if len(unicodedata.normalize("NFKC", chr(c))) == 1
                          and unicodedata.normalize("NFKC", chr(c)) in "()[]{}+-*/=,.;:!<>"})
# The ideographic full stop and comma that end a sentence and separate items in Chinese and Japanese text
# (。 as a full stop is, 、 as a comma), and TeX's \lgroup \rgroup drawn as characters (⟮ ⟯): round brackets.
FULLWIDTH_SYMBOLS.update({ord("。"): ".", ord("｡"): ".", ord("、"): ",", ord("､"): ",", ord("⟮"): "(", ord("⟯"): ")"})

#: Vulgar fractions (½x is x/2): the numerator and denominator, from Unicode's own numeric values.
VULGAR_FRACTIONS: dict[str, tuple[int, int]] = {
    ch: Fraction(unicodedata.numeric(ch)).limit_denominator(10).as_integer_ratio()
    for ch in "½⅓⅔¼¾⅕⅖⅗⅘⅙⅚⅐⅛⅜⅝⅞⅑⅒"
}

#: Superscript characters -> the ASCII they stand for (x² is x^2).
SUPERSCRIPT_CHARS = {"⁰": "0", "¹": "1", "²": "2", "³": "3", "⁴": "4", "⁵": "5", "⁶": "6",
                     "⁷": "7", "⁸": "8", "⁹": "9", "⁻": "-", "⁺": "+"}



def _superscript_others() -> dict[str, str]:
    """Superscript letters, brackets and = (``ᵃ``, ``ⁿ``, ``ᶿ``, ``⁽``): what each raises (``a``, ``n``, ``θ``, ``(``).

    Not read (``e⁻ᵃᵇ`` could be e^(-a·b) or a misrendered name), only refused with the text to type
    instead. The ordinal indicators ª and º are left out: they are not superscripts to a typist.
    """
    found = {}
    blocks = (range(0x2B0, 0x2C0), range(0x2E0, 0x2E5), range(0x1D2C, 0x1DC0), range(0x2070, 0x20A0), (0x2C7D, 0xA770))
    for code in (code for block in blocks for code in block):
        ch = chr(code)
        parts = unicodedata.decomposition(ch).split()
        if len(parts) == 2 and parts[0] == "<super>":
            target = chr(int(parts[1], 16))
            if ch not in SUPERSCRIPT_CHARS and (target.isalpha() or target in "()="):
                found[ch] = target
    return found


#: Superscript letters and brackets -> the character they raise (ᵃ -> a, ᶿ -> θ, ⁽ -> ().
SUPERSCRIPT_OTHERS: dict[str, str] = _superscript_others()

#: Subscript digits (m₁ is m_1).
SUBSCRIPT_DIGITS = {chr(0x2080 + i): str(i) for i in range(10)}


def _subscript_letters() -> dict[str, str]:
    """Subscript letters (``ₓ``, ``ₘₐₓ``, ``ᵢ``, ``ᵦ``) -> the letter's name text (``x``, ``beta``), from Unicode's
    own decompositions. ``ₒ`` is left out: after a name it is the zero a student meant (v₀) more often than
    the letter, so it stays refused, saying so."""
    found = {}
    for code in (*range(0x1D62, 0x1D6B), *range(0x2090, 0x209D), 0x2C7C):
        ch = chr(code)
        parts = unicodedata.decomposition(ch).split()
        if len(parts) == 2 and parts[0] == "<sub>" and ch != "ₒ":
            letter = chr(int(parts[1], 16))
            if letter.isascii() or letter in GREEK_CHARS:
                found[ch] = GREEK_CHARS.get(letter, letter)
    return found


#: Subscript letters (vₓ is v_x, θₘₐₓ is theta_max).
SUBSCRIPT_LETTERS = _subscript_letters()

#: Radical signs -> root index.
ROOT_CHARS = {"√": 2, "∛": 3, "∜": 4}

#: Accents after a letter: dot above = first, diaeresis = second time derivative (the combining
#: marks, and the spacing ones a keyboard without combining input types: θ˙, θ¨).
COMBINING_DOTS = {"\u0307": 1, "\u0308": 2, "\u02d9": 1, "\u00a8": 2}


def _dotted_letters() -> dict[str, tuple[str, int]]:
    """Every precomposed letter that is a Latin or Greek letter with dots above (ẋ, ÿ, ä, ϊ).

    Found from Unicode's own decompositions, so none is missed: the letter and its derivative order.
    """
    found = {}
    for code in [*range(0xC0, 0x250), *range(0x370, 0x400), *range(0x1E00, 0x1F00)]:
        ch = chr(code)
        base, *marks = unicodedata.normalize("NFD", ch)
        if not marks or not all(m in ("\u0307", "\u0308") for m in marks):
            continue
        letter = base if base.isascii() and base.isalpha() else GREEK_CHARS.get(base)
        if letter:
            found[ch] = (letter, sum(COMBINING_DOTS[m] for m in marks))
    return found


#: Precomposed dotted letters -> (letter, derivative order): ẋ is xdot, ÿ is yddot.
DOTTED_LETTERS = _dotted_letters()

#: Prime marks after a name: theta' and theta'' are time derivatives.
# ʹ ʺ (modifier letter primes) and ´ (the acute accent that European keyboards give for ') are
# primes too: after a variable they mean nothing else.
PRIME_CHARS = {"'": 1, "′": 1, "″": 2, "’": 1, "ʹ": 1, "ʺ": 2, "´": 1}

_INVISIBLE = {"\u200b", "\u200c", "\u200d", "\u2060", "\ufeff", "\u00ad", "\u200e", "\u200f"}

# Letters from other scripts that look like Latin ones, with the letter they imitate.
_LOOKALIKES = {
    "а": "a", "е": "e", "о": "o", "р": "p", "с": "c", "х": "x", "у": "y", "к": "k", "м": "m",
    "т": "t", "н": "h", "в": "b", "і": "i", "ј": "j", "ѕ": "s", "ԁ": "d", "ɡ": "g",
    "А": "A", "В": "B", "Е": "E", "К": "K", "М": "M", "Н": "H", "О": "O", "Р": "P", "С": "C",
    "Т": "T", "Х": "X", "І": "I",
    "ο": "o", "Α": "A", "Β": "B", "Ε": "E", "Ζ": "Z", "Η": "H", "Ι": "I", "Κ": "K", "Μ": "M",
    "Ν": "N", "Ο": "O", "Ρ": "P", "Τ": "T", "Υ": "Y", "Χ": "X",
}


_SPACING_ACCENTS = {"\u02d9", "\u00a8"}
_GENERIC_HINT = "use letters, digits, + - * / ^ and brackets (Greek letters and θ̇ are fine)"
_QUOTES_HINT = "delete the quotation marks: the answer is the formula alone"
# What to type instead of symbols people paste from their notes.
_SYMBOL_HINTS = {
    "∂": "write a time derivative as a dotted variable (θ̇, theta_dot or theta')",
    "∫": "give the result of the integral, not the integral",
    "∑": "write the sum out term by term",
    "≤": "give an expression, or an equation with =", "≥": "give an expression, or an equation with =",
    "≠": "give an expression, or an equation with =",
    "∞": "no answer here is infinite",
    "…": "an answer has no '…': give it in full (an exact expression, or all its terms), without the '…'",
    "⋯": "an answer has no '⋯': give it in full (an exact expression, or all its terms), without the '⋯'",
    "ᴇ": "ᴇ is a calculator's 'times ten to the': write it between a number and a whole power, as in 1.5ᴇ-3 or 1.5e-3",
    "°": "angles are in radians: degrees only follow a number, as in 30°",
    "±": "give one sign (the answer with + or the one with -)",
    "∓": "give one sign (the answer with + or the one with -)",
    # a phone's or word processor's quotation marks around a pasted answer (’ after a name is a prime)
    **dict.fromkeys("“”„‟«»‘‚‛", _QUOTES_HINT),
    # relations that are no equation, as their LaTeX commands are refused (\\equiv, \\propto, \\leqslant)
    **dict.fromkeys("≡≔≕≝≜≞≟", "it means 'identical to' or 'defined as', not an equation: write = between the two sides"),
    **dict.fromkeys("≃≅≊∼≈", "it means 'approximately equal' (or 'of the order of'), not an equation: write = between the two sides"),
    "∝": "it means 'proportional to', not an equation: write = and the factor, as in F = k x",
    **dict.fromkeys("≦≧⩽⩾≲≳≪≫⋜⋝", "inequalities are not supported: give an expression, or an equation with ="),
    "∶": "'∶' (a ratio) is not part of a formula: write a ratio with /, as in a/b",
    # brackets of other scripts and of typesetting (an input method's 【】 〔〕, angle brackets): not grouping here
    **dict.fromkeys("〔〕【】⟨⟩〈〉⦅⦆❨❩❪❫《》「」『』〘〙〚〛",
                    "group with round brackets ( ) (or [ ] or { }), as in m(g + a)"),
    **dict.fromkeys("✓✔✅☑", "delete the check mark: the answer is the formula alone"),
    "٫": "'٫' is the Arabic decimal separator: write a point, as in 0.3",
    "←": "'←' (an assignment) is no equation: write = (T = …), or give the expression alone",
    "∥": "'∥' (parallel, or a norm) is not part of a formula: write |x| for the absolute value of a number",
}


def is_space(ch: str) -> bool:
    """Blank characters, including no-break and thin spaces pasted from documents.

    Examples
    --------
    >>> is_space("\u00a0"), is_space("\u200b")
    (True, False)
    """
    return ch in " \t\r" or unicodedata.category(ch) == "Zs"


def misleading_character(text: str) -> ExpressionError | None:
    """The error for the first character of ``text`` that reads as something it is not (an invisible
    character, a Cyrillic or Greek look-alike of a Latin letter, a full-width letter, a quotation
    mark), or None. For texts read outside the tokenizer, such as a number's unit, whose own
    message would show the character as the letter it imitates.

    Examples
    --------
    >>> misleading_character("Н").message
    "'Н' (CYRILLIC CAPITAL LETTER EN) looks like the Latin letter 'H' but is a different character"
    >>> misleading_character("kg m/s^2") is None
    True
    """
    for position, ch in enumerate(text):
        if (ch in _LOOKALIKES or ch in _INVISIBLE or unicodedata.category(ch) == "Cf"
                or 0xFF01 <= ord(ch) <= 0xFF5E or _SYMBOL_HINTS.get(ch) == _QUOTES_HINT):
            return bad_character(ch, position)
    return None


def bad_character(ch: str, position: int) -> ExpressionError:
    """The error for a character the grammar refuses, naming it and saying what to type.

    Examples
    --------
    >>> bad_character("а", 3).message
    "'а' (CYRILLIC SMALL LETTER A) looks like the Latin letter 'a' but is a different character"
    """
    name = unicodedata.name(ch, f"U+{ord(ch):04X}")
    if ch in _LOOKALIKES:
        latin = _LOOKALIKES[ch]
        return ExpressionError(f"'{ch}' ({name}) looks like the Latin letter "
                               f"'{latin}' but is a different character", position, "bad_character",
                               f"retype it as '{latin}' on an English keyboard layout")
    if 0xFF01 <= ord(ch) <= 0xFF5E:
        ascii_ch = chr(ord(ch) - 0xFEE0)
        return ExpressionError(f"full-width character '{ch}' ({name})",
                               position, "bad_character", f"type the ordinary '{ascii_ch}' (half-width input)")
    if ch == "\u2064":  # Word's INVISIBLE PLUS inside a mixed number, 2⁤½: read as +, 2⁤½k would be 2 + k/2
        return ExpressionError(f"invisible character {name} (U+2064), which Word puts inside a mixed number "
                               "such as 2½", position, "bad_character", "write the number as 5/2 or (2 + 1/2)")
    if ch in _INVISIBLE or unicodedata.category(ch) == "Cf":
        return ExpressionError(f"invisible character {name} (U+{ord(ch):04X})",
                               position, "bad_character", "delete it (it often comes with copy and paste)")
    if ch in VARIATION_SELECTORS:  # after anything but an operator's emoji (✖️), where it is read
        return ExpressionError(f"invisible character {name} (U+{ord(ch):04X}), an emoji's style mark",
                               position, "bad_character", "delete it (it comes with an emoji keyboard's symbols)")
    if unicodedata.category(ch) == "Co":  # a symbol font's character (Word's Symbol font, a PDF's): its glyph is
        # that font's, so which letter it shows is not known here (in Symbol, U+F071 is θ; in Wingdings, no letter)
        return ExpressionError(f"private-use character U+{ord(ch):04X}, which only a special font (such as Word's "
                               "Symbol font, or a PDF's) draws as a symbol", position, "bad_character",
                               "retype that symbol: a Greek letter as θ or theta, an operator as + - * /")
    if unicodedata.category(ch) == "Nd" and not unicodedata.normalize("NFKC", ch).isascii():  # ٢, ۲, २: a digit of another script (an Arabic or Hindi keyboard)
        return ExpressionError(f"'{ch}' ({name}) is the digit {unicodedata.digit(ch)} of another script",
                               position, "bad_character", f"type the ordinary digit '{unicodedata.digit(ch)}' "
                               "(digits 0-9, with a point for decimals)")
    if unicodedata.category(ch) == "Cs":  # half of a UTF-16 pair, alone: a broken copy or encoding
        return ExpressionError(f"broken character U+{ord(ch):04X} (a lone surrogate, not text)",
                               position, "bad_character", "delete it and retype what was there")
    if unicodedata.category(ch).startswith("C"):
        return ExpressionError(f"control character U+{ord(ch):04X}",
                               position, "bad_character", "delete it")
    if unicodedata.combining(ch):
        return ExpressionError(f"accent {name} does not follow a variable name",
                               position, "bad_character", "a dot accent marks a time derivative, as in θ̇")
    if ch in _SPACING_ACCENTS:
        return ExpressionError(f"accent {name} does not follow a variable name", position, "bad_character",
                               "put the dot right after the variable, as in θ˙ or theta_dot")
    if ch == "ₒ":  # v ₒ: the subscript letter o where the subscript zero was meant
        return ExpressionError(f"'{ch}' ({name}) is the letter o, not the digit zero", position, "bad_character",
                               "for a subscript zero type v₀ or v_0; for the letter, v_o")
    plain = unicodedata.normalize("NFKC", ch)
    if len(plain) == 1 and plain.isascii() and plain.isalnum():  # a styled digit such as 𝟐
        return ExpressionError(f"character '{ch}' ({name}) is not allowed", position, "bad_character",
                               f"type the ordinary '{plain}'")
    shown = ch if ch.isprintable() else f"U+{ord(ch):04X}"
    return ExpressionError(f"character '{shown}' ({name}) is not allowed",
                           position, "bad_character", _SYMBOL_HINTS.get(ch, _GENERIC_HINT))
