"""Leibniz notation: dθ/dt, d²x/dt², \\frac{d\\theta}{dt} and d/dt(θ) read as the dotted variables,
only where d, t and the d-words mean nothing else, and every refusal names the text and the fix."""

import time

import pytest

from grader.expressions import ExpressionError, Namespace, Variable, parse_equation, parse_expression
from grader.expressions.leibniz import dotted, read_leibniz
from grader.expressions.parser import parse_system
from grader.expressions.tokens import tokenize


def _ns(*extra):
    return Namespace([
        Variable("m", "mass", "positive"), Variable("l", "length", "positive"),
        Variable("g", "acceleration", "positive"),
        Variable("theta", "angle"), Variable("thetadot", "angular_velocity"),
        Variable("thetaddot", "angular_acceleration"),
        Variable("x", "length"), Variable("xdot", "velocity"), Variable("xddot", "acceleration"),
        Variable("x1", "length"), Variable("x1dot", "velocity"), Variable("x2", "length"),
        Variable("x2dot", "velocity"), Variable("theta1", "angle"), Variable("theta1dot", "angular_velocity"),
        *extra,
    ])


@pytest.fixture
def ns():
    return _ns()


def parse(text, ns):
    return parse_expression(text, ns).expr


@pytest.mark.parametrize("text, name", [
    ("dθ/dt", "thetadot"),
    ("dtheta/dt", "thetadot"),
    ("d theta/dt", "thetadot"),
    ("dθ / dt", "thetadot"),
    ("d(θ)/dt", "thetadot"),
    ("dθ̇/dt", "thetaddot"),                     # the derivative of a dotted variable
    ("d²θ/dt²", "thetaddot"),
    ("d^2θ/dt^2", "thetaddot"),
    ("d^2 x/dt^2", "xddot"),
    ("d^{2}x/dt^{2}", "xddot"),
    ("d²(x)/dt²", "xddot"),
    ("dx_1/dt", "x1dot"),
    ("dθ₁/dt", "theta1dot"),
    ("d x/d t", "xdot"),
    (r"\frac{d\theta}{dt}", "thetadot"),
    (r"\frac{d^2\theta}{dt^2}", "thetaddot"),
    (r"\frac{d^{2}\theta}{dt^{2}}", "thetaddot"),
    (r"\frac{\mathrm{d}\theta}{\mathrm{d}t}", "thetadot"),
    (r"\frac{\mathrm{d}x}{\mathrm{d}t}", "xdot"),
    (r"\frac{d x_2}{d t}", "x2dot"),
    (r"\frac{d\theta_1}{dt}", "theta1dot"),
    (r"\tfrac{d\theta}{dt}", "thetadot"),
    (r"\dfrac{d^2 x}{dt^2}", "xddot"),
    ("d/dt θ", "thetadot"),
    ("d/dt(θ)", "thetadot"),
    ("d/dt (x_2)", "x2dot"),
    ("d/dt θ̇", "thetaddot"),
    ("d²/dt² x", "xddot"),
    (r"\frac{d}{dt}\theta", "thetadot"),
    (r"\frac{d}{dt}\left(\theta\right)", "thetadot"),
    (r"\frac{d}{dt}\dot{\theta}", "thetaddot"),
    (r"\frac{d^2}{dt^2}x", "xddot"),
    ("d/dt(dθ/dt)", "thetaddot"),               # the derivative of a derivative
    ("d/dt (dx/dt)", "xddot"),
    ("d/dt(d/dt(θ))", "thetaddot"),
    (r"\frac{d}{dt}\left(\frac{d\theta}{dt}\right)", "thetaddot"),
])
def test_every_leibniz_form_is_the_dotted_variable(ns, text, name):
    parsed = parse_expression(text, ns)
    assert parsed.expr == ns.symbol(name)
    assert parsed.notes == [f"read '{text}' as {dotted(name)}"]


