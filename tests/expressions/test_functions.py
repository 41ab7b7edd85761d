"""The function registry is the one place the grammar's functions are defined, and it is complete."""

import math

import flint
import pytest
import sympy

from grader.expressions import Namespace, Variable, dimension_of, parse_dimension, parse_expression
from grader.expressions.functions import (BY_SYMPY, CONSTANTS, FUNCTIONS, INVERSES, REGISTRY, Undefined,
                                          function_names, latex_commands)
from grader.expressions.printing import to_latex, to_text

PROMISED = ("sin cos tan cot sec csc cosec asin acos atan atan2 arcsin arccos arctan arctan2 sinh cosh tanh "
            "asinh acosh atanh sech csch coth exp log ln log10 sqrt abs Abs sign sgn").split()
EVALUATED = [f for f in REGISTRY.values() if f.sympy_func is not None]


def test_every_promised_function_is_allowed():
    assert set(PROMISED) <= set(FUNCTIONS)


def test_nothing_dangerous_is_allowed():
    for name in ["factorial", "gamma", "Integral", "eval", "exec", "__import__", "Function", "Symbol", "lambda"]:
        assert name not in FUNCTIONS


def test_arities():
    assert (FUNCTIONS["atan2"].min_args, FUNCTIONS["atan2"].max_args) == (2, 2)
    assert FUNCTIONS["log"].max_args == 2 and FUNCTIONS["sin"].max_args == 1


@pytest.mark.parametrize("alias, name", [("ln", "log"), ("Abs", "abs"), ("arcsin", "asin"), ("arctan2", "atan2"),
                                         ("cosec", "csc"), ("sgn", "sign"), ("arsinh", "asinh"), ("tg", "tan"),
                                         ("ctg", "cot"), ("arctg", "atan"), ("lg", "log10"),
                                         ("cosech", "csch")])  # the hyperbolic cosecant as UK texts spell it
def test_aliases_are_the_same_function(alias, name):
    assert FUNCTIONS[alias] is REGISTRY[name]


def test_inverse_table_and_constants():
    assert INVERSES["sin"] == "asin" and INVERSES["cosh"] == "acosh" and set(INVERSES.values()) <= set(REGISTRY)
    assert CONSTANTS["pi"] is sympy.pi and CONSTANTS["E"] is sympy.E


def test_hint_list_is_readable():
    names = function_names()
    assert "sin" in names and "ln" in names and "asinh" in names and "Abs" not in names


def test_latex_commands_come_from_the_registry():
    assert latex_commands()["arcsin"] == "asin" and latex_commands()["coth"] == "coth"


@pytest.mark.parametrize("spec", EVALUATED, ids=lambda f: f.name)
def test_every_function_evaluates_prints_and_reads_back(spec):
    """One registry entry is enough for the evaluator, both printers and the parser to know a function."""
    symbols = sympy.symbols("x y", real=True)[:spec.min_args]
    expr = spec.sympy_func(*symbols)
    ns = Namespace([Variable("x", "dimensionless", "real"), Variable("y", "dimensionless", "real")])
    assert parse_expression(to_text(expr), ns).expr == expr
    assert to_latex(expr).startswith(spec.latex or r"\left|")
    args = [1.6, 0.5] if spec.name == "acosh" else [0.6, 0.5]  # inside every domain
    with flint.ctx.workprec(80):
        ball = spec.arb(*[flint.arb(a) for a in args[:spec.min_args]])
    value = spec.real(math, *args[:spec.min_args])
    assert abs(float(ball.mid()) - value) < 1e-12 and float(ball.rad()) < 1e-20


@pytest.mark.parametrize("name, point, reason", [
    ("acosh", 0.5, "below 1"), ("atanh", 1.0, "outside (-1, 1)"), ("asin", 2.0, "outside [-1, 1]"),
    ("csch", 0.0, "csch at 0"), ("coth", 0.0, "coth at 0"), ("log", -1.0, "not positive"),
])
def test_points_outside_a_domain_are_undefined_in_both_arithmetics(name, point, reason):
    spec = REGISTRY[name]
    for evaluate in (lambda: spec.arb(flint.arb(point)), lambda: spec.real(math, point)):
        with pytest.raises(Undefined, match=reason.replace("(", r"\(").replace(")", r"\)").replace("[", r"\[")):
            evaluate()


@pytest.mark.parametrize("text, dimension", [
    ("abs(x)", "length"), ("sign(x)", "dimensionless"), ("atan2(x, l)", "dimensionless"),
    ("asinh(x/l) + sech(x/l)", "dimensionless"),
])
def test_dimension_rules_come_from_the_registry(text, dimension):
    ns = Namespace([Variable("x", "length", "real"), Variable("l", "length", "positive")])
    assert dimension_of(parse_expression(text, ns).expr, ns.dimensions()) == parse_dimension(dimension)


def test_every_sympy_class_maps_back_to_its_entry():
    assert all(BY_SYMPY[f.sympy_func] is f for f in EVALUATED)
