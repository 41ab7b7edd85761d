"""The third session's red teams' textbook scenes (2026-11-27): bodies on tracks cut in carts free to
move (their momentum conserved and not zero), a block leaving a hemisphere free on a floor (a cubic),
hoops spun up or about a tangent, a ball rolling in a bowl, an equilibrium without [initial], a wedge on
a spring. Each answer is derived by hand (in the comment above it) and compared with the engine's
closed form exactly and at random points (test_red_team_scenes.agree).

The scene files under tests/mechanics/scenes are also confirmed along the simulated motion by
tests/numerical/test_problems_confirmed.py; those under scenes/not_simulated say why they are not.
"""

from __future__ import annotations

from functools import lru_cache

import pytest
import sympy

from grader.expressions import parse_expression
from grader.mechanics.lagrange import derive
from grader.mechanics.scene import SceneError, parse_scene
from tests.mechanics.conftest import SCENES
from tests.mechanics.test_red_team_scenes import agree
from tests.mechanics.test_red_team_scenes_4 import assert_exactly


@lru_cache(maxsize=None)
def derived(scene: str):
    path = SCENES / f"{scene}.toml"
    path = path if path.exists() else SCENES / "not_simulated" / f"{scene}.toml"
    return derive(parse_scene(path.read_text(), source=path.name))


def assert_hand_derived(derivation, answer: str, expected: str) -> None:
    agree(derivation, answer, expected)
    assert_exactly(derivation, answer, expected)


# A block from rest on top of a smooth hemisphere M free on a smooth floor (Morin): with (M + m) Ẋ +
# m R θ̇ cos θ = 0 and energy, θ̇² = 2 g (M + m)(1 − cos θ)/(R (M + m sin²θ)); the normal force, from
# the block's acceleration towards the centre in the hemisphere's (accelerated) frame,
# N = M m g (3 (M + m) cos θ − m cos³θ − 2 (M + m))/(M + m sin²θ)². It vanishes where
# k c³ − 3 c + 2 = 0 (c = cos θ, k = m/(M + m)): three real roots for 0 < k < 1, the one in (0, 1) Viète's
# c = (2/√k) cos(acos(−√k)/3 − 2π/3) (√3 − 1 for M = m).
HEMISPHERE_C = "(2*sqrt((M + m)/m)*cos(acos(-sqrt(m/(M + m)))/3 - 2*pi/3))"