@pytest.mark.parametrize("leibniz, dots", [
    ("m l (dθ/dt)^2", "m l θ̇^2"),
    ("m l (dθ/dt)²", "m l θ̇²"),
    ("m l² d²θ/dt² + m g l sin θ", "m l² θ̈ + m g l sin θ"),
    (r"m l^2 \frac{d^2\theta}{dt^2} + m g l \sin\theta", r"m l^2 \ddot{\theta} + m g l \sin\theta"),
    ("1/2 m (dx/dt)^2", "1/2 m ẋ^2"),
    ("dx/dt/l", "ẋ/l"),
    ("m dθ/dt l", "m θ̇ l"),
    ("cos dθ/dt", "cos θ̇"),
    ("d/dt(x) + dx/dt", "2 ẋ"),
    ("d/dt θ * x", "θ̇ * x"),
    ("d/dt(θ) x", "θ̇ x"),
])
def test_the_same_expression_as_the_dot_notation(ns, leibniz, dots):
    assert parse(leibniz, ns) == parse(dots, ns)


def test_the_checker_grades_leibniz_like_dots():
    from grader.answers.checker import check
    variables = {"m": {"dimension": "mass", "domain": "positive"}, "l": {"dimension": "length", "domain": "positive"},
                 "theta": {"dimension": "angle", "domain": "real"},
                 "thetadot": {"dimension": "angular_velocity", "domain": "real"}}
    verdict = check("m*l*thetadot**2", "m l (dθ/dt)^2", variables)
    assert verdict.verdict == "equivalent"
    assert "read 'dθ/dt' as θ̇" in verdict.parsed["notes"]


def test_equations_and_systems_read_it_too(ns):
    eq = parse_equation("d²θ/dt² = -g/l sin θ", ns)
    assert eq.lhs == ns.symbol("thetaddot") and "read 'd²θ/dt²' as θ̈" in eq.notes
    first, second = parse_system("dx/dt = x2dot; d/dt(θ) = x1dot / l", ns)
    assert first.lhs == ns.symbol("xdot") and second.lhs == ns.symbol("thetadot")


def test_the_derivative_token_spans_exactly_the_typed_text(ns):
    text = "m + \\frac{d^2\\theta}{dt^2} l"
    tokens = read_leibniz(tokenize(text), ns, text)
    derivative = next(t for t in tokens if t.kind == "derivative")
    assert (derivative.pos, derivative.end) == (4, 26)
    assert text[derivative.pos:derivative.end] == derivative.text == "\\frac{d^2\\theta}{dt^2}"
    assert [t.kind for t in tokens] == ["name", "op", "derivative", "name", "end"]


@pytest.mark.parametrize("text", ["m*l*thetadot^2", "dot(theta) + ddot(x)", "sin(θ)/l", "x1dot - x2dot"])
def test_text_without_leibniz_keeps_its_very_tokens(ns, text):
    tokens = tokenize(text)
    assert read_leibniz(tokens, ns, text) is tokens


@pytest.mark.parametrize("text", [
    "d²θ/dt²", "d^2θ/dt^2", r"\frac{d^2\theta}{dt^2}", "d/dt θ̇", "d(θ̇)/dt",
])
def test_a_missing_derivative_is_refused_as_the_dot_notation_refuses_it(text):
    no_acceleration = Namespace([Variable("theta", "angle"), Variable("thetadot", "angular_velocity")])
    with pytest.raises(ExpressionError) as dots:
        parse_expression("θ̈", no_acceleration)
    with pytest.raises(ExpressionError) as leibniz:
        parse_expression(text, no_acceleration)
    err = leibniz.value
    assert (err.code, err.hint) == (dots.value.code, dots.value.hint)
    assert err.position == 0 and "but this problem has no variable thetaddot" in err.message


# -- ambiguity: the Leibniz reading only ever replaces text that means nothing today -------------

