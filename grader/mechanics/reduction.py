"""Express quantities of the full, constrained state in independent variables.

A scene's coordinates q are tied by k constraints; answers are written in n − k independent
variables u: either the ``[parametrization]`` the instructor gave (the pendulum's θ for x, y), or
the coordinates left after solving the constraints for k of them. :class:`Reduction` holds the map
q = Φ(u, t) with its velocities and the reduced Lagrangian L_r(u, u̇, t), whose Euler–Lagrange
equations give ü and whose Jacobi integral h = Σ u̇ ∂L_r/∂u̇ − L_r is conserved when L_r does not
depend on t (then it is the energy T + V for scleronomic constraints).

Examples
--------
>>> from grader.mechanics.scene import load_scene
>>> r = Reduction(load_scene("problems/sphere.toml"))
>>> r.phi
{r: R, theta: theta}
"""

from __future__ import annotations

import itertools

import numpy
import sympy

from grader.mechanics import budget
from grader.mechanics.augmented import generic_point, solve_augmented
from grader.mechanics.scene import Coordinate, Scene, SceneError
from grader.mechanics.simplification import pythagorean_roots, readable_denominator, tidy_trig

__all__ = ["Reduction", "without_hidden_coordinates"]


class Reduction:
    """The map from a scene's coordinates to its independent variables, and what follows from it."""

    def __init__(self, scene: Scene):
        self.scene = scene
        # With several branches of the solved constraints: the expression in the independent
        # variables that vanishes where the branch taken ends, and the branch, for messages.
        self.branch_end: sympy.Expr | None = None
        self.branch_of = ""
        self.branch_radicands: list[sympy.Expr] = []
        if scene.parametrization is not None:
            self.independent: dict[str, Coordinate] = dict(scene.parametrization.variables)
            self.phi = dict(scene.parametrization.mapping)
            self._check_parametrization()
        else:
            self.independent, self.phi = self._solve_constraints()
        self.phi_dot = {q: self.time_derivative(expr) for q, expr in self.phi.items()}
        # [initial] given in coordinates the constraints made dependent (the disk's x of a disk and
        # a hanging block, when the answers keep the block's y): the independent variables' start
        # follows from it. The scene read by everything downstream is the one with it completed.
        self.scene = scene = self._with_completed_initial(scene)
        # The time too: a wire turned at ω, in Cartesian coordinates, leaves sin²ωt + cos²ωt in L_r,
        # which is free of t (its Jacobi integral, written with t, costs a tidy-up at every use).
        self.lagrangian = without_hidden_coordinates(sympy.expand(self.to_independent(scene.lagrangian)),
                                                      [u.symbol for u in self.independent.values()] + [scene.time])
        self.accelerations: dict[sympy.Symbol, sympy.Expr] = {}
        self.multipliers: dict[str, sympy.Expr] = {}

    # -- the map ---------------------------------------------------------------------------------
    def time_derivative(self, expr: sympy.Expr) -> sympy.Expr:
        """d/dt of an expression in the independent variables u, u̇ and t."""
        result = sympy.diff(expr, self.scene.time)
        for u in self.independent.values():
            result += sympy.diff(expr, u.symbol) * u.dot + sympy.diff(expr, u.dot) * u.ddot
        return result

    def to_independent(self, expr: sympy.Expr) -> sympy.Expr:
        """Replace scene coordinates and velocities by their expressions in u, u̇, t."""
        subs = {}
        for c in self.scene.coordinates.values():
            if c.symbol in self.phi and self.phi[c.symbol] != c.symbol:
                subs[c.symbol] = self.phi[c.symbol]
                subs[c.dot] = self.phi_dot[c.symbol]
        # A root of the scene's coordinates (√(x² + y²) in a constraint) is tidied as it is mapped,
        # before anything expands it.
        return pythagorean_roots(expr.xreplace(subs)) if subs else expr

    def _with_completed_initial(self, scene: Scene) -> Scene:
        """The scene with [initial] values for every independent variable that [initial] fixes
        through the constraints; the scene itself when nothing is missing or nothing fixes it.

        Positions come from the map q = Φ(u, 0) at the coordinates [initial] gives, velocities from
        q̇ = Φ̇ (linear in u̇); a value is added only when it is the one solution (a map with
        several, θ from x = l sin θ, is left to [initial]) and every given value agrees with it.
        """
        given = scene.initial
        us = list(self.independent.values())
        missing = [u.symbol for u in us if u.name not in given] + [u.dot for u in us if u.dot.name not in given]
        dependent = [c for c in scene.coordinates.values()
                     if self.phi.get(c.symbol, c.symbol) != c.symbol or c.name not in self.independent]
        if not missing or not any(c.name in given or c.dot.name in given for c in dependent):
            return scene
        known = {u.symbol: given[u.name] for u in us if u.name in given}
        known.update({u.dot: given[u.dot.name] for u in us if u.dot.name in given})
        at_start = {scene.time: sympy.Integer(0)}
        positions = [(self.phi[c.symbol].xreplace(at_start) - given[c.name]) for c in dependent if c.name in given]
        velocities = [(self.phi_dot[c.symbol].xreplace(at_start) - given[c.dot.name])
                      for c in dependent if c.dot.name in given]
        added = {}
        for equations, unknowns in ((positions, [u.symbol for u in us]), (velocities, [u.dot for u in us])):
            equations = [sympy.expand(e.xreplace(known).xreplace(added)) for e in equations]
            wanted = [x for x in unknowns if x in missing and any(x in e.free_symbols for e in equations)]
            if not wanted:
                continue
            solution = budget.attempt(lambda: _unique_solution(equations, wanted), 1.0, fallback=lambda: None)
            state = {s for u in us for s in (u.symbol, u.dot)}
            if solution is None or any(v.free_symbols & state for v in solution.values()):
                continue
            added.update(solution)
        if not added:
            return scene
        completed = dict(given)
        for u in us:
            for symbol, name in ((u.symbol, u.name), (u.dot, u.dot.name)):
                if symbol in added and name not in completed:
                    completed[name] = added[symbol]
        import dataclasses

        return dataclasses.replace(scene, initial=completed)

    def _check_parametrization(self) -> None:
        scene = self.scene
        dof = len(scene.coordinates) - len(scene.constraints)
        if len(self.independent) != dof:
            raise SceneError(scene.source, "parametrization.variables",
                             f"has {len(self.independent)} variable(s), but the scene has {dof} degree(s) "
                             "of freedom (coordinates minus constraints)")
        for c in scene.constraints:
            residual = c.f.xreplace(self.phi)
            if not _vanishes(residual):
                raise SceneError(scene.source, "parametrization.map",
                                 f"does not satisfy constraint '{c.name}': f = {c.f} becomes "
                                 f"{sympy.simplify(residual)}, not 0")

    def _solve_constraints(self) -> tuple[dict[str, Coordinate], dict]:
        """Pick k dependent coordinates and solve f = 0 for them."""
        scene = self.scene
        if not scene.constraints:
            return dict(scene.coordinates), {c.symbol: c.symbol for c in scene.coordinates.values()}
        wanted = set()
        for a in scene.answers:
            wanted |= set(a.in_terms_of or ())
        # Later coordinates are eliminated first; coordinates an answer is asked in are kept.
        order = sorted(reversed(list(scene.coordinates.values())), key=lambda c: c.name in wanted)
        dependent: list[Coordinate] = []
        for constraint in scene.constraints:
            symbols = constraint.f.free_symbols
            for c in order:
                if c.symbol in symbols and c not in dependent:
                    dependent.append(c)
                    break
        jac = sympy.Matrix([[sympy.diff(k.f, c.symbol) for c in dependent] for k in scene.constraints])
        if len(dependent) < len(scene.constraints) or jac.det() == 0:
            # The first choice, constraint by constraint, can take the one coordinate a later
            # constraint has (B in x + aψ - B = 0, then B - bt²/2 = 0): any set with a nonzero
            # Jacobian will do, the most preferred first.
            dependent, jac = self._dependent_set(order)
        try:
            solutions = sympy.solve([k.f for k in scene.constraints], [c.symbol for c in dependent], dict=True)
        except NotImplementedError:
            solutions = []
        if not solutions:
            raise SceneError(scene.source, "constraints",
                             "the engine cannot solve the constraints in closed form; add a [parametrization]")
        solution = self._branch(solutions, dependent)
        phi = {c.symbol: solution.get(c.symbol, c.symbol) for c in scene.coordinates.values()}
        independent = {n: c for n, c in scene.coordinates.items() if c not in dependent}
        if len(solutions) > 1:
            # Where det(∂f/∂q_dependent) vanishes the branch taken ends (y = √(R² − x²) at x = ±R): a
            # motion that gets there goes on along another branch, which no formula in x follows.
            self.branch_end = jac.det().xreplace(phi)
            self.branch_of = ", ".join(f"{c.name} = {sympy.sstr(solution[c.symbol])}" for c in dependent)
            # the radicands whose root's sign tells the branches apart (R² − x² in y = ±√(R² − x²))
            self.branch_radicands = sorted({p.base for c in dependent for p in solution[c.symbol].atoms(sympy.Pow)
                                            if p.exp.is_Rational and p.exp.q == 2}, key=sympy.default_sort_key)
        return independent, phi

    def _dependent_set(self, order: list[Coordinate]) -> tuple[list[Coordinate], sympy.Matrix]:
        """The first set of coordinates, in the order of preference, whose Jacobian is not singular."""
        scene = self.scene
        k = len(scene.constraints)
        for chosen in itertools.combinations(order, k):
            jac = sympy.Matrix([[sympy.diff(c.f, q.symbol) for q in chosen] for c in scene.constraints])
            if jac.det() != 0:
                return list(chosen), jac
        raise SceneError(scene.source, "constraints",
                         "cannot solve the constraints for any set of coordinates (their Jacobian is singular "
                         "for every choice); add a [parametrization] that satisfies them")

    def _branch(self, solutions: list[dict], dependent: list[Coordinate]) -> dict:
        """With several branches (y = ±√(l² − x²)), take the one the initial state is on."""
        if len(solutions) == 1:
            return solutions[0]
        scene = self.scene
        initial = {scene.coordinates[n].symbol: v for n, v in scene.initial.items() if n in scene.coordinates}
        kept = [c for c in scene.coordinates.values() if c not in dependent]
        if all(c.symbol in initial for c in dependent) and any(c.symbol not in initial for c in kept):
            # [initial] in the coordinate the answers leave dependent (x of a bead on y = a x², the
            # answers in y): the kept one's start follows through the constraints when it is their
            # one solution (y₀ = a x₀²).
            missing = [c.symbol for c in kept if c.symbol not in initial]
            equations = [sympy.expand(k.f.xreplace(initial).xreplace({scene.time: sympy.Integer(0)}))
                         for k in scene.constraints]
            start = budget.attempt(lambda: _unique_solution(equations, missing), 1.0, fallback=lambda: None)
            state = {c.symbol for c in scene.coordinates.values()}
            if start is not None and not any(v.free_symbols & state for v in start.values()):
                initial = {**initial, **start}
        if all(c.symbol in initial for c in dependent):
            point = {s: v for s, v in _sample_parameters(scene).items()}
            point[scene.time] = sympy.Integer(0)
            for solution in solutions:
                try:
                    ok = all(
                        abs(complex(sympy.N((solution[c.symbol] - initial[c.symbol]).xreplace(initial).subs(point))))
                        < 1e-9
                        for c in dependent
                    )
                except TypeError:  # a coordinate [initial] does not fix, left in the branch's formula
                    ok = False
                if ok:
                    return solution
        raise SceneError(scene.source, "constraints",
                         "the constraints have several solution branches; give the initial position of "
                         f"{', '.join(c.name for c in scene.coordinates.values())} in [initial] (the start "
                         f"of {', '.join(c.name for c in dependent)} picks the branch) or add a [parametrization]")

    # -- dynamics in the independent variables ----------------------------------------------------
    def solve(self, eom) -> None:
        """ü and λ as functions of (u, u̇, t).

        When the mass matrix M is invertible, ü comes from the reduced Lagrangian (M_r ü = F_r with
        M_r = ∂²L_r/∂u̇², each entry simplified while it is small, so that a double pendulum's
        cos θ₁ cos θ₂ + sin θ₁ sin θ₂ becomes cos(θ₁ − θ₂) before any solve), and λ from the
        Schur complement J M⁻¹ Jᵀ on the map. Both are small systems solved with the adjugate,
        over determinants written as people write them (m₁ + m₂ sin²(θ₁ − θ₂)). A singular M (a
        coordinate without kinetic energy of its own) falls back to solving the Euler–Lagrange rows
        of the scene's coordinates with q̈ = Φ̈(u, u̇, ü) for (ü, λ) together.
        """
        scene = self.scene
        phi_ddot = {}
        for c in scene.coordinates.values():
            if c.symbol in self.phi and self.phi[c.symbol] != c.symbol:
                phi_ddot[c.ddot] = self.time_derivative(self.phi_dot[c.symbol])
        with budget.step("solving the equations of motion in the independent variables"):
            if not (eom.system is not None and self._solve_structured(eom)):
                self._solve_rows(eom, phi_ddot)
        accelerations = {}
        for c in scene.coordinates.values():
            value = phi_ddot.get(c.ddot, c.ddot)
            accelerations[c.ddot] = value.xreplace(self.accelerations)
        self.coordinate_accelerations = accelerations
        self.forces = {}
        for k in scene.constraints:
            for c in scene.coordinates.values():
                gradient = self.to_independent(sympy.diff(k.f, c.symbol))
                self.forces[scene.forces[(k.name, c.name)]] = self.multipliers[k.name] * gradient

    def _solve_structured(self, eom) -> bool:
        """ü from the reduced Lagrangian, λ from the Schur complement; False if M is singular."""
        scene = self.scene
        A, b = eom.system
        n, k = len(scene.coordinates), len(scene.constraints)
        M = A[:n, :n]
        point = generic_point(A.free_symbols)
        if M.subs(point).det() == 0:
            return False
        us = list(self.independent.values())
        L = self.lagrangian
        Mr = sympy.Matrix(len(us), len(us), lambda i, j: _tidy_entry(
            sympy.diff(L, us[i].dot, us[j].dot)))
        if any(u.dot in Mr.free_symbols for u in us):
            return False
        Fr = sympy.Matrix([_tidy_entry(
            sympy.diff(L, u.symbol)
            - sum((sympy.diff(L, u.dot, w.symbol) * w.dot for w in us), sympy.Integer(0))
            - sympy.diff(L, u.dot, scene.time)) for u in us])
        uddot = _solve_small(Mr, Fr)
        self.accelerations = {u.ddot: uddot[i] for i, u in enumerate(us)}
        if k:
            C, J = A[:n, n:], A[n:, :n]
            b1, b2 = b[:n, :], b[n:, :]
            if M.is_diagonal():
                Minv = sympy.diag(*[1 / M[i, i] for i in range(n)])
                MinvC, Minvb1 = Minv * C, Minv * b1
            else:
                # M⁻¹C and M⁻¹b₁ by fraction-free solves over sin and cos as generators; a symbolic
                # M.inv() of a hoop with a bead inside (4 × 4, trigonometric) ran over a minute.
                columns = [sympy.Matrix(solve_augmented(M, C[:, j])) for j in range(k)]
                MinvC = sympy.Matrix.hstack(*columns)
                Minvb1 = sympy.Matrix(solve_augmented(M, b1))
            S = (J * MinvC).applyfunc(lambda e: _tidy_entry(self.to_independent(sympy.cancel(e))))
            r = (J * Minvb1 - b2).applyfunc(lambda e: _tidy_entry(self.to_independent(sympy.cancel(e))))
            lam = _solve_small(S, r)
            if not M.is_diagonal() or (k > 1 and _denominator_ops(lam) > _denominator_ops(uddot)):
                # The same λ from k Euler–Lagrange rows is shorter for some scenes (the bead's
                # 2M + m sin²(θ + α), where the Schur complement spreads it over sin α, sin θ; a
                # rod between a floor and an inclined wall, where det S is of degree 4 in sines
                # and cosines and the rows share ü's denominator) and longer for others (a rod with
                # both ends on a circle): the shorter of each is kept. With a diagonal M, the rows
                # are tried only where det S came out longer than ü's denominator (a wedge with a
                # block on it and another hanging: 0.2 s for nothing).
                rows = self._multipliers_from_rows(C, M, b1)
                if rows is not None:
                    lam = [min((a, b), key=sympy.count_ops) for a, b in zip(lam, rows)]
        else:
            lam = []
        self.multipliers = {c.name: lam[i] for i, c in enumerate(scene.constraints)}
        return True

    def _multipliers_from_rows(self, C: sympy.Matrix, M: sympy.Matrix, b1: sympy.Matrix) -> list[sympy.Expr] | None:
        """λ from k Euler–Lagrange rows C λ = b₁ − M q̈, with q̈ = Φ̈(u, u̇, ü) and ü already solved.

        The rows are consistent (ü solves them all), so any k rows whose block of C is invertible
        give λ; the simplest such block is taken (usually the coordinates the constraints were
        solved for). This avoids inverting a full mass matrix with cross terms symbolically (a hoop
        rolling down an incline with a bead inside: M⁻¹ of 4 × 4 trigonometric entries ran over a
        minute; these rows take a fraction of a second). None where the rows are too long to tidy.
        """
        import itertools

        scene = self.scene
        coordinates = list(scene.coordinates.values())
        n, k = C.shape
        qddot = []
        for c in coordinates:
            if c.symbol in self.phi and self.phi[c.symbol] != c.symbol:
                value = self.time_derivative(self.phi_dot[c.symbol])
            else:
                value = c.ddot
            qddot.append(value.xreplace(self.accelerations))
        Ci = C.applyfunc(lambda e: _tidy_entry(self.to_independent(e)))
        point = generic_point(Ci.free_symbols)
        blocks = []
        for rows in itertools.combinations(range(n), k):
            block = Ci.extract(list(rows), list(range(k)))
            if block.subs(point).det() != 0:
                blocks.append((sum(sympy.count_ops(e) for e in block), rows, block))
        if not blocks:
            raise SceneError(scene.source, "constraints",
                             "the constraint forces cannot be solved for: the constraints' gradients are dependent")
        _, rows, block = min(blocks, key=lambda item: item[:2])
        residual = [sympy.cancel(self.to_independent(b1[i, 0] - sum(
            (M[i, j] * qddot[j] for j in range(n) if M[i, j] != 0), sympy.Integer(0))).xreplace(self.accelerations))
            for i in rows]
        if any(sympy.count_ops(e) > 3 * _TIDY_LIMIT for e in residual):
            # Too long to tidy (see _tidy_entry): λ from these rows would not be the shorter one,
            # and solving them costs more than the rest of the reduction (a pendulum hung from a
            # ring on a parabola: 0.7 s of 2.4).
            return None
        return _solve_small(block, sympy.Matrix([_tidy_entry(e) for e in residual]))

    def _solve_rows(self, eom, phi_ddot: dict) -> None:
        """Solve the scene's Euler–Lagrange rows with q̈ = Φ̈ for (ü, λ) together (any M)."""
        scene = self.scene
        us = list(self.independent.values())
        rows = []
        for name, c in scene.coordinates.items():
            row = (eom.lhs[name] - eom.rhs[name]).xreplace(phi_ddot)
            rows.append(_tidy_entry(self.to_independent(row)))
        unknowns = [u.ddot for u in us] + [k.multiplier for k in scene.constraints]
        A, b = sympy.linear_eq_to_matrix(rows, unknowns)
        A, b = A.applyfunc(_tidy_entry), b.applyfunc(_tidy_entry)
        point = {s: sympy.Rational(7 + 3 * i, 11 + 2 * i) for i, s in enumerate(sorted(A.free_symbols, key=str))}
        if A.subs(point).rank() < len(unknowns):
            raise SceneError(scene.source, "constraints",
                             "the equations of motion cannot be solved in the independent variables "
                             f"{', '.join(self.independent)}: the system is singular")
        solution = solve_augmented(A, b)
        self.accelerations = {u.ddot: solution[i] for i, u in enumerate(us)}
        self.multipliers = {k.name: solution[len(us) + i] for i, k in enumerate(scene.constraints)}

    def jacobi_integral(self) -> sympy.Expr | None:
        """h = Σ u̇ ∂L/∂u̇ − L when it is conserved (L free of t), else None.

        L is L_r, or an equivalent Lagrangian free of t when L_r depends on t only through a total
        derivative dF/dt and a function of t alone (:meth:`autonomous_lagrangian`): a pendulum in a
        car accelerating at A, whose energy in the car's frame is conserved.
        """
        L = self.autonomous_lagrangian()
        if L is None:
            return None
        h = sum((u.dot * sympy.diff(L, u.dot) for u in self.independent.values()), sympy.Integer(0)) - L
        return sympy.expand(h)

    def autonomous_lagrangian(self) -> sympy.Expr | None:
        """L_r, or L_r − dF/dt − g(t) free of t (same equations of motion), or None.

        The terms of L_r linear in the velocities, Σ aᵢ(u, t) u̇ᵢ, are split as aᵢ(u, 0) u̇ᵢ plus
        ∂F/∂uᵢ with F = ∫ (a₁(u, t) − a₁(u, 0)) du₁, when every aᵢ(u, t) − aᵢ(u, 0) is ∂F/∂uᵢ;
        dF/dt = Σ ∂F/∂uᵢ u̇ᵢ + ∂F/∂t is then removed, and the terms free of the state (m A² t²/2 of
        the car) are dropped. The result is kept only when it is free of t.

        >>> import sympy
        >>> from types import SimpleNamespace as NS
        >>> th, thd, t, A, l = sympy.symbols("theta thetadot t A l")
        >>> r = NS(scene=NS(time=t), independent={"theta": NS(symbol=th, dot=thd)})
        >>> r.lagrangian = sympy.expand(((A*t + l*sympy.cos(th)*thd)**2 + (l*sympy.sin(th)*thd)**2)/2)
        >>> sympy.expand(sympy.trigsimp(Reduction.autonomous_lagrangian(r)))
        -A*l*sin(theta) + l**2*thetadot**2/2
        """
        L, t = self.lagrangian, self.scene.time
        if sympy.diff(L, t) == 0:
            return L
        us = list(self.independent.values())
        velocities = [u.dot for u in us]
        try:
            poly = sympy.Poly(L, *velocities)
        except sympy.PolynomialError:
            return None
        linear = [poly.coeff_monomial(v) for v in velocities]
        gauge = [sympy.expand(a - a.xreplace({t: 0})) for a in linear]
        if gauge[0] == 0:
            F = sympy.Integer(0)
        else:
            F = budget.attempt(lambda: sympy.integrate(gauge[0], us[0].symbol), 1.0, fallback=lambda: None)
            if F is None or F.has(sympy.Integral):
                return None
        if any(sympy.expand(sympy.diff(F, u.symbol) - a) != 0 for u, a in zip(us, gauge)):
            return None
        dF = sympy.diff(F, t) + sum((sympy.diff(F, u.symbol) * u.dot for u in us), sympy.Integer(0))
        reduced = sympy.expand(L - dF)
        state = {s for u in us for s in (u.symbol, u.dot)}
        reduced = sympy.Add(*[term for term in sympy.Add.make_args(reduced) if term.free_symbols & state])
        if t in reduced.free_symbols:
            reduced = without_hidden_coordinates(reduced, [t])
        return reduced if t not in reduced.free_symbols else None

    def initial_value(self, expr: sympy.Expr) -> sympy.Expr | None:
        """expr at the [initial] state, or None when [initial] does not fix every variable it uses."""
        subs = {}
        for name, value in self.scene.initial.items():
            for u in self.independent.values():
                if name == u.name:
                    subs[u.symbol] = value
                elif name == u.dot.name:
                    subs[u.dot] = value
        subs[self.scene.time] = sympy.Integer(0)
        result = expr.xreplace(subs)
        state = {s for u in self.independent.values() for s in (u.symbol, u.dot)}
        return None if result.free_symbols & state else result


