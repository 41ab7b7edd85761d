"""The fourth red team's textbook scenes, each answer derived by hand (Newton's laws, in the comment
above it) and compared with the engine's closed form: exactly (the difference simplifies to zero)
and at random points of the parameters and the state (test_red_team_scenes.agree).

Every scene is a file under tests/mechanics/scenes, so tests/numerical/test_problems_confirmed.py
also confirms its answers along the simulated motion, independently of the engine.
"""

from __future__ import annotations

import re
from functools import lru_cache

import pytest
import sympy

from grader.expressions import parse_expression
from grader.mechanics.lagrange import derive
from grader.mechanics.scene import parse_scene
from tests.mechanics.conftest import SCENES
from tests.mechanics.test_red_team_scenes import agree

# Wedge and pulley: the blocks' relative acceleration a (the hanging one up, the other down the
# incline) and the wedge's A; D = (m1 + m2)(M + m1 + m2) − m1² cos²α.
PULLEY_D = "((m1 + m2)*(M + m1 + m2) - m1^2*cos(alpha)^2)"
PULLEY_REL = f"(g*(m1*sin(alpha) - m2)*(M + m1 + m2)/{PULLEY_D})"
PULLEY_A = f"(m1*cos(alpha)*{PULLEY_REL}/(M + m1 + m2))"
# Rod between a floor and a plane at β: T = m l² K(θ) θ̇²/2 with K = xc'² + yc'² + 1/12 (per l²).
ROD_K = "(cos(beta - theta)^2/sin(beta)^2 - cos(beta - theta)*sin(theta)/sin(beta) + 1/3)"
ROD_K1 = "(sin(2*beta - 2*theta)/sin(beta)^2 - cos(beta - 2*theta)/sin(beta))"  # dK/dθ
ROD_THETADDOT = f"(-(g*cos(theta)/(2*l) + {ROD_K1}*thetadot^2/2)/{ROD_K})"
ROD_XP = "(-l*cos(beta - theta)/sin(beta) + l*sin(theta)/2)"  # dxc/dθ
ROD_XPP = "(-l*sin(beta - theta)/sin(beta) + l*cos(theta)/2)"  # d²xc/dθ²
ROD_XDDOT = f"({ROD_XP}*{ROD_THETADDOT} + {ROD_XPP}*thetadot^2)"
ROD_YDDOT = f"(l/2*(cos(theta)*{ROD_THETADDOT} - sin(theta)*thetadot^2))"


def halfway(state_function: str) -> str:
    """A force of the rod's state at θ = θ0/2, θ̇² from energy."""
    speed_squared = f"(g*(sin(theta0) - sin(theta0/2))/(l*{ROD_K.replace('theta', 'theta0/2')}))"
    return re.sub(r"\btheta\b", "(theta0/2)", state_function.replace("thetadot^2", speed_squared))


# Spool on an incline, thread from the axle's top over a pulley: k = (R + r)/R, the block rises k s.
SPOOL_K = "((R + r)/R)"
SPOOL_A = f"(g*(M*sin(alpha) - m*{SPOOL_K})/(3*M/2 + m*{SPOOL_K}^2))"
SPOOL_T = f"(m*(g + {SPOOL_K}*{SPOOL_A}))"
# Pendulum from the axle of a rolling cylinder: the axle's acceleration.
ROLLING_A = "(m*sin(theta)*(g*cos(theta) + l*thetadot^2)/(3*M/2 + m*sin(theta)^2))"
# Pendulum from a ring on Y = X²/(2c): s = c sin θ − X cos θ.
RING_S = "(c*sin(theta) - X*cos(theta))"
RING_XDDOT = (f"((m*{RING_S}*(c*g*cos(theta) + c*l*thetadot^2 + Xdot^2*cos(theta)) - M*X*(c*g + Xdot^2))"
              f"/(M*(c^2 + X^2) + m*{RING_S}^2))")
RING_TENSION = f"(m*(g*cos(theta) + l*thetadot^2 + Xdot^2*cos(theta)/c) - m*{RING_XDDOT}*{RING_S}/c)"


