"""The engine derives the right physics: the paper's five problems (with the paper's errors
corrected, see problems/ERRATA.md) and textbook scenes it has never seen.

Expected results are written by hand from Newtonian mechanics; each is compared with the engine's
closed form by exact symbolic difference, so a wrong factor or sign fails.
"""

from __future__ import annotations

import pytest
import sympy

from grader.expressions import parse_expression


def assert_same(derivation, answer: str, expected: str) -> None:
    scene = derivation.scene
    value = derivation.answers[answer]
    want = parse_expression(expected, scene.namespace).expr
    assert sympy.simplify(value - want) == 0, f"{scene.id}.{answer}: engine {value}, expected {want}"


@pytest.mark.parametrize(
    "problem, answer, expected",
    [
        # Problem 1: T = m l thetadot^2 + m g cos(theta) (1.16); at the bottom from rest at theta0.
        ("pendulum", "tension", "m*l*thetadot^2 + m*g*cos(theta)"),
        ("pendulum", "tension_lowest", "m*g*(3 - 2*cos(theta0))"),
        # Problem 2: half-Atwood.
        ("half_atwood", "acceleration", "m2*g/(m1 + m2)"),
        ("half_atwood", "acceleration_m1", "m2*g/(m1 + m2)"),
        ("half_atwood", "tension", "m1*m2*g/(m1 + m2)"),
        ("half_atwood", "normal_force", "m1*g"),
        # Problem 3: yo-yo (solid cylinder).
        ("yoyo", "acceleration", "2*g/3"),
        ("yoyo", "angular_acceleration", "2*g/(3*R)"),
        ("yoyo", "tension", "m*g/3"),
        # Problem 4: sphere. The paper's h = R/3 is the drop, not the height (ERRATA).
        ("sphere", "normal_force", "m*g*(3*cos(theta) - 2)"),
        ("sphere", "separation_cos", "2/3"),
        ("sphere", "separation_height", "2*R/3"),
        ("sphere", "separation_drop", "R/3"),
        # Problem 5: rolling with I = beta m R^2: friction beta m g sin(alpha)/(1 + beta) (ERRATA).
        ("incline_general", "acceleration", "g*sin(alpha)/(1 + beta)"),
        ("incline_general", "friction_force", "beta*m*g*sin(alpha)/(1 + beta)"),
        ("incline_general", "normal_force", "m*g*cos(alpha)"),
        ("incline_disk", "friction_force", "m*g*sin(alpha)/3"),
        ("incline_ring", "friction_force", "m*g*sin(alpha)/2"),
        ("incline_solid_sphere", "friction_force", "2*m*g*sin(alpha)/7"),
        ("incline_spherical_shell", "friction_force", "2*m*g*sin(alpha)/5"),
        ("incline_disk", "acceleration", "2*g*sin(alpha)/3"),
        ("incline_solid_sphere", "acceleration", "5*g*sin(alpha)/7"),
        ("incline_spherical_shell", "acceleration", "3*g*sin(alpha)/5"),
    ],
)
def test_paper_problems(derived, problem, answer, expected):
    assert_same(derived(f"problems/{problem}.toml"), answer, expected)


