"""Closed forms of a scene's ``[[answers]]``.

An answer's ``expr`` is written over parameters, coordinates and their dots/ddots, multipliers
``lambda_<c>``, constraint forces ``Q_<c>_<q>``, ``t`` and earlier answers. The engine replaces
multipliers, forces and accelerations by the solved equations of motion, moves to the independent
variables (:mod:`grader.mechanics.reduction`), removes a velocity that ``in_terms_of`` does not
allow with the conserved Jacobi integral (energy) from ``[initial]``, and simplifies.

An answer with ``where = "lhs = rhs"`` is a special value: its expression at the configuration
where the condition holds, taking the root that the motion from ``[initial]`` reaches first
(:mod:`grader.mechanics.special_values`).

Examples
--------
>>> from grader.mechanics.scene import load_scene
>>> from grader.mechanics.lagrange import equations_of_motion
>>> scene = load_scene("problems/sphere.toml") 
>>> evaluate_answers(scene, equations_of_motion(scene))[0]["normal_force"]
g*m*(3*cos(theta) - 2)
"""

from __future__ import annotations

import sympy

from grader.mechanics.reduction import Reduction
from grader.mechanics.scene import AnswerSpec, Scene, SceneError
from grader.mechanics.simplification import human_form

__all__ = ["AnswerEvaluator", "evaluate_answers"]


def evaluate_answers(scene: Scene, eom) -> tuple[dict[str, sympy.Expr], dict[str, sympy.Equality]]:
    """Closed form of every answer, and for ``kind = "equation"`` answers the reference equation."""
    evaluator = AnswerEvaluator(scene, eom)
    answers, equations = {}, {}
    for spec in scene.answers:
        value = evaluator.evaluate(spec)
        answers[spec.name] = value
        if spec.kind == "equation":
            equations[spec.name] = sympy.Eq(spec.expr, value, evaluate=False)
    return answers, equations


class AnswerEvaluator:
    """Evaluates answers one after another; later answers and conditions may use earlier ones."""

    def __init__(self, scene: Scene, eom):
        self.scene = scene
        self.reduction = Reduction(scene)
        self.reduction.solve(eom)
        subs = {k.multiplier: self.reduction.multipliers[k.name] for k in scene.constraints}
        subs.update(self.reduction.forces)
        subs.update(self.reduction.coordinate_accelerations)
        subs.update(self.reduction.accelerations)
        self.dynamics = subs
        self.values: dict[sympy.Symbol, sympy.Expr] = {}

    @property
    def parameters(self) -> set[sympy.Symbol]:
        return {p.symbol for p in self.scene.parameters.values()}

    def state_symbols(self, velocities: bool = True) -> set[sympy.Symbol]:
        symbols = {u.symbol for u in self.reduction.independent.values()}
        if velocities:
            symbols |= {u.dot for u in self.reduction.independent.values()}
        return symbols

    def evaluate(self, spec: AnswerSpec) -> sympy.Expr:
        key = f"answers ({spec.name})"
        if spec.where is not None:
            from grader.mechanics.special_values import special_value

            value = special_value(self, spec)
        else:
            value = self.reduce(spec.expr, self.target(spec), key)
        self.values[spec.symbol] = value
        return value

    def target(self, spec: AnswerSpec, default_state: bool = True) -> set[sympy.Symbol]:
        """The symbols an answer may keep: its ``in_terms_of``, else parameters, t and the state."""
        if spec.in_terms_of is None:
            target = self.parameters | {self.scene.time}
            return target | self.state_symbols() if default_state else target
        target = set()
        allowed = self.parameters | self.state_symbols() | {self.scene.time} | {
            u.ddot for u in self.reduction.independent.values()}
        for name in spec.in_terms_of:
            symbol = self.scene.namespace.symbol(name)
            if symbol not in allowed:
                names = ", ".join(self.reduction.independent)
                raise SceneError(self.scene.source, f"answers ({spec.name}).in_terms_of",
                                 f"'{name}' is not a parameter or an independent variable; answers are "
                                 f"expressed in {names} (and their dots)")
            target.add(symbol)
        return target

    def reduce(self, expr: sympy.Expr, target: set[sympy.Symbol], key: str) -> sympy.Expr:
        """``expr`` with dynamics solved, in the independent variables, free of what target excludes."""
        expr = expr.xreplace(self.values)
        keep = {s for s in target if s.name.endswith("ddot")}
        dynamics = {s: v for s, v in self.dynamics.items() if s not in keep}
        expr = expr.xreplace(dynamics)
        expr = self.reduction.to_independent(expr)
        expr = human_form(expr)
        expr = self.eliminate_velocities(expr, target, key)
        leftover = expr.free_symbols - target
        if leftover:
            names = ", ".join(sorted(str(s) for s in leftover))
            wanted = ", ".join(sorted(str(s) for s in target)) or "nothing"
            raise SceneError(self.scene.source, key,
                             f"cannot be written in terms of {wanted}: it still depends on {names}")
        return expr

    def eliminate_velocities(self, expr: sympy.Expr, target: set[sympy.Symbol], key: str) -> sympy.Expr:
        """Remove a velocity that target excludes with the conserved Jacobi integral (energy)."""
        extra = [u for u in self.reduction.independent.values()
                 if u.dot in expr.free_symbols and u.dot not in target]
        if not extra:
            return expr
        if len(extra) > 1:
            raise SceneError(self.scene.source, key,
                             "energy conservation removes one velocity, but "
                             f"{', '.join(u.dot.name for u in extra)} all remain")
        u = extra[0]
        squared = self.velocity_squared(u, key)
        expr = sympy.expand(expr)
        expr = expr.replace(
            lambda e: e.is_Pow and e.base == u.dot and e.exp.is_Integer and e.exp % 2 == 0,
            lambda e: squared ** (e.exp // 2),
        )
        if u.dot in expr.free_symbols:
            raise SceneError(self.scene.source, key,
                             f"{u.dot.name} appears to an odd power, so its sign is not fixed by energy "
                             "conservation; add it to in_terms_of")
        return human_form(expr)

    def velocity_squared(self, u, key: str) -> sympy.Expr:
        """u̇² from h(u, u̇) = h(initial)."""
        h = self.reduction.jacobi_integral()
        if h is None:
            raise SceneError(self.scene.source, key,
                             f"{u.dot.name} cannot be eliminated: the reduced Lagrangian depends on t, so "
                             "energy is not conserved")
        h0 = self.reduction.initial_value(h)
        if h0 is None:
            names = ", ".join(f"{v.name}, {v.dot.name}" for v in self.reduction.independent.values())
            raise SceneError(self.scene.source, key,
                             f"{u.dot.name} is eliminated with energy conservation, which needs [initial] "
                             f"values for {names}")
        poly = sympy.Poly(h, u.dot)
        if poly.degree() != 2 or poly.coeff_monomial(u.dot) != 0:
            raise SceneError(self.scene.source, key,
                             f"the energy is not of the form a·{u.dot.name}² + c, so {u.dot.name} cannot be "
                             "eliminated")
        a, c = poly.coeff_monomial(u.dot ** 2), poly.coeff_monomial(1)
        return human_form((h0 - c) / a)
