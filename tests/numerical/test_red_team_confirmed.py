"""The red-team scenes' values that are not a moment of the motion from [initial] (small-oscillation
frequencies, a steady orbit, the lowest point of a swing), each confirmed by an experiment of its own
with the numerical machinery, which differentiates the scene's T, V and f numerically and never sees
the engine's results (see test_special_values_confirmed.py). States are written in each scene's own
coordinates (Cartesian, for most of them)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq, minimize_scalar

from grader.simulate.constrained import Event, simulate
from grader.simulate.lagrangian_numeric import snapshot
from tests.numerical.test_special_values_confirmed import closed_form, engine
from tests.numerical.test_special_values_confirmed import frequency_from_crossings as _frequency


def test_bead_on_a_hoop_turned_about_its_rim_oscillates_at_omega():
    model, answers = engine("bead_hoop_turning_about_rim")
    R, w = model.values["R"], model.values["omega"]
    theta = 1e-4  # at rest on the hoop, at t = 0 (centre at (R, 0))
    q0 = [R + R * math.cos(theta), R * math.sin(theta)]
    qdot0 = [-R * w * math.sin(theta), R * w * (1 + math.cos(theta))]

    def angle(s):
        c, d = s.q[0] - R * math.cos(w * s.t), s.q[1] - R * math.sin(w * s.t)
        return math.remainder(math.atan2(d, c) - w * s.t, 2 * math.pi)

    expected = closed_form(model, answers, "small_oscillation_frequency")
    measured = _frequency(model, q0, qdot0, angle, 0.0, 2 * math.pi / expected)
    # (The rheonomic constraint's drift in the integration costs this one digit.)
    assert abs(measured - expected) < 1e-5 * expected


def test_bead_on_a_cycloid_oscillates_at_sqrt_g_over_4a():
    model, answers = engine("bead_on_cycloid")
    a = model.values["a"]
    phi = 1e-4
    q0 = [a * (phi + math.sin(phi)), a * (1 - math.cos(phi)), phi]
    expected = closed_form(model, answers, "small_oscillation_frequency")
    measured = _frequency(model, q0, [0.0, 0.0, 0.0], lambda s: s.q[2], 0.0, 2 * math.pi / expected)
    assert abs(measured - expected) < 1e-6 * expected


def test_bead_on_a_spun_hoop_oscillates_about_its_relative_equilibrium():
    model, answers = engine("bead_spinning_hoop_cartesian")
    a, w = model.values["a"], model.values["omega"]

    def state(theta):  # at rest on the hoop at t = 0, the hoop in the x-z plane
        return [a * math.sin(theta), 0.0, -a * math.cos(theta)], [0.0, a * w * math.sin(theta), 0.0]

    def angle(s):
        return math.atan2(s.q[0] * math.cos(w * s.t) + s.q[1] * math.sin(w * s.t), -s.q[2])

    def in_plane_acceleration(theta):  # θ̈ a = tangential acceleration, seen at t = 0
        s = snapshot(model.numeric, 0.0, *state(theta))
        return (s.qddot[0] + a * w ** 2 * math.sin(theta)) * math.cos(theta) + s.qddot[2] * math.sin(theta)

    equilibrium = brentq(in_plane_acceleration, 0.3, 1.5, xtol=1e-15)
    expected = closed_form(model, answers, "small_oscillation_frequency")
    measured = _frequency(model, *state(equilibrium + 1e-4), angle, equilibrium, 2 * math.pi / expected)
    assert abs(measured - expected) < 1e-6 * expected


def _paraboloid_state(model, r: float, phidot: float):
    c = model.values["c"]
    return [r, 0.0, r * r / (2 * c)], [0.0, r * phidot, 0.0]


def test_paraboloid_orbit_at_the_engines_rate_keeps_its_radius():
    model, answers = engine("particle_in_paraboloid")
    for radius in (0.2, 0.7):
        omega = closed_form(model, answers, "orbit_angular_velocity", r=radius)
        motion = simulate(model.numeric, *_paraboloid_state(model, radius, omega), 2.0,
                          sample_times=np.linspace(0, 2, 9))
        assert max(abs(math.hypot(s.q[0], s.q[1]) - radius) for s in motion.samples) < 1e-8 * radius


def test_paraboloid_radial_oscillations_about_the_orbit_of_the_starting_momentum():
    model, answers = engine("particle_in_paraboloid")
    h = model.values["r0"] ** 2 * model.values["Omega0"]

    def radial_acceleration(r):  # at rest radially, φ̇ = h/r², at φ = 0: r̈ = ẍ + r φ̇²
        s = snapshot(model.numeric, 0.0, *_paraboloid_state(model, r, h / r ** 2))
        return s.qddot[0] + r * (h / r ** 2) ** 2

    equilibrium = brentq(radial_acceleration, 0.05, 2.0, xtol=1e-15)
    r = equilibrium + 1e-5
    expected = closed_form(model, answers, "small_oscillation_frequency")
    measured = _frequency(model, *_paraboloid_state(model, r, h / r ** 2), lambda s: math.hypot(s.q[0], s.q[1]),
                          equilibrium, 2 * math.pi / expected)
    assert abs(measured - expected) < 1e-6 * expected


def test_block_on_a_pulley_and_spring_oscillates_and_turns_back_where_the_engine_says():
    model, answers = engine("pulley_spring_block")
    R, m, g, k = (model.values[n] for n in ("R", "m", "g", "k"))
    expected = closed_form(model, answers, "small_oscillation_frequency")
    # Released from rest with the spring unstretched: the block swings about m g/k, down to 2 m g/k.
    measured = _frequency(model, [0.0, 0.0, 0.0], [0.0, 0.0, 0.0], lambda s: s.q[0], m * g / k,
                          2 * math.pi / expected)
    assert abs(measured - expected) < 1e-6 * expected
    turn = Event("turn", lambda s: s.qdot[0], terminal=True)
    motion = simulate(model.numeric, [1e-9, 1e-9 / R, 1e-9], [1e-6, 1e-6 / R, 1e-6], 2 * math.pi / expected,
                      events=[turn])
    lowest = motion.first("turn").q[0]
    assert abs(lowest - closed_form(model, answers, "lowest_depth")) < 1e-6 * lowest


def test_half_cylinder_rocks_at_the_engines_frequency():
    model, answers = engine("rocking_half_cylinder")
    R = model.values["R"]
    theta = 1e-4
    expected = closed_form(model, answers, "small_oscillation_frequency")
    measured = _frequency(model, [-R * theta, R, theta], [0.0, 0.0, 0.0], lambda s: s.q[2], 0.0,
                          2 * math.pi / expected)
    assert abs(measured - expected) < 1e-6 * expected


def test_puck_seen_from_a_rotating_frame_oscillates_radially_at_the_engines_rate():
    model, answers = engine("rotating_frame_spring_orbit")
    k, l0, m, w = (model.values[n] for n in ("k", "l0", "m", "Omega"))
    r_e = k * l0 / (k - m * w ** 2)
    r = r_e + 1e-5  # the momentum m r_e² Ω of the scene's start, at rest radially
    expected = closed_form(model, answers, "small_oscillation_frequency")
    measured = _frequency(model, [r, 0.0], [0.0, r_e ** 2 * w / r ** 2 - w], lambda s: s.q[0], r_e,
                          2 * math.pi / expected)
    assert abs(measured - expected) < 1e-6 * expected


def test_steady_orbit_seen_from_a_rotating_frame_keeps_its_radius():
    model, answers = engine("rotating_frame_spring_orbit")
    for radius in (0.5, 0.9):
        psidot = closed_form(model, answers, "steady_relative_angular_velocity", r=radius)
        motion = simulate(model.numeric, [radius, 0.0], [0.0, psidot], 2.0, sample_times=np.linspace(0, 2, 9))
        assert max(abs(s.q[0] - radius) for s in motion.samples) < 1e-8 * radius


# -- the second red team (2026-11): relative equilibria, frequencies and a threshold ------------------

def _wire_state(model, s: float):
    """Coordinates (x, y, z) on the wire at t = 0 (in the x-z plane), at rest relative to it."""
    a, w = model.values["alpha"], model.values["omega"]
    return [s * math.sin(a), 0.0, s * math.cos(a)], [0.0, w * s * math.sin(a), 0.0]


def test_bead_on_a_turning_inclined_wire_rests_at_the_engines_distance():
    model, answers = engine("bead_inclined_rotating_wire")
    a, w = model.values["alpha"], model.values["omega"]
    s_eq = closed_form(model, answers, "equilibrium_distance")
    # At rest relative to the wire the bead only goes round: its acceleration is centripetal.
    s = snapshot(model.numeric, 0.0, *_wire_state(model, s_eq))
    rho = s_eq * math.sin(a)
    assert np.allclose(s.qddot, [-w ** 2 * rho, 0.0, 0.0], atol=1e-9 * w ** 2 * rho)
    # ... and stays (the equilibrium is unstable: 0.5 s multiplies a 1e-12 error by a few).
    motion = simulate(model.numeric, *_wire_state(model, s_eq), 0.5, sample_times=np.linspace(0, 0.5, 6))
    assert max(abs(np.linalg.norm(m.q) - s_eq) for m in motion.samples) < 1e-8 * s_eq
    # A little further out it climbs away, a little further in it slides down.
    for factor, sign in ((1.001, 1), (0.999, -1)):
        s = snapshot(model.numeric, 0.0, *_wire_state(model, factor * s_eq))
        assert sign * s.qddot[2] > 0


def _plane_state(model, s: float):
    """Coordinates (x, y, z) on the plane at t = 0 (u = 0), at rest relative to it."""
    a, w = model.values["alpha"], model.values["omega"]
    return [s * math.cos(a), 0.0, s * math.sin(a)], [0.0, w * s * math.cos(a), 0.0]


def test_particle_on_a_turning_inclined_plane_rests_at_the_engines_distance_and_normal_force():
    model, answers = engine("particle_rotating_inclined_plane")
    a, w = model.values["alpha"], model.values["omega"]
    s_eq = closed_form(model, answers, "equilibrium_distance")
    s = snapshot(model.numeric, 0.0, *_plane_state(model, s_eq))
    rho = s_eq * math.cos(a)
    assert np.allclose(s.qddot, [-w ** 2 * rho, 0.0, 0.0], atol=1e-9 * w ** 2 * rho)
    normal = closed_form(model, answers, "equilibrium_normal_force")
    assert abs(s.multipliers[0] - normal) < 1e-9 * normal
    motion = simulate(model.numeric, *_plane_state(model, s_eq), 0.5, sample_times=np.linspace(0, 0.5, 6))
    assert max(abs(np.linalg.norm(m.q) - s_eq) for m in motion.samples) < 1e-8 * s_eq


def test_pendulum_in_an_accelerating_car_oscillates_about_its_tilt_at_the_engines_rate():
    model, answers = engine("pendulum_accelerating_car")
    l, A = model.values["l"], model.values["A"]

    def state(theta):  # at t = 0 the car is at rest (it accelerates from rest), the bob at rest with it
        return [l * math.sin(theta), -l * math.cos(theta)], [0.0, 0.0]

    def relative_tangential(theta):  # l θ̈ = (ẍ − A) cos θ + ÿ sin θ, at rest relative to the car
        s = snapshot(model.numeric, 0.0, *state(theta))
        return (s.qddot[0] - A) * math.cos(theta) + s.qddot[1] * math.sin(theta)

    tilt = brentq(relative_tangential, -1.5, 0.0, xtol=1e-15)

    def angle(s):
        return math.atan2(s.q[0] - A * s.t ** 2 / 2, -s.q[1])

    expected = closed_form(model, answers, "small_oscillation_frequency")
    measured = _frequency(model, *state(tilt + 1e-4), angle, tilt, 2 * math.pi / expected)
    assert abs(measured - expected) < 1e-6 * expected


def test_trammel_with_a_spring_oscillates_about_the_upright_position_at_the_engines_rate():
    model, answers = engine("trammel_spring")
    l = model.values["l"]
    theta = 1e-4
    expected = closed_form(model, answers, "small_oscillation_frequency")
    measured = _frequency(model, [l * math.sin(theta), 0.0, 0.0, l * math.cos(theta)], [0.0] * 4,
                          lambda s: math.atan2(s.q[0], s.q[3]), 0.0, 2 * math.pi / expected)
    assert abs(measured - expected) < 1e-6 * expected


def test_a_yoyo_of_the_balancing_mass_leaves_its_counterweight_at_rest():
    from tests.numerical.test_special_values_confirmed import scene_of
    from grader.simulate.scene_numeric import SceneModel

    model, answers = engine("yoyo_counterweight")
    M = closed_form(model, answers, "balancing_mass")
    line = 'M = { dimension = "mass", domain = "positive", value = 2.0 }'
    for factor, sign in ((1.0, 0), (1.001, -1)):
        balanced = SceneModel(scene_of("yoyo_counterweight", ((line, line.replace("2.0", repr(M * factor))),)))
        start = balanced.initial_state()
        y2ddot = snapshot(balanced.numeric, 0.0, start.q, start.qdot).qddot[2]
        if sign == 0:
            assert abs(y2ddot) < 1e-9 * model.values["g"]
        else:
            assert y2ddot < 0  # a heavier yo-yo lifts the block


def test_a_face_pushed_at_the_engines_least_acceleration_holds_the_block():
    from tests.numerical.test_special_values_confirmed import scene_of
    from grader.simulate.scene_numeric import SceneModel

    model, answers = engine("block_on_accelerated_incline")
    a = model.values["alpha"]
    A = closed_form(model, answers, "least_acceleration")
    line = 'A = { dimension = "acceleration", domain = "positive", value = 8.0 }'
    for factor, sign in ((1.0, 0), (1.001, 1)):
        pushed = SceneModel(scene_of("block_on_accelerated_incline", ((line, line.replace("8.0", repr(A * factor))),)))
        start = pushed.initial_state()
        s = snapshot(pushed.numeric, 0.0, start.q, start.qdot)
        # Up the face relative to the wedge: (ẍ + A) cos α + ÿ sin α.
        up = (s.qddot[0] + A * factor) * math.cos(a) + s.qddot[1] * math.sin(a)
        if sign == 0:
            assert abs(up) < 1e-9 * model.values["g"]
        else:
            assert up > 0  # pushed harder, the block climbs


# -- the third red team (2026-11-27): frequencies, a relative equilibrium, and a release ---------------

def test_cylinder_in_a_free_carts_hollow_oscillates_at_the_engines_rate():
    model, answers = engine("cart_cylinder")
    R, a = model.values["R"], model.values["a"]
    b, theta = R - a, 1e-4
    # At rest in the hollow, the cart at rest: (X, ρ, θ, ψ) with (R − a) θ + a ψ = 0.
    q0 = [0.0, b, theta, -b * theta / a]
    expected = closed_form(model, answers, "small_oscillation_frequency")
    measured = _frequency(model, q0, [0.0] * 4, lambda s: s.q[2], 0.0, 2 * math.pi / expected)
    assert abs(measured - expected) < 1e-6 * expected


def test_hoop_with_an_offcentre_mass_rocks_at_the_engines_rate():
    model, answers = engine("offcentre_wheel")
    R, phi = model.values["R"], 1e-4
    expected = closed_form(model, answers, "small_oscillation_frequency")
    measured = _frequency(model, [R * phi, R, phi], [0.0] * 3, lambda s: s.q[2], 0.0, 2 * math.pi / expected)
    assert abs(measured - expected) < 1e-6 * expected


def test_rod_with_both_ends_on_a_circle_oscillates_at_the_engines_rate():
    model, answers = engine("rod_ends_on_circle")
    R, beta, phi = model.values["R"], model.values["beta"], 1e-4
    q0 = [R * math.sin(phi - beta), -R * math.cos(phi - beta), R * math.sin(phi + beta), -R * math.cos(phi + beta)]

    def midpoint_angle(s):
        return math.atan2(s.q[0] + s.q[2], -(s.q[1] + s.q[3]))

    expected = closed_form(model, answers, "small_oscillation_frequency")
    measured = _frequency(model, q0, [0.0] * 4, midpoint_angle, 0.0, 2 * math.pi / expected)
    assert abs(measured - expected) < 1e-6 * expected


def test_bead_at_the_engines_angle_stays_at_rest_in_a_hoop_rolling_down_an_incline():
    model, answers = engine("hoop_bead_incline")
    R = model.values["R"]
    theta = math.atan(closed_form(model, answers, "relative_equilibrium_tan"))
    # (s, φ, r, θ) at rest: the bead keeps its angle, the hoop accelerates at the engine's rate ...
    s = snapshot(model.numeric, 0.0, [0.0, 0.0, R, theta], [0.0] * 4)
    acceleration = closed_form(model, answers, "relative_equilibrium_acceleration")
    assert abs(s.qddot[3]) < 1e-9
    assert abs(s.qddot[0] - acceleration) < 1e-9 * acceleration
    # ... and the bead stays at that angle while the hoop rolls on.
    motion = simulate(model.numeric, [0.0, 0.0, R, theta], [0.0] * 4, 1.0, sample_times=np.linspace(0, 1, 6))
    assert max(abs(m.q[3] - theta) for m in motion.samples) < 1e-8
    # A little off it, the bead swings (θ̈ pulls it back towards the angle).
    for offset in (1e-3, -1e-3):
        s = snapshot(model.numeric, 0.0, [0.0, 0.0, R, theta + offset], [0.0] * 4)
        assert s.qddot[3] * offset < 0


def test_particle_leaves_a_hemisphere_where_the_engine_says_by_scipy_alone():
    """Independently of both the engine and grader.simulate: ẍ = 2λx/m, ÿ = −g + 2λy/m with λ from
    f̈ = 0 (2 λ R² = m (g y − v²)), integrated by solve_ivp from a nudge at the top until λ = 0."""
    from scipy.integrate import solve_ivp

    model, answers = engine("hemisphere_cartesian")
    g, R = model.values["g"], model.values["R"]

    def force(state):  # 2λ/m
        x, y, vx, vy = state
        return (g * y - vx * vx - vy * vy) / R ** 2

    def rhs(t, state):
        x, y, vx, vy = state
        k = force(state)
        return [vx, vy, k * x, -g + k * y]

    release = lambda t, state: force(state)  # noqa: E731
    release.terminal = True
    start = 1e-6
    x0, y0 = R * math.sin(start), R * math.cos(start)
    run = solve_ivp(rhs, (0.0, 20.0), [x0, y0, 0.0, 0.0], events=release, rtol=1e-12, atol=1e-14)
    x, y, vx, vy = run.y_events[0][0]
    assert abs(y - closed_form(model, answers, "leaving_height")) < 1e-7 * R
    assert abs(x - closed_form(model, answers, "leaving_distance")) < 1e-7 * R
    assert abs(math.hypot(vx, vy) - closed_form(model, answers, "leaving_speed")) < 1e-6 * math.sqrt(g * R)


def test_two_masses_on_a_rod_in_a_circle_oscillate_about_their_tilt_at_the_engines_rate():
    model, answers = engine("dumbbell_in_circle")
    R, beta = model.values["R"], model.values["beta"]
    tilt = closed_form(model, answers, "equilibrium_angle")

    def state(phi):
        return [R * math.sin(phi - beta), -R * math.cos(phi - beta),
                R * math.sin(phi + beta), -R * math.cos(phi + beta)], [0.0] * 4

    def midpoint_angle(s):
        return math.atan2(s.q[0] + s.q[2], -(s.q[1] + s.q[3]))

    # At the tilt, at rest, nothing moves; the rod's compression there is the engine's.
    s = snapshot(model.numeric, 0.0, *state(tilt))
    assert np.allclose(s.qddot, 0.0, atol=1e-9)
    expected = closed_form(model, answers, "small_oscillation_frequency")
    measured = _frequency(model, *state(tilt + 1e-4), midpoint_angle, tilt, 2 * math.pi / expected)
    assert abs(measured - expected) < 1e-6 * expected


# -- the fifth red team (2026-11-27): a block on a track cut in a free cart -------------------------

def _launched(model, v0: float, *events):
    """The block launched at v0 from the bottom of the cart's track, the cart at rest: (X, r, θ)."""
    R = model.values["R"]
    return simulate(model.numeric, [0.0, R, 0.0], [0.0, 0.0, v0 / R], 5.0, events=list(events))