@pytest.mark.parametrize(
    "scene, answer, expected",
    [
        # Bead on a hoop driven at omega (rheonomic constraint phi = omega t).
        ("bead_rotating_hoop", "drive_torque", "2*m*a^2*omega*thetadot*sin(theta)*cos(theta)"),
        ("bead_rotating_hoop", "speed_squared",
         "omega^2*(sin(theta)^2 - sin(0.3)^2) + 2*g/a*(cos(theta) - cos(0.3))"),
        # Atwood machine with a disk pulley of mass M: a = (m1 - m2) g / (m1 + m2 + M/2).
        ("atwood_massive_pulley", "acceleration", "(m1 - m2)*g/(m1 + m2 + M/2)"),
        ("atwood_massive_pulley", "tension_left", "m1*(g - (m1 - m2)*g/(m1 + m2 + M/2))"),
        ("atwood_massive_pulley", "tension_right", "m2*(g + (m1 - m2)*g/(m1 + m2 + M/2))"),
        # Ladder on a smooth wall and floor leaves the wall at sin(theta) = 2/3 sin(theta0).
        ("ladder_wall", "wall_force", "3/4*m*g*cos(theta)*(3*sin(theta) - 2*sin(theta0))"),
        ("ladder_wall", "leave_sin", "2/3*sin(theta0)"),
        # Block on a free wedge: N = m M g cos(alpha) / (M + m sin^2(alpha)).
        ("wedge", "normal_force", "m*M*g*cos(alpha)/(M + m*sin(alpha)^2)"),
        ("wedge", "wedge_acceleration", "-m*g*sin(alpha)*cos(alpha)/(M + m*sin(alpha)^2)"),
        # Double pendulum: the lower rod's tension (Newton on bob 2 along the rod).
        ("double_pendulum", "tension_lower",
         "m1*m2*(g*cos(theta2) + l1*theta1dot^2*cos(theta1 - theta2) + l2*theta2dot^2"
         " - g*sin(theta1)*sin(theta1 - theta2))/(m1 + m2*sin(theta1 - theta2)^2)"),
    ],
)
def test_textbook_scenes(derived, scene, answer, expected):
    assert_same(derived(scene), answer, expected)


