"""``grader bench accuracy``: what accuracy costs in time (work–precision diagrams) and in drift.

Every error is measured against an exact solution, never against a finer numerical run:

- **large-amplitude pendulum** (θ₀ = 2.5 rad, from rest, ten periods): θ(t) = 2 arcsin(k sn(K − ωt | k²)),
  θ̇(t) = −2kω cn(K − ωt | k²) with k = sin(θ₀/2), ω = √(g/l), K the complete elliptic integral;
  the error is the phase-space distance at the end, √(Δθ² + (Δθ̇/ω)²);
- **the same pendulum in Cartesian coordinates** (x, y, one constraint x² + y² = l²), with the constraint
  enforced at the acceleration level and stabilised in three ways: none, Baumgarte (ḟ and f fed back),
  projection (positions and velocities put back on the constraint after every step);
- **a bead leaving a sphere** released at rest from θ₀ = 0.1 rad: it leaves where cos θ = (2/3) cos θ₀;
  the error is the angle of the located event minus that value.

Methods: explicit Runge–Kutta (scipy's RK45 and DOP853), implicit (Radau), multistep (LSODA), and
symplectic fixed-step schemes where they apply (Störmer–Verlet, 2nd order; Yoshida's 4th-order
composition). Each is swept over tolerances (or step counts); one point is (run time, error).

A second table integrates 1000 periods at one tolerance and reports the constraint drift max|r − l| and
the relative energy drift of each formulation. Figures go to ``bench-results/accuracy.json``, plots to
``bench-results/accuracy-*.png`` and ``.svg``.

Examples
--------
>>> theta, omega = pendulum_exact(2.5, 9.81, 1.0, [0.0])
>>> round(float(theta[0]), 12), round(float(omega[0]), 12)
(2.5, 0.0)
"""

from __future__ import annotations

import json
import math
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Callable

import click
import numpy as np
from scipy.integrate import DOP853, solve_ivp
from scipy.special import ellipj, ellipk

__all__ = [
    "Point",
    "bench_accuracy",
    "cartesian_pendulum",
    "cheapest",
    "drift_table",
    "pendulum_exact",
    "run_sweeps",
    "sphere_separation",
]

G, L = 9.81, 1.0
THETA0 = 2.5  # rad: large enough that the small-angle period is 30 % off
SPHERE_THETA0 = 0.1
ADAPTIVE = ("RK45", "DOP853", "Radau", "LSODA")
TOLERANCES = tuple(10.0 ** -k for k in range(3, 14))
STEPS_PER_PERIOD = (25, 50, 100, 200, 400, 800, 1600, 3200, 6400)


@dataclass
class Point:
    """One run: a method, a formulation, the setting swept, its error and its cost."""

    problem: str
    method: str
    formulation: str
    setting: float  # tolerance (adaptive) or steps per period (fixed step)
    error: float
    seconds: float
    rhs_evaluations: int


@dataclass
class Curve:
    problem: str
    method: str
    formulation: str
    points: list[Point] = field(default_factory=list)

    @property
    def label(self) -> str:
        return f"{self.method} ({self.formulation})"


def pendulum_period(theta0: float = THETA0, g: float = G, l: float = L) -> float:
    """The exact period 4K(k²)/ω of a pendulum released from rest at ``theta0``."""
    return 4.0 * ellipk(math.sin(theta0 / 2) ** 2) / math.sqrt(g / l)


def pendulum_exact(theta0: float, g: float, l: float, t) -> tuple[np.ndarray, np.ndarray]:
    """θ(t) and θ̇(t) of a pendulum released from rest at ``theta0``, by Jacobi elliptic functions."""
    k = math.sin(theta0 / 2)
    omega = math.sqrt(g / l)
    u = ellipk(k * k) - omega * np.asarray(t, dtype=float)
    sn, cn, _dn, _ph = ellipj(u, k * k)
    return 2.0 * np.arcsin(k * sn), -2.0 * k * omega * cn