@pytest.mark.parametrize("declared, text, same_as", [
    # with d and t declared, d x/d t is the quotient of products (as it always was)
    ([Variable("d", "length"), Variable("t", "time")], "d x/d t", "d*x/d*t"),
    ([Variable("d", "length"), Variable("t", "time")], "dx/dt", "d*x/d*t"),
    ([Variable("d", "length"), Variable("t", "time")], "dθ/dt", "d*theta/d*t"),
    ([Variable("d", "length"), Variable("t", "time")], r"\frac{d\theta}{dt}", "d*theta/(d*t)"),
    ([Variable("d", "length"), Variable("t", "time")], "d/dt θ", "d/d*t*theta"),
    # a declared dtheta (dt) is that variable
    ([Variable("dtheta", "angle"), Variable("dt", "time")], "dθ/dt", "dtheta/dt"),
    ([Variable("dx", "length"), Variable("dt", "time")], "dx/dt", "dx/dt"),
])
def test_declared_names_keep_their_meaning(declared, text, same_as):
    ns = _ns(*declared)
    parsed = parse_expression(text, ns)
    assert parsed.expr == parse(same_as, ns)
    assert not any("as θ̇" in note or "as ẋ" in note for note in parsed.notes)


@pytest.mark.parametrize("declared, text, unknown", [
    ([Variable("d", "length")], "dx/dt", "dt"),           # d is a length: dt means nothing, as before
    ([Variable("d", "length")], "d x/d t", "t"),
    ([Variable("dt", "time")], "dx/dt", "dx"),            # dt is a time step: dx means nothing, as before
    ([Variable("dt", "time")], r"\frac{d\theta}{dt}", "d"),
    ([], "dθ/dx", "dθ"),                                  # only derivatives by the time t
    ([], "dy/dx", "dy"),
    ([], "dq/dt", "dq"),                                  # no coordinate q and no qdot: not a derivative
    ([], "delta/dt", "delta"),                            # a spelled-out δ is not d·elta
])
def test_without_the_leibniz_reading_the_old_error_stands(declared, text, unknown):
    with pytest.raises(ExpressionError) as caught:
        parse_expression(text, _ns(*declared))
    assert caught.value.code == "unknown_name" and f"'{unknown}'" in caught.value.message


@pytest.mark.parametrize("text, name", [("dθ/dt", "thetadot"), ("d x/d t", "xdot"), ("d²x/dt²", "xddot"),
                                        (r"\frac{d}{dt}\theta", "thetadot")])
def test_a_declared_time_t_is_fine(text, name):
    ns = _ns(Variable("t", "time", "nonnegative", "time"))
    assert parse(text, ns) == ns.symbol(name)


@pytest.mark.parametrize("text, position", [("dθ/dt", 3), ("d x/d t", 6), ("d/dt θ", 2), (r"\frac{d\theta}{dt}", 15)])
def test_a_t_that_is_not_the_time_is_refused(text, position):
    with pytest.raises(ExpressionError) as caught:
        parse_expression(text, _ns(Variable("t", "length", "positive")))
    err = caught.value
    assert err.position == position and "a length (m), not the time" in err.message
    assert "dot" in err.hint