def without_hidden_coordinates(lagrangian: sympy.Expr, coordinates: list[sympy.Symbol],
                               thorough: bool = False) -> sympy.Expr:
    """An expression (the reduced Lagrangian) with sin² + cos² = 1 applied when that removes a coordinate.

    A map written in Cartesian coordinates (x = l sin θ cos φ, y = l sin θ sin φ) expands into
    terms in sin²φ and cos²φ that add up to no φ at all: the azimuth of a spherical pendulum is
    cyclic, but only after the identity. Its conserved momentum (and the check that L_r is free of
    a coordinate) needs the form without it; every other Lagrangian is kept exactly as expanded
    (the very same object is returned). ``thorough`` (for an answer that would otherwise be refused
    as depending on the coordinate) also reduces fractions and odd powers, modulo every
    sin²u + cos²u − 1 at once, by polynomial remainders.

    >>> th, ph, thd, phd = sympy.symbols("theta phi thetadot phidot")
    >>> L = sympy.expand(thd**2*(sympy.cos(th)**2*sympy.cos(ph)**2 + sympy.cos(th)**2*sympy.sin(ph)**2)
    ...                  + phd**2*sympy.sin(th)**2*(sympy.sin(ph)**2 + sympy.cos(ph)**2))
    >>> sorted(map(str, without_hidden_coordinates(L, [th, ph]).free_symbols))
    ['phidot', 'theta', 'thetadot']
    """
    present = lagrangian.free_symbols & set(coordinates)
    if not present or not lagrangian.has(sympy.sin, sympy.cos):
        return lagrangian
    if not thorough:
        tidied = sympy.expand(tidy_trig(lagrangian))
        if tidied.free_symbols & set(coordinates) < present and _vanishes(tidied - lagrangian):
            return tidied
        return lagrangian
    # thorough: a fraction, or odd powers (sin³φ cos φ + sin φ cos³φ − sin φ cos φ = 0): numerator and
    # denominator reduced modulo sin²u + cos²u − 1 as polynomials in each cos u, for every angle u
    # (the φ terms of a top's pivot force cancel only once sin²θ + cos²θ = 1 is used too).
    angles = {f.args[0] for f in lagrangian.atoms(sympy.cos)} & {f.args[0] for f in lagrangian.atoms(sympy.sin)}
    pairs = {u: (sympy.Dummy("s"), sympy.Dummy("c")) for u in angles}
    replaced = lagrangian.xreplace({f(u): d for u, ds in pairs.items() for f, d in zip((sympy.sin, sympy.cos), ds)})
    numerator, denominator = sympy.fraction(sympy.together(replaced))
    try:
        for sine, cosine in pairs.values():
            identity = sine ** 2 + cosine ** 2 - 1
            numerator, denominator = (sympy.rem(sympy.expand(p), identity, cosine) for p in (numerator, denominator))
        reduced = sympy.cancel(numerator / denominator)
    except sympy.PolynomialError:  # an angle also inside a root or another function: not a polynomial
        return lagrangian
    reduced = reduced.xreplace({d: f(u) for u, ds in pairs.items() for f, d in zip((sympy.sin, sympy.cos), ds)})
    if reduced.free_symbols & set(coordinates) < present and _vanishes(reduced - lagrangian):
        return reduced
    return lagrangian


