"""Putting a state on the constraint manifold: f(q, t) = 0 and ḟ = J q̇ + ∂f/∂t = 0.

The integrator in :mod:`grader.simulate.constrained` enforces the constraints only at the
acceleration level (index reduction), so f and ḟ drift slowly with the integration error; these
projections remove that drift. The same functions complete an initial state in which only some
coordinates are given (the ``free`` ones are solved for).

Corrections are minimum-norm (Gauss–Newton with the pseudo-inverse of J restricted to the free
coordinates). For drift correction the metric does not matter; the steps are ~1e-12.

Examples
--------
A pendulum bob at (0.6, -0.8) with the string of length 1 and y left free: y is solved for.

>>> from grader.simulate.lagrangian_numeric import NumericConstraint, NumericScene
>>> pendulum = NumericScene(("x", "y"), lambda q, v, t: (v[0]**2 + v[1]**2) / 2, lambda q, t: q[1],
...     (NumericConstraint("rod", lambda q, t: q[0]**2 + q[1]**2 - 1),))
>>> project_positions(pendulum, 0.0, [0.6, -0.7], free=[False, True]).round(15).tolist()
[0.6, -0.8]
>>> project_velocities(pendulum, 0.0, [0.6, -0.8], [0.8, 0.0], free=[False, True]).round(15).tolist()
[0.8, 0.6]
"""

from __future__ import annotations

from typing import Sequence

import numpy as np

from grader.simulate.lagrangian_numeric import NumericScene, constraint_terms

__all__ = ["ConstraintViolation", "project_positions", "project_velocities"]

_EPS = np.finfo(float).eps


class ConstraintViolation(ValueError):
    """The constraints cannot be met by moving the free coordinates."""


def _free_mask(scene: NumericScene, free: Sequence[bool] | None) -> np.ndarray:
    n = len(scene.coordinates)
    mask = np.ones(n, dtype=bool) if free is None else np.asarray(free, dtype=bool)
    if mask.shape != (n,):
        raise ValueError(f"free must have one flag per coordinate ({n})")
    return mask


def project_positions(scene: NumericScene, t: float, q: Sequence[float], *,
                      free: Sequence[bool] | None = None, max_iterations: int = 50) -> np.ndarray:
    """Move the free coordinates (least change) until f(q, t) = 0 to rounding.

    Raises
    ------
    ConstraintViolation
        When Newton's iteration does not converge, e.g. a start where the constraint's gradient
        with respect to the free coordinates vanishes.
    """
    q = np.array(q, dtype=float)
    mask = _free_mask(scene, free)
    if not scene.constraints:
        return q
    for _ in range(max_iterations):
        terms = constraint_terms(scene, t, q)
        # f is evaluated exactly at the float q, so rounding of q alone leaves |f| ~ eps |J| |q|.
        if np.all(np.abs(terms.value) <= 64 * _EPS * (1.0 + np.abs(terms.jacobian) @ np.abs(q))):
            return q
        step, *_ = np.linalg.lstsq(terms.jacobian[:, mask], -terms.value, rcond=None)
        q[mask] += step
    names = ", ".join(scene.constraint_names)
    free_names = ", ".join(n for n, f in zip(scene.coordinates, mask) if f)
    raise ConstraintViolation(f"cannot satisfy the constraints ({names}) by moving {free_names or 'nothing'}; "
                              f"residual {terms.value.tolist()}")


def project_velocities(scene: NumericScene, t: float, q: Sequence[float], qdot: Sequence[float], *,
                       free: Sequence[bool] | None = None) -> np.ndarray:
    """Change the free velocities (least change) so that ḟ = J q̇ + ∂f/∂t = 0.

    Raises
    ------
    ConstraintViolation
        When the free velocities cannot make ḟ vanish.
    """
    qdot = np.array(qdot, dtype=float)
    mask = _free_mask(scene, free)
    if not scene.constraints:
        return qdot
    terms = constraint_terms(scene, t, q)
    J = terms.jacobian
    step, *_ = np.linalg.lstsq(J[:, mask], -(J @ qdot + terms.rate), rcond=None)
    qdot[mask] += step
    rate = J @ qdot + terms.rate
    scale = np.abs(J) @ np.abs(qdot) + np.abs(terms.rate) + 1.0
    if np.any(np.abs(rate) > 1e-9 * scale):
        raise ConstraintViolation(f"the velocities cannot satisfy the constraints ({', '.join(scene.constraint_names)}); "
                                  f"df/dt = {rate.tolist()}")
    return qdot