def test_block_up_a_track_on_a_free_cart_climbs_to_the_engines_height_and_reaches_the_rim_from_its_least_speed():
    model, answers = engine("cart_quarter_circle")
    v0 = model.values["v0"]
    turn = Event("turn", lambda s: s.qdot[2], terminal=True)
    rim = Event("rim", lambda s: s.q[2] - math.pi / 2, terminal=True)
    top = _launched(model, v0, turn).first("turn")
    height = model.values["R"] - top.q[1] * math.cos(top.q[2])
    assert abs(height - closed_form(model, answers, "max_height")) < 1e-6 * height
    least = closed_form(model, answers, "least_launch_speed")
    for factor, reaches in ((1.001, True), (0.999, False)):
        motion = _launched(model, least * factor, rim, turn)
        assert (motion.first("rim") is not None) == reaches
    faster = 1.5 * least  # θ̇² at the rim is a function of the launch speed
    at_rim = _launched(model, faster, rim).first("rim")
    expected = closed_form(model, answers, "rim_angular_speed_squared", v0=faster)
    assert abs(at_rim.qdot[2] ** 2 - expected) < 1e-6 * expected


def test_ball_rolling_in_a_bowl_needs_no_more_friction_than_the_engines_least_coefficient():
    """|F|/N over a whole swing of the integrated motion peaks at the engine's value (at the release)."""
    model, answers = engine("sphere_in_bowl")
    R, a, theta0 = (model.values[n] for n in ("R", "a", "theta0"))
    b = R - a
    motion = simulate(model.numeric, [b, theta0, -b * theta0 / a], [0.0, 0.0, 0.0], 2.5,
                      sample_times=np.linspace(0.0, 2.5, 2001))
    ratios = [abs(s.multiplier("roll")) / abs(s.multiplier("contact")) for s in motion.samples]
    expected = closed_form(model, answers, "least_friction_coefficient")
    assert max(ratios) <= expected * (1 + 1e-6)
    assert abs(max(ratios) - expected) < 1e-6 * expected
    assert min(s.q[1] for s in motion.samples) < -0.99 * theta0  # a whole swing, out to the other side