@pytest.mark.parametrize(
    "scene, answer, expected",
    [
        # Massless pulley: the angle phi has no kinetic energy of its own; M = diag(m1, m2, 0) is
        # singular, [M J^T; J 0] is not. Newton: a = (m1 - m2) g/(m1 + m2), T = 2 m1 m2 g/(m1 + m2).
        ("atwood_massless_pulley", "acceleration", "(m1 - m2)*g/(m1 + m2)"),
        ("atwood_massless_pulley", "angular_acceleration", "(m1 - m2)*g/(R*(m1 + m2))"),
        ("atwood_massless_pulley", "tension_left", "2*m1*m2*g/(m1 + m2)"),
        ("atwood_massless_pulley", "tension_right", "2*m1*m2*g/(m1 + m2)"),
        # Puck tied through a hole: angular momentum m1 r^2 phidot = m1 r0^2 omega0 removes phidot;
        # (m1 + m2) rddot = m1 r phidot^2 - m2 g; energy and momentum together give rdot^2.
        ("table_hole_orbit", "radial_acceleration", "(m1*r0^4*omega0^2/r^3 - m2*g)/(m1 + m2)"),
        ("table_hole_orbit", "tension", "m1*m2*(g + r0^4*omega0^2/r^3)/(m1 + m2)"),
        ("table_hole_orbit", "radial_speed_squared",
         "(m1*omega0^2*r0^2*(1 - r0^2/r^2) - 2*m2*g*(r - r0))/(m1 + m2)"),
        # Steady orbit: rddot = 0 solved for phidot, the sign the motion (omega0 > 0) gives it.
        ("table_hole_orbit", "steady_angular_velocity", "sqrt(m2*g/(m1*r))"),
        # Spinning hoop: theta'' = sin(theta) (omega^2 cos(theta) - g/a); the bead swings about
        # cos(theta*) = g/(a omega^2), with omega_small^2 = omega^2 sin^2(theta*) (linearised).
        ("bead_hoop_equilibrium", "equilibrium_cos", "g/(a*omega^2)"),
        ("bead_hoop_equilibrium", "small_oscillation_frequency", "sqrt(omega^2 - g^2/(a^2*omega^2))"),
        # Helix: z = b phi, so the drop h is reached at phi = -h/b (four turns down), v^2 = 2 g h.
        ("bead_helix", "turns_angle", "-h/b"),
        ("bead_helix", "speed_squared_there", "2*g*h"),
        # Driven support x_s = A cos(Omega t): the support's acceleration acts as a horizontal
        # inertial force m A Omega^2 cos(Omega t) in its frame.
        ("pendulum_driven_support", "equation_of_motion",
         "(A*Omega^2*cos(Omega*t)*cos(theta) - g*sin(theta))/l"),
        ("pendulum_driven_support", "tension",
         "m*(g*cos(theta) + l*thetadot^2 + A*Omega^2*cos(Omega*t)*sin(theta))"),
        # Double incline, three constraints: a = g (m1 sin(alpha) - m2 sin(beta))/(m1 + m2),
        # T = m1 m2 g (sin(alpha) + sin(beta))/(m1 + m2), N1 = m1 g cos(alpha).
        ("double_incline_cartesian", "acceleration", "g*(m1*sin(alpha) - m2*sin(beta))/(m1 + m2)"),
        ("double_incline_cartesian", "tension", "m1*m2*g*(sin(alpha) + sin(beta))/(m1 + m2)"),
        ("double_incline_cartesian", "normal_left", "m1*g*cos(alpha)"),
        # Inside a loop: N = m v^2/R + m g cos(phi) with v^2 = v0^2 - 2 g R (1 - cos(phi)); it
        # leaves where N = 0; it goes round only if N(pi) >= 0, i.e. v0 >= sqrt(5 g R).
        ("loop_inside_track", "normal_force", "m*(v0^2/R - 2*g + 3*g*cos(phi))"),
        ("loop_inside_track", "leave_cos", "(2*g*R - v0^2)/(3*g*R)"),
        ("loop_inside_track", "top_normal_force", "m*(v0^2/R - 5*g)"),
        ("loop_inside_track", "least_launch_speed", "sqrt(5*g*R)"),
        # Solid cylinder rolling inside a cylinder: T = 3/4 m (R - r)^2 phidot^2, so
        # (R - r) phidot^2 = 4 g (cos(phi) - cos(phi0))/3, N = m g (7 cos(phi) - 4 cos(phi0))/3,
        # friction F = m g sin(phi)/3 (the rolling constraint's reaction), omega^2 = 2 g/(3 (R - r)).
        ("cylinder_in_cylinder", "normal_force", "m*g*(7*cos(phi) - 4*cos(phi0))/3"),
        ("cylinder_in_cylinder", "friction_force", "m*g*sin(phi)/3"),
        ("cylinder_in_cylinder", "small_oscillation_frequency", "sqrt(2*g/(3*(R - r)))"),
        # Largest normal force over the swing: at the bottom, N(0) = m g (7 - 4 cos(phi0))/3.
        ("cylinder_in_cylinder", "largest_normal_force", "m*g*(7 - 4*cos(phi0))/3"),
    ],
)
def test_constraint_chapter_scenes(derived, scene, answer, expected):
    assert_same(derived(scene), answer, expected)


@pytest.mark.parametrize(
    "scene, answer, expected",
    [
        ("pendulum", "equation_of_motion", ("thetaddot", "-g*sin(theta)/l")),
        ("bead_rotating_hoop", "equation_of_motion", ("thetaddot", "sin(theta)*(omega^2*cos(theta) - g/a)")),
    ],
)
def test_equation_answers_are_equations(derived, scene, answer, expected):
    d = derived(f"problems/{scene}.toml" if scene == "pendulum" else scene)
    lhs, rhs = (parse_expression(e, d.scene.namespace).expr for e in expected)
    equation = d.equations[answer]
    assert equation.lhs == lhs
    assert sympy.simplify(equation.rhs - rhs) == 0


