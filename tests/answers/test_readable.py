"""Can the grader read an answer at all? The checker's own reading, asked before anything is stored."""

import pytest

from grader.answers.readable import read_error

VARIABLES = {"m": {"dimension": "mass", "domain": "positive"}, "g": {"dimension": "acceleration", "domain": "positive"}}


@pytest.mark.parametrize("kind, text", [
    ("expression", "m*g/3"), ("expression", "m g / 3"), ("expression", r"\frac{m g}{3}"),
    ("equation", "m*g = 3*m*g/3"), ("equation", "m*g - m*g"),  # an expression alone reads as "... = 0"
    ("numeric", "14.7 N"), ("numeric", "1.47e1 kg*m/s^2"),
])
def test_what_the_checker_reads_is_readable(kind, text):
    assert read_error({"kind": kind, "variables": VARIABLES}, text) is None


@pytest.mark.parametrize("kind, text, code, column", [
    ("expression", "m*g/", "syntax", 4),
    ("expression", "m*g/(3", "unbalanced", 5),
    ("expression", "m*q", "unknown_name", 3),
    ("equation", "m*g = ", "syntax", None),
    ("numeric", "14,7 N", "number", None),
])
def test_what_it_cannot_read_says_where_counting_from_one(kind, text, code, column):
    error = read_error({"kind": kind, "variables": VARIABLES}, text)
    assert error["code"] == code and error["message"]
    if column is not None:
        assert (error["column"], error["position"]) == (column, column - 1)


def test_a_broken_reference_is_left_to_the_checker_to_report():
    assert read_error({"kind": "expression", "variables": {"m": {"dimension": "no such thing"}}}, "m") is None
