"""The sixteenth engine red team (2026-11-28): textbook scenes written independently of the engine.

Eight scenes from the constraints chapters (Goldstein, Taylor, Morin, Kleppner & Kolenkow, Hand & Finch,
Marion & Thornton), each of a structure none of the 102 earlier scenes has:

- pendulum_winding_on_cylinder: a pendulum whose string winds round a fixed horizontal cylinder, the
  winding angle a coordinate without kinetic energy of its own (two constraints on the bob's x, y);
- bead_on_free_hoop: a bead on a hoop turning freely about its vertical diameter (the hoop's angle a
  coordinate with inertia, its angular momentum conserved; Routh's reduction for small oscillations);
- hinged_rods_on_floor: two rods hinged at the top, their feet sliding apart on a smooth floor (six
  coordinates, four constraints; the hinge's force changes sign; the least floor force over the fall);
- pendulum_vertically_driven_support: the support driven up and down (a rheonomic constraint);
- compound_atwood_massive_pulleys: a fixed and a movable massive pulley, three blocks (six coordinates,
  four constraints; four different tensions; the balancing mass, a threshold on a parameter);
- bead_on_free_rod: a bead on a rod turning freely in a horizontal plane (momentum and energy together);
- rod_in_bowl_on_rim: a rod with one end in a smooth hemispherical bowl, resting on its rim (the
  equilibrium 4a cos²θ − l cos θ − 2a = 0, the forces at rest, small oscillations);
- cylinder_in_free_cylinder: a cylinder rolling inside a hollow cylinder that turns freely on its axle
  (friction as a reaction force, the outer cylinder's momentum, small oscillations).

Every answer the engine gives agrees with the closed form derived by hand (in the comment above each
scene's cases) at two parameter points and two states. The values along the motion are also confirmed by
tests/numerical/test_problems_confirmed.py, and the special values by experiments of their own in
tests/numerical/test_red_team_confirmed.py. No scene was refused and no value was wrong. Found and fixed:

1. Readable forms: k sin²x + k cos²x was left in a sum (the rod in the bowl's rim force printed
   12a² sin²θ + 12a² cos²θ − 9al cos θ + 2l²); pythagorean_pairs now writes it k.
2. Refusals: a closed form the checker cannot read (a small-oscillation frequency about the root of a
   quartic, 124,524 characters) was refused with 'asked as kind = "numeric", it is found numerically',
   which a small_oscillation, equation, maximum or minimum answer cannot be; the advice now fits the kind.

3. Extremes: a stationary or turning point whose condition has no closed form (the winding pendulum turns
   back where R (θ cos θ − sin θ) + l cos θ is its start's value) was left out, and the extreme taken among
   the others: the highest point of the bob was answered y = −l (its lowest), the least cos θ as 1. WRONG
   references. The quantity is now sampled along the motion, and an extreme the candidates miss is refused.

The rod in the bowl derives in 2.9 s (best of 3), over the 2 s the issue asks for one degree of freedom.
"""

from __future__ import annotations

import functools
import math
import re
from pathlib import Path

import pytest
import sympy

from grader.mechanics.lagrange import derive
from grader.mechanics.scene import load_scene
from tests.mechanics.test_red_team_scenes_7 import at

SCENES = Path(__file__).resolve().parent / "scenes"


@functools.lru_cache(maxsize=None)
def _derived(name: str):
    return derive(load_scene(SCENES / f"{name}.toml"))