def test_pendulum_multiplier_has_the_dimension_of_force_per_length(derived):
    """ERRATA (1.15): lambda = m thetadot^2/2 + m g cos(theta)/(2 l), not ... + m g cos(theta)/2."""
    d = derived("problems/pendulum.toml")
    scene = d.scene
    from grader.mechanics.answers import AnswerEvaluator

    evaluator = AnswerEvaluator(scene, d.eom)
    lam = evaluator.reduce(scene.namespace.symbol("lambda_string"),
                           evaluator.parameters | evaluator.state_symbols(), "test")
    expected = parse_expression("m*thetadot^2/2 + m*g*cos(theta)/(2*l)", scene.namespace).expr
    assert sympy.simplify(lam - expected) == 0


def test_constraint_forces_follow_the_papers_convention(derived):
    """Q_<c>_<q> = lambda_c * df_c/dq: for the yo-yo (f = R theta - s), Q_s = -lambda, Q_theta = R lambda."""
    d = derived("problems/yoyo.toml")
    forces = d.eom.constraint_forces["unwind"]
    lam = d.eom.multipliers["unwind"]
    R = d.scene.namespace.symbol("R")
    assert sympy.simplify(forces["s"] + lam) == 0
    assert sympy.simplify(forces["theta"] - R * lam) == 0


@pytest.mark.parametrize(
    "scene, answer, written",
    [
        # The forms a physicist writes: factored, single angles, sin² rather than 1 - cos².
        ("problems/sphere.toml", "normal_force", "g*m*(3*cos(theta) - 2)"),
        ("problems/incline_general.toml", "friction_force", "beta*g*m*sin(alpha)/(beta + 1)"),
        ("wedge", "wedge_acceleration", "-g*m*sin(alpha)*cos(alpha)/(M + m*sin(alpha)**2)"),
        # One square root over a radicand with the common factor out of its sums, not
        # sqrt(2*g/(3*R - 3*r)) or sqrt(2)*sqrt(d)*sqrt(1/sin(alpha))/sqrt(g).
        ("cylinder_in_cylinder", "small_oscillation_frequency", "sqrt(2*g/(3*(R - r)))"),
        ("block_incline_time", "time_to_slide", "sqrt(2*d/(g*sin(alpha)))"),
        ("table_hole_orbit", "steady_angular_velocity", "sqrt(g*m2/(m1*r))"),
        ("loop_inside_track", "least_launch_speed", "sqrt(5*R*g)"),
        ("bead_rotating_rod", "speed_at_end", "omega*sqrt(L**2 - r0**2)"),
        # The motion in time with hyperbolic functions, not r0*exp(omega*t)/2 + r0*exp(-omega*t)/2.
        ("bead_rotating_rod", "radius_in_time", "r0*cosh(omega*t)"),
        # acosh(L/r0) rather than the log((L + sqrt(L**2 - r0**2))/r0) that solve() returns.
        ("bead_rotating_rod", "time_to_end", "acosh(L/r0)/omega"),
        # The double angle where it is shorter (2 sinh·cosh, 2 sin·cos), not where it is not (the
        # wedge above).
        ("bead_rotating_rod", "drive_torque_in_time", "m*omega**2*r0**2*sinh(2*omega*t)"),
        ("bead_rotating_hoop", "drive_torque", "a**2*m*omega*thetadot*sin(2*theta)"),
        # Terms grouped over their common factor (m1 + m2), over m1 + m2 sin²(θ1 − θ2).
        ("double_pendulum", "tension_upper",
         "m1*(l2*m2*theta2dot**2*cos(theta1 - theta2) + (m1 + m2)*(g*cos(theta1) + l1*theta1dot**2))"
         "/(m1 + m2*sin(theta1 - theta2)**2)"),
        ("double_pendulum", "tension_lower",
         "m1*m2*(l2*theta2dot**2 + (g*cos(theta1) + l1*theta1dot**2)*cos(theta1 - theta2))"
         "/(m1 + m2*sin(theta1 - theta2)**2)"),
        # m (v0²/R + g (3 cos φ − 2)), not m (3 R g cos φ − 2 R g + v0²)/R.
        ("loop_inside_track", "normal_force", "m*(g*(3*cos(phi) - 2) + v0**2/R)"),
        ("loop_inside_track", "top_normal_force", "m*(-5*g + v0**2/R)"),
        # Circular and hyperbolic functions of one argument, each sum over its common factor.
        ("bead_vertical_rotating_rod", "velocity_in_time",
         "g*(cos(omega*t) - cosh(omega*t))/(2*omega) + omega*r0*sinh(omega*t)"),
        # The ladder's largest wall force with the halves cleared from (√(sin²θ0 + 18) − 3 sin θ0).
        ("ladder_wall", "largest_wall_force",
         "3*g*m*sqrt(1 - (sqrt(sin(theta0)**2 + 18) + sin(theta0))**2/36)*(sqrt(sin(theta0)**2 + 18) - 3*sin(theta0))/8"),
    ],
)
def test_answers_are_in_the_form_a_person_writes(derived, scene, answer, written):
    assert sympy.sstr(derived(scene).answers[answer]) == written


