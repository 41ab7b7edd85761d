"""The fourth session's engine red team (2026-11-27): answers about a family of motions.

An answer in terms of a parameter that [initial] uses (a launch speed ω₀, a start x = 3R/5 that
scales with R) is a formula over a family of motions. Where the motion from [initial] reaches the
condition, at the scene's values and across the declared domains, it still decides which root
holds and which way the body moves there; where the way depends on the parameters (released at θ₀
on either side of the bottom), no one formula holds and the file is refused, saying so. Each answer
is derived by hand (in the comment above it) and compared exactly and at random points; the scene
files are also confirmed along the simulated motion by tests/numerical/test_problems_confirmed.py.
"""

from __future__ import annotations

import pytest

from tests.mechanics.test_red_team_scenes_5 import assert_hand_derived, derived
from tests.mechanics.conftest import SCENES
from grader.mechanics.lagrange import derive
from grader.mechanics.scene import SceneError, parse_scene


@pytest.mark.parametrize("scene, answer, expected", [
    # Launched at ω₀ from the bottom: energy, θ̇² = ω₀² − 2 (g/l)(1 − cos θ). θ = 0.2 is met on the way
    # out (θ̇ > 0); θ = -0.2 only after the turn at θ* = acos(1 − l ω₀²/(2g)), on the way back (θ̇ < 0).
    ("pendulum_launched_from_bottom", "angular_velocity_out", "sqrt(w0^2 - 2*g*(1 - cos(1/5))/l)"),
    ("pendulum_launched_from_bottom", "angular_velocity_back", "-sqrt(w0^2 - 2*g*(1 - cos(1/5))/l)"),
    ("pendulum_launched_from_bottom", "turning_angle", "acos(1 - l*w0^2/(2*g))"),
    # From rest at (3R/5, -4R/5) on a circle, energy brings the bead to rest again at the same height on
    # the other side, (-3R/5, -4R/5); not at x = ±R, which the motion never reaches (y stays ≤ -4R/5).
    ("bead_circle_cartesian_from_rest", "x_at_rest_again", "-3*R/5"),
    ("bead_circle_cartesian_from_rest", "y_at_rest_again", "-4*R/5"),
])
def test_an_answer_about_a_family_of_motions_is_where_the_motion_goes(scene, answer, expected):
    assert_hand_derived(derived(scene), answer, expected)


def test_the_way_a_family_passes_a_root_must_be_the_same_across_the_domains():
    # Released from rest at θ₀ in [-1.5, 1.5], the bob passes the bottom moving against θ₀'s sign:
    # θ̇ = -2 √(g/l) sin(θ₀/2). One sign taken at the scene's θ₀ = 0.8 was wrong for every θ₀ < 0.
    text = (SCENES / "pendulum_launched_from_bottom.toml").read_text()
    text = (text.replace('w0 = { dimension = "angular_velocity", domain = "positive", value = 2.0 }',
                         'theta0 = { dimension = "angle", domain = [-1.5, 1.5], value = 0.8 }')
                .replace('theta = 0\nthetadot = "w0"', 'theta = "theta0"\nthetadot = 0')
                .replace('"w0"]', '"theta0"]').replace("theta = 1/5", "theta = 0"))
    with pytest.raises(SceneError, match="which way the motion passes the root depends on the parameter values"):
        derive(parse_scene(text, source="released_either_side.toml"))
