"""The twelfth engine red team (2026-11-28): scenes from the constraints chapters of the textbooks.

0. Small oscillations of one coordinate when another is not cyclic but only feels a uniform force (a
   pendulum hung from a block sliding down a smooth incline, or from a cart pushed by a constant force)
   were refused ("the others are not cyclic"): the pendulum's φ̈, the block's s̈ eliminated, depends on φ
   and φ̇ alone, so its frequency is well posed. It is computed now whenever ü is free of the other
   coordinates and their velocities.
1. θ where θ̈ = 0, asked in terms of φ̇, for a spherical pendulum whose support is driven round a
   horizontal circle: the condition has a φ̇² sin θ cos θ term; solving it along the motion ran out of
   budget and the engine fell back to reading it at rest, silently setting φ̇ = 0: atan(a ω² cos(ωt − φ)/g),
   wrong wherever φ̇ ≠ 0. A velocity that in_terms_of names and the condition depends on is never read at
   rest now; the answer is refused with the reason instead.
2. A numeric answer (the angle where a cylinder leaves another cylinder that itself rolls on the floor)
   whose closed form is longer than the checker reads (Ferrari's root of a quartic in cos θ, 4,154
   characters) was refused ("cannot be checked: the text is too long"); it is found numerically now, as
   at a root nobody can type.
4. Beside such a uniformly forced coordinate, φ̇² as a function of φ (and with it an answer at a given φ,
   or the extremes of the swing) was refused ("the energy is not of the form a·φ̇² + c": energy holds
   ṡ and s). The momentum E ṡ + c(φ) φ̇ grows as F t; in Routh's function it leaves the potential
   Fᵀ E⁻¹ ∫c dφ, and ½ (a − cᵀ E⁻¹ c) φ̇² + V(φ) + Fᵀ E⁻¹ ∫c dφ is conserved. An acceleration set to
   zero keeps being read as before (at rest where energy gave no φ̇²(φ)).
5. A root real on part of the state space was dropped beside roots real everywhere: cos θ where θ̈ = 0, in
   terms of φ̇, for a spherical pendulum (no [initial]): θ = 0 and π always, cos θ = g/(l φ̇²) only where
   φ̇² ≥ g/l; tried at a slower φ̇, the textbook answer was no alternative (the reference was cos θ = 1).
   A state where more roots are real is looked for now.
3. A coordinate named d has the acceleration ddot, a parameter named ln is a function: both crashed the
   scene reader with a traceback (ValueError); they are refused naming the name to change.

Each answer is derived by hand (in the comment above it); the values were also checked against a
numerical integration of the Cartesian equations with Lagrange multipliers.
"""

from __future__ import annotations

import math

import pytest
import sympy
from scipy.optimize import brentq

from grader.expressions import parse_expression
from grader.mechanics.lagrange import derive
from grader.mechanics.scene import SceneError, parse_scene
from tests.mechanics.test_red_team_scenes_7 import at

# -- 0. small oscillations beside a uniformly forced coordinate ----------------------------------------
# Block M at distance s along a rail of inclination α (down the rail), pendulum m, l at φ from the
# downward vertical, and a constant force P pushing the block down the rail. T = (M + m) ṡ²/2 +
# m l cos(φ + α) ṡ φ̇ + m l² φ̇²/2, V = −(M + m) g s sin α − P s − m g l cos φ. With s̈ eliminated,
# φ̈ depends on φ, φ̇ only: in the frame that moves with the uniform force's acceleration along the rail,
# the pendulum swings as on a free cart on a level rail, under an effective gravity. With ψ = φ + α (the angle from the normal to the rail) the effective potential is
# −m l (g cos α cos ψ − (P/(M + m)) sin ψ) = −m l G cos(ψ − ψ*), G = √(g² cos²α + (P/(M + m))²),
# tan ψ* = −P/((M + m) g cos α), and the inertia m l² (M + m sin²ψ)/(M + m), so
#     ω² = G (M + m)/(l (M + m sin²ψ*)),
# (P = 0, the incline: ω² = (M + m) g cos α/(M l), about φ = −α; α = 0: a cart pushed on level ground).
_PUSHED = '''
id = "pendulum_on_pushed_block"
title = "Pendulum hung from a block on a rail"
[parameters]
m = {{ dimension = "mass", domain = "positive", value = 0.5 }}
M = {{ dimension = "mass", domain = "positive", value = 2.0 }}
g = {{ dimension = "acceleration", domain = "positive", value = 9.81 }}
l = {{ dimension = "length", domain = "positive", value = 0.8 }}
{extra}
[coordinates]
s = {{ dimension = "length" }}
phi = {{ dimension = "angle", domain = [-1.55, 1.55] }}
[energy]
kinetic = "(M + m)/2*sdot^2 + m*l*cos(phi + {alpha})*sdot*phidot + m*l^2/2*phidot^2"
potential = "-(M + m)*g*s*sin({alpha}) - {push}*s - m*g*l*cos(phi)"
[[answers]]
name = "frequency"
prompt = "frequency of small oscillations"
kind = "small_oscillation"
expr = "phi"
where = "{where}"
'''


