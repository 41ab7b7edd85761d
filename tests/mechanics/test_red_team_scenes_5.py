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
import sympy

from grader.expressions import parse_expression
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
    # Where θ̇ = 0 the block moves with the cart, m v0/(M + m): the condition sets θ̇ in the answer
    # (through the height θ* it reached, R and g were left in it, and it was refused).
    ("cart_speed_at_max", "m*v0/(M + m)"),
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


# A block from rest on top of a smooth hemisphere M free on a smooth floor (Morin): with (M + m) Ẋ +
# m R θ̇ cos θ = 0 and energy, θ̇² = 2 g (M + m)(1 − cos θ)/(R (M + m sin²θ)); the normal force, from
# the block's acceleration towards the centre in the hemisphere's (accelerated) frame,
# N = M m g (3 (M + m) cos θ − m cos³θ − 2 (M + m))/(M + m sin²θ)². It vanishes where
# k c³ − 3 c + 2 = 0 (c = cos θ, k = m/(M + m)): three real roots for 0 < k < 1, the one in (0, 1) Viète's
# c = (2/√k) cos(acos(−√k)/3 − 2π/3) (√3 − 1 for M = m).
HEMISPHERE_C = "(2*sqrt((M + m)/m)*cos(acos(-sqrt(m/(M + m)))/3 - 2*pi/3))"


@pytest.mark.parametrize("answer, expected", [
    ("hemisphere_velocity", "-m*R*thetadot*cos(theta)/(M + m)"),
    ("angular_speed_squared", "2*g*(M + m)*(1 - cos(theta))/(R*(M + m*sin(theta)^2))"),
    ("normal_force", "M*m*g*(3*(M + m)*cos(theta) - m*cos(theta)^3 - 2*(M + m))/(M + m*sin(theta)^2)^2"),
])
def test_a_block_on_a_hemisphere_free_on_a_floor(answer, expected):
    d = derived("movable_hemisphere")
    agree(d, answer, expected)
    assert_exactly(d, answer, expected)


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


# A bead on a vertical hoop spun at ω about a vertical tangent (the axis at a (1 + sin θ) from the
# bead), released at rest relative to the hoop at θ = 0.3: energy in the turning frame,
# θ̇² = ω² ((sin θ + 2) sin θ − (sin θ₀ + 2) sin θ₀) + 2 g (cos θ − cos θ₀)/a, so it turns back where
# that vanishes again, at θ = 1.45783 for a = 0.2, ω = 6, g = 9.81 (a root without closed form).
HOOP_ON_A_TANGENT = r'''id = "hoop_tangent_axis"
title = "Bead on a vertical hoop spun about a vertical tangent line"

[parameters]
m = { dimension = "mass", domain = "positive", value = 0.05 }
g = { dimension = "acceleration", domain = "positive", value = 9.81 }
a = { dimension = "length", domain = "positive", value = 0.2 }
omega = { dimension = "angular_velocity", domain = "positive", value = 6.0 }

[coordinates]
rho = { dimension = "length", domain = "positive" }
phi = { dimension = "angle" }
z = { dimension = "length" }

[energy]
kinetic = "m/2*(rhodot^2 + rho^2*phidot^2 + zdot^2)"
potential = "m*g*z"

[[constraints]]
name = "drive"
f = "phi - omega*t"

[[constraints]]
name = "hoop"
f = "(rho - a)^2 + z^2 - a^2"

[parametrization.variables]
theta = { dimension = "angle", domain = [-3.1416, 3.1416] }

[parametrization.map]
rho = "a*(1 + sin(theta))"
z = "-a*cos(theta)"
phi = "omega*t"

[initial]
theta = 0.3
thetadot = 0

[[answers]]
name = "turning_angle"
kind = "numeric"
expr = "theta"
where = "thetadot = 0"
unit = "rad"
'''


def test_where_a_velocity_vanishes_without_a_closed_form_is_the_turning_point_found_numerically():
    """θ̇ = 0 from energy is √(f(θ)) = 0, which touches 0 at the turning point without crossing it; it
    was refused as having no root."""
    from grader.expressions.implicit import Implicit
    from grader.mechanics.special_values import _numeric

    d = derive(parse_scene(HOOP_ON_A_TANGENT, source="hoop_tangent_axis.toml"))
    rule = Implicit.from_json(d.implicit["turning_angle"])
    condition = parse_expression(rule.condition, d.scene.namespace).expr
    numbers = {s: sympy.Float(v, 30) for s, v in {"a": 0.2, "omega": 6.0, "g": 9.81}.items()}
    at_values = condition.xreplace({d.scene.namespace.symbol(n): v for n, v in numbers.items()})
    theta = d.scene.namespace.symbol("theta")
    assert abs(rule.solve(_numeric(at_values, theta)) - 1.45783) < 1e-4