@pytest.mark.parametrize("text, named, fix, code", [
    ("d²θ/dt", "'d²θ/dt' has d² on top but dt below", "d²θ/dt²", "syntax"),
    ("dθ/dt²", "'dθ/dt²' has d on top but dt² below", "(dθ/dt)²", "syntax"),
    ("d^2x/dt", "'d^2x/dt' has d² on top but dt below", "d²x/dt²", "syntax"),
    (r"\frac{d^2\theta}{dt}", r"'\frac{d^2\theta}{dt}' has d² on top", "d²", "syntax"),
    ("d²/dt θ", "'d²/dt' has d² on top but dt below", "d²/dt²", "syntax"),
    ("d³θ/dt³", "'d³θ/dt³' is a third or higher time derivative", "at most two dots", "unknown_name"),
    ("d/dt θ^2", "'d/dt θ^2' is ambiguous", "(dθ/dt)^2", "ambiguous"),
    ("d/dt θ²", "'d/dt θ²' is ambiguous", "(dθ/dt)^2", "ambiguous"),
    ("d/dt(θ)^2", "'d/dt(θ)^2' is ambiguous", "(dθ/dt)^2", "ambiguous"),
    (r"\frac{d}{dt}\theta^{2}", r"'\frac{d}{dt}\theta^{2}' is ambiguous", r"(d\theta/dt)^2", "ambiguous"),
    ("d/dt θ x", "'d/dt θ x' is ambiguous", "(dθ/dt)·x", "ambiguous"),
    ("d/dt(dθ/dt)^2", "'d/dt(dθ/dt)^2' is ambiguous", "(d/dt(dθ/dt))^2", "ambiguous"),
    ("d/dt(d/dt(d/dt(θ)))", "'d/dt(d/dt(d/dt(θ)))' is a third or higher", "at most two dots", "unknown_name"),
    ("d/dt(d²θ/dt)", "'d²θ/dt' has d² on top but dt below", "d²θ/dt²", "syntax"),
    ("d/dt m", "m is a constant of this problem, so its time derivative ('d/dt m') is 0", "leave the term out",
     "unknown_name"),
])
def test_every_refusal_names_the_text_and_the_fix(ns, text, named, fix, code):
    with pytest.raises(ExpressionError) as caught:
        parse_expression(text, ns)
    err = caught.value
    assert named in err.message and fix in err.hint and err.code == code


# -- \frac d{dt}: the unbraced numerator, one letter as TeX reads it ------------------------------

@pytest.mark.parametrize("text, name", [
    (r"\frac d{dt}\theta", "thetadot"),
    (r"\frac d {dt} \theta", "thetadot"),
    (r"\frac d{dt}(\theta)", "thetadot"),
    (r"\frac d{dt}\left(\theta\right)", "thetadot"),
    (r"\frac d{d t}x", "xdot"),
    (r"\dfrac d{dt}\dot{\theta}", "thetaddot"),
    (r"\frac d{dt}\left(\frac{d\theta}{dt}\right)", "thetaddot"),
    (r"\frac d{dt}(\frac d{dt}\theta)", "thetaddot"),
    (r"\frac{d}{dt}\theta", "thetadot"),                     # the braced forms, for comparison
    (r"\frac{d}{dt}(\theta)", "thetadot"),
])
def test_an_unbraced_d_over_a_braced_dt_reads_as_the_braced_form(ns, text, name):
    parsed = parse_expression(text, ns)
    assert parsed.expr == ns.symbol(name)
    assert parsed.notes == [f"read '{text}' as {dotted(name)}"]


@pytest.mark.parametrize("text, named, fix, code", [
    (r"\frac{d}dt\theta", r"'\frac{d}dt' needs braces around dt", r"\frac{d}{dt}", "syntax"),
    (r"\frac d dt\theta", r"'\frac d dt' needs braces around dt", r"\frac{d}{dt}", "syntax"),
    (r"\frac d{dt^2}\theta", r"'\frac d{dt^2}' has d on top but dt² below", "d²/dt²", "syntax"),
    (r"\frac d{dt}\theta^2", r"'\frac d{dt}\theta^2' is ambiguous", r"(d\theta/dt)^2", "ambiguous"),
    (r"\frac d{dt}m", r"m is a constant of this problem, so its time derivative ('\frac d{dt}m') is 0",
     "leave the term out", "unknown_name"),
])
def test_unbraced_leibniz_refusals_name_the_text_and_the_fix(ns, text, named, fix, code):
    with pytest.raises(ExpressionError) as caught:
        parse_expression(text, ns)
    err = caught.value
    assert named in err.message and fix in err.hint and err.code == code


