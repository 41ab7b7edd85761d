"""The effects a scene declares on its constraints, with numbers, and the contact mode they are in.

A constraint is one of:

- ``bilateral`` (default): f = 0 always; no event, no switching.
- ``unilateral``: a contact or a string. **f ≥ 0 is the side the body may move into** (write the
  sphere as ``r - R``, a string of length l as ``l^2 - x^2 - y^2``), so that while it holds its
  multiplier λ ≥ 0 (the force λ ∂f/∂q pushes or pulls towards f > 0). The body leaves when λ
  would turn negative; it comes back when f returns to 0, with Newton's impact law
  ``restitution = e`` (0, the default: perfectly inelastic; 1: elastic).
- ``rolling``: f is the slip of the contact point (a length, e.g. ``s - R*theta``); ``normal``
  names the constraint whose multiplier is the normal force N. While it sticks, the friction is
  λ (|λ| ≤ μ_s N); it slips when |λ| would exceed μ_s N, then kinetic friction μ_k N opposes the
  slip velocity ḟ; it sticks again when ḟ returns to 0 and static friction can hold it.

Examples
--------
>>> from grader.mechanics.scene import load_scene
>>> scene = load_scene("problems/sphere.toml")
>>> [(e.name, e.kind, e.restitution) for e in declared_effects(scene, {"m": 0.2, "g": 9.81, "R": 0.8})]
[('surface', 'unilateral', 0.0)]
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Mapping

import sympy

__all__ = ["Effect", "Mode", "declared_effects"]


@dataclass(frozen=True)
class Effect:
    """One constraint's effect with numbers: what the simulation switches on and off."""

    index: int
    name: str
    kind: str  # "bilateral" | "unilateral" | "rolling"
    restitution: float = 0.0
    mu_s: float = 0.0
    mu_k: float = 0.0
    normal: int | None = None  # index of the normal constraint of a rolling one


@dataclass
class Mode:
    """Which constraints hold now, and how the slipping ones slip.

    Attributes
    ----------
    active : set of int
        Constraints in the equations of motion (f = offset holds).
    slipping : dict int -> float
        Rolling constraints that slip, with the sign σ of the slip velocity ḟ (0 while the
        normal contact is open, when there is no friction).
    offsets : dict int -> float
        For a rolling constraint that stuck again after slipping, the value f keeps.
    """

    active: set[int]
    slipping: dict[int, float] = field(default_factory=dict)
    offsets: dict[int, float] = field(default_factory=dict)

    def copy(self) -> "Mode":
        return Mode(set(self.active), dict(self.slipping), dict(self.offsets))

    def key(self) -> tuple:
        return tuple(sorted(self.active)), tuple(sorted(self.slipping.items()))


def _number(expr: sympy.Expr | None, scene, values: Mapping[str, float], what: str) -> float:
    if expr is None:
        return 0.0
    numbers = {p.symbol: values[name] for name, p in scene.parameters.items()}
    value = complex(sympy.N(expr.xreplace(numbers)))
    if value.imag or not value.real >= 0:
        raise ValueError(f"{scene.source}: {what} is {value.real:g}; it must be >= 0")
    return value.real


def declared_effects(scene, values: Mapping[str, float]) -> list[Effect]:
    """Every constraint of a scene as an :class:`Effect`, with the parameter ``values``."""
    names = [c.name for c in scene.constraints]
    effects = []
    for index, c in enumerate(scene.constraints):
        where = f"constraint {c.name}"
        restitution = _number(getattr(c, "restitution", None), scene, values, f"{where}: restitution")
        if restitution > 1:
            raise ValueError(f"{scene.source}: {where}: restitution is {restitution:g}; it must lie in [0, 1]")
        normal = getattr(c, "normal", None)
        effects.append(Effect(
            index, c.name, c.kind, restitution,
            _number(getattr(c, "mu_s", None), scene, values, f"{where}: mu_s"),
            _number(getattr(c, "mu_k", None), scene, values, f"{where}: mu_k"),
            names.index(normal) if normal is not None else None,
        ))
    return effects
