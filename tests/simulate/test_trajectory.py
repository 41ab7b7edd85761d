"""The effect-aware simulation (grader.simulate.trajectory): events where physics puts them, and
the motion after them.

Closed forms used (energy conservation plus the condition that the contact force vanishes):
- smooth sphere, released from rest at θ₀: leaves where cos θ = (2/3) cos θ₀;
- ladder on a smooth wall and floor, released from rest at θ₀ to the floor: leaves the wall when
  its top is at 2/3 of its initial height, sin θ = (2/3) sin θ₀;
- bob on a string launched at v₀ from the lowest point: slack where cos θ = (2gl − v₀²)/(3gl);
- disk on an incline: rolls (a = (2/3) g sin α) while tan α ≤ 3 μ_s, else slides with
  a = g (sin α − μ_k cos α) and spins up at R θ̈ = 2 μ_k g cos α.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from grader.mechanics.scene import load_scene, parse_scene
from grader.simulate.compiled import CompiledScene, parameter_values
from grader.simulate.effects import declared_effects
from grader.simulate.trajectory import Simulation, simulate_scene

ROOT = Path(__file__).resolve().parents[2]
SPHERE = load_scene(ROOT / "problems" / "sphere.toml")
CIRCLE = load_scene(ROOT / "problems" / "vertical_circle.toml")
LADDER = load_scene(ROOT / "tests" / "mechanics" / "scenes" / "ladder_wall.toml")
SLIPPING = load_scene(ROOT / "problems" / "incline_slipping.toml")

BALL = parse_scene('''
id = "ball"
[parameters]
m = { dimension = "mass", domain = "positive", value = 1.0 }
g = { dimension = "acceleration", domain = "positive", value = 9.81 }
e = { dimension = "dimensionless", domain = [0, 1], value = 0.5 }
[coordinates]
x = { dimension = "length" }
y = { dimension = "length" }
[energy]
kinetic = "m/2*(xdot^2 + ydot^2)"
potential = "m*g*y"
[[constraints]]
name = "floor"
f = "y"
kind = "unilateral"
restitution = "e"
[initial]
x = 0
y = 1
xdot = 0.5
''', source="ball.toml")


def simulation(scene, **overrides) -> Simulation:
    compiled = CompiledScene(scene, parameter_values(scene, overrides))
    return Simulation(compiled, declared_effects(scene, compiled.values))


@pytest.mark.parametrize("theta0", [0.05, 0.3, 0.8, 1.2])
def test_body_leaves_the_sphere_where_cos_theta_is_two_thirds_of_cos_theta0(theta0):
    motion = simulate_scene(SPHERE, {}, t_end=5.0, initial={"theta": theta0})
    release = motion.events[0]
    assert (release.effect, release.constraint) == ("release", "surface")
    assert math.cos(release.state["theta"]) == pytest.approx(2 / 3 * math.cos(theta0), abs=1e-9)


def test_free_flight_after_leaving_the_sphere_never_touches_it_again():
    motion = simulate_scene(SPHERE, {}, t_end=3.0, initial={"theta": 0.3}, samples=600)
    release = motion.events[0].t
    after = motion.t > release
    assert len(motion.events) == 1
    assert np.all(motion.q[after, 0] > 0.8)          # r > R all along the free flight
    assert not motion.active[after, 0].any()
    assert np.all(motion.multipliers[after, 0] == 0)


@pytest.mark.parametrize("theta0", [0.9, 1.2, 1.4])
def test_ladder_leaves_the_wall_with_its_top_at_two_thirds_of_its_initial_height(theta0):
    motion = simulate_scene(LADDER, {"theta0": theta0}, t_end=5.0)
    release = motion.events[0]
    assert (release.effect, release.constraint) == ("release", "wall")
    assert math.sin(release.state["theta"]) == pytest.approx(2 / 3 * math.sin(theta0), abs=1e-7)


@pytest.mark.parametrize("v0", [4.5, 5.5, 6.2])
def test_string_goes_slack_exactly_where_the_tension_is_zero(v0):
    g, l = 9.81, 0.9
    motion = simulate_scene(CIRCLE, {"v0": v0}, t_end=3.0)
    slack = motion.events[0]
    assert (slack.effect, slack.constraint) == ("release", "string")
    cos_theta = -slack.state["y"] / l
    assert cos_theta == pytest.approx((2 * g * l - v0 ** 2) / (3 * g * l), abs=1e-9)
    # The tension m l θ̇² + m g cos θ computed from the state at the event is zero.
    speed2 = slack.state["xdot"] ** 2 + slack.state["ydot"] ** 2
    assert 0.3 * speed2 / l + 0.3 * g * cos_theta == pytest.approx(0.0, abs=1e-9)


def test_slack_string_becomes_taut_again_at_its_length_and_the_jerk_removes_the_radial_speed():
    l = 0.9
    motion = simulate_scene(CIRCLE, {}, t_end=2.0)
    (slack, taut) = motion.events[:2]
    assert taut.effect == "contact" and taut.constraint == "string"
    x, y, xdot, ydot = (taut.state[k] for k in ("x", "y", "xdot", "ydot"))
    assert math.hypot(x, y) == pytest.approx(l, abs=1e-12)
    assert x * xdot + y * ydot == pytest.approx(0.0, abs=1e-12)   # inelastic: no radial velocity left
    between = (motion.t > slack.t) & (motion.t < taut.t)
    assert np.all(np.hypot(motion.q[between, 0], motion.q[between, 1]) < l)


def test_a_restart_at_an_event_does_not_fire_it_again_and_continues_the_same_motion():
    sim = simulation(SPHERE)
    first = sim.run(0.0, [0.8, 0.3], [0.0, 0.0], 1.5, np.linspace(0.0, 1.5, 31))
    release = first.events[0]
    q = [release.state["r"], release.state["theta"]]
    qdot = [release.state["rdot"], release.state["thetadot"]]
    later = first.t[first.t > release.t]
    restart = sim.run(release.t, q, qdot, 1.5, later)
    assert restart.events == []
    assert not restart.active.any()
    np.testing.assert_allclose(restart.q, first.q[first.t > release.t], rtol=1e-9, atol=1e-12)


def test_a_ball_bounces_with_its_restitution_and_comes_to_rest_after_a_finite_time():
    g, e, h = 9.81, 0.5, 1.0
    motion = simulate_scene(BALL, {}, t_end=2.0)
    bounces = [x for x in motion.events if x.effect == "bounce"]
    v1 = math.sqrt(2 * g * h)
    for k, bounce in enumerate(bounces[:6]):
        assert bounce.state["ydot"] == pytest.approx(v1 * e ** (k + 1), rel=1e-9)
    rest = motion.events[-1]
    assert rest.effect == "contact"
    # Zeno: t∞ = t₁ + 2 e v₁ / (g (1 − e)).
    assert rest.t == pytest.approx(math.sqrt(2 * h / g) + 2 * e * v1 / (g * (1 - e)), rel=1e-7)
    resting = motion.t > rest.t
    assert np.allclose(motion.q[resting, 1], 0.0, atol=1e-12)
    assert np.allclose(motion.multipliers[resting, 0], 9.81, rtol=1e-9)   # N = m g


@pytest.mark.parametrize("alpha, rolls", [(0.5, True), (0.6, False), (0.9, False)])
def test_disk_on_a_rough_incline_rolls_or_slides_as_friction_allows(alpha, rolls):
    g, R, mu_s, mu_k = 9.81, 0.2, 0.2, 0.15
    assert (math.tan(alpha) <= 3 * mu_s) == rolls
    motion = simulate_scene(SLIPPING, {"alpha": alpha}, t_end=1.0, samples=11)
    t, s, theta = motion.t[-1], motion.q[-1, 0], motion.q[-1, 1]
    if rolls:
        assert motion.events == []
        assert s == pytest.approx(g * math.sin(alpha) / 3 * t ** 2, rel=1e-9)
        assert R * theta == pytest.approx(s, rel=1e-9)
    else:
        assert [(x.effect, x.t) for x in motion.events] == [("slip", 0.0)]
        assert s == pytest.approx(g * (math.sin(alpha) - mu_k * math.cos(alpha)) / 2 * t ** 2, rel=1e-9)
        assert R * theta == pytest.approx(mu_k * g * math.cos(alpha) * t ** 2, rel=1e-9)
        # The friction reported is kinetic: μ_k N up the plane.
        assert -motion.forces[-1, 0, 0] == pytest.approx(mu_k * 1.5 * g * math.cos(alpha), rel=1e-12)


def test_a_disk_launched_without_spin_slides_until_its_slip_stops_then_rolls():
    # Launched down a gentle slope at 2 m/s without spin: kinetic friction spins it up until
    # v = R ω; from then on it rolls (tan α < 3 μ_s).
    alpha, g, R, mu_k = 0.2, 9.81, 0.2, 0.15
    motion = simulate_scene(SLIPPING, {"alpha": alpha}, t_end=2.0, initial={"sdot": 2.0, "thetadot": 0.0})
    effects = [(x.effect, x.constraint) for x in motion.events]
    assert effects == [("stick", "roll")]
    stick = motion.events[0]
    assert stick.state["sdot"] == pytest.approx(R * stick.state["thetadot"], rel=1e-12)
    # v(t) = v0 + g (sin α − μ_k cos α) t and R ω(t) = 2 μ_k g cos α t meet at t*.
    t_star = 2.0 / (2 * mu_k * g * math.cos(alpha) - g * (math.sin(alpha) - mu_k * math.cos(alpha)))
    assert stick.t == pytest.approx(t_star, rel=1e-9)


def test_a_ball_starting_on_the_floor_moving_into_it_bounces_at_the_start():
    motion = simulate_scene(BALL, {}, t_end=0.2, initial={"y": 0.0, "ydot": -1.0})
    first, second = motion.events[:2]
    assert (first.effect, first.t, first.state["ydot"]) == ("bounce", 0.0, pytest.approx(0.5, rel=1e-12))
    assert second.t == pytest.approx(2 * 0.5 / 9.81, rel=1e-9)   # flight time of a 0.5 m/s hop


def test_a_slipping_rolling_constraint_does_not_count_as_holding():
    motion = simulate_scene(SLIPPING, {"alpha": 0.9}, t_end=0.5, samples=6)
    assert not motion.active[:, 0].any()      # roll: slipping all along
    assert motion.active[:, 1].all()          # contact: holds


def test_a_scene_without_effects_costs_exactly_the_plain_integration():
    # Count the compiled M, F, J, b evaluations: the simulation of a scene with only bilateral
    # constraints must do the work of solve_ivp on the compiled right-hand side and nothing more.
    from scipy.integrate import solve_ivp

    scene = load_scene(ROOT / "tests" / "mechanics" / "scenes" / "double_pendulum.toml")
    sim = simulation(scene)
    compiled = sim.compiled
    q0 = np.array([0.6, -0.8, 0.6 + 0.7 * math.sin(0.4), -0.8 - 0.7 * math.cos(0.4)])
    calls = []
    terms = compiled.terms
    compiled.terms = lambda *args: calls.append(1) or terms(*args)
    solve_ivp(compiled.rhs, (0.0, 2.0), np.concatenate([q0, np.zeros(4)]), method="DOP853",
              rtol=sim.rtol, atol=sim.atol, dense_output=True)
    plain, calls[:] = len(calls), []
    motion = sim.run(0.0, q0, np.zeros(4), 2.0, ())
    assert len(calls) == plain and motion.events == []
    assert not sim.switching


@pytest.mark.parametrize("eps", [3e-4, 1e-5, 3e-6])
def test_a_force_that_turns_negative_and_back_within_one_step_is_a_release(eps):
    # Whirled just below the critical speed, the tension is negative for a few ms about the top,
    # less than one integrator step: scipy tests event functions only at the ends of the steps,
    # so the string kept pulling with a negative tension. Then the lift-off is so tangential
    # that the gap stays at rounding level (±1e-16) for many steps: that must not be an impact.
    g, l = 9.81, 0.9
    v0 = math.sqrt(5 * g * l) * (1 - eps)
    motion = simulate_scene(CIRCLE, {"v0": v0}, t_end=1.0)
    assert [e.effect for e in motion.events] == ["release", "contact"]
    assert -motion.events[0].state["y"] / l == pytest.approx((2 * g * l - v0 ** 2) / (3 * g * l), abs=1e-9)
    assert np.all(motion.multipliers[motion.active[:, 0], 0] >= 0)


def test_a_contact_force_exactly_zero_all_along_is_not_a_release():
    # Without gravity the floor carries exactly 0; scipy takes 0 -> 0 as a crossing of λ.
    motion = simulate_scene(BALL, {"g": 0.0}, t_end=1.0, initial={"y": 0})
    assert motion.events == []
    assert motion.active.all()


@pytest.mark.parametrize("depth", [1e-1, 1e-3, 1e-6])
def test_a_body_whose_path_crosses_a_surface_within_one_step_hits_it(depth):
    # Without gravity the flight is a straight line, which DOP853 crosses in steps as long as the
    # run: the gap to the sphere was negative only between two step ends and the body went
    # through the sphere (no event). It hits where the line meets the circle.
    R = 0.8
    scene = parse_scene(f'''
id = "through"
[parameters]
m = {{ dimension = "mass", domain = "positive", value = 1.0 }}
R = {{ dimension = "length", domain = "positive", value = {R} }}
[coordinates]
x = {{ dimension = "length" }}
y = {{ dimension = "length" }}
[energy]
kinetic = "m/2*(xdot^2 + ydot^2)"
potential = "0"
[[constraints]]
name = "sphere"
f = "x^2 + y^2 - R^2"
kind = "unilateral"
restitution = 1
[initial]
x = -2
y = {R - depth!r}
xdot = 20
''', source="through.toml")
    motion = simulate_scene(scene, {}, t_end=0.3)
    assert [e.effect for e in motion.events] == ["bounce"]
    # (to 1e-10 s: a gap counts as closed 1e-13 of its scale below zero, here at grazing incidence)
    assert motion.events[0].t == pytest.approx((2 - math.sqrt(R ** 2 - (R - depth) ** 2)) / 20, abs=1e-10)
    assert np.all(np.hypot(motion.q[:, 0], motion.q[:, 1]) >= R - 1e-12)


@pytest.mark.parametrize("beta", [0.3, 0.7, 1.1])
def test_a_contact_force_at_rounding_level_is_not_a_release(beta):
    # A block sliding along a wall parallel to gravity, in coordinates turned by β: the wall's
    # force is ±1e-16 (rounding of m g (sin β cos β − cos β sin β)); at β = 1.1 it was −8.9e-16
    # and the block released, touched and released again 16 times in 5 s.
    scene = parse_scene(f'''
id = "wall"
[parameters]
m = {{ dimension = "mass", domain = "positive", value = 1.0 }}
g = {{ dimension = "acceleration", domain = "positive", value = 9.81 }}
b = {{ dimension = "angle", domain = "real", value = {beta} }}
h = {{ dimension = "length", domain = "positive", value = 1.0 }}
[coordinates]
u = {{ dimension = "length" }}
v = {{ dimension = "length" }}
[energy]
kinetic = "m/2*(udot^2 + vdot^2)"
potential = "m*g*(u*sin(b) + v*cos(b))"
[[constraints]]
name = "wall"
f = "u*cos(b) - v*sin(b)"
kind = "unilateral"
[initial]
u = 0
v = 0
udot = "0.3*sin(b)*sqrt(g*h)"
vdot = "0.3*cos(b)*sqrt(g*h)"
''', source="wall.toml")
    motion = simulate_scene(scene, {}, t_end=5.0)
    assert motion.events == []
    assert motion.active.all()


@pytest.mark.parametrize("eps", [1e-11, 0.0, -1e-11])
def test_a_tension_that_only_touches_zero_at_the_critical_speed_holds(eps):
    # At v0² = 5 g l the tension at the top is 0, a touch; the integration leaves it ±1e-10
    # relative, which the in-step scan found below 1e-13 and released the string.
    g, l = 9.81, 0.9
    motion = simulate_scene(CIRCLE, {"v0": math.sqrt(5 * g * l) * (1 - eps)}, t_end=2.0)
    assert motion.events == []
    assert motion.active.all()


ROD = '''
id = "rod"
[parameters]
m = { dimension = "mass", domain = "positive", value = 1.0 }
g = { dimension = "acceleration", domain = "positive", value = 9.81 }
L = { dimension = "length", domain = "positive", value = 1.0 }
h = { dimension = "length", domain = "positive", value = 1.0 }
e = { dimension = "dimensionless", domain = [0, 1], value = 0.5 }
[coordinates]
x = { dimension = "length" }
y = { dimension = "length" }
theta = { dimension = "angle", domain = "real" }
[energy]
kinetic = "m/2*(xdot^2 + ydot^2) + m*L^2/24*thetadot^2"
potential = "m*g*y"
[[constraints]]
name = "left"
f = "y - L/2*sin(theta)"
kind = "unilateral"
restitution = "e"
[[constraints]]
name = "right"
f = "y + L/2*sin(theta)"
kind = "unilateral"
restitution = "e"
[initial]
x = 0
y = "h"
theta = 0
'''


@pytest.mark.parametrize("e", [0.0, 0.5, 1.0])
def test_a_rod_falling_flat_lands_on_both_ends_at_once_and_does_not_spin(e):
    # Both ends strike at t = sqrt(2h/g); each contact gets Newton's law together with the other,
    # so the rod rebounds at e v without rotation. One end after the other, e = 0.5 left it
    # spinning at θ̇ = -0.62 rad/s with ẏ = 1.49 instead of 2.21.
    motion = simulate_scene(parse_scene(ROD, source="rod.toml"), {"e": e}, t_end=0.5)
    v = math.sqrt(2 * 9.81)
    assert {x.constraint for x in motion.events} == {"left", "right"}
    assert all(x.t == pytest.approx(math.sqrt(2 / 9.81), abs=1e-10) for x in motion.events)
    after = motion.events[-1].state
    assert after["ydot"] == pytest.approx(e * v, abs=1e-9)
    assert after["thetadot"] == pytest.approx(0.0, abs=1e-9)
    assert [x.effect for x in motion.events] == (["contact"] * 2 if e == 0 else ["bounce"] * 2)
