"""A string that goes slack and becomes taut again (problems/vertical_circle.toml).

While slack the bob is a projectile (energy conserved, inside the circle); the string becomes
taut when the bob is back at the distance l; the inelastic jerk (restitution 0) removes exactly the
radial part of the velocity, so the energy lost is ½ m v_r²; from then on the bob swings on the
circle with a positive tension.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from grader.mechanics.scene import load_scene
from grader.simulate.compiled import CompiledScene, parameter_values
from grader.simulate.trajectory import simulate_scene

CIRCLE = load_scene(Path(__file__).resolve().parents[2] / "problems" / "vertical_circle.toml")
M, G, L = 0.3, 9.81, 0.9


@pytest.mark.parametrize("v0", [4.8, 5.5, 6.5])
def test_slack_then_taut_again(v0):
    motion = simulate_scene(CIRCLE, {"v0": v0}, t_end=2.5, samples=501)
    compiled = CompiledScene(CIRCLE, parameter_values(CIRCLE, {"v0": v0}))
    slack, taut = motion.events[:2]
    assert [slack.effect, taut.effect] == ["release", "contact"]

    def energy(state):
        return compiled.energy(0.0, [state["x"], state["y"]], [state["xdot"], state["ydot"]])

    flight = (motion.t > slack.t) & (motion.t < taut.t)
    radius = np.hypot(motion.q[flight, 0], motion.q[flight, 1])
    assert np.all(radius < L) and np.all(motion.multipliers[flight, 0] == 0)
    start = 0.5 * M * v0 ** 2 - M * G * L
    energies = [compiled.energy(0.0, q, v) for q, v in zip(motion.q[flight], motion.qdot[flight])]
    np.testing.assert_allclose(energies, start, rtol=1e-9)
    assert energy(slack.state) == pytest.approx(start, rel=1e-9)

    # At the jerk the velocity is the projectile's, whose radial part is removed.
    x, y = taut.state["x"], taut.state["y"]
    vx, vy = slack.state["xdot"], slack.state["ydot"] - G * (taut.t - slack.t)
    radial = (x * vx + y * vy) / L
    assert radial > 0                                          # moving outwards when it jerks taut
    assert start - energy(taut.state) == pytest.approx(0.5 * M * radial ** 2, rel=1e-7)

    after = motion.t > taut.t
    after &= motion.t < (motion.events[2].t if len(motion.events) > 2 else np.inf)
    assert np.all(motion.multipliers[after, 0] > 0)             # taut: the string pulls
    np.testing.assert_allclose(np.hypot(motion.q[after, 0], motion.q[after, 1]), L, rtol=1e-10)
