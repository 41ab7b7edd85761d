"""A pendulum swinging 1e-8 rad: the motion is resolved at its own scale, and the period is the
small-oscillation period 2π√(l/g) (the amplitude correction θ₀²/16 is 6e-18)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from grader.mechanics.scene import parse_scene
from grader.simulate.trajectory import simulate_scene

PENDULUM = parse_scene('''
id = "pendulum_angle"
[parameters]
m = { dimension = "mass", domain = "positive", value = 1.0 }
g = { dimension = "acceleration", domain = "positive", value = 9.81 }
l = { dimension = "length", domain = "positive", value = 1.0 }
[coordinates]
theta = { dimension = "angle" }
[energy]
kinetic = "m/2*l^2*thetadot^2"
potential = "-m*g*l*cos(theta)"
[initial]
theta = 1e-8
thetadot = 0
''', source="pendulum_angle.toml")


@pytest.mark.parametrize("theta0", [1e-8, 1e-6])
def test_tiny_swing_has_the_small_oscillation_period_to_1e_9(theta0):
    period = 2 * math.pi * math.sqrt(1.0 / 9.81)
    # Samples every quarter period over 39 of them: θ = θ₀ cos(2π t/P) is ±θ₀ at the even ones
    # and crosses zero at the odd ones, where |θ| = θ₀ 2π |δt|/P: a timing error of 1e-9 P
    # shows as |θ| = 2π·1e-9 θ₀.
    motion = simulate_scene(PENDULUM, t_end=39 * period / 4, samples=40, initial={"theta": theta0})
    np.testing.assert_allclose(motion.t, period / 4 * np.arange(40), rtol=1e-15)
    crossings, turning = motion.q[1::2, 0], motion.q[0::2, 0]
    assert np.abs(crossings).max() <= 2 * math.pi * 1e-9 * theta0
    np.testing.assert_allclose(np.abs(turning), theta0, rtol=1e-9)
