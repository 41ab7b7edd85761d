"""The numerical experiment against closed forms derived by hand.

Each case is a textbook system written as plain callables (no engine, no sympy). Along the
integrated motion the multipliers, reaction forces and accelerations of the KKT system must
match the hand-derived closed forms to 1e-6 relative, the tolerance the grader relies on when it
confirms the symbolic engine (``test_problems_confirmed.py``). Forces near zero are compared
against the case's natural scale (e.g. m g) instead of their own size.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import mpmath
import numpy as np
import pytest

from grader.simulate.constrained import (
    Event,
    NumericConstraint,
    NumericScene,
    Snapshot,
    multiplier_zero,
    simulate,
)
from grader.simulate.lagrangian_numeric import constraint_terms
from grader.simulate.manifold import ConstraintViolation, project_velocities

RTOL = 1e-6
G = 9.81


@dataclass
class Case:
    """A system, a consistent start, and its hand-derived closed forms at a snapshot."""

    scene: NumericScene
    q0: list[float]
    qdot0: list[float]
    sample_times: list[float]
    # snapshot -> [(what, numeric value, closed form, natural scale of the quantity)]
    closed_forms: Callable[[Snapshot], list[tuple[str, float, float, float]]]
    # (t, q, qdot) -> a quantity conserved along the motion (energy or Jacobi integral)
    invariant: Callable[[float, np.ndarray, np.ndarray], float]


def mechanical_energy(scene: NumericScene) -> Callable:
    def energy(t, q, v):
        with mpmath.workdps(30):
            q, v = [mpmath.mpf(x) for x in q], [mpmath.mpf(x) for x in v]
            return float(scene.kinetic(q, v, t) + scene.potential(q, t))
    return energy


# -- pendulum in Cartesian coordinates -------------------------------------------------------------
def pendulum_scene(m: float, l: float) -> NumericScene:
    return NumericScene(
        ("x", "y"),
        kinetic=lambda q, v, t: m / 2 * (v[0] ** 2 + v[1] ** 2),
        potential=lambda q, t: m * G * q[1],
        constraints=(NumericConstraint("string", lambda q, t: q[0] ** 2 + q[1] ** 2 - l ** 2, unilateral=True),),
    )


def pendulum_angle(s: Snapshot, l: float) -> tuple[float, float, float]:
    """θ from the downward vertical, θ̇ and θ̈ from the Cartesian state."""
    x, y = s.q
    vx, vy = s.qdot
    ax, ay = s.qddot
    return math.atan2(x, -y), (x * vy - y * vx) / l ** 2, (x * ay - y * ax) / l ** 2


def pendulum(m=0.7, l=1.5, theta0=0.3, omega0=1.2) -> Case:
    scene = pendulum_scene(m, l)

    def closed_forms(s):
        theta, omega, alpha = pendulum_angle(s, l)
        # The string pulls inward: Q = λ ∇f = 2 λ (x, y), so the tension is -2 l λ.
        return [("tension", -2 * l * s.multiplier("string"), m * l * omega ** 2 + m * G * math.cos(theta), m * G),
                ("thetaddot", alpha, -G / l * math.sin(theta), G / l)]

    return Case(scene, [l * math.sin(theta0), -l * math.cos(theta0)],
                [l * omega0 * math.cos(theta0), l * omega0 * math.sin(theta0)],
                [0.0, 0.4, 1.1, 2.5], closed_forms, mechanical_energy(scene))


# -- bead on a sphere, polar coordinates (r, θ), from (nearly) rest at the top ----------------------
PUSH = 1e-6  # θ̇0: leaves the unstable top; all closed forms below include its energy exactly.


def sphere_scene(m: float, R: float) -> NumericScene:
    return NumericScene(
        ("r", "theta"),
        kinetic=lambda q, v, t: m / 2 * (v[0] ** 2 + q[0] ** 2 * v[1] ** 2),
        potential=lambda q, t: m * G * q[0] * mpmath.cos(q[1]),
        constraints=(NumericConstraint("surface", lambda q, t: q[0] - R, unilateral=True),),
    )


def sphere(m=1.3, R=0.8) -> Case:
    scene = sphere_scene(m, R)

    def closed_forms(s):
        c = math.cos(s.coordinate("theta"))
        # Energy: R θ̇² = 2 g (1 - cos θ) + R θ̇0²; radial Newton: λ = m g cos θ - m R θ̇².
        normal = m * G * (3 * c - 2) - m * R * PUSH ** 2
        return [("normal force", s.multiplier("surface"), normal, m * G),
                ("normal force from rest", s.force("surface", "r"), m * G * (3 * c - 2), m * G)]

    return Case(scene, [R, 0.0], [0.0, PUSH], [1.0, 3.0, 3.6], closed_forms, mechanical_energy(scene))


# -- half-Atwood machine ---------------------------------------------------------------------------
def half_atwood(m1=2.0, m2=0.5) -> Case:
    # x1: block on the table toward the pulley; y2: hanging mass, downward. String: x1 = y2.
    scene = NumericScene(
        ("x1", "y2"),
        kinetic=lambda q, v, t: m1 / 2 * v[0] ** 2 + m2 / 2 * v[1] ** 2,
        potential=lambda q, t: -m2 * G * q[1],
        constraints=(NumericConstraint("string", lambda q, t: q[0] - q[1]),),
    )

    def closed_forms(s):
        # Q_x1 = λ pulls the block toward the pulley: λ is the tension.
        return [("tension", s.multiplier("string"), m1 * m2 * G / (m1 + m2), m2 * G),
                ("tension on hanging mass", -s.force("string", "y2"), m1 * m2 * G / (m1 + m2), m2 * G),
                ("acceleration", s.acceleration("x1"), m2 * G / (m1 + m2), G)]

    return Case(scene, [0.0, 0.0], [0.3, 0.3], [0.0, 0.5, 1.0], closed_forms, mechanical_energy(scene))


# -- yo-yo (uniform disc unwinding from a fixed string) -------------------------------------------
def yoyo(m=0.25, R=0.04) -> Case:
    # s: centre's drop, phi: rotation. The engine's convention f = R φ - s: Q_s = -λ is the upward
    # string force on the centre, so λ is the tension.
    scene = NumericScene(
        ("s", "phi"),
        kinetic=lambda q, v, t: m / 2 * v[0] ** 2 + m * R ** 2 / 4 * v[1] ** 2,
        potential=lambda q, t: -m * G * q[0],
        constraints=(NumericConstraint("unwind", lambda q, t: R * q[1] - q[0]),),
    )

    def closed_forms(s):
        return [("tension", s.multiplier("unwind"), m * G / 3, m * G),
                ("torque of the string", s.force("unwind", "phi"), m * G * R / 3, m * G * R),
                ("acceleration", s.acceleration("s"), 2 * G / 3, G)]

    return Case(scene, [0.0, 0.0], [0.0, 0.0], [0.2, 0.6], closed_forms, mechanical_energy(scene))


# -- body rolling down an incline: two constraints (contact and rolling) --------------------------
def rolling(beta: float, alpha=0.5, m=2.0, R=0.3) -> Case:
    # x down the slope, y the centre's height above the slope, phi the rolling angle; I = β m R².
    scene = NumericScene(
        ("x", "y", "phi"),
        kinetic=lambda q, v, t: m / 2 * (v[0] ** 2 + v[1] ** 2) + beta * m * R ** 2 / 2 * v[2] ** 2,
        potential=lambda q, t: -m * G * q[0] * math.sin(alpha) + m * G * q[1] * math.cos(alpha),
        constraints=(NumericConstraint("contact", lambda q, t: q[1] - R, unilateral=True),
                     NumericConstraint("roll", lambda q, t: q[0] - R * q[2])),
    )

    def closed_forms(s):
        # Q_x = λ_roll is the friction along +x (down the slope): friction up the slope is -λ_roll.
        return [("acceleration", s.acceleration("x"), G * math.sin(alpha) / (1 + beta), G),
                ("friction", -s.multiplier("roll"), beta * m * G * math.sin(alpha) / (1 + beta), m * G),
                ("normal force", s.multiplier("contact"), m * G * math.cos(alpha), m * G)]

    return Case(scene, [0.0, R, 0.0], [1.0, 0.0, 1.0 / R], [0.0, 0.7], closed_forms, mechanical_energy(scene))


# -- bead on a hoop turning about the vertical at ω: rheonomic plane constraint --------------------
def hoop(m=0.2, R=0.5, omega=7.0, theta0=0.4, thetadot0=0.5) -> Case:
    # Cartesian (x, y, z); on the sphere of radius R and in the plane through the z axis at angle ωt.
    scene = NumericScene(
        ("x", "y", "z"),
        kinetic=lambda q, v, t: m / 2 * (v[0] ** 2 + v[1] ** 2 + v[2] ** 2),
        potential=lambda q, t: m * G * q[2],
        constraints=(NumericConstraint("hoop", lambda q, t: q[0] ** 2 + q[1] ** 2 + q[2] ** 2 - R ** 2),
                     NumericConstraint("plane", lambda q, t: -q[0] * mpmath.sin(omega * t)
                                       + q[1] * mpmath.cos(omega * t))),
    )

    def angle(t, q, v):
        """θ from the downward vertical and θ̇, from the in-plane horizontal coordinate ρ."""
        c, s = math.cos(omega * t), math.sin(omega * t)
        rho, rhodot = q[0] * c + q[1] * s, v[0] * c + v[1] * s  # ρ̇: the plane's f = 0 drops ω f
        return math.atan2(rho, -q[2]), (-q[2] * rhodot + rho * v[2]) / R ** 2, rho, rhodot

    def closed_forms(s):
        theta, thetadot, rho, rhodot = angle(s.t, s.q, s.qdot)
        c, sn = math.cos(omega * s.t), math.sin(omega * s.t)
        rhoddot = s.qddot[0] * c + s.qddot[1] * sn + omega * (-s.qdot[0] * sn + s.qdot[1] * c)
        thetaddot = (-s.q[2] * rhoddot + rho * s.qddot[2]) / R ** 2
        # Inertial Newton in cylindrical components: along the hoop's radius
        # -2 λ_hoop R = m R (θ̇² + ω² sin²θ) + m g cos θ; across the plane λ_plane = 2 m ω ρ̇.
        return [("thetaddot", thetaddot, math.sin(theta) * (omega ** 2 * math.cos(theta) - G / R), omega ** 2),
                ("hoop normal force", -2 * R * s.multiplier("hoop"),
                 m * R * (thetadot ** 2 + omega ** 2 * math.sin(theta) ** 2) + m * G * math.cos(theta), m * G),
                ("force across the plane", s.multiplier("plane"), 2 * m * omega * R * math.cos(theta) * thetadot,
                 m * G)]

    def jacobi(t, q, v):
        # Energy is not conserved (the hoop is driven), h = T_rel - ½ m ω² ρ² + V is.
        theta, thetadot, rho, _ = angle(t, q, v)
        return m * R ** 2 / 2 * thetadot ** 2 - m * omega ** 2 * rho ** 2 / 2 - m * G * R * math.cos(theta)

    rho0 = R * math.sin(theta0)
    return Case(scene, [rho0, 0.0, -R * math.cos(theta0)],
                [R * math.cos(theta0) * thetadot0, omega * rho0, R * math.sin(theta0) * thetadot0],
                [0.0, 0.4, 1.0], closed_forms, jacobi)


# -- double pendulum in Cartesian coordinates ----------------------------------------------------
def double_pendulum(m1=1.0, m2=0.6, l1=1.0, l2=0.7, angles=(0.9, -0.5), rates=(0.4, 1.5)) -> Case:
    scene = NumericScene(
        ("x1", "y1", "x2", "y2"),
        kinetic=lambda q, v, t: m1 / 2 * (v[0] ** 2 + v[1] ** 2) + m2 / 2 * (v[2] ** 2 + v[3] ** 2),
        potential=lambda q, t: m1 * G * q[1] + m2 * G * q[3],
        constraints=(NumericConstraint("rod1", lambda q, t: q[0] ** 2 + q[1] ** 2 - l1 ** 2),
                     NumericConstraint("rod2", lambda q, t: (q[2] - q[0]) ** 2 + (q[3] - q[1]) ** 2 - l2 ** 2)),
    )

    def closed_forms(s):
        x1, y1, x2, y2 = s.q
        vx1, vy1, vx2, vy2 = s.qdot
        th1, th2 = math.atan2(x1, -y1), math.atan2(x2 - x1, -(y2 - y1))
        w1 = (x1 * vy1 - y1 * vx1) / l1 ** 2
        w2 = ((x2 - x1) * (vy2 - vy1) - (y2 - y1) * (vx2 - vx1)) / l2 ** 2
        d = th1 - th2
        den = 2 * m1 + m2 - m2 * math.cos(2 * d)
        # The standard angular accelerations (e.g. myphysicslab's double pendulum).
        a1 = (-G * (2 * m1 + m2) * math.sin(th1) - m2 * G * math.sin(th1 - 2 * th2)
              - 2 * math.sin(d) * m2 * (w2 ** 2 * l2 + w1 ** 2 * l1 * math.cos(d))) / (l1 * den)
        a2 = 2 * math.sin(d) * (w1 ** 2 * l1 * (m1 + m2) + G * (m1 + m2) * math.cos(th1)
                                + w2 ** 2 * l2 * m2 * math.cos(d)) / (l2 * den)
        # Newton along each rod (unit vectors e_i from the upper end to the bob):
        # T2 = m2 (g cos θ2 - a2·e2), T1 = m1 g cos θ1 + m1 l1 θ̇1² + T2 cos(θ1 - θ2).
        t2 = m2 * (G * math.cos(th2) - l1 * a1 * math.sin(th2 - th1) + l1 * w1 ** 2 * math.cos(d) + l2 * w2 ** 2)
        t1 = m1 * G * math.cos(th1) + m1 * l1 * w1 ** 2 + t2 * math.cos(d)
        alpha1 = (x1 * s.qddot[1] - y1 * s.qddot[0]) / l1 ** 2
        scale = (m1 + m2) * G
        return [("upper rod tension", -2 * l1 * s.multiplier("rod1"), t1, scale),
                ("lower rod tension", -2 * l2 * s.multiplier("rod2"), t2, scale),
                ("theta1ddot", alpha1, a1, G / l1)]

    (th1, th2), (w1, w2) = angles, rates
    x1, y1 = l1 * math.sin(th1), -l1 * math.cos(th1)
    vx1, vy1 = l1 * w1 * math.cos(th1), l1 * w1 * math.sin(th1)
    q0 = [x1, y1, x1 + l2 * math.sin(th2), y1 - l2 * math.cos(th2)]
    v0 = [vx1, vy1, vx1 + l2 * w2 * math.cos(th2), vy1 + l2 * w2 * math.sin(th2)]
    return Case(scene, q0, v0, [0.0, 0.6, 1.3], closed_forms, mechanical_energy(scene))


CASES = {
    "pendulum": pendulum,
    "sphere": sphere,
    "half-atwood": half_atwood,
    "yo-yo": yoyo,
    "rolling-sphere": lambda: rolling(2 / 5),
    "rolling-cylinder": lambda: rolling(1 / 2),
    "rolling-hoop": lambda: rolling(1.0),
    "bead-on-rotating-hoop": hoop,
    "double-pendulum": double_pendulum,
}


@pytest.fixture(scope="module", params=list(CASES))
def case_and_motion(request):
    case = CASES[request.param]()
    return case, simulate(case.scene, case.q0, case.qdot0, max(case.sample_times), sample_times=case.sample_times)


def relative_error(numeric: float, exact: float, scale: float) -> float:
    return abs(numeric - exact) / max(abs(exact), scale)


def test_multipliers_and_accelerations_match_closed_forms(case_and_motion):
    case, motion = case_and_motion
    assert [s.t for s in motion.samples] == case.sample_times
    for s in motion.samples:
        for what, numeric, exact, scale in case.closed_forms(s):
            assert relative_error(numeric, exact, scale) < RTOL, f"{what} at t = {s.t}: {numeric} vs {exact}"


def test_motion_stays_on_the_constraints_and_conserves_its_invariant(case_and_motion):
    case, motion = case_and_motion
    start = case.invariant(0.0, np.array(case.q0), np.array(case.qdot0))
    scale = max(abs(start), 1.0)
    for s in motion.samples:
        assert np.all(np.abs(s.residual) < 1e-12), f"constraint drift at t = {s.t}: {s.residual}"
        assert abs(case.invariant(s.t, s.q, s.qdot) - start) < 1e-9 * scale, f"invariant drift at t = {s.t}"


# -- events ------------------------------------------------------------------------------------
def test_bead_leaves_the_sphere_where_cos_theta_is_two_thirds():
    m, R = 1.3, 0.8
    motion = simulate(sphere_scene(m, R), [R, 0.0], [0.0, PUSH], t_end=20.0, events=[multiplier_zero("surface")])
    assert motion.stopped_by == "lambda_surface = 0"
    at = motion.first("lambda_surface = 0")
    # N = 0 where 3 cos θ - 2 = R θ̇0² / g.
    assert math.cos(at.coordinate("theta")) == pytest.approx(2 / 3 + R * PUSH ** 2 / (3 * G), rel=RTOL)
    assert abs(at.multiplier("surface")) < 1e-9 * m * G


def test_string_goes_slack_where_the_energy_balance_says():
    # From the bottom with v0² = 3.5 g l the tension m v0²/l - 2 m g + 3 m g cos θ vanishes at
    # cos θ = -1/2, before the top; the event stops the integration there, not elsewhere.
    m, l = 0.7, 1.5
    v0 = math.sqrt(3.5 * G * l)
    motion = simulate(pendulum_scene(m, l), [0.0, -l], [v0, 0.0], t_end=5.0, sample_times=[0.1, 4.0],
                      events=[multiplier_zero("string")])
    at = motion.first("lambda_string = 0")
    theta, _, _ = pendulum_angle(at, l)
    assert motion.stopped_by == "lambda_string = 0"
    assert math.cos(theta) == pytest.approx(-0.5, rel=RTOL)
    assert [s.t for s in motion.samples] == [0.1]  # the sample after the event is not reached


def test_non_terminal_events_are_all_recorded():
    # A pendulum swinging through the bottom (x = 0) twice per period.
    l, theta0 = 1.0, 0.2
    period = 2 * math.pi * math.sqrt(l / G) * (1 + theta0 ** 2 / 16)  # to the small-angle correction
    bottom = Event("bottom", lambda s: s.q[0], terminal=False)
    motion = simulate(pendulum_scene(1.0, l), [l * math.sin(theta0), -l * math.cos(theta0)], [0.0, 0.0],
                      t_end=2.2 * period, events=[bottom])
    crossings = [s.t for s in motion.events["bottom"]]
    assert len(crossings) == 4 and motion.stopped_by is None
    assert crossings[2] - crossings[0] == pytest.approx(period, rel=1e-5)


# -- initial states -----------------------------------------------------------------------------
def test_inconsistent_initial_state_is_refused():
    with pytest.raises(ConstraintViolation, match="string"):
        simulate(pendulum_scene(1.0, 1.0), [0.0, -1.1], [0.0, 0.0], t_end=1.0)


def test_rheonomic_start_is_completed_by_velocity_projection():
    # The bead at rest relative to the hoop still moves with it: ẏ = ω ρ is forced by the plane.
    case = hoop(thetadot0=0.0)
    qdot = project_velocities(case.scene, 0.0, case.q0, [0.0, 0.0, 0.0], free=[False, True, False])
    np.testing.assert_allclose(qdot, case.qdot0, atol=1e-15)


def test_periodic_projection_keeps_the_whole_trajectory_on_the_manifold():
    # Between projections f drifts only by the integration error, so every raw step, not just
    # the (projected) samples, satisfies the constraints to ~1e-13; and energy is conserved.
    case = double_pendulum(angles=(0.3, -0.2), rates=(0.0, 0.0))
    motion = simulate(case.scene, case.q0, case.qdot0, 1.5, sample_times=[1.5], projection_interval=0.25)
    drift = max(np.abs(constraint_terms(case.scene, t, q).value).max() for t, q in zip(motion.t, motion.q))
    assert drift < 1e-12
    (end,) = motion.samples
    start = case.invariant(0.0, np.array(case.q0), np.array(case.qdot0))
    assert case.invariant(end.t, end.q, end.qdot) == pytest.approx(start, rel=1e-10)
