"""Euler–Lagrange equations with Lagrange multipliers (the paper's equations VI–VIII).

With L' = L + Σ_i λ_i f_i(q, t), each coordinate q_j obeys

    d/dt ∂L/∂q̇_j = ∂L/∂q_j + Σ_i λ_i ∂f_i/∂q_j,

and each constraint, differentiated twice in time, restricts the accelerations:

    Σ_j ∂f_i/∂q_j q̈_j + Σ_jk ∂²f_i/∂q_j∂q_k q̇_j q̇_k + 2 Σ_j ∂²f_i/∂q_j∂t q̇_j + ∂²f_i/∂t² = 0.

Together they are linear in (q̈, λ): the engine solves that system once, symbolically. The
generalized constraint force of constraint i on q_j is Q_ij = λ_i ∂f_i/∂q_j. Velocities and
accelerations are plain symbols (``thetadot``, ``thetaddot``) so that d/dt is the chain rule, which
keeps the engine fast and its output in the file's own names.

Examples
--------
>>> from grader.mechanics.scene import parse_scene
>>> scene = parse_scene('''
... id = "yoyo"
... [parameters]
... m = { dimension = "mass", domain = "positive" }
... g = { dimension = "acceleration", domain = "positive" }
... R = { dimension = "length", domain = "positive" }
... [coordinates]
... s = { dimension = "length" }
... theta = { dimension = "angle" }
... [energy]
... kinetic = "m/2*sdot^2 + m*R^2/4*thetadot^2"
... potential = "-m*g*s"
... [[constraints]]
... name = "unwind"
... f = "R*theta - s"
... [[answers]]
... name = "tension"
... expr = "lambda_unwind"
... ''')
>>> derive(scene).answers["tension"]
g*m/3
"""

from __future__ import annotations

from dataclasses import dataclass, field

import sympy

from grader.mechanics import budget
from grader.mechanics.augmented import singular_directions, solve_augmented
from grader.mechanics.scene import Scene, SceneError
from grader.mechanics.simplification import declared_domains, quick_form

__all__ = ["Derivation", "EquationsOfMotion", "derive", "equations_of_motion", "time_derivative"]


def time_derivative(expr: sympy.Expr, scene: Scene, coordinates=None) -> sympy.Expr:
    """d/dt of an expression in q, q̇ and t, by the chain rule over plain symbols.

    Examples
    --------
    >>> from grader.mechanics.scene import load_scene
    >>> sphere = load_scene("problems/sphere.toml")
    >>> time_derivative(sphere.kinetic, sphere)
    m*r**2*thetaddot*thetadot + m*r*rdot*thetadot**2 + m*rddot*rdot
    """
    coordinates = scene.coordinates.values() if coordinates is None else coordinates
    result = sympy.diff(expr, scene.time)
    for c in coordinates:
        result += sympy.diff(expr, c.symbol) * c.dot + sympy.diff(expr, c.dot) * c.ddot
    return result


@dataclass
class EquationsOfMotion:
    """The constrained equations of motion of a scene and their solution.

    Attributes
    ----------
    lhs, rhs : per coordinate name, d/dt ∂L/∂q̇ and ∂L/∂q + Σ λ ∂f/∂q.
    accelerations : per coordinate name, q̈ as a function of the state (q, q̇, t).
    multipliers : per constraint name, λ as a function of the state.
    constraint_forces : per constraint and coordinate, Q = λ ∂f/∂q as a function of the state.
    """

    lhs: dict[str, sympy.Expr]
    rhs: dict[str, sympy.Expr]
    partials: dict[str, dict[str, sympy.Expr]]
    accelerations: dict[str, sympy.Expr]
    multipliers: dict[str, sympy.Expr]
    constraint_forces: dict[str, dict[str, sympy.Expr]]
    system: tuple[sympy.Matrix, sympy.Matrix] | None = None  # the augmented A, b of (q̈, λ)
    _tidy: "EquationsOfMotion | None" = None

    def tidy(self) -> "EquationsOfMotion":
        """The same results, each cancelled and factored for people to read (computed once)."""
        if self._tidy is None:
            self._tidy = EquationsOfMotion(
                self.lhs, self.rhs, self.partials,
                {q: _tidy(v) for q, v in self.accelerations.items()},
                {k: _tidy(v) for k, v in self.multipliers.items()},
                {k: {q: _tidy(v) for q, v in forces.items()} for k, forces in self.constraint_forces.items()},
                self.system,
            )
            self._tidy._tidy = self._tidy
        return self._tidy


def _tidy(expr: sympy.Expr) -> sympy.Expr:
    # The solve returns cancelled fractions; only small ones gain from factoring (a large one,
    # a double pendulum's x1ddot in Cartesian coordinates, has no short form to find).
    return quick_form(expr) if sympy.count_ops(expr) < 100 else expr