@pytest.mark.parametrize("declared, text, same_as", [
    ([Variable("d", "length"), Variable("t", "time")], r"\frac d{dt}\theta", "d/(d*t)*theta"),
    ([Variable("d", "length"), Variable("t", "time")], r"\frac{d}dt\theta", "d/d*t*theta"),
])
def test_a_declared_d_keeps_the_unbraced_frac_a_quotient(declared, text, same_as):
    ns = _ns(*declared)
    assert parse(text, ns) == parse(same_as, ns)


def test_errors_point_into_the_text_as_typed(ns):
    text = "m l + d²θ/dt"
    with pytest.raises(ExpressionError) as caught:
        parse_expression(text, ns)
    assert caught.value.position == text.index("d²")


def test_an_earlier_error_is_reported_first(ns):
    with pytest.raises(ExpressionError) as caught:
        parse_expression("q + d²θ/dt", ns)
    assert caught.value.position == 0 and caught.value.code == "unknown_name"


def test_a_remembered_parse_keeps_its_note(ns):
    first = parse_expression("dθ/dt", ns)
    again = parse_expression("dθ/dt", ns)
    assert again.notes == first.notes == ["read 'dθ/dt' as θ̇"]


@pytest.mark.parametrize("name, shown", [("thetadot", "θ\u0307"), ("xddot", "x\u0308"), ("theta1dot", "θ\u0307₁"),
                                         ("x_2ddot", "x\u0308₂"), ("Omegadot", "Ω\u0307"),
                                         ("lambda_surfacedot", "lambda_surface\u0307")])
def test_dotted_spells_the_derivative_as_students_see_it(name, shown):
    assert dotted(name) == shown


HOSTILE = [
    "dθ/dt*" * 330 + "1",                  # many matches: each d-word is looked up once per text
    "d²θ/dt²+" * 220 + "1",
    "d x/d t " * 240,
    "dq/dt+" * 330,                          # unknown words, each a search for suggestions if not kept
    "d/dt " * 390,                           # the first refusal ends the pass
    r"\frac{d}{dt}" * 160,
    r"\frac d{dt}" * 160,
    "d/dt(" * 50 + "θ" + ")" * 50,
    "(dθ/dt)^" * 240 + "2",
    "d" + "θ" * 1990 + "/dt",
    "d" * 1999,
]


@pytest.mark.parametrize("text", HOSTILE, ids=[f"hostile{i}" for i in range(len(HOSTILE))])
def test_hostile_leibniz_input_is_handled_quickly(ns, text):
    start = time.perf_counter()
    try:
        parse(text[:2000], ns)
    except ExpressionError:
        pass
    assert time.perf_counter() - start < 0.5


# -- d/dt of an expression: the chain rule through the declared derivatives ----------------------

@pytest.mark.parametrize("text, same_as", [
    ("d/dt(θ^2)", "2*theta*thetadot"),
    ("d/dt(m l θ)", "m*l*thetadot"),                          # m, l: parameters, constant
    ("d/dt(m l^2 θ̇)", "m*l**2*thetaddot"),
    ("d/dt(m l^2 dθ/dt)", "m*l**2*thetaddot"),
    ("d/dt(x θ)", "xdot*theta + x*thetadot"),
    ("d/dt(m (ẋ + l θ̇ cos θ))", "m*(xddot + l*thetaddot*cos(theta) - l*thetadot**2*sin(theta))"),
    ("d/dt(sin θ)", "cos(theta)*thetadot"),
    ("d²/dt²(x θ)", "xddot*theta + 2*xdot*thetadot + x*thetaddot"),
    ("2 d/dt(x^2)/x", "4*xdot"),
    ("d/dt[x θ]", "xdot*theta + x*thetadot"),
    (r"\frac{d}{dt}\left(m l^2\dot\theta\right)", "m*l**2*thetaddot"),
    (r"\frac d{dt}(m\theta)", "m*thetadot"),
])
def test_d_dt_of_an_expression_is_its_total_time_derivative(ns, text, same_as):
    parsed = parse_expression(text, ns)
    assert parsed.expr - parse_expression(same_as, ns).expr == 0 or \
        (parsed.expr - parse_expression(same_as, ns).expr).expand() == 0
    assert any(note.startswith("read '") for note in parsed.notes)