@pytest.mark.parametrize("case", ["incline", "pushed_on_level", "pushed_down_incline"])
def test_small_oscillations_beside_a_uniformly_forced_coordinate(case):
    alpha = {"incline": "alpha", "pushed_on_level": "0", "pushed_down_incline": "alpha"}[case]
    push = {"incline": "0", "pushed_on_level": "P", "pushed_down_incline": "P"}[case]
    extra = ('alpha = { dimension = "angle", domain = [0.05, 1.5], value = 0.5 }\n' if alpha == "alpha" else "") + \
        ('P = { dimension = "force", domain = "positive", value = 3.0 }\n' if push == "P" else "")
    where = {"incline": "phi = -alpha", "pushed_on_level": "phiddot = 0",
             "pushed_down_incline": "phiddot = 0"}[case]
    text = _PUSHED.format(alpha=alpha, push=push, extra=extra, where=where)
    derivation = derive(parse_scene(text, source=f"{case}.toml"))
    for point in ({"m": 0.5, "M": 2.0, "g": 9.81, "l": 0.8, "alpha": 0.5, "P": 3.0},
                  {"m": 3.0, "M": 1.0, "g": 1.6, "l": 2.5, "alpha": 1.1, "P": 0.7}):
        a = point["alpha"] if alpha == "alpha" else 0.0
        p = point["P"] if push == "P" else 0.0
        total = point["M"] + point["m"]
        G = math.hypot(point["g"] * math.cos(a), p / total)
        psi = math.atan2(-p / total, point["g"] * math.cos(a))
        expected = math.sqrt(G * total / (point["l"] * (point["M"] + point["m"] * math.sin(psi) ** 2)))
        declared = {k: v for k, v in point.items() if k in derivation.scene.namespace.names}
        assert at(derivation, derivation.answers["frequency"], declared) == pytest.approx(expected, rel=1e-12)


# A coordinate that feels more than a uniform force still refuses, naming it: the block on a spring.
def test_small_oscillations_beside_a_coupled_coordinate_are_still_refused():
    text = _PUSHED.format(alpha="0", push="0", extra='k = { dimension = "stiffness", domain = "positive", '
                                                      'value = 5.0 }\n', where="phi = 0")
    text = text.replace('- m*g*l*cos(phi)"', '- m*g*l*cos(phi) + k*s^2/2"')
    with pytest.raises(SceneError, match="s is not: the Lagrangian depends on it, and so does phiddot"):
        derive(parse_scene(text, source="spring.toml"))


# -- 1. a velocity in in_terms_of is not set to zero by reading the condition at rest ------------------
# Support at (a cos ωt, a sin ωt, 0) (circle) or (a cos ωt, 0, 0) (line); bob at support + l (sin θ cos φ,
# sin θ sin φ, −cos θ). θ̈ = φ̇² sin θ cos θ − g sin θ/l + (cos θ/l) (−A_s)·(cos φ, sin φ, 0) with A_s the
# support's acceleration. θ where θ̈ = 0 in terms of φ̇: the answer, if given, must make θ̈ vanish at
# states with φ̇ ≠ 0 (at rest it was atan(a ω² cos(ωt − φ)/g), which does not).
_DRIVEN = '''
id = "spherical_pendulum_driven_support"
title = "Spherical pendulum with a driven support"
[parameters]
m = { dimension = "mass", domain = "positive", value = 0.3 }
g = { dimension = "acceleration", domain = "positive", value = 9.81 }
l = { dimension = "length", domain = "positive", value = 0.9 }
a = { dimension = "length", domain = "positive", value = 0.15 }
omega = { dimension = "angular_velocity", domain = "positive", value = 2.5 }
[coordinates]
theta = { dimension = "angle", domain = [0.01, 3.1] }
phi = { dimension = "angle" }
[energy]
kinetic = "m/2*((-a*omega*sin(omega*t) + l*(cos(theta)*cos(phi)*thetadot - sin(theta)*sin(phi)*phidot))^2 + (YS + l*(cos(theta)*sin(phi)*thetadot + sin(theta)*cos(phi)*phidot))^2 + (l*sin(theta)*thetadot)^2)"
potential = "-m*g*l*cos(theta)"
[[answers]]
name = "steady_angle"
prompt = "theta where thetaddot = 0"
expr = "theta"
where = "thetaddot = 0"
in_terms_of = ["g", "l", "a", "omega", "phi", "phidot", "t"]
'''