@pytest.mark.parametrize(
    "scene, answer, expected",
    [
        # Helix turned at ω (ψ = φ − ωt the angle in the wire, z = b ψ): L = m (a² (ψ̇ + ω)² + b² ψ̇²)/2
        # − m g b ψ, so (a² + b²) ψ̈ = −g b, z̈ = −g b²/(a² + b²). The wire's force in the cylinder is
        # λ (0, −b/a, 1) (across the wire): vertically m z̈ = λ − m g, λ = m g a²/(a² + b²); its torque
        # about the axis −b λ; radially −m a φ̇² with φ̇ = ω + ż/b. From rest in the wire,
        # z = −g b² t²/(2(a² + b²)); after the drop h, ż = −√(2 g h) b/√(a² + b²).
        ("helix_rotating_bead", "equation_of_motion", "-g*b^2/(a^2 + b^2)"),
        ("helix_rotating_bead", "radial_force", "m*a*(omega + zdot/b)^2"),
        ("helix_rotating_bead", "vertical_force", "m*g*a^2/(a^2 + b^2)"),
        ("helix_rotating_bead", "axial_torque", "-m*g*a^2*b/(a^2 + b^2)"),
        ("helix_rotating_bead", "time_to_drop", "sqrt(2*h*(a^2 + b^2)/(g*b^2))"),
        ("helix_rotating_bead", "radial_force_there", "m*a*(omega - sqrt(2*g*h/(a^2 + b^2)))^2"),
        # Cone (s along the generator, ρ = s sin α): s̈ = s sin²α φ̇² − g cos α − k (s − l0)/m; the
        # spring lies along the generator, so across it N − m g sin α = m ρ φ̇² cos α. On the orbit
        # of radius ρ0, sin²α φ̇² = (g cos α + k (s0 − l0)/m)/s0; with h = s² sin²α φ̇ conserved,
        # ω² = 3 h²/(s0⁴ sin²α) + k/m = 3 sin²α φ̇² + k/m.
        ("cone_spring_orbit", "radial_equation",
         "sin(alpha)^2*rho*phidot^2 - g*sin(alpha)*cos(alpha) - k*(rho - l0*sin(alpha))/m"),
        ("cone_spring_orbit", "normal_force", "m*(g*sin(alpha) + rho*phidot^2*cos(alpha))"),
        ("cone_spring_orbit", "orbit_angular_velocity",
         "sqrt((g*cos(alpha) + k*(rho/sin(alpha) - l0)/m)/(rho*sin(alpha)))"),
        ("cone_spring_orbit", "radial_speed_squared",
         "sin(alpha)^2*(Omega0^2*rho0^2*(1 - rho0^2/rho^2) + 2*g*cos(alpha)*(rho0 - rho)/sin(alpha)"
         " + k*((rho0/sin(alpha) - l0)^2 - (rho/sin(alpha) - l0)^2)/m)"),
        # Wedge with a pulley at its top: the horizontal momentum M A + m1 (A − a cos α) + m2 A = 0;
        # the hanging block T − m2 g = m2 a, the groove pushes it with m2 A; down the incline
        # m1 (a − A cos α) = m1 g sin α − T; across it m1 (−A sin α) = N − m1 g cos α.
        ("wedge_pulley_hanging_block", "wedge_acceleration", PULLEY_A),
        ("wedge_pulley_hanging_block", "hanging_block_acceleration", PULLEY_REL),
        ("wedge_pulley_hanging_block", "tension", f"m2*(g + {PULLEY_REL})"),
        ("wedge_pulley_hanging_block", "incline_normal_force", f"m1*(g*cos(alpha) - {PULLEY_A}*sin(alpha))"),
        ("wedge_pulley_hanging_block", "groove_force", f"m2*{PULLEY_A}"),
        ("wedge_pulley_hanging_block", "wedge_position_in_time", f"{PULLEY_A}*t^2/2"),
        ("wedge_pulley_hanging_block", "time_to_rise", f"sqrt(2*h/{PULLEY_REL})"),
        # Rod from a floor to a plane at β: the triangle of the ends and the corner (sine rule) gives
        # x_A = l sin(β − θ)/sin β, so xc = l sin(β − θ)/sin β − l cos θ/2, yc = l sin θ/2;
        # energy m l² K θ̇²/2 + m g l sin θ/2 from rest at θ0; the centre: m ẍc = N_B sin β,
        # m ÿc = N_A + N_B cos β − m g; halfway, at θ0/2, with θ̇² from energy.
        ("rod_floor_inclined_wall", "equation_of_motion", ROD_THETADDOT),
        ("rod_floor_inclined_wall", "wall_force", f"m*{ROD_XDDOT}/sin(beta)"),
        ("rod_floor_inclined_wall", "floor_force", f"m*({ROD_YDDOT} + g) - m*{ROD_XDDOT}*cos(beta)/sin(beta)"),
        ("rod_floor_inclined_wall", "angular_speed_squared", f"g*(sin(theta0) - sin(theta))/(l*{ROD_K})"),
        ("rod_floor_inclined_wall", "wall_force_halfway", halfway(f"m*{ROD_XDDOT}/sin(beta)")),
        ("rod_floor_inclined_wall", "floor_force_halfway",
         halfway(f"m*({ROD_YDDOT} + g) - m*{ROD_XDDOT}*cos(beta)/sin(beta)")),
        # Ball (I = 2 m a²/5) rolling inside a loop, b = R − a: tangentially m b φ̈ = −m g sin φ + F,
        # spin I ψ̈ = a F with ψ = −b φ/a: φ̈ = −5 g sin φ/(7b), F = 2 m g sin φ/7. Energy
        # 7 m v²/10 + m g b (1 − cos φ) from v0 at the bottom; N = m v²/b + m g cos φ
        # = m (v0²/b + g (17 cos φ − 10)/7): at the top m (v0²/b − 27 g/7), so v0² ≥ 27 g b/7.
        ("ball_rolling_loop", "equation_of_motion", "-5*g*sin(phi)/(7*(R - a))"),
        ("ball_rolling_loop", "friction_force", "2*m*g*sin(phi)/7"),
        ("ball_rolling_loop", "normal_force", "m*(v0^2/(R - a) + g*(17*cos(phi) - 10)/7)"),
        ("ball_rolling_loop", "leave_cos", "(10 - 7*v0^2/(g*(R - a)))/17"),
        # Cylinder on a plank at X = A sin Ωt: m ẍ = F, (m R²/2) φ̈ = F R and ẍ + R φ̈ = Ẍ give
        # F = m Ẍ/3, ẍ = Ẍ/3; from rest at 0, ẋ = (Ẋ − Ẋ(0))/3 = A Ω (cos Ωt − 1)/3, again 0 at
        # t = 2π/Ω; R φ̇ = Ẋ − ẋ; it coasts (ẍ = 0) first at t = π/Ω.
        ("cylinder_on_oscillating_plank", "equation_of_motion", "-A*Omega^2*sin(Omega*t)/3"),
        ("cylinder_on_oscillating_plank", "friction_force", "-m*A*Omega^2*sin(Omega*t)/3"),
        ("cylinder_on_oscillating_plank", "position_in_time", "A*(sin(Omega*t) - Omega*t)/3"),
        ("cylinder_on_oscillating_plank", "velocity_in_time", "A*Omega*(cos(Omega*t) - 1)/3"),
        ("cylinder_on_oscillating_plank", "spin_in_time", "A*Omega*(2*cos(Omega*t) + 1)/(3*R)"),
        ("cylinder_on_oscillating_plank", "first_coast", "pi/Omega"),
        # Spool (I = M R²/2) rolling down (s = R φ), thread from the axle's top (it moves at
        # ṡ + r φ̇ = k ṡ) up over a pulley to the block, which rises k s: energy gives
        # (3M/2 + m k²) s̈ = g (M sin α − m k); the block m k s̈ = T − m g; the spool M s̈ =
        # M g sin α − T − F and (M R²/2) φ̈ = F R − T r, so F = M s̈/2 + T r/R (up the incline).
        # From rest, after the block rose h (s = h/k): |ẏ| = k ṡ = √(2 k h s̈), t = √(2 h/(k s̈)).
        ("spool_incline_pulley", "spool_acceleration", SPOOL_A),
        ("spool_incline_pulley", "tension", SPOOL_T),
        ("spool_incline_pulley", "friction_force", f"M*{SPOOL_A}/2 + {SPOOL_T}*r/R"),
        # |ẏ| = √(ẏ²) with ẏ² = 2 K h a ≥ 0 while the block rises (the engine writes the bars so)
        ("spool_incline_pulley", "block_speed", f"sqrt(2*{SPOOL_K}*h*{SPOOL_A})"),
        ("spool_incline_pulley", "time_to_rise", f"sqrt(2*h/({SPOOL_K}*{SPOOL_A}))"),
        # Pendulum from the axle of a rolling cylinder (T_cyl = 3 M ẋ²/4): x is cyclic,
        # p = (3M/2 + m) ẋ + m l θ̇ cos θ; the bob across the rod l θ̈ = −ẍ cos θ − g sin θ, so
        # ẍ (3M/2 + m sin²θ) = m sin θ (g cos θ + l θ̇²). The whole horizontally F = d/dt((M + m) ẋ +
        # m l θ̇ cos θ) = d/dt(p − M ẋ/2) = −M ẍ/2; vertically N = (M + m) g + m l (θ̈ sin θ + θ̇² cos θ).
        # At the bottom, from rest at θ0 (p = 0, energy): ẋ² = 2 m² g l (1 − cos θ0)/((3M/2 + m) 3M/2),
        # l θ̇² = 2 g (1 − cos θ0)(3M/2 + m)/(3M/2), θ̈ = 0.
        ("pendulum_rolling_cylinder", "cylinder_acceleration", ROLLING_A),
        ("pendulum_rolling_cylinder", "friction_force", f"-M*{ROLLING_A}/2"),
        ("pendulum_rolling_cylinder", "normal_force",
         f"(M + m)*g + m*(-({ROLLING_A}*cos(theta) + g*sin(theta))*sin(theta) + l*thetadot^2*cos(theta))"),
        ("pendulum_rolling_cylinder", "bottom_cylinder_speed",
         "m*sqrt(2*g*l*(1 - cos(theta0))/((3*M/2 + m)*3*M/2))"),
        ("pendulum_rolling_cylinder", "bottom_normal_force",
         "(M + m)*g + 2*m*g*(1 - cos(theta0))*(3*M/2 + m)/(3*M/2)"),
        # Two beads on a hoop spun at ω, a rod keeping θ1,2 = θ ± β: in the hoop's frame
        # L = m a² (θ̇² + ω² (sin²θ1 + sin²θ2)/2) + m g a (cos θ1 + cos θ2), so
        # θ̈ = ω² sin 2θ cos 2β/2 − g sin θ cos β/a; bead 1's own equation gives the rod's generalized
        # force λ = m a² (θ̈ − ω² sin θ1 cos θ1 + g sin θ1/a), whose part along the chord is
        # C = λ/(a cos β) (m g tan β on a resting hoop at θ = 0); energy in the hoop's frame
        # m a² θ̇² − 2 m g a cos β cos θ + m a² ω² cos 2β cos 2θ/2 from rest at θ0.
        ("hoop_spinning_two_beads_rod", "equation_of_motion",
         "omega^2*sin(2*theta)*cos(2*beta)/2 - g*sin(theta)*cos(beta)/a"),
        ("hoop_spinning_two_beads_rod", "rod_compression",
         "m*a*(omega^2*sin(2*theta)*cos(2*beta)/2 - g*sin(theta)*cos(beta)/a"
         " - omega^2*sin(2*theta + 2*beta)/2 + g*sin(theta + beta)/a)/cos(beta)"),
        ("hoop_spinning_two_beads_rod", "angular_speed_squared",
         "2*g*cos(beta)*(cos(theta) - cos(theta0))/a + omega^2*cos(2*beta)*(cos(2*theta0) - cos(2*theta))/2"),
        # Ring on Y = X²/(2c) (Ÿ = (X Ẍ + Ẋ²)/c), bob at l ê, ê = (sin θ, −cos θ): along ê
        # m (a_R·ê − l θ̇²) = −T + m g cos θ, across it m (a_R·ê_θ + l θ̈) = −m g sin θ; the ring along
        # its tangent (c, X): M (Ẍ (c² + X²) + Ẋ² X)/c = T s − M g X, and along the normal (−X, c):
        # M Ẋ² = N √(c² + X²) − T (X sin θ + c cos θ) − M g c.
        ("pendulum_pivot_on_parabola", "ring_equation", RING_XDDOT),
        ("pendulum_pivot_on_parabola", "rod_tension", RING_TENSION),
        ("pendulum_pivot_on_parabola", "wire_force",
         f"(M*(Xdot^2 + g*c) + {RING_TENSION}*(X*sin(theta) + c*cos(theta)))/sqrt(c^2 + X^2)"),
        ("pendulum_pivot_on_parabola", "pendulum_equation",
         f"-(g*sin(theta) + {RING_XDDOT}*(cos(theta) + X*sin(theta)/c) + Xdot^2*sin(theta)/c)/l"),
    ],
)
def test_red_team_scenes_4(derived, scene, answer, expected):
    d = derived(scene)
    if d.scene.answer(answer).kind == "equation":
        equation = d.equations[answer]
        assert equation.lhs == d.scene.answer(answer).expr
        assert equation.rhs == d.answers[answer]
    agree(d, answer, expected)
    assert_exactly(d, answer, expected)