# -- pendulum_winding_on_cylinder -----------------------------------------------------------------------
# The string leaves the cylinder at P = R(cos θ, sin θ) along (sin θ, −cos θ) with free length L = l + Rθ:
# the bob's velocity is L θ̇ (cos θ, sin θ) (P's own motion cancels against the string's change of
# length), so T = m L² θ̇²/2 and V = m g (R sin θ − L cos θ). Lagrange: L θ̈ + R θ̇² + g sin θ = 0. The bob
# turns about P on a circle of radius L: the tension is m (L θ̇² + g cos θ). Energy from rest at θ0 gives
# θ̇², at θ = 0 the tension m g (3 − 2 cos θ0 + 2R (sin θ0 − θ0 cos θ0)/l); linearised, ω = √(g/l).
_WINDING = {
    "tension": "m*(g*cos(theta) + (l + R*theta)*thetadot^2)",
    "angular_acceleration": "-(R*thetadot^2 + g*sin(theta))/(l + R*theta)",
    "angular_speed_squared": "2*g*(R*(sin(theta0) - theta0*cos(theta0) - sin(theta) + theta*cos(theta))"
                             " + l*(cos(theta) - cos(theta0)))/(l + R*theta)^2",
    "bottom_tension": "m*g*(3 - 2*cos(theta0) + 2*R*(sin(theta0) - theta0*cos(theta0))/l)",
    "small_oscillation_frequency": "sqrt(g/l)",
}
_WINDING_POINTS = [
    {"m": 0.3, "g": 9.81, "l": 1.2, "R": 0.2, "theta0": 0.8, "theta": 0.3, "thetadot": -1.1},
    {"m": 1.7, "g": 1.6, "l": 0.4, "R": 0.35, "theta0": 0.2, "theta": -0.6, "thetadot": 0.4},
]

# -- bead_on_free_hoop ----------------------------------------------------------------------------------
# T = I φ̇²/2 + m a² (θ̇² + sin²θ φ̇²)/2, V = −m g a cos θ. φ is cyclic: h = (I + m a² sin²θ) φ̇ =
# (I + m a² sin²θ0) Ω0. Energy: θ̇² = (I + m a² sin²θ0) Ω0² (sin²θ − sin²θ0)/(I + m a² sin²θ)
# + 2 g (cos θ − cos θ0)/a. Towards the centre: m (a θ̇² + a sin²θ φ̇² + g cos θ) (the radial acceleration
# in spherical coordinates, and gravity's component). Perpendicular to the hoop: the bead's
# m (ρ φ̈ + 2 ρ̇ φ̇), ρ = a sin θ, with I φ̈ = −ρ N (the bead's reaction turns the hoop), so
# N = 2 I m a cos θ θ̇ φ̇/(I + m a² sin²θ). Routh: V_eff = h²/(2 (I + m a² sin²θ)) − m g a cos θ, whose
# second derivative at θ = 0 over m a² gives ω² = g/a − h²/I².
_FREE_HOOP = {
    "hoop_angular_velocity": "Omega0*(I + m*a^2*sin(theta0)^2)/(I + m*a^2*sin(theta)^2)",
    "thetadot_squared": "(I + m*a^2*sin(theta0)^2)*Omega0^2*(sin(theta)^2 - sin(theta0)^2)/(I + m*a^2*sin(theta)^2)"
                        " + 2*g*(cos(theta) - cos(theta0))/a",
    "radial_force": "m*(a*thetadot^2 + a*sin(theta)^2*phidot^2 + g*cos(theta))",
    "sideways_force": "2*I*m*a*cos(theta)*thetadot*phidot/(I + m*a^2*sin(theta)^2)",
    "small_oscillation_frequency": "sqrt(g/a - ((I + m*a^2*sin(theta0)^2)*Omega0/I)^2)",
}
_FREE_HOOP_POINTS = [
    {"m": 0.2, "I": 0.05, "a": 0.5, "g": 9.81, "theta0": 0.5, "Omega0": 2.0, "theta": 1.1, "thetadot": -0.7,
     "phidot": 1.3},
    {"m": 0.9, "I": 0.4, "a": 0.3, "g": 9.81, "theta0": 1.2, "Omega0": 0.7, "theta": -0.4, "thetadot": 2.1,
     "phidot": -0.5},
]

