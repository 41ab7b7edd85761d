"""Notation of other graders (math-expressions, KAS, Numbas) that our grammar reads or refuses.

Inverse functions the grammar leaves out (arcsec, sec^-1, arccoth): refused, saying how to write them.

math-expressions, KAS and Maxima read ``arcsec x``, ``sec^(-1)(x)`` and ``arccoth(x)``; here the
whitelist has only the inverses of sin, cos, tan and their hyperbolic twins, so every other
spelling is refused with both readings of ``f^-1`` (inverse or reciprocal) and the way to write
the inverse with the functions we have.
"""

import pytest
import sympy

from grader.expressions import ExpressionError, Namespace, Variable, parse_expression


@pytest.fixture
def ns():
    return Namespace([Variable("x", "dimensionless", "real")])


@pytest.mark.parametrize("text, inverse", [
    ("sec^-1 x", "acos(1/x)"), ("sec^(-1)(x)", "acos(1/x)"), ("csc^-1(x)", "asin(1/x)"),
    ("cosec^-1 x", "asin(1/x)"), ("cot^-1 x", "atan(1/x)"), ("sech^-1(x)", "acosh(1/x)"),
    ("csch^-1 x", "asinh(1/x)"), ("coth^(-1) x", "atanh(1/x)"), ("log^-1 x", "exp(x)"),
    ("ln^-1(x)", "exp(x)"), ("exp^-1 x", "log(x)"),
])
def test_a_function_to_the_minus_one_names_the_inverse_and_the_reciprocal(ns, text, inverse):
    with pytest.raises(ExpressionError) as err:
        parse_expression(text, ns)
    name = text.split("^")[0]
    canonical = {"cosec": "csc", "ln": "log"}.get(name, name)
    assert err.value.code == "ambiguous"
    assert "inverse function" in err.value.message and f"1/{canonical}" in err.value.message
    assert inverse in err.value.hint and f"1/{canonical}(x) for the reciprocal" in err.value.hint


@pytest.mark.parametrize("text", ["abs^-1 x", "sign^-1(x)"])
def test_a_function_with_no_inverse_to_the_minus_one_offers_the_reciprocal_only(ns, text):
    with pytest.raises(ExpressionError) as err:
        parse_expression(text, ns)
    assert "inverse" not in err.value.message and "for the reciprocal" in err.value.hint


@pytest.mark.parametrize("text", ["sin^-1 x", "tanh^-1(x)", "cos^(-1)(x)"])
def test_the_inverses_the_grammar_has_are_still_read(ns, text):
    assert parse_expression(text, ns).expr.func.__name__ in ("asin", "atanh", "acos")


@pytest.mark.parametrize("text, write", [
    ("arcsec(x)", "acos(1/x)"), ("arcsec x", "acos(1/x)"), ("asec x", "acos(1/x)"),
    ("arccsc x", "asin(1/x)"), ("arccot x", "atan(1/x)"), ("acot(x)", "atan(1/x)"),
    ("arcsech(x)", "acosh(1/x)"), ("asech x", "acosh(1/x)"), ("arccsch(x)", "asinh(1/x)"),
    ("arcsch x", "asinh(1/x)"), ("arccoth(x)", "atanh(1/x)"), ("arcoth x", "atanh(1/x)"),
])
def test_an_inverse_function_other_systems_know_is_refused_with_how_to_write_it(ns, text, write):
    # with or without brackets: "arcsec x" is the function, not a misspelt variable
    with pytest.raises(ExpressionError) as err:
        parse_expression(text, ns)
    assert err.value.code == "unsupported_function"
    assert "is not a function you can use here" in err.value.message and write in err.value.hint


# -- other graders' plain-text spellings of roots and logarithm bases ---------------------------

@pytest.fixture
def pos():
    return Namespace([Variable("x", "dimensionless", "positive")])