_TIDY_LIMIT = 200  # operations; the textbook scenes' numerators have at most 50


def _tidy_entry(expr: sympy.Expr) -> sympy.Expr:
    """Cheap simplification of one matrix entry (see :func:`tidy_trig`); an entry of more than
    three times :data:`_TIDY_LIMIT` operations is left as it is (a pendulum hung from a ring on a
    parabola: one residual of 1,154 operations took tidy_trig 1.5 s to bring to 834, and the
    multipliers from the Schur complement were shorter anyway)."""
    if sympy.count_ops(expr) > 3 * _TIDY_LIMIT:
        return expr
    return tidy_trig(expr)


def _denominator_ops(values: list[sympy.Expr]) -> int:
    """The longest denominator among ``values``, in operations."""
    return max((sympy.count_ops(sympy.fraction(v)[1]) for v in values), default=0)


def _solve_small(A: sympy.Matrix, b: sympy.Matrix) -> list[sympy.Expr]:
    """Solve a small system A x = b exactly, over a denominator written as people write it."""
    result = []
    for value in solve_augmented(A, b):
        numerator, denominator = sympy.fraction(value)
        if denominator.could_extract_minus_sign():
            numerator, denominator = -numerator, -denominator
        # A long numerator (a top's pivot force: a thousand operations) has no short form for
        # tidy_trig to find, and takes it seconds; the answer is tidied at the end anyway.
        if sympy.count_ops(numerator) <= _TIDY_LIMIT:
            numerator = tidy_trig(numerator)
        result.append(numerator / readable_denominator(denominator))
    return result


