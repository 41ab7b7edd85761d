"""Separation starting at the unstable top of a smooth sphere, and the flight after it.

At rest exactly on the top the body is in equilibrium (θ̈ = 0, N = m g) and never leaves. The
smallest push θ̇₀ sets it off; energy conservation with N = 0 puts the separation at
cos θ = 2/3 + R θ̇₀²/(3 g). After leaving tangentially (the gap r − R grows like (t − t_s)³:
gap, its rate and its second derivative are all zero at the release) the body flies free and must
not be taken back onto the sphere by rounding.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from grader.mechanics.scene import load_scene
from grader.simulate.trajectory import simulate_scene

SPHERE = load_scene(Path(__file__).resolve().parents[2] / "problems" / "sphere.toml")
M, G, R = 0.2, 9.81, 0.8


def test_a_body_exactly_at_rest_on_the_top_never_leaves():
    motion = simulate_scene(SPHERE, t_end=20.0, samples=21, initial={"theta": 0.0, "thetadot": 0.0})
    assert motion.events == []
    assert np.all(motion.q == [R, 0.0])
    assert np.all(motion.multipliers[:, 0] == M * G)


@pytest.mark.parametrize("push", [1e-9, 1e-6, 1e-3, 0.5])
def test_the_smallest_push_separates_it_at_the_right_angle(push):
    motion = simulate_scene(SPHERE, t_end=15.0, samples=2, initial={"theta": 0.0, "thetadot": push})
    release = motion.events[0]
    assert (release.effect, release.constraint) == ("release", "surface")
    assert math.cos(release.state["theta"]) == pytest.approx(2 / 3 + R * push ** 2 / (3 * G), abs=1e-9)


def test_after_a_tangential_lift_off_the_body_is_not_taken_back():
    motion = simulate_scene(SPHERE, t_end=0.6, samples=2, initial={"theta": 0.3})
    release = motion.events[0].t
    # Sample the first instants of the flight densely, where the gap is below 1e-12.
    times = release + np.geomspace(1e-6, 3.0, 60)
    from grader.simulate.compiled import CompiledScene, parameter_values
    from grader.simulate.effects import declared_effects
    from grader.simulate.trajectory import Simulation

    compiled = CompiledScene(SPHERE, parameter_values(SPHERE))
    flight = Simulation(compiled, declared_effects(SPHERE, compiled.values)).run(
        0.0, [R, 0.3], [0.0, 0.0], float(times[-1]), np.concatenate([[0.0], times]))
    assert [e.effect for e in flight.events] == ["release"]
    gap = flight.q[1:, 0] - R
    assert np.all(gap >= 0)                     # never inside the sphere, not even by rounding
    assert np.all(gap[times - release > 1e-4] > 0)
    # The gap opens like (t − t_s)³ right after the release (fit where it is above rounding).
    early = (times - release > 1e-4) & (times - release < 1e-2)
    order = np.polyfit(np.log(times[early] - release), np.log(gap[early]), 1)[0]
    assert order == pytest.approx(3.0, abs=0.05)
