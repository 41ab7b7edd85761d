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


# -- red team 22: operators as phones, input methods and symbol pickers type them --

@pytest.mark.parametrize("typed, plain", [
    ("m・n", "m*n"), ("m･n", "m*n"), ("m‧n", "m*n"),  # Japanese and Chinese input methods' middle dots
    ("m ー n", "m - n"), ("ーm", "-m"), ("m ｰ n", "m - n"),  # the long-vowel mark of a kana-mode '-' key
    ("m ✕ n", "m*n"), ("m ✖ n", "m*n"), ("m ✖\ufe0f n", "m*n"), ("m ✖\ufe0e n", "m*n"), ("m ⨯ n", "m*n"),
    ("m ➕ n", "m + n"), ("m ➕\ufe0f n", "m + n"), ("m ➖ n", "m - n"), ("➖m", "-m"), ("m ➗ n", "m/n"),
    ("m ˖ n", "m + n"), ("m ˗ n", "m - n"), ("˗m", "-m"), ("mˆ2", "m^2"), ("(m + n)ˆ(-1)", "(m + n)^(-1)"),
    ("m ﹢ n", "m + n"), ("m﹡n", "m*n"), ("﹙m + n﹚n", "(m + n)n"), ("m ﹦ n", "m = n"),
    ("⟮m + n⟯n", "(m + n)n"), ("m︵n + 1︶", "m(n + 1)"),
])
def test_operators_drawn_by_other_characters_read_as_the_operator(typed, plain):
    ns = Namespace([Variable(n, "dimensionless", "real") for n in "mn"])
    if "=" in plain:
        from grader.expressions import parse_equation
        assert parse_equation(typed, ns).lhs - parse_equation(typed, ns).rhs \
            == parse_equation(plain, ns).lhs - parse_equation(plain, ns).rhs
    else:
        assert parse_expression(typed, ns).expr == parse_expression(plain, ns).expr


@pytest.mark.parametrize("typed", ["m n。", "m n｡", "m n、", "m n\u037e"])  # U+037E: GREEK QUESTION MARK, ';' to Unicode
def test_a_sentence_end_of_chinese_japanese_or_greek_text_ends_the_answer(typed):
    ns = Namespace([Variable(n, "dimensionless", "real") for n in "mn"])
    assert parse_expression(typed, ns).expr == ns.symbol("m") * ns.symbol("n")


@pytest.mark.parametrize("typed", ["2・5", "2･5", "2‧5"])
def test_a_middle_dot_of_an_input_method_between_digits_is_as_ambiguous_as_the_latin_one(typed):
    from grader.expressions import ExpressionError
    with pytest.raises(ExpressionError) as caught:
        parse_expression(typed, Namespace([]))
    assert caught.value.code == "ambiguous" and "2.5" in caught.value.message and "2×5" in caught.value.message


@pytest.mark.parametrize("char, words", [
    ("≡", ["IDENTICAL TO", "not an equation", "write ="]), ("≔", ["COLON EQUALS", "defined as"]),
    ("≝", ["defined as"]), ("≅", ["approximately"]), ("∼", ["approximately"]), ("≈", ["approximately", "write ="]),
    ("∝", ["proportional", "write ="]), ("⩽", ["inequalities"]), ("≦", ["inequalities"]), ("≪", ["inequalities"]),
    ("∶", ["RATIO", "with /"]),
    ("\uf071", ["private-use character U+F071", "Symbol font", "retype"]),  # θ in Word's Symbol font
    ("٢", ["ARABIC-INDIC DIGIT TWO", "digit 2", "'2'"]), ("۳", ["digit 3", "'3'"]), ("५", ["digit 5", "'5'"]),
    ("\ufe0f", ["VARIATION SELECTOR-16", "emoji", "delete"]),
])
def test_relations_symbol_fonts_and_other_scripts_digits_are_named_with_the_fix(char, words):
    error = bad_character(char, 3)
    assert error.code == "bad_character" and error.position == 3
    for word in words:
        assert word in error.message + "; " + error.hint


def test_a_variation_selector_after_a_letter_is_not_dropped():
    # m️1 must not read as m·1 where m1 looks typed: the invisible mark is named
    from grader.expressions import ExpressionError
    with pytest.raises(ExpressionError) as caught:
        parse_expression("m\ufe0f1", Namespace([Variable("m1", "dimensionless")]))
    assert "VARIATION SELECTOR-16" in caught.value.message


@pytest.mark.parametrize("char, words", [("【", ["round brackets"]), ("〔", ["round brackets"]), ("⟨", ["round brackets"]),
                                         ("✓", ["check mark"]), ("✅", ["check mark"])])
def test_brackets_of_other_scripts_and_check_marks_are_named_with_the_fix(char, words):
    error = bad_character(char, 0)
    for word in words:
        assert word in error.hint
