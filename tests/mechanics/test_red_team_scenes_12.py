"""The eighteenth engine red team (2026-11-28): textbook scenes written independently of the engine.

Seven scenes from the constraints chapters (Kleppner & Kolenkow, Morin, Taylor, Marion & Thornton,
Goldstein, Hand & Finch), each of a structure the 110 earlier scenes have not:

- yoyo_pulled_up_accelerating: a yo-yo whose string's top is pulled up at a given acceleration (the
  hand's motion A t²/2 in the constraint; the hand's acceleration that holds the axis still, a threshold
  on a parameter; the height in time);
- incline_peg_spring_hanging: a block on an incline tied over a peg to a hanging block that a spring
  holds to the floor (two bodies, one string, a spring on one side: the rest position, the frequency,
  the farthest climb, the least and the largest tension over the motion);
- bead_rod_spun_up: a bead on a horizontal rod whose angular velocity grows at a constant rate
  (φ = ω₀t + αt²/2: the rod's force and the motor's torque depend on t explicitly);
- bead_vertical_ellipse_cartesian: a bead on a vertical elliptical wire in x, y (the force at the
  bottom, m g (1 + 2b²(a − √(a² − x₀²))/a³), through the radius of curvature a²/b; ω = √(g b)/a);
- disk_incline_spring_axle: a disk rolling on an incline with a spring on its axle (friction as the
  reaction force; the least friction coefficient over the motion, tan α/3, the same as without the spring);
- swinging_atwood: the swinging Atwood machine (three coordinates, the tension M m (g (1 + cos θ) + r θ̇²)/(M + m),
  the mass M that holds r unaccelerated, in the state);
- bead_on_swinging_rod: a bead sliding on a rod that swings freely, the bead in Cartesian x, y and the
  answers in r, θ through a parametrization (the rod's force vanishes at rest at r = 2l/3, the centre of
  percussion).

Every answer is compared with the closed form derived by hand (the comment above each table) at two
parameter points and states, and confirmed by a numerical experiment of its own: each scene's motion is
written again with Newton's laws in Cartesian or polar form (the reaction forces as unknowns of a linear
system at each instant, never the engine's equations) and integrated with scipy; the forces and
accelerations are compared at states along it, the special values (extremes, thresholds, frequencies) with
what the integrated motion does. Those special values are listed in
tests/numerical/test_problems_confirmed.py's CONFIRMED_ELSEWHERE.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from grader.mechanics.lagrange import derive
from tests.mechanics.hand_checks import (agrees_by_hand, hand_cases, integrate, period, scene_values,
                                         unchecked_answers)
from tests.mechanics.hand_checks import derived as _derived, engine_value as _engine
from tests.mechanics.test_red_team_scenes_7 import at

SCENES = Path(__file__).resolve().parent / "scenes"




# -- yoyo_pulled_up_accelerating ------------------------------------------------------------------------
# m ÿ = T − m g, I φ̈ = T R, and the string: ÿ + R φ̈ = A. So T (1/m + R²/I) = A + g:
# T = I m (A + g)/(I + m R²), ÿ = (A I − m R² g)/(I + m R²), φ̈ = R m (A + g)/(I + m R²); the axis stays
# still (ÿ = 0) for A = m R² g/I (2g for a uniform disk); from rest y = ÿ t²/2.
_YOYO = {
    "tension": "I*m*(A + g)/(I + m*R^2)",
    "axis_acceleration": "(A*I - m*R^2*g)/(I + m*R^2)",
    "angular_acceleration": "R*m*(A + g)/(I + m*R^2)",
    "hovering_acceleration": "m*R^2*g/I",
    "height_in_time": "(A*I - m*R^2*g)/(I + m*R^2)*t^2/2",
}
_YOYO_POINTS = [
    {"m": 0.2, "I": 0.0004, "R": 0.05, "A": 3.0, "g": 9.81, "t": 0.7},
    {"m": 1.3, "I": 0.02, "R": 0.2, "A": 0.4, "g": 1.6, "t": 2.1},
]

# -- incline_peg_spring_hanging -------------------------------------------------------------------------
# s up the incline, z = −s: L = (m1 + m2) ṡ²/2 − m1 g s sin α + m2 g s − k s²/2, so
# (m1 + m2) s̈ = g (m2 − m1 sin α) − k s. The block: m1 s̈ = T − m1 g sin α, so
# T = m1 (m2 g (1 + sin α) − k s)/(m1 + m2). At rest where s̈ = 0: s* = g (m2 − m1 sin α)/k; ω = √(k/(m1 + m2)).
# From rest at s = 0 (m2 > m1 sin α) it swings between 0 and 2 s*; T falls linearly with s: largest
# m1 m2 g (1 + sin α)/(m1 + m2) at s = 0, least m1 g (2 m1 sin α + m2 sin α − m2)/(m1 + m2) at s = 2 s*.
_PEG = {
    "tension": "m1*(m2*g*(1 + sin(alpha)) - k*s)/(m1 + m2)",
    "block_acceleration": "(g*(m2 - m1*sin(alpha)) - k*s)/(m1 + m2)",
    "equilibrium": "g*(m2 - m1*sin(alpha))/k",
    "frequency": "sqrt(k/(m1 + m2))",
    "largest_stretch": "2*g*(m2 - m1*sin(alpha))/k",
    "least_tension": "m1*g*(2*m1*sin(alpha) + m2*sin(alpha) - m2)/(m1 + m2)",
    "largest_tension": "m1*m2*g*(1 + sin(alpha))/(m1 + m2)",
}
_PEG_POINTS = [
    {"m1": 1.0, "m2": 2.0, "k": 200.0, "alpha": 0.5, "g": 9.81, "s": 0.07},
    {"m1": 0.4, "m2": 0.9, "k": 35.0, "alpha": 1.1, "g": 3.7, "s": -0.02},
]

# -- bead_rod_spun_up -----------------------------------------------------------------------------------
# Polar: m (r̈ − r φ̇²) = 0 along the rod; across it m (r φ̈ + 2 ṙ φ̇) = N with φ̇ = ω₀ + α t, φ̈ = α:
# N = m (α r + 2 ṙ (ω₀ + α t)); the light rod's torque is r N.
_SPUN = {
    "rod_force": "m*(alpha*r + 2*rdot*(omega0 + alpha*t))",
    "torque": "m*r*(alpha*r + 2*rdot*(omega0 + alpha*t))",
    "radial_equation": "r*(omega0 + alpha*t)^2",
}
_SPUN_POINTS = [
    {"m": 0.1, "omega0": 1.0, "alpha": 0.5, "r0": 0.2, "r": 0.35, "rdot": 0.4, "t": 1.2},
    {"m": 2.3, "omega0": 0.2, "alpha": 3.0, "r0": 0.5, "r": 1.1, "rdot": -0.3, "t": 0.4},
]

# -- bead_vertical_ellipse_cartesian --------------------------------------------------------------------
# From rest at x0 on the lower half (y0 = −b √(1 − x0²/a²)) to the bottom (0, −b): v² = 2 g (b + y0) =
# 2 b g (a − √(a² − x0²))/a, the largest speed. The bottom's radius of curvature is a²/b, so the wire
# pushes up with m g + m v² b/a² = m g (1 + 2 b² (a − √(a² − x0²))/a³). Near the bottom y ≈ −b + b x²/(2a²):
# V ≈ m g b x²/(2a²), T ≈ m ẋ²/2, so ω = √(g b)/a.
_ELLIPSE = {
    "bottom_force": "m*g*(1 + 2*b^2*(a - sqrt(a^2 - x0^2))/a^3)",
    "largest_speed_squared": "2*b*g*(a - sqrt(a^2 - x0^2))/a",
    "frequency": "sqrt(g*b)/a",
}
_ELLIPSE_POINTS = [
    {"m": 0.05, "a": 0.5, "b": 0.3, "x0": 0.4, "g": 9.81},
    {"m": 1.7, "a": 0.2, "b": 0.9, "x0": 0.05, "g": 9.81},
]

# -- disk_incline_spring_axle ---------------------------------------------------------------------------
# m ẍ = m g sin α − k x − F, (m R²/2) φ̈ = F R, ẍ = R φ̈: ẍ = 2 (g sin α − k x/m)/3, F = m ẍ/2 =
# (m g sin α − k x)/3. ω = √(2k/(3m)). From rest at x = 0 it swings between 0 and 2 m g sin α/k, where F
# is ±m g sin α/3: the least coefficient is |F|/(m g cos α) at its largest, tan α/3. Energy:
# (3/4) m ẋ² = m g x sin α − k x²/2, largest at x = m g sin α/k: ẋ = g sin α √(2m/(3k)).
_DISK = {
    "friction": "(m*g*sin(alpha) - k*x)/3",
    "acceleration": "2*(g*sin(alpha) - k*x/m)/3",
    "frequency": "sqrt(2*k/(3*m))",
    "least_friction_coefficient": "tan(alpha)/3",
    "largest_speed": "g*sin(alpha)*sqrt(2*m/(3*k))",
}
_DISK_POINTS = [
    {"m": 2.0, "R": 0.1, "k": 50.0, "alpha": 0.4, "g": 9.81, "x": 0.1},
    {"m": 0.3, "R": 0.6, "k": 7.0, "alpha": 1.2, "g": 1.6, "x": -0.05},
]

# -- swinging_atwood ------------------------------------------------------------------------------------
# The block (depth z = L − r): M z̈ = M g − T. The bob, along its string: m (r̈ − r θ̇²) = m g cos θ − T,
# across it r θ̈ + 2 ṙ θ̇ + g sin θ = 0. With z̈ = −r̈: T = M m (g (1 + cos θ) + r θ̇²)/(M + m),
# r̈ = (g (m cos θ − M) + m r θ̇²)/(M + m); r̈ = 0 for M = m (cos θ + r θ̇²/g).
_ATWOOD = {
    "tension": "M*m*(g*(1 + cos(theta)) + r*thetadot^2)/(M + m)",
    "radial_acceleration": "(g*(m*cos(theta) - M) + m*r*thetadot^2)/(M + m)",
    "angular_equation": "-(g*sin(theta) + 2*rdot*thetadot)/r",
    "block_acceleration": "(g*(M - m*cos(theta)) - m*r*thetadot^2)/(M + m)",
    "balancing_mass": "m*(cos(theta) + r*thetadot^2/g)",
}
_ATWOOD_POINTS = [
    {"M": 1.2, "m": 1.0, "L": 2.0, "g": 9.81, "r": 0.8, "rdot": 0.3, "theta": 0.7, "thetadot": -1.1},
    {"M": 0.4, "m": 2.5, "L": 3.0, "g": 1.6, "r": 1.9, "rdot": -0.6, "theta": -1.4, "thetadot": 0.5},
]

# -- bead_on_swinging_rod -------------------------------------------------------------------------------
# The bead in polar r, θ: along the rod m (r̈ − r θ̇²) = m g cos θ; across it m (r θ̈ + 2 ṙ θ̇) = N − m g sin θ.
# The rod (I = M l²/3 about its end): I θ̈ = −M g (l/2) sin θ − N r. Eliminating N:
# (I + m r²) θ̈ = −g sin θ (M l/2 + m r) − 2 m r ṙ θ̇, and N = m (g sin θ (I − M l r/2) + 2 I ṙ θ̇)/(I + m r²):
# at rest it vanishes at r = 2I/(M l) = 2l/3, the centre of percussion; in general at
# r = (2l/3)(1 + 2 ṙ θ̇/(g sin θ)).
_ROD = {
    "normal_force": "m*(g*sin(theta)*(M*l^2/3 - M*l*r/2) + 2*M*l^2/3*rdot*thetadot)/(M*l^2/3 + m*r^2)",
    "angular_acceleration": "-(g*sin(theta)*(M*l/2 + m*r) + 2*m*r*rdot*thetadot)/(M*l^2/3 + m*r^2)",
    "radial_acceleration": "g*cos(theta) + r*thetadot^2",
    "no_force_point": "2*l/3*(1 + 2*rdot*thetadot/(g*sin(theta)))",
}
_ROD_POINTS = [
    {"M": 0.6, "m": 0.2, "l": 1.0, "g": 9.81, "r": 0.45, "rdot": 0.2, "theta": 0.4, "thetadot": -0.9},
    {"M": 2.0, "m": 1.1, "l": 0.7, "g": 1.6, "r": 0.3, "rdot": -0.5, "theta": -1.2, "thetadot": 1.4},
]

TABLES = {
    "yoyo_pulled_up_accelerating": (_YOYO, _YOYO_POINTS),
    "incline_peg_spring_hanging": (_PEG, _PEG_POINTS),
    "bead_rod_spun_up": (_SPUN, _SPUN_POINTS),
    "bead_vertical_ellipse_cartesian": (_ELLIPSE, _ELLIPSE_POINTS),
    "disk_incline_spring_axle": (_DISK, _DISK_POINTS),
    "swinging_atwood": (_ATWOOD, _ATWOOD_POINTS),
    "bead_on_swinging_rod": (_ROD, _ROD_POINTS),
}
CASES = hand_cases(TABLES)


@pytest.mark.parametrize("scene, answer, expected, points", CASES, ids=[f"{c[0]}-{c[1]}" for c in CASES])
def test_answer_agrees_with_the_hand_derivation(scene, answer, expected, points):
    agrees_by_hand(_derived(scene), answer, expected, points)


def test_every_answer_of_the_new_scenes_is_checked_by_hand():
    assert unchecked_answers(TABLES) == {}


# -- numerical experiments: Newton's laws written again, integrated with scipy ---------------------------
def test_yoyo_hovers_at_the_engines_acceleration_and_rises_as_its_height_in_time():
    p = scene_values("yoyo_pulled_up_accelerating")
    m, I, R, g = p["m"], p["I"], p["R"], p["g"]

    def newton(A):  # unknowns ÿ, φ̈, T: m ÿ = T − m g, I φ̈ = T R, ÿ + R φ̈ = A
        return np.linalg.solve([[m, 0, -1], [0, I, -R], [1, R, 0]], [-m * g, 0, A])

    hover = _engine("yoyo_pulled_up_accelerating", "hovering_acceleration", p)
    assert abs(newton(hover)[0]) < 1e-12 * g
    assert newton(1.01 * hover)[0] > 0 > newton(0.99 * hover)[0]
    y_acc, _, tension = newton(p["A"])
    assert tension == pytest.approx(_engine("yoyo_pulled_up_accelerating", "tension", p), rel=1e-12)
    run = integrate(lambda t, s: [s[1], y_acc], [0.0, 0.0], 1.5)
    assert run.sol(1.5)[0] == pytest.approx(
        _engine("yoyo_pulled_up_accelerating", "height_in_time", {**p, "t": 1.5}), rel=1e-9)


def test_incline_peg_spring_swing_its_period_and_tensions():
    name = "incline_peg_spring_hanging"
    p = scene_values(name)
    m1, m2, k, alpha, g = p["m1"], p["m2"], p["k"], p["alpha"], p["g"]

    def newton(s, z):  # unknowns s̈, z̈, T: m1 s̈ = T − m1 g sin α, m2 z̈ = T − m2 g − k z, s̈ + z̈ = 0
        return np.linalg.solve([[m1, 0, -1], [0, m2, -1], [1, 1, 0]], [-m1 * g * math.sin(alpha), -m2 * g - k * z, 0])

    def rhs(t, y):
        s, sdot = y
        return [sdot, newton(s, -s)[0]]

    run = integrate(rhs, [0.0, 0.0], 1.5)
    ts = np.linspace(0.0, 1.5, 15001)
    s = run.sol(ts)[0]
    tensions = [newton(x, -x)[2] for x in s]
    omega = 2 * math.pi / period(run, 1, 1.5)
    assert omega == pytest.approx(_engine(name, "frequency", p), rel=1e-6)
    assert max(s) == pytest.approx(_engine(name, "largest_stretch", p), rel=1e-6)
    assert min(tensions) == pytest.approx(_engine(name, "least_tension", p), rel=1e-6)
    assert max(tensions) == pytest.approx(_engine(name, "largest_tension", p), rel=1e-6)
    rest = _engine(name, "equilibrium", p)
    assert abs(newton(rest, -rest)[0]) < 1e-12 * g


def test_bead_on_a_spun_up_rod_feels_the_engines_force_in_an_inertial_frame():
    name = "bead_rod_spun_up"
    p = scene_values(name)
    m, w0, alpha, r0 = p["m"], p["omega0"], p["alpha"], p["r0"]

    def rhs(t, y):  # the bead in inertial x, y; the rod's force λ (−sin φ, cos φ) keeps −x sin φ + y cos φ = 0
        x, y_, vx, vy = y
        phi, w = w0 * t + alpha * t * t / 2, w0 + alpha * t
        s, c = math.sin(phi), math.cos(phi)
        # m ẍ = −λ s, m ÿ = λ c, and the constraint's second derivative vanishes:
        # −ẍ s + ÿ c − 2 φ̇ (ẋ c + ẏ s) − φ̈ (x c + y s) + φ̇² (x s − y c) = 0
        lam = m * (2 * w * (vx * c + vy * s) + alpha * (x * c + y_ * s) - w * w * (x * s - y_ * c))
        return [vx, vy, -lam * s / m, lam * c / m]

    run = integrate(rhs, [r0, 0.0, 0.0, w0 * r0], 1.6)
    for t in (0.0, 0.5, 1.1, 1.6):
        x, y_, vx, vy = run.sol(t)
        phi, w = w0 * t + alpha * t * t / 2, w0 + alpha * t
        s, c = math.sin(phi), math.cos(phi)
        lam = m * (2 * w * (vx * c + vy * s) + alpha * (x * c + y_ * s) - w * w * (x * s - y_ * c))
        r, rdot = x * c + y_ * s, vx * c + vy * s
        state = {**p, "r": r, "rdot": rdot, "t": t}
        assert _engine(name, "rod_force", state) == pytest.approx(lam, rel=1e-8)
        assert _engine(name, "torque", state) == pytest.approx(lam * r, rel=1e-8)
        assert abs(x * s - y_ * c) < 1e-8 * r0  # still on the rod


def _ellipse_run(p, x0, t_end):
    a, b, g = p["a"], p["b"], p["g"]

    def forces(x, y, vx, vy):  # m ẍ = λ 2x/a², m ÿ = −m g + λ 2y/b², f̈ = 0 (per unit mass)
        gx, gy = 2 * x / a**2, 2 * y / b**2
        lam = (g * gy - 2 * vx * vx / a**2 - 2 * vy * vy / b**2) / (gx * gx + gy * gy)
        return lam * gx, -g + lam * gy, lam * gy

    def rhs(t, s):
        ax, ay, _ = forces(*s)
        return [s[2], s[3], ax, ay]

    start = [x0, -b * math.sqrt(1 - x0**2 / a**2), 0.0, 0.0]
    bottom = lambda t, s: s[0]  # noqa: E731
    return integrate(rhs, start, t_end, events=bottom), forces


def test_bead_on_an_ellipse_speed_and_force_at_the_bottom_and_its_frequency():
    name = "bead_vertical_ellipse_cartesian"
    p = scene_values(name)
    run, forces = _ellipse_run(p, p["x0"], 1.5)
    x, y, vx, vy = run.y_events[0][0]
    assert vx * vx + vy * vy == pytest.approx(_engine(name, "largest_speed_squared", p), rel=1e-8)
    assert p["m"] * forces(x, y, vx, vy)[2] == pytest.approx(_engine(name, "bottom_force", p), rel=1e-8)
    ts = np.linspace(0.0, 1.5, 3001)
    speeds = [v[2] ** 2 + v[3] ** 2 for v in run.sol(ts).T]
    assert max(speeds) <= _engine(name, "largest_speed_squared", p) * (1 + 1e-9)
    small, _ = _ellipse_run(p, 1e-4 * p["a"], 5.0)
    assert 2 * math.pi / period(small, 2, 5.0) == pytest.approx(_engine(name, "frequency", p), rel=1e-6)


def test_disk_on_an_incline_with_a_spring_needs_tan_alpha_over_three():
    name = "disk_incline_spring_axle"
    p = scene_values(name)
    m, R, k, alpha, g = p["m"], p["R"], p["k"], p["alpha"], p["g"]

    def newton(x):  # unknowns ẍ, φ̈, F: m ẍ = m g sin α − k x − F, m R²/2 φ̈ = F R, ẍ = R φ̈
        return np.linalg.solve([[m, 0, 1], [0, m * R * R / 2, -R], [1, -R, 0]], [m * g * math.sin(alpha) - k * x, 0, 0])

    run = integrate(lambda t, y: [y[1], newton(y[0])[0]], [0.0, 0.0], 3.0)
    ts = np.linspace(0.0, 3.0, 30001)
    xs, vs = run.sol(ts)
    mu = max(abs(newton(x)[2]) / (m * g * math.cos(alpha)) for x in xs)
    assert mu == pytest.approx(_engine(name, "least_friction_coefficient", p), rel=1e-6)
    assert max(vs) == pytest.approx(_engine(name, "largest_speed", p), rel=1e-6)
    assert 2 * math.pi / period(run, 1, 3.0) == pytest.approx(_engine(name, "frequency", p), rel=1e-6)
    for point in _DISK_POINTS[:1]:
        assert newton(point["x"])[2] == pytest.approx(_engine(name, "friction", point), rel=1e-12)


@pytest.mark.parametrize("point", _ATWOOD_POINTS)
def test_swinging_atwood_tension_from_newton_in_cartesian_coordinates(point):
    # The bob at (X, Y) = (r sin θ, −r cos θ), the block at depth z: m (Ẍ, Ÿ) = −T (X, Y)/r − (0, m g),
    # M z̈ = M g − T, and r̈ + z̈ = 0 with r̈ = (X Ẍ + Y Ÿ + Ẋ² + Ẏ²)/r − ṙ²/r.
    M, m, g, r, rdot, th, thd = (point[k] for k in ("M", "m", "g", "r", "rdot", "theta", "thetadot"))
    X, Y = r * math.sin(th), -r * math.cos(th)
    VX = rdot * math.sin(th) + r * thd * math.cos(th)
    VY = -rdot * math.cos(th) + r * thd * math.sin(th)
    # unknowns Ẍ, Ÿ, z̈, T
    system = [[m, 0, 0, X / r], [0, m, 0, Y / r], [0, 0, M, 1], [X / r, Y / r, 1, 0]]
    rhs = [0, -m * g, M * g, -(VX * VX + VY * VY) / r + rdot * rdot / r]
    ax, ay, zdd, tension = np.linalg.solve(system, rhs)
    thetaddot = (ax * math.cos(th) + ay * math.sin(th) - 2 * rdot * thd) / r
    assert _engine("swinging_atwood", "tension", point) == pytest.approx(tension, rel=1e-10)
    assert _engine("swinging_atwood", "block_acceleration", point) == pytest.approx(zdd, rel=1e-10)
    assert _engine("swinging_atwood", "radial_acceleration", point) == pytest.approx(-zdd, rel=1e-10)
    assert at(_derived("swinging_atwood"), _ATWOOD["angular_equation"], point) == pytest.approx(thetaddot, rel=1e-10)
    balancing = {**point, "M": _engine("swinging_atwood", "balancing_mass", point)}
    system[2][2] = balancing["M"]
    rhs[2] = balancing["M"] * g
    assert abs(np.linalg.solve(system, rhs)[2]) < 1e-12 * g


@pytest.mark.parametrize("point", _ROD_POINTS)
def test_bead_on_swinging_rod_force_from_newton_in_cartesian_coordinates(point):
    # The bead at (x, y), the rod at θ: m ẍ = λ cos θ, m ÿ = −m g + λ sin θ,
    # I θ̈ = −M g (l/2) sin θ + λ (−x sin θ + y cos θ), and (x cos θ + y sin θ)'' = 0.
    M, m, l, g, r, rdot, th, thd = (point[k] for k in ("M", "m", "l", "g", "r", "rdot", "theta", "thetadot"))
    I = M * l * l / 3
    s, c = math.sin(th), math.cos(th)
    x, y = r * s, -r * c
    vx, vy = rdot * s + r * thd * c, -rdot * c + r * thd * s
    arm = -x * s + y * c
    system = [[m, 0, 0, -c], [0, m, 0, -s], [0, 0, I, -arm], [c, s, arm, 0]]
    rhs = [0, -m * g, -M * g * l / 2 * s, -2 * thd * (-vx * s + vy * c) + thd * thd * (x * c + y * s)]
    ax, ay, thdd, lam = np.linalg.solve(system, rhs)
    rdd = ax * s - ay * c + 2 * thd * (vx * c + vy * s) + thdd * (x * c + y * s) - thd * thd * (x * s - y * c)
    assert _engine("bead_on_swinging_rod", "normal_force", point) == pytest.approx(lam, rel=1e-10)
    assert _engine("bead_on_swinging_rod", "angular_acceleration", point) == pytest.approx(thdd, rel=1e-10)
    assert _engine("bead_on_swinging_rod", "radial_acceleration", point) == pytest.approx(rdd, rel=1e-10)
    # At the engine's point r the rod pushes nothing.
    moved = {**point, "r": _engine("bead_on_swinging_rod", "no_force_point", point)}
    assert abs(_engine("bead_on_swinging_rod", "normal_force", moved)) < 1e-10 * m * g


# -- Found and fixed: an answer at the start that depends on t itself ------------------------------------
# The spun-up rod's force m (α r + 2 ṙ (ω₀ + α t)) at the release (t = 0, r = r0, ṙ = 0) is m α r0: the
# state [initial] gives, as for any answer at t = 0. Because the answer's expression holds t, it was sent to
# the motion in time first, which has no closed form here (r̈ = r (ω₀ + α t)²), and the file was refused.
_SPUN_TEXT = (SCENES / "bead_rod_spun_up.toml").read_text()


def test_an_answer_at_the_start_that_depends_on_t_is_read_at_initial():
    from grader.mechanics.scene import parse_scene
    text = _SPUN_TEXT + '''
[[answers]]
name = "rod_force_at_start"
prompt = "The rod's force on the bead at the release"
expr = "rod_force"
where = "t = 0"
in_terms_of = ["m", "omega0", "alpha", "r0"]
'''
    derivation = derive(parse_scene(text, source="spun.toml"))
    point = {"m": 0.3, "omega0": 1.7, "alpha": 0.6, "r0": 0.25}
    assert at(derivation, derivation.answers["rod_force_at_start"], point) == pytest.approx(0.3 * 0.6 * 0.25, rel=1e-12)


# -- Found and fixed: a truncated power series taken for the motion in time -------------------------------
# With r̈ = r (ω₀ + α t)², sympy's dsolve answers r(t) = … + O(t⁶), a series; the engine compared it with the
# numerical motion and refused "the closed form r(t) = … O(t**6) disagrees with a numerical integration …:
# None against 0.2125", which reads as an engine fault. It is now refused as having no closed form.
def test_a_power_series_from_dsolve_is_refused_as_no_closed_form():
    from grader.mechanics.scene import SceneError, parse_scene
    text = _SPUN_TEXT + '''
[[answers]]
name = "rod_force_without_rdot"
prompt = "The rod's force in terms of r and t"
expr = "lambda_motor/r"
in_terms_of = ["m", "omega0", "alpha", "r", "t", "r0"]
dimension = "force"
'''
    with pytest.raises(SceneError) as refused:
        derive(parse_scene(text, source="spun.toml"))
    message = str(refused.value)
    assert "energy is not conserved" in message and "truncated power series" in message, message
    assert "O(t" not in message and "disagrees" not in message, message


# -- Found and fixed: a special value along a motion that leaves a coordinate at rest ----------------------
# The swinging Atwood machine released from rest with its bob hanging straight down (θ0 = 0, θ̇0 = 0, where
# θ̈ = −(g sin θ + 2 ṙ θ̇)/r vanishes) is a plain Atwood machine: r̈ = g (m − M)/(M + m), so from r0 = 1 m
# ṙ² = 2 g (m − M)(r − r0)/(M + m). Its ṙ² where r = L/4 was refused ('it still depends on theta,
# thetadot'): the energy that removes ṙ holds m r² θ̇² and m g r cos θ. Extremes already took such
# coordinates at their start (the elastic pendulum hanging straight down); special values along the motion
# now do too. Released tilted (θ0 = 1), θ moves, and the answer is still refused.
_ATWOOD_TEXT = (SCENES / "swinging_atwood.toml").read_text() + '''
[[answers]]
name = "speed_squared_at_quarter"
prompt = "The square of the rate r changes at when r = L/4"
expr = "rdot^2"
where = "r = L/4"
in_terms_of = ["M", "m", "g", "L"]
'''


def test_a_special_value_along_a_motion_that_leaves_a_coordinate_at_rest():
    from grader.mechanics.scene import parse_scene
    text = _ATWOOD_TEXT.replace("theta = 1.0\n", "theta = 0\n", 1)
    derivation = derive(parse_scene(text, source="atwood.toml"))
    for point in ({"M": 1.2, "m": 1.0, "g": 9.81, "L": 2.0}, {"M": 0.3, "m": 0.7, "g": 1.6, "L": 7.0}):
        expected = 2 * point["g"] * (point["m"] - point["M"]) * (point["L"] / 4 - 1.0) / (point["M"] + point["m"])
        assert at(derivation, derivation.answers["speed_squared_at_quarter"], point) == pytest.approx(expected, rel=1e-12)


def test_a_special_value_along_a_motion_in_which_the_other_coordinate_moves_is_still_refused():
    from grader.mechanics.scene import SceneError, parse_scene
    with pytest.raises(SceneError, match="still depends on theta, thetadot"):
        derive(parse_scene(_ATWOOD_TEXT, source="atwood.toml"))
