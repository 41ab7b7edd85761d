"""Evaluation at a point: balls that contain the truth, and undefined points named, never crashing."""

import math

import flint
import pytest
import sympy

from grader.answers.evaluate import (
    _log2_mag,
    SCALE,
    ArbBackend,
    FloatBackend,
    MpmathBackend,
    Undefined,
    Unresolved,
    Unsupported,
    compile_expr,
)

theta = sympy.Symbol("theta", real=True)
x = sympy.Symbol("x", real=True)


def arb_at(expr, point, prec=128):
    with flint.ctx.workprec(prec):
        env = {s: flint.arb(v) for s, v in point.items()}
        env[SCALE] = -math.inf
        return compile_expr(expr, ArbBackend())(env)


def test_one_minus_cos_at_a_tiny_angle_is_exact_in_balls_but_zero_in_float64():
    # 1 - cos(1e-8) = 5e-17: float64 cancels every digit, ball arithmetic keeps them
    f = compile_expr(1 - sympy.cos(theta), FloatBackend())
    assert f({theta: 1e-8, SCALE: 0.0}) == 0.0
    value = arb_at(1 - sympy.cos(theta), {theta: 1e-8}, prec=256)
    with flint.ctx.workprec(256):
        t = flint.arb(1e-8)
        assert t**2 / 2 - t**4 / 24 < value < t**2 / 2  # Taylor's bounds: every digit is right
    assert value.rel_accuracy_bits() > 40


@pytest.mark.parametrize("expr, value, reason", [
    (sympy.log(x), -1.0, "logarithm"),
    (sympy.sqrt(x), -2.0, "square root"),
    (1 / x, 0.0, "division by zero"),
    (sympy.asin(x), 2.0, "asin"),
    (x ** sympy.Rational(1, 3), -8.0, "negative"),
    (sympy.atan2(x, x), 0.0, "atan2"),
])
@pytest.mark.parametrize("backend", [ArbBackend(), FloatBackend(), MpmathBackend()], ids=lambda b: b.name)
def test_undefined_points_are_named(expr, value, reason, backend):
    f = compile_expr(expr, backend)
    env = {x: backend.point(value), SCALE: -math.inf}
    with pytest.raises(Undefined, match=reason):
        if backend.name == "arb":
            with flint.ctx.workprec(64):
                f(env)
        else:
            f(env)


def test_a_ball_straddling_a_pole_is_unresolved_not_undefined():
    with flint.ctx.workprec(64):
        f = compile_expr(1 / (sympy.cos(theta)), ArbBackend())
        with pytest.raises(Unresolved):
            f({theta: flint.arb.pi() / 2, SCALE: -math.inf})


@pytest.mark.parametrize("expr", [sympy.zoo, sympy.Function("f")(x), sympy.gamma(x), sympy.I * x])
def test_anything_outside_real_elementary_functions_is_unsupported(expr):
    with pytest.raises(Unsupported):
        compile_expr(expr, ArbBackend())


def test_scale_records_the_largest_term_added():
    # m*g*(sin^2 + cos^2 - 1) is zero, but its terms are of size 1: that is the cancellation scale
    env_value = arb_at(sympy.sin(theta) ** 2 + sympy.cos(theta) ** 2 - 1, {theta: 0.7})
    assert env_value.contains(0)


# -- fuzzing: every registered function and number form, in every backend ------------------------
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from grader.answers.equivalence import Options, compare_expressions  # noqa: E402
from grader.answers.sampling import Sampler  # noqa: E402
from grader.expressions import ExpressionError, Namespace, parse_expression  # noqa: E402
from grader.expressions.functions import FUNCTIONS  # noqa: E402

FUZZ_NAMESPACE = Namespace.from_spec({"x": {"domain": "real"}, "y": {"domain": "positive"},
                                      "z": {"domain": [-1, 1]}, "w": {"domain": [5, "inf"]}})
NUMBERS = ["0", "1", "2", "-3", "0.5", "0.1", "2.75", "1.5e-3", "1e2", "3/4", "-0.25", "pi", "e", "E", "10^-3"]
LEAVES = st.sampled_from(NUMBERS + ["x", "y", "z", "w"])


def _call(name, args):
    spec = FUNCTIONS[name]
    if spec.min_args == 2:
        return f"{name}({args[0]}, {args[1]})"
    return f"{name}({args[0]})" if name != "sqrt" else f"sqrt({args[0]})"