def test_ball_rolling_in_a_bowl_oscillates_at_the_engines_rate():
    model, answers = engine("sphere_in_bowl")
    R, a = model.values["R"], model.values["a"]
    b, theta = R - a, 1e-4
    expected = closed_form(model, answers, "small_oscillation_frequency")
    measured = _frequency(model, [b, theta, -b * theta / a], [0.0, 0.0, 0.0], lambda s: s.q[1], 0.0,
                          2 * math.pi / expected)
    assert abs(measured - expected) < 1e-6 * expected


def test_pendulum_hung_from_a_block_sliding_down_an_incline_swings_about_the_normal_at_the_engines_rate():
    # Red team 12's scene: the block's s is no cyclic coordinate (gravity pulls it down the slope), but
    # the swing does not depend on it. Everything starts at rest; the rest state where the bob's
    # acceleration relative to the block has no component along its path is located numerically.
    model, answers = engine("pendulum_on_block_on_incline")
    l = model.values["l"]

    def state(phi):  # X, Y of the block (at the origin), x, y of the bob, all at rest
        return [0.0, 0.0, l * math.sin(phi), -l * math.cos(phi)], [0.0, 0.0, 0.0, 0.0]

    def relative_tangential(phi):  # l φ̈ = (ẍ − Ẍ) cos φ + (ÿ − Ÿ) sin φ
        a = snapshot(model.numeric, 0.0, *state(phi)).qddot
        return (a[2] - a[0]) * math.cos(phi) + (a[3] - a[1]) * math.sin(phi)

    alpha = model.values["alpha"]
    rest = brentq(relative_tangential, -alpha - 0.5, -alpha + 0.5, xtol=1e-15)
    assert rest == pytest.approx(-alpha, abs=1e-9)  # about the normal to the incline, as the scene says

    def angle(s):
        return math.atan2(s.q[2] - s.q[0], -(s.q[3] - s.q[1]))

    expected = closed_form(model, answers, "small_oscillation_frequency")
    measured = _frequency(model, *state(rest + 1e-4), angle, rest, 2 * math.pi / expected)
    assert abs(measured - expected) < 1e-6 * expected