def _phase_error(theta: float, omega_dot: float, t: float) -> float:
    exact_theta, exact_dot = pendulum_exact(THETA0, G, L, [t])
    w = math.sqrt(G / L)
    return math.hypot(theta - exact_theta[0], (omega_dot - exact_dot[0]) / w)


def _timed(run: Callable[[], tuple[float, int]], repeat: int) -> tuple[float, float, int]:
    """Best wall time of ``repeat`` runs of ``run`` (which returns (error, evaluations))."""
    best = math.inf
    for _ in range(repeat):
        start = time.perf_counter()
        error, evaluations = run()
        best = min(best, time.perf_counter() - start)
    return error, best, evaluations


# -- minimal coordinates ---------------------------------------------------------------------------

def _pendulum_rhs(_t, y):
    return [y[1], -G / L * math.sin(y[0])]


def _pendulum_adaptive(method: str, tol: float, t_end: float) -> tuple[float, int]:
    solution = solve_ivp(_pendulum_rhs, (0.0, t_end), [THETA0, 0.0], method=method, rtol=tol, atol=tol)
    return _phase_error(solution.y[0, -1], solution.y[1, -1], t_end), solution.nfev


# Yoshida's coefficients: three Störmer–Verlet steps of sizes w1 h, w0 h, w1 h give fourth order.
_W1 = 1.0 / (2.0 - 2.0 ** (1.0 / 3.0))
_W0 = 1.0 - 2.0 * _W1


def _verlet(theta: float, omega: float, h: float, steps: int, weights: tuple[float, ...]) -> tuple[float, float]:
    """Compositions of velocity-Verlet (kick–drift–kick) steps for θ̈ = −(g/l) sin θ."""
    c = G / L
    sin = math.sin
    for _ in range(steps):
        for w in weights:
            hw = h * w
            omega -= 0.5 * hw * c * sin(theta)
            theta += hw * omega
            omega -= 0.5 * hw * c * sin(theta)
    return theta, omega


SYMPLECTIC = {"Störmer–Verlet": (1.0,), "Yoshida 4": (_W1, _W0, _W1)}


def _pendulum_symplectic(name: str, steps_per_period: int, t_end: float, period: float) -> tuple[float, int]:
    steps = max(1, round(steps_per_period * t_end / period))
    weights = SYMPLECTIC[name]
    theta, omega = _verlet(THETA0, 0.0, t_end / steps, steps, weights)
    return _phase_error(theta, omega, t_end), 2 * steps * len(weights)


# -- Cartesian coordinates with one constraint ---------------------------------------------------

def cartesian_pendulum(stabilisation: str, alpha: float = 10.0):
    """The right-hand side of the Cartesian pendulum (x, y, ẋ, ẏ), unit mass, constraint x² + y² = l².

    The multiplier comes from the twice-differentiated constraint J q̈ = −|q̇|² (index reduction);
    ``"baumgarte"`` adds −2α ḟ − α² f to it (critically damped feedback of the drift).
    """
    baumgarte = stabilisation == "baumgarte"

    def rhs(_t, s):
        x, y, vx, vy = s
        rr = x * x + y * y
        target = -(vx * vx + vy * vy)
        if baumgarte:
            f = 0.5 * (rr - L * L)
            fdot = x * vx + y * vy
            target -= 2.0 * alpha * fdot + alpha * alpha * f
        # J (F + Jᵀ λ) = target with F = (0, −g), J = (x, y)
        lam = (target + G * y) / rr
        return [vx, vy, lam * x, -G + lam * y]

    return rhs


def _cartesian_start() -> list[float]:
    return [L * math.sin(THETA0), -L * math.cos(THETA0), 0.0, 0.0]


def _project(s: np.ndarray) -> np.ndarray:
    """Put a Cartesian pendulum state back on r = l and on the tangent (ṙ = 0)."""
    x, y, vx, vy = s
    r = math.hypot(x, y)
    x, y = x * L / r, y * L / r
    radial = (x * vx + y * vy) / (L * L)
    return np.array([x, y, vx - radial * x, vy - radial * y])


