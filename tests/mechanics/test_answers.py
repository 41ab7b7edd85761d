"""Answers in their variables (grader.mechanics.answers): velocities removed with the first integrals,
and values along the motion in time."""

from __future__ import annotations

import pytest
import sympy

from grader.expressions import parse_expression
from grader.mechanics.lagrange import derive
from grader.mechanics.scene import SceneError, load_scene, parse_scene
from tests.mechanics.conftest import ROOT, SCENES


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


def _with_answer_in(path, name: str, in_terms_of: str) -> str:
    """The scene's text with the answer ``name`` asked in other variables."""
    text = path.read_text(encoding="utf-8")
    start = text.index(f'name = "{name}"')
    line = text.index("in_terms_of = ", start)
    end = text.index("\n", line)
    return text[:line] + f"in_terms_of = {in_terms_of}" + text[end:]


@pytest.mark.parametrize("path, name, in_terms_of, expected", [
    # Hemisphere in Cartesian coordinates, the answers in x: N = m g (3√(R² − x²) − 2R)/R is, with
    # the height y = √(R² − x²), m g (3y − 2R)/R (it was "'y' is not an independent variable").
    (SCENES / "hemisphere_cartesian.toml", "normal_force", '["m", "g", "R", "y"]', "m*g*(3*y - 2*R)/R"),
    (SCENES / "hemisphere_cartesian.toml", "normal_force", '["m", "g", "R", "x"]', "m*g*(3*sqrt(R^2 - x^2) - 2*R)/R"),
    # Pendulum parametrized by θ: T = m g (3 cos θ − 2 cos θ0), and y = −l cos θ below the pivot.
    (ROOT / "problems" / "pendulum.toml", "tension", '["m", "g", "l", "y", "theta0"]',
     "-m*g*(3*y/l + 2*cos(theta0))"),
])
def test_an_answer_may_be_asked_in_a_coordinate_the_constraints_made_dependent(path, name, in_terms_of, expected):
    """The answer is written in the independent coordinate, then the dependent one read back through
    its map: every solution of Φ(u) = c gives one value (x = ±√(R² − y²) in an even function)."""
    text = _with_answer_in(path, name, in_terms_of)
    scene = parse_scene(text, source=path.name)
    value = derive(scene).answers[name]
    assert sympy.simplify(value - _expected(scene, expected)) == 0


@pytest.mark.parametrize("name, in_terms_of, expected", [
    # On the circle x² + y² = R², v² = ẋ² + ẏ² = R² ẋ²/y² = R² ẏ²/x², and N = m g y/R − m v²/R
    # (outwards); ẍ = g x y/R² − x v²/R². Each written by hand in the variables asked.
    ("normal_force_state", '["m", "g", "R", "y", "ydot"]', "m*g*y/R - m*R*ydot^2/(R^2 - y^2)"),
    ("normal_force_state", '["m", "g", "R", "x", "ydot"]', "m*g*sqrt(R^2 - x^2)/R - m*R*ydot^2/x^2"),
    ("normal_force_state", '["m", "g", "R", "y", "xdot"]', "m*g*y/R - m*R*xdot^2/y^2"),
    ("horizontal_acceleration", '["g", "R", "x", "ydot"]', "g*x*sqrt(R^2 - x^2)/R^2 - ydot^2/x"),
    # ẏ named beside ẋ: the answer in ẋ needs none of it.
    ("horizontal_acceleration", '["g", "R", "x", "xdot", "ydot"]', "g*x*sqrt(R^2 - x^2)/R^2 - x*xdot^2/(R^2 - x^2)"),
])
def test_an_answer_may_be_asked_in_the_velocity_of_a_dependent_coordinate(name, in_terms_of, expected):
    """ẏ stands for the ẋ it leaves out: ẏ = −x ẋ/y on the hemisphere, solved for ẋ, then the
    position read back as for a dependent coordinate (it was "'ydot' is not an independent variable")."""
    path = SCENES / "hemisphere_cartesian.toml"
    scene = parse_scene(_with_answer_in(path, name, in_terms_of), source=path.name)
    value = derive(scene).answers[name]
    assert sympy.simplify(value - _expected(scene, expected)) == 0


@pytest.mark.parametrize("in_terms_of", [
    '["g", "R", "ydot"]',       # no position at all: x is left over
    '["g", "R", "y", "ydot"]',  # ẍ is odd in x: x = ±√(R² − y²) gives two values
])
def test_a_dependent_velocity_that_leaves_a_variable_or_two_values_is_refused(in_terms_of):
    path = SCENES / "hemisphere_cartesian.toml"
    scene = parse_scene(_with_answer_in(path, "horizontal_acceleration", in_terms_of), source=path.name)
    with pytest.raises(SceneError, match="expressed in x"):
        derive(scene)


def test_an_answer_in_a_dependent_coordinate_with_branches_of_different_value_is_refused():
    """ẍ = g x (3√(R² − x²) − 2R)/R² in y alone is ±g √(R² − y²)(3y − 2R)/R²: which sign depends on
    the side, so it is refused, naming the variables answers are expressed in."""
    path = SCENES / "hemisphere_cartesian.toml"
    scene = parse_scene(_with_answer_in(path, "horizontal_acceleration", '["g", "R", "y"]'), source=path.name)
    with pytest.raises(SceneError, match="expressed in x"):
        derive(scene)


_X = sympy.Symbol("x", real=True)


@pytest.mark.parametrize("candidates, expected", [
    ([_X**2, (-_X)**2], True),                   # the two branches x = ±√(…) of an even answer
    ([_X, -_X], False),                          # an odd one: refused
    ([_X, sympy.nan], False),                    # a nan compares as agreeing with everything
    ([sympy.zoo * _X, sympy.zoo * _X], False),   # zoo: nothing is shown
])
def test_branches_of_a_dependent_coordinate_agree_only_on_finite_values(candidates, expected):
    from grader.mechanics.answers import _one_value

    assert _one_value(candidates) is expected
