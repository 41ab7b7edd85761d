"""A disk on a rough incline (problems/incline_slipping.toml) at the edges of its friction law.

Rolling needs the friction F = m g sin α / 3 against the normal force N = m g cos α, so the disk
rolls while tan α ≤ 3 μ_s. Exactly at tan α = 3 μ_s the needed friction equals μ_s N (up to
rounding), and slipping needs |F| > μ_s N: it rolls, with F = μ_s N. At α = π/2 (a vertical wall)
N = 0: there is no friction at all, the disk falls freely without spinning.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from grader.mechanics.scene import load_scene
from grader.simulate.trajectory import simulate_scene

SCENE = load_scene(Path(__file__).resolve().parents[2] / "problems" / "incline_slipping.toml")
M, G, R, MU_S, MU_K = 1.5, 9.81, 0.2, 0.2, 0.15


@pytest.mark.parametrize("mu_s", [0.2, 0.35, 1.0])
def test_exactly_at_the_slip_threshold_the_disk_rolls(mu_s):
    alpha = math.atan(3 * mu_s)
    motion = simulate_scene(SCENE, {"alpha": alpha, "mu_s": mu_s}, t_end=2.0, samples=21)
    assert motion.events == []
    s, theta = motion.q[:, 0], motion.q[:, 1]
    np.testing.assert_allclose(s, G * math.sin(alpha) / 3 * motion.t ** 2, rtol=1e-10, atol=1e-14)
    np.testing.assert_allclose(R * theta, s, rtol=1e-10, atol=1e-14)
    friction, normal = -motion.forces[:, 0, 0], motion.multipliers[:, 1]
    np.testing.assert_allclose(friction, mu_s * normal, rtol=1e-12)


def test_just_beyond_the_threshold_it_slips_from_the_start():
    alpha = math.atan(3 * MU_S) * (1 + 1e-6)
    motion = simulate_scene(SCENE, {"alpha": alpha}, t_end=1.0, samples=2)
    assert [(e.effect, e.t) for e in motion.events] == [("slip", 0.0)]


def test_on_a_vertical_wall_the_disk_falls_freely_without_spinning():
    motion = simulate_scene(SCENE, {"alpha": math.pi / 2}, t_end=1.0, samples=11)
    assert [e.effect for e in motion.events] == ["slip"]
    np.testing.assert_allclose(motion.q[:, 0], G / 2 * motion.t ** 2, rtol=1e-12, atol=1e-15)
    assert np.abs(motion.q[:, 1]).max() < 1e-12          # cos(π/2) = 6e-17 in floats: no spin
    assert np.abs(motion.forces[:, 0, 0]).max() < 1e-12  # and no friction to speak of