@pytest.mark.parametrize("text, same_as, shown", [
    # the quotient form, as F = d(mv)/dt and the Euler–Lagrange equation are written by hand
    ("d(m l^2 θ̇)/dt", "m*l**2*thetaddot", "d(m l^2 θ̇)/dt"),
    ("d[x θ]/dt", "xdot*theta + x*thetadot", "d[x θ]/dt"),
    ("d²(x θ)/dt²", "xddot*theta + 2*xdot*thetadot + x*thetaddot", "d²(x θ)/dt²"),
    ("d^2(x θ)/dt^2", "xddot*theta + 2*xdot*thetadot + x*thetaddot", "d^2(x θ)/dt^2"),
    (r"\frac{d(ml^2\dot\theta)}{dt}", "m*l**2*thetaddot", r"\frac{d(ml^2\dot\theta)}{dt}"),
    (r"\frac{\mathrm{d}(m x)}{\mathrm{d}t}", "m*xdot", r"\frac{\mathrm{d}(m x)}{\mathrm{d}t}"),
    ("(d/dt)(m l^2 θ̇)", "m*l**2*thetaddot", "(d/dt)(m l^2 θ̇)"),
    ("2 d(x^2)/dt/x", "4*xdot", "d(x^2)/dt"),
])
def test_the_quotient_form_of_d_dt_of_an_expression_is_the_same_derivative(ns, text, same_as, shown):
    parsed = parse_expression(text, ns)
    assert (parsed.expr - parse_expression(same_as, ns).expr).expand() == 0
    assert any(note.startswith(f"read '{shown}'") for note in parsed.notes), parsed.notes


@pytest.mark.parametrize("text, named", [
    ("d(x θ)/dt²", "has d on top but dt² below"),
    (r"\frac{d(x\theta)}{dt^2}", "has d on top but dt² below"),
])
def test_the_quotient_form_is_refused_as_the_operator_form_is(ns, text, named):
    with pytest.raises(ExpressionError) as error:
        parse_expression(text, ns)
    assert named in str(error.value)


def test_a_declared_d_keeps_the_quotient_form_a_product():
    ns = _ns(Variable("d", "length", "positive"), Variable("t", "time", "positive"))
    assert parse_expression("d(x + l)/t", ns).expr == parse_expression("d*(x + l)/t", ns).expr


def test_d_dt_of_an_expression_with_a_declared_time_differentiates_it_too():
    ns = _ns(Variable("t", "time", "real", "time"), Variable("w", "angular_velocity", "positive"))
    assert parse_expression("d/dt(l cos(w t))", ns).expr == parse_expression("-l w sin(w t)", ns).expr


@pytest.mark.parametrize("text, named, fix, code", [
    ("d/dt(m ẍ)", "'d/dt' needs the time derivative of xddot", "with dots", "unknown_name"),
    ("d/dt(m θ̇₁)", "'d/dt' needs the time derivative of theta1dot", "with dots", "unknown_name"),
    ("d/dt(x θ)^2", "'d/dt(x θ)^2' is ambiguous", "(d/dt(x θ))^2", "ambiguous"),
    ("d/dt(x θ)²", "'d/dt(x θ)²' is ambiguous", "(d/dt(x θ))^2", "ambiguous"),
    ("d/dt(m sign(x) ẋ)", "'d/dt' is applied to something with no derivative everywhere", "with dots", "syntax"),
])
def test_d_dt_of_an_expression_is_refused_where_a_derivative_is_missing_or_the_power_is_ambiguous(ns, text, named,
                                                                                                  fix, code):
    with pytest.raises(ExpressionError) as caught:
        parse_expression(text, ns)
    err = caught.value
    assert named in err.message and fix in err.hint and err.code == code


