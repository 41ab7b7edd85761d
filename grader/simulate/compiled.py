"""A scene's equations of motion compiled to numpy: the fast numerics of ``grader simulate``.

From the scene's own T, V and constraints f (as the scene loader parsed them) this module builds,
once and symbolically, the pieces of the constrained Euler–Lagrange equations

    M(q, t) q̈ − Jᵀ λ = F(q, q̇, t),        J q̈ + b(q, q̇, t) = 0,

with M = ∂²T/∂q̇∂q̇, F = ∂L/∂q − (∂p/∂q) q̇ − ∂p/∂t (p = ∂L/∂q̇), J = ∂f/∂q and b the rest of f̈
(f̈ = J q̈ + b; the time derivatives are the engine's chain rule,
:func:`grader.mechanics.lagrange.time_derivative`). They are compiled with ``sympy.lambdify`` to
one numpy function with common subexpressions shared, so one evaluation costs microseconds. The
KKT solve for (q̈, λ) is numeric, per step, over whichever constraints are active: that is what
lets :mod:`grader.simulate.trajectory` switch contacts on and off without compiling again.

The expressions compiled here were built by our whitelist parser from a validated scene (never
from raw text), so compiling lambdify's generated code is safe.

Examples
--------
A bob on a rigid rod in Cartesian coordinates (``problems/pendulum.toml``), at θ = 0.6 at rest:
the tension 2 l λ is m g cos θ.

>>> import math
>>> from grader.mechanics.scene import load_scene
>>> scene = load_scene("problems/pendulum.toml")
>>> compiled = CompiledScene(scene, parameter_values(scene))
>>> l, theta = 1.2, 0.6
>>> q, qdot = [l * math.sin(theta), -l * math.cos(theta)], [0.0, 0.0]
>>> qddot, lam = compiled.accelerations(0.0, q, qdot)
>>> round(float(2 * l * lam[0] / (0.5 * 9.81 * math.cos(theta))), 12)
1.0
"""

from __future__ import annotations

import math
from typing import Mapping, Sequence

import numpy as np
import sympy
from scipy.linalg.lapack import dgesv as _dgesv

from grader.mechanics.lagrange import time_derivative

__all__ = ["CompiledScene", "SingularDynamics", "kkt_solve", "parameter_values"]


class SingularDynamics(ValueError):
    """The equations of motion cannot be solved for q̈ and λ at some state (no mass, redundant
    constraints, or a coordinate singularity)."""


def parameter_values(scene, overrides: Mapping[str, float] | None = None) -> dict[str, float]:
    """Each parameter's number: ``overrides`` first, then ``value`` from the scene file.

    Raises
    ------
    KeyError
        With a one-line message, for an override of an unknown name or a parameter with no number.

    Examples
    --------
    >>> from grader.mechanics.scene import load_scene
    >>> parameter_values(load_scene("problems/sphere.toml"), {"R": 2.0})
    {'m': 0.2, 'g': 9.81, 'R': 2.0}
    """
    overrides = dict(overrides or {})
    unknown = sorted(set(overrides) - set(scene.parameters))
    if unknown:
        known = ", ".join(scene.parameters) or "none"
        raise KeyError(f"{scene.source}: no parameter named {', '.join(unknown)} (parameters: {known})")
    values = {}
    for name, parameter in scene.parameters.items():
        value = overrides.get(name, parameter.value)
        if value is None:
            raise KeyError(f"{scene.source}: parameter '{name}' has no value; give one with --set {name}=...")
        values[name] = float(value)
    return values


def _compile(arguments: Sequence[sympy.Symbol], expressions: Sequence[sympy.Expr]):
    # Dummy argument names: a coordinate may be called like a numpy function or a keyword.
    return sympy.lambdify(arguments, list(expressions), modules="numpy", cse=True, dummify=True)


