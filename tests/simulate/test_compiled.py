"""The compiled equations of motion (grader.simulate.compiled) against ones derived by hand."""

from __future__ import annotations

import math

import numpy as np
import pytest

from grader.mechanics.scene import parse_scene
from grader.simulate.compiled import CompiledScene, SingularDynamics, kkt_solve, parameter_values

POLAR = parse_scene('''
id = "polar"
[parameters]
m = { dimension = "mass", domain = "positive", value = 0.2 }
g = { dimension = "acceleration", domain = "positive", value = 9.81 }
R = { dimension = "length", domain = "positive", value = 0.8 }
[coordinates]
r = { dimension = "length", domain = "positive" }
theta = { dimension = "angle" }
[energy]
kinetic = "m/2*(rdot^2 + r^2*thetadot^2)"
potential = "m*g*r*cos(theta)"
[[constraints]]
name = "surface"
f = "r - R"
''')

SHAKEN = parse_scene('''
id = "shaken"
[parameters]
m = { dimension = "mass", domain = "positive", value = 2.0 }
A = { dimension = "length", domain = "positive", value = 0.1 }
w = { dimension = "frequency", domain = "positive", value = 3.0 }
[coordinates]
x = { dimension = "length" }
y = { dimension = "length" }
[energy]
kinetic = "m/2*(xdot^2 + ydot^2)"
[[constraints]]
name = "drive"
f = "x - A*sin(w*t)"
''')


@pytest.mark.parametrize("r, theta, rdot, thetadot", [(0.8, 0.3, 0.0, 1.2), (1.1, -2.0, 0.4, -0.7)])
def test_polar_mass_matrix_forces_and_jacobian_are_the_textbook_ones(r, theta, rdot, thetadot):
    m, g = 0.2, 9.81
    compiled = CompiledScene(POLAR, parameter_values(POLAR))
    M, F, J, b = compiled.terms(0.0, [r, theta], [rdot, thetadot])
    np.testing.assert_allclose(M, [[m, 0], [0, m * r ** 2]], rtol=1e-15)
    np.testing.assert_allclose(F, [m * r * thetadot ** 2 - m * g * math.cos(theta),
                                   -2 * m * r * rdot * thetadot + m * g * r * math.sin(theta)], rtol=1e-14)
    np.testing.assert_allclose(J, [[1.0, 0.0]])
    np.testing.assert_allclose(b, [0.0])


def test_normal_force_on_the_sphere_is_m_g_cos_theta_minus_m_r_thetadot_squared():
    compiled = CompiledScene(POLAR, parameter_values(POLAR))
    qddot, lam = compiled.accelerations(0.0, [0.8, 0.5], [0.0, 1.5])
    assert lam[0] == pytest.approx(0.2 * 9.81 * math.cos(0.5) - 0.2 * 0.8 * 1.5 ** 2, rel=1e-14)
    assert qddot[0] == 0.0
    assert qddot[1] == pytest.approx(9.81 / 0.8 * math.sin(0.5), rel=1e-14)


@pytest.mark.parametrize("t", [0.0, 0.4, 1.3])
def test_a_driven_constraint_carries_its_time_derivatives(t):
    # x = A sin(w t): the drive's force is m ẍ = −m A w² sin(w t), and ḟ = ẋ − A w cos(w t).
    compiled = CompiledScene(SHAKEN, parameter_values(SHAKEN))
    x, xdot = 0.1 * math.sin(3 * t), 0.3 * math.cos(3 * t)
    qddot, lam = compiled.accelerations(t, [x, 0.0], [xdot, 0.0])
    assert qddot[0] == pytest.approx(-0.9 * math.sin(3 * t), abs=1e-14)
    assert lam[0] == pytest.approx(2.0 * -0.9 * math.sin(3 * t), abs=1e-14)
    assert compiled.rates(t, [x, 0.0], [xdot, 0.0])[0] == pytest.approx(0.0, abs=1e-15)


def test_parameter_values_take_set_over_the_file_and_refuse_unknown_names():
    assert parameter_values(POLAR, {"R": 2.0})["R"] == 2.0
    with pytest.raises(KeyError, match="no parameter named Rr"):
        parameter_values(POLAR, {"Rr": 2.0})


def test_a_body_without_mass_is_refused_with_a_clear_error():
    compiled = CompiledScene(POLAR, parameter_values(POLAR, {"m": 0.0}))
    with pytest.raises(SingularDynamics, match="without mass"):
        compiled.accelerations(0.0, [0.8, 0.3], [0.0, 0.0])


def test_kkt_solve_with_a_force_proportional_to_a_multiplier():
    # A block on a floor (y = 0) sliding in +x with kinetic friction 0.5 N: ẍ = −0.5 g, N = m g.
    M, F, J, b = np.eye(2), np.array([0.0, -9.81]), np.array([[0.0, 1.0]]), np.zeros(1)
    extra = np.array([[0.5], [0.0]])
    qddot, lam = kkt_solve(M, F, J, b, extra)
    np.testing.assert_allclose(qddot, [-0.5 * 9.81, 0.0], atol=1e-15)
    np.testing.assert_allclose(lam, [9.81])
