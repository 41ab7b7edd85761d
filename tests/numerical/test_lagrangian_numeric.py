"""The numerical Lagrangian terms against derivatives worked out by hand.

Each case is a system whose mass matrix, generalized force or constraint terms are known in
closed form; the finite differences at 40 digits must reproduce them to double precision.
"""

import math

import mpmath
import numpy as np
import pytest

from grader.simulate.lagrangian_numeric import (
    NumericConstraint,
    NumericScene,
    constraint_terms,
    lagrangian_terms,
    snapshot,
)

M_, OMEGA = 1.7, 0.9


def rotating_frame() -> NumericScene:
    # A free particle seen from axes turning at ω: T has terms linear in q̇ (Coriolis).
    return NumericScene(("x", "y"),
                        lambda q, v, t: M_ / 2 * ((v[0] - OMEGA * q[1]) ** 2 + (v[1] + OMEGA * q[0]) ** 2),
                        lambda q, t: 0)


def growing_mass() -> NumericScene:
    # T depends on t explicitly: d/dt(m(t) v) = m v̇ + ṁ v, so the force has -ṁ v = -2 t v.
    return NumericScene(("z",), lambda q, v, t: (1 + t ** 2) * v[0] ** 2 / 2, lambda q, t: 0)


def test_rotating_frame_gives_coriolis_and_centrifugal_forces():
    x, y, vx, vy = 0.3, -1.1, 0.7, 2.0
    terms = lagrangian_terms(rotating_frame(), 0.0, [x, y], [vx, vy])
    np.testing.assert_allclose(terms.mass, M_ * np.eye(2), rtol=1e-14, atol=1e-15)
    # Force = 2 m ω (ẏ, -ẋ) + m ω² (x, y), the textbook fictitious forces.
    expected = [2 * M_ * OMEGA * vy + M_ * OMEGA ** 2 * x, -2 * M_ * OMEGA * vx + M_ * OMEGA ** 2 * y]
    np.testing.assert_allclose(terms.force, expected, rtol=1e-14)


def test_explicit_time_dependence_of_kinetic_energy_enters_the_force():
    terms = lagrangian_terms(growing_mass(), 1.5, [0.0], [2.0])
    assert terms.mass[0, 0] == pytest.approx(1 + 1.5 ** 2, rel=1e-15)
    assert terms.force[0] == pytest.approx(-2 * 1.5 * 2.0, rel=1e-14)


def test_double_pendulum_mass_matrix_in_angles():
    # M = [[(m1+m2) l1², m2 l1 l2 cos(θ1-θ2)], [.., m2 l2²]]: off-diagonal terms by polarization.
    m1, m2, l1, l2 = 1.0, 2.0, 0.5, 0.8
    scene = NumericScene(
        ("theta1", "theta2"),
        lambda q, v, t: ((m1 + m2) / 2 * l1 ** 2 * v[0] ** 2 + m2 / 2 * l2 ** 2 * v[1] ** 2
                         + m2 * l1 * l2 * v[0] * v[1] * mpmath.cos(q[0] - q[1])),
        lambda q, t: 0)
    terms = lagrangian_terms(scene, 0.0, [0.4, -0.3], [1.0, 2.0])
    c = m2 * l1 * l2 * math.cos(0.7)
    np.testing.assert_allclose(terms.mass, [[(m1 + m2) * l1 ** 2, c], [c, m2 * l2 ** 2]], rtol=1e-14)


def test_rheonomic_constraint_bias_and_rate():
    # A ring of radius 1 whose centre moves as (t², 0): f = (x - t²)² + y² - 1.
    # f̈ - J q̈ = 2 (ẋ - 2t)² - 4 (x - t²) + 2 ẏ²  and  ∂f/∂t = -4 t (x - t²).
    scene = NumericScene(("x", "y"), lambda q, v, t: (v[0] ** 2 + v[1] ** 2) / 2, lambda q, t: 0,
                         (NumericConstraint("ring", lambda q, t: (q[0] - t ** 2) ** 2 + q[1] ** 2 - 1),))
    t, x, y, vx, vy = 0.7, 0.9, 0.6, -0.4, 1.3
    terms = constraint_terms(scene, t, [x, y], [vx, vy])
    np.testing.assert_allclose(terms.jacobian, [[2 * (x - t ** 2), 2 * y]], rtol=1e-14)
    assert terms.rate[0] == pytest.approx(-4 * t * (x - t ** 2), rel=1e-14)
    assert terms.bias[0] == pytest.approx(2 * (vx - 2 * t) ** 2 - 4 * (x - t ** 2) + 2 * vy ** 2, rel=1e-13)


def test_machine_float_callables_are_rejected():
    # math.cos silently drops to 16 digits, which would ruin the second differences.
    scene = NumericScene(("theta",), lambda q, v, t: v[0] ** 2 / 2, lambda q, t: -9.81 * math.cos(q[0]))
    with pytest.raises(TypeError, match="mpmath"):
        snapshot(scene, 0.0, [0.1], [0.0])


def test_redundant_constraints_make_the_kkt_system_singular():
    scene = NumericScene(("x", "y"), lambda q, v, t: (v[0] ** 2 + v[1] ** 2) / 2, lambda q, t: 0,
                         (NumericConstraint("a", lambda q, t: q[0]), NumericConstraint("b", lambda q, t: 2 * q[0])))
    with pytest.raises(np.linalg.LinAlgError):
        snapshot(scene, 0.0, [0.0, 0.0], [0.0, 1.0])
