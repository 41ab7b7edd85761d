"""Lagrangian terms of a scene given as plain numeric callables, by high-precision differences.

A scene here is nothing but numbers in, numbers out: T(q, q̇, t), V(q, t) and constraint
functions f_i(q, t). Everything the constrained equations of motion need is obtained from them
*numerically*, never symbolically, so this module is an independent check of the symbolic engine
(:mod:`grader.mechanics`). With L' = L + Σ_i λ_i f_i, at each instant

    [[M, -Jᵀ], [J, 0]] [q̈; λ] = [∂L/∂q - (∂p/∂q) q̇ - ∂p/∂t ; -b]

with M = ∂²T/∂q̇∂q̇, p = ∂T/∂q̇, J = ∂f/∂q and the acceleration bias
b = q̇ᵀ(∂²f/∂q∂q)q̇ + 2(∂²f/∂q∂t)q̇ + ∂²f/∂t². The generalized constraint force of constraint i on
coordinate j is Q_ij = λ_i J_ij.

Why high precision: second derivatives by central differences in double precision are good to
about 1e-8 at best, too close to the 1e-6 we check against. The callables are evaluated with
mpmath at ``dps`` digits (default 40) with steps of 10^(-dps/3) (first derivatives) and
10^(-dps/4) (second derivatives); truncation and rounding errors are then both ~1e-20 relative
for variables whose natural scale is above ~1e-5, far below double precision. The linear
system itself is solved in double precision.

The callables must therefore compute with mpmath (``mpmath.cos``, not ``math.cos``); a callable
that returns a Python float is rejected rather than silently losing the precision.

Examples
--------
A pendulum of length 2 in Cartesian coordinates, hanging straight down and moving at speed 3:
the string tension m v²/l + m g is -2 l λ for the constraint x² + y² - l² = 0.

>>> import mpmath
>>> m, g, l = 1, 9.81, 2
>>> pendulum = NumericScene(
...     coordinates=("x", "y"),
...     kinetic=lambda q, v, t: m * (v[0] ** 2 + v[1] ** 2) / 2,
...     potential=lambda q, t: m * g * q[1],
...     constraints=(NumericConstraint("rod", lambda q, t: q[0] ** 2 + q[1] ** 2 - l ** 2),),
... )
>>> s = snapshot(pendulum, 0.0, [0.0, -2.0], [3.0, 0.0])
>>> round(-2 * l * s.multiplier("rod"), 9)
14.31
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable, Sequence

import mpmath
import numpy as np

__all__ = [
    "FunctionTerms",
    "LagrangianTerms",
    "NumericConstraint",
    "NumericScene",
    "Snapshot",
    "constraint_terms",
    "function_terms",
    "lagrangian_terms",
    "snapshot",
]

Kinetic = Callable[[Sequence[Any], Sequence[Any], Any], Any]
Potential = Callable[[Sequence[Any], Any], Any]


@dataclass(frozen=True)
class NumericConstraint:
    """A holonomic constraint f(q, t) = 0 as a numeric callable.

    Parameters
    ----------
    name : str
        The constraint's name; its multiplier is reported under this name.
    f : callable
        ``f(q, t)`` with ``q`` a list of mpmath numbers; must compute with mpmath.
    unilateral : bool
        True for a one-sided contact f ≥ 0, which holds while λ ≥ 0 (then the reaction
        Q = λ ∇f points to growing f, i.e. pushes away from the surface).
    """

    name: str
    f: Potential
    unilateral: bool = False


@dataclass(frozen=True)
class NumericScene:
    """A mechanical system as plain callables with all parameter values already bound.

    Parameters
    ----------
    coordinates : tuple of str
        Names of the generalized coordinates q, in the order of the vectors passed around.
    kinetic : callable
        ``T(q, qdot, t)``; ``q`` and ``qdot`` are lists of mpmath numbers.
    potential : callable
        ``V(q, t)``.
    constraints : tuple of NumericConstraint
        Holonomic, possibly time-dependent (rheonomic) constraints.
    dps : int
        Decimal digits of the mpmath evaluations (see the module notes).
    """

    coordinates: tuple[str, ...]
    kinetic: Kinetic
    potential: Potential
    constraints: tuple[NumericConstraint, ...] = ()
    dps: int = 40

    @property
    def constraint_names(self) -> tuple[str, ...]:
        return tuple(c.name for c in self.constraints)


@dataclass(frozen=True)
class FunctionTerms:
    """Values and derivatives of functions f_i(x, t) at one state (float arrays, one row per f_i).

    Used for the constraints (x = q) and for a parametrization's map q = Φ(u, t) (x = u).

    Attributes
    ----------
    value : f(x, t)
    jacobian : ∂f/∂x
    rate : ∂f/∂t, so that ḟ = (∂f/∂x) ẋ + rate
    bias : b = f̈ - (∂f/∂x) ẍ (None when no velocity was given)
    """

    value: np.ndarray
    jacobian: np.ndarray
    rate: np.ndarray
    bias: np.ndarray | None


@dataclass(frozen=True)
class LagrangianTerms:
    """The pieces of the constrained equations of motion at one state (float arrays).

    Attributes
    ----------
    mass : M = ∂²T/∂q̇∂q̇
    force : ∂L/∂q - (∂p/∂q) q̇ - ∂p/∂t, the right-hand side of M q̈ = force + Jᵀλ
    constraints : FunctionTerms
    """

    mass: np.ndarray
    force: np.ndarray
    constraints: FunctionTerms


@dataclass(frozen=True)
class Snapshot:
    """The full dynamic state at one instant: positions to reaction forces.

    Attributes
    ----------
    t, q, qdot, qddot : time, coordinates, velocities, accelerations
    multipliers : λ_i, one per constraint, in the scene's constraint order
    forces : Q[i, j] = λ_i ∂f_i/∂q_j, the generalized force of constraint i on coordinate j
    residual : f_i(q, t), how far the state is off the constraint manifold
    """

    scene: NumericScene
    t: float
    q: np.ndarray
    qdot: np.ndarray
    qddot: np.ndarray
    multipliers: np.ndarray
    forces: np.ndarray
    residual: np.ndarray

    def _coordinate(self, name: str) -> int:
        return self.scene.coordinates.index(name)

    def _constraint(self, name: str) -> int:
        return self.scene.constraint_names.index(name)

    def coordinate(self, name: str) -> float:
        return float(self.q[self._coordinate(name)])

    def velocity(self, name: str) -> float:
        return float(self.qdot[self._coordinate(name)])

    def acceleration(self, name: str) -> float:
        return float(self.qddot[self._coordinate(name)])

    def multiplier(self, constraint: str) -> float:
        return float(self.multipliers[self._constraint(constraint)])

    def force(self, constraint: str, coordinate: str) -> float:
        return float(self.forces[self._constraint(constraint), self._coordinate(coordinate)])


def _steps(dps: int) -> tuple[mpmath.mpf, mpmath.mpf]:
    # Balance truncation (h^2) against rounding (10^-dps / h^k) for k = 1 and k = 2.
    return mpmath.mpf(10) ** (-(dps // 3)), mpmath.mpf(10) ** (-(dps // 4))


def _checked(value: Any, what: str) -> mpmath.mpf:
    if isinstance(value, mpmath.mpf):
        return value
    if isinstance(value, (float, complex, np.floating)):
        raise TypeError(f"the {what} callable returned a machine float ({value!r}); compute with "
                        "mpmath functions (mpmath.cos, ...) so that derivatives keep their precision")
    if isinstance(value, mpmath.mpc):
        raise ValueError(f"the {what} callable returned a complex number ({value}) at this state")
    return mpmath.mpf(value)


def _shifted(x: list, steps: dict[int, Any]) -> list:
    y = list(x)
    for index, step in steps.items():
        y[index] = y[index] + step
    return y


def _along(q: list, v: list, s) -> list:
    return [qi + s * vi for qi, vi in zip(q, v)]


def _function_terms_mp(functions: Sequence[Callable], names: Sequence[str], dps: int, t, x: list,
                       v: list | None) -> FunctionTerms:
    h1, h2 = _steps(dps)
    n, rows = len(x), []
    for fn, name in zip(functions, names):
        def f(xx, tt, fn=fn, name=name):
            return _checked(fn(xx, tt), name)

        f0 = f(x, t)
        grad = [(f(_shifted(x, {j: h1}), t) - f(_shifted(x, {j: -h1}), t)) / (2 * h1) for j in range(n)]
        rate = (f(x, t + h1) - f(x, t - h1)) / (2 * h1)
        bias = None
        if v is not None:
            # b = d²/ds² f(x + s ẋ, t + s) at s = 0: the velocity-squared, mixed and ∂²f/∂t²
            # terms of f̈ in one directional second difference.
            bias = (f(_along(x, v, h2), t + h2) - 2 * f0 + f(_along(x, v, -h2), t - h2)) / h2 ** 2
        rows.append((f0, grad, rate, bias))
    m = len(rows)
    return FunctionTerms(
        value=np.array([float(r[0]) for r in rows]),
        jacobian=np.array([[float(d) for d in r[1]] for r in rows]).reshape(m, n),
        rate=np.array([float(r[2]) for r in rows]),
        bias=None if v is None else np.array([float(r[3]) for r in rows]),
    )


def function_terms(functions: Sequence[Callable], t: float, x: Sequence[float],
                   xdot: Sequence[float] | None = None, *, dps: int = 40,
                   names: Sequence[str] | None = None) -> FunctionTerms:
    """Values, Jacobian, time rate and (given ẋ) second-derivative bias of functions f_i(x, t).

    The functions take a list of mpmath numbers and the time and must compute with mpmath;
    ``names`` label them in error messages.

    Examples
    --------
    The map θ -> (l sin θ, -l cos θ) of a pendulum with l = 2 at θ = 0 moving at θ̇ = 3:
    Jacobian (2, 0)ᵀ and centripetal bias (0, l θ̇²) = (0, 18).

    >>> terms = function_terms([lambda u, t: 2 * mpmath.sin(u[0]), lambda u, t: -2 * mpmath.cos(u[0])],
    ...                        0.0, [0.0], [3.0])
    >>> terms.jacobian.round(12).tolist(), terms.bias.round(9).tolist()
    ([[2.0], [0.0]], [0.0, 18.0])
    """
    names = [f"function {i}" for i in range(len(functions))] if names is None else names
    with mpmath.workdps(dps):
        x_mp = [mpmath.mpf(a) for a in x]
        v_mp = None if xdot is None else [mpmath.mpf(a) for a in xdot]
        return _function_terms_mp(functions, names, dps, mpmath.mpf(t), x_mp, v_mp)


def _constraint_functions(scene: NumericScene) -> tuple[list, list]:
    return [c.f for c in scene.constraints], [f"constraint '{c.name}'" for c in scene.constraints]


def constraint_terms(scene: NumericScene, t: float, q: Sequence[float],
                     qdot: Sequence[float] | None = None) -> FunctionTerms:
    """Constraint values, Jacobian, time rate and (given q̇) acceleration bias at a state.

    Examples
    --------
    A bead held on a circle of radius 1 whose centre moves as (t², 0): at t = 1 the bead at
    (2, 0) has f = 0, J = (2, 0), ∂f/∂t = -4.

    >>> ring = NumericScene(("x", "y"), lambda q, v, t: (v[0]**2 + v[1]**2) / 2, lambda q, t: 0,
    ...     (NumericConstraint("ring", lambda q, t: (q[0] - t**2)**2 + q[1]**2 - 1),))
    >>> terms = constraint_terms(ring, 1.0, [2.0, 0.0])
    >>> terms.jacobian.round(12).tolist(), terms.rate.round(12).tolist()
    ([[2.0, 0.0]], [-4.0])
    """
    functions, names = _constraint_functions(scene)
    return function_terms(functions, t, q, qdot, dps=scene.dps, names=names)


def lagrangian_terms(scene: NumericScene, t: float, q: Sequence[float],
                     qdot: Sequence[float]) -> LagrangianTerms:
    """Mass matrix, generalized force and constraint terms at a state, by differences.

    Examples
    --------
    A particle in the plane in polar coordinates (r, θ): M = diag(m, m r²) and the
    centrifugal term m r θ̇² appears in the r component of the force.

    >>> polar = NumericScene(("r", "theta"),
    ...     lambda q, v, t: 2 * (v[0]**2 + q[0]**2 * v[1]**2) / 2, lambda q, t: 0)
    >>> terms = lagrangian_terms(polar, 0.0, [3.0, 0.5], [0.0, 2.0])
    >>> terms.mass.round(12).tolist(), terms.force.round(12).tolist()
    ([[2.0, 0.0], [0.0, 18.0]], [24.0, 0.0])
    """
    n = len(scene.coordinates)
    if len(q) != n or len(qdot) != n:
        raise ValueError(f"expected {n} coordinates and velocities, got {len(q)} and {len(qdot)}")
    with mpmath.workdps(scene.dps):
        h1, h2 = _steps(scene.dps)
        t = mpmath.mpf(t)
        q = [mpmath.mpf(x) for x in q]
        v = [mpmath.mpf(x) for x in qdot]

        def T(qq, vv, tt):
            return _checked(scene.kinetic(qq, vv, tt), "kinetic energy")

        def L(qq):
            return T(qq, v, t) - _checked(scene.potential(qq, t), "potential energy")

        T0 = T(q, v, t)
        mass = [[None] * n for _ in range(n)]
        for j in range(n):
            plus, minus = T(q, _shifted(v, {j: h2}), t), T(q, _shifted(v, {j: -h2}), t)
            mass[j][j] = (plus - 2 * T0 + minus) / h2 ** 2
            for k in range(j):
                mass[j][k] = mass[k][j] = (
                    T(q, _shifted(v, {j: h2, k: h2}), t) - T(q, _shifted(v, {j: h2, k: -h2}), t)
                    - T(q, _shifted(v, {j: -h2, k: h2}), t) + T(q, _shifted(v, {j: -h2, k: -h2}), t)
                ) / (4 * h2 ** 2)

        force = []
        for j in range(n):
            dL_dq = (L(_shifted(q, {j: h1})) - L(_shifted(q, {j: -h1}))) / (2 * h1)
            # (∂p_j/∂q) q̇ + ∂p_j/∂t: mixed difference of T in q̇_j and along (q + s q̇, t + s).
            def along(s, u):
                return T(_along(q, v, s), _shifted(v, {j: u}), t + s)

            momentum_rate = (along(h2, h2) - along(h2, -h2) - along(-h2, h2) + along(-h2, -h2)) / (4 * h2 ** 2)
            # Subtract at high precision: the two terms may nearly cancel.
            force.append(dL_dq - momentum_rate)

        return LagrangianTerms(
            mass=np.array([[float(x) for x in row] for row in mass]),
            force=np.array([float(x) for x in force]),
            constraints=_function_terms_mp(*_constraint_functions(scene), scene.dps, t, q, v),
        )


def snapshot(scene: NumericScene, t: float, q: Sequence[float], qdot: Sequence[float]) -> Snapshot:
    """Solve for accelerations, multipliers and constraint forces at a state.

    Raises
    ------
    numpy.linalg.LinAlgError
        When the KKT matrix is singular (no inertia in some unconstrained direction, or
        redundant constraints).

    Examples
    --------
    A free particle of mass 2 falling under gravity 9.81 (no constraints):

    >>> fall = NumericScene(("z",), lambda q, v, t: v[0]**2, lambda q, t: 2 * 9.81 * q[0])
    >>> float(snapshot(fall, 0.0, [0.0], [0.0]).qddot[0].round(12))
    -9.81
    """
    terms = lagrangian_terms(scene, t, q, qdot)
    n, J = len(q), terms.constraints.jacobian
    m = J.shape[0]
    kkt = np.block([[terms.mass, -J.T], [J, np.zeros((m, m))]])
    solution = np.linalg.solve(kkt, np.concatenate([terms.force, -terms.constraints.bias]))
    qddot, lam = solution[:n], solution[n:]
    return Snapshot(scene=scene, t=float(t), q=np.array(q, dtype=float), qdot=np.array(qdot, dtype=float),
                    qddot=qddot, multipliers=lam, forces=lam[:, None] * J,
                    residual=terms.constraints.value)
