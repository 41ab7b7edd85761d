"""Special values that are not a moment of the motion from [initial], confirmed numerically.

``test_problems_confirmed.py`` confirms a ``where`` answer at the first moment its condition holds
along the motion from ``[initial]``. Some special values define a *state* or a *parameter*
instead: a steady orbit (r̈ = 0 solved for φ̇), the frequency of small oscillations about an
equilibrium, a threshold on the launch speed, a value at a configuration the motion from the
scene's own ``[initial]`` does not reach. Each is confirmed here by an experiment of its own with
the numerical machinery (:mod:`grader.simulate`), which differentiates the scene's T, V and f
numerically and never sees the engine's results; only the closed form under test comes from the
engine.
"""

from __future__ import annotations

import functools
import math
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq, minimize_scalar

from grader.simulate.constrained import Event, multiplier_zero, simulate
from grader.simulate.lagrangian_numeric import snapshot
from grader.simulate.scene_numeric import SceneModel

SCENES = Path(__file__).resolve().parents[1] / "mechanics" / "scenes"


def scene_of(name: str, replace: tuple[tuple[str, str], ...] = ()):
    """A scene file, optionally with some text replaced (another parameter value)."""
    from grader.mechanics.scene import parse_scene

    text = (SCENES / f"{name}.toml").read_text(encoding="utf-8")
    for old, new in replace:
        assert old in text
        text = text.replace(old, new)
    return parse_scene(text, source=f"{name}.toml")


@functools.lru_cache(maxsize=None)
def engine(name: str):
    """The scene's numeric model and the engine's closed-form answers."""
    from grader.mechanics.lagrange import derive

    scene = scene_of(name)
    return SceneModel(scene), derive(scene).answers


def closed_form(model: SceneModel, answers, name: str, **state: float) -> float:
    return model.evaluate(answers[name], {**model.values, **state})


@pytest.mark.parametrize("radius", [0.6, 0.9])
def test_steady_orbit_angular_velocity_keeps_the_radius(radius):
    """Started at r with ṙ = 0 and the engine's φ̇(r), the puck's radial acceleration vanishes."""
    model, answers = engine("table_hole_orbit")
    l, g = model.values["l"], model.values["g"]
    omega = closed_form(model, answers, "steady_angular_velocity", r=radius)
    s = snapshot(model.numeric, 0.0, [radius, 0.0, l - radius], [0.0, omega, 0.0])
    assert abs(s.qddot[0]) < 1e-9 * g
    # ... and stays there: over two seconds the radius drifts by nothing measurable.
    motion = simulate(model.numeric, [radius, 0.0, l - radius], [0.0, omega, 0.0], 2.0,
                      sample_times=np.linspace(0, 2, 9))
    assert max(abs(s.q[0] - radius) for s in motion.samples) < 1e-8 * radius


def frequency_from_crossings(model, q0, qdot0, angle_of, equilibrium: float, period_guess: float) -> float:
    """Angular frequency of the motion from (q0, qdot0), from the crossings of angle_of(state) = equilibrium."""
    crossing = Event("crossing", lambda s: angle_of(s) - equilibrium, terminal=False)
    motion = simulate(model.numeric, q0, qdot0, 3.2 * period_guess, events=[crossing])
    times = [s.t for s in motion.events["crossing"]]
    assert len(times) >= 5, "fewer than two and a half oscillations"
    return 2 * math.pi / ((times[4] - times[0]) / 2)


def _measured_frequency(model, q_of, coordinate: int, equilibrium: float, epsilon: float, period_guess: float):
    """Angular frequency of the motion released at rest at equilibrium + epsilon, from its zero crossings."""
    q0, qdot0 = q_of(equilibrium + epsilon)
    return frequency_from_crossings(model, q0, qdot0, lambda s: s.q[coordinate], equilibrium, period_guess)


def test_small_oscillations_about_the_spinning_hoops_relative_equilibrium():
    model, answers = engine("bead_hoop_equilibrium")
    omega = model.values["omega"]

    def state(theta):  # coordinates (theta, phi); the drive fixes phi = omega t
        return [theta, 0.0], [0.0, omega]

    # The equilibrium located numerically: θ̈ = 0 at rest, away from the axis.
    equilibrium = brentq(lambda th: snapshot(model.numeric, 0.0, *state(th)).qddot[0], 0.3, 1.5, xtol=1e-15)
    expected = closed_form(model, answers, "small_oscillation_frequency")
    measured = _measured_frequency(model, state, 0, equilibrium, 1e-4, 2 * math.pi / expected)
    assert abs(measured - expected) < 1e-6 * expected