# -- Red team 16: textbook scenes written independently of the engine -----------------------------------

def test_pendulum_whose_string_winds_round_a_cylinder_oscillates_at_the_engines_rate():
    # The bob at (x, y), the winding angle θ (no kinetic energy of its own): released at rest a little
    # off the vertical, the string leaving the cylinder at (R cos θ, R sin θ) with the free length l + Rθ.
    model, answers = engine("pendulum_winding_on_cylinder")
    R, l = model.values["R"], model.values["l"]
    theta = 1e-4
    q0 = [R * math.cos(theta) + (l + R * theta) * math.sin(theta),
          R * math.sin(theta) - (l + R * theta) * math.cos(theta), theta]
    expected = closed_form(model, answers, "small_oscillation_frequency")
    measured = _frequency(model, q0, [0.0, 0.0, 0.0], lambda s: s.q[2], 0.0, 2 * math.pi / expected)
    assert abs(measured - expected) < 1e-6 * expected


def test_bead_on_a_freely_turning_hoop_oscillates_about_the_bottom_with_the_releases_angular_momentum():
    # The scene's release (θ0, hoop at Ω0) fixes the angular momentum h = (I + m a² sin²θ0) Ω0 about the
    # vertical; the bead is started at rest on the hoop a little off the bottom with that momentum.
    model, answers = engine("bead_on_free_hoop")
    m, inertia, a = (model.values[n] for n in ("m", "I", "a"))
    h = (inertia + m * a ** 2 * math.sin(model.values["theta0"]) ** 2) * model.values["Omega0"]
    theta = 1e-4
    phidot = h / (inertia + m * a ** 2 * math.sin(theta) ** 2)
    q0 = [a * math.sin(theta), 0.0, -a * math.cos(theta), 0.0]
    qdot0 = [0.0, a * math.sin(theta) * phidot, 0.0, phidot]

    def angle(s):  # from the bottom, signed in the hoop's plane
        return math.atan2(s.q[0] * math.cos(s.q[3]) + s.q[1] * math.sin(s.q[3]), -s.q[2])

    expected = closed_form(model, answers, "small_oscillation_frequency")
    measured = _frequency(model, q0, qdot0, angle, 0.0, 2 * math.pi / expected)
    assert abs(measured - expected) < 1e-6 * expected