def equations_of_motion(scene: Scene) -> EquationsOfMotion:
    """Build and solve the Euler–Lagrange equations with multipliers of a scene."""
    coords = list(scene.coordinates.values())
    cons = scene.constraints
    L = scene.lagrangian
    lhs, rhs, partials = {}, {}, {}
    for c in coords:
        dL_dq = sympy.diff(L, c.symbol)
        dL_dqdot = sympy.diff(L, c.dot)
        ddt = time_derivative(dL_dqdot, scene)
        reaction = sum((k.multiplier * sympy.diff(k.f, c.symbol) for k in cons), sympy.Integer(0))
        partials[c.name] = {"dL_dq": dL_dq, "dL_dqdot": dL_dqdot, "ddt_dL_dqdot": ddt,
                            **{f"df_{k.name}": sympy.diff(k.f, c.symbol) for k in cons}}
        lhs[c.name] = sympy.expand(ddt)
        rhs[c.name] = sympy.expand(dL_dq + reaction)

    # The system is linear in the unknowns (q̈, λ): A x = b.
    unknowns = [c.ddot for c in coords] + [k.multiplier for k in cons]
    rows = [lhs[c.name] - rhs[c.name] for c in coords]
    for k in cons:
        rows.append(sympy.expand(time_derivative(time_derivative(k.f, scene), scene)))
    A, b = sympy.linear_eq_to_matrix(rows, unknowns)
    _check_solvable(scene, A, len(coords))
    solution = solve_augmented(A, b, len(coords))
    accelerations = {c.name: solution[i] for i, c in enumerate(coords)}
    multipliers = {k.name: solution[len(coords) + i] for i, k in enumerate(cons)}
    forces = {k.name: {c.name: multipliers[k.name] * sympy.diff(k.f, c.symbol) for c in coords}
              for k in cons}
    return EquationsOfMotion(lhs, rhs, partials, accelerations, multipliers, forces, (A, b))


def _check_solvable(scene: Scene, A: sympy.Matrix, n: int) -> None:
    """Refuse only a truly singular augmented system [M Jᵀ; J 0], saying what makes it so.

    A singular mass matrix alone is fine (a winding angle, a massless pulley): the constraints
    may tie the coordinate without kinetic energy to the others.
    """
    problem = singular_directions(A, n, list(scene.coordinates), [k.name for k in scene.constraints])
    if problem is not None:
        key = "constraints" if problem.startswith("the constraints") else "energy.kinetic"
        raise SceneError(scene.source, key, problem)


@dataclass
class Derivation:
    """Everything the engine derives from a scene (see :func:`derive`)."""

    scene: Scene
    eom: EquationsOfMotion
    answers: dict[str, sympy.Expr]
    equations: dict[str, sympy.Equality] = field(default_factory=dict)
    steps: list = field(default_factory=list)
    references_cache: list | None = None
    # Derived alternatives: other right values of an answer (a special value with several roots).
    alternatives: dict[str, list[sympy.Expr]] = field(default_factory=dict)
    # Numeric answers without a closed form: the answer is its expression in an unknown, taken at
    # the root of a condition found numerically ({name: Implicit JSON}, grader.expressions.implicit).
    implicit: dict[str, dict] = field(default_factory=dict)

    def to_json(self) -> dict:
        """The contract of ``grader derive --json``: every expression in sympy's str() syntax."""
        from grader.mechanics.report import derivation_json

        return derivation_json(self)

    def references(self):
        """Reference answers as the checker takes them (see :mod:`grader.mechanics.references`)."""
        from grader.mechanics.references import reference_answers

        if self.references_cache is None:
            self.references_cache = reference_answers(self)
        return self.references_cache


def derive(scene: Scene, budget_s: float | None = None) -> Derivation:
    """Derive equations of motion, multipliers, constraint forces and every answer of a scene.

    With ``budget_s``, a derivation that runs longer raises
    :class:`~grader.mechanics.budget.BudgetExceeded` naming the step and the answer it was
    working on (only in the main thread; elsewhere the caller's own limit applies).
    """
    from grader.mechanics.answers import evaluate_answers
    from grader.mechanics.steps import derivation_steps

    # Declared intervals (an angle in [0.05, 3]) decide signs in the readable forms of the answers.
    bounds = {v.symbol: (v.domain.lo, v.domain.hi) for v in (*scene.parameters.values(), *scene.coordinates.values())
              if v.domain.kind == "interval"}
    # and so do parameters declared below another (d < R: |R − d| is R − d).
    below = {p.symbol: scene.parameters[p.below].symbol for p in scene.parameters.values() if p.below is not None}
    with budget.overall_budget(budget_s), declared_domains(bounds, below):
        with budget.step("solving the equations of motion"):
            eom = equations_of_motion(scene)
        answers, equations, alternatives, implicit = evaluate_answers(scene, eom)
        derivation = Derivation(scene, eom, answers, equations, alternatives=alternatives, implicit=implicit)
        with budget.step("writing the step-by-step derivation"):
            derivation.steps = derivation_steps(derivation)
    return derivation