def test_small_oscillations_of_a_cylinder_rolling_inside_a_cylinder():
    model, answers = engine("cylinder_in_cylinder")
    R, r = model.values["R"], model.values["r"]

    def state(phi):  # coordinates (rho, phi, psi): in contact and rolling
        return [R - r, phi, -(R - r) * phi / r], [0.0, 0.0, 0.0]

    expected = closed_form(model, answers, "small_oscillation_frequency")
    measured = _measured_frequency(model, state, 1, 0.0, 1e-4, 2 * math.pi / expected)
    assert abs(measured - expected) < 1e-6 * expected


def _loop_run(v0: float):
    """Launch on the loop at v0 (a numeric model only): the first release and the first arrival at the top."""
    model = SceneModel(scene_of("loop_inside_track", (("value = 4.0 }", f"value = {v0!r} }}"),)))
    R = model.values["R"]
    top = Event("top", lambda s: s.q[1] - math.pi, terminal=True)
    return simulate(model.numeric, [R, 0.0], [0.0, v0 / R], 10.0,
                    events=[top, multiplier_zero("track", terminal=False)])


@pytest.mark.parametrize("factor, goes_round", [(1.0001, True), (0.9999, False)])
def test_least_launch_speed_is_the_threshold_for_going_round(factor, goes_round):
    model, answers = engine("loop_inside_track")
    motion = _loop_run(closed_form(model, answers, "least_launch_speed") * factor)
    reached = motion.first("top")
    assert reached is not None, "the block is carried (bilaterally) up to the top"
    # N(φ) = m (v0²/R − 2g + 3g cos φ) is least at the top, so the track holds the block all the
    # way round exactly when the numerically computed N there is still positive.
    assert (reached.multiplier("track") > 0) == goes_round


def test_normal_force_at_the_top_for_a_launch_that_gets_there():
    model, answers = engine("loop_inside_track")
    motion = _loop_run(6.0)
    top = motion.first("top")
    assert top is not None and motion.first("lambda_track = 0") is None
    expected = closed_form(model, answers, "top_normal_force", v0=6.0)
    assert abs(top.multiplier("track") - expected) < 1e-6 * abs(expected)


def _largest_multiplier_over_the_swing(model, constraint: str, state_at, low: float, high: float) -> float:
    """max over u in [low, high] of the numeric λ at the state the motion has there.

    The speed at u comes from the scene's own numeric T and V: T is quadratic in the velocity, so
    with the direction of motion fixed, u̇² = (E₀ − V(u)) / T(u, u̇ = 1).
    """
    numeric = model.numeric
    q_start, _ = state_at(high, 0.0)
    energy = float(numeric.potential(q_start, 0.0))

    def multiplier(u: float) -> float:
        q, _ = state_at(u, 0.0)
        _, unit = state_at(u, 1.0)
        kinetic_per_unit = float(numeric.kinetic(q, unit, 0.0))
        speed = math.sqrt(max(energy - float(numeric.potential(q, 0.0)), 0.0) / kinetic_per_unit)
        q, qdot = state_at(u, -speed)
        return snapshot(numeric, 0.0, q, qdot).multiplier(constraint)

    grid = np.linspace(low, high, 401)
    values = [multiplier(u) for u in grid]
    i = int(np.argmax(values))
    bounds = (grid[max(i - 1, 0)], grid[min(i + 1, len(grid) - 1)])
    if bounds[0] == bounds[1]:
        return values[i]
    best = minimize_scalar(lambda u: -multiplier(u), bounds=bounds, method="bounded",
                           options={"xatol": 1e-10})
    return max(-best.fun, values[i])


def test_largest_normal_force_on_a_cylinder_rolling_inside_a_cylinder():
    model, answers = engine("cylinder_in_cylinder")
    R, r, phi0 = model.values["R"], model.values["r"], model.values["phi0"]

    def state_at(phi, phidot):  # in contact and rolling
        return [R - r, phi, -(R - r) * phi / r], [0.0, phidot, -(R - r) * phidot / r]

    measured = _largest_multiplier_over_the_swing(model, "contact", state_at, -phi0, phi0)
    expected = closed_form(model, answers, "largest_normal_force")
    assert abs(measured - expected) < 1e-6 * expected


