"""Red team 2 of the simulation's effects, on scenes in tests/simulate/scenes/ written for it: each
effect happens where its textbook closed form puts it, each regime keeps what it must keep, and an
effect the scene does not declare never happens (the same geometry with a bilateral constraint).

Closed forms (each derived by hand in the test that uses it):
- impacts on bodies that rest against others: the blow is passed on contact by contact (Newton's
  cradle: the last ball leaves at v; a small ball on a big one dropped on the floor leaves at
  v (3M − m)/(M + m)), and a contact that could only be kept by pulling lets go (the string of an
  Atwood machine whose mass is struck upwards goes slack);
- block on a platform on a spring: it leaves where the spring has its natural length;
- particle on a cylinder accelerating sideways at a: it leaves where cos ψ = (2/3) g/√(g² + a²),
  ψ from the effective upward direction (a, g);
- bob on a string in polar coordinates: slack where cos θ = (2gl − v₀²)/(3gl), a parabola inside
  the circle, then the jerk keeps the tangential velocity only;
- yo-yo struck upwards: taut again after 2v/g, then ẏ = v m b²/(m b² + I).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from grader.mechanics.scene import load_scene, parse_scene
from grader.simulate.trajectory import simulate_scene

SCENES = Path(__file__).resolve().parent / "scenes"
G = 9.81


def scene(name: str, kind: str | None = None):
    """A scene of tests/simulate/scenes, with its unilateral constraints made ``kind``."""
    text = (SCENES / f"{name}.toml").read_text()
    if kind is not None:
        text = text.replace('kind = "unilateral"', f'kind = "{kind}"')
    return parse_scene(text, source=f"{name}.toml")


def effects(motion) -> list[tuple[str, str]]:
    return [(e.effect, e.constraint) for e in motion.events]


def between(motion, start: float, stop: float) -> np.ndarray:
    return (motion.t > start) & (motion.t < stop)


# -- impacts on bodies resting against others ------------------------------------------------------

@pytest.mark.parametrize("mb, e", [(1.0, 1.0), (1.0, 0.0), (0.5, 0.5)])
def test_a_struck_atwood_mass_lets_its_string_go_slack_and_the_string_jerks_taut_later(mb, e):
    # Before: the impact was solved with the string held rigid, so the string pushed mass 2 down
    # (ẏ₂ = +2.6 m/s for e = 1) and the ball bounced off both masses at once.
    m, L, h, d, u = 1.0, 3.0, 1.5, 0.5, 5.0
    motion = simulate_scene(load_scene(SCENES / "atwood_struck_from_below.toml"), {"mb": mb, "e": e},
                            t_end=0.6, samples=601)
    t_hit = (u - math.sqrt(u * u - 2 * G * d)) / G
    u_hit = math.sqrt(u * u - 2 * G * d)
    w = (1 + e) * mb * u_hit / (mb + m)           # mass 1 alone takes the blow: the string is slack
    ball = (mb - e * m) * u_hit / (mb + m)
    expected = ([("contact", "hit")] if e == 0 else [("bounce", "hit")]) + [("release", "string"),
                                                                            ("contact", "string")]
    if e == 0:
        expected.append(("release", "hit"))  # the jerk pulls mass 1 up off the ball
    assert effects(motion) == expected
    hit, slack, taut = motion.events[:3]
    assert hit.t == slack.t == pytest.approx(t_hit, abs=1e-12)
    assert (hit.state["y1dot"], hit.state["y2dot"], hit.state["ybdot"]) == pytest.approx((-w, 0.0, -ball), abs=1e-9)
    # Slack: both masses fall freely, L − y1 − y2 = w τ − g τ², taut again at τ = w/g, when mass 1
    # is at rest and mass 2 falls at w; the inelastic jerk leaves ∓w/2 (equal masses).
    assert taut.t == pytest.approx(t_hit + w / G, abs=1e-10)
    assert (taut.state["y1dot"], taut.state["y2dot"]) == pytest.approx((-w / 2, w / 2), abs=1e-9)
    flight = between(motion, slack.t, taut.t)
    tau = motion.t[flight] - t_hit
    np.testing.assert_allclose(motion.q[flight, 1], L - h + G * tau ** 2 / 2, atol=1e-10)
    assert not motion.active[flight, 0].any()
    energy = (m / 2 * (motion.qdot[:, 0] ** 2 + motion.qdot[:, 1] ** 2) + mb / 2 * motion.qdot[:, 2] ** 2
              - G * (m * motion.q[:, 0] + m * motion.q[:, 1] + mb * motion.q[:, 2]))
    assert np.ptp(energy[flight]) < 1e-9
    after = motion.t > taut.t
    assert energy[flight][0] - energy[after][0] == pytest.approx(m * w * w / 4, rel=1e-8)
    assert np.all(motion.multipliers[motion.active[:, 0], 0] >= 0)


@pytest.mark.parametrize("e, m3, final", [
    (1.0, 0.2, (0.0, 0.0, 1.0)),            # the blow passes through: the last ball leaves at v
    (1.0, 0.4, (-1 / 3, 0.0, 2 / 3)),       # ball 2 bounces back off the heavy ball 3 and hits ball 1
    (0.0, 0.2, (1 / 3, 1 / 3, 1 / 3)),      # inelastic: all three together
    (0.0, 0.4, (1 / 4, 1 / 4, 1 / 4)),
])
def test_newtons_cradle_passes_the_blow_on_contact_by_contact(e, m3, final):
    # Before: the resting contact between balls 2 and 3 was held rigid whatever its restitution,
    # so with e = 1 ball 1 bounced back at −v/3 off a pair moving at 2v/3.
    v, m = 1.2, 0.2
    motion = simulate_scene(load_scene(SCENES / "newtons_cradle.toml"), {"e": e, "m3": m3}, t_end=0.5, samples=51)
    hit = motion.events[0]
    assert hit.t == pytest.approx((0.3 - 0.05) / v, abs=1e-12)
    assert {x.t for x in motion.events} == {hit.t}
    assert [hit.state[k] for k in ("x1dot", "x2dot", "x3dot")] == pytest.approx([v * x for x in final], abs=1e-9)
    after = motion.qdot[motion.t > hit.t]
    assert m * (after[:, 0] + after[:, 1]) + m3 * after[:, 2] == pytest.approx(m * v, rel=1e-12)
    kinetic = m / 2 * (after[:, 0] ** 2 + after[:, 1] ** 2) + m3 / 2 * after[:, 2] ** 2
    if e == 1.0:
        np.testing.assert_allclose(kinetic, m / 2 * v * v, rtol=1e-9)
    gaps = np.diff(motion.q, axis=1) - 0.05
    assert gaps.min() > -1e-12


@pytest.mark.parametrize("M", [0.15, 0.5, 0.05])
def test_a_small_ball_dropped_on_a_big_one_leaves_at_v_times_3M_minus_m_over_M_plus_m(M):
    # Before: the small ball resting on the big one was held to it at the floor's impact, and both
    # rebounded at v together (the small ball rose to h, not to 4h for M = 3m).
    m, h = 0.05, 1.0
    motion = simulate_scene(load_scene(SCENES / "stacked_balls_drop.toml"), {"M": M}, t_end=0.8, samples=801)
    v = math.sqrt(2 * G * h)
    bounce = motion.events[0]
    assert bounce.t == pytest.approx(math.sqrt(2 * h / G), abs=1e-10)
    big, small = v * (M - 3 * m) / (M + m), v * (3 * M - m) / (M + m)
    if big < 0:  # equal masses: the big ball goes back into the floor and rebounds at v again
        big = -big
    assert (bounce.state["y1dot"], bounce.state["y2dot"]) == pytest.approx((big, small), abs=1e-9)
    energy = M / 2 * motion.qdot[:, 0] ** 2 + m / 2 * motion.qdot[:, 1] ** 2 + G * (M * motion.q[:, 0] + m * motion.q[:, 1])
    assert np.ptp(energy) < 1e-8 * M * G * h
    assert motion.q[:, 0].min() > -1e-12 and (motion.q[:, 1] - motion.q[:, 0]).min() > 0.24 - 1e-12


# -- a block thrown off a platform on a spring ------------------------------------------------------

def platform_flight(m, M, k, A):
    """Hand-derived: release time and speed, then the first landing of the free block on the
    platform oscillating alone (SHM about −Mg/k at √(k/M)), and the common velocity after it."""
    w = math.sqrt(k / (M + m))
    t1 = math.acos(-G / (A * w * w)) / w
    v1 = A * w * math.sin(w * t1)
    wp, c = math.sqrt(k / M), M * G / k

    def gap(tau):
        return v1 * tau - G * tau ** 2 / 2 - (-c + c * math.cos(wp * tau) + v1 / wp * math.sin(wp * tau))

    taus = np.linspace(1e-3, 2.0, 2001)
    j = next(j for j in range(1, len(taus)) if gap(taus[j]) < 0)
    tau = brentq(gap, taus[j - 1], taus[j], xtol=1e-15)
    block, plate = v1 - G * tau, -c * wp * math.sin(wp * tau) + v1 * math.cos(wp * tau)
    return t1, v1, t1 + tau, (M * plate + m * block) / (M + m), (block - plate)


@pytest.mark.parametrize("A", [0.15, 0.12])
def test_a_block_leaves_a_platform_on_a_spring_where_the_spring_has_its_natural_length(A):
    m, M, k = 0.5, 1.5, 200.0
    motion = simulate_scene(load_scene(SCENES / "block_on_spring_platform.toml"), {"A": A}, t_end=0.8, samples=801)
    t1, v1, t2, common, approach = platform_flight(m, M, k, A)
    assert effects(motion)[:2] == [("release", "platform"), ("contact", "platform")]
    release, landing = motion.events[:2]
    assert release.t == pytest.approx(t1, abs=1e-10)
    assert (release.state["y"], release.state["ydot"], release.state["zdot"]) == pytest.approx((0.0, v1, v1), abs=1e-9)
    assert landing.t == pytest.approx(t2, abs=1e-9)
    assert (landing.state["ydot"], landing.state["zdot"]) == pytest.approx((common, common), abs=1e-8)
    energy = (M / 2 * motion.qdot[:, 0] ** 2 + m / 2 * motion.qdot[:, 1] ** 2 + k / 2 * motion.q[:, 0] ** 2
              + G * (M * motion.q[:, 0] + m * motion.q[:, 1]))
    flight, riding = between(motion, release.t, landing.t), motion.t < release.t
    assert np.ptp(energy[riding]) < 1e-9 and np.ptp(energy[flight]) < 1e-9
    # the inelastic landing loses (1/2) μ (relative speed)², μ = m M/(m + M)
    lost = energy[flight][-1] - energy[motion.t > landing.t][0]
    assert lost == pytest.approx(m * M / (m + M) * approach ** 2 / 2, rel=1e-7)
    assert (motion.q[:, 1] - motion.q[:, 0]).min() > -1e-12
    assert np.all(motion.multipliers[motion.active[:, 0], 0] >= 0)


def test_a_block_on_a_platform_pushed_down_less_than_its_threshold_or_glued_to_it_never_leaves():
    m, M, k = 0.5, 1.5, 200.0
    below = simulate_scene(load_scene(SCENES / "block_on_spring_platform.toml"), {"A": 0.9 * (M + m) * G / k},
                           t_end=1.0)
    glued = simulate_scene(scene("block_on_spring_platform", "bilateral"), {}, t_end=1.0)
    assert below.events == [] and glued.events == []
    assert below.active.all() and below.multipliers[:, 0].min() > 0
    # glued, the platform pulls the block down on the way up: N = m (g + ÿ) < 0 above y = 0
    np.testing.assert_allclose(glued.multipliers[:, 0], m * (G + 0.15 * k / (M + m) * np.cos(math.sqrt(k / (M + m)) * glued.t)),
                               rtol=1e-8, atol=1e-8)
    assert glued.multipliers[:, 0].min() < -1


# -- a particle on a cylinder that accelerates sideways --------------------------------------------

@pytest.mark.parametrize("a", [3.0, -3.0, 12.0])
def test_a_particle_leaves_a_sideways_accelerating_cylinder_where_the_effective_gravity_says(a):
    R = 0.5
    motion = simulate_scene(load_scene(SCENES / "cylinder_accelerating.toml"), {"a": a}, t_end=1.0, samples=401)
    assert effects(motion) == [("release", "surface")]
    release = motion.events[0]
    ge = math.hypot(G, a)
    x, y = release.state["x"] - a * release.t ** 2 / 2, release.state["y"]
    assert (a * x + G * y) / (ge * R) == pytest.approx(2 / 3 * G / ge, abs=1e-9)
    assert math.copysign(1, x) == -math.copysign(1, a)  # it slides off backwards
    # An independent integration in the cylinder's frame: R ψ̈ = g_e sin ψ, ψ from (a, g)/g_e, from
    # ψ₀ = atan(a/g) (towards −x for a > 0), until N/m = g_e cos ψ − R ψ̇² = 0.
    def rhs(t, s):
        return [s[1], ge / R * math.sin(s[0])]

    def leaves(t, s):
        return ge * math.cos(s[0]) - R * s[1] ** 2

    leaves.terminal = True
    check = solve_ivp(rhs, (0, 2), [math.atan(abs(a) / G), 0.0], method="DOP853", rtol=1e-12, atol=1e-12,
                      events=leaves)
    assert release.t == pytest.approx(check.t_events[0][0], abs=1e-9)
    speed = R * check.y_events[0][0][1]  # relative to the cylinder, plus its velocity a t
    assert math.hypot(release.state["xdot"] - a * release.t, release.state["ydot"]) == pytest.approx(speed, rel=1e-9)
    before, after = motion.t < release.t, motion.t > release.t
    xr = motion.q[:, 0] - a * motion.t ** 2 / 2
    jacobi = (((motion.qdot[:, 0] - a * motion.t) ** 2 + motion.qdot[:, 1] ** 2) / 2 + a * xr + G * motion.q[:, 1])
    assert np.ptp(jacobi[before]) < 1e-9
    free = (motion.qdot ** 2).sum(axis=1) / 2 + G * motion.q[:, 1]
    assert np.ptp(free[after]) < 1e-9
    assert np.all(np.hypot(xr[after], motion.q[after, 1]) > R)


def test_a_bead_on_a_sideways_accelerating_ring_never_leaves_it():
    motion = simulate_scene(scene("cylinder_accelerating", "bilateral"), {}, t_end=1.0)
    assert motion.events == []
    xr = motion.q[:, 0] - 3.0 * motion.t ** 2 / 2
    np.testing.assert_allclose(np.hypot(xr, motion.q[:, 1]), 0.5, rtol=1e-10)
    assert motion.multipliers[:, 0].min() < 0 < motion.multipliers[:, 0].max()


# -- a string in polar coordinates: slack, parabola, taut ------------------------------------------

@pytest.mark.parametrize("v0", [5.5, 4.6])
def test_a_bob_on_a_string_in_polar_coordinates_flies_a_parabola_and_keeps_only_its_tangential_velocity(v0):
    m, l = 0.3, 0.8
    motion = simulate_scene(load_scene(SCENES / "pendulum_polar_slack.toml"), {"v0": v0}, t_end=1.5, samples=601)
    assert effects(motion) == [("release", "string"), ("contact", "string")]
    slack, taut = motion.events
    cos = (2 * G * l - v0 ** 2) / (3 * G * l)
    assert math.cos(slack.state["theta"]) == pytest.approx(cos, abs=1e-9)
    theta, v = math.acos(cos), math.sqrt(-G * l * cos)
    x0, y0, vx, vy = l * math.sin(theta), -l * math.cos(theta), v * math.cos(theta), v * math.sin(theta)

    def off(tau):
        return math.hypot(x0 + vx * tau, y0 + vy * tau - G * tau * tau / 2) - l

    taus = np.linspace(1e-3, 2.0, 4001)
    j = next(j for j in range(1, len(taus)) if off(taus[j]) >= 0)
    tau = brentq(off, taus[j - 1], taus[j], xtol=1e-15)
    x, y, vyf = x0 + vx * tau, y0 + vy * tau - G * tau * tau / 2, vy - G * tau
    assert taut.t == pytest.approx(slack.t + tau, abs=1e-10)
    assert math.atan2(x, -y) % (2 * math.pi) == pytest.approx(taut.state["theta"] % (2 * math.pi), abs=1e-9)
    assert taut.state["rdot"] == 0.0 or abs(taut.state["rdot"]) < 1e-12
    assert l * taut.state["thetadot"] == pytest.approx((x * vyf - y * vx) / l, rel=1e-9)
    energy = m / 2 * (motion.qdot[:, 0] ** 2 + (motion.q[:, 0] * motion.qdot[:, 1]) ** 2) - m * G * motion.q[:, 0] * np.cos(motion.q[:, 1])
    for part in (motion.t < slack.t, between(motion, slack.t, taut.t), motion.t > taut.t):
        assert np.ptp(energy[part]) < 1e-9
    radial = (x * vx + y * vyf) / l
    assert energy[motion.t < slack.t][0] - energy[motion.t > taut.t][0] == pytest.approx(m * radial ** 2 / 2, rel=1e-8)


def test_a_bob_on_a_rod_in_polar_coordinates_swings_up_to_its_energy_level_and_the_rod_pushes():
    # v0² = 30.25 < 4 g l: it turns back where cos θ = 1 − v0²/(2 g l), the rod pushing it up
    motion = simulate_scene(scene("pendulum_polar_slack", "bilateral"), {}, t_end=1.5, samples=1501)
    assert motion.events == []
    assert math.cos(motion.q[:, 1].max()) == pytest.approx(1 - 5.5 ** 2 / (2 * G * 0.8), abs=1e-5)
    np.testing.assert_allclose(motion.q[:, 0], 0.8, rtol=1e-12)
    assert motion.multipliers[:, 0].min() < 0


# -- a yo-yo struck upwards -----------------------------------------------------------------------

@pytest.mark.parametrize("v, I", [(1.5, 1e-4), (0.4, 1e-5)])
def test_a_yoyo_struck_upwards_flies_freely_and_its_string_jerks_taut_after_2v_over_g(v, I):
    m, b, h = 0.2, 0.01, 0.5
    motion = simulate_scene(load_scene(SCENES / "yoyo_struck_up.toml"), {"v": v, "I": I}, t_end=0.5, samples=501)
    assert effects(motion) == [("contact", "string")]
    taut = motion.events[0]
    assert taut.t == pytest.approx(2 * v / G, abs=1e-12)
    after = v * m * b * b / (m * b * b + I)
    assert (taut.state["y"], taut.state["ydot"], taut.state["phidot"]) == pytest.approx((h, after, after / b), rel=1e-10)
    flight = motion.t < taut.t
    np.testing.assert_allclose(motion.q[flight, 0], h - v * motion.t[flight] + G * motion.t[flight] ** 2 / 2, atol=1e-12)
    np.testing.assert_allclose(motion.qdot[flight, 1], 0.0, atol=1e-12)
    falling = motion.t > taut.t
    tau = motion.t[falling] - taut.t
    np.testing.assert_allclose(motion.q[falling, 0], h + after * tau + G * m * b * b / (m * b * b + I) * tau ** 2 / 2,
                               atol=1e-10)
    np.testing.assert_allclose(motion.multipliers[falling, 0], m * G * I / (m * b * b + I), rtol=1e-9)


# -- a bead on a spun rod bouncing against a stop (a rheonomic constraint held through impacts) ----

@pytest.mark.parametrize("e", [0.5, 0.8, 0.0])
def test_a_bead_flung_out_along_a_spun_rod_bounces_on_its_stop_and_comes_to_rest_there_in_finite_time(e):
    # Before: each contact was located 1e-13 beyond the stop (where the gap function fires), so
    # the restart after a rebound sat exactly on the next segment's firing threshold: the gap's
    # rounding (L² − x² − y², ±5e-17) fired the same bounce again within 1e-14 s, the Newton step
    # moved time backwards, and the run stopped after 10,000 events near t = 1.0889 (e = 0.5).
    # Located on the stop, the last rebounds (1e-7 m/s) gained energy at every inexact impact and
    # never ended either.
    m, w, r0, L = 0.1, 4.0, 0.1, 0.5
    motion = simulate_scene(load_scene(SCENES / "bead_spinning_rod_stop.toml"), {"e": e}, t_end=1.5 if e < 0.7 else 3.0,
                            samples=301)
    c = math.sqrt(L * L - r0 * r0)
    times = [math.acosh(L / r0) / w]
    for k in range(1, 200):
        times.append(times[-1] + 2 / w * math.atanh(e ** k * c / L))
    assert all(b.t > a.t for a, b in zip(motion.events, motion.events[1:]))
    bounces = [x for x in motion.events if x.effect == "bounce"]
    rest = motion.events[-1]
    assert rest.effect == "contact" and {x.effect for x in motion.events[:-1]} <= {"bounce"}
    for k, bounce in enumerate(bounces[:8]):
        assert bounce.t == pytest.approx(times[k], abs=1e-9)
        s = bounce.state
        r = math.hypot(s["x"], s["y"])
        assert r == pytest.approx(L, abs=1e-12)
        # radial speed reversed times e; the velocity across the rod is the rod's, ω L
        assert (s["x"] * s["xdot"] + s["y"] * s["ydot"]) / r == pytest.approx(-e ** (k + 1) * w * c, rel=1e-7)
        assert (s["x"] * s["ydot"] - s["y"] * s["xdot"]) / r == pytest.approx(w * L, rel=1e-9)
    # the sequence ends when a rebound could not lift the bead out of the rounding of its gap
    # (~1e-7 m/s here), which leaves out the last ~1e-7 s of the infinitely many bounces
    assert rest.t == pytest.approx(times[-1], abs=2e-7)
    held = motion.t > rest.t
    np.testing.assert_allclose(2 * L * motion.multipliers[held, 1], m * w * w * L, rtol=1e-8)
    # between bounces ṙ² − ω² r² is constant (the Jacobi integral of the rotating frame)
    r = np.hypot(motion.q[:, 0], motion.q[:, 1])
    rdot = (motion.q * motion.qdot).sum(axis=1) / r
    first = motion.t < times[0]
    np.testing.assert_allclose(rdot[first] ** 2 - w * w * r[first] ** 2, -(w * r0) ** 2, atol=1e-10)
    assert r.max() <= L + 1e-10  # held at the stop the constraint drifts by ~1e-11 over the run


# -- a string jerked taut lifts a block off the floor ----------------------------------------------

@pytest.mark.parametrize("m1, m2", [(1.0, 2.0), (2.0, 1.0)])
def test_a_falling_mass_jerks_its_string_taut_and_lifts_the_block_off_the_floor(m1, m2):
    # Before: for m1 < m2 the cycles of landing and jerking (each leaving m1/(m1 + m2) of the
    # speed) went on below 1e-7 m/s, where each inexact impact gained as much energy as it lost,
    # until the run stopped at 10,000 events near t = 1.0096.
    s, L, D = 0.2, 3.0, 2.0
    motion = simulate_scene(load_scene(SCENES / "atwood_jerk_off_floor.toml"), {"m1": m1, "m2": m2},
                            t_end=1.5, samples=301)
    v, t1 = math.sqrt(2 * G * s), math.sqrt(2 * s / G)
    V = m1 * v / (m1 + m2)
    assert effects(motion)[:2] == [("contact", "string"), ("release", "floor")]
    jerk = motion.events[0]
    assert jerk.t == pytest.approx(t1, abs=1e-12)
    assert (jerk.state["y1dot"], jerk.state["y2dot"]) == pytest.approx((V, -V), rel=1e-10)
    a = (m1 - m2) * G / (m1 + m2)
    if m1 > m2:
        assert len(motion.events) == 2
        after = motion.t > t1
        tau = motion.t[after] - t1
        np.testing.assert_allclose(motion.q[after, 1], D - V * tau - a * tau ** 2 / 2, atol=1e-10)
        return
    # The block rises and lands at V after 2V/|a|; mass 1 flies up on the slack string and jerks
    # it taut again at V after 2V/g; each cycle leaves m1/(m1 + m2) of the speed.
    cycle = 2 / G + 2 / abs(a)
    landing, slack, again = motion.events[2], motion.events[3], motion.events[4]
    assert [(x.effect, x.constraint) for x in (landing, slack, again)] == [
        ("contact", "floor"), ("release", "string"), ("contact", "string")]
    assert landing.t == pytest.approx(t1 + 2 * V / abs(a), abs=1e-10)
    assert again.t == pytest.approx(t1 + cycle * V, abs=1e-10)
    assert again.state["y1dot"] == pytest.approx(V * m1 / (m1 + m2), rel=1e-9)
    rest = t1 + cycle * V / (1 - m1 / (m1 + m2))
    assert motion.events[-1].t == pytest.approx(rest, abs=3e-7)
    still = motion.t > motion.events[-1].t
    assert motion.active[still].all()
    np.testing.assert_allclose(motion.multipliers[still], [[m1 * G, (m2 - m1) * G]] * still.sum(), rtol=1e-9)
    np.testing.assert_allclose(motion.qdot[still], 0.0, atol=1e-12)


# -- a ball thrown along a rough floor with backspin ---------------------------------------------

@pytest.mark.parametrize("w0", [0.0, 200.0, 300.0])
def test_a_ball_thrown_with_backspin_slides_until_it_rolls_at_5v0_minus_2R_w0_over_7(w0):
    # Sliding: ẍ = −μ_k g, R θ̈ = (5/2) μ_k g (I = 2/5 m R², the backspin counts as θ̇ < 0): the
    # slip ẋ − R θ̇ falls at (7/2) μ_k g to zero, then it rolls on (backwards for 2 R ω0 > 5 v0).
    m, R, mu, v0 = 0.16, 0.03, 0.2, 3.0
    motion = simulate_scene(load_scene(SCENES / "ball_with_backspin.toml"), {"w0": w0}, t_end=2.0, samples=401)
    assert effects(motion) == [("stick", "roll")]
    stick = motion.events[0]
    assert stick.t == pytest.approx(2 * (v0 + R * w0) / (7 * mu * G), abs=1e-10)
    final = (5 * v0 - 2 * R * w0) / 7
    assert (stick.state["xdot"], R * stick.state["thetadot"]) == pytest.approx((final, final), abs=1e-9)
    sliding, rolling = motion.t < stick.t, motion.t > stick.t
    t = motion.t[sliding]
    np.testing.assert_allclose(motion.q[sliding, 0], v0 * t - mu * G * t ** 2 / 2, atol=1e-10)
    np.testing.assert_allclose(motion.multipliers[sliding, 0], -mu * m * G, rtol=1e-9)  # kinetic friction, backwards
    np.testing.assert_allclose(motion.qdot[rolling, 0], final, atol=1e-9)
    np.testing.assert_allclose(motion.multipliers[rolling, 0], 0.0, atol=1e-9)
    assert motion.active[:, 1].all() and not motion.active[sliding, 0].any()
    kinetic = m / 2 * motion.qdot[:, 0] ** 2 + m * R * R / 5 * motion.qdot[:, 1] ** 2
    lost = kinetic[0] - kinetic[rolling][0]
    assert lost == pytest.approx(m / 2 * v0 ** 2 + m * R * R / 5 * w0 ** 2 - 7 / 10 * m * final ** 2, rel=1e-8)


@pytest.mark.parametrize("e", [1.0, 0.5, 0.0])
def test_a_ball_rolling_into_a_smooth_wall_rebounds_with_its_spin_and_rolls_back_at_2_minus_5e_over_7(e):
    # Before: the rolling constraint was held rigid through the wall's impact, so a friction
    # impulse from a floor that took no impulse reversed the spin: the ball rolled straight back
    # at e v (energy kept for e = 1) instead of sliding first.
    m, R, mu, v, d = 0.16, 0.03, 0.2, 2.0, 0.5
    motion = simulate_scene(load_scene(SCENES / "ball_rolling_into_wall.toml"), {"e": e}, t_end=1.2, samples=241)
    hit_t = (d - R) / v
    assert effects(motion) == [("bounce" if e else "contact", "wall"), ("slip", "roll"), ("stick", "roll")]
    hit, slip, stick = motion.events
    assert hit.t == slip.t == pytest.approx(hit_t, abs=1e-12)
    assert (hit.state["xdot"], R * hit.state["thetadot"]) == pytest.approx((-e * v, v), rel=1e-10)
    if e:
        # sliding away from the wall: ẍ = +μ g, R θ̈ = −(5/2) μ g; rolling again at (2 − 5e) v/7
        assert stick.t == pytest.approx(hit_t + 2 * (1 + e) * v / (7 * mu * G), abs=1e-10)
        final = (2 - 5 * e) * v / 7
    else:
        # pressed against the wall by the friction while the spin runs down: I θ̈ = −μ m g R
        assert stick.t == pytest.approx(hit_t + 2 * v / (5 * mu * G), abs=1e-10)
        final = 0.0
    assert (stick.state["xdot"], R * stick.state["thetadot"]) == pytest.approx((final, final), abs=1e-9)
    after = motion.t > stick.t
    np.testing.assert_allclose(motion.qdot[after, 0], final, atol=1e-9)
    # the floor's normal force stays m g: the impact never lifted the ball
    np.testing.assert_allclose(motion.multipliers[:, 1], m * G, rtol=1e-9)


# -- counting π with elastic collisions -----------------------------------------------------------

def billiard(m: float, M: float, v: float) -> tuple[int, float, float]:
    """Galperin's blocks by hand: collisions of the blocks and of the light one with the wall,
    alternately, until the light block is no faster towards the wall than the heavy one."""
    v1, v2, count = 0.0, -v, 0
    while True:
        if v2 < v1:
            v1, v2 = ((m - M) * v1 + 2 * M * v2) / (m + M), ((M - m) * v2 + 2 * m * v1) / (m + M)
        elif v1 < 0:
            v1 = -v1
        else:
            return count, v1, v2
        count += 1


@pytest.mark.parametrize("M, touching", [(1.0, False), (100.0, False), (1e4, True)])
def test_a_heavy_block_pushing_a_light_one_into_a_wall_makes_pi_sqrt_M_over_m_elastic_collisions(M, touching):
    # Touching from the start, all 3,141 collisions (M = 10⁶ m) happen at t = 0. Before: after
    # 1,000 of them the rest were taken together inelastically, and both blocks stopped dead.
    m, v = 0.01, 1.0
    count, v1, v2 = billiard(m, M, v)
    assert count == math.floor(math.pi * math.sqrt(M / m))
    motion = simulate_scene(load_scene(SCENES / "pi_billiard.toml"), {"M": M}, t_end=6.0, samples=61,
                            initial={"x1": 0.0, "x2": 0.0} if touching else None)
    assert len(motion.events) == (2 if touching else count)
    assert {x.effect for x in motion.events} == {"bounce"}
    assert motion.qdot[-1] == pytest.approx([v1, v2], rel=1e-9)
    kinetic = m / 2 * motion.qdot[:, 0] ** 2 + M / 2 * motion.qdot[:, 1] ** 2
    np.testing.assert_allclose(kinetic, M / 2 * v * v, rtol=1e-9)
    assert motion.q[:, 0].min() >= -1e-12 and (motion.q[:, 1] - motion.q[:, 0]).min() >= -1e-12


# -- a ball bouncing on a vibrating plate (impacts on a moving surface) -----------------------------

def test_a_ball_bouncing_on_a_vibrating_plate_rebounds_at_e_times_its_speed_relative_to_the_plate():
    # An independent event-driven calculation: free fall between impacts, the plate at A cos ωt,
    # each impact leaving v⁺ = u − e (v⁻ − u) with u the plate's velocity there.
    A, w, e = 0.05, 20.0, 0.7
    text = (SCENES / "vibrating_plate.toml").read_text().replace('kind = "unilateral"', f'kind = "unilateral"\nrestitution = {e}')
    motion = simulate_scene(parse_scene(text, source="vibrating_plate_bouncing.toml"), {}, t_end=1.0, samples=11)
    assert effects(motion)[0] == ("release", "plate") and motion.events[0].t == 0.0
    bounces = motion.events[1:]
    t, y, v = 0.0, A, 0.0
    for bounce in bounces:
        def gap(s):
            return y + v * (s - t) - G * (s - t) ** 2 / 2 - A * math.cos(w * s)

        grid = np.linspace(t + 1e-6, t + 2.0, 20001)
        values = np.array([gap(s) for s in grid])
        j = int(np.argmax(values < 0))
        s = brentq(gap, grid[j - 1], grid[j], xtol=1e-15)
        u = -A * w * math.sin(w * s)
        t, y, v = s, A * math.cos(w * s), u - e * (v - G * (s - t) - u)
        assert (bounce.effect, bounce.t, bounce.state["ydot"]) == ("bounce", pytest.approx(t, abs=1e-9),
                                                                   pytest.approx(v, abs=1e-8))
    assert len(bounces) == 5


# -- a string whose upper end is driven down faster than g ------------------------------------------

@pytest.mark.parametrize("x0", [0.0, 0.2])
def test_a_string_whose_end_is_pulled_down_faster_than_g_goes_slack_at_once_and_jerks_taut_above_it(x0):
    # Relative to the end the bob moves up at (a − g) t²/2 from (x0, −h); taut again where that
    # puts it a length l from the end, h above it; the jerk keeps the relative tangential velocity.
    m, l, a = 0.5, 0.6, 15.0
    motion = simulate_scene(load_scene(SCENES / "pendulum_pivot_dropped.toml"), {"x0": x0}, t_end=1.0, samples=201)
    assert effects(motion) == [("release", "string"), ("contact", "string")]
    slack, taut = motion.events
    h = math.sqrt(l * l - x0 * x0)
    t = math.sqrt(4 * h / (a - G))
    assert slack.t == 0.0 and taut.t == pytest.approx(t, abs=1e-10)
    assert (taut.state["x"], taut.state["y"]) == pytest.approx((x0, h - a * t * t / 2), abs=1e-9)
    rise = (a - G) * t                     # the bob's velocity relative to the end, straight up
    tangent = (h / l, -x0 / l)
    along = rise * tangent[1]
    expected = (along * tangent[0], -a * t + along * tangent[1])
    assert (taut.state["xdot"], taut.state["ydot"]) == pytest.approx(expected, abs=1e-9)
    flight = motion.t < taut.t
    np.testing.assert_allclose(motion.q[flight, 1], -h - G * motion.t[flight] ** 2 / 2, atol=1e-12)
    if x0 == 0.0:
        np.testing.assert_allclose(2 * l * motion.multipliers[motion.t > taut.t, 0], m * (a - G), rtol=1e-9)


def test_a_rod_whose_end_is_pulled_down_faster_than_g_pushes_the_bob_down_with_it():
    m, l, a = 0.5, 0.6, 15.0
    motion = simulate_scene(scene("pendulum_pivot_dropped", "bilateral"), {}, t_end=1.0)
    assert motion.events == []
    np.testing.assert_allclose(2 * l * motion.multipliers[:, 0], -m * (a - G), rtol=1e-9)
    np.testing.assert_allclose(motion.q[:, 1], -l - a * motion.t ** 2 / 2, atol=1e-9)


@pytest.mark.parametrize("v0, w0, mu_s, mu_k", [(3.0, 50.0, 0.3, 0.2), (1.0, 10.0, 5.0, 5.0), (3.0, 50.0, 0.0, 0.0)])
def test_a_spinning_ball_bouncing_on_a_rough_floor_takes_a_coulomb_friction_impulse_at_every_impact(v0, w0, mu_s, mu_k):
    # Before: an impact took no friction impulse at all; the ball bounced with its horizontal
    # velocity and spin unchanged until its bounces ended, and only then slid.
    m, R, e, h = 0.16, 0.03, 0.5, 0.03
    u = math.sqrt(2 * G * h)
    motion = simulate_scene(load_scene(SCENES / "ball_with_backspin.toml"),
                            {"v0": v0, "w0": w0, "mu_s": mu_s, "mu_k": mu_k, "e": e}, t_end=1.5, samples=301,
                            initial={"y": h})
    first = motion.events[0]
    assert (first.effect, first.constraint, first.t) == ("bounce", "floor", pytest.approx(math.sqrt(2 * h / G), abs=1e-12))
    if 2 * (v0 + R * w0) / 7 <= mu_s * (1 + e) * u:
        after = ((5 * v0 - 2 * R * w0) / 7,) * 2                    # it sticks: rolls as it leaves
    else:
        after = (v0 - mu_k * (1 + e) * u, -R * w0 + 5 / 2 * mu_k * (1 + e) * u)
    assert (first.state["xdot"], R * first.state["thetadot"], first.state["ydot"]) == pytest.approx(
        (*after, e * u), abs=1e-9)
    # Every impulse acts at the contact point, which keeps the angular momentum about it: it
    # ends up rolling at (5 v0 − 2 R ω0)/7 (or, without friction, sliding as it started).
    final = (5 * v0 - 2 * R * w0) / 7 if mu_k else v0
    assert motion.qdot[-1, 0] == pytest.approx(final, abs=1e-8)
    energy = m / 2 * (motion.qdot[:, 0] ** 2 + motion.qdot[:, 2] ** 2) + m * R * R / 5 * motion.qdot[:, 1] ** 2 + m * G * motion.q[:, 2]
    assert np.all(np.diff(energy) <= 1e-9)


# -- Zeno sequences that end in resting contact ----------------------------------------------------

@pytest.mark.parametrize("e, M, h", [(0.31, 0.5, 1.23), (0.58, 0.73, 0.47)])
def test_a_small_ball_bouncing_on_a_big_one_comes_to_rest_on_it(e, M, h):
    # Before: the small ball's last rebounds off the big one, resting on the floor, came out of
    # each impact at ~3e-9 m/s, never lifted the gap out of its rounding, and bounced 10,000
    # times at the same height (the rebound test used the free fall of both balls, in which
    # the gap between them does not accelerate at all).
    m = 0.05
    motion = simulate_scene(load_scene(SCENES / "stacked_balls_drop.toml"), {"e": e, "M": M, "h": h}, t_end=2.0,
                            samples=201)
    assert motion.events[-1].effect == "contact"
    rest = motion.t > motion.events[-1].t
    assert rest.sum() > 10 and motion.active[rest].all()
    np.testing.assert_allclose(motion.multipliers[rest], [[(M + m) * G, m * G]] * rest.sum(), rtol=1e-9)
    energy = M / 2 * motion.qdot[:, 0] ** 2 + m / 2 * motion.qdot[:, 1] ** 2 + G * (M * motion.q[:, 0] + m * motion.q[:, 1])
    assert np.all(np.diff(energy) <= 1e-9)


@pytest.mark.parametrize("e, mu_s, mu_k, v", [
    (0.089, 0.59, 0.42, 0.77),
    (0.23783859635689797, 0.5190224277267071, 0.10847674431672183, 2.9051136600917373),
])
def test_a_ball_driven_back_into_a_wall_by_its_spin_comes_to_rest_against_it(e, mu_s, mu_k, v):
    # With e < 2/5 friction brings the ball back to the wall, again and again. Before: the wall's
    # last rebounds were counted as bounces although friction pressed the ball into it (the
    # rebound test left friction out), or, at 1e-8 m/s, the contact was located 1e-13 inside
    # the wall where Newton's steps could not reach the gap's zero, and the bounce fired again
    # at once: 10,000 events either way.
    motion = simulate_scene(load_scene(SCENES / "ball_rolling_into_wall.toml"),
                            {"e": e, "mu_s": mu_s, "mu_k": mu_k, "v": v}, t_end=2.5, samples=251)
    assert motion.events[-1].effect == "stick"
    rest = motion.t > motion.events[-1].t
    assert rest.sum() > 10
    np.testing.assert_allclose(motion.qdot[rest], 0.0, atol=1e-9)
    np.testing.assert_allclose(motion.q[rest, 0], 0.5 - 0.03, atol=1e-12)
    assert all(b.t >= a.t for a, b in zip(motion.events, motion.events[1:]))


# -- a massless pulley held by strings that could go slack -------------------------------------------

@pytest.mark.parametrize("m2, m3", [(1.0, 2.0), (1.053, 2.263)])
def test_a_double_atwood_machine_with_a_massless_pulley_and_slack_capable_strings_is_simulated(m2, m3):
    # The movable pulley's coordinate has no mass: M is singular, the KKT system is not. Before:
    # projecting the start onto the strings solved M Δq̇ = Jᵀ Λ with M alone and raised numpy's
    # bare "Singular matrix", so the scene had no simulation at all, whatever its values.
    m1 = 3.0
    scene_ = load_scene(Path(__file__).resolve().parents[1] / "mechanics" / "scenes" / "double_atwood.toml")
    motion = simulate_scene(scene_, {"m2": m2, "m3": m3}, t_end=1.0, samples=51)
    assert motion.events == [] and motion.active.all()
    mu = m1 * (m2 + m3) + 4 * m2 * m3
    upper = 8 * m1 * m2 * m3 * G / mu
    np.testing.assert_allclose(motion.q[:, 0], 1.0 + G * (m1 * (m2 + m3) - 4 * m2 * m3) / mu * motion.t ** 2 / 2,
                               atol=1e-10)
    np.testing.assert_allclose(motion.multipliers, [[upper, upper / 2]] * len(motion.t), rtol=1e-9)