# -- hinged_rods_on_floor -------------------------------------------------------------------------------
# By symmetry the hinge stays above its start (no horizontal force outside: the hinge's X is cyclic and
# Ẋ = 0) and the rods keep equal angles. Each centre is at (±(l/2) sin θ, (l/2) cos θ), so each rod has
# T = m l² θ̇²/8 + m l² θ̇²/24 = m l² θ̇²/6 and V = m g (l/2) cos θ: θ̇² = 3 g (cos θ0 − cos θ)/l,
# θ̈ = 3 g sin θ/(2l). Rod 1's centre: H = m ẍ = (3 m g/4) sin θ (3 cos θ − 2 cos θ0) (the hinge pushes
# until cos θ = 2 cos θ0/3, then pulls), N = m g + m ÿ = (m g/4)(9 cos²θ − 6 cos θ cos θ0 + 1) (the hinge's
# vertical force vanishes by symmetry), least (m g/4) sin²θ0 at cos θ = cos θ0/3, which the fall reaches
# before the hinge lands (θ = π/2, at the speed l θ̇ = √(3 g l cos θ0)). A foot moves at l cos θ θ̇.
_HINGED = {
    "thetadot_squared": "3*g*(cos(theta0) - cos(theta))/l",
    "foot_speed_squared": "3*g*l*(cos(theta0) - cos(theta))*cos(theta)^2",
    "hinge_force": "3*m*g/4*sin(theta)*(3*cos(theta) - 2*cos(theta0))",
    "floor_force": "m*g/4*(9*cos(theta)^2 - 6*cos(theta)*cos(theta0) + 1)",
    "hinge_force_vanishes_cos": "2*cos(theta0)/3",
    "landing_speed": "sqrt(3*g*l*cos(theta0))",
    "least_floor_force": "m*g*sin(theta0)^2/4",
}
_HINGED_POINTS = [
    {"m": 0.4, "l": 1.0, "g": 9.81, "theta0": 0.3, "theta": 0.9},
    {"m": 2.3, "l": 0.35, "g": 1.6, "theta0": 1.1, "theta": 1.3},
]

# -- pendulum_vertically_driven_support -----------------------------------------------------------------
# In the support's frame gravity is g + ÿ_s = g − a ω² cos ωt: θ̈ = −(g − a ω² cos ωt) sin θ/l, the
# tension m (l θ̇² + (g − a ω² cos ωt) cos θ), and its vertical component on the bob T cos θ.
_DRIVEN = {
    "tension": "m*(l*thetadot^2 + (g - a*omega^2*cos(omega*t))*cos(theta))",
    "equation_of_motion": "-(g - a*omega^2*cos(omega*t))*sin(theta)/l",
    "support_force": "m*(l*thetadot^2 + (g - a*omega^2*cos(omega*t))*cos(theta))*cos(theta)",
}
_DRIVEN_POINTS = [
    {"m": 0.25, "g": 9.81, "l": 0.6, "a": 0.05, "omega": 9.0, "theta": 0.4, "thetadot": 1.5, "t": 0.3},
    {"m": 1.1, "g": 9.81, "l": 1.4, "a": 0.3, "omega": 30.0, "theta": 2.8, "thetadot": -0.2, "t": 1.7},
]

# -- bead_on_free_rod -----------------------------------------------------------------------------------
# T = I φ̇²/2 + m (ṙ² + r² φ̇²)/2, no potential. φ cyclic: (I + m r²) φ̇ = (I + m r0²) Ω0. Energy with
# ṙ0 = 0: ṙ² = (I + m r0²) Ω0² (r² − r0²)/(I + m r²). Radially r̈ = r φ̇² (no force along the smooth rod).
# Across it the bead needs m (r φ̈ + 2 ṙ φ̇) = N while the rod feels I φ̈ = −r N: N = 2 I m ṙ φ̇/(I + m r²).
# At the end r = L the bead moves outwards at Ω0 √((I + m r0²)(L² − r0²)/(I + m L²)).
_FREE_ROD = {
    "rod_angular_velocity": "Omega0*(I + m*r0^2)/(I + m*r^2)",
    "radial_speed_squared": "(I + m*r0^2)*Omega0^2*(r^2 - r0^2)/(I + m*r^2)",
    "radial_equation": "r*phidot^2",
    "normal_force": "2*I*m*rdot*phidot/(I + m*r^2)",
    "end_speed": "Omega0*sqrt((I + m*r0^2)*(L^2 - r0^2)/(I + m*L^2))",
}
_FREE_ROD_POINTS = [
    {"m": 0.1, "I": 0.02, "r0": 0.2, "L": 0.8, "Omega0": 3.0, "r": 0.5, "rdot": 0.3, "phidot": 2.0},
    {"m": 2.0, "I": 0.3, "r0": 0.05, "L": 2.5, "Omega0": 0.4, "r": 1.7, "rdot": -0.9, "phidot": -0.6},
]