def test_largest_wall_force_on_a_sliding_ladder():
    """Released at θ₀, the ladder slides down to the floor; the wall force peaks on the way."""
    model, answers = engine("ladder_wall")
    l, theta0 = model.values["l"], model.values["theta0"]

    def state_at(theta, thetadot):  # coordinates (theta, xc, yc) on the wall and the floor
        return ([theta, l / 2 * math.cos(theta), l / 2 * math.sin(theta)],
                [thetadot, -l / 2 * math.sin(theta) * thetadot, l / 2 * math.cos(theta) * thetadot])

    measured = _largest_multiplier_over_the_swing(model, "wall", state_at, 1e-3, theta0)
    expected = closed_form(model, answers, "largest_wall_force")
    assert abs(measured - expected) < 1e-6 * expected


# -- the motion in time: values as functions of t, and the time a condition is first reached --------
def test_bead_on_a_rotating_rod_follows_the_closed_form_in_time_and_reaches_the_end_when_it_says():
    """r(t), the motor's torque λ(t) and the time to reach r = L, against the integrated motion."""
    model, answers = engine("bead_rotating_rod")
    omega, r0, L = (model.values[n] for n in ("omega", "r0", "L"))
    end = Event("end", lambda s: s.q[0] - L, terminal=True)
    times = np.linspace(0.0, 0.6, 7)
    motion = simulate(model.numeric, [r0, 0.0], [0.0, omega], 5.0, events=[end], sample_times=times)
    assert len(motion.samples) == len(times)
    for s in motion.samples:
        assert abs(s.q[0] - closed_form(model, answers, "radius_in_time", t=s.t)) < 1e-8 * L
        torque = closed_form(model, answers, "drive_torque_in_time", t=s.t)
        assert abs(s.multiplier("drive") - torque) < 1e-7 * max(1.0, abs(torque))
    reached = motion.first("end")
    assert reached is not None
    assert abs(reached.t - closed_form(model, answers, "time_to_end")) < 1e-8
    assert abs(reached.qdot[0] - closed_form(model, answers, "speed_at_end")) < 1e-7 * omega * L


def test_extremes_over_a_driven_motion_are_those_of_the_integrated_motion_over_two_periods():
    """A cylinder rolling on a plank driven as A sin Ωt: the largest friction, least velocity and
    largest spin along the integrated motion (sampled over two periods) are the engine's."""
    model, answers = engine("cylinder_on_oscillating_plank")
    omega, A, R = model.values["Omega"], model.values["A"], model.values["R"]
    times = np.linspace(0.0, 4 * math.pi / omega, 2001)
    # At rest at x = 0 on the plank moving at AΩ: rolling, ẋ + R φ̇ = AΩ cos 0.
    motion = simulate(model.numeric, [0.0, 0.0], [0.0, A * omega / R], float(times[-1]), sample_times=times)
    assert len(motion.samples) == len(times)
    friction = max(s.multiplier("roll") for s in motion.samples)
    velocity = min(s.qdot[0] for s in motion.samples)
    spin = max(s.qdot[1] for s in motion.samples)
    # Sampled every 1/1000 of a period: an extreme is missed by at most (π/1000)²/2 of its size.
    for measured, name in ((friction, "largest_friction"), (velocity, "least_velocity"), (spin, "largest_spin")):
        expected = closed_form(model, answers, name)
        assert abs(measured - expected) < 1e-5 * abs(expected), name


def test_a_block_slides_the_distance_d_down_a_smooth_incline_in_the_time_the_engine_gives():
    model, answers = engine("block_incline_time")
    alpha, d = model.values["alpha"], model.values["d"]
    # s is the distance along the incline: x = s cos α, y = −s sin α.
    slid = Event("slid", lambda s: math.hypot(s.q[0], s.q[1]) - d, terminal=True)
    motion = simulate(model.numeric, [0.0, 0.0], [0.0, 0.0], 10.0, events=[slid], sample_times=[0.2, 0.4])
    for s in motion.samples:
        assert abs(s.q[0] / math.cos(alpha) - closed_form(model, answers, "distance_in_time", t=s.t)) < 1e-9
    reached = motion.first("slid")
    assert reached is not None
    assert abs(reached.t - closed_form(model, answers, "time_to_slide")) < 1e-8


# -- small oscillations with cyclic coordinates, and thresholds on a parameter ---------------------
def _frequency_from_crossings(model, q0, qdot0, offset, period_guess: float) -> float:
    """Angular frequency from the crossings of ``offset(snapshot) = 0`` (an equilibrium), released at q0."""
    crossing = Event("crossing", offset, terminal=False)
    motion = simulate(model.numeric, q0, qdot0, 3.2 * period_guess, events=[crossing])
    times = [s.t for s in motion.events["crossing"]]
    assert len(times) >= 5, "fewer than two and a half oscillations"
    return 2 * math.pi / ((times[4] - times[0]) / 2)


