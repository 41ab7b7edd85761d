"""Non-ASCII input: accepted symbols and refused look-alikes."""

import pytest

from grader.expressions.unicode_input import GREEK_CHARS, bad_character, is_space


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
