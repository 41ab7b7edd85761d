"""Answers in their variables (grader.mechanics.answers): velocities removed with the first integrals,
and values along the motion in time."""

from __future__ import annotations

import sympy

from grader.expressions import parse_expression
from grader.mechanics.lagrange import derive
from grader.mechanics.scene import load_scene
from tests.mechanics.conftest import SCENES


def _expected(scene, text: str) -> sympy.Expr:
    return parse_expression(text, scene.namespace).expr


def test_a_start_at_rest_on_an_unstable_equilibrium_moves_the_way_it_is_pushed():
    """A disk on top of a cylinder, θ = 0, θ̇ = 0, θ̈ = 0: where it leaves (cos θ = 4/7, found pushing it
    forwards) its centre moves at +√(4 g (R + a)/7); θ̇ at an odd power was refused ('the motion from
    [initial] does not fix its sign') although the root itself was found with that push."""
    scene = load_scene(SCENES / "disk_rolling_off_cylinder.toml")
    value = derive(scene).answers["speed_at_separation"]
    assert sympy.simplify(value - _expected(scene, "sqrt(4*g*(R + a)/7)")) == 0


def test_a_value_in_time_may_pass_through_a_parameter_that_cancels_along_the_motion():
    """The block of a yo-yo's counterweight rises y1 − R φ: R cancels only once y1(t) and φ(t) are
    substituted (it was refused as 'still depends on R')."""
    scene = load_scene(SCENES / "yoyo_counterweight.toml")
    value = derive(scene).answers["block_height_in_time"]
    assert sympy.simplify(value - _expected(scene, "g*(M - 3*m)*t^2/(2*(M + 3*m))")) == 0
