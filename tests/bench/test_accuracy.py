"""What ``grader bench accuracy`` measures against: exact solutions, and methods that behave as theory says."""

from __future__ import annotations

import math

import numpy as np
import pytest

from grader.bench import accuracy
from grader.bench.accuracy import Curve, Point, cheapest, pendulum_exact, pendulum_period, sphere_separation

G, L = accuracy.G, accuracy.L


@pytest.mark.parametrize("theta0", [0.3, 1.5, 2.5, 3.0])
def test_elliptic_solution_conserves_energy_and_starts_at_rest(theta0):
    t = np.linspace(0.0, 7.3, 200)
    theta, omega = pendulum_exact(theta0, G, L, t)
    energy = 0.5 * L * omega ** 2 - G * np.cos(theta)
    assert theta[0] == pytest.approx(theta0, abs=1e-14) and omega[0] == pytest.approx(0.0, abs=1e-14)
    assert np.max(np.abs(energy + G * math.cos(theta0))) < 1e-11


@pytest.mark.parametrize("theta0", [0.3, 2.5])
def test_elliptic_solution_obeys_the_equation_of_motion(theta0):
    # θ̈ by central differences of the exact θ̇ equals −(g/l) sin θ.
    t, h = np.linspace(0.1, 5.0, 50), 1e-5
    _, ahead = pendulum_exact(theta0, G, L, t + h)
    _, behind = pendulum_exact(theta0, G, L, t - h)
    theta, _ = pendulum_exact(theta0, G, L, t)
    assert np.max(np.abs((ahead - behind) / (2 * h) + G / L * np.sin(theta))) < 1e-6


def test_period_is_the_small_angle_one_for_small_amplitudes_and_longer_for_large():
    assert pendulum_period(1e-4) == pytest.approx(2 * math.pi * math.sqrt(L / G), rel=1e-8)
    assert pendulum_period(2.5) > 1.3 * 2 * math.pi * math.sqrt(L / G)
    theta, _ = pendulum_exact(2.5, G, L, [pendulum_period(2.5)])
    assert theta[0] == pytest.approx(2.5, abs=1e-10)


@pytest.mark.parametrize("method", ["RK45", "DOP853", "Radau", "LSODA"])
def test_tighter_tolerances_give_smaller_errors(method):
    t_end = 3 * pendulum_period()
    loose, _ = accuracy._pendulum_adaptive(method, 1e-5, t_end)
    tight, _ = accuracy._pendulum_adaptive(method, 1e-10, t_end)
    assert tight < loose / 100


def test_yoshida_composition_is_fourth_order_and_verlet_second():
    period = pendulum_period()
    ratios = {}
    for name in accuracy.SYMPLECTIC:
        coarse, _ = accuracy._pendulum_symplectic(name, 200, period, period)
        fine, _ = accuracy._pendulum_symplectic(name, 400, period, period)
        ratios[name] = coarse / fine
    assert 3.0 < ratios["Störmer–Verlet"] < 5.0  # 2² = 4
    assert 10.0 < ratios["Yoshida 4"] < 24.0  # 2⁴ = 16


def test_stabilisation_keeps_the_cartesian_pendulum_on_its_circle():
    rows = {r["formulation"]: r for r in accuracy.drift_table(periods=30)}
    none = rows["Cartesian, none"]["constraint_drift"]
    assert none > 1e-6  # index reduction alone drifts off the circle...
    assert rows["Cartesian, baumgarte"]["constraint_drift"] < none / 1e3  # ...feedback holds it...
    assert rows["Cartesian, projection"]["constraint_drift"] < 1e-14  # ...projection puts it back exactly


def test_symplectic_energy_error_does_not_grow_where_runge_kutta_drifts():
    def energy_drift(periods):
        return {r["method"].split(",")[0].split(" tol")[0] + " " + r["formulation"]: r["energy_drift"]
                for r in accuracy.drift_table(periods=periods)}

    short, long = energy_drift(20), energy_drift(200)
    assert long["Störmer–Verlet minimal"] < 1.5 * short["Störmer–Verlet minimal"]  # bounded oscillation
    assert long["DOP853 minimal"] > 4 * short["DOP853 minimal"]  # secular growth, ~ linear in time


@pytest.mark.parametrize("method", ["DOP853", "Radau", "LSODA"])
def test_sphere_separation_is_located_at_the_exact_angle(method):
    error, _ = sphere_separation(method, 1e-11)
    assert error < 1e-9


def test_cheapest_is_the_fastest_run_that_reaches_the_target():
    def point(method, error, seconds):
        return Point("pendulum", method, "minimal", 1e-6, error, seconds, 10)

    fast_but_rough, slow_and_fine, fine_and_faster = point("a", 1e-6, 0.001), point("b", 1e-10, 0.5), point("c", 1e-9, 0.1)
    curves = [Curve("pendulum", "a", "minimal", [fast_but_rough]),
              Curve("pendulum", "b", "minimal", [slow_and_fine, fine_and_faster])]
    assert cheapest(curves, "pendulum", 1e-9) is fine_and_faster
    assert cheapest(curves, "pendulum", 1e-12) is None
