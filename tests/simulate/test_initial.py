"""The [initial] state completed by the constraints (grader.simulate.initial), and refused when it
cannot be."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from grader.mechanics.scene import load_scene, parse_scene
from grader.simulate.compiled import CompiledScene, parameter_values
from grader.simulate.initial import InitialStateError, initial_state

PROBLEMS = Path(__file__).resolve().parents[2] / "problems"


def start(scene, **overrides):
    return initial_state(scene, CompiledScene(scene, parameter_values(scene, overrides)))


def test_coordinates_left_out_are_solved_from_the_constraints():
    q, qdot = start(load_scene(PROBLEMS / "sphere.toml"), R=1.5)     # [initial] gives only θ
    assert q.tolist() == [1.5, 0.0]


def test_a_parametrization_maps_its_variables_and_their_rates():
    q, qdot = start(load_scene(PROBLEMS / "vertical_circle.toml"))  # θ = 0, θ̇ = v0/l
    np.testing.assert_allclose(q, [0.0, -0.9], atol=1e-15)
    np.testing.assert_allclose(qdot, [5.5, 0.0], atol=1e-15)


def test_velocities_left_out_keep_the_constraint_rates_zero():
    q, qdot = start(load_scene(PROBLEMS / "half_atwood.toml"), L=1.5)  # x = L/2, ẋ = 0; y, ẏ, z, ż solved
    np.testing.assert_allclose(q, [0.75, 0.75, 0.0], atol=1e-15)
    np.testing.assert_allclose(qdot, 0.0, atol=1e-15)


RING = '''
id = "ring"
[parameters]
m = { dimension = "mass", domain = "positive", value = 1.0 }
l = { dimension = "length", domain = "positive", value = 1.0 }
[coordinates]
x = { dimension = "length" }
y = { dimension = "length" }
[energy]
kinetic = "m/2*(xdot^2 + ydot^2)"
[[constraints]]
name = "rod"
f = "l^2 - x^2 - y^2"
kind = "KIND"
[initial]
'''


@pytest.mark.parametrize("kind, initial, message", [
    ("bilateral", "x = 2\ny = 0", "off constraint 'rod'"),
    ("unilateral", "x = 2\ny = 0", "wrong side of constraint 'rod'"),
    ("bilateral", "x = 1\ny = 0\nxdot = 1\nydot = 0", "initial velocities break constraint 'rod'"),
])
def test_a_state_off_the_constraints_is_refused_naming_the_constraint(kind, initial, message):
    scene = parse_scene(RING.replace("KIND", kind) + initial, source="ring.toml")
    with pytest.raises(InitialStateError, match=message):
        start(scene)


def test_a_unilateral_contact_may_start_open():
    scene = parse_scene(RING.replace("KIND", "unilateral") + "x = 0.5\ny = 0\nxdot = 1", source="ring.toml")
    q, qdot = start(scene)
    assert q.tolist() == [0.5, 0.0] and qdot.tolist() == [1.0, 0.0]


def test_a_parametrization_without_its_variables_is_refused():
    scene = load_scene(PROBLEMS / "pendulum.toml")
    scene.initial.pop("theta")
    with pytest.raises(InitialStateError, match="gives no value for theta"):
        start(scene)


def test_a_coordinate_left_out_that_cannot_close_every_contact_is_named():
    # A body on a sphere above a floor: r from both contacts at once has no solution; the
    # least-squares compromise was refused as 'the wrong side of surface', not naming r.
    scene = parse_scene('''
id = "sphere_floor"
[parameters]
m = { dimension = "mass", domain = "positive", value = 1.0 }
g = { dimension = "acceleration", domain = "positive", value = 9.81 }
R = { dimension = "length", domain = "positive", value = 0.8 }
[coordinates]
r = { dimension = "length", domain = "positive" }
theta = { dimension = "angle", domain = "real" }
[energy]
kinetic = "m/2*(rdot^2 + r^2*thetadot^2)"
potential = "m*g*r*cos(theta)"
[[constraints]]
name = "surface"
f = "r - R"
kind = "unilateral"
[[constraints]]
name = "floor"
f = "r*cos(theta) + R"
kind = "unilateral"
[initial]
theta = 0.3
''', source="sphere_floor.toml")
    with pytest.raises(InitialStateError, match=r"leaves out r, .*\(surface, floor\) at once: give r in \[initial\]"):
        start(scene)
    scene.initial["r"] = scene.parameters["R"].symbol
    q, _ = start(scene)
    assert q.tolist() == [0.8, 0.3]