@pytest.mark.parametrize("text", [
    "d²/dt²(" + "".join(f"(x + {i} l)" for i in range(1, 40)) + ")",
    "d/dt(" + "".join(f"(x + {i} l)" for i in range(1, 80)) + ")",
])
def test_d_dt_of_a_long_product_is_refused_at_once(ns, text):
    # the product rule multiplies the size by the product's length at each order: minutes, unchecked
    started = time.monotonic()
    with pytest.raises(ExpressionError) as caught:
        parse_expression(text, ns)
    assert time.monotonic() - started < 0.5
    assert caught.value.code == "too_large" and "with dots" in caught.value.hint


@pytest.mark.parametrize("text, shown, position", [
    ("d/dt(g)", "('d/dt(g)') ", 0), ("dg/dt", "('dg/dt') ", 0), (r"\frac{dg}{dt}", r"('\frac{dg}{dt}') ", 0),
    ("ġ", "('ġ') ", 0), ("g'", "('g'') ", 0), (r"\dot{g}", "", 5), ("dot(g)", "", 4), ("d²l/dt²", "('d²l/dt²') ", 0),
    ("m l^2 θ̈ + d/dt(l) θ̇", "('d/dt(l)') ", 11),  # (θ̈ is two code points)
])
def test_a_parameters_time_derivative_is_refused_saying_it_is_constant(ns, text, shown, position):
    # not "this problem has no variable gdot": g is constant, so its derivative is 0, and the student may have
    # meant g itself (a stray dot over θ in an editor); a CAS's diff(l, t) still computes 0
    with pytest.raises(ExpressionError) as caught:
        parse_expression(text, ns)
    error = caught.value
    assert f"a constant of this problem, so its time derivative {shown}is 0" in error.message, error.message
    assert error.position == position and "leave the term out" in error.hint


def test_a_parameter_with_a_declared_rate_is_not_constant():
    ns = _ns(Variable("L", "length", "positive"), Variable("Ldot", "velocity"))
    assert str(parse_expression("dL/dt", ns).expr) == "Ldot"


# WIRIS / MathType brace a base before its power: {d}^{2} and d{t}^{2}.
@pytest.mark.parametrize("text, name", [
    (r"\frac{{d}^{2}\theta }{d{t}^{2}}", "thetaddot"),
    (r"\frac{{\mathrm{d}}^{2}\theta }{\mathrm{d}{t}^{2}}", "thetaddot"),
    (r"\frac{{d}^{2}\mathrm{\theta }}{d{t}^{2}}", "thetaddot"),
    (r"\frac{{d}^{2}x}{d{t}^{2}}", "xddot"),
    (r"\frac{{d}^{2}}{d{t}^{2}}\theta ", "thetaddot"),
    (r"\frac{{d}^{2}}{d{t}^{2}}\left(x\right)", "xddot"),
    (r"{d}^{2}\theta /d{t}^{2}", "thetaddot"),
    (r"{d}^{2}x/d{t}^{2}", "xddot"),
])
def test_the_braced_bases_of_wiris_are_leibniz_too(ns, text, name):
    parsed = parse_expression(text, ns)
    assert parsed.expr == ns.symbol(name)


@pytest.mark.parametrize("text, top, below", [
    (r"\frac{{d}^{2}\theta }{dt}", "d²", "dt below"),
    (r"\frac{d\theta }{d{t}^{2}}", "d on top", "dt²"),
])
def test_wiris_braced_orders_that_disagree_are_refused(ns, text, top, below):
    with pytest.raises(ExpressionError) as error:
        parse_expression(text, ns)
    assert top in str(error.value) and below in str(error.value)


