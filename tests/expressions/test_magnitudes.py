"""Exact arithmetic that cannot be made to explode."""

import pytest
import sympy

from grader.expressions import ExpressionError
from grader.expressions.magnitudes import MAX_DIGITS, checked, digits, guarded_pow

x = sympy.Symbol("x")


@pytest.mark.parametrize("base, exponent", [
    (sympy.Integer(9), sympy.Integer(387420489)),     # 9^9^9 would have 370 million digits
    (sympy.Integer(10), sympy.Integer(1001)),
    (sympy.Integer(10) ** 500, sympy.Integer(3)),
    (x, sympy.Integer(10 ** 6)),
    (sympy.Integer(2), sympy.Rational(1, 10 ** 7)),
])
def test_huge_powers_are_refused_before_evaluation(base, exponent):
    with pytest.raises(ExpressionError) as err:
        guarded_pow(base, exponent, 0)
    assert err.value.code == "too_large"


@pytest.mark.parametrize("base, exponent, expected", [
    (sympy.Integer(10), sympy.Integer(999), sympy.Integer(10) ** 999),
    (sympy.Integer(2), sympy.Integer(1000), sympy.Integer(2) ** 1000),
    (x, sympy.Integer(-1000), x ** -1000),
    (sympy.Integer(4), sympy.Rational(1, 2), sympy.Integer(2)),
])
def test_reasonable_powers_are_built(base, exponent, expected):
    assert guarded_pow(base, exponent, 0) == expected


@pytest.mark.parametrize("expr", [sympy.zoo, sympy.nan, x + sympy.oo, sympy.I * x,
                                  sympy.Integer(10) ** (MAX_DIGITS + 1)])
def test_undefined_imaginary_or_huge_results_are_refused(expr):
    with pytest.raises(ExpressionError):
        checked(expr, 0)


def test_digits_counts_numerator_or_denominator():
    assert digits(sympy.Rational(1, 10 ** 50)) == 50


@pytest.mark.parametrize("exponent", ["0.666666666666667", "0.1234567", "1.23456789012345678", "0.333333333333333"])
def test_a_decimal_exponent_with_too_many_digits_is_refused_for_its_digits_not_its_size(exponent):
    # x^0.666666666666667 (a calculator's 2/3) is small: the message must not say "too large"
    with pytest.raises(ExpressionError) as err:
        guarded_pow(x, sympy.Rational(exponent), 0)
    assert err.value.code == "too_large" and "too many digits" in err.value.message
    assert "as a fraction" in err.value.hint


@pytest.mark.parametrize("exponent", ["0.123456", "1.6", "0.5"])
def test_a_decimal_exponent_with_six_decimals_is_built(exponent):
    assert guarded_pow(x, sympy.Rational(exponent), 0) == x ** sympy.Rational(exponent)


# -- red team 22: log(sin(exp(99999999))), whose sign took the parse without end --

@pytest.mark.parametrize("text", ["log(sin(exp(99999999)))", "log(sin(sinh(99999999)))", "log(cos(cosh(-10^9)))",
                                  "log(sin(exp(999)*exp(999)*exp(999)))", "tan(exp(exp(exp(exp(1)))))", "sec(exp(99999))"])
def test_a_periodic_function_of_a_number_with_more_digits_than_a_number_may_have_is_refused(text):
    from grader.expressions import Namespace, parse_expression
    with pytest.raises(ExpressionError) as err:
        parse_expression(text, Namespace([]))
    assert err.value.code == "too_large" and "more than 1000 digits" in err.value.message


@pytest.mark.parametrize("text", ["sin(exp(1000))", "sin(10^999)", "exp(99999999)", "exp(-4000)", "sinh(3/10)",
                                  "exp(exp(exp(exp(1))))", "log(sin(exp(2000)))"])
def test_the_same_numbers_elsewhere_or_smaller_are_built(text):
    # exp(exp(exp(e))) times an answer is a wrong answer (the corpus's yoyo item), not an unreadable one
    from grader.expressions import Namespace, parse_expression
    assert parse_expression(text, Namespace([])).expr.is_number
