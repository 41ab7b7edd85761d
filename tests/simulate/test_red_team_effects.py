"""Red team of the simulation's effects on scenes it was not written for: a contact is released
exactly where the scene's physics says (and only if the scene declares it unilateral), a
bilateral constraint never is, and a contact force of zero or a body at rest in equilibrium is
not a release.

Hand-derived values (energy conservation plus the vanishing contact force, or free fall):
- particle from rest at θ₀ on a smooth cylinder (any coordinates): cos θ = (2/3) cos θ₀;
- block on a plate at height A cos ωt (A ω² > g): it leaves where the plate's downward
  acceleration A ω² cos ωt reaches g, lands where its free fall meets the plate;
- Atwood machine, mass 1 thrown up at v with mass 2 at rest: both fall freely and the string is
  taut again at t = v/g, when the inelastic jerk leaves ẏ₁ = −ẏ₂ = −v m₂/(m₁ + m₂);
- bob whirled from the lowest point at v₀ < √(5 g l): slack where cos θ = (2 g l − v₀²)/(3 g l)
  (from the downward vertical), also when v₀ is within 1e-5 of the critical speed.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

from grader.mechanics.scene import load_scene, parse_scene
from grader.simulate.trajectory import simulate_scene

ROOT = Path(__file__).resolve().parents[2]
SCENES = Path(__file__).resolve().parent / "scenes"
G = 9.81


def scene_text(name: str) -> str:
    return (SCENES / f"{name}.toml").read_text()


def cylinder(kind: str):
    text = scene_text("cylinder_cartesian").replace('kind = "unilateral"', f'kind = "{kind}"')
    return parse_scene(text, source=f"cylinder_{kind}.toml")


def whirl(kind: str, v0: float, l: float = 0.9):
    return parse_scene(f'''
id = "whirl"
[parameters]
m = {{ dimension = "mass", domain = "positive", value = 0.3 }}
g = {{ dimension = "acceleration", domain = "positive", value = {G} }}
l = {{ dimension = "length", domain = "positive", value = {l} }}
v0 = {{ dimension = "velocity", domain = "nonnegative", value = {v0!r} }}
[coordinates]
x = {{ dimension = "length" }}
y = {{ dimension = "length" }}
[energy]
kinetic = "m/2*(xdot^2 + ydot^2)"
potential = "m*g*y"
[[constraints]]
name = "string"
f = "l^2 - x^2 - y^2"
kind = "{kind}"
[initial]
x = 0
y = "-l"
xdot = "v0"
ydot = 0
''', source=f"whirl_{kind}.toml")


def energy(motion, m=1.0):
    return m / 2 * (motion.qdot ** 2).sum(axis=1) + m * G * motion.q[:, -1]


@pytest.mark.parametrize("theta0", [1e-3, 0.4, 1.0])
def test_a_particle_leaves_a_cylinder_given_in_cartesian_coordinates_where_cos_theta_is_two_thirds_of_cos_theta0(theta0):
    motion = simulate_scene(cylinder("unilateral"), {"theta0": theta0}, t_end=3.0, samples=601)
    assert [(e.effect, e.constraint) for e in motion.events] == [("release", "surface")]
    release = motion.events[0]
    assert release.state["y"] / 0.7 == pytest.approx(2 / 3 * math.cos(theta0), abs=1e-9)
    before, after = motion.t < release.t, motion.t > release.t
    assert np.ptp(energy(motion)[before]) < 1e-8 and np.ptp(energy(motion)[after]) < 1e-8
    assert np.all(motion.multipliers[before, 0] >= 0) and np.all(np.hypot(*motion.q[after].T) > 0.7)


def test_a_bead_on_a_circular_wire_never_leaves_it_and_its_normal_force_changes_sign():
    motion = simulate_scene(cylinder("bilateral"), {}, t_end=3.0, samples=601)
    assert motion.events == []
    assert motion.active.all()
    assert motion.multipliers[:, 0].max() > 1 and motion.multipliers[:, 0].min() < -1
    np.testing.assert_allclose(np.hypot(*motion.q.T), 0.7, rtol=1e-10)
    assert np.ptp(energy(motion)) < 1e-8


@pytest.mark.parametrize("eps", [1e-2, 3e-4, 1e-5, 3e-6])
def test_a_string_whirled_just_below_the_critical_speed_goes_slack_where_the_tension_vanishes(eps):
    # The tension is negative only for a few ms about the top, shorter than one step of the
    # integrator: a sign change tested only at the ends of the steps was missed (no event, the
    # string pulling with a negative tension), and the near-tangential lift-off then chattered.
    l = 0.9
    v0 = math.sqrt(5 * G * l) * (1 - eps)
    motion = simulate_scene(whirl("unilateral", v0), {}, t_end=1.0, samples=401)
    assert [(e.effect, e.constraint) for e in motion.events] == [("release", "string"), ("contact", "string")]
    cos_theta = -motion.events[0].state["y"] / l
    assert cos_theta == pytest.approx((2 * G * l - v0 ** 2) / (3 * G * l), abs=1e-9)
    assert np.all(motion.multipliers[motion.active[:, 0], 0] >= 0)


@pytest.mark.parametrize("v0", [math.sqrt(5 * G * 0.9) * (1 - 1e-5), 5.5, 3.0])
def test_a_rigid_rod_never_goes_slack_and_pushes_where_a_string_could_not(v0):
    motion = simulate_scene(whirl("bilateral", v0), {}, t_end=1.0, samples=401)
    assert motion.events == []
    if v0 > math.sqrt(2 * G * 0.9):
        assert motion.multipliers[:, 0].min() < 0
    assert np.ptp(energy(motion, 0.3)) < 1e-8


@pytest.mark.parametrize("v0", [0.0, 3.0, math.sqrt(5 * G * 0.9) * (1 + 1e-6), 7.0])
def test_a_string_that_stays_taut_is_never_released(v0):
    motion = simulate_scene(whirl("unilateral", v0), {}, t_end=2.0)
    assert motion.events == []
    assert motion.active.all()


def test_bodies_at_rest_in_equilibrium_on_their_contacts_stay_there():
    sphere = simulate_scene(load_scene(ROOT / "problems" / "sphere.toml"), {}, t_end=5.0)
    assert sphere.events == [] and np.all(sphere.q[:, 1] == 0)
    np.testing.assert_allclose(sphere.multipliers[:, 0], 0.2 * G, rtol=1e-12)
    atwood = simulate_scene(load_scene(SCENES / "atwood_slack.toml"), {"m2": 1.0, "v": 0.0}, t_end=5.0)
    assert atwood.events == []
    np.testing.assert_allclose(atwood.multipliers[:, 0], G, rtol=1e-12)


def test_a_contact_force_that_is_exactly_zero_is_never_a_release():
    # No gravity: the floor carries 0 at every instant; scipy counts 0 -> 0 as a crossing.
    floor = parse_scene('''
id = "weightless"
[parameters]
m = { dimension = "mass", domain = "positive", value = 1.0 }
g = { dimension = "acceleration", domain = "nonnegative", value = 0.0 }
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
[initial]
x = 0
y = 0
xdot = 1
''', source="weightless.toml")
    motion = simulate_scene(floor, {}, t_end=2.0)
    assert motion.events == []
    assert np.all(motion.q[:, 1] == 0)


def test_a_block_on_a_vibrating_plate_leaves_and_lands_where_free_fall_says():
    A, w = 0.05, 20.0
    motion = simulate_scene(load_scene(SCENES / "vibrating_plate.toml"), {}, t_end=0.45, samples=901)
    kinds = [e.effect for e in motion.events]
    assert kinds == ["release", "contact", "release"]
    release, contact, again = motion.events
    # At t = 0 the plate is at its top, accelerating down at A w^2 = 20 > g: it leaves at once.
    assert release.t == 0.0

    def gap(t):
        return A - G / 2 * t ** 2 - A * math.cos(w * t)

    assert contact.t == pytest.approx(brentq(gap, 0.05, 0.2, xtol=1e-15), abs=1e-10)
    # Inelastic landing, then carried until A w^2 cos(w t) = g again on the way up to the top.
    assert again.t == pytest.approx((2 * math.pi - math.acos(G / (A * w * w))) / w, abs=1e-10)
    riding = (motion.t > contact.t) & (motion.t < again.t)
    np.testing.assert_allclose(motion.q[riding, 0], A * np.cos(w * motion.t[riding]), atol=1e-12)
    assert np.all(motion.multipliers[riding, 0] >= 0)


@pytest.mark.parametrize("m1, m2, v", [(1.0, 2.0, 2.0), (3.0, 1.0, 0.5)])
def test_an_atwood_string_slack_from_the_start_jerks_taut_at_v_over_g(m1, m2, v):
    motion = simulate_scene(load_scene(SCENES / "atwood_slack.toml"), {"m1": m1, "m2": m2, "v": v},
                            t_end=1.0, samples=401)
    assert [(e.effect, e.constraint) for e in motion.events] == [("contact", "string")]
    taut = motion.events[0]
    assert taut.t == pytest.approx(v / G, rel=1e-10)
    assert taut.state["y1dot"] == pytest.approx(-v * m2 / (m1 + m2), rel=1e-10)
    assert taut.state["y2dot"] == pytest.approx(v * m2 / (m1 + m2), rel=1e-10)
    after = motion.t > taut.t
    np.testing.assert_allclose(motion.multipliers[after, 0], 2 * m1 * m2 * G / (m1 + m2), rtol=1e-9)


def test_two_contacts_release_in_sequence_each_at_its_own_angle():
    spheres = parse_scene('''
id = "two_spheres"
[parameters]
m = { dimension = "mass", domain = "positive", value = 1.0 }
g = { dimension = "acceleration", domain = "positive", value = 9.81 }
R = { dimension = "length", domain = "positive", value = 0.8 }
[coordinates]
r1 = { dimension = "length", domain = "positive" }
a1 = { dimension = "angle", domain = "real" }
r2 = { dimension = "length", domain = "positive" }
a2 = { dimension = "angle", domain = "real" }
[energy]
kinetic = "m/2*(r1dot^2 + r1^2*a1dot^2) + m/2*(r2dot^2 + r2^2*a2dot^2)"
potential = "m*g*r1*cos(a1) + m*g*r2*cos(a2)"
[[constraints]]
name = "first"
f = "r1 - R"
kind = "unilateral"
[[constraints]]
name = "second"
f = "r2 - R"
kind = "unilateral"
[initial]
a1 = 0.3
a2 = 0.05
''', source="two_spheres.toml")
    motion = simulate_scene(spheres, {}, t_end=3.0)
    assert [(e.effect, e.constraint) for e in motion.events] == [("release", "first"), ("release", "second")]
    first, second = motion.events
    assert math.cos(first.state["a1"]) == pytest.approx(2 / 3 * math.cos(0.3), abs=1e-9)
    assert math.cos(second.state["a2"]) == pytest.approx(2 / 3 * math.cos(0.05), abs=1e-9)
    between = (motion.t > first.t) & (motion.t < second.t)
    assert not motion.active[between, 0].any() and motion.active[between, 1].all()


def test_a_ladder_leaves_the_wall_but_not_the_floor_and_keeps_its_energy():
    m, l = 10.0, 3.0
    motion = simulate_scene(load_scene(ROOT / "tests" / "mechanics" / "scenes" / "ladder_wall.toml"),
                            {"theta0": 1.2}, t_end=1.0, samples=1001)
    assert [(e.effect, e.constraint) for e in motion.events] == [("release", "wall")]
    assert math.sin(motion.events[0].state["theta"]) == pytest.approx(2 / 3 * math.sin(1.2), abs=1e-9)
    assert motion.active[:, 1].all() and motion.multipliers[:, 1].min() > 0
    kinetic = m / 2 * (motion.qdot[:, 1] ** 2 + motion.qdot[:, 2] ** 2) + m * l ** 2 / 24 * motion.qdot[:, 0] ** 2
    assert np.ptp(kinetic + m * G * motion.q[:, 2]) < 1e-7


@pytest.mark.parametrize("mu", [0.3, 1.0, 100.0])
def test_a_disk_rolling_off_a_cylinder_slips_where_friction_runs_out_then_leaves_where_n_vanishes(mu):
    # Rolling: (R + a) θ̇² = (4/3) g (cos θ₀ − cos θ), N = m g cos θ − m (R + a) θ̇², friction
    # m g sin θ / 3: it slips where sin θ / 3 = μ ((7/3) cos θ − (4/3) cos θ₀), before
    # N = 0 (cos θ = (4/7) cos θ₀) for any μ. Then kinetic friction μ N until N = 0, integrated
    # here independently: ρ θ̈ = g sin θ − μ N/m, (a/2) φ̈ = μ N/m.
    from scipy.integrate import solve_ivp

    g, rho, a, theta0 = G, 1.2, 0.2, 0.05
    motion = simulate_scene(load_scene(SCENES / "disk_off_cylinder.toml"), {"mu": mu}, t_end=3.0)
    assert [(e.effect, e.constraint) for e in motion.events] == [("slip", "roll"), ("release", "contact")]
    slip, release = motion.events
    expected = brentq(lambda th: math.sin(th) / 3 - mu * (7 / 3 * math.cos(th) - 4 / 3 * math.cos(theta0)),
                      theta0, math.acos(4 / 7 * math.cos(theta0)), xtol=1e-15)
    assert slip.state["theta"] == pytest.approx(expected, abs=1e-9)

    def rhs(t, y):
        theta, w, _, wphi = y
        normal = g * math.cos(theta) - rho * w * w
        return [w, (g * math.sin(theta) - mu * normal) / rho, wphi, 2 * mu * normal / a]

    def leaves(t, y):
        return g * math.cos(y[0]) - rho * y[1] ** 2

    leaves.terminal = True
    s = slip.state
    check = solve_ivp(rhs, (slip.t, 3.0), [s["theta"], s["thetadot"], s["phi"], s["phidot"]], method="DOP853",
                      rtol=1e-12, atol=1e-12, events=leaves)
    assert release.t == pytest.approx(check.t_events[0][0], abs=1e-9)
    assert release.state["theta"] == pytest.approx(check.y_events[0][0][0], abs=1e-9)
    assert release.state["phidot"] == pytest.approx(check.y_events[0][0][3], rel=1e-9)


def test_a_body_that_leaves_a_sphere_lands_on_the_floor_and_bounces_with_its_restitution():
    R, e = 0.8, 0.5
    scene = parse_scene(f'''
id = "sphere_floor"
[parameters]
m = {{ dimension = "mass", domain = "positive", value = 1.0 }}
g = {{ dimension = "acceleration", domain = "positive", value = {G} }}
R = {{ dimension = "length", domain = "positive", value = {R} }}
e = {{ dimension = "dimensionless", domain = [0, 1], value = {e} }}
[coordinates]
r = {{ dimension = "length", domain = "positive" }}
theta = {{ dimension = "angle", domain = "real" }}
[energy]
kinetic = "m/2*(rdot^2 + r^2*thetadot^2)"
potential = "m*g*r*cos(theta)"
[[constraints]]
name = "surface"
f = "r - R"
kind = "unilateral"
[[constraints]]
name = "floor"
f = "r*cos(theta) + R"
kind = "unilateral"
restitution = "e"
[initial]
r = "R"
theta = 0.3
''', source="sphere_floor.toml")
    motion = simulate_scene(scene, {}, t_end=1.6)
    assert [(x.effect, x.constraint) for x in motion.events] == [("release", "surface"), ("bounce", "floor"),
                                                                ("bounce", "floor")]
    release, land, again = motion.events
    assert math.cos(release.state["theta"]) == pytest.approx(2 / 3 * math.cos(0.3), abs=1e-9)

    def cartesian(state):
        r, th, rdot, thdot = state["r"], state["theta"], state["rdot"], state["thetadot"]
        return (r * math.sin(th), r * math.cos(th), rdot * math.sin(th) + r * thdot * math.cos(th),
                rdot * math.cos(th) - r * thdot * math.sin(th))

    x0, y0, vx, vy = cartesian(release.state)
    fall = (vy + math.sqrt(vy * vy + 2 * G * (y0 + R))) / G
    assert land.t == pytest.approx(release.t + fall, abs=1e-10)
    x1, y1, vx1, vy1 = cartesian(land.state)
    assert (x1, y1, vx1) == pytest.approx((x0 + vx * fall, -R, vx), abs=1e-9)
    assert vy1 == pytest.approx(-e * (vy - G * fall), rel=1e-9)
    assert again.t == pytest.approx(land.t + 2 * vy1 / G, abs=1e-10)


def test_a_bob_dropped_inside_its_slack_string_falls_freely_until_the_string_jerks_taut():
    # From rest at (x0, 0) inside the circle: free fall to y = −√(l² − x0²), then the inelastic
    # jerk keeps only the velocity's component along the tangent (−y, x0)/l.
    l, x0 = 0.9, 0.5
    motion = simulate_scene(whirl("unilateral", 1.0), {}, t_end=1.0,
                            initial={"x": x0, "y": 0.0, "xdot": 0.0, "ydot": 0.0})
    assert [(e.effect, e.constraint) for e in motion.events] == [("contact", "string")]
    taut = motion.events[0]
    y = -math.sqrt(l * l - x0 * x0)
    fall = math.sqrt(-2 * y / G)
    tangential = -G * fall * x0 / l
    assert taut.t == pytest.approx(fall, abs=1e-12)
    assert taut.state["xdot"] == pytest.approx(tangential * -y / l, rel=1e-10)
    assert taut.state["ydot"] == pytest.approx(tangential * x0 / l, rel=1e-10)
    after = motion.t > taut.t
    np.testing.assert_allclose(np.hypot(motion.q[after, 0], motion.q[after, 1]), l, rtol=1e-10)


@pytest.mark.parametrize("alpha, k", [(0.5, 10.0), (1.0, 3.0), (0.2, 50.0)])
def test_a_block_lifts_off_an_incline_whose_acceleration_grows_when_it_reaches_g_cot_alpha(alpha, k):
    # The wedge moves by k t³/6 (acceleration A = k t); in its frame N = m g cos α − m A sin α,
    # whatever the block's sliding: it leaves at t = g cot α / k.
    scene = parse_scene(f'''
id = "wedge"
[parameters]
m = {{ dimension = "mass", domain = "positive", value = 1.0 }}
g = {{ dimension = "acceleration", domain = "positive", value = {G} }}
alpha = {{ dimension = "angle", domain = "real", value = {alpha} }}
k = {{ dimension = "length/time^3", domain = "positive", value = {k} }}
h = {{ dimension = "length", domain = "positive", value = 1.0 }}
[coordinates]
x = {{ dimension = "length" }}
y = {{ dimension = "length" }}
[energy]
kinetic = "m/2*(xdot^2 + ydot^2)"
potential = "m*g*y"
[[constraints]]
name = "incline"
f = "y*cos(alpha) - (x - k*t^3/6)*sin(alpha)"
kind = "unilateral"
[initial]
x = "h"
y = "h*tan(alpha)"
xdot = 0
ydot = 0
''', source="wedge.toml")
    motion = simulate_scene(scene, {}, t_end=3.0)
    assert [(e.effect, e.constraint) for e in motion.events] == [("release", "incline")]
    assert motion.events[0].t == pytest.approx(G / math.tan(alpha) / k, abs=1e-10)