# -- rod_in_bowl_on_rim ---------------------------------------------------------------------------------
# The chord from the rim E = (a, 0) to the end A at θ below the horizontal has length 2a cos θ, so the centre
# G = E + (l − 2a cos θ)(cos θ, sin θ) and V = m g (l − 2a cos θ) sin θ; V' = m g (2a − 4a cos²θ + l cos θ)
# vanishes at cos θ* = (l + √(l² + 32a²))/(8a). |Ġ|² = θ̇² (4a² sin²θ + (l − 2a cos θ)²), I = m l²/3,
# V'' = m g sin θ (8a cos θ − l): ω² = g sin θ* (8a cos θ* − l)/(4a² sin²θ* + (l − 2a cos θ*)² + l²/3).
# At rest there, moments about A: the rim's force (perpendicular to the rod) N_E 2a cos θ = m g l cos θ,
# N_E = m g l/(2a); A = (−a cos 2θ, −a sin 2θ), and horizontally N_A cos 2θ = N_E sin θ.
_EQUILIBRIUM_COS = "(l + sqrt(l^2 + 32*a^2))/(8*a)"
_BOWL = {
    "equilibrium_cos": _EQUILIBRIUM_COS,
    "small_oscillation_frequency": f"sqrt(g*sin(acos({_EQUILIBRIUM_COS}))*(8*a*{_EQUILIBRIUM_COS} - l)"
                                   f"/(4*a^2*(1 - ({_EQUILIBRIUM_COS})^2) + (l - 2*a*{_EQUILIBRIUM_COS})^2 + l^2/3))",
}
_BOWL_POINTS = [
    {"m": 0.5, "g": 9.81, "a": 1.0, "l": 1.5},
    {"m": 1.3, "g": 1.6, "a": 0.4, "l": 0.3},
]

# -- cylinder_in_free_cylinder --------------------------------------------------------------------------
# With ρ = R − r, ψ = (R α − ρ φ)/r: T = m ρ² φ̇²/2 + m (R α̇ − ρ φ̇)²/4 + J α̇²/2. α is cyclic, at rest at
# the release: (J + m R²/2) α̇ = m R ρ φ̇/2, α̇ = m R ρ φ̇/D, D = 2J + m R². Routh: the swing's inertia is
# m ρ² (1 + J/D), so φ̇² = 2 g D (cos φ − cos φ0)/(ρ (D + J)) and ω² = g D/(ρ (D + J)) (J → ∞: 2g/(3ρ), the
# fixed cylinder; J = 0: g/ρ, no friction). The outer cylinder's J α̈ = −R λ gives the friction
# λ = J m g sin φ/(3J + m R²) (m g sin φ/3 on a fixed cylinder); the normal force m (ρ φ̇² + g cos φ).
_FREE_CYLINDER = {
    "outer_angular_velocity": "m*R*(R - r)*phidot/(2*J + m*R^2)",
    "phidot_squared": "2*g*(2*J + m*R^2)*(cos(phi) - cos(phi0))/((R - r)*(3*J + m*R^2))",
    "normal_force": "m*((R - r)*phidot^2 + g*cos(phi))",
    "friction_force": "J*m*g*sin(phi)/(3*J + m*R^2)",
    "small_oscillation_frequency": "sqrt(g*(2*J + m*R^2)/((R - r)*(3*J + m*R^2)))",
}
_FREE_CYLINDER_POINTS = [
    {"m": 2.0, "J": 0.3, "g": 9.81, "R": 0.5, "r": 0.1, "phi0": 0.7, "phi": 0.2, "phidot": -1.4},
    {"m": 0.3, "J": 4.0, "g": 1.6, "R": 2.0, "r": 1.1, "phi0": 1.3, "phi": -1.0, "phidot": 0.6},
]