def test_braced_bases_keep_their_meaning_when_d_is_declared():
    declared = Namespace([Variable("d", "length", "positive"), Variable("t", "time", "positive"),
                          Variable("x", "length", "positive")])
    d, t, x = (declared.symbol(n) for n in "dtx")
    assert parse(r"\frac{{d}^{2}x}{d{t}^{2}}", declared) == d * x / t**2
    # a command's braced argument before a power is not unbraced: \sqrt{x}^{2} is (√x)², not √(x²)
    assert parse(r"\frac{{d}^{2}\theta }{d{t}^{2}} + \sqrt{x}^{2}", _ns()) == \
        _ns().symbol("thetaddot") + _ns().symbol("x")


@pytest.mark.parametrize("text, name", [
    # ASCIIMath's fraction of two bracketed arguments (MathJax, Moodle, WeBWorK, Canvas)
    ("frac(d theta)(dt)", "thetadot"), ("frac(d^2 theta)(dt^2)", "thetaddot"), ("frac(d^2x)(dt^2)", "xddot"),
    ("frac(d theta_1)(d t)", "theta1dot"), ("frac(d)(dt)(x)", "xdot"), ("frac(d^2)(dt^2)(theta)", "thetaddot"),
])
def test_asciimath_fraction_of_differentials_is_the_dotted_variable(ns, text, name):
    assert parse_expression(text, ns).expr == ns.symbol(name)


@pytest.mark.parametrize("text, words", [
    ("frac(d^2 theta)(dt)", "d² on top but dt below"),
    ("frac(d theta)(dt^2)", "on top but dt² below"),
])
def test_asciimath_fraction_of_unequal_differentials_is_refused_by_name(ns, text, words):
    with pytest.raises(ExpressionError) as refused:
        parse_expression(text, ns)
    assert words in refused.value.message and text in refused.value.message


@pytest.mark.parametrize("text, name", [
    # the derivative of a dotted variable in LaTeX, as dθ̇/dt typed is
    (r"\frac{d\dot\theta}{dt}", "thetaddot"), (r"\frac{d\dot{\theta}}{dt}", "thetaddot"),
    (r"\frac{d \dot{x}}{d t}", "xddot"), (r"\frac{\mathrm{d}\dot{\theta}}{\mathrm{d}t}", "thetaddot"),
    (r"d\dot{x}/dt", "xddot"), (r"(d\dot x)/(dt)", "xddot"),
    # TeX's \mathrm takes one letter without braces: \mathrm dt is \mathrm{d}t
    (r"\frac{\mathrm d\theta}{\mathrm dt}", "thetadot"), (r"\frac{\mathrm d^2\theta}{\mathrm dt^2}", "thetaddot"),
    (r"\mathrm d\theta/\mathrm dt", "thetadot"), (r"\frac{\mathrm d}{\mathrm dt}\theta", "thetadot"),
    (r"\frac{\mathrm d\dot x}{\mathrm dt}", "xddot"),
])
def test_a_dotted_variable_and_an_unbraced_mathrm_d_in_latex_leibniz(ns, text, name):
    assert parse(text, ns) == ns.symbol(name)


def test_the_orders_of_a_dotted_variables_derivative_must_agree(ns):
    with pytest.raises(ExpressionError, match=r"has d on top but dt² below") as err:
        parse(r"\frac{d\dot x}{dt^2}", ns)
    assert r"d\dot{x}/dt" in err.value.hint


# -- red team 22: UnicodeMath's differential d (Word's \dd), ⅆ --

@pytest.mark.parametrize("text, name", [("ⅆθ/ⅆt", "thetadot"), ("ⅆ𝜃/ⅆ𝑡", "thetadot"), ("(ⅆ^2 𝜃)/(ⅆ𝑡^2 )", "thetaddot"),
                                        ("ⅆ^2 θ/ⅆt^2", "thetaddot"), ("ⅆx/ⅆt", "xdot")])
def test_word_s_differential_d_is_a_leibniz_d(ns, text, name):
    # ⅆ was "character 'ⅆ' (DOUBLE-STRUCK ITALIC SMALL D) is not allowed", as ⅇ was before it read as e
    assert parse(text, ns) == parse(name, ns)