@pytest.mark.parametrize("support", ["circle", "line"])
def test_a_velocity_asked_in_is_not_dropped_by_reading_the_condition_at_rest(support):
    text = _DRIVEN.replace("YS", "a*omega*cos(omega*t)" if support == "circle" else "0")
    try:
        derivation = derive(parse_scene(text, source=f"{support}.toml"))
    except SceneError as error:
        assert "steady_angle" in str(error)
        return
    for point in ({"g": 9.81, "l": 0.9, "a": 0.15, "omega": 2.5, "phi": 0.3, "phidot": 2.0, "t": 0.4},
                  {"g": 9.81, "l": 0.9, "a": 0.15, "omega": 2.5, "phi": -0.7, "phidot": 4.0, "t": 1.3}):
        theta = at(derivation, derivation.answers["steady_angle"], point)
        ys = 1.0 if support == "circle" else 0.0
        drive = point["a"] * point["omega"] ** 2 * (math.cos(point["omega"] * point["t"]) * math.cos(point["phi"])
                                                    + ys * math.sin(point["omega"] * point["t"]) * math.sin(point["phi"]))
        thetaddot = (point["phidot"] ** 2 * math.sin(theta) * math.cos(theta) - point["g"] * math.sin(theta) / point["l"]
                     + math.cos(theta) * drive / point["l"])
        assert thetaddot == pytest.approx(0, abs=1e-9)


# -- 4. the speed beside a uniformly forced coordinate ------------------------------------------------
# The pendulum of section 0 released at rest at φ₀ (the block at rest). On the incline (P = 0) it swings
# as on a free cart under g cos α about ψ = φ + α = 0: φ̇² = 2 (M + m) g cos α (cos ψ − cos ψ₀)/
# (l (M + m sin²ψ)), and the least φ is −2α − φ₀. Pushed on level ground (α = 0) by P it swings under
# G = √(g² + A²), A = P/(M + m), about φ = −δ, tan δ = A/g: φ̇² = 2 (M + m) G (cos(φ + δ) − cos(φ₀ + δ))/
# (l (M + m sin²φ)), least φ −2δ − φ₀ (both checked against an integration of the Cartesian equations with
# a multiplier, to 1e-9). (The least φ itself, asked as a minimum, is still refused: solving φ̇² = 0 for φ
# runs out of budget.)
_RELEASED = """
[initial]
s = 0
sdot = 0
phi = "phi0"
phidot = 0

[[answers]]
name = "speed_squared"
prompt = "phidot^2 as a function of phi"
expr = "phidot^2"
in_terms_of = ["m", "M", "g", "l", "phi", "phi0"{more}]

[[answers]]
name = "lowest_speed_squared"
prompt = "phidot^2 where the pendulum passes its equilibrium"
expr = "phidot^2"
where = "{where}"
in_terms_of = ["m", "M", "g", "l", "phi0"{more}]
"""