CASES = [(scene, answer, expected, points) for scene, table, points in (
    ("pendulum_winding_on_cylinder", _WINDING, _WINDING_POINTS),
    ("bead_on_free_hoop", _FREE_HOOP, _FREE_HOOP_POINTS),
    ("hinged_rods_on_floor", _HINGED, _HINGED_POINTS),
    ("pendulum_vertically_driven_support", _DRIVEN, _DRIVEN_POINTS),
    ("bead_on_free_rod", _FREE_ROD, _FREE_ROD_POINTS),
    ("rod_in_bowl_on_rim", _BOWL, _BOWL_POINTS),
    ("cylinder_in_free_cylinder", _FREE_CYLINDER, _FREE_CYLINDER_POINTS),
) for answer, expected in table.items()]


@pytest.mark.parametrize("scene, answer, expected, points", CASES, ids=[f"{c[0]}-{c[1]}" for c in CASES])
def test_answer_agrees_with_the_hand_derivation(scene, answer, expected, points):
    derivation = _derived(scene)
    for point in points:
        got, want = at(derivation, derivation.answers[answer], point), at(derivation, expected, point)
        assert got == pytest.approx(want, rel=1e-10, abs=1e-12), f"{answer} at {point}"


def test_every_answer_of_the_new_scenes_is_checked_by_hand():
    tables = {"pendulum_winding_on_cylinder": _WINDING, "bead_on_free_hoop": _FREE_HOOP,
              "hinged_rods_on_floor": _HINGED, "pendulum_vertically_driven_support": _DRIVEN,
              "bead_on_free_rod": _FREE_ROD, "rod_in_bowl_on_rim": _BOWL,
              "cylinder_in_free_cylinder": _FREE_CYLINDER}
    unchecked = {"pendulum_winding_on_cylinder": {"far_turning_angle"},  # numeric: below, by a root
                 "rod_in_bowl_on_rim": {"rim_force", "bowl_force"}}        # below, at the equilibrium
    for scene, table in tables.items():
        names = {a.name for a in load_scene(SCENES / f"{scene}.toml").answers}
        assert names - set(table) == unchecked.get(scene, set()), scene


# The rod in the bowl at rest at its equilibrium: the rim's force m g l/(2a), the bowl's m g l sin θ*/(2a cos 2θ*)
# (the answers as functions of θ and θ̇, read at θ*, θ̇ = 0).
@pytest.mark.parametrize("point", _BOWL_POINTS)
def test_rod_in_a_bowl_at_rest_at_its_equilibrium_feels_the_static_forces(point):
    derivation = _derived("rod_in_bowl_on_rim")
    m, g, a, l = (point[n] for n in ("m", "g", "a", "l"))
    theta = math.acos((l + math.sqrt(l * l + 32 * a * a)) / (8 * a))
    state = {**point, "theta": theta, "thetadot": 0.0}
    assert at(derivation, derivation.answers["rim_force"], state) == pytest.approx(m * g * l / (2 * a), rel=1e-10)
    assert at(derivation, derivation.answers["bowl_force"], state) == pytest.approx(
        m * g * l * math.sin(theta) / (2 * a * math.cos(2 * theta)), rel=1e-10)


# The winding pendulum released at θ0 comes to rest next where θ̇² = 0, on the side where the string winds on:
# R (θ cos θ − sin θ) + l cos θ = R (θ0 cos θ0 − sin θ0) + l cos θ0, below −θ0 (no closed form: numeric).
def test_winding_pendulum_turns_back_at_the_root_of_its_energy():
    from scipy.optimize import brentq

    derivation = _derived("pendulum_winding_on_cylinder")
    reference = next(r for r in derivation.references() if r["name"] == "far_turning_angle")
    from grader.answers.numeric import reference_value

    values = {name: spec["value"] for name, spec in reference["parameters"].items() if "value" in spec}
    R, l, theta0 = values["R"], values["l"], values["theta0"]

    def energy(theta):
        return R * (theta * math.cos(theta) - math.sin(theta)) + l * math.cos(theta) - (
            R * (theta0 * math.cos(theta0) - math.sin(theta0)) + l * math.cos(theta0))

    expected = brentq(energy, -math.pi / 2, 0.0, xtol=1e-15)
    # The string winds on and is shorter there: the bob must swing through a larger angle to rise as high.
    assert expected < -theta0
    got = reference_value(reference["reference"], reference["variables"], values, reference["implicit"])
    assert got == pytest.approx(expected, abs=1e-9)


