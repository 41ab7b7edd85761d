"""A spherical pendulum through the pole, where the angles (θ, φ) are singular.

In the angles the mass matrix is diag(m l², m l² sin²θ): singular at θ = 0. A swing with φ̇ = 0 is
planar and passes through the pole; it must be the plane pendulum, period 4 √(l/g) K(sin²(θ₀/2)).
In Cartesian coordinates with x² + y² + z² = l² there is no singularity: a swing with a tiny
sideways speed passes by the pole to the far side and back while energy and the vertical angular
momentum m (x ẏ − y ẋ) stay what they were.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.special import ellipk

from grader.mechanics.scene import parse_scene
from grader.simulate.compiled import CompiledScene, parameter_values
from grader.simulate.trajectory import simulate_scene

ANGLES = parse_scene('''
id = "spherical_angles"
[parameters]
m = { dimension = "mass", domain = "positive", value = 1.0 }
g = { dimension = "acceleration", domain = "positive", value = 9.81 }
l = { dimension = "length", domain = "positive", value = 1.0 }
[coordinates]
theta = { dimension = "angle" }
phi = { dimension = "angle" }
[energy]
kinetic = "m/2*l^2*(thetadot^2 + sin(theta)^2*phidot^2)"
potential = "-m*g*l*cos(theta)"
[initial]
theta = 0.4
phi = 0
thetadot = 0
phidot = 0
''', source="spherical_angles.toml")

CARTESIAN = parse_scene('''
id = "spherical_cartesian"
[parameters]
m = { dimension = "mass", domain = "positive", value = 1.0 }
g = { dimension = "acceleration", domain = "positive", value = 9.81 }
l = { dimension = "length", domain = "positive", value = 1.0 }
[coordinates]
x = { dimension = "length" }
y = { dimension = "length" }
z = { dimension = "length" }
[energy]
kinetic = "m/2*(xdot^2 + ydot^2 + zdot^2)"
potential = "m*g*z"
[[constraints]]
name = "rod"
f = "x^2 + y^2 + z^2 - l^2"
[initial]
x = 0.4
y = 0
z = "-l*sqrt(1 - 0.16)"
xdot = 0
ydot = 1e-5
zdot = 0
''', source="spherical_cartesian.toml")


def test_a_planar_swing_through_the_pole_in_angles_is_the_plane_pendulum():
    theta0 = 0.4
    period = 4 * math.sqrt(1 / 9.81) * ellipk(math.sin(theta0 / 2) ** 2)
    motion = simulate_scene(ANGLES, t_end=2 * period, samples=5)
    np.testing.assert_allclose(motion.q[:, 0], [theta0, -theta0, theta0, -theta0, theta0], rtol=1e-9)
    assert np.all(motion.q[:, 1] == 0.0)


def test_in_cartesian_coordinates_the_pole_is_an_ordinary_point():
    motion = simulate_scene(CARTESIAN, t_end=3.0, samples=3001)
    compiled = CompiledScene(CARTESIAN, parameter_values(CARTESIAN))
    x, y = motion.q[:, 0], motion.q[:, 1]
    # It swings through the pole region to the far side and back, hardly leaving the x-z plane.
    assert x.min() < -0.39 and np.abs(y).max() < 1e-5
    energy = np.array([compiled.energy(0.0, q, v) for q, v in zip(motion.q, motion.qdot)])
    np.testing.assert_allclose(energy, energy[0], rtol=1e-10)
    momentum = x * motion.qdot[:, 1] - y * motion.qdot[:, 0]
    np.testing.assert_allclose(momentum, 0.4 * 1e-5, rtol=1e-7)
    assert motion.q[0, 2] == pytest.approx(-math.sqrt(1 - 0.16), rel=1e-15)