def _bowl_state(model, theta: float):
    a, l = model.values["a"], model.values["l"]
    return [a + (l - 2 * a * math.cos(theta)) * math.cos(theta), (l - 2 * a * math.cos(theta)) * math.sin(theta),
            theta], [0.0, 0.0, 0.0]


def test_rod_in_a_bowl_on_its_rim_rests_and_oscillates_where_the_engine_says():
    model, answers = engine("rod_in_bowl_on_rim")
    rest = brentq(lambda th: snapshot(model.numeric, 0.0, *_bowl_state(model, th)).qddot[2], 0.1, 1.1, xtol=1e-15)
    assert abs(math.cos(rest) - closed_form(model, answers, "equilibrium_cos")) < 1e-9
    expected = closed_form(model, answers, "small_oscillation_frequency")
    measured = _frequency(model, *_bowl_state(model, rest + 1e-4), lambda s: s.q[2], rest, 2 * math.pi / expected)
    assert abs(measured - expected) < 1e-6 * expected


def test_cylinder_in_a_freely_turning_cylinder_oscillates_at_the_engines_rate():
    model, answers = engine("cylinder_in_free_cylinder")
    R, r = model.values["R"], model.values["r"]
    phi = 1e-4  # rolling contact, everything at rest (no angular momentum about the axle, as released)
    expected = closed_form(model, answers, "small_oscillation_frequency")
    measured = _frequency(model, [R - r, phi, -(R - r) * phi / r, 0.0], [0.0, 0.0, 0.0, 0.0], lambda s: s.q[1],
                          0.0, 2 * math.pi / expected)
    assert abs(measured - expected) < 1e-6 * expected