def _integrate_projected(rhs, start, t_end: float, tol: float,
                         observe: Callable[[np.ndarray], None] | None = None) -> tuple[np.ndarray, int]:
    """DOP853 step by step, projecting after every accepted step (the stepper then restarts its
    first-same-as-last stage from the projected state, so no step uses an unprojected slope).
    ``observe`` sees every projected state."""
    solver = DOP853(rhs, 0.0, np.array(start, dtype=float), t_end, rtol=tol, atol=tol)
    evaluations = 0
    while solver.status == "running":
        solver.step()
        solver.y = _project(solver.y)
        solver.f = np.asarray(rhs(solver.t, solver.y))
        evaluations += 1
        if observe is not None:
            observe(solver.y)
    return solver.y, solver.nfev + evaluations


def _cartesian_state_error(s, t_end: float) -> float:
    x, y, vx, vy = s
    theta = math.atan2(x, -y)
    omega = (x * vy - y * vx) / (x * x + y * y)
    return _phase_error(theta, omega, t_end)


def _pendulum_cartesian(stabilisation: str, tol: float, t_end: float) -> tuple[float, int]:
    rhs = cartesian_pendulum(stabilisation)
    if stabilisation == "projection":
        state, evaluations = _integrate_projected(rhs, _cartesian_start(), t_end, tol)
        return _cartesian_state_error(state, t_end), evaluations
    solution = solve_ivp(rhs, (0.0, t_end), _cartesian_start(), method="DOP853", rtol=tol, atol=tol)
    return _cartesian_state_error(solution.y[:, -1], t_end), solution.nfev


# -- a bead leaving a sphere -----------------------------------------------------------------------

def _sphere_rhs(_t, y):
    return [y[1], G / L * math.sin(y[0])]


def _normal_force(_t, y):
    # N/m = g cos θ − R θ̇²: the contact pushes while this is positive.
    return G * math.cos(y[0]) - L * y[1] ** 2


_normal_force.terminal = True
_normal_force.direction = -1


def sphere_separation(method: str, tol: float) -> tuple[float, int]:
    """Error of the located separation angle of a bead released at rest from θ₀ on a sphere."""
    exact = math.acos(2.0 / 3.0 * math.cos(SPHERE_THETA0))
    solution = solve_ivp(_sphere_rhs, (0.0, 10.0), [SPHERE_THETA0, 0.0], method=method, rtol=tol, atol=tol,
                         events=_normal_force)
    if not solution.t_events[0].size:
        return math.inf, solution.nfev
    return abs(solution.y_events[0][0][0] - exact), solution.nfev


# -- sweeps, tables, plots -------------------------------------------------------------------------

def run_sweeps(tolerances=TOLERANCES, steps_per_period=STEPS_PER_PERIOD, periods: float = 10.0,
               repeat: int = 3) -> list[Curve]:
    """Every (problem, method, formulation) curve of the work–precision diagrams."""
    period = pendulum_period()
    t_end = periods * period
    curves: list[Curve] = []

    def sweep(curve: Curve, settings, run) -> None:
        for setting in settings:
            error, seconds, evaluations = _timed(lambda: run(setting), repeat)
            curve.points.append(Point(curve.problem, curve.method, curve.formulation, setting,
                                      max(error, 1e-17), seconds, evaluations))
        curves.append(curve)

    for method in ADAPTIVE:
        sweep(Curve("pendulum", method, "minimal"), tolerances,
              lambda tol, m=method: _pendulum_adaptive(m, tol, t_end))
    for name in SYMPLECTIC:
        sweep(Curve("pendulum", name, "minimal"), steps_per_period,
              lambda n, s=name: _pendulum_symplectic(s, n, t_end, period))
    for stabilisation in ("none", "baumgarte", "projection"):
        sweep(Curve("pendulum", "DOP853", f"Cartesian, {stabilisation}"), tolerances,
              lambda tol, s=stabilisation: _pendulum_cartesian(s, tol, t_end))
    for method in ADAPTIVE:
        sweep(Curve("sphere", method, "minimal, event"), tolerances,
              lambda tol, m=method: sphere_separation(m, tol))
    return curves