@pytest.mark.parametrize("answer, expected", [
    # A bead on a hoop spun up about its vertical diameter, φ = α t²/2: with φ̇ = α t,
    # θ̈ = φ̇² sin θ cos θ − (g/a) sin θ; the motor's torque is d/dt(m a² sin²θ φ̇), and the hoop's
    # sideways push on the bead that torque over the lever a sin θ.
    ("equation_of_motion", "(alpha^2*t^2*cos(theta) - g/a)*sin(theta)"),
    ("drive_torque", "m*a^2*alpha*(2*t*thetadot*sin(theta)*cos(theta) + sin(theta)^2)"),
    ("sideways_force", "m*a*alpha*(2*t*thetadot*cos(theta) + sin(theta))"),
    # The lowest point stops being stable once φ̇² = α²t² passes g/a: a moment the parameters alone fix,
    # though the motion has no closed form (it was refused for that).
    ("lowest_point_unstable_time", "sqrt(g/a)/alpha"),
])
def test_a_bead_on_a_hoop_spun_up_at_a_constant_rate(answer, expected):
    d = derived("hoop_angular_acceleration")
    agree(d, answer, expected)
    assert_exactly(d, answer, expected)


@pytest.mark.parametrize("answer, expected", [
    # A solid ball (I = 2ma²/5) rolling in a bowl, its centre on a circle of radius R − a: energy gives
    # (7/10) m (R − a)² θ̇² = m g (R − a)(cos θ − cos θ₀); along the groove m (R − a) θ̈ = −m g sin θ + F
    # with F the friction, and for the spin (2/5) m a² ψ̈ = −a F: F = 2 m g sin θ/7 (against the slide);
    # across it N − m g cos θ = m (R − a) θ̇², so N = m g (17 cos θ − 10 cos θ₀)/7.
    ("normal_force", "m*g*(17*cos(theta) - 10*cos(theta0))/7"),
    ("friction_force", "2*m*g*sin(theta)/7"),
    ("bottom_normal_force", "m*g*(17 - 10*cos(theta0))/7"),
    # |F|/N = 2 sin θ/(17 cos θ − 10 cos θ₀) grows with |θ|: its largest is at the release, (2/7) tan θ₀
    # (it was refused: the bars' derivative ran the solve out of its budget).
    ("least_friction_coefficient", "2*tan(theta0)/7"),
    ("small_oscillation_frequency", "sqrt(5*g/(7*(R - a)))"),
])
def test_a_ball_rolling_in_a_bowl(answer, expected):
    d = derived("sphere_in_bowl")
    agree(d, answer, expected)
    assert_exactly(d, answer, expected)


# A bead on a hoop spun at ω about its vertical diameter, tied to the lowest point by a spring k of zero
# length, without [initial] (second red team of the session). At rest in the turning frame:
# m R ω² sin θ cos θ = (k R + m g) sin θ, so cos θₑ = (kR + mg)/(mRω²); the hoop's force along the radius
# is then λ = R (k cos θ − k + m ω² sin²θ) + m g cos θ = R (m ω² − k) there.
HOOP_SPRING_NO_START = r"""id = "hoop_bead_spring_to_bottom"
title = "Bead on a hoop spun about its vertical diameter, tied to the hoop's lowest point by a spring"
statement = '''
A smooth circular hoop of radius $R$ is turned at the constant angular velocity $\omega$ about its
vertical diameter. A bead of mass $m$ slides on it and is tied to the hoop's lowest point by a
spring of stiffness $k$ and zero natural length (Marion–Thornton, Morin). Coordinates in the hoop's
plane: the bead's distance $r$ from the centre and the angle $\theta$ from the downward vertical.
'''

[parameters]
m = { dimension = "mass", domain = "positive", value = 0.1 }
g = { dimension = "acceleration", domain = "positive", value = 9.81 }
k = { dimension = "stiffness", domain = "positive", value = 2.0 }
R = { dimension = "length", domain = "positive", value = 0.5 }
omega = { dimension = "angular_velocity", domain = "positive", value = 12.0 }

[coordinates]
r = { dimension = "length", domain = "positive" }
theta = { dimension = "angle", domain = [0.01, 3.1] }

[energy]
kinetic = "m/2*(rdot^2 + r^2*thetadot^2 + omega^2*r^2*sin(theta)^2)"
potential = "k/2*(r^2 - 2*R*r*cos(theta) + R^2) - m*g*r*cos(theta)"

[[constraints]]
name = "hoop"
f = "R - r"

[[answers]]
name = "equation_of_motion"
kind = "equation"
expr = "thetaddot"
in_terms_of = ["m", "g", "k", "R", "omega", "theta"]

[[answers]]
name = "equilibrium_cos"
expr = "cos(theta)"
where = "thetaddot = 0"
in_terms_of = ["m", "g", "k", "R", "omega"]

[[answers]]
name = "frequency"
kind = "small_oscillation"
expr = "theta"
where = "thetaddot = 0"

[[answers]]
name = "hoop_force_state"
expr = "lambda_hoop"
in_terms_of = ["m", "g", "k", "R", "omega", "theta", "thetadot"]
dimension = "force"

[[answers]]
name = "hoop_force_equilibrium"
expr = "hoop_force_state"
where = "thetaddot = 0"
in_terms_of = ["m", "g", "k", "R", "omega"]
dimension = "force"

[[answers]]
name = "critical_omega"
expr = "omega"
where = "equilibrium_cos = 1"
in_terms_of = ["m", "g", "k", "R"]
dimension = "angular_velocity"
"""