@pytest.mark.parametrize("scene, answer, expected", [
    # Block at the bottom of a quarter-circle track of radius R cut in a cart M, launched at v0, the cart
    # at rest (Kleppner–Kolenkow). The momentum m v0 = (M + m) Ẋ + m R θ̇ cos θ; at the top of its
    # climb θ̇ = 0, both move at m v0/(M + m), and energy gives the height M v0²/(2 g (M + m)).
    ("cart_quarter_circle", "max_height", "M*v0^2/(2*g*(M + m))"),
    # At the start the cart is at rest and the block moves on a circle about a point at rest, but
    # the cart is pushed: in the cart's frame the block's acceleration towards the centre is v0²/R and
    # the cart's acceleration is horizontal there, so N = m g + m v0²/R.
    ("cart_quarter_circle", "normal_force_bottom", "m*(g + v0^2/R)"),
    # At the rim (θ = π/2) the block moves vertically relative to the cart, so both move at m v0/(M + m)
    # horizontally, and energy: m v0²/2 = (M + m) (m v0/(M + m))²/2 + m R² θ̇²/2 + m g R.
    ("cart_quarter_circle", "rim_angular_speed_squared", "M*v0^2/(R^2*(M + m)) - 2*g/R"),
    # Reaching the rim at all: the least v0 with θ̇² ≥ 0 there, v0² = 2 g R (M + m)/M.
    ("cart_quarter_circle", "least_launch_speed", "sqrt(2*g*R*(M + m)/M)"),
    # N on the block in its state (θ, θ̇): M m (g cos θ + R θ̇²)/(M + m sin²θ), as for a pendulum on a
    # sliding support (the track pushes instead of the rod pulling).
    ("cart_quarter_circle", "normal_force_state", "M*m*(g*cos(theta) + R*thetadot^2)/(M + m*sin(theta)^2)"),
    # Where θ̇ = 0 the block moves with the cart, m v0/(M + m): the condition sets θ̇ in the answer
    # (through the height θ* it reached, R and g were left in it, and it was refused).
    ("cart_quarter_circle", "cart_speed_at_max", "m*v0/(M + m)"),
    # The hemisphere (see HEMISPHERE_C above).
    ("movable_hemisphere", "hemisphere_velocity", "-m*R*thetadot*cos(theta)/(M + m)"),
    ("movable_hemisphere", "angular_speed_squared", "2*g*(M + m)*(1 - cos(theta))/(R*(M + m*sin(theta)^2))"),
    ("movable_hemisphere", "normal_force",
     "M*m*g*(3*(M + m)*cos(theta) - m*cos(theta)^3 - 2*(M + m))/(M + m*sin(theta)^2)^2"),
    # A bead on a hoop spun up about its vertical diameter, φ = α t²/2: with φ̇ = α t,
    # θ̈ = φ̇² sin θ cos θ − (g/a) sin θ; the motor's torque is d/dt(m a² sin²θ φ̇), and the hoop's
    # sideways push on the bead that torque over the lever a sin θ.
    ("hoop_angular_acceleration", "equation_of_motion", "(alpha^2*t^2*cos(theta) - g/a)*sin(theta)"),
    ("hoop_angular_acceleration", "drive_torque", "m*a^2*alpha*(2*t*thetadot*sin(theta)*cos(theta) + sin(theta)^2)"),
    ("hoop_angular_acceleration", "sideways_force", "m*a*alpha*(2*t*thetadot*cos(theta) + sin(theta))"),
    # The lowest point stops being stable once φ̇² = α²t² passes g/a: a moment the parameters alone fix,
    # though the motion has no closed form (it was refused for that).
    ("hoop_angular_acceleration", "lowest_point_unstable_time", "sqrt(g/a)/alpha"),
    # A solid ball (I = 2ma²/5) rolling in a bowl, its centre on a circle of radius R − a: energy gives
    # (7/10) m (R − a)² θ̇² = m g (R − a)(cos θ − cos θ₀); along the groove m (R − a) θ̈ = −m g sin θ + F
    # with F the friction, and for the spin (2/5) m a² ψ̈ = −a F: F = 2 m g sin θ/7 (against the slide);
    # across it N − m g cos θ = m (R − a) θ̇², so N = m g (17 cos θ − 10 cos θ₀)/7.
    ("sphere_in_bowl", "normal_force", "m*g*(17*cos(theta) - 10*cos(theta0))/7"),
    ("sphere_in_bowl", "friction_force", "2*m*g*sin(theta)/7"),
    ("sphere_in_bowl", "bottom_normal_force", "m*g*(17 - 10*cos(theta0))/7"),
    # |F|/N = 2 sin θ/(17 cos θ − 10 cos θ₀) grows with |θ|: its largest is at the release, (2/7) tan θ₀
    # (it was refused: the bars' derivative ran the solve out of its budget).
    ("sphere_in_bowl", "least_friction_coefficient", "2*tan(theta0)/7"),
    ("sphere_in_bowl", "small_oscillation_frequency", "sqrt(5*g/(7*(R - a)))"),
    # A bead on a hoop spun at ω about its vertical diameter, tied to the lowest point by a spring k of
    # zero length, without [initial]. At rest in the turning frame m R ω² sin θ cos θ = (k R + m g) sin θ,
    # so cos θₑ = (kR + mg)/(mRω²); the hoop's force along the radius is then
    # λ = R (k cos θ − k + m ω² sin²θ) + m g cos θ = R (m ω² − k): with no motion to follow, taken at
    # rest (it was refused, needing [initial] for θ̇ from energy).
    ("hoop_bead_spring_to_bottom", "equilibrium_cos", "(k*R + m*g)/(m*R*omega^2)"),
    ("hoop_bead_spring_to_bottom", "hoop_force_equilibrium", "R*(m*omega^2 - k)"),
    ("hoop_bead_spring_to_bottom", "critical_omega", "sqrt((k*R + m*g)/(m*R))"),
    # A wedge M on a smooth floor tied to a wall by a spring k, a block m sliding down its face from
    # rest: the wedge oscillates, X(t) = −(m g sin α cos α/k)(1 − cos Ωt) with Ω² = k/(M + m sin²α),
    # while the block's s(t) grows as t² (over the coordinate X the motion "runs away": the extreme is
    # taken over time); the face's force is m g cos α (M + m sin²α (1 − cos Ωt))/(M + m sin²α), least
    # at t = 0.
    ("wedge_spring_wall_block", "greatest_compression", "m*g*sin(2*alpha)/k"),
    ("wedge_spring_wall_block", "least_normal", "M*m*g*cos(alpha)/(M + m*sin(alpha)^2)"),
])
def test_the_engine_gives_the_hand_derived_closed_form(scene, answer, expected):
    assert_hand_derived(derived(scene), answer, expected)