def cheapest(curves: list[Curve], problem: str, target: float) -> Point | None:
    """The fastest run of ``problem`` whose error is at most ``target`` (None if no run reaches it)."""
    reached = [p for c in curves if c.problem == problem for p in c.points if p.error <= target]
    return min(reached, key=lambda p: p.seconds, default=None)


def _energy(s) -> float:
    x, y, vx, vy = s
    return 0.5 * (vx * vx + vy * vy) + G * y


def drift_table(periods: int = 1000, tol: float = 1e-8) -> list[dict]:
    """Constraint and energy drift of each formulation over ``periods`` periods at one tolerance."""
    period = pendulum_period()
    t_end = periods * period
    e0 = _energy(_cartesian_start())
    rows = []
    samples = np.linspace(0.0, t_end, 20 * periods + 1)

    def cartesian_row(stabilisation: str) -> dict:
        rhs = cartesian_pendulum(stabilisation)
        start = time.perf_counter()
        if stabilisation == "projection":
            worst = [0.0, 0.0]

            def observe(state):
                worst[0] = max(worst[0], abs(math.hypot(state[0], state[1]) - L))
                worst[1] = max(worst[1], abs(_energy(state) - e0))

            _integrate_projected(rhs, _cartesian_start(), t_end, tol, observe)
            seconds = time.perf_counter() - start
            r_drift, e_drift = worst[0], worst[1] / abs(e0)
        else:
            solution = solve_ivp(rhs, (0.0, t_end), _cartesian_start(), method="DOP853", rtol=tol, atol=tol,
                                 t_eval=samples)
            seconds = time.perf_counter() - start
            r_drift = float(np.max(np.abs(np.hypot(solution.y[0], solution.y[1]) - L)))
            e_drift = float(np.max(np.abs([_energy(s) - e0 for s in solution.y.T]))) / abs(e0)
        return {"formulation": f"Cartesian, {stabilisation}", "method": f"DOP853 tol {tol:g}",
                "constraint_drift": r_drift, "energy_drift": e_drift, "seconds": seconds}

    for stabilisation in ("none", "baumgarte", "projection"):
        rows.append(cartesian_row(stabilisation))
    e_min = -G * L * math.cos(THETA0)

    start = time.perf_counter()
    solution = solve_ivp(_pendulum_rhs, (0.0, t_end), [THETA0, 0.0], method="DOP853", rtol=tol, atol=tol,
                         t_eval=samples)
    seconds = time.perf_counter() - start
    energy = 0.5 * L * L * solution.y[1] ** 2 - G * L * np.cos(solution.y[0])
    rows.append({"formulation": "minimal", "method": f"DOP853 tol {tol:g}", "constraint_drift": 0.0,
                 "energy_drift": float(np.max(np.abs(energy - e_min))) / abs(e_min), "seconds": seconds})
    for name, weights in SYMPLECTIC.items():
        h = period / 200
        theta, omega, worst = THETA0, 0.0, 0.0
        start = time.perf_counter()
        for _ in range(20 * periods):  # the energy is read 20 times a period, as for the others
            theta, omega = _verlet(theta, omega, h, 10, weights)
            worst = max(worst, abs(0.5 * L * L * omega ** 2 - G * L * math.cos(theta) - e_min))
        seconds = time.perf_counter() - start
        rows.append({"formulation": "minimal", "method": f"{name}, 200 steps/period", "constraint_drift": 0.0,
                     "energy_drift": worst / abs(e_min), "seconds": seconds})
    return rows


def _plot(curves: list[Curve], problem: str, title: str, out_dir: Path) -> list[Path]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(figsize=(7.5, 5.0))
    for curve in (c for c in curves if c.problem == problem):
        points = sorted(curve.points, key=lambda p: p.seconds)
        axes.loglog([p.seconds * 1e3 for p in points], [p.error for p in points], marker="o", markersize=3,
                    label=curve.label)
    axes.axhline(1e-9, color="grey", linestyle=":", linewidth=1)
    axes.set_xlabel("run time (ms)")
    axes.set_ylabel("error against the exact solution")
    axes.set_title(title)
    axes.grid(True, which="major", alpha=0.3)
    axes.legend(fontsize=8)
    figure.tight_layout()
    written = []
    for suffix in ("png", "svg"):
        path = out_dir / f"accuracy-{problem}.{suffix}"
        figure.savefig(path, dpi=110)
        written.append(path)
    plt.close(figure)
    return written