TEXTS = st.recursive(
    LEAVES,
    lambda inner: st.one_of(
        st.builds(_call, st.sampled_from(sorted(FUNCTIONS)), st.lists(inner, min_size=2, max_size=2)),
        st.builds(lambda a, op, b: f"({a}) {op} ({b})", inner, st.sampled_from("+-*/"), inner),
        st.builds(lambda a, p: f"({a})^({p})", inner, st.sampled_from(["2", "-1", "0.5", "1/3", "1.5", "x", "-2"])),
        st.builds(lambda a, offset: f"{a} + {offset}", inner, st.sampled_from(["0.5", "1e-3", "2.5", "-0.125"])),
    ),
    max_leaves=8,
)
FUZZ_SAMPLER = Sampler({v.symbol: v.domain for v in FUZZ_NAMESPACE.variables}, seed=11)
BACKENDS = [ArbBackend(), FloatBackend(), MpmathBackend()]


def _parse_or_none(text):
    try:
        return parse_expression(text, FUZZ_NAMESPACE)
    except ExpressionError:
        return None  # the parser's own fuzzer checks what it refuses


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(TEXTS)
def test_every_parsed_expression_compiles_and_evaluates_or_is_undefined_in_every_backend(text):
    """A valid text never makes the evaluator raise anything but Undefined/Unresolved (no TypeError)."""
    parsed = _parse_or_none(text)
    if parsed is None:
        return
    for backend in BACKENDS:
        f = compile_expr(parsed.expr, backend)  # never Unsupported: the grammar builds only what it knows
        for i in range(3):
            env = {s: backend.point(v) for s, v in FUZZ_SAMPLER.point(i).items()}
            env[SCALE] = -math.inf
            try:
                with flint.ctx.workprec(64):
                    f(env)
            except (Undefined, Unresolved):
                pass


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(TEXTS, TEXTS)
def test_comparing_any_two_valid_texts_gives_a_comparison(reference, answer):
    r, a = _parse_or_none(reference), _parse_or_none(answer)
    if r is None or a is None:
        return
    c = compare_expressions(r.expr, a.expr, FUZZ_SAMPLER, Options(points=3, max_bits=512),
                            answer_conditions=a.conditions, reference_conditions=r.conditions)
    assert c.equivalent in (True, False, None) and c.reason


# -- red team 2026-11-10b: constants beyond the largest float -------------------------------------

@pytest.mark.parametrize("constant", [sympy.Integer(10) ** 400, sympy.Integer(-3) * sympy.Integer(10) ** 308,
                                      sympy.Rational(10 ** 400, 3)])
def test_a_float64_constant_beyond_the_largest_float_is_undefined_where_evaluated(constant):
    t = sympy.Symbol("t")
    f = compile_expr(constant * t + 1, FloatBackend())  # compiling does not raise
    with pytest.raises(Undefined):
        f({t: 2.0})


def test_a_float64_rational_of_huge_integers_is_its_correctly_rounded_value():
    f = compile_expr(sympy.Rational(10 ** 400 + 1, 4 * 10 ** 399), FloatBackend())
    assert f({}) == 2.5


def _exact_log2_mag(x) -> float:
    # The definition: the upper bound's mantissa and exponent, as integers.
    u = x.abs_upper()
    if u.is_zero():
        return -math.inf
    if not u.is_finite():
        return math.inf
    man, exp = u.man_exp()
    return float(int(exp) + int(man).bit_length())


@pytest.mark.parametrize("prec", [53, 132, 1024, 4096])
@pytest.mark.parametrize("make", [
    lambda: flint.arb(2) ** 40,                                      # a power of two: its own exponent
    lambda: flint.arb(2) ** 40 - flint.arb(2) ** -20,                # just below one: rounds up to it as a float
    lambda: flint.arb(2) ** -30 - flint.arb(2) ** -3000,             # (at every precision that holds it)
    lambda: -(flint.arb(2) ** 7 - flint.arb(2) ** -200),
    lambda: flint.arb(3).sqrt() * flint.arb(2) ** 1000,
    lambda: flint.arb(3).sqrt() * flint.arb(2) ** 1100,              # beyond the floats
    lambda: flint.arb(3).sqrt() * flint.arb(2) ** -1100,             # below their normal range
    lambda: flint.arb(0),
    lambda: flint.arb(1.5, 2.0 ** -60),                              # a ball: its upper bound counts
    lambda: (flint.arb(2).sqrt() * flint.arb(5).log()).rad(),
])
def test_a_balls_log2_magnitude_is_its_upper_bounds_exponent(prec, make):
    # _log2_mag reads the exponent from the bound's float where that cannot be off by one
    with flint.ctx.workprec(prec):
        x = make()
        assert _log2_mag(x) == _exact_log2_mag(x)