@pytest.mark.parametrize("case", ["incline", "pushed_on_level"])
def test_the_swing_beside_a_uniformly_forced_coordinate(case):
    incline = case == "incline"
    extra = ('alpha = { dimension = "angle", domain = [0.05, 1.5], value = 0.5 }\n' if incline else
             'P = { dimension = "force", domain = "positive", value = 3.0 }\n')
    extra += 'phi0 = { dimension = "angle", domain = [0, 0.5], value = 0.3 }\n'
    text = _PUSHED.format(alpha="alpha" if incline else "0", push="0" if incline else "P", extra=extra,
                          where="phi = 0")
    text = text[:text.index("[[answers]]")] + _RELEASED.format(
        more=', "alpha"' if incline else ', "P"', where="phi = -alpha" if incline else "tan(phi) = -P/((M + m)*g)")
    derivation = derive(parse_scene(text, source=f"{case}.toml"))
    for point in ({"m": 0.5, "M": 2.0, "g": 9.81, "l": 0.8, "alpha": 0.5, "P": 3.0, "phi0": 0.3},
                  {"m": 3.0, "M": 1.0, "g": 1.6, "l": 2.5, "alpha": 1.1, "P": 0.7, "phi0": 0.0}):
        declared = {k: v for k, v in point.items() if k in derivation.scene.namespace.names}
        m, M, g, l, phi0 = (point[k] for k in ("m", "M", "g", "l", "phi0"))
        if incline:
            a = point["alpha"]
            least = -2 * a - phi0
            lowest = 2 * (M + m) * g * math.cos(a) * (1 - math.cos(phi0 + a)) / (l * M)
        else:
            delta = math.atan(point["P"] / ((M + m) * g))
            least = -2 * delta - phi0
            lowest = 2 * (M + m) * math.hypot(g, point["P"] / (M + m)) * (1 - math.cos(phi0 + delta)) / (
                l * (M + m * math.sin(delta) ** 2))
        got = at(derivation, derivation.answers["lowest_speed_squared"], declared)
        assert got == pytest.approx(lowest, rel=1e-10, abs=1e-12)
        for phi in (least + 0.01, -0.2, phi0 - 0.01):
            if incline:
                psi, psi0 = phi + a, phi0 + a
                expected = 2 * (M + m) * g * math.cos(a) * (math.cos(psi) - math.cos(psi0)) / (
                    l * (M + m * math.sin(psi) ** 2))
            else:
                G = math.hypot(g, point["P"] / (M + m))
                expected = 2 * (M + m) * G * (math.cos(phi + delta) - math.cos(phi0 + delta)) / (
                    l * (M + m * math.sin(phi) ** 2))
            got = at(derivation, derivation.answers["speed_squared"], {**declared, "phi": phi})
            assert got == pytest.approx(expected, rel=1e-10, abs=1e-12)


# -- 5. a root real on part of the state space ---------------------------------------------------------
# T = m l² (θ̇² + sin²θ φ̇²)/2, V = −m g l cos θ: θ̈ = sin θ (cos θ φ̇² − g/l), zero at θ = 0, π and where
# cos θ = g/(l φ̇²) (the steady conical motion, real for φ̇² ≥ g/l). Each must be a right answer.
_CONICAL = """
id = "conical"
title = "Spherical pendulum"
[parameters]
m = { dimension = "mass", domain = "positive", value = 0.3 }
g = { dimension = "acceleration", domain = "positive", value = 9.81 }
l = { dimension = "length", domain = "positive", value = 0.9 }
[coordinates]
theta = { dimension = "angle", domain = [0, 3.1416] }
phi = { dimension = "angle" }
[energy]
kinetic = "m*l^2/2*(thetadot^2 + sin(theta)^2*phidot^2)"
potential = "-m*g*l*cos(theta)"
[[answers]]
name = "steady"
prompt = "where thetaddot = 0"
expr = "EXPR"
where = "thetaddot = 0"
in_terms_of = ["g", "l", "phidot"]
"""


@pytest.mark.parametrize("expr, steady", [("cos(theta)", lambda c: c), ("theta", math.acos)])
def test_a_root_real_only_for_fast_turning_is_a_right_answer(expr, steady):
    derivation = derive(parse_scene(_CONICAL.replace("EXPR", expr), source="conical.toml"))
    for point in ({"g": 9.81, "l": 0.9, "phidot": 5.0}, {"g": 1.6, "l": 2.0, "phidot": 1.3}):
        expected = steady(point["g"] / (point["l"] * point["phidot"] ** 2))
        forms = [derivation.answers["steady"], *derivation.alternatives.get("steady", [])]
        assert any(at(derivation, f, point) == pytest.approx(expected, rel=1e-12) for f in forms)