def test_small_oscillations_of_a_pendulum_on_a_freely_sliding_cart():
    """Released at rest at θ = 10⁻⁴, the bob crosses below the cart (x = X) at the engine's rate."""
    model, answers = engine("pendulum_sliding_support")
    l = model.values["l"]
    theta = 1e-4  # coordinates (X, x, y); the total momentum is zero and stays so
    q0, qdot0 = [0.0, l * math.sin(theta), -l * math.cos(theta)], [0.0, 0.0, 0.0]
    expected = closed_form(model, answers, "small_oscillation_frequency")
    measured = _frequency_from_crossings(model, q0, qdot0, lambda s: s.q[1] - s.q[0], 2 * math.pi / expected)
    assert abs(measured - expected) < 1e-6 * expected


def test_a_nudged_conical_pendulum_nods_about_its_cone_at_the_engines_rate():
    """θ₀ + 10⁻⁴ with the steady motion's angular momentum: θ oscillates about θ₀."""
    model, answers = engine("conical_pendulum")
    g, l, theta0 = (model.values[n] for n in ("g", "l", "theta0"))
    momentum = math.sin(theta0) ** 2 * math.sqrt(g / (l * math.cos(theta0)))  # per m l²
    theta = theta0 + 1e-4  # coordinates (r, theta, phi)
    q0, qdot0 = [l, theta, 0.0], [0.0, 0.0, momentum / math.sin(theta) ** 2]
    expected = closed_form(model, answers, "small_oscillation_frequency")
    measured = _frequency_from_crossings(model, q0, qdot0, lambda s: s.q[1] - theta0, 2 * math.pi / expected)
    assert abs(measured - expected) < 1e-6 * expected


def test_small_oscillations_of_a_bead_about_the_bottom_of_a_spinning_parabola():
    model, answers = engine("bead_rotating_parabola")
    a, omega = model.values["a"], model.values["omega"]

    def state(r):  # coordinates (r, phi, z) on the wire, turning with it
        return [r, 0.0, a * r ** 2], [0.0, omega, 0.0]

    expected = closed_form(model, answers, "small_oscillation_frequency")
    measured = _measured_frequency(model, state, 0, 0.0, 1e-4, 2 * math.pi / expected)
    assert abs(measured - expected) < 1e-6 * expected


@pytest.mark.parametrize("factor, stable", [(0.9999, True), (1.0001, False)])
def test_the_bottom_of_the_spinning_parabola_is_stable_only_below_the_critical_rate(factor, stable):
    """Just below ω_c the bead at rest off the axis is pulled back to it, just above it is flung out."""
    _, answers = engine("bead_rotating_parabola")
    reference = SceneModel(scene_of("bead_rotating_parabola"))
    omega = closed_form(reference, answers, "critical_angular_velocity") * factor
    model = SceneModel(scene_of("bead_rotating_parabola", (("value = 4.0 }", f"value = {omega!r} }}"),)))
    a, r = model.values["a"], 0.05
    s = snapshot(model.numeric, 0.0, [r, 0.0, a * r ** 2], [0.0, omega, 0.0])
    assert (s.qddot[0] < 0) == stable


def _turntable_state(model, r: float):
    """On the slot at t = 0 (along x), at rest relative to the table."""
    return [r, 0.0], [0.0, model.values["omega"] * r]


def test_small_oscillations_in_a_turntable_slot_about_the_relative_equilibrium():
    model, answers = engine("turntable_slot_spring")
    equilibrium = closed_form(model, answers, "equilibrium_radius")
    expected = closed_form(model, answers, "small_oscillation_frequency")
    q0, qdot0 = _turntable_state(model, equilibrium + 1e-5)
    measured = _frequency_from_crossings(model, q0, qdot0, lambda s: math.hypot(s.q[0], s.q[1]) - equilibrium,
                                         2 * math.pi / expected)
    assert abs(measured - expected) < 1e-6 * expected


