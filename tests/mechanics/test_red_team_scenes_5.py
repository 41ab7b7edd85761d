"""The fifth red team's textbook scenes: a body on a track cut in a cart that is free to move, so that
the cart's momentum is conserved and not zero. Each answer is derived by hand (in the comment above
it) and compared with the engine's closed form exactly and at random points
(test_red_team_scenes.agree).

The scene files are under tests/mechanics/scenes, so tests/numerical/test_problems_confirmed.py also
confirms their answers along the simulated motion, independently of the engine.
"""

from __future__ import annotations

from functools import lru_cache

import pytest

from grader.mechanics.lagrange import derive
from grader.mechanics.scene import SceneError, parse_scene
from tests.mechanics.conftest import SCENES
from tests.mechanics.test_red_team_scenes import agree
from tests.mechanics.test_red_team_scenes_4 import assert_exactly


@lru_cache(maxsize=None)
def derived(scene: str):
    return derive(parse_scene((SCENES / f"{scene}.toml").read_text(), source=f"{scene}.toml"))


# The pendulum below a cart on a smooth rail, the cart pushed off at V0: the momentum
# (M + m) Ẋ + m l θ̇ cos θ = (M + m) V0 is conserved and the cart's uniform drift carries no energy
# of the swing, so it swings as from rest: up to θ0, the bob's height l (1 − cos θ0).
MOVING_CART = '''[initial]
X = 0
Xdot = "V0"
theta = "theta0"
thetadot = 0

[[answers]]
name = "max_height"
kind = "maximum"
expr = "l - l*cos(theta)"
in_terms_of = ["l", "theta0"]
dimension = "length"

[[answers]]
name = "cart_velocity"
expr = "Xdot"
in_terms_of = ["m", "M", "l", "theta", "thetadot", "V0"]
'''
MOVING_CART_PARAMETER = 'V0 = { dimension = "velocity", domain = "positive", value = 0.7 }\n'


@lru_cache(maxsize=None)
def moving_cart():
    text = (SCENES / "pendulum_sliding_support.toml").read_text()
    text = text.replace("[coordinates]", MOVING_CART_PARAMETER + "\n[coordinates]", 1)
    return derive(parse_scene(text[:text.index("[initial]")] + MOVING_CART, source="pendulum_sliding_support.toml"))


@pytest.mark.parametrize("answer, expected", [
    # Block at the bottom of a quarter-circle track of radius R cut in a cart M, launched at v0, the cart
    # at rest (Kleppner–Kolenkow). The momentum m v0 = (M + m) Ẋ + m R θ̇ cos θ; at the top of its
    # climb θ̇ = 0, both move at m v0/(M + m), and energy gives the height M v0²/(2 g (M + m)).
    ("max_height", "M*v0^2/(2*g*(M + m))"),
    # At the start the cart is at rest and the block moves on a circle about a point at rest, but
    # the cart is pushed: in the cart's frame the block's acceleration towards the centre is v0²/R and
    # the cart's acceleration is horizontal there, so N = m g + m v0²/R.
    ("normal_force_bottom", "m*(g + v0^2/R)"),
    # At the rim (θ = π/2) the block moves vertically relative to the cart, so both move at m v0/(M + m)
    # horizontally, and energy: m v0²/2 = (M + m) (m v0/(M + m))²/2 + m R² θ̇²/2 + m g R.
    ("rim_angular_speed_squared", "M*v0^2/(R^2*(M + m)) - 2*g/R"),
    # Reaching the rim at all: the least v0 with θ̇² ≥ 0 there, v0² = 2 g R (M + m)/M.
    ("least_launch_speed", "sqrt(2*g*R*(M + m)/M)"),
    # N on the block in its state (θ, θ̇): M m (g cos θ + R θ̇²)/(M + m sin²θ), as for a pendulum on a
    # sliding support (the track pushes instead of the rod pulling).
    ("normal_force_state", "M*m*(g*cos(theta) + R*thetadot^2)/(M + m*sin(theta)^2)"),
])
def test_a_block_launched_up_a_track_on_a_free_cart(answer, expected):
    d = derived("cart_quarter_circle")
    agree(d, answer, expected)
    assert_exactly(d, answer, expected)


@pytest.mark.parametrize("answer, expected", [
    ("max_height", "l*(1 - cos(theta0))"),
    ("cart_velocity", "V0 - m*l*thetadot*cos(theta)/(M + m)"),
])
def test_a_moving_cart_keeps_the_swing_of_a_cart_at_rest(answer, expected):
    d = moving_cart()
    agree(d, answer, expected)
    assert_exactly(d, answer, expected)


def test_an_extreme_whose_turning_points_have_no_closed_form_is_refused_not_guessed(monkeypatch):
    """Where the motion turns back but energy does not give u̇² in closed form, the best of the other
    candidates (a stationary point, the start) is not the extreme: the scene is refused."""
    from grader.mechanics import extremes

    monkeypatch.setattr(extremes, "energy_speed_squared", lambda *args, **kwargs: None)
    text = (SCENES / "cart_quarter_circle.toml").read_text()
    with pytest.raises(SceneError, match="turns back, but where it does"):
        derive(parse_scene(text, source="cart_quarter_circle.toml"))
