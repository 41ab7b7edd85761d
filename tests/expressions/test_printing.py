"""The fast printers: text reads back to the same expression, LaTeX reads as a person writes it."""

from __future__ import annotations

import random

import pytest
import sympy

from grader.expressions import Namespace, Variable, parse_expression
from grader.expressions.printing import _minus, _printing_order, to_latex, to_text

NS = Namespace([
    Variable("m", "mass", "positive"), Variable("m1", "mass", "positive"), Variable("m2", "mass", "positive"),
    Variable("g", "acceleration", "positive"), Variable("l", "length", "positive"),
    Variable("theta", "angle", "real"), Variable("thetadot", "angular_velocity", "real"),
    Variable("alpha", "angle", [0, 1.5708]), Variable("beta", "dimensionless", [0, 1]),
])


@pytest.mark.parametrize("text", [
    "m*g*(3*cos(theta) - 2)",
    "-beta*g*m*sin(alpha)/(beta + 1)",
    "m1*m2*g/(m1 + m2)",
    "m*l*thetadot^2 + m*g*cos(theta)",
    "sqrt(g/l)",
    "1/sqrt(g*l)",
    "-g*sin(theta)/l",
    "(1 - cos(theta))^(3/2)",
    "abs(sin(theta)) + exp(-theta^2/2) + log(m1/m2)",
    "atan2(m1, m2) - asin(beta)/3",
    "2^(m1/m2) + pi*E",
    "-(m1 - m2)^2/(2*m)",
    "1.5e-3*m",
])
def test_text_reads_back_to_the_same_expression(text):
    expr = parse_expression(text, NS).expr
    assert parse_expression(to_text(expr), NS).expr == expr


@pytest.mark.parametrize("text, latex", [
    ("m*g*(3*cos(theta) - 2)", r"g m \left(3 \cos{\left(\theta \right)} - 2\right)"),
    ("m1*m2*g/(m1 + m2)", r"\frac{g m_{1} m_{2}}{m_{1} + m_{2}}"),
    ("sqrt(g/l)", r"\frac{\sqrt{g}}{\sqrt{l}}"),  # sympy splits the root of positive symbols
    ("sin(theta)^2", r"\sin^{2}{\left(\theta \right)}"),
    ("-g*sin(theta)/l", r"- \frac{g \sin{\left(\theta \right)}}{l}"),
    ("2*m/3", r"\frac{2 m}{3}"),
])
def test_latex_reads_as_written(text, latex):
    expr = parse_expression(text, NS).expr
    assert to_latex(expr, NS.latex_names()) == latex


def test_unknown_node_falls_back_to_sympy():
    x = sympy.Symbol("x")
    integral = sympy.Integral(x, x)
    assert to_text(integral) == sympy.sstr(integral)


def _products(seed: int, count: int):
    rng = random.Random(seed)
    syms = [NS.symbol(n) for n in ("m", "m1", "m2", "g", "l", "theta", "thetadot", "alpha", "beta")]
    for _ in range(count):
        factors = [s ** rng.choice([1, 1, 2, 3, sympy.Rational(1, 2), sympy.Rational(3, 2)])
                   for s in rng.sample(syms, rng.randint(2, 5))]
        factors.append(rng.choice([1, 2, 3, sympy.Rational(1, 3), sympy.Rational(2, 3)]))
        if rng.random() < 0.3:
            factors.append(sympy.cos(rng.choice(syms)))
        yield sympy.Mul(*factors)


@pytest.mark.parametrize("seed", range(5))
def test_products_print_their_factors_in_sympys_order(seed):
    # The text orders factors as sympy's str does (quickly for symbols and their powers).
    for expr in _products(seed, 200):
        assert to_text(expr) == str(expr)


@pytest.mark.parametrize("factors", [
    (-3, "x"), (sympy.Rational(-1, 2), "x", "y"), (2, "x"), ("x", "y"), (-1, sympy.zoo), (-3, sympy.zoo, "x"),
    (sympy.Float(-1.5), "x"), (sympy.nan, "x"), (-1, sympy.oo, "x"),
])
def test_a_products_sign_is_read_as_sympy_reads_it(factors):
    expr = sympy.Mul(*(sympy.Symbol(f) if isinstance(f, str) else f for f in factors), evaluate=False)
    assert _minus(expr) == expr.could_extract_minus_sign()


@pytest.mark.parametrize("text, printed", [
    ("-2 l", "-2*l"),
    ("-l cos(theta)", "-l*cos(theta)"),
    ("-m1 m2 g/(m1 + m2)", "-g*m1*m2/(m1 + m2)"),
    ("-(m1 - m2) g", "-g*(m1 - m2)"),
])
def test_a_negated_product_prints_without_brackets(text, printed):
    # "-(2*l)" for a typed "-2 l" reads oddly back to the student; the minus binds the whole product anyway.
    expr = parse_expression(text, NS).expr
    assert to_text(expr) == printed
    assert parse_expression(printed, NS).expr == expr


@pytest.mark.parametrize("text", [
    "m l thetadot = -m g sin(theta)",
    "(m1 + m2) l θ̇ + m2 l cos(theta) = -m g sin θ; m1 = m2 g",
    "-2 l = m1 sqrt(g/l)",
])
def test_equations_print_with_the_fast_printers_and_read_back(text):
    from grader.expressions import parse_system

    for equation in parse_system(text, NS):
        again = parse_system(equation.text, NS)[0]
        assert (again.lhs, again.rhs) == (equation.lhs, equation.rhs)
        assert equation.latex.count("=") == 1 and "*" not in equation.latex


def _mixed_products(seed: int, count: int):
    # Factors of one class and of several: sums, functions of one name and of several, powers of them,
    # exp and E**x, numbers; the printer compares their class keys first and sort keys only on a tie.
    rng = random.Random(seed)
    syms = [NS.symbol(n) for n in ("m", "m1", "m2", "g", "l", "theta", "alpha")]
    makers = [
        lambda: rng.choice(syms),
        lambda: rng.choice(syms) + rng.choice([1, 2, -3]) * rng.choice(syms),
        lambda: sympy.cos(rng.choice(syms)), lambda: sympy.sin(rng.choice(syms) - rng.choice(syms)),
        lambda: sympy.tan(rng.choice(syms)), lambda: sympy.atan2(rng.choice(syms), rng.choice(syms)),
        lambda: sympy.exp(rng.choice(syms)), lambda: sympy.log(rng.choice(syms)), lambda: sympy.Abs(rng.choice(syms)),
        lambda: sympy.sqrt(rng.choice(syms) + 1),
    ]
    for _ in range(count):
        factors = [rng.choice(makers)() ** rng.choice([1, 1, 2, 3, sympy.Rational(1, 2)]) for _ in range(rng.randint(2, 5))]
        factors.append(rng.choice([1, 2, sympy.Rational(1, 3)]))
        yield sympy.Mul(*factors)


@pytest.mark.parametrize("seed", range(5))
def test_products_of_sums_and_functions_order_their_factors_as_sympy_does(seed):
    for expr in _mixed_products(seed, 200):
        factors = list(sympy.Mul.make_args(expr))
        assert _printing_order(factors) == sorted(factors, key=sympy.default_sort_key), expr
