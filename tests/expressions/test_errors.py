"""Errors carry what a student and a program need."""

import pytest

from grader.expressions import DimensionError, ExpressionError


def test_expression_error_fields_and_text():
    err = ExpressionError("unknown name 'thta'", 4, "unknown_name", "did you mean 'theta'?")
    assert (err.message, err.position, err.code, err.hint) == ("unknown name 'thta'", 4, "unknown_name",
                                                               "did you mean 'theta'?")
    # The text counts characters from 1, as the caret shows them; `position` is the 0-based index.
    assert str(err) == "unknown name 'thta' at character 5; did you mean 'theta'?"
    assert err.to_json() == {"message": "unknown name 'thta'", "position": 4, "code": "unknown_name",
                             "hint": "did you mean 'theta'?"}
    assert isinstance(err, ValueError)


def test_show_puts_a_caret_under_the_position():
    err = ExpressionError("unexpected ')'", 3, "syntax")
    assert err.show("x +)").splitlines()[:2] == ["x +)", "   ^"]


def test_unknown_codes_are_a_programming_error():
    with pytest.raises(ValueError):
        ExpressionError("x", 0, "whatever")


def test_dimension_error_keeps_the_expression():
    err = DimensionError("adds a force (kg·m/s²) to a length (m)", expr="m*g + l")
    assert str(err) == "adds a force (kg·m/s²) to a length (m)" and err.expr == "m*g + l"
    assert isinstance(err, ValueError)