@pytest.mark.parametrize("text, expected", [
    ("sqrt[3]{x}", lambda x: sympy.sign(x) * sympy.Abs(x) ** sympy.Rational(1, 3)),  # KAS, MathQuill text
    ("Sqrt[3]{x}", lambda x: sympy.sign(x) * sympy.Abs(x) ** sympy.Rational(1, 3)),
    ("sqrt[4]{x}", lambda x: x ** sympy.Rational(1, 4)),
    ("sqrt[3]{x}^2", lambda x: (sympy.sign(x) * sympy.Abs(x) ** sympy.Rational(1, 3)) ** 2),
    ("sqrt[2]{x+1}", lambda x: sympy.sqrt(x + 1)),
    # no radicand after the brackets: Mathematica's Sqrt[2], a number
    ("sqrt[2]+x", lambda x: sympy.sqrt(2) + x), ("Sqrt[3] x", lambda x: sympy.sqrt(3) * x),
])
def test_a_root_typed_as_sqrt_index_braces_is_that_root(ns, text, expected):
    x = ns.symbol("x")
    assert parse_expression(text, ns).expr == expected(x)


def test_an_odd_root_typed_so_is_real_for_negative_numbers(ns):
    assert parse_expression("sqrt[3]{-8}", ns).expr == -2


@pytest.mark.parametrize("text, hint", [
    ("sqrt[3](x)", "cbrt(x) for the root"), ("sqrt[3]x", "cbrt(x) for the root"),
    ("sqrt[2] x", "sqrt(x) for the root"), ("sqrt[5](x+1)", "x^(1/5) for the root"),
])
def test_sqrt_index_then_a_factor_is_refused_with_both_readings(ns, text, hint):
    # the root, or Mathematica's Sqrt[3] times the factor: never silently √3·x
    with pytest.raises(ExpressionError) as err:
        parse_expression(text, ns)
    assert err.value.code == "ambiguous" and hint in err.value.hint and "for the product" in err.value.hint


@pytest.mark.parametrize("text", ["sqrt[x]{2}", "sqrt[1]{x}", "sqrt[2.5]{x}"])
def test_a_root_index_that_is_no_whole_number_from_two_is_refused(ns, text):
    with pytest.raises(ExpressionError) as err:
        parse_expression(text, ns)
    assert "index" in err.value.message and "x^(1/n)" in err.value.hint


@pytest.mark.parametrize("text, base", [("log_2.5x", "2.5"), ("log_2.5 x", "2.5"), ("\\log_2.5x", "2.5"),
                                        ("log_10.5(x)", "10.5")])
def test_a_logarithm_base_with_a_decimal_point_is_refused_not_read_as_log2_of_a_decimal(pos, text, base):
    # KAS reads log_2.5x as the logarithm to base 2.5; the tokens alone said log₂(0.5·x)
    with pytest.raises(ExpressionError) as err:
        parse_expression(text, pos)
    assert err.value.code == "ambiguous" and f"log(x, {base})" in err.value.hint


@pytest.mark.parametrize("text", ["log_2 x", "log_10(x)", "log_2(x)"])
def test_whole_number_logarithm_bases_are_still_read(pos, text):
    x = pos.symbol("x")
    base = 2 if "_2" in text else 10
    assert sympy.simplify(parse_expression(text, pos).expr - sympy.log(x) / sympy.log(base)) == 0


@pytest.mark.parametrize("text", ["2\\frac{1}{2}", "2 \\frac{1}{2}", "2\\dfrac{1}{2}x", "2\\frac12"])
def test_a_whole_number_before_a_numeric_latex_fraction_is_refused_as_a_mixed_number(ns, text):
    # 2\frac{1}{2} prints 2½: 5/2 at school, 1 to KAS; refused as "1½" is, with both readings
    with pytest.raises(ExpressionError) as err:
        parse_expression(text, ns)
    assert "mixes a number and a fraction" in err.value.message
    assert "2 + 1/2 for the mixed number" in err.value.hint and "2*1/2 for the product" in err.value.hint