# -- 2. a numeric answer whose closed form is too long to check ------------------------------------------
# A cylinder (m, r, I = k m r²) on top of a solid cylinder (M, R) that rolls on the floor, both rolling
# without slipping, released at the top with a tiny push. With θ the line of centres' angle from the upward
# vertical and X the bottom cylinder's position (cyclic: p_X = 0), T = (3M/4 + (1 + k) m/2) Ẋ² +
# m (R + r)(cos θ − k) Ẋ θ̇ + (1 + k) m (R + r)² θ̇²/2, and the normal force vanishes at a root of a quartic
# in cos θ. The angles below come from integrating the
# Cartesian equations with Lagrange multipliers (scipy, from θ₀ = 1e-7 at rest) to where the normal
# force changes sign: 57.174091° (k = 1/2, M = 3 m) and 65.024912° (k = 1, M = 1.5 m).
_ON_ROLLING = '''
id = "cylinder_on_rolling_cylinder"
title = "Cylinder on a cylinder that rolls"
[parameters]
m = { dimension = "mass", domain = "positive", value = 1.0 }
M = { dimension = "mass", domain = "positive", value = MASS }
g = { dimension = "acceleration", domain = "positive", value = 9.81 }
R = { dimension = "length", domain = "positive", value = 0.5 }
r = { dimension = "length", domain = "positive", value = 0.2 }
[coordinates]
theta = { dimension = "angle", domain = [-3.1416, 3.1416] }
rho = { dimension = "length", domain = "positive" }
X = { dimension = "length" }
beta = { dimension = "angle" }
psi = { dimension = "angle" }
[energy]
kinetic = "M/2*Xdot^2 + M*R^2/4*betadot^2 + m/2*((Xdot + rhodot*sin(theta) + rho*cos(theta)*thetadot)^2 + (rhodot*cos(theta) - rho*sin(theta)*thetadot)^2) + K*m*r^2/2*psidot^2"
potential = "m*g*rho*cos(theta)"
[[constraints]]
name = "contact"
f = "rho - R - r"
kind = "unilateral"
[[constraints]]
name = "floor"
f = "X + R*beta"
[[constraints]]
name = "top"
f = "(R + r)*theta + r*psi + R*beta"
[initial]
theta = 0
thetadot = 0
X = 0
Xdot = 0
[[answers]]
name = "normal_force"
prompt = "normal force as a function of theta"
expr = "lambda_contact"
in_terms_of = ["m", "M", "g", "theta"]
dimension = "force"
[[answers]]
name = "separation_angle"
prompt = "angle where the top cylinder leaves (deg)"
kind = "numeric"
expr = "theta"
where = "normal_force = 0"
unit = "deg"
'''


@pytest.mark.parametrize("k, mass, degrees", [("1/2", "3.0", 57.174091439), ("1", "1.5", 65.024911775)])
def test_a_numeric_answer_too_long_in_closed_form_is_found_numerically(k, mass, degrees):
    text = _ON_ROLLING.replace("MASS", mass).replace("K*", f"({k})*")
    derivation = derive(parse_scene(text, source="on_rolling.toml"))
    implicit = derivation.implicit["separation_angle"]
    theta = derivation.scene.namespace.symbol("theta")
    point = {"m": 1.0, "M": float(mass), "g": 9.81, "R": 0.5, "r": 0.2}
    condition = parse_expression(implicit["condition"], derivation.scene.namespace).expr.subs(
        {derivation.scene.namespace.symbol(n): v for n, v in point.items()})
    f = sympy.lambdify(theta, condition)
    grid = [-3.1416 + 6.2832 * i / 4000 for i in range(4001)]
    roots = [brentq(f, a, b, xtol=1e-14) for a, b in zip(grid, grid[1:]) if f(a) * f(b) < 0]
    assert math.degrees(roots[implicit["root"]]) == pytest.approx(degrees, abs=1e-6)
    assert derivation.answers["separation_angle"] == theta


# -- 3. names the expression grammar reads as functions --------------------------------------------------
_NAMED = '''
id = "named"
title = "A block on a spring"
[parameters]
m = { dimension = "mass", domain = "positive", value = 0.5 }
PARAM = { dimension = "stiffness", domain = "positive", value = 5.0 }
[coordinates]
COORD = { dimension = "length" }
[energy]
kinetic = "m/2*COORDdot^2"
potential = "PARAM/2*COORD^2"
'''


@pytest.mark.parametrize("coordinate, parameter, named", [
    ("d", "k", "'d'"),      # its acceleration would be ddot
    ("x", "ln", "'ln'"),    # a function
    ("x", "sin", "'sin'"),
])
def test_a_name_read_as_a_function_is_refused_with_the_name(coordinate, parameter, named):
    text = _NAMED.replace("COORD", coordinate).replace("PARAM", parameter)
    with pytest.raises(SceneError, match=named):
        parse_scene(text, source="named.toml")


def test_a_name_that_is_no_function_still_loads():
    text = _NAMED.replace("COORD", "s").replace("PARAM", "k")
    derivation = derive(parse_scene(text + '[[answers]]\nname = "a"\nprompt = "a"\nexpr = "sddot"\n'
                                           'in_terms_of = ["m", "k", "s"]\n', source="named.toml"))
    assert sympy.simplify(derivation.answers["a"] - sympy.sympify("-k*s/m", locals={
        n: derivation.scene.namespace.symbol(n) for n in ("k", "s", "m")})) == 0