# The compound Atwood machine, derived independently in Y (m1's height) and u (m3's rise relative to the
# movable pulley): T = (m1 + M2 + M1/2) Ẏ²/2 + m2 (Ẏ + u̇)²/2 + m3 (u̇ − Ẏ)²/2 + M2 u̇²/4, V = g ((m1 − M2) Y −
# m2 (Y + u) + m3 (u − Y)). Each block's tension is m (g + ÿ); the movable pulley's strand holds
# M2 (g + ÿ_P) + T2 + T3. Massless pulleys give the textbook a1 = g (4 m2 m3 − m1 (m2 + m3))/(4 m2 m3 +
# m1 (m2 + m3)) and T2 = 4 g m1 m2 m3/(4 m2 m3 + m1 (m2 + m3)); the balancing m1 is then 4 m2 m3/(m2 + m3).
def _atwood_by_hand():
    m1, m2, m3, M1, M2, g = sympy.symbols("m1 m2 m3 M1 M2 g", positive=True)
    Ydd, udd = sympy.symbols("Ydd udd")
    # Lagrange's equations of the quadratic T and linear V above: mass matrix times accelerations = −∇V.
    mass = sympy.Matrix([[m1 + M2 + M1 / 2 + m2 + m3, m2 - m3], [m2 - m3, m2 + m3 + M2 / 2]])
    force = sympy.Matrix([-g * (m1 - M2 - m2 - m3), -g * (m3 - m2)])
    Ydd, udd = mass.LUsolve(force)
    accelerations = {"y1": Ydd, "yP": -Ydd, "y2": -Ydd - udd, "y3": -Ydd + udd}
    t2, t3 = m2 * (g + accelerations["y2"]), m3 * (g + accelerations["y3"])
    values = {
        "acceleration_1": accelerations["y1"], "acceleration_2": accelerations["y2"],
        "tension_1": m1 * (g + accelerations["y1"]), "tension_2": t2, "tension_3": t3,
        "tension_P": M2 * (g + accelerations["yP"]) + t2 + t3,
    }
    balancing = sympy.solve(sympy.numer(sympy.together(Ydd)), m1)
    assert len(balancing) == 1
    values["balancing_mass"] = balancing[0]
    return (m1, m2, m3, M1, M2, g), values


_ATWOOD_POINTS = [
    {"m1": 3.0, "m2": 1.0, "m3": 1.5, "M1": 0.8, "M2": 0.6, "R1": 0.1, "R2": 0.05, "g": 9.81},
    {"m1": 0.7, "m2": 2.2, "m3": 0.4, "M1": 3.1, "M2": 0.05, "R1": 0.4, "R2": 0.3, "g": 1.6},
    {"m1": 1.0, "m2": 1.0, "m3": 3.0, "M1": 1e-9, "M2": 1e-9, "R1": 0.2, "R2": 0.2, "g": 9.81},
]


@pytest.mark.parametrize("answer", ["acceleration_1", "acceleration_2", "tension_1", "tension_P", "tension_2",
                                    "tension_3", "balancing_mass"])
def test_compound_atwood_with_massive_pulleys_agrees_with_the_hand_derivation(answer):
    derivation = _derived("compound_atwood_massive_pulleys")
    symbols, values = _atwood_by_hand()
    for point in _ATWOOD_POINTS:
        want = float(values[answer].subs({s: point[str(s)] for s in symbols}))
        assert at(derivation, derivation.answers[answer], point) == pytest.approx(want, rel=1e-10)