def assert_exactly(derivation, answer: str, expected: str) -> None:
    """The answer is the expected closed form exactly, not only at agree's points. A square root may
    be written with another radicand: equal squares and, from agree, equal signs."""
    got = derivation.answers[answer]
    want = parse_expression(expected, derivation.scene.namespace).expr
    assert exactly_zero(got - want) or exactly_zero(got**2 - want**2), \
        f"{derivation.scene.id}.{answer}: {got} vs {want}"


def exactly_zero(expr: sympy.Expr) -> bool:
    """Whether expr is identically zero, as a rational function of tan(x/2) for every angle x
    (sympy.simplify proves the same but takes minutes on the rod's and the ring's forces). An angle
    that also appears halved (θ0 and θ0/2) is written as a multiple of one variable first; |…| is
    compared by its argument (agree compares the values themselves)."""
    expr = expr.replace(sympy.Abs, lambda argument: argument)
    arguments = [f.args[0] for f in expr.atoms(sympy.sin, sympy.cos)]
    for s in set().union(*(a.free_symbols for a in arguments)):
        denominators = [sympy.fraction(sympy.nsimplify(a.coeff(s)))[1] for a in arguments]
        scale = sympy.ilcm(*[int(q) for q in denominators if q.is_Integer], 1)
        if scale != 1:
            expr = expr.xreplace({s: scale*sympy.Dummy(s.name)})
    expr = sympy.expand_trig(expr)
    for x in {f.args[0] for f in expr.atoms(sympy.sin, sympy.cos)}:
        u = sympy.Dummy("u")
        expr = expr.xreplace({sympy.sin(x): 2*u/(1 + u**2), sympy.cos(x): (1 - u**2)/(1 + u**2)})
    return sympy.cancel(sympy.together(expr)) == 0


