"""How typed names resolve to the namespace's variables."""

import pytest
import sympy

from grader.expressions import ExpressionError, Namespace, Variable, parse_expression
from grader.expressions.names import derivative_name, resolve_name


@pytest.mark.parametrize("typed, order, canonical", [
    ("theta", 0, "theta"),
    ("theta_dot", 0, "thetadot"),
    ("theta_ddot", 0, "thetaddot"),
    ("m_1", 0, "m1"),
    ("theta", 1, "thetadot"),
    ("theta", 2, "thetaddot"),
    ("thetadot", 1, "thetaddot"),
    ("lambda_surface", 0, "lambda_surface"),
])
def test_spellings_resolve_to_the_canonical_variable(ns, typed, order, canonical):
    resolved = resolve_name(typed, ns, order=order)
    assert resolved.kind == "symbol" and resolved.value == ns.symbol(canonical)


@pytest.mark.parametrize("base, order, name", [("x", 1, "xdot"), ("x", 2, "xddot"), ("xdot", 1, "xddot")])
def test_derivative_names(base, order, name):
    assert derivative_name(base, order) == name


@pytest.mark.parametrize("typed, parts", [
    ("mg", ["m", "g"]),
    ("mgl", ["m", "g", "l"]),
    ("m1g", ["m1", "g"]),
    ("mthetadot", ["m", "thetadot"]),
    ("mgcos", ["m", "g", "cos"]),
    ("sin2x", ["sin", "2", "x"]),
    ("pir", ["pi", "r"]),
])
def test_glued_names_split_into_known_names(ns, typed, parts):
    resolved = resolve_name(typed, ns)
    assert resolved.kind == "split" and resolved.value == parts
    assert resolved.notes and resolved.notes[0].startswith(f"read '{typed}' as")


@pytest.mark.parametrize("typed", ["E", "e", "pi"])
def test_constants(ns, typed):
    assert resolve_name(typed, ns).value in (sympy.E, sympy.pi)


def test_functions_are_recognised_in_any_case(ns):
    assert resolve_name("Sin", ns).value == "sin" and resolve_name("Abs", ns).value == "abs"


@pytest.mark.parametrize("typed, called, code", [
    ("thetta", False, "unknown_name"),
    ("factorial", True, "unsupported_function"),
    ("__class__", False, "unsupported_function"),
    ("import", False, "unsupported_function"),
    ("zdot", False, "unknown_name"),
])
def test_refusals(ns, typed, called, code):
    with pytest.raises(ExpressionError) as err:
        resolve_name(typed, ns, called=called)
    assert err.value.code == code


def test_missing_derivative_says_which_variable_is_missing():
    ns = Namespace([Variable("x", "length", "real", "coordinate")])
    with pytest.raises(ExpressionError, match="no variable xdot"):
        resolve_name("x", ns, order=1, typed="x'")


def test_a_parameters_derivative_says_it_is_constant():
    # a parameter (the default kind) is constant in time, as d/dt(m x) takes it
    with pytest.raises(ExpressionError, match="x is a constant of this problem"):
        resolve_name("x", Namespace([Variable("x", "length")]), order=1, typed="x'")


def test_unknown_long_name_is_shortened_in_the_message(ns):
    with pytest.raises(ExpressionError) as err:
        resolve_name("q" * 500, ns)
    assert len(err.value.message) < 100


# -- a declared name glued to Euler's e before a power: ye^x -------------------------------------

@pytest.mark.parametrize("typed, parts", [
    ("ye", ["y", "e"]),
    ("me", ["m", "e"]),
    ("m_1e", ["m1", "e"]),                 # a subscripted name, underscores ignored as in m_1g
    ("thetae", ["theta", "e"]),
    ("mge", ["m", "g", "e"]),              # a glued run of declared names, as mg is read
    ("pie", ["pi", "e"]),
])
def test_a_declared_name_glued_to_e_before_a_power_reads_as_the_name_times_e(ns, typed, parts):
    resolved = resolve_name(typed, ns, before_power=True)
    assert resolved.kind == "split" and resolved.value == parts
    assert resolved.notes == [f"read '{typed}' as {'·'.join(parts)}"]