@pytest.mark.parametrize("text, expected", [
    ("2\\frac{x}{2}", "x"), ("3\\frac{1}{x}", "3/x"), ("2\\cdot\\frac{1}{2}", "1"),
    ("\\frac{1}{2}\\frac{1}{2}", "1/4"), ("x^2\\frac{1}{2}", "x**2/2"), ("x^{2}\\frac{1}{2}", "x**2/2"),
    ("2+\\frac{1}{2}", "5/2"), ("2.5\\frac{1}{2}", "5/4"),
])
def test_other_products_with_a_latex_fraction_are_read(ns, text, expected):
    assert str(parse_expression(text, ns).expr) == expected


@pytest.mark.parametrize("text, typed", [("y =/= x", "=/="), ("y<>x", "<>"), ("y /= x", "/="), ("y =\\= x", "=\\="),
                                         ("y != x", "!=")])
def test_not_equal_in_other_languages_is_named_as_not_equal(ns, text, typed):
    # KAS's =/=, Fortran's /=, BASIC's <>, Prolog's =\=: not a stray '/', a second '=' or an inequality
    ns = Namespace([Variable("x", "dimensionless", "real"), Variable("y", "dimensionless", "real")])
    with pytest.raises(ExpressionError) as err:
        parse_expression(text, ns)
    assert f"'{typed}' (not equal)" in err.value.message and "equation with =" in err.value.hint


@pytest.mark.parametrize("text, expected", [("x/2", "x/2"), ("x / -2", "-x/2"), ("2 < 3", None)])
def test_division_and_inequalities_are_unchanged(ns, text, expected):
    if expected is None:
        with pytest.raises(ExpressionError) as err:
            parse_expression(text, ns)
        assert "inequalities" in err.value.message
    else:
        assert str(parse_expression(text, ns).expr) == expected


@pytest.mark.parametrize("text, write", [("3.e10", "3e10 or 3.0e10"), ("3.E-3*x", "3E-3 or 3.0E-3"),
                                         ("12.e+4", "12e+4 or 12.0e+4")])
def test_a_bare_decimal_point_before_e_notation_says_how_to_write_the_number(ns, text, write):
    # Moodle Formulas and C accept 3.e10; here the point must be followed by digits, and the hint says so
    with pytest.raises(ExpressionError) as err:
        parse_expression(text, ns)
    assert "decimal point" in err.value.message and write in err.value.hint


@pytest.mark.parametrize("text", ["5.x", "2.e"])
def test_other_bare_decimal_points_keep_the_general_hint(ns, text):
    with pytest.raises(ExpressionError) as err:
        parse_expression(text, ns)
    assert "write 0.5" in err.value.hint


# -- Mathematica's named characters: what its InputForm and "Copy As Plain Text" give for θ, ω, × -----

def _mechanics():
    return Namespace([Variable("m", "mass", "positive"), Variable("g", "acceleration", "positive"),
                      Variable("l", "length", "positive"), Variable("theta", "angle"),
                      Variable("thetadot", "angular_velocity"), Variable("omega", "angular_velocity"),
                      Variable("Omega", "angular_velocity"), Variable("theta1", "angle")])


@pytest.mark.parametrize("text, same_as", [
    (r"m g Cos[\[Theta]] + m l thetadot^2", "m g cos(θ) + m l θ̇^2"),
    (r"m l \[Omega]^2", "m l ω^2"),
    (r"\[CapitalOmega] \[Times] m", "Ω m"),
    (r"Sin[\[Theta]1] \[CenterDot] l", "l sin(θ₁)"),
    (r"m g \[Minus] m l \[Omega]^2", "m g - m l ω^2"),
    (r"Cos[\[CurlyTheta]]", "cos θ"),
    (r"\[Theta]'", "θ̇"),
    (r"l Sin[30 \[Degree]]", "l sin(30°)"),
])
def test_mathematicas_named_characters_read_as_the_characters(text, same_as):
    ns = _mechanics()
    assert parse_expression(text, ns).expr == parse_expression(same_as, ns).expr


