"""The parser's public entry points on generated text: they parse or raise ExpressionError, nothing else.

Texts are token soups of the grammar (names, numbers from tiny to huge, operators, functions with
the wrong number of arguments, unicode notation, LaTeX), arbitrary unicode including lone
surrogates and control characters, and deep nesting. Whatever comes in, the answer is a parse or
an `ExpressionError` with a documented code and a position inside the text, within a bounded time.
"""

import time

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from grader.expressions import ExpressionError, Namespace, parse_equation, parse_expression, parse_system
from grader.expressions.errors import ERROR_CODES

NAMESPACE = Namespace.from_spec({
    "m": {"dimension": "mass", "domain": "positive"},
    "g": {"dimension": "acceleration", "domain": "positive"},
    "l": {"dimension": "length", "domain": "positive"},
    "x": {"dimension": "dimensionless", "domain": "real"},
    "theta": {"dimension": "angle", "domain": "real"},
    "thetadot": {"dimension": "angular_velocity", "domain": "real"},
})
TOKENS = [
    "m", "g", "l", "x", "theta", "thetadot", "θ", "θ̇", "mg", "gl", "thta", "t", "e", "E", "pi", "π", "i", "I",
    "0", "1", "2", "0.5", ".5", "1e3", "1e999", "1e-999", "9" * 400, "0." + "0" * 300 + "1", "1_000", "½", "²", "³",
    "+", "-", "−", "*", "·", "×", "/", "÷", "^", "**", "^-", "(", ")", "[", "]", "{", "}", ",", "=", ";", "!", "'",
    "sin", "cos", "tan", "atan2", "atan2(x)", "atan2(x, 1, 2)", "sqrt", "√", "log", "ln", "exp", "Abs", "|", "sin^2",
    "sin^-1", "\\frac{", "\\sin", "\\cdot", "\\sqrt{", "\\left(", "\\right)", "\\theta", "__import__", "lambda",
    "\t", "\n", " ", "\u200b", "\x00", "\ud800", "\udfff", "\U0001F600", "e^(", "10^10^10", "x^x^x^x",
]
soup = st.lists(st.sampled_from(TOKENS), max_size=40).map("".join)
# Surrogates (category Cs) are what a JSON decoder hands over for "\ud800"; they must be refused cleanly.
unicode_text = st.text(st.characters(codec=None, categories=["L", "M", "N", "P", "S", "Z", "C", "Cs"]), max_size=60)
nested = st.builds(lambda n, core, close: "(" * n + core + (")" * n if close else ""),
                   st.integers(0, 600), st.sampled_from(["x", "-x", "sin x", "", "x^"]), st.booleans())
towers = st.builds(lambda n, op: op.join(["x"] * n), st.integers(1, 400), st.sampled_from(["^", "-", "*sin(", "/"]))
TEXTS = st.one_of(soup, unicode_text, nested, towers)
PARSERS = [parse_expression, parse_equation, parse_system]


@pytest.mark.parametrize("parse", PARSERS, ids=lambda f: f.__name__)
@settings(max_examples=250, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(text=TEXTS)
def test_any_text_parses_or_raises_an_expression_error_in_bounded_time(parse, text):
    started = time.monotonic()
    try:
        parse(text, NAMESPACE)
    except ExpressionError as error:
        assert error.code in ERROR_CODES
        assert error.position is None or 0 <= error.position <= len(text)
        assert str(error)
    assert time.monotonic() - started < 2.0
