"""The eleventh engine red team (2026-11-27): a root outside an angle's half-line domain, a realness
test taken at one arbitrary state, a motion on an invariant subset, a refusal with a false reason,
and a small-oscillation frequency at the root of a cubic that ran past the whole budget.

0. A root in an angle declared ``positive`` (or ``nonnegative``) is brought inside: θ = −π/6 came out
   for θ > 0 (kept because its image by 2π is inside); now its least image inside, 11π/6.
1. A condition whose roots are real on part of the domain of the state it is written in (the steady
   precession of a prolate top, A > C: (A − C) cos θ φ̇² − C ψ̇ φ̇ + M g l = 0) was said to have "no real
   root anywhere": the realness was tested at ψ̇ = 0.7 only. Both roots are alternatives; with [initial]
   whose sense both have, nothing decides either (it said "give [initial]" though [initial] was given).
2. An elastic pendulum released hanging straight down (θ = 0, θ̇ = 0, where θ̈ = 0) stays there: the
   motion reduces to r. Its extremes were refused as "the motion runs away"; released tilted, the
   refusal now gives the true reason (θ moves too: energy alone does not give r's range).
3. A small-oscillation frequency at the equilibrium that is the root of a cubic (a particle on a cone
   held by gravity and a −k/s attraction) spent the whole 60 s tidying Cardano's root: the tidying
   has a budget now, and the closed form comes as it is where the budget runs out.

Each answer is derived by hand (in the comment above it) and compared at several parameter points.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy

from grader.mechanics.lagrange import derive
from grader.mechanics.scene import SceneError, parse_scene
from tests.mechanics.conftest import SCENES
from tests.mechanics.test_red_team_scenes_7 import _scene, at

NOT_SIMULATED = SCENES / "not_simulated"


def values_of(derivation, answer: str, point: dict[str, float]) -> list[float]:
    """The reference and every alternative of an answer at named numbers, sorted."""
    forms = [derivation.answers[answer]] + derivation.alternatives.get(answer, [])
    return sorted(at(derivation, f, point) for f in forms)


# -- 0. a root outside an angle's half-line is brought inside -----------------------------------------
# A pendulum, θ̈ = −(g/l) sin θ; θ̈ = g/(2l) where sin θ = −1/2: θ = −π/6 + 2πj and 7π/6 + 2πj. With θ
# declared positive the least such angles are 7π/6 and 11π/6 (−π/6 is outside: it was the reference).
@pytest.mark.parametrize("domain, expected", [
    ('"positive"', [7 * math.pi / 6, 11 * math.pi / 6]),
    ('"nonnegative"', [7 * math.pi / 6, 11 * math.pi / 6]),
    ('"real"', [-math.pi / 6, 7 * math.pi / 6]),  # solve's own roots: both in the domain
])
@pytest.mark.parametrize("point", [{"g": 9.81, "l": 0.8, "m": 0.2}, {"g": 1.6, "l": 2.0, "m": 3.0}])
def test_every_root_of_an_angle_on_a_half_line_is_inside_it(domain, expected, point):
    text = _scene(NOT_SIMULATED / "pendulum_angle_positive.toml", [('domain = "positive"', f"domain = {domain}")])
    derivation = derive(parse_scene(text, source="pendulum.toml"))
    assert values_of(derivation, "angle", point) == pytest.approx(expected, abs=1e-12)


# A bead on a horizontal hoop, a spring to the hoop's point (0, R) (see test_red_team_scenes_7): the
# spring's length is 2R|cos(θ/2)|, V' = 0 where sin θ = 0 (θ = 0, π) or |cos(θ/2)| = c = L0/(2R)
# (θ = ±2 acos c, ±2 acos(−c)), each + 2πj. For θ > 0 the equilibrium θ = 0 is θ = 2π (it was returned
# as 0, outside); for θ ≥ 0 it is 0. Every value must lie in the domain, and the values cover the four
# configurations.
HOOP_POINTS = [{"m": 0.1, "R": 0.5, "k": 10.0, "L0": 0.6}, {"m": 0.3, "R": 1.2, "k": 4.0, "L0": 0.5}]


@pytest.mark.parametrize("domain, smallest", [('"positive"', 2 * math.pi), ('"nonnegative"', 0.0)])
@pytest.mark.parametrize("point", HOOP_POINTS)
def test_the_equilibria_of_a_hoop_bead_on_a_half_line_are_all_inside_it(domain, smallest, point):
    text = _scene(NOT_SIMULATED / "horizontal_hoop_spring.toml", [("[0.05, 3.1]", domain)])
    text = text[:text.index('[[answers]]\nname = "omega_small"')]
    derivation = derive(parse_scene(text, source="hoop.toml"))
    numbers = values_of(derivation, "equilibrium_theta", point)
    assert all(v > 0 if domain == '"positive"' else v >= 0 for v in numbers), numbers
    assert at(derivation, derivation.answers["equilibrium_theta"], point) == pytest.approx(smallest, abs=1e-12)
    c = point["L0"] / (2 * point["R"])
    configurations = {round(v % (2 * math.pi), 9) for v in numbers}
    assert configurations == {round(v % (2 * math.pi), 9) for v in
                              (0.0, math.pi, 2 * math.acos(c), 2 * math.acos(-c))}


# -- 1. steady precession of a prolate top ------------------------------------------------------------
# T = A(θ̇² + sin²θ φ̇²)/2 + C(ψ̇ + φ̇ cos θ)²/2, V = M g l cos θ: the θ equation is
# A θ̈ = sin θ [(A − C) cos θ φ̇² − C ψ̇ φ̇ + M g l], so θ̈ = 0 off the axis where
# φ̇ = (C ψ̇ ± √(C² ψ̇² − 4 (A − C) M g l cos θ))/(2 (A − C) cos θ), both real where C²ψ̇² ≥ 4(A − C)Mgl cos θ
# (always where (A − C) cos θ < 0; at θ = 1, ψ̇ = 100 with the scene's numbers 4.0734 and 106.9755).
def _discriminant(p: dict[str, float]) -> float:
    a, c, mgl = p["A"], p["C"], p["M"] * p["g"] * p["l"]
    return c * c * p["psidot"] ** 2 - 4 * (a - c) * mgl * math.cos(p["theta"])


def _precessions(p: dict[str, float]) -> list[float]:
    a, c = p["A"], p["C"]
    cos, spin = math.cos(p["theta"]), p["psidot"]
    root = math.sqrt(_discriminant(p))
    return sorted((c * spin + s * root) / (2 * (a - c) * cos) for s in (-1, 1))


TOP = {"M": 0.3, "g": 9.81, "l": 0.04, "A": 0.0008, "C": 0.0003}
TOP_STATES = [{"theta": 1.0, "psidot": 100.0}, {"theta": 0.4, "psidot": 300.0}, {"theta": 2.0, "psidot": 5.0},
              {"theta": 2.8, "psidot": -40.0}]
INITIAL = '''
[initial]
theta = 1.5
thetadot = 0
phi = 0
phidot = 8
psi = 0
psidot = 100
'''


def _top_point(variant: str, state: dict) -> dict:
    return {**TOP, **state, **({"C": 0.0011} if variant == "oblate" else {})}


# Each variant at the states where it has a steady precession: the obtuse one (θ in [1.6, 3.1]) only at those tilts
_TOP_CASES = [(variant, state) for variant in ("as_is", "obtuse", "with_initial", "oblate") for state in TOP_STATES
              if not (variant == "obtuse" and state["theta"] < 1.6) and _discriminant(_top_point(variant, state)) >= 0]


@pytest.mark.parametrize("variant, state", _TOP_CASES)
def test_both_steady_precessions_of_a_top_are_right_answers(variant, state):
    text = (NOT_SIMULATED / "top_steady_precession_prolate.toml").read_text()
    point = _top_point(variant, state)
    if variant == "obtuse":  # the tilt below the horizontal only: cos θ < 0, both roots real always
        text = text.replace("domain = [0, 3.1416]", "domain = [1.6, 3.1]")
    elif variant == "with_initial":  # spun at 100 from θ = 1.5, φ̇ = 8: both roots have that sense
        text += INITIAL
    elif variant == "oblate":  # A < C: one root of each sign
        text = text.replace('value = 0.0003, below = "A"', "value = 0.0011")
    derivation = derive(parse_scene(text, source="top.toml"))
    assert len(derivation.alternatives["steady_precession"]) == 1
    assert values_of(derivation, "steady_precession", point) == pytest.approx(_precessions(point), rel=1e-12)


def test_the_precession_at_the_reported_state_has_the_reported_values():
    derivation = derive(parse_scene((NOT_SIMULATED / "top_steady_precession_prolate.toml").read_text(), "top.toml"))
    got = values_of(derivation, "steady_precession", {**TOP, "theta": 1.0, "psidot": 100.0})
    assert got == pytest.approx([4.0734, 106.9755], abs=1e-4)


def test_a_parameter_left_out_of_in_terms_of_is_named_not_a_missing_root():
    # C = k A with k a parameter: the answer is in k, which in_terms_of leaves out; the refusal says so
    # (it said "no real root anywhere"), and with k named the roots are those above with C = k A.
    text = (NOT_SIMULATED / "top_steady_precession_prolate.toml").read_text()
    text = text.replace('C = { dimension = "moment_of_inertia", domain = "positive", value = 0.0003, below = "A" }',
                        'q = { dimension = "dimensionless", domain = [0.1, 0.9], value = 0.375 }')
    text = text.replace("C/2*", "q*A/2*")
    with pytest.raises(SceneError, match="still depends on q"):
        derive(parse_scene(text.replace('"A", "C", ', '"A", '), "ratio.toml"))
    derivation = derive(parse_scene(text.replace('"A", "C", ', '"A", "q", '), "ratio.toml"))
    for state in TOP_STATES:
        point = {**{n: v for n, v in TOP.items() if n != "C"}, "q": 0.375, **state}
        assert values_of(derivation, "steady_precession", point) == pytest.approx(
            _precessions({**point, "C": 0.375 * TOP["A"]}), rel=1e-12)


# -- 2. an elastic pendulum on its invariant line θ = 0 -----------------------------------------------
# Released from rest at θ = 0: θ̈ = −(g sin θ + 2 ṙ θ̇)/r vanishes there with θ̇ = 0, so θ stays 0 and
# m r̈ = m g − k (r − l0). Energy: m ṙ²/2 − m g r + k (r − l0)²/2 is constant, ṙ = 0 at r0 and at its
# mirror about the equilibrium l0 + m g/k: r1 = 2(l0 + m g/k) − r0. From r0 below the equilibrium (the
# scene, r0 = 0.65 < 0.7226) r runs over [r0, r1]: the largest length is r1 = 0.79525 m, the least
# tension k (r0 − l0) = 2.0 N. From r0 above it, the largest length is r0 and the least tension
# k (r1 − l0) = k (l0 − r0) + 2 m g.
HANGING = SCENES / "elastic_pendulum_hanging.toml"
HANG_POINTS = [{"m": 0.5, "g": 9.81, "k": 40.0, "l0": 0.6}, {"m": 1.2, "g": 9.81, "k": 150.0, "l0": 0.3},
               {"m": 0.1, "g": 1.6, "k": 2.0, "l0": 1.0}]


@pytest.mark.parametrize("r0, answer, expected, below", [
    ("0.65", "r_max", "2*(l0 + m*g/k) - r0", True),
    ("0.65", "tension_min", "k*(r0 - l0)", True),
    ("0.9", "r_max", "r0", False),
    ("0.9", "tension_min", "k*(l0 - r0) + 2*m*g", False),
])
def test_the_extremes_of_an_elastic_pendulum_released_hanging_straight_down(r0, answer, expected, below):
    text = HANGING.read_text().replace("value = 0.65 }", f"value = {r0} }}")
    derivation = derive(parse_scene(text, "hanging.toml"))
    for p in HANG_POINTS:
        # r0 on the same side of the equilibrium as the scene's, where that closed form holds
        equilibrium = p["l0"] + p["m"] * p["g"] / p["k"]
        for r in (p["l0"] + 0.3 * (equilibrium - p["l0"]), equilibrium * 1.4):
            if (r < equilibrium) == below:
                point = {**p, "r0": r}
                assert at(derivation, derivation.answers[answer], point) == pytest.approx(
                    at(derivation, expected, point), rel=1e-12)


def test_the_reported_numbers_of_the_hanging_elastic_pendulum():
    derivation = derive(parse_scene(HANGING.read_text(), "hanging.toml"))
    point = {"m": 0.5, "g": 9.81, "k": 40.0, "l0": 0.6, "r0": 0.65}
    assert at(derivation, derivation.answers["r_max"], point) == pytest.approx(0.79525, abs=1e-12)
    assert at(derivation, derivation.answers["tension_min"], point) == pytest.approx(2.0, abs=1e-12)


@pytest.mark.parametrize("start", [("theta = 0\n", "theta = 0.3\n"), ("thetadot = 0\n", "thetadot = 1.5\n")])
def test_an_elastic_pendulum_that_swings_too_is_refused_with_the_true_reason(start):
    # Released tilted (or pushed sideways), θ moves: energy gives ṙ² only with θ and θ̇ in it. The
    # motion is bounded; "the motion runs away" was the reason given.
    text = HANGING.read_text().replace(*start)
    with pytest.raises(SceneError) as refused:
        derive(parse_scene(text, "tilted.toml"))
    message = str(refused.value)
    assert "theta moves as well as r" in message and "runs away" not in message


def test_a_condition_in_the_swinging_state_is_still_a_formula_in_it():
    # r̈ = g cos θ + k (l0 − r)/m + r θ̇² = 0 at r = (m g cos θ + k l0)/(k − m θ̇²): a formula over the
    # states, not the one motion on θ = 0 (whose coordinates at rest are not substituted there).
    text = HANGING.read_text() + '''
[[answers]]
name = "r_eq"
prompt = "r where rddot vanishes"
expr = "r"
where = "rddot = 0"
in_terms_of = ["m", "g", "k", "l0", "theta", "thetadot"]
'''
    derivation = derive(parse_scene(text, "both.toml"))
    for p in HANG_POINTS:
        for theta, thetadot in ((0.4, 0.5), (-1.0, 1.1)):
            point = {**p, "theta": theta, "thetadot": thetadot}
            assert at(derivation, derivation.answers["r_eq"], point) == pytest.approx(at(
                derivation, "(m*g*cos(theta) + k*l0)/(k - m*thetadot^2)", point), rel=1e-12)


# -- 3. a small-oscillation frequency at the root of a cubic ------------------------------------------
# On the cone (x, y, z) = (s sin α cos φ, s sin α sin φ, s cos α): T = m(ṡ² + s² sin²α φ̇²)/2,
# V = −k/s + m g s cos α; p_φ = m s² sin²α φ̇ = L = m s0² sin²α Ω. Routh: m s̈ = L²/(m s³ sin²α) − k/s² −
# m g cos α, zero at s* with m g cos α s³ + k s − L²/(m sin²α) = 0 (one real root: the cubic increases).
# ω² = −∂s̈/∂s = 3 L²/(m² s⁴ sin²α) − 2k/(m s³) = k/(m s*³) + 3 g cos α/s* with the equilibrium.
# At the scene's numbers s* = 0.3335384 m, ω = 12.033692 rad/s.
def _cone_frequency(p: dict[str, float]) -> float:
    m, k, g, alpha, s0, om = (p[n] for n in ("m", "k", "g", "alpha", "s0", "Om"))
    angular = m * s0 ** 2 * math.sin(alpha) ** 2 * om
    roots = np.roots([m * g * math.cos(alpha), 0.0, k, -angular ** 2 / (m * math.sin(alpha) ** 2)])
    (s,) = [r.real for r in roots if abs(r.imag) < 1e-9 * abs(r)]
    return math.sqrt(k / (m * s ** 3) + 3 * g * math.cos(alpha) / s)


CONE_POINTS = [{"m": 0.2, "k": 0.5, "alpha": 0.5, "s0": 0.4, "g": 9.81, "Om": 14.0},
               {"m": 1.0, "k": 2.0, "alpha": 1.1, "s0": 1.3, "g": 9.81, "Om": 3.0},
               {"m": 0.05, "k": 0.01, "alpha": 0.2, "s0": 0.2, "g": 1.6, "Om": 40.0}]


@pytest.fixture(scope="module")
def cone():
    return derive(parse_scene((SCENES / "cone_orbit_inverse_attraction.toml").read_text(), "cone.toml"))


@pytest.mark.parametrize("point", CONE_POINTS)
def test_the_frequency_about_an_orbit_at_the_root_of_a_cubic(cone, point):
    got = at(cone, cone.answers["small_oscillation_frequency"], point)
    assert got == pytest.approx(_cone_frequency(point), rel=1e-10)


def test_the_reported_frequency_on_the_cone(cone):
    assert at(cone, cone.answers["small_oscillation_frequency"], CONE_POINTS[0]) == pytest.approx(12.033692, abs=1e-6)