# -- special values that the motion from the scene's [initial] does not reach ---------------------
# A threshold, a small oscillation or a value at a configuration this launch does not reach: the
# numerical confirmation (tests/numerical/test_problems_confirmed.py) follows the scene's own motion,
# so these answers are derived here from the scene file with the answer appended.

STEADY_CONE_START = '''
[initial]
rho = "rho0"
rhodot = 0
phi = 0
phidot = "sqrt((g*cos(alpha) + k/m*(rho0/sin(alpha) - l0))/rho0/sin(alpha))"
'''


# The answer blocks the table below appends to its scenes more than once.
TOP_FORCE = """
[[answers]]
name = "top_normal_force"
expr = "normal_force"
where = "phi = pi"
in_terms_of = ["m", "g", "R", "a", "v0"]
dimension = "force"
"""


def small_oscillation(coordinate: str, equilibrium: str) -> str:
    """The block of a ``small_oscillation_frequency`` answer about ``equilibrium``."""
    return f"""
[[answers]]
name = "small_oscillation_frequency"
kind = "small_oscillation"
expr = "{coordinate}"
where = "{equilibrium}"
"""


@lru_cache(maxsize=None)
def derived_with(scene: str, answers: str, start: str = ""):
    text = (SCENES / f"{scene}.toml").read_text()
    if start:
        # Another start, and only the answers given here.
        text = text[:text.index("[initial]")] + start
    return derive(parse_scene(text + answers, source=f"{scene}.toml"))