def test_a_sum_that_is_a_square_is_printed_as_one(derived):
    """Watt's governor: (M + m)², not the M² + 2Mm + m² that cancelling leaves. (Whether its roots
    are gathered into one depends on how far simplify gets within its budget.)"""
    printed = sympy.sstr(derived("watt_governor").answers["small_oscillation_frequency"])
    assert "(M + m)**2" in printed and "M**2" not in printed


def test_largest_wall_force_on_the_ladder_is_at_the_stationary_point(derived):
    """dN/dθ = 0 for N = 3/4 m g cos θ (3 sin θ − 2 sin θ₀) gives 6 sin²θ − 2 sin θ₀ sin θ − 3 = 0,
    so sin θ* = (sin θ₀ + √(sin²θ₀ + 18))/6 (inside the slide from θ₀ down), and N there."""
    d = derived("ladder_wall")
    value = d.answers["largest_wall_force"]
    m, g, theta0 = (d.scene.namespace.symbol(n) for n in ("m", "g", "theta0"))
    s0 = sympy.sin(theta0)
    star = (s0 + sympy.sqrt(s0 ** 2 + 18)) / 6
    expected = sympy.Rational(3, 4) * m * g * sympy.sqrt(1 - star ** 2) * (3 * star - 2 * s0)
    for point in ({m: 10, g: 9.81, theta0: 1.2}, {m: 2.5, g: 3.7, theta0: 0.6}):
        assert abs(float((value - expected).subs(point))) < 1e-12 * float(expected.subs(point))


D_ATWOOD = "(4*m2*m3 + m1*(m2 + m3))"
DISK_WEDGE = "(3*M + m + 2*m*sin(alpha)^2)"