def test_an_unknown_named_character_is_refused_by_name_and_latex_display_math_is_still_read():
    ns = _mechanics()
    with pytest.raises(ExpressionError) as err:
        parse_expression(r"\[Bogus] m", ns)
    assert r"'\[Bogus]'" in err.value.message and "type the character itself" in err.value.hint
    assert parse_expression(r"\[m g\]", ns).expr == parse_expression("m g", ns).expr


# -- SymPy's, CortexJS's, MathQuill's and lambda-feedback's parser suites (red team, 2026-11-27) --------

@pytest.fixture
def xy():
    return Namespace([Variable("x", "dimensionless", "real"), Variable("y", "dimensionless", "real")])


@pytest.mark.parametrize("text, expected", [
    # a function name, a space, then a number in brackets is the function's call, not an equation's number
    ("sin (2)", "sin(2)"), ("cos (0)", "1"), ("2 sin (3)", "2*sin(3)"), ("sqrt (3)", "sqrt(3)"),
    (r"\sin (2)", "sin(2)"), (r"\sin \left( 2 \right)", "sin(2)"), (r"2\cos \left(2\right)", "2*cos(2)"),
    # a bracket glued to the number of a function's argument stays in it, as sin 2x is sin(2x)
    ("sin 2(x+1)", "sin(2*x + 2)"),
])
def test_a_function_takes_the_bracket_that_follows_it(xy, text, expected):
    assert parse_expression(text, xy).expr == parse_expression(expected, xy).expr


def test_an_equation_number_after_a_variable_is_still_refused(xy):
    with pytest.raises(ExpressionError) as err:
        parse_expression("x + y (2)", xy)
    assert err.value.code == "ambiguous"


@pytest.mark.parametrize("text, read_as, note", [
    # readings that follow precedence but that other parsers flag: said in a note, never silent
    ("√x+y²", "sqrt(x) + y**2", "write √(…) around everything the root covers"),
    ("√x-y^2", "sqrt(x) - y**2", "write √(…) around everything the root covers"),
    ("cos 2*x", "x*cos(2)", "write cos(…) around everything the cos covers"),
    ("sin x/2", "sin(x)/2", "write sin(…) around everything the sin covers"),
    ("x^1/2", "x/2", "write ^(1/2) for the power 1/2"),
    ("x^-1/2", "1/(2*x)", "write ^(-1/2) for the power -1/2"), ("x^−1/3", "1/(3*x)", "write ^(-1/3) for the power -1/3"),
])
def test_a_reading_other_parsers_call_ambiguous_is_said(xy, text, read_as, note):
    parsed = parse_expression(text, xy)
    assert parsed.text == read_as
    assert any(note in n for n in parsed.notes), parsed.notes


@pytest.mark.parametrize("text", ["√2+1", "x^(1/2)", "2 sin(x) y", "sin(x)/2"])
def test_unambiguous_forms_get_no_such_note(xy, text):
    assert not any("covers" in n or "for the power" in n for n in parse_expression(text, xy).notes)


@pytest.mark.parametrize("text, braced", [(r"\frac1234", r"\frac{12}{34}"), (r"\frac123", r"\frac{12}{3}"),
                                          (r"\dfrac 12 3", r"\frac{12}{3}")])
def test_unbraced_frac_digits_then_a_number_name_both_readings(xy, text, braced):
    # SymPy's LaTeX suite: \frac1234 is ½·34 to TeX; a student meant 12/34. Refused, saying both.
    with pytest.raises(ExpressionError) as err:
        parse_expression(text, xy)
    assert err.value.code == "ambiguous" and "one digit for each argument" in err.value.message
    assert braced in err.value.hint