@pytest.mark.parametrize("typed", [
    "ze",          # z is not declared
    "sine",        # a function before the e: sin(e^x)? not guessed
    "x_e",         # a subscript e: x_e^2 is the square of x_e
    "ee",          # nothing declared before the e
    "e",
])
def test_other_names_ending_in_e_are_not_split_before_a_power(ns, typed):
    with pytest.raises(ExpressionError) as err:
        resolve_name(typed + "x" if typed == "e" else typed, ns, before_power=True)
    # (sine is the function's name spelt out: refused as that, saying to write sin)
    assert err.value.code == ("unsupported_function" if typed == "sine" else "unknown_name")


def test_without_a_power_after_it_ye_is_refused_with_the_product_to_type(ns):
    with pytest.raises(ExpressionError) as err:
        resolve_name("ye", ns)
    assert err.value.message == "unknown name 'ye'"
    assert err.value.hint == "write y*e for y·e with e Euler's number; or did you mean 'y'?"


@pytest.mark.parametrize("text, expected", [
    ("ye^x", lambda s: s["y"] * sympy.exp(s["x"])),
    ("ae^-2x", lambda s: s["a"] * sympy.exp(-2 * s["x"])),   # the exponent keeps its glued factor, as e^-2x does
    ("ae^(-2x)", lambda s: s["a"] * sympy.exp(-2 * s["x"])),
    ("m ge^(-t)", lambda s: s["m"] * s["g"] * sympy.exp(-s["t"])),
    ("mge^{-t}", lambda s: s["m"] * s["g"] * sympy.exp(-s["t"])),
    ("2ye^x", lambda s: 2 * s["y"] * sympy.exp(s["x"])),
    ("θe^(x/l)", lambda s: s["theta"] * sympy.exp(s["x"] / s["l"])),
])
def test_glued_exponentials_parse(text, expected):
    ns = Namespace([Variable(n, "1") for n in ("y", "x", "a", "m", "g", "t", "theta", "l")])
    parsed = parse_expression(text, ns)
    assert parsed.expr == expected({n: ns.symbol(n) for n in ns.names})
    assert any(note.startswith("read '") and note.endswith("·e") for note in parsed.notes)


def test_a_declared_variable_named_e_keeps_its_meaning():
    ns = Namespace([Variable("y", "1"), Variable("e", "1"), Variable("x", "1")])
    e, x, y = (ns.symbol(n) for n in "exy")
    assert parse_expression("ye^x", ns).expr == y * e ** x
    assert parse_expression("e^x", ns).expr == e ** x


def test_a_declared_name_ending_in_e_keeps_its_meaning():
    ns = Namespace([Variable("y", "1"), Variable("ye", "1"), Variable("x", "1")])
    assert parse_expression("ye^x", ns).expr == ns.symbol("ye") ** ns.symbol("x")


# -- \pi2, \omega2: a LaTeX command with digits typed after it ------------------------------------

@pytest.mark.parametrize("typed, hint", [
    ("\\pi2", "write 2\\pi for the product"),
    ("\\omega2", "write 2\\omega for the product, or \\omega_{2} for a variable with subscript 2"),
])
def test_an_unknown_command_with_digits_names_the_product_and_the_subscript(ns, typed, hint):
    with pytest.raises(ExpressionError) as err:
        resolve_name(typed[1:], ns, typed=typed)
    assert err.value.message == f"unknown name '{typed}'" and err.value.hint == hint


# Functions other systems (STACK/Maxima, calculators) have and the grammar leaves out: the refusal
# says how to write each with the functions it has, not only "did you mean cot".
@pytest.mark.parametrize("text, hint", [
    ("root(x, 3)", "x^(1/n)"), ("logbase(x, 2)", "log(x, b)"), ("lg(x, 3)", "log(x, b)"), ("log10(x, 3)", "log(x, b)"),
    ("acot(x)", "atan(1/x)"), ("arccot(x)", "atan(1/x)"), ("asec(x)", "acos(1/x)"), ("acsc(x)", "asin(1/x)"),
    ("arcsec(x)", "acos(1/x)"),
])
def test_functions_of_other_systems_are_refused_with_the_way_to_write_them(text, hint):
    ns = Namespace([Variable("x", "dimensionless", "real")])
    with pytest.raises(ExpressionError) as err:
        parse_expression(text, ns)
    assert hint in err.value.hint


