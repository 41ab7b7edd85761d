"""Evaluation at a point: balls that contain the truth, and undefined points named, never crashing."""

import math

import flint
import pytest
import sympy

from grader.answers.evaluate import (
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