@pytest.mark.parametrize(
    "scene, start, answers, answer, expected",
    [
        # The ball at the top of the loop (see above): m (v0²/b − 27 g/7), zero for v0² = 27 g b/7;
        # about the bottom φ̈ = −5 g φ/(7b).
        ("ball_rolling_loop", "", TOP_FORCE + '''
[[answers]]
name = "least_launch_speed"
expr = "v0"
where = "top_normal_force = 0"
in_terms_of = ["g", "R", "a"]
''', "least_launch_speed", "sqrt(27*g*(R - a)/7)"),
        ("ball_rolling_loop", "", TOP_FORCE, "top_normal_force", "m*(v0^2/(R - a) - 27*g/7)"),
        ("ball_rolling_loop", "", small_oscillation("phi", "phi = 0"), "small_oscillation_frequency", "sqrt(5*g/(7*(R - a)))"),
        # The blocks stay at rest relative to the wedge when m2 = m1 sin α (then A = 0 too).
        ("wedge_pulley_hanging_block", "", '''
[[answers]]
name = "balancing_mass"
expr = "m2"
where = "y2ddot = 0"
in_terms_of = ["m1", "alpha"]
dimension = "mass"
''', "balancing_mass", "m1*sin(alpha)"),
        # The spool can stay at rest when M sin α = m k: m = M R sin α/(R + r).
        ("spool_incline_pulley", "", '''
[[answers]]
name = "balancing_mass"
expr = "m"
where = "sddot = 0"
in_terms_of = ["M", "R", "r", "alpha"]
dimension = "mass"
''', "balancing_mass", "M*R*sin(alpha)/(R + r)"),
        # Linearised with p = 0: m l² θ̇² (3M/2)/(3M/2 + m) against m g l θ²: ω² = g (3M + 2m)/(3 M l).
        ("pendulum_rolling_cylinder", "", small_oscillation("theta", "theta = 0"), "small_oscillation_frequency", "sqrt(g*(3*M + 2*m)/(3*M*l))"),
        # Started on the steady orbit of radius ρ0 (see above): N = m g sin α + m ρ0 φ̇² cos α, and
        # ω² = 3 sin²α φ̇² + k/m.
        ("cone_spring_orbit", STEADY_CONE_START, '''
[[answers]]
name = "orbit_normal_force"
expr = "lambda_cone"
where = "rho = rho0"
in_terms_of = ["m", "g", "k", "l0", "alpha", "rho0"]
dimension = "force"
''', "orbit_normal_force",
         "m*(g*sin(alpha) + cos(alpha)*(g*cos(alpha) + k*(rho0/sin(alpha) - l0)/m)/sin(alpha))"),
        ("cone_spring_orbit", STEADY_CONE_START, small_oscillation("rho", "rho = rho0"), "small_oscillation_frequency",
         "sqrt(3*(g*cos(alpha) + k*(rho0/sin(alpha) - l0)/m)*sin(alpha)/rho0 + k/m)"),
    ],
)
def test_special_values_off_the_motion(scene, start, answers, answer, expected):
    d = derived_with(scene, answers, start)
    agree(d, answer, expected)
    assert_exactly(d, answer, expected)
    assert answer not in d.alternatives