@pytest.mark.parametrize("factor, restoring", [(0.9999, True), (1.0001, False)])
def test_the_spring_holds_the_particle_in_the_slot_only_below_the_critical_rate(factor, restoring):
    """d r̈/dr at rest in the slot (measured numerically) is negative below ω_c and positive above."""
    _, answers = engine("turntable_slot_spring")
    reference = SceneModel(scene_of("turntable_slot_spring"))
    omega = closed_form(reference, answers, "critical_angular_velocity") * factor
    model = SceneModel(scene_of("turntable_slot_spring", (("value = 5.0 }", f"value = {omega!r} }}"),)))

    def rddot(r):
        return model.quantities(snapshot(model.numeric, 0.0, *_turntable_state(model, r)))["rddot"]

    assert ((rddot(0.4) - rddot(0.3)) < 0) == restoring


@pytest.mark.parametrize("factor", [1.0, 1.001])
def test_the_balancing_mass_of_a_double_atwood_machine_stays_at_rest(factor):
    _, answers = engine("double_atwood")
    reference = SceneModel(scene_of("double_atwood"))
    m1 = closed_form(reference, answers, "balancing_mass") * factor
    model = SceneModel(scene_of("double_atwood", (("value = 3.0 }", f"value = {m1!r} }}"),)))
    start = model.initial_state()
    y1ddot = snapshot(model.numeric, 0.0, start.q, start.qdot).qddot[0]
    if factor == 1.0:
        assert abs(y1ddot) < 1e-9 * model.values["g"]
    else:
        assert y1ddot > 0  # a heavier m1 goes down


@pytest.mark.parametrize("offset", [0.0, 0.01])
def test_a_spool_pulled_at_the_critical_angle_does_not_roll(offset):
    _, answers = engine("spool_pulled_at_angle")
    reference = SceneModel(scene_of("spool_pulled_at_angle"))
    beta = math.acos(closed_form(reference, answers, "critical_cos")) - offset
    model = SceneModel(scene_of("spool_pulled_at_angle", (("[0, 1.5], value = 0.4 }", f"[0, 1.5], value = {beta!r} }}"),)))
    start = model.initial_state()
    xddot = snapshot(model.numeric, 0.0, start.q, start.qdot).qddot[0]
    if offset == 0.0:
        assert abs(xddot) < 1e-9
    else:
        assert xddot > 0  # pulled more horizontally, the spool rolls towards the pull


def _governor_state(model, theta: float):
    """Coordinates (theta, phi, z): the sleeve on its arms, at rest relative to the shaft."""
    return [theta, 0.0, 2 * model.values["l"] * math.cos(theta)], [0.0, model.values["omega"], 0.0]


def test_the_governors_relative_equilibrium_is_where_it_stays_at_rest():
    model, answers = engine("watt_governor")
    equilibrium = brentq(lambda th: snapshot(model.numeric, 0.0, *_governor_state(model, th)).qddot[0],
                         0.05, 1.5, xtol=1e-15)
    assert abs(closed_form(model, answers, "equilibrium_cos") - math.cos(equilibrium)) < 1e-9


def test_small_oscillations_of_a_watt_governor_about_its_relative_equilibrium():
    model, answers = engine("watt_governor")
    # The equilibrium located numerically: thetaddot = 0 at rest, off the shaft.
    equilibrium = brentq(lambda th: snapshot(model.numeric, 0.0, *_governor_state(model, th)).qddot[0],
                         0.05, 1.5, xtol=1e-15)
    expected = closed_form(model, answers, "small_oscillation_frequency")
    measured = _measured_frequency(model, lambda th: _governor_state(model, th), 0, equilibrium, 1e-4,
                                   2 * math.pi / expected)
    assert abs(measured - expected) < 1e-6 * expected


@pytest.mark.parametrize("factor, lifts", [(0.9999, False), (1.0001, True)])
def test_the_governors_balls_lift_off_the_shaft_only_above_the_least_rate(factor, lifts):
    _, answers = engine("watt_governor")
    reference = SceneModel(scene_of("watt_governor"))
    omega = closed_form(reference, answers, "least_angular_velocity") * factor
    model = SceneModel(scene_of("watt_governor", (("value = 12.0 }", f"value = {omega!r} }}"),)))
    thetaddot = snapshot(model.numeric, 0.0, *_governor_state(model, 0.01)).qddot[0]
    assert (thetaddot > 0) == lifts


def _stationary_points(model, q0, qdot0, t_end: float, rates: dict) -> dict:
    """The snapshots where each named rate crosses zero along the integrated motion (located by the
    integrator on its dense output, to a few ulps in t), with the start and the end: an extreme of a
    quantity over the motion is at one of them, found exactly rather than between two samples."""
    events = [Event(name, rate, terminal=False) for name, rate in rates.items()]
    motion = simulate(model.numeric, q0, qdot0, t_end, sample_times=[0.0], events=events)
    return motion, {name: motion.samples + motion.events[name] + (motion.end,) for name in rates}