@pytest.mark.parametrize(
    "scene, answer, expected",
    [
        # Spherical pendulum, Cartesian with x^2 + y^2 + z^2 = l^2: radial Newton gives
        # T = m l (thetadot^2 + sin^2(theta) phidot^2) + m g cos(theta); L_z = m l^2 sin^2(theta) phidot and
        # energy from (theta0, Omega0) remove both velocities; steady cone: phidot^2 = g/(l cos(theta)).
        ("spherical_pendulum", "tension_state", "m*(g*cos(theta) + l*(thetadot^2 + sin(theta)^2*phidot^2))"),
        ("spherical_pendulum", "tension", "m*l*Omega0^2*sin(theta0)^2 + m*g*(3*cos(theta) - 2*cos(theta0))"),
        ("spherical_pendulum", "polar_speed_squared",
         "Omega0^2*sin(theta0)^2*(1 - sin(theta0)^2/sin(theta)^2) + 2*g/l*(cos(theta) - cos(theta0))"),
        ("spherical_pendulum", "conical_angular_velocity", "sqrt(g/(l*cos(theta)))"),
        # Pendulum on a free cart: M Xddot = T sin(theta) and, along the rod,
        # T = m g cos(theta) + m l thetadot^2 - m Xddot sin(theta); across it
        # l thetaddot = -g sin(theta) - Xddot cos(theta). Momentum (M + m) Xdot + m l cos(theta) thetadot = 0.
        ("pendulum_sliding_support", "tension", "M*m*(g*cos(theta) + l*thetadot^2)/(M + m*sin(theta)^2)"),
        ("pendulum_sliding_support", "cart_acceleration",
         "m*sin(theta)*(g*cos(theta) + l*thetadot^2)/(M + m*sin(theta)^2)"),
        ("pendulum_sliding_support", "angular_acceleration",
         "-sin(theta)*((M + m)*g + m*l*thetadot^2*cos(theta))/(l*(M + m*sin(theta)^2))"),
        ("pendulum_sliding_support", "cart_velocity", "-m*l*cos(theta)*thetadot/(M + m)"),
        # At the bottom the kinetic energy is M m l^2 thetadot^2/(2 (M + m)) = m g l (1 - cos(theta0)).
        ("pendulum_sliding_support", "bottom_tension", "m*g*(1 + 2*(M + m)*(1 - cos(theta0))/M)"),
        # Inside a cone (z = rho cot(alpha)): along the normal N - m g sin(alpha) = m rho phidot^2 cos(alpha);
        # rho^2 phidot = rho0^2 Omega0, and T = m/2 (rhodot^2/sin^2(alpha) + rho^2 phidot^2).
        ("particle_in_cone", "normal_force_state", "m*(g*sin(alpha) + rho*phidot^2*cos(alpha))"),
        ("particle_in_cone", "normal_force", "m*(g*sin(alpha) + rho0^4*Omega0^2*cos(alpha)/rho^3)"),
        ("particle_in_cone", "radial_acceleration",
         "sin(alpha)^2*rho0^4*Omega0^2/rho^3 - g*sin(alpha)*cos(alpha)"),
        ("particle_in_cone", "radial_speed_squared",
         "sin(alpha)^2*rho0^2*Omega0^2*(1 - rho0^2/rho^2) - 2*g*(rho - rho0)*sin(alpha)*cos(alpha)"),
        ("particle_in_cone", "orbit_angular_velocity", "sqrt(g*cos(alpha)/(rho*sin(alpha)))"),
        # Disk (I = m R^2/2) rolling down a free wedge: (M + m) Xddot + m cos(alpha) sddot = 0 and
        # m cos(alpha) Xddot + 3/2 m sddot = m g sin(alpha); friction I psiddot/R = m sddot/2;
        # normal force N = m g cos(alpha) + m Xddot sin(alpha); Xdot = -m cos(alpha) sdot/(M + m),
        # sdot^2 = 2 sddot s.
        ("disk_on_sliding_wedge", "wedge_acceleration", f"-2*m*g*sin(alpha)*cos(alpha)/{DISK_WEDGE}"),
        ("disk_on_sliding_wedge", "rolling_acceleration", f"2*g*sin(alpha)*(M + m)/{DISK_WEDGE}"),
        ("disk_on_sliding_wedge", "friction_force", f"m*g*sin(alpha)*(M + m)/{DISK_WEDGE}"),
        ("disk_on_sliding_wedge", "normal_force", f"m*g*cos(alpha)*(3*M + m)/{DISK_WEDGE}"),
        ("disk_on_sliding_wedge", "wedge_velocity",
         f"-m*cos(alpha)/(M + m)*sqrt(4*g*s*sin(alpha)*(M + m)/{DISK_WEDGE})"),
        # Bead on z = a r^2 spun at omega: L = m/2 ((1 + 4 a^2 r^2) rdot^2 + omega^2 r^2) - m g a r^2;
        # vertically m zddot = lambda - m g; phi: the motor's torque d/dt(m r^2 omega).
        ("bead_rotating_parabola", "equation_of_motion",
         "r*(omega^2 - 2*g*a - 4*a^2*rdot^2)/(1 + 4*a^2*r^2)"),
        ("bead_rotating_parabola", "vertical_reaction",
         "m*(g + 2*a*rdot^2 + 2*a*omega^2*r^2)/(1 + 4*a^2*r^2)"),
        ("bead_rotating_parabola", "drive_torque", "2*m*omega*r*rdot"),
        ("bead_rotating_parabola", "radial_speed_squared", "(omega^2 - 2*g*a)*(r^2 - r0^2)/(1 + 4*a^2*r^2)"),
        ("bead_rotating_parabola", "small_oscillation_frequency", "sqrt(2*g*a - omega^2)"),
        ("bead_rotating_parabola", "critical_angular_velocity", "sqrt(2*g*a)"),
        # Double Atwood: T1 = 2 T2 (massless pulley), a2 + a3 = -2 a1, T2 = 4 g/(4/m1 + 1/m2 + 1/m3).
        ("double_atwood", "acceleration_1", f"g*(m1*(m2 + m3) - 4*m2*m3)/{D_ATWOOD}"),
        ("double_atwood", "acceleration_2", f"g*(4*m2*m3 + m1*m2 - 3*m1*m3)/{D_ATWOOD}"),
        ("double_atwood", "acceleration_3", f"g*(4*m2*m3 + m1*m3 - 3*m1*m2)/{D_ATWOOD}"),
        ("double_atwood", "tension_upper", f"8*g*m1*m2*m3/{D_ATWOOD}"),
        ("double_atwood", "tension_lower", f"4*g*m1*m2*m3/{D_ATWOOD}"),
        ("double_atwood", "balancing_mass", "4*m2*m3/(m2 + m3)"),
        # Dumbbell in a corner: N_wall = m xddot_2 = -m l (sin(theta) thetaddot + cos(theta) thetadot^2),
        # N_floor = 2 m g + m yddot_1, with thetaddot = -g cos(theta)/l; leaves at sin(theta) = 2/3 sin(theta0).
        ("rod_in_corner", "wall_force_state", "m*cos(theta)*(g*sin(theta) - l*thetadot^2)"),
        ("rod_in_corner", "floor_force_state", "m*(g*(1 + sin(theta)^2) - l*thetadot^2*sin(theta))"),
        ("rod_in_corner", "wall_force", "m*g*cos(theta)*(3*sin(theta) - 2*sin(theta0))"),
        ("rod_in_corner", "leave_sin", "2*sin(theta0)/3"),
        # Spool: m xddot = F cos(beta) + f, I xddot/R = -F b - R f (torques about the axis).
        ("spool_pulled_at_angle", "acceleration", "F*R*(R*cos(beta) - b)/(m*R^2 + I)"),
        ("spool_pulled_at_angle", "friction_force", "-F*(m*b*R + I*cos(beta))/(m*R^2 + I)"),
        ("spool_pulled_at_angle", "normal_force", "m*g - F*sin(beta)"),
        ("spool_pulled_at_angle", "critical_cos", "b/R"),
        # Slot on a turntable: rddot = omega^2 r - k (r - l0)/m; sideways the Coriolis force 2 m omega rdot.
        ("turntable_slot_spring", "equation_of_motion", "(omega^2 - k/m)*r + k*l0/m"),
        ("turntable_slot_spring", "slot_force", "2*m*omega*rdot"),
        ("turntable_slot_spring", "equilibrium_radius", "k*l0/(k - m*omega^2)"),
        ("turntable_slot_spring", "small_oscillation_frequency", "sqrt(k/m - omega^2)"),
        ("turntable_slot_spring", "critical_angular_velocity", "sqrt(k/m)"),
        # Conical pendulum: the spherical pendulum's tension with Omega0^2 = g/(l cos(theta0)).
        ("conical_pendulum", "tension", "m*g*sin(theta0)^2/cos(theta0) + m*g*(3*cos(theta) - 2*cos(theta0))"),
        ("conical_pendulum", "steady_tension", "m*g/cos(theta0)"),
        ("conical_pendulum", "period", "2*pi*sqrt(l*cos(theta0)/g)"),
        # Watt governor: L = m l^2 (thetadot^2 + omega^2 sin^2(theta)) + 2 M l^2 sin^2(theta) thetadot^2
        # + 2 (m + M) g l cos(theta); the sleeve M zddot = M g + lambda with z = 2 l cos(theta); about
        # cos(theta*) = (m + M) g/(m l omega^2): omega_s^2 = m omega^2 sin^2(theta*)/(m + 2 M sin^2(theta*)).
        ("watt_governor", "equation_of_motion",
         "sin(theta)*(l*cos(theta)*(m*omega^2 - 2*M*thetadot^2) - (m + M)*g)/(l*(m + 2*M*sin(theta)^2))"),
        ("watt_governor", "sleeve_force",
         "M*m*(g*(1 - 2*sin(theta)^2) + 2*l*cos(theta)*(thetadot^2 + omega^2*sin(theta)^2))/(m + 2*M*sin(theta)^2)"),
        ("watt_governor", "small_oscillation_frequency",
         "sqrt(m*omega^2*(m^2*l^2*omega^4 - (m + M)^2*g^2)/(l^2*m^2*omega^4*(m + 2*M) - 2*M*(m + M)^2*g^2))"),
        ("watt_governor", "least_angular_velocity", "sqrt((m + M)*g/(m*l))"),
        # thetaddot = 0 holds on the swing from theta0 too, but in terms of m, M, g, l, omega alone it
        # can only name the relative equilibrium, at rest: d/dtheta of the effective potential is zero.
        ("watt_governor", "equilibrium_cos", "(m + M)*g/(m*l*omega^2)"),
        # Cylinder (I = m R^2/2) on a pulled plank: f = m xddot, R f = I phiddot, xddot + R phiddot = Xddot,
        # M Xddot = F - f; the cylinder's momentum m xdot - m (Xdot - xdot)/2 stays 0.
        ("cylinder_on_plank", "plank_acceleration", "3*F/(3*M + m)"),
        ("cylinder_on_plank", "cylinder_acceleration", "F/(3*M + m)"),
        ("cylinder_on_plank", "friction_force", "m*F/(3*M + m)"),
        ("cylinder_on_plank", "cylinder_speed", "sqrt(6*F*X/(3*M + m))/3"),
        # Heavy top, I1 = A + M l^2 about the pivot: N_z = M g + M zddot_c with z_c = l cos(theta) and
        # I1 thetaddot = I1 sin cos phidot^2 - C omega3 phidot sin + M g l sin (omega3 = psidot + phidot cos);
        # p_psi = C omega3 = C s0 and p_phi = I1 sin^2 phidot + C omega3 cos = C s0 cos(theta0); energy.
        ("heavy_top", "vertical_pivot_force",
         "M*g - M*l*cos(theta)*thetadot^2 - M*l*sin(theta)*(sin(theta)*cos(theta)*phidot^2"
         " - C*(psidot + phidot*cos(theta))*phidot*sin(theta)/(A + M*l^2) + M*g*l*sin(theta)/(A + M*l^2))"),
        ("heavy_top", "precession_rate", "C*s0*(cos(theta0) - cos(theta))/((A + M*l^2)*sin(theta)^2)"),
        ("heavy_top", "nutation_speed_squared",
         "2*M*g*l*(cos(theta0) - cos(theta))/(A + M*l^2)"
         " - C^2*s0^2*(cos(theta0) - cos(theta))^2/((A + M*l^2)^2*sin(theta)^2)"),
    ],
)
def test_more_constraint_chapter_scenes(derived, scene, answer, expected):
    assert_same(derived(scene), answer, expected)
