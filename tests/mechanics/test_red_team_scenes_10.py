"""The thirteenth engine red team (2026-11-28): answer kinds over the motion (values in time, extremes,
special values by a condition on a parameter) in textbook scenes.

1. An extreme over a motion that goes round and round an angle (a block launched round the whole of a
   vertical loop, a bob on a rod launched over the top) was refused ("the motion runs away"): energy never
   turns the angle back, and the range of the motion was taken to be unknown. Where u̇² from energy is a
   2π-periodic function of the angle alone, the motion covers every angle, and the extreme of a quantity
   periodic in it is over the whole turn: the least normal force on the loop is m (v0²/R − 5 g), at the
   top. A quantity that is not periodic in the angle (the angle itself) has no extreme, and says so.
2. Checked without a change: a stick falling with its lower end on a smooth floor (θ̇², θ̇ > 0 as it
   falls, the floor's force, its least value, m g/4 as it lands flat), a particle in a tube turned at ω in
   a vertical plane (r(t), ṙ(t), the drive's torque in t), a mass on a vertical spring released at its
   natural length (x(t), the times to the equilibrium and to the lowest point, the extremes), a particle
   pushed off the top of a sphere at v0 (where and how fast it leaves; the v0 that makes it leave at θ),
   a bead on a turning hoop released at θ0 (its highest point, the ω that holds it at rest at θ), and the
   largest tension, speed and horizontal pull of a pendulum released at θ0.

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

