"""The thirteenth engine red team (2026-11-28): answer kinds over the motion (values in time, extremes,
special values by a condition on a parameter) in textbook scenes.

1. An extreme over a motion that goes round and round an angle (a block launched round the whole of a
   vertical loop, a bob on a rod launched over the top) was refused ("the motion runs away"): energy never
   turns the angle back, and the range of the motion was taken to be unknown. Where u̇² from energy is a
   2π-periodic function of the angle alone, the motion covers every angle, and the extreme of a quantity
   periodic in it is over the whole turn: the least normal force on the loop is m (v0²/R − 5 g), at the
   top. A quantity that is not periodic in the angle (the angle itself) has no extreme, and says so.
2. A cyclic coordinate in time beside a motion with no closed form (the centre of mass of two pucks
   joined by a spring, X = X0 + Vx t; the foot of a falling stick on a smooth floor, x = x0) was refused
   with the rest of the motion ("no closed form in elementary functions"): its conserved momentum gives
   its velocity free of the other coordinates, so its motion is known alone. It is used now when the
   answer needs nothing else; an angle whose velocity depends on the others (φ̇ = l0² w0/r²) stays refused.
3. Checked: a stick falling with its lower end on a smooth floor (θ̇ > 0 as it falls, the floor's force,
   its least value, m g/4 as it lands flat). Also checked by hand and numerically without a change (not
   tested here): a particle in a tube turned at ω in a vertical plane (r(t), ṙ(t), the drive's torque), a
   mass on a vertical spring released at its natural length (x(t), the times to the equilibrium and to the
   lowest point, the extremes), a particle pushed off a sphere at v0 (where and how fast it leaves, the v0
   that makes it leave at θ), a bead on a turning hoop released at θ0 (its highest point, the ω that holds
   it at θ), and a pendulum released at θ0 (largest tension, speed and horizontal pull).

Each answer is derived by hand (in the comment above it) and checked against a numerical integration
(scipy) of the equations of motion written independently of the engine.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from grader.mechanics.lagrange import derive
from grader.mechanics.scene import SceneError, parse_scene
from tests.mechanics.test_red_team_scenes_7 import at

# -- 1. extremes over a motion that goes round an angle ---------------------------------------------
# Polar r, φ about the loop's centre, φ from the downward vertical, launched at the bottom at v0.
# Energy: v² = R² φ̇² = v0² − 2 g R (1 − cos φ) > 0 for every φ when v0² > 4 g R (the track, v0² > 5 g R,
# never lets go). Track (f = R − r, pushes inwards): N = λ = m (v²/R + g cos φ) = m (v0²/R − 2 g + 3 g cos φ);
# rod (f = r − l): the tension −λ is the same. Least at the top (φ = π): m (v0²/R − 5 g), with the least
# speed √(v0² − 4 g R); largest at the bottom: m (v0²/R + g).
_ROUND = '''
id = "round_the_loop"
title = "Round a vertical loop"
[parameters]
m = {{ dimension = "mass", domain = "positive", value = 0.2 }}
g = {{ dimension = "acceleration", domain = "positive", value = 9.81 }}
R = {{ dimension = "length", domain = "positive", value = 0.5 }}
v0 = {{ dimension = "velocity", domain = [5.0, 20.0], value = 6.0 }}
[coordinates]
r = {{ dimension = "length", domain = "positive" }}
phi = {{ dimension = "angle" }}
[energy]
kinetic = "m/2*(rdot^2 + r^2*phidot^2)"
potential = "-m*g*r*cos(phi)"
[[constraints]]
name = "c"
f = "{f}"
kind = "{kind}"
[initial]
phi = 0
phidot = "{sign}v0/R"
[[answers]]
name = "force"
prompt = "normal force (track) or tension (rod), as a function of phi"
expr = "{force}"
in_terms_of = ["m", "g", "R", "v0", "phi"]
dimension = "force"
[[answers]]
name = "least_force"
prompt = "least force over the motion"
kind = "minimum"
expr = "force"
dimension = "force"
[[answers]]
name = "largest_force"
prompt = "largest force over the motion"
kind = "maximum"
expr = "force"
dimension = "force"
[[answers]]
name = "least_speed"
prompt = "least speed over the motion"
kind = "minimum"
expr = "R*abs(phidot)"
dimension = "velocity"
'''


def _round(case: str) -> str:
    track = case.startswith("track")
    return _ROUND.format(f="R - r" if track else "r - R", kind="unilateral" if track else "bilateral",
                         force="lambda_c" if track else "-lambda_c", sign="-" if case.endswith("backwards") else "")


def _integrated_round(m, g, R, v0, sign):
    """The force and speed along three turns, from φ̈ = −g sin φ/R integrated numerically."""
    turn = 2 * math.pi * R / math.sqrt(v0 ** 2 - 4 * g * R)
    solution = solve_ivp(lambda t, s: [s[1], -g * math.sin(s[0]) / R], [0, 3 * turn], [0, sign * v0 / R],
                         rtol=1e-12, atol=1e-12, max_step=turn / 4000)
    phi, phidot = solution.y
    return m * (R * phidot ** 2 + g * np.cos(phi)), R * np.abs(phidot)


@pytest.mark.parametrize("case", ["track", "rod", "track_backwards"])
def test_extremes_over_a_motion_that_goes_round(case):
    derivation = derive(parse_scene(_round(case), source=f"{case}.toml"))
    for m, g, R, v0 in ((0.2, 9.81, 0.5, 6.0), (1.3, 1.6, 2.0, 4.1)):
        point = {"m": m, "g": g, "R": R, "v0": v0}
        force, speed = _integrated_round(m, g, R, v0, -1 if case.endswith("backwards") else 1)
        least = at(derivation, derivation.answers["least_force"], point)
        assert least == pytest.approx(m * (v0 ** 2 / R - 5 * g), rel=1e-12)
        assert least == pytest.approx(force.min(), rel=1e-6)
        largest = at(derivation, derivation.answers["largest_force"], point)
        assert largest == pytest.approx(m * (v0 ** 2 / R + g), rel=1e-12)
        assert largest == pytest.approx(force.max(), rel=1e-6)
        slowest = at(derivation, derivation.answers["least_speed"], point)
        assert slowest == pytest.approx(math.sqrt(v0 ** 2 - 4 * g * R), rel=1e-12)
        assert slowest == pytest.approx(speed.min(), rel=1e-6)


# The angle itself grows without bound on such a motion: it has no maximum, and is refused, saying why.
def test_a_quantity_not_periodic_in_an_angle_that_goes_round_has_no_extreme():
    text = _round("track") + '''
[[answers]]
name = "farthest"
prompt = "largest angle"
kind = "maximum"
expr = "phi"
'''
    with pytest.raises(SceneError, match="goes round and round in phi"):
        derive(parse_scene(text, source="farthest.toml"))


# A swing that energy turns back keeps its extremes (the bob released at rest at φ0 = 1: least tension
# m g cos φ0 at the ends, largest m g (3 − 2 cos φ0) at the bottom).
def test_a_swing_that_turns_back_keeps_its_extremes():
    text = _round("rod").replace('phidot = "v0/R"', 'phi = 1\nphidot = 0').replace("phi = 0\n", "", 1)
    derivation = derive(parse_scene(text, source="swing.toml"))
    point = {"m": 0.2, "g": 9.81, "R": 0.5, "v0": 6.0}
    assert at(derivation, derivation.answers["least_force"], point) == pytest.approx(0.2 * 9.81 * math.cos(1))
    assert at(derivation, derivation.answers["largest_force"], point) == pytest.approx(0.2 * 9.81 * (3 - 2 * math.cos(1)))


# -- 2. a cyclic coordinate's motion in time when the rest of the motion has none ---------------------
# Two pucks of mass m joined by a spring (k, l0) on a smooth table: centre of mass X, Y, separation r at
# the angle φ. T = m (Ẋ² + Ẏ²) + (m/4)(ṙ² + r² φ̇²), V = k (r − l0)²/2. X, Y are cyclic with momenta
# 2 m Ẋ, 2 m Ẏ: X = X0 + Vx t, Y = Vy t whatever the spring does; r(t) is not elementary (it was refused
# with it: "cannot be written in terms of t ... the motion has no closed form"). φ̇ = l0² w0/r² depends on
# r, so φ(t) stays refused. Checked against the two pucks' Cartesian equations integrated numerically.
_PUCKS = '''
id = "pucks_on_a_spring"
title = "Two pucks joined by a spring on a smooth table"
[parameters]
m = { dimension = "mass", domain = "positive", value = 0.5 }
k = { dimension = "stiffness", domain = "positive", value = 20.0 }
l0 = { dimension = "length", domain = "positive", value = 0.4 }
X0 = { dimension = "length", domain = "real", value = 0.3 }
Vx = { dimension = "velocity", domain = "positive", value = 1.0 }
Vy = { dimension = "velocity", domain = "positive", value = 0.7 }
w0 = { dimension = "angular_velocity", domain = "positive", value = 3.0 }
[coordinates]
X = { dimension = "length" }
Y = { dimension = "length" }
r = { dimension = "length", domain = "positive" }
phi = { dimension = "angle" }
[energy]
kinetic = "m*(Xdot^2 + Ydot^2) + m/4*(rdot^2 + r^2*phidot^2)"
potential = "k/2*(r - l0)^2"
[initial]
X = "X0"
Y = 0
Xdot = "Vx"
Ydot = "Vy"
r = "l0"
rdot = 0
phi = 0
phidot = "w0"
[[answers]]
name = "centre_x"
prompt = "X of the centre of mass at the time t"
expr = "X"
in_terms_of = ["X0", "Vx", "t"]
[[answers]]
name = "centre_y"
prompt = "Y of the centre of mass at the time t"
expr = "Y"
in_terms_of = ["Vy", "t"]
[[answers]]
name = "centre_speed_squared"
prompt = "squared speed of the centre of mass at the time t"
expr = "Xdot^2 + Ydot^2"
in_terms_of = ["Vx", "Vy", "t"]
[[answers]]
name = "rdot_squared"
prompt = "rdot^2 as a function of r"
expr = "rdot^2"
in_terms_of = ["m", "k", "l0", "w0", "r"]
'''


def test_the_centre_of_mass_in_time_beside_a_motion_without_closed_form():
    derivation = derive(parse_scene(_PUCKS, source="pucks.toml"))
    m, k, l0, x0, vx, vy, w0 = 0.5, 20.0, 0.4, 0.3, 1.0, 0.7, 3.0
    # Puck 1 at centre − (r/2) e, puck 2 at centre + (r/2) e; the spring pulls each towards the other.
    def rhs(t, s):
        p1, p2, v1, v2 = s[0:2], s[2:4], s[4:6], s[6:8]
        d = np.subtract(p2, p1)
        r = math.hypot(*d)
        f = k * (r - l0) * d / r  # on puck 1, towards puck 2 when stretched
        return [*v1, *v2, *(f / m), *(-f / m)]
    e, n = np.array([1.0, 0.0]), np.array([0.0, 1.0])
    c0, vc = np.array([x0, 0.0]), np.array([vx, vy])
    state = [*(c0 - l0 / 2 * e), *(c0 + l0 / 2 * e), *(vc - l0 / 2 * w0 * n), *(vc + l0 / 2 * w0 * n)]
    solution = solve_ivp(rhs, [0, 3.0], state, rtol=1e-11, atol=1e-12, dense_output=True)
    point = {"m": m, "k": k, "l0": l0, "X0": x0, "Vx": vx, "Vy": vy, "w0": w0}
    for t in (0.4, 1.7, 2.9):
        s = solution.sol(t)
        centre = (s[0:2] + s[2:4]) / 2
        assert at(derivation, derivation.answers["centre_x"], {**point, "t": t}) == pytest.approx(centre[0], abs=1e-8)
        assert at(derivation, derivation.answers["centre_y"], {**point, "t": t}) == pytest.approx(centre[1], abs=1e-8)
        assert at(derivation, derivation.answers["centre_speed_squared"], {**point, "t": t}) == pytest.approx(vx ** 2 + vy ** 2)
        r = math.hypot(*(s[2:4] - s[0:2]))
        rdot = np.dot(s[6:8] - s[4:6], s[2:4] - s[0:2]) / r
        assert at(derivation, derivation.answers["rdot_squared"], {**point, "r": r}) == pytest.approx(rdot ** 2, abs=1e-8)


def test_a_cyclic_coordinate_whose_velocity_needs_the_rest_of_the_motion_stays_refused():
    text = _PUCKS + '''
[[answers]]
name = "angle_in_time"
prompt = "phi at the time t"
expr = "phi"
in_terms_of = ["l0", "w0", "t"]
'''
    with pytest.raises(SceneError, match="angle_in_time.*no closed form"):
        derive(parse_scene(text, source="pucks_angle.toml"))


# -- 3. a stick falling with its lower end on a smooth floor ----------------------------------------
# Centre (x, y), y = (l/2) cos θ, θ from the upward vertical, released at rest at θ0. No horizontal force:
# x = x0 throughout (x is cyclic, m ẋ = 0; it was refused with θ(t), which is not elementary). Energy:
# (m l²/24)(1 + 3 sin²θ) θ̇² = (m g l/2)(cos θ0 − cos θ), θ̇ > 0 as it falls. The floor's force
# N = m (g + ÿ) = m g (4 − 6 cos θ cos θ0 + 3 cos²θ)/(1 + 3 sin²θ)², m g/4 as it lands flat; its least
# value over the fall is found here by an integration of Newton's equations (N − m g = m ÿ,
# (m l²/12) θ̈ = N (l/2) sin θ).
_STICK = '''
id = "falling_stick"
title = "Stick falling with its lower end on a smooth floor"
[parameters]
m = { dimension = "mass", domain = "positive", value = 1.0 }
g = { dimension = "acceleration", domain = "positive", value = 9.81 }
l = { dimension = "length", domain = "positive", value = 1.0 }
x0 = { dimension = "length", domain = "real", value = 0.2 }
theta0 = { dimension = "angle", domain = [0.01, 1.5], value = 0.3 }
[coordinates]
theta = { dimension = "angle", domain = [0, 1.5708] }
x = { dimension = "length" }
y = { dimension = "length" }
[energy]
kinetic = "m/2*(xdot^2 + ydot^2) + m*l^2/24*thetadot^2"
potential = "m*g*y"
[[constraints]]
name = "floor"
f = "y - l/2*cos(theta)"
kind = "unilateral"
[initial]
theta = "theta0"
thetadot = 0
x = "x0"
xdot = 0
[[answers]]
name = "spin"
prompt = "thetadot as a function of theta"
expr = "thetadot"
in_terms_of = ["g", "l", "theta", "theta0"]
[[answers]]
name = "floor_force"
prompt = "the floor's force as a function of theta"
expr = "lambda_floor"
in_terms_of = ["m", "g", "theta", "theta0"]
dimension = "force"
[[answers]]
name = "landing_force"
prompt = "the floor's force as the stick lands flat"
expr = "floor_force"
where = "theta = pi/2"
dimension = "force"
[[answers]]
name = "least_floor_force"
prompt = "the least force of the floor during the fall"
kind = "minimum"
expr = "floor_force"
dimension = "force"
[[answers]]
name = "centre_x"
prompt = "x of the centre at the time t"
expr = "x"
in_terms_of = ["x0", "t"]
'''


def test_a_stick_falling_on_a_smooth_floor():
    derivation = derive(parse_scene(_STICK, source="stick.toml"))
    assert derivation.answers["centre_x"] == derivation.scene.namespace.symbol("x0")
    for g, l, theta0 in ((9.81, 1.0, 0.3), (3.0, 2.5, 1.1)):
        def rhs(t, s):
            th, w = s
            return [w, (g - l / 2 * math.cos(th) * w * w) * l / 2 * math.sin(th) / (l * l / 12 + l * l / 4 * math.sin(th) ** 2)]
        flat = lambda t, s: s[0] - math.pi / 2
        flat.terminal = True
        solution = solve_ivp(rhs, [0, 100], [theta0, 0], rtol=1e-12, atol=1e-12, events=flat, dense_output=True)
        forces = []
        for t in np.linspace(0, solution.t[-1], 4001):
            th, w = solution.sol(t)
            force = g - l / 2 * (math.cos(th) * w * w + math.sin(th) * rhs(t, [th, w])[1])
            forces.append(force)
            point = {"m": 1.0, "g": g, "l": l, "theta0": theta0, "theta": th}
            if 0 < t and math.isclose(t, solution.t[-1] * 0.6, rel_tol=1e-3):
                assert at(derivation, derivation.answers["spin"], point) == pytest.approx(w, rel=1e-8)
                assert at(derivation, derivation.answers["floor_force"], point) == pytest.approx(force, rel=1e-8)
        point = {"m": 1.0, "g": g, "l": l, "theta0": theta0}
        assert at(derivation, derivation.answers["landing_force"], point) == pytest.approx(g / 4, rel=1e-12)
        assert at(derivation, derivation.answers["least_floor_force"], point) == pytest.approx(min(forces), rel=1e-6)


# -- 4. a parameter by a condition, as a formula over a state [initial] gives a number ---------------
# A bob on a string (l) launched at the bottom at v0, φ from the downward vertical. The string's tension
# T = m (v²/l + g cos φ), v² = v0² − 2 g l (1 − cos φ): T = m (g (3 cos φ − 2) + v0²/l). The launch speed
# at which the string goes slack at φ is v0 = √(g l (2 − 3 cos φ)) (real for cos φ < 2/3, reached for
# cos φ < 0). It was refused ("no real root for v0 anywhere in its domain"): the root was only tried at
# φ = 0.7 (φ0 = 0 from [initial]), where 2 − 3 cos φ < 0. Checked by launching the bob at that v0
# (φ̈ = −g sin φ/l integrated) and finding where the tension first vanishes. The speed and height where it
# goes slack for a given v0 (v² = (v0² − 2 g l)/3, −l cos φ = (v0²/g − 2 l)/3) came out right before.
_SLACK = '''
id = "string_goes_slack"
title = "Bob on a string launched at the bottom"
[parameters]
m = { dimension = "mass", domain = "positive", value = 0.2 }
g = { dimension = "acceleration", domain = "positive", value = 9.81 }
l = { dimension = "length", domain = "positive", value = 0.5 }
v0 = { dimension = "velocity", domain = "positive", value = 4.0 }
[coordinates]
r = { dimension = "length", domain = "positive" }
phi = { dimension = "angle" }
[energy]
kinetic = "m/2*(rdot^2 + r^2*phidot^2)"
potential = "-m*g*r*cos(phi)"
[[constraints]]
name = "string"
f = "r - l"
kind = "unilateral"
[initial]
phi = 0
phidot = "v0/l"
[[answers]]
name = "tension"
prompt = "the string's tension as a function of phi"
expr = "-lambda_string"
in_terms_of = ["m", "g", "l", "v0", "phi"]
dimension = "force"
[[answers]]
name = "slack_launch_speed"
prompt = "the launch speed for which the string goes slack at phi"
expr = "v0"
where = "tension = 0"
in_terms_of = ["g", "l", "phi"]
'''


@pytest.mark.parametrize("phi_slack", [1.9, 2.4, 2.9])
def test_the_launch_speed_for_a_string_to_go_slack_at_an_angle(phi_slack):
    derivation = derive(parse_scene(_SLACK, source="slack.toml"))
    for g, l in ((9.81, 0.5), (1.6, 2.2)):
        v0 = at(derivation, derivation.answers["slack_launch_speed"], {"g": g, "l": l, "phi": phi_slack})
        assert v0 == pytest.approx(math.sqrt(g * l * (2 - 3 * math.cos(phi_slack))), rel=1e-12)
        slack = lambda t, s: g * (3 * math.cos(s[0]) - 2) + v0 ** 2 / l
        slack.terminal = True
        solution = solve_ivp(lambda t, s: [s[1], -g * math.sin(s[0]) / l], [0, 100], [0, v0 / l],
                             rtol=1e-12, atol=1e-12, events=slack)
        assert solution.y_events[0][0][0] == pytest.approx(phi_slack, rel=1e-8)