@pytest.mark.parametrize("typed, canonical", [
    ("thetaddot_1", "theta1ddot"), ("thetaddot1", "theta1ddot"), ("thetadot_2", "theta2dot"),
    ("theta_ddot_1", "theta1ddot"), ("xddot_2", "x2ddot"), ("theta1ddot", "theta1ddot"),
])
def test_the_dots_typed_before_the_index_name_the_indexed_derivative(typed, canonical):
    ns = Namespace([Variable(name, "1/s^2") for name in ("theta1ddot", "theta2ddot", "x2ddot")]
                   + [Variable(name, "1/s") for name in ("theta1dot", "theta2dot")])
    resolved = resolve_name(typed, ns)
    assert resolved.kind == "symbol" and resolved.value == ns.symbol(canonical)


def test_the_dots_before_an_index_do_not_shadow_a_declared_name():
    ns = Namespace([Variable("thetadot1", "1/s"), Variable("theta1dot", "1/s")])
    assert resolve_name("thetadot1", ns).value == ns.symbol("thetadot1")


@pytest.mark.parametrize("text", ["acot(k)", "acot k", "asec(k)", "arccsc(k)", "acoth(k)"])
def test_a_function_refused_by_name_is_not_split_into_a_declared_variable(text):
    # with a variable a declared, acot(k) was read as a·cot(k): it is the inverse cotangent, refused saying how
    # to write it
    from grader.expressions import parse_expression

    ns = Namespace([Variable("a", "length"), Variable("k", "dimensionless")])
    with pytest.raises(ExpressionError) as caught:
        parse_expression(text, ns)
    assert "is not a function you can use here" in caught.value.message


@pytest.mark.parametrize("text, letter, name", [("ν0^2", "v", "v0"), ("κ x", "k", "k"), ("ρ0", "p", "p0")])
def test_a_greek_letter_that_looks_latin_is_named_with_the_latin_variable(text, letter, name):
    # ν0 for v0 said only "unknown name 'ν0'"
    ns = Namespace([Variable("v0", "velocity", "real"), Variable("k", "1/m", "positive"),
                    Variable("x", "length", "real"), Variable("p0", "momentum", "positive")])
    with pytest.raises(ExpressionError) as refused:
        parse_expression(text, ns)
    assert f"looks like the Latin '{letter}'" in refused.value.message and f"type {name}" in refused.value.hint


def test_a_greek_letter_the_problem_declares_is_its_variable():
    ns = Namespace([Variable("nu", "frequency", "positive"), Variable("v", "velocity", "real")])
    assert parse_expression("ν v", ns).expr == ns.symbol("nu") * ns.symbol("v")


@pytest.mark.parametrize("text, unit", [("sqrt(g*l) m/s", "s"), ("l ms", "ms"), ("l km", "km")])
def test_an_unknown_name_that_is_a_unit_symbol_says_units_are_not_part_of_the_answer(text, unit):
    ns = Namespace([Variable("g", "acceleration", "positive"), Variable("l", "length", "positive"),
                    Variable("m", "mass", "positive")])
    with pytest.raises(ExpressionError) as refused:
        parse_expression(text, ns)
    assert f"if '{unit}' is a unit, delete it" in refused.value.hint


# -- red team 22: a phone capitalises the first letter of what is typed --

@pytest.mark.parametrize("text, meant", [
    ("Mg cos(theta)", "mg"), ("M g cos(theta)", "m"), ("Ml thetadot^2", "ml"), ("G m", "g"), ("Theta + phi", "theta"),
])
def test_a_capital_first_letter_where_the_problem_has_the_lowercase_name_says_so(ns, text, meant):
    # 'Mg' was answered "did you mean 'g'?", which sends the student away from the m they typed
    with pytest.raises(ExpressionError) as refused:
        parse_expression(text, ns)
    assert refused.value.code == "unknown_name" and f"did you mean '{meant}'" in refused.value.hint \
        and "capitalised the first letter" in refused.value.hint


@pytest.mark.parametrize("text", ["m Mg", "Mq", "MG", "(Mg)"])
def test_a_capital_elsewhere_or_of_no_lowercase_name_gets_no_such_hint(ns, text):
    with pytest.raises(ExpressionError) as refused:
        parse_expression(text, ns)
    assert "capitalised" not in (refused.value.hint or "")