@pytest.mark.parametrize("answer, expected", [
    # a cubic with three real roots: real closed forms (Viète), never Cardano's complex cube roots
    ("separation_cos", HEMISPHERE_C),
    ("hemisphere_speed_at_separation",
     f"m*{HEMISPHERE_C}/(M + m)*sqrt(2*g*R*(M + m)*(1 - {HEMISPHERE_C})/(M + m*(1 - {HEMISPHERE_C}^2)))"),
    ("separation_angle_numeric", f"acos({HEMISPHERE_C})"),
])
def test_a_block_leaves_a_hemisphere_free_on_a_floor_at_a_root_of_a_cubic(answer, expected):
    d = derived("movable_hemisphere")
    agree(d, answer, expected)
    assert "I" not in str(d.answers[answer])


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
    ("max_height", "l*(1 - cos(theta0))"),
    ("cart_velocity", "V0 - m*l*thetadot*cos(theta)/(M + m)"),
])
def test_a_moving_cart_keeps_the_swing_of_a_cart_at_rest(answer, expected):
    assert_hand_derived(moving_cart(), answer, expected)


def test_an_extreme_whose_turning_points_have_no_closed_form_is_refused_not_guessed(monkeypatch):
    """Where the motion turns back but energy does not give u̇² in closed form, the best of the other
    candidates (a stationary point, the start) is not the extreme: the scene is refused."""
    from grader.mechanics import extremes

    monkeypatch.setattr(extremes, "energy_speed_squared", lambda *args, **kwargs: None)
    text = (SCENES / "cart_quarter_circle.toml").read_text()
    with pytest.raises(SceneError, match="turns back, but where it does"):
        derive(parse_scene(text, source="cart_quarter_circle.toml"))


# A bead on a vertical hoop spun at ω about a vertical tangent (the axis at a (1 + sin θ) from the
# bead), released at rest relative to the hoop at θ = 0.3: energy in the turning frame,
# θ̇² = ω² ((sin θ + 2) sin θ − (sin θ₀ + 2) sin θ₀) + 2 g (cos θ − cos θ₀)/a, so it turns back where
# that vanishes again, at θ = 1.45783 for a = 0.2, ω = 6, g = 9.81 (a root without closed form).
def test_where_a_velocity_vanishes_without_a_closed_form_is_the_turning_point_found_numerically():
    """θ̇ = 0 from energy is √(f(θ)) = 0, which touches 0 at the turning point without crossing it; it
    was refused as having no root."""
    from grader.expressions.implicit import Implicit
    from grader.mechanics.special_values import _numeric

    d = derived("hoop_tangent_axis")
    rule = Implicit.from_json(d.implicit["turning_angle"])
    condition = parse_expression(rule.condition, d.scene.namespace).expr
    numbers = {s: sympy.Float(v, 30) for s, v in {"a": 0.2, "omega": 6.0, "g": 9.81}.items()}
    at_values = condition.xreplace({d.scene.namespace.symbol(n): v for n, v in numbers.items()})
    theta = d.scene.namespace.symbol("theta")
    assert abs(rule.solve(_numeric(at_values, theta)) - 1.45783) < 1e-4