@pytest.mark.parametrize("factor, sign", [(1.0, 0), (1.01, -1), (0.99, 1)])
def test_compound_atwood_with_the_engines_balancing_mass_leaves_m1_at_rest(factor, sign):
    from tests.numerical.test_special_values_confirmed import scene_of
    from grader.simulate.scene_numeric import SceneModel

    model, answers = engine("compound_atwood_massive_pulleys")
    m1 = factor * closed_form(model, answers, "balancing_mass")
    line = 'm1 = { dimension = "mass", domain = "positive", value = 3.0 }'
    balanced = SceneModel(scene_of("compound_atwood_massive_pulleys",
                                   ((line, line.replace("3.0", repr(m1))),)))
    acceleration = snapshot(balanced.numeric, 0.0, [0.0] * 6, [0.0] * 6).qddot[0]  # m1's, up
    if sign == 0:
        assert abs(acceleration) < 1e-12 * balanced.values["g"]
    else:  # heavier sinks, lighter rises: the balance is the threshold
        assert math.copysign(1.0, acceleration) == sign and abs(acceleration) > 1e-4


def test_hinged_rods_floor_force_is_least_where_the_engine_says_before_the_hinge_lands():
    model, answers = engine("hinged_rods_on_floor")
    l, theta0 = model.values["l"], model.values["theta0"]

    def rod(theta, side):  # x, y, θ of a rod's centre, the hinge at x = 0
        return [side * l / 2 * math.sin(theta), l / 2 * math.cos(theta), theta]

    landed = Event("landed", lambda s: s.q[1] + l / 2 * math.cos(s.q[2]), terminal=True)  # the hinge's height
    motion = simulate(model.numeric, rod(theta0, 1) + rod(theta0, -1), [0.0] * 6, 1.5, events=[landed],
                      sample_times=np.linspace(0.0, 1.5, 301))
    assert motion.first("landed") is not None
    samples = [s for s in motion.samples if s.t <= motion.first("landed").t]
    i = min(range(1, len(samples) - 1), key=lambda k: samples[k].multiplier("foot1"))  # not at either end
    before = samples[i - 1]

    def floor_force(t):  # refined between the neighbouring samples
        return simulate(model.numeric, before.q, before.qdot, t, t0=before.t, sample_times=[t]).samples[0].multiplier("foot1")

    least = minimize_scalar(floor_force, bounds=(before.t, samples[i + 1].t), method="bounded",
                            options={"xatol": 1e-10}).fun
    expected = closed_form(model, answers, "least_floor_force")
    assert abs(least - expected) < 1e-6 * expected
    assert min(s.multiplier("foot1") for s in samples) >= expected * (1 - 1e-9)