# -- red team 22: words for operators, as dictation or a formula read aloud gives them --

@pytest.mark.parametrize("text, word, fix", [
    ("m l thetadot squared", "squared", "^2"), ("x cubed", "cubed", "^3"), ("m g plus m l", "plus", "+"),
    ("m g minus m l", "minus", "-"), ("g over l", "over", "/"),
    ("theta prime", "prime", "θ'"), ("m g two", "two", "2"),
    ("half m g", "half", "1/2"), ("m g where g = 9.8", "where", "without the explanation"),
])
def test_a_word_for_an_operator_is_named_with_the_symbol_to_type(ns, text, word, fix):
    # 'squared' was "did you mean 'surd'?", 'cosine' "did you mean 'cosec' or 'sin' or 'cos'?"
    with pytest.raises(ExpressionError) as refused:
        parse_expression(text, ns)
    assert f"'{word}'" in refused.value.message and "word" in refused.value.message and fix in refused.value.hint


def test_a_lone_x_that_is_no_variable_may_be_a_times_sign(ns):
    small = Namespace([Variable("m", "mass", "positive"), Variable("g", "acceleration", "positive")])
    with pytest.raises(ExpressionError) as refused:
        parse_expression("m x g", small)
    assert "if 'x' stands for times, type *" in refused.value.hint


@pytest.mark.parametrize("text", ["m g Newtons", "m g Kilograms"])
def test_a_unit_word_with_a_capital_is_a_unit(ns, text):
    with pytest.raises(ExpressionError) as refused:
        parse_expression(text, ns)
    assert "units are not part of the answer" in refused.value.message


@pytest.mark.parametrize("text, fix", [("m g cosine(theta)", "write cos, as in cos(θ)"), ("sine theta", "write sin"),
                                       ("tangent(theta)", "write tan"), ("ch(theta)", "write cosh(x)"),
                                       ("sh(theta)", "write sinh(x)"), ("th(theta)", "write tanh(x)")])
def test_a_function_spelt_out_is_named_with_its_name_here(ns, text, fix):
    with pytest.raises(ExpressionError) as refused:
        parse_expression(text, ns)
    assert refused.value.hint.startswith(fix)


@pytest.mark.parametrize("text, greek", [("cos a", "alpha"), ("m g cos q", "theta"), ("w t", "omega")])
def test_a_latin_letter_for_a_greek_one_of_the_problem_is_named(text, greek):
    # sin a for sin α (no Greek on the keyboard; q is θ in Word's Symbol font): it was "unknown name 'a'"
    ns = Namespace([Variable("alpha", "angle", "real"), Variable("theta", "angle", "real"), Variable("m", "mass"),
                    Variable("g", "acceleration"), Variable("omega", "angular_velocity"), Variable("t", "time")])
    with pytest.raises(ExpressionError) as refused:
        parse_expression(text, ns)
    assert f"({greek})" in refused.value.message and refused.value.hint.startswith(f"type {greek}")


@pytest.mark.parametrize("text, said, fix", [
    ("inf", "infinity", "finite"), ("m g + Infinity", "infinity", "finite"), ("NaN", "not-a-number", "finite"),
    ("nan", "not-a-number", "finite"), ("tau", "no variable τ", "2*pi"), ("2 tau m g", "no variable τ", "2*pi"),
    ("i^2", "imaginary unit", "real quantities"), ("1 + I", "imaginary unit", "real quantities"),
    ("\\mathrm{i}^2", "imaginary unit", "real quantities"), ("2j", "imaginary unit", "real quantities"),
    ("fact(3)", "fact", "write the product out"), ("root(8, 3)", "root", "write surd(x, n) for the real n-th root"),
])
def test_other_graders_constants_and_fact_are_named_with_the_fix(ns, text, said, fix):
    # edX's and mathjs' inf, NaN, tau and fact(n): 'nan' was "did you mean 'tan'?", fact "'arctg' or 'arctan'?";
    # Maple's root(x, n) was told x^(1/n), which has no value for x < 0; edX's i and j, Wolfram's I: 'i' was
    # "did you mean 'pi'?"
    with pytest.raises(ExpressionError) as refused:
        parse_expression(text, ns)
    assert said in refused.value.message and fix in refused.value.hint