def test_compound_atwood_with_massless_pulleys_is_the_textbooks():
    _, values = _atwood_by_hand()
    m1, m2, m3, g = 1.3, 0.7, 2.9, 9.81
    point = {"m1": m1, "m2": m2, "m3": m3, "M1": 0, "M2": 0, "g": g}
    numbers = {sympy.Symbol(k, positive=True): v for k, v in point.items()}
    denominator = 4 * m2 * m3 + m1 * (m2 + m3)
    assert float(values["acceleration_1"].subs(numbers)) == pytest.approx(g * (4 * m2 * m3 - m1 * (m2 + m3)) / denominator)
    assert float(values["tension_2"].subs(numbers)) == pytest.approx(4 * g * m1 * m2 * m3 / denominator)
    assert float(values["balancing_mass"].subs(numbers)) == pytest.approx(4 * m2 * m3 / (m2 + m3))


# -- a closed form the checker cannot read: what the refusal tells the instructor to do -------------------
# A small-oscillation frequency about the bead's tilted relative equilibrium on the freely turning hoop
# (Ω0 = 5: the bottom is unstable) is about the root of a quartic in cos θ; its closed form runs to 124,524
# characters. The refusal said 'asked as kind = "numeric", it is found numerically': but kind = "numeric"
# is another kind, and a small_oscillation (equation, maximum, minimum) answer cannot be asked so. The
# advice now depends on the kind: numeric only where it applies.
def test_a_frequency_too_long_to_check_is_refused_without_advice_it_cannot_follow():
    from grader.mechanics.scene import SceneError, parse_scene

    text = (SCENES / "bead_on_free_hoop.toml").read_text()
    text = text.replace('Omega0 = { dimension = "angular_velocity", domain = "positive", value = 2.0 }',
                        'Omega0 = { dimension = "angular_velocity", domain = "positive", value = 5.0 }')
    text = text.replace('where = "theta = 0"', 'where = "thetaddot = 0"')
    with pytest.raises(SceneError) as refusal:
        derive(parse_scene(text, source="tilted.toml")).references()
    message = str(refusal.value)
    assert "small_oscillation_frequency" in message and "too long" in message
    assert "it is found numerically" not in message
    assert "the equilibrium itself may be asked as kind = \"numeric\"" in message


@pytest.mark.parametrize("kind, advice", [
    ("expression", 'asked as kind = "numeric", it is found numerically'),
    ("equation", "an equation is checked in closed form only"),
    ("small_oscillation", "small-oscillation frequency is computed in closed form only"),
    ("maximum", "a maximum is computed in closed form only"),
    ("minimum", "a minimum is computed in closed form only"),
])
def test_an_unreadable_closed_form_is_refused_with_advice_for_its_kind(kind, advice):
    import dataclasses

    from grader.mechanics.references import _readable_by_the_checker
    from grader.mechanics.scene import SceneError

    scene = load_scene(SCENES / "bead_on_free_rod.toml")
    spec = dataclasses.replace(scene.answer("normal_force"), kind=kind)
    with pytest.raises(SceneError) as refusal:
        # A closed form nobody can type (LambertW, as a condition like m g l sin θ = k θ may give).
        _readable_by_the_checker(scene, spec, ["rddot = LambertW(r)" if kind == "equation" else "LambertW(r)"],
                                 scene.namespace)
    message = str(refusal.value)
    assert "LambertW" in message and advice in message
    if kind != "expression":
        assert "kind = \"numeric\", it is found" not in message


# -- k sin²x + k cos²x is k -----------------------------------------------------------------------------
# The rod in the bowl printed its rim force with 12a² sin²θ + 12a² cos²θ − 9al cos θ + 2l² and its bowl
# force with (sin²θ + cos²θ − 4): pythagorean_pairs wrote k sin²x beside −k as −k cos²x, but left k sin²x
# beside k cos²x. Every such pair in a sum is now k, whatever k is and whatever else the sum holds.
_x, _y = sympy.symbols("x y", real=True)
_a, _l, _k = sympy.symbols("a l k", positive=True)


