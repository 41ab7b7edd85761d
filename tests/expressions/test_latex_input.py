"""The LaTeX subset."""

import pytest

from grader.expressions import ExpressionError
from grader.expressions.latex_input import classify_command, subscript_text


@pytest.mark.parametrize("command, expected", [
    ("theta", ("greek", "theta")), ("varphi", ("greek", "phi")), ("Omega", ("greek", "Omega")),
    ("pi", ("greek", "pi")), ("sin", ("function", "sin")), ("arctan", ("function", "atan")),
    ("cdot", ("op", "*")), ("times", ("op", "*")), ("div", ("op", "/")), ("quad", ("space", "")),
    ("dfrac", ("structure", "frac")), ("sqrt", ("structure", "sqrt")), ("ddot", ("structure", "ddot")),
    ("mathrm", ("wrapper", "mathrm")),
])
def test_commands(command, expected):
    assert classify_command(command, 0) == expected


@pytest.mark.parametrize("command", ["int", "sum", "partial", "infty", "input", "def"])
def test_other_commands_are_refused_by_name(command):
    with pytest.raises(ExpressionError) as err:
        classify_command(command, 3)
    assert err.value.code == "unsupported_function" and f"\\{command}" in err.value.message


@pytest.mark.parametrize("content, name", [("1", "1"), ("roll,s", "roll_s"), ("\\mathrm{roll}, s", "roll_s"),
                                          ("\\text{surface}", "surface"), ("\\theta", "theta")])
def test_subscripts(content, name):
    assert subscript_text(content, 0) == name


@pytest.mark.parametrize("content", ["", "a+b", "\\frac{1}{2}"])
def test_subscripts_must_be_names(content):
    with pytest.raises(ExpressionError):
        subscript_text(content, 0)


# -- red team 2026-11 ---------------------------------------------------------------------------

@pytest.mark.parametrize("command, expected", [
    ("big", ("space", "")), ("Big", ("space", "")), ("bigg", ("space", "")), ("Bigg", ("space", "")),
    ("bigm", ("space", "")), ("Biggm", ("space", "")), ("bigl", ("structure", "bigl")),
    ("Bigr", ("structure", "bigr")), ("biggl", ("structure", "bigl")), ("Biggr", ("structure", "bigr")),
    ("mid", ("structure", "vert")), ("scriptstyle", ("space", "")),
])
def test_bracket_sizes_and_bars(command, expected):
    assert classify_command(command, 0) == expected
