"""The function whitelist is exactly what the grammar promises."""

import sympy

from grader.expressions.functions import CONSTANTS, FUNCTIONS, INVERSES, function_names

PROMISED = "sin cos tan cot sec csc asin acos atan atan2 sinh cosh tanh exp log ln sqrt abs Abs".split()


def test_every_promised_function_is_allowed():
    assert set(PROMISED) <= set(FUNCTIONS)


def test_nothing_dangerous_is_allowed():
    for name in ["factorial", "gamma", "Integral", "eval", "exec", "__import__", "Function", "Symbol", "lambda"]:
        assert name not in FUNCTIONS


def test_arities():
    assert (FUNCTIONS["atan2"].min_args, FUNCTIONS["atan2"].max_args) == (2, 2)
    assert FUNCTIONS["log"].max_args == 2 and FUNCTIONS["sin"].max_args == 1


def test_aliases_build_the_same_function():
    x = sympy.Symbol("x")
    assert FUNCTIONS["ln"].build(x) == FUNCTIONS["log"].build(x) == sympy.log(x)
    assert FUNCTIONS["Abs"].build(x) == sympy.Abs(x)


def test_inverse_table_and_constants():
    assert INVERSES == {"sin": "asin", "cos": "acos", "tan": "atan", "sinh": "asinh", "cosh": "acosh", "tanh": "atanh"}
    assert CONSTANTS["pi"] is sympy.pi and CONSTANTS["E"] is sympy.E


def test_hint_list_is_readable():
    names = function_names()
    assert "sin" in names and "ln" in names and "Abs" not in names