def _table(curves: list[Curve], targets=(1e-6, 1e-9)) -> list[str]:
    lines = [f"{'problem':9} {'method (formulation)':34} {'best error':>10} "
             + " ".join(f"{'ms to ' + format(t, '.0e'):>12}" for t in targets)]
    lines.append("-" * len(lines[0]))
    for curve in curves:
        best = min(p.error for p in curve.points)
        cells = []
        for target in targets:
            reached = [p for p in curve.points if p.error <= target]
            cells.append(f"{min(p.seconds for p in reached) * 1e3:12.2f}" if reached else f"{'—':>12}")
        lines.append(f"{curve.problem:9} {curve.label:34} {best:10.1e} " + " ".join(cells))
    return lines


@click.command("accuracy")
@click.option("--out-dir", default="bench-results", show_default=True, type=click.Path(file_okay=False))
@click.option("--repeat", default=3, show_default=True, help="Repetitions per point (best time kept).")
@click.option("--periods", default=1000, show_default=True, help="Periods for the drift table.")
@click.option("--quick", is_flag=True, help="Fewer points and 50 drift periods (a smoke run).")
def bench_accuracy(out_dir: str, repeat: int, periods: int, quick: bool) -> None:
    """Work–precision diagrams against exact solutions, and drift over many periods."""
    started = time.perf_counter()
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    tolerances = TOLERANCES[::3] if quick else TOLERANCES
    steps = STEPS_PER_PERIOD[::3] if quick else STEPS_PER_PERIOD
    curves = run_sweeps(tolerances, steps, repeat=1 if quick else repeat)
    for line in _table(curves):
        click.echo(line)
    click.echo("")
    summary = {}
    for problem in ("pendulum", "sphere"):
        for target in (1e-6, 1e-9):
            best = cheapest(curves, problem, target)
            summary[f"{problem} {target:.0e}"] = asdict(best) if best else None
            click.echo(f"cheapest to reach {target:.0e} on the {problem}: "
                       + (f"{best.method} ({best.formulation}) at setting {best.setting:g}, "
                          f"{best.seconds * 1e3:.2f} ms" if best else "no method"))
    drift_periods = 50 if quick else periods
    rows = drift_table(drift_periods)
    click.echo("")
    click.echo(f"drift over {drift_periods} periods of the θ₀ = {THETA0} rad pendulum")
    header = f"{'formulation':24} {'method':32} {'max |r − l|':>12} {'energy drift':>13} {'seconds':>8}"
    click.echo(header)
    click.echo("-" * len(header))
    for row in rows:
        click.echo(f"{row['formulation']:24} {row['method']:32} {row['constraint_drift']:12.1e} "
                   f"{row['energy_drift']:13.1e} {row['seconds']:8.2f}")
    plots = _plot(curves, "pendulum", f"Large-amplitude pendulum (θ₀ = {THETA0} rad), 10 periods", out)
    plots += _plot(curves, "sphere", f"Bead leaving a sphere: separation angle (θ₀ = {SPHERE_THETA0} rad)", out)
    figures = {"curves": [{"problem": c.problem, "method": c.method, "formulation": c.formulation,
                           "points": [asdict(p) for p in c.points]} for c in curves],
               "cheapest": summary, "drift": {"periods": drift_periods, "rows": rows},
               "seconds": time.perf_counter() - started}
    (out / "accuracy.json").write_text(json.dumps(figures, indent=2))
    click.echo("")
    click.echo(f"plots: {', '.join(str(p) for p in plots)}; figures: {out / 'accuracy.json'} "
               f"({figures['seconds']:.0f} s)")
