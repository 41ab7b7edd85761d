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


_SWING = '''
id = "swing"
title = "Pendulum"
[parameters]
g = { dimension = "acceleration", domain = "positive", value = 9.81 }
l = { dimension = "length", domain = "positive", value = 1.0 }
m = { dimension = "mass", domain = "positive", value = 1.0 }
theta1 = { dimension = "angle", domain = [0.2, 0.5], value = 0.3 }
[coordinates]
theta = { dimension = "angle", domain = [-3.1416, 3.1416] }
[energy]
kinetic = "m*l^2/2*thetadot^2"
potential = "-m*g*l*cos(theta)"
[[answers]]
name = "omega_small"
kind = "small_oscillation"
expr = "theta"
where = "WHERE"
'''


@pytest.mark.parametrize("where, refused", [
    ("theta = 0.3", "theta = 3/10 is not an equilibrium of the motion (thetaddot = "),
    ("theta = theta1", "theta = theta1 is not an equilibrium of the motion (thetaddot = "),
    ("theta = pi", "the equilibrium is unstable"),   # an equilibrium, but the top one
])
def test_one_coordinate_oscillates_only_about_an_equilibrium(where, refused):
    # −∂θ̈/∂θ at θ = 0.3 is g cos(0.3)/l, but the pendulum does not rest there: no small oscillations
    with pytest.raises(SceneError, match=refused.replace("(", r"\(")):
        derive(parse_scene(_SWING.replace("WHERE", where), source="swing.toml"))


def test_one_coordinate_about_its_equilibrium_has_its_frequency():
    derivation = derive(parse_scene(_SWING.replace("WHERE", "theta = 0"), source="swing.toml"))
    assert_same(derivation, "omega_small", "sqrt(g/l)")