def _unique_solution(equations: list[sympy.Expr], unknowns: list[sympy.Symbol]) -> dict | None:
    """The one solution of the equations for the unknowns, consistent with every equation, or None."""
    try:
        solutions = sympy.solve(equations, unknowns, dict=True)
    except (NotImplementedError, ValueError, TypeError):
        return None
    if len(solutions) != 1 or set(solutions[0]) != set(unknowns):
        return None
    solution = solutions[0]
    if any(v.free_symbols & set(unknowns) for v in solution.values()):
        return None
    if not all(_vanishes(e.xreplace(solution)) for e in equations):
        return None
    return solution


def _vanishes(expr: sympy.Expr) -> bool:
    """Whether an expression is identically zero: numerically at generic points, then symbolically."""
    expr = sympy.sympify(expr, strict=True)  # an expression or a number, never text
    if expr == 0:
        return True
    symbols = sorted(expr.free_symbols, key=str)
    for shift in (0.0, 0.37):
        point = {s: 0.61 + 0.29 * i + shift for i, s in enumerate(symbols)}
        if abs(complex(expr.evalf(30, subs=point))) > 1e-20:
            return False
    # Zero to 20 digits at two generic points: a nonzero analytic expression would have to
    # vanish there by accident.
    return True


def _sample_parameters(scene: Scene) -> dict[sympy.Symbol, sympy.Expr]:
    """Numbers for the parameters: their `value`, else a generic point of their domain."""
    rng = numpy.random.default_rng(20261121)
    point = {}
    for p in scene.parameters.values():
        value = p.value if p.value is not None else p.domain.sample(rng)
        point[p.symbol] = sympy.Float(value, 30)
    return point
