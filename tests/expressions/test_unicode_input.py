"""Non-ASCII input: accepted symbols and refused look-alikes."""

import pytest
import sympy

from grader.expressions import Namespace, Variable, parse_expression
from grader.expressions.unicode_input import (GREEK_CHARS, SUPERSCRIPT_CHARS, SUPERSCRIPT_OTHERS, bad_character,
                                              is_space)


@pytest.mark.parametrize("char, name", [("θ", "theta"), ("λ", "lambda"), ("ω", "omega"), ("Ω", "Omega"),
                                        ("ϕ", "phi"), ("µ", "mu"), ("π", "pi")])
def test_greek_letters_spell_out(char, name):
    assert GREEK_CHARS[char] == name


@pytest.mark.parametrize("char", ["ο", "Α", "Ο", "Ρ", "Υ"])
def test_greek_letters_that_look_latin_are_not_names(char):
    assert char not in GREEK_CHARS


@pytest.mark.parametrize("char, words", [
    ("а", ["CYRILLIC SMALL LETTER A", "Latin letter 'a'"]),
    ("ο", ["GREEK SMALL LETTER OMICRON", "'o'"]),
    ("ｍ", ["full-width", "FULLWIDTH LATIN SMALL LETTER M"]),
    ("\u200b", ["invisible", "ZERO WIDTH SPACE"]),
    ("\ufeff", ["invisible"]),
    ("\x00", ["control character U+0000"]),
    ("\ud800", ["lone surrogate", "U+D800"]),
    ("😀", ["GRINNING FACE"]),
])
def test_refused_characters_are_named(char, words):
    error = bad_character(char, 7)
    assert error.code == "bad_character" and error.position == 7
    for word in words:
        assert word in error.message + (error.hint or "")


@pytest.mark.parametrize("char, blank", [(" ", True), ("\u00a0", True), ("\u2009", True), ("\u200b", False),
                                         ("x", False)])
def test_pasted_spaces_are_blank_but_zero_width_is_not(char, blank):
    assert is_space(char) is blank


# -- red team 2026-11: what Word, PDFs and word processors make of typed letters and minus signs --

@pytest.mark.parametrize("char, name", [
    ("𝑚", "m"), ("𝑔", "g"), ("𝑀", "M"), ("ℎ", "h"), ("𝐱", "x"), ("𝒍", "l"), ("𝓁", "l"), ("𝗆", "m"), ("𝚖", "m"),
    ("𝜃", "theta"), ("𝛼", "alpha"), ("𝜔", "omega"), ("𝜗", "theta"), ("𝜑", "phi"), ("𝝁", "mu"), ("𝛩", "Theta"),
])
def test_styled_mathematical_letters_are_the_letters(char, name):
    from grader.expressions.unicode_input import MATH_LETTERS
    assert MATH_LETTERS[char] == name


@pytest.mark.parametrize("char", ["𝛢", "𝛰", "𝜊", "𝟐"])  # styled Alpha, Omicron, omicron look Latin; a digit is no letter
def test_styled_lookalikes_and_digits_are_not_letters(char):
    from grader.expressions.unicode_input import MATH_LETTERS
    assert char not in MATH_LETTERS


@pytest.mark.parametrize("char", ["—", "‒", "‐", "‑", "﹣", "–", "−"])
def test_every_dash_is_a_minus(char):
    from grader.expressions.unicode_input import OPERATOR_CHARS
    assert OPERATOR_CHARS[char] == "-"


@pytest.mark.parametrize("char, plain", [("𝟐", "2"), ("𝟎", "0"), ("𝟗", "9")])
def test_a_styled_digit_is_refused_naming_the_plain_one(char, plain):
    error = bad_character(char, 0)
    assert char in error.message and f"'{plain}'" in error.hint


@pytest.mark.parametrize("ch, plain", [("ᵃ", "a"), ("ⁿ", "n"), ("ˣ", "x"), ("ᶿ", "θ"), ("ᴬ", "A"),
                                       ("⁽", "(")])
def test_superscript_letters_know_the_letter_they_raise(ch, plain):
    assert SUPERSCRIPT_OTHERS[ch] == plain


def test_superscript_digits_and_ordinal_indicators_are_not_superscript_letters():
    assert not set(SUPERSCRIPT_OTHERS) & (set(SUPERSCRIPT_CHARS) | {"ª", "º"})


@pytest.mark.parametrize("typed, plain", [
    # What a CJK input method types for digits, operators and brackets reads as their ASCII (PrairieLearn
    # accepts them too); full-width letters stay refused, named, like every other look-alike letter.
    ("m - （n + m）", "m - (n + m)"),
    ("m ＋ n", "m + n"),
    ("m － n", "m - n"),
    ("２m／n", "2m/n"),
    ("m＊n＾２", "m*n^2"),
    ("［m + n］＊３", "[m + n]*3"),
    ("１.５m", "1.5m"),
])
def test_full_width_digits_operators_and_brackets_read_as_ascii(typed, plain):
    from grader.expressions import Namespace, Variable, parse_expression

    ns = Namespace([Variable(n, "dimensionless", "real") for n in "mn"])
    assert parse_expression(typed, ns).expr == parse_expression(plain, ns).expr


@pytest.mark.parametrize("text", ["ⅇ^x", "ℯ^x", "e^x"])
def test_every_exponential_e_of_editors_is_eulers_number(text):
    # UnicodeMath's ⅇ (Word's \ee) was refused while ℯ was read
    ns = Namespace([Variable("x", "dimensionless")])
    assert parse_expression(text, ns).expr == sympy.exp(ns.symbol("x"))