@pytest.mark.parametrize("answer, expected", [
    ("equilibrium_cos", "(k*R + m*g)/(m*R*omega^2)"),
    # no motion to follow: the answer at the equilibrium is taken at rest (it was refused, needing
    # [initial] for θ̇ from energy)
    ("hoop_force_equilibrium", "R*(m*omega^2 - k)"),
    ("critical_omega", "sqrt((k*R + m*g)/(m*R))"),
])
def test_an_answer_at_an_equilibrium_without_a_motion_is_taken_at_rest(answer, expected):
    d = derive(parse_scene(HOOP_SPRING_NO_START, source="hoop_bead_spring_to_bottom.toml"))
    agree(d, answer, expected)
    assert_exactly(d, answer, expected)


# A wedge M on a smooth floor tied to a wall by a spring k, a block m sliding down its face from rest
# (second red team of the session): the wedge oscillates, X(t) = −(m g sin α cos α/k)(1 − cos Ωt) with
# Ω² = k/(M + m sin²α), while the block's s(t) grows as t²; the face's force is
# m g cos α (M + m sin²α (1 − cos Ωt))/(M + m sin²α), least at t = 0.
WEDGE_ON_A_SPRING = r"""id = "wedge_spring_wall_block"
title = "Block sliding down a smooth wedge that is tied to a wall by a spring"
statement = '''
A wedge of mass $M$ with a smooth face inclined at $\alpha$ rests on a smooth floor; a horizontal
spring of stiffness $k$ joins its back to a wall, relaxed at the start. A block of mass $m$ is released
at rest on the face; everything starts at rest (Kleppner–Kolenkow, Irodov). Coordinates: the
wedge's displacement $X$ (towards the side the face looks to), the block's distance $s$ down the
face, and its height $n$ above the face along the normal. The face can only push.
'''

[parameters]
m = { dimension = "mass", domain = "positive", value = 0.5 }
M = { dimension = "mass", domain = "positive", value = 2.0 }
g = { dimension = "acceleration", domain = "positive", value = 9.81 }
k = { dimension = "stiffness", domain = "positive", value = 40.0 }
alpha = { dimension = "angle", domain = [0.05, 1.5], value = 0.6 }

[coordinates]
X = { dimension = "length" }
s = { dimension = "length" }
n = { dimension = "length" }

[energy]
kinetic = "M/2*Xdot^2 + m/2*((Xdot + sdot*cos(alpha) + ndot*sin(alpha))^2 + (ndot*cos(alpha) - sdot*sin(alpha))^2)"
potential = "k/2*X^2 + m*g*(n*cos(alpha) - s*sin(alpha))"

[[constraints]]
name = "face"
f = "n"
kind = "unilateral"

[initial]
X = 0
Xdot = 0
s = 0
sdot = 0

[[answers]]
name = "greatest_compression"
kind = "maximum"
expr = "-X"
in_terms_of = ["m", "M", "g", "k", "alpha"]
dimension = "length"

[[answers]]
name = "least_normal"
kind = "minimum"
expr = "lambda_face"
in_terms_of = ["m", "M", "g", "alpha"]
dimension = "force"
"""


@pytest.mark.parametrize("answer, expected", [
    # over the coordinate X the motion "runs away" (s grows): the extreme is taken over time instead
    ("greatest_compression", "m*g*sin(2*alpha)/k"),
    ("least_normal", "M*m*g*cos(alpha)/(M + m*sin(alpha)^2)"),
])
def test_an_extreme_where_another_coordinate_runs_away_is_taken_over_time(answer, expected):
    d = derive(parse_scene(WEDGE_ON_A_SPRING, source="wedge_spring_wall_block.toml"))
    agree(d, answer, expected)
    assert_exactly(d, answer, expected)
