"""Small oscillations with other coordinates cyclic (Routh's reduction), and its refusals."""

from __future__ import annotations

import pytest

from grader.mechanics.lagrange import derive
from grader.mechanics.scene import SceneError, parse_scene
from tests.mechanics.conftest import SCENES
from tests.mechanics.test_lagrange import assert_same


@pytest.mark.parametrize(
    "scene, answer, expected",
    [
        # The cart recoils: the reduced mass of the swing gives omega^2 = (M + m) g/(M l) (Landau §5).
        ("pendulum_sliding_support", "small_oscillation_frequency", "sqrt((M + m)*g/(M*l))"),
        # Nodding of a conical pendulum about theta0: omega^2 = g (1 + 3 cos^2 theta0)/(l cos theta0).
        ("conical_pendulum", "small_oscillation_frequency", "sqrt(g*(1 + 3*cos(theta0)^2)/(l*cos(theta0)))"),
    ],
)
def test_frequency_with_the_cyclic_momenta_conserved(derived, scene, answer, expected):
    assert_same(derived(scene), answer, expected)


def edited(name: str, old: str, new: str) -> str:
    text = (SCENES / f"{name}.toml").read_text()
    assert old in text, old
    return text.replace(old, new)


def test_other_coordinates_that_are_not_cyclic_are_named():
    # A double pendulum has two coupled modes; theta2 appears in the Lagrangian.
    text = (SCENES / "double_pendulum.toml").read_text() + '''
[[answers]]
name = "mode"
kind = "small_oscillation"
expr = "theta1"
where = "theta1 = 0"
'''
    with pytest.raises(SceneError, match="theta2 is not: the Lagrangian depends on it"):
        derive(parse_scene(text, source="double_pendulum.toml"))


def test_a_point_that_is_not_an_equilibrium_for_the_initial_momenta_is_refused():
    # Started faster than the steady conical motion, theta does not stay at theta0.
    text = edited("conical_pendulum", 'phidot = "sqrt(g/(l*cos(theta0)))"', 'phidot = "2*sqrt(g/(l*cos(theta0)))"')
    with pytest.raises(SceneError, match="theta = theta0 is not an equilibrium of the motion with the conserved"):
        derive(parse_scene(text, source="conical_pendulum.toml"))