def test_extremes_of_a_spherical_pendulum_swinging_through_the_pole_are_those_of_the_integrated_swing():
    """Released at rest at θ₀ (θ on [0, π] from the downward vertical), the bob swings through the
    lowest point, the pole of θ, and up the other side: its largest θ̇ (the speed at the bottom over l,
    reached with θ rising again) and its largest and least ż along a whole swing are the engine's."""
    model, answers = engine("spherical_pendulum_through_the_pole")
    l, theta0 = model.values["l"], model.values["theta0"]
    start = [l * math.sin(theta0), 0.0, -l * math.cos(theta0)]
    # More than a period (about 2 s); the speed is stationary where v·a = 0, ż where z̈ = 0.
    motion, at = _stationary_points(model, start, [0.0, 0.0, 0.0], 3.0, {
        "speed": lambda s: float(np.dot(s.qdot, s.qddot)), "rise": lambda s: float(s.qddot[2])})
    assert min(motion.q[:, 0]) < -0.9 * start[0]  # it did swing through to the other side
    assert len(motion.events["speed"]) >= 2 and len(motion.events["rise"]) >= 2
    speed = max(float(np.linalg.norm(s.qdot)) for s in at["speed"])
    rise = [float(s.qdot[2]) for s in at["rise"]]
    for measured, name in ((speed / l, "thetadot_max"), (max(rise), "rise_rate_max"), (min(rise), "rise_rate_min")):
        expected = closed_form(model, answers, name)
        assert abs(measured - expected) < 1e-8 * abs(expected), name


def test_extremes_of_an_elastic_pendulum_released_hanging_straight_down_are_those_of_the_integrated_bounce():
    """Released at rest at θ = 0 with the spring at r0: θ stays 0 and r bounces; its largest length and
    least tension over more than a period of the integrated motion are the engine's."""
    model, answers = engine("elastic_pendulum_hanging")
    m, k, r0 = model.values["m"], model.values["k"], model.values["r0"]
    l0 = model.values["l0"]
    period = 2 * math.pi * math.sqrt(m / k)
    # r is stationary where ṙ = 0 (at the release and at each turn of the bounce).
    motion, at = _stationary_points(model, [r0, 0.0], [0.0, 0.0], 1.5 * period,
                                    {"turn": lambda s: float(s.qdot[0])})
    assert float(np.max(np.abs(motion.q[:, 1]))) < 1e-9  # it stays on θ = 0
    assert len(motion.events["turn"]) >= 1
    lengths = [float(s.q[0]) for s in at["turn"]]
    assert abs(max(lengths) - closed_form(model, answers, "r_max")) < 1e-9
    assert abs(k * (min(lengths) - l0) - closed_form(model, answers, "tension_min")) < 1e-9 * k


def test_a_nudged_orbit_on_a_cone_oscillates_at_the_engines_rate():
    """With the angular momentum [initial] gives, the circular orbit is where the radial acceleration
    vanishes (found numerically); released 10⁻⁴ beyond it, s oscillates about it at the engine's ω."""
    model, answers = engine("cone_orbit_inverse_attraction")
    m, alpha, s0, om = (model.values[n] for n in ("m", "alpha", "s0", "Om"))
    momentum = m * s0 ** 2 * math.sin(alpha) ** 2 * om

    def state(s):  # coordinates (x, y, z) at φ = 0 on the cone, φ̇ from the momentum
        phidot = momentum / (m * s ** 2 * math.sin(alpha) ** 2)
        return [s * math.sin(alpha), 0.0, s * math.cos(alpha)], [0.0, s * math.sin(alpha) * phidot, 0.0]

    # At φ = 0, z̈ = s̈ cos α: the orbit is where it vanishes.
    orbit = brentq(lambda s: snapshot(model.numeric, 0.0, *state(s)).qddot[2], 0.05, 2.0, xtol=1e-15)
    expected = closed_form(model, answers, "small_oscillation_frequency")
    q0, qdot0 = state(orbit + 1e-4)
    measured = _frequency_from_crossings(
        model, q0, qdot0,
        lambda s: math.sqrt(s.q[0] ** 2 + s.q[1] ** 2 + s.q[2] ** 2) - orbit, 2 * math.pi / expected)
    assert abs(measured - expected) < 1e-6 * expected