class CompiledScene:
    """M, F, J, b, f, ḟ and the energy of a scene with numbers for its parameters.

    Parameters
    ----------
    scene : grader.mechanics.scene.Scene
    values : mapping of str to float
        A number for every parameter (see :func:`parameter_values`).

    Attributes
    ----------
    coordinates, constraints : tuple of str
        Names, in the scene's order.
    n, m : int
        Numbers of coordinates and of constraints.
    """

    def __init__(self, scene, values: Mapping[str, float]):
        self.scene = scene
        self.values = dict(values)
        coords = list(scene.coordinates.values())
        self.coordinates = tuple(c.name for c in coords)
        self.constraints = tuple(k.name for k in scene.constraints)
        self.n, self.m = len(coords), len(scene.constraints)
        numbers = {p.symbol: sympy.Float(self.values[name], 17) for name, p in scene.parameters.items()}
        q = [c.symbol for c in coords]
        qd = [c.dot for c in coords]
        no_acceleration = {c.ddot: 0 for c in coords}

        L = scene.lagrangian.xreplace(numbers)
        momenta = [sympy.diff(L, c.dot) for c in coords]
        mass = [sympy.diff(p, v) for p in momenta for v in qd]
        force = [sympy.diff(L, c.symbol) - time_derivative(p, scene).xreplace(no_acceleration)
                 for c, p in zip(coords, momenta)]
        fs = [k.f.xreplace(numbers) for k in scene.constraints]
        jacobian = [sympy.diff(f, s) for f in fs for s in q]
        rate = [time_derivative(f, scene) for f in fs]
        bias = [time_derivative(r, scene).xreplace(no_acceleration) for r in rate]
        energy = scene.kinetic.xreplace(numbers) + scene.potential.xreplace(numbers)

        args = [scene.time] + q + qd
        self._dynamics = _compile(args, mass + force + jacobian + bias)
        self._gaps = _compile([scene.time] + q, fs + jacobian)
        self._rates = _compile(args, rate)
        self._energy = _compile(args, [energy])

    # -- pieces -----------------------------------------------------------------------------------
    def terms(self, t: float, q, qdot) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """M (n×n), F (n), J (m×n) and b (m) at a state."""
        n, m = self.n, self.m
        flat = np.array(self._dynamics(t, *q, *qdot), dtype=float)
        M = flat[: n * n].reshape(n, n)
        F = flat[n * n: n * n + n]
        J = flat[n * n + n: n * n + n + m * n].reshape(m, n)
        b = flat[n * n + n + m * n:]
        return M, F, J, b

    def gaps(self, t: float, q) -> tuple[np.ndarray, np.ndarray]:
        """f (m) and J = ∂f/∂q (m×n) at a configuration."""
        flat = np.array(self._gaps(t, *q), dtype=float)
        return flat[: self.m], flat[self.m:].reshape(self.m, self.n)

    def rates(self, t: float, q, qdot) -> np.ndarray:
        """ḟ = J q̇ + ∂f/∂t of every constraint."""
        return np.array(self._rates(t, *q, *qdot), dtype=float)

    def energy(self, t: float, q, qdot) -> float:
        """T + V (conserved when nothing depends on t and no friction or impact acts)."""
        return float(self._energy(t, *q, *qdot)[0])

    # -- the bilateral solve -----------------------------------------------------------------------
    def rhs(self, t: float, y: np.ndarray) -> np.ndarray:
        """d/dt (q, q̇) with every constraint active: the plain right-hand side for ``solve_ivp``."""
        n = self.n
        M, F, J, b = self.terms(t, y[:n], y[n:])
        qddot, _ = kkt_solve(M, F, J, b, t=t)
        return np.concatenate([y[n:], qddot])

    def accelerations(self, t: float, q, qdot) -> tuple[np.ndarray, np.ndarray]:
        """q̈ and λ with every constraint active (the engine's bilateral model).

        Raises
        ------
        SingularDynamics
            When M with the constraints cannot be solved (see :func:`kkt_solve`).
        """
        M, F, J, b = self.terms(t, np.asarray(q, float), np.asarray(qdot, float))
        return kkt_solve(M, F, J, b, t=t)


def kkt_solve(M, F, J, b, extra=None, *, t: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Solve [[M, −Jᵀ + extra], [J, 0]] [q̈, λ] = [F, −b] for q̈ and λ.

    ``extra`` (n×k, optional) adds forces proportional to the multipliers (kinetic friction
    proportional to a normal force).

    Examples
    --------
    >>> qddot, lam = kkt_solve(np.eye(2), np.array([0.0, -9.81]), np.array([[0.0, 1.0]]), np.zeros(1))
    >>> qddot.tolist(), lam.tolist()
    ([0.0, 0.0], [9.81])
    """
    n, k = M.shape[0], J.shape[0]
    if k == 0:
        K, rhs = M, F
    else:
        K = np.empty((n + k, n + k))
        K[:n, :n] = M
        K[:n, n:] = -J.T if extra is None else extra - J.T
        K[n:, :n] = J
        K[n:, n:] = 0.0
        rhs = np.concatenate([F, -b])
    # LAPACK's dgesv directly: numpy.linalg.solve's checks cost more than the solve at this size.
    _, _, x, info = _dgesv(K, rhs)
    if info != 0 or not math.isfinite(x.sum()):
        if not math.isfinite(K.sum() + rhs.sum()):
            raise SingularDynamics(f"at t = {t:.6g} the equations of motion are not finite numbers (a "
                                   "division by zero or a function outside its domain in the scene)")
        raise SingularDynamics(f"at t = {t:.6g} the equations of motion cannot be solved for the "
                               "accelerations: a body without mass, redundant constraints, or a "
                               "singular point of the coordinates")
    return x[:n], x[n:]