@pytest.mark.parametrize("total, expected", [
    (sympy.sin(_x) ** 2 + sympy.cos(_x) ** 2, sympy.S.One),
    (12 * _a ** 2 * sympy.sin(_x) ** 2 + 12 * _a ** 2 * sympy.cos(_x) ** 2 - 9 * _a * _l * sympy.cos(_x) + 2 * _l ** 2,
     12 * _a ** 2 - 9 * _a * _l * sympy.cos(_x) + 2 * _l ** 2),
    (3 * _a * _l * (sympy.sin(_x) ** 2 + sympy.cos(_x) ** 2 - 4) * sympy.sin(_x), -9 * _a * _l * sympy.sin(_x)),
    (_k * sympy.cos(2 * _x) ** 2 + _k * sympy.sin(2 * _x) ** 2 + _k * sympy.sin(_y) ** 2, _k + _k * sympy.sin(_y) ** 2),
    (_k * sympy.sin(_x) ** 2 + _k * sympy.cos(_y) ** 2, _k * sympy.sin(_x) ** 2 + _k * sympy.cos(_y) ** 2),  # two angles
    (2 * sympy.sin(_x) ** 2 + sympy.cos(_x) ** 2 - 1, sympy.sin(_x) ** 2),  # the pair beside −k, as before
])
def test_a_pythagorean_pair_with_equal_coefficients_is_its_coefficient(total, expected):
    from grader.mechanics.simplification import pythagorean_pairs

    assert sympy.expand(pythagorean_pairs(total) - expected) == 0
    assert sympy.count_ops(pythagorean_pairs(total)) == sympy.count_ops(expected)


def test_the_rod_in_the_bowl_prints_its_forces_without_a_pythagorean_pair():
    derivation = _derived("rod_in_bowl_on_rim")
    for name in ("rim_force", "bowl_force"):
        for total in derivation.answers[name].atoms(sympy.Add):
            sines = {p.base.args[0] for p in total.atoms(sympy.Pow) if isinstance(p.base, sympy.sin) and p.exp == 2}
            cosines = {p.base.args[0] for p in total.atoms(sympy.Pow) if isinstance(p.base, sympy.cos) and p.exp == 2}
            for angle in sines & cosines:
                pairs = [t for t in sympy.Add.make_args(total) if t.has(sympy.sin(angle) ** 2)]
                assert not any(t.subs(sympy.sin(angle) ** 2, sympy.cos(angle) ** 2) in sympy.Add.make_args(total)
                               for t in pairs), f"{name}: {total}"


# -- an extreme at a point with no closed form is not replaced by the best of the others -------------------
# The winding pendulum released at rest at θ0 = 0.8 swings to θ1 = −0.883216 (the root of its energy,
# R (θ cos θ − sin θ) + l cos θ = const, which has no closed form) and back. Its highest point is at the ends
# (y = y0 there, by energy) and cos θ is least at θ1; solving in closed form found only θ = 0 (and −l/R,
# off the swing), and the engine answered the highest point y = −l and the least cos θ = 1: the lowest point
# and the largest value, WRONG references. A quantity sampled along the swing that beats every closed-form
# candidate now refuses the extreme, naming where it lies; where the candidates hold the extreme it stays.
@pytest.mark.parametrize("kind, expr, expected", [
    ("maximum", "y", "near theta = 0.8,"),
    ("minimum", "cos(theta)", "near theta = -0.883216,"),
    ("maximum", "cos(theta)", "1"),
    ("minimum", "y", "-l"),
])
def test_an_extreme_at_a_turning_point_without_closed_form_is_refused_not_taken_elsewhere(kind, expr, expected):
    from grader.mechanics.scene import SceneError, parse_scene

    text = (SCENES / "pendulum_winding_on_cylinder.toml").read_text() + f'''
[[answers]]
name = "extreme"
prompt = "the {kind} over the swing"
kind = "{kind}"
expr = "{expr}"
'''
    if expected.startswith("near"):
        with pytest.raises(SceneError, match=f"the {kind} of {re.escape(expr)} on the motion from \\[initial\\] is "
                                             f"{re.escape(expected)} a stationary or turning point that has no closed form"):
            derive(parse_scene(text, source="extreme.toml"))
    else:
        derivation = derive(parse_scene(text, source="extreme.toml"))
        point = {"m": 0.3, "g": 9.81, "l": 1.2, "R": 0.2, "theta0": 0.8}
        assert at(derivation, derivation.answers["extreme"], point) == pytest.approx(at(derivation, expected, point))
