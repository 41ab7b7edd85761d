"""Closed forms of a scene's ``[[answers]]``.

An answer's ``expr`` is written over parameters, coordinates and their dots/ddots, multipliers
``lambda_<c>``, constraint forces ``Q_<c>_<q>``, ``t`` and earlier answers. The engine replaces
multipliers, forces and accelerations by the solved equations of motion, moves to the independent
variables (:mod:`grader.mechanics.reduction`), removes velocities that ``in_terms_of`` does not
allow with the first integrals from ``[initial]`` (conserved momenta of cyclic coordinates, then
the Jacobi integral, i.e. energy), and simplifies.

An answer with ``where = "lhs = rhs"`` is a special value: its expression where the condition
holds, solved for the condition's one unknown (:mod:`grader.mechanics.special_values`).

Examples
--------
>>> from grader.mechanics.scene import load_scene
>>> from grader.mechanics.lagrange import equations_of_motion
>>> scene = load_scene("problems/sphere.toml") 
>>> evaluate_answers(scene, equations_of_motion(scene))[0]["normal_force"]
g*m*(3*cos(theta) - 2)
"""

from __future__ import annotations

import cmath
import contextlib
import contextvars

import sympy

from grader.mechanics import budget
from grader.mechanics.reduction import Reduction, without_hidden_coordinates
from grader.mechanics.scene import AnswerSpec, Scene, SceneError
from grader.mechanics.simplification import TIDY_MAX_OPS, factored_sums, human_form, joined_roots, seen_nonzero

# Whether u̇² may come from the motion of u alone beside coordinates that feel only a uniform force
# (AnswerEvaluator._uniformly_forced_squared). Off while an acceleration set to zero is solved: that
# names an equilibrium, read at rest where energy gave no u̇²(u) before (a bead resting relative to a
# hoop that rolls down an incline), and it stays so.
_UNIFORM_FORCE: contextvars.ContextVar[bool] = contextvars.ContextVar("uniform_force", default=True)


@contextlib.contextmanager
def without_uniform_force():
    """Within it, u̇² beside a uniformly forced coordinate is not formed (see _UNIFORM_FORCE)."""
    token = _UNIFORM_FORCE.set(False)
    try:
        yield
    finally:
        _UNIFORM_FORCE.reset(token)

# Set while a special value is taken along the motion from [initial]: coordinates that motion leaves at
# rest throughout (resting_coordinates) are at their start in what is reduced (the swinging Atwood machine
# released with its bob hanging straight down: ṙ² where r = L/4 needs no θ, θ̇).
_ALONG_THE_MOTION: contextvars.ContextVar[bool] = contextvars.ContextVar("along_the_motion", default=False)


@contextlib.contextmanager
def along_the_motion():
    """Within it, :meth:`AnswerEvaluator.reduce` puts the coordinates the motion leaves at rest at their start."""
    token = _ALONG_THE_MOTION.set(True)
    try:
        yield
    finally:
        _ALONG_THE_MOTION.reset(token)


__all__ = ["AnswerEvaluator", "evaluate_answers"]


def evaluate_answers(scene: Scene, eom) -> tuple[dict[str, sympy.Expr], dict[str, sympy.Equality],
                                                 dict[str, list[sympy.Expr]], dict[str, dict]]:
    """Closed form of every answer, for ``kind = "equation"`` answers the reference equation, the
    derived alternatives (a special value at several roots that nothing decides between), and for
    numeric answers without a closed form the root their unknown is at (special_values._implicit)."""
    with budget.step("reducing the scene to its independent coordinates"):
        evaluator = AnswerEvaluator(scene, eom)
    answers, equations = {}, {}
    for spec in scene.answers:
        # Printed with each product's roots joined (√(2gR/3)); later answers compute with the
        # evaluator's own value, which sympy keeps split. The answer is named when the budget runs
        # out anywhere in it, not only in the steps that name themselves.
        with budget.step("deriving its value", spec.name):
            value = _joined(evaluator.evaluate(spec))
        answers[spec.name] = value
        if spec.kind == "equation":
            equations[spec.name] = sympy.Eq(spec.expr, value, evaluate=False)
    alternatives = {name: [_joined(a) for a in values] for name, values in evaluator.alternatives.items()}
    return answers, equations, alternatives, evaluator.implicit


#: CPU seconds for joining an answer's roots for print (a frequency at a root of a cubic, Cardano's,
#: ran past the whole derivation's budget there).
_JOINED_BUDGET_S = 2.0


def _joined(value: sympy.Expr) -> sympy.Expr:
    if sympy.count_ops(value) > TIDY_MAX_OPS:
        return value  # (Cardano's root of a cubic: nothing to join that makes it readable)
    return budget.attempt(lambda: joined_roots(value), _JOINED_BUDGET_S, fallback=lambda: value)


def _factored(value: sympy.Expr) -> sympy.Expr:
    return budget.attempt(lambda: factored_sums(value), _FACTORED_BUDGET_S, fallback=lambda: value)


_FACTORED_BUDGET_S = 0.3


class AnswerEvaluator:
    """Evaluates answers one after another; later answers and conditions may use earlier ones."""

    def __init__(self, scene: Scene, eom):
        self.scene = scene
        self.reduction = Reduction(scene)
        # The scene with [initial] completed in the independent variables (see Reduction).
        self.scene = scene = self.reduction.scene
        self.reduction.solve(eom)
        subs = {k.multiplier: self.reduction.multipliers[k.name] for k in scene.constraints}
        subs.update(self.reduction.forces)
        subs.update(self.reduction.coordinate_accelerations)
        subs.update(self.reduction.accelerations)
        self.dynamics = subs
        self.values: dict[sympy.Symbol, sympy.Expr] = {}
        # Other right values of an answer, derived (special values at several admissible roots).
        self.alternatives: dict[str, list[sympy.Expr]] = {}
        # Numeric answers without a closed form: which root of which condition their unknown is at
        # (grader.expressions.implicit.Implicit, as JSON).
        self.implicit: dict[str, dict] = {}

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
        if spec.kind in ("maximum", "minimum"):
            from grader.mechanics.extremes import extreme_value

            if self.reduction.branch_end is not None:
                # (a function of the state is a formula on the branch its states are on, as a student
                # writes it; an extreme is one number over the whole motion, on both branches.) Checked
                # first: past the branch's end the formula turns complex, and the extreme's own search
                # said the motion "runs away" (a bead carried over the end of a spun ellipse's lower half).
                from grader.mechanics.special_values import motion_stays_on_the_branch

                motion_stays_on_the_branch(self, spec)
            value = extreme_value(self, spec)
        elif spec.kind == "small_oscillation" and len(self.reduction.independent) > 1:
            from grader.mechanics.oscillations import small_oscillation_with_cyclic_coordinates

            value = small_oscillation_with_cyclic_coordinates(self, spec)
        elif spec.where is not None:
            from grader.mechanics.special_values import special_value

            value = special_value(self, spec)
        else:
            with budget.step("expressing the answer in its variables", spec.name):
                value = self.reduce_in_time(spec, key)
        # Last, the small sums in it that factor shorter: cancelling and combining multiply out
        # M² + 2Mm + m² on the way, and it is (M + m)² in the answer.
        value = _factored(value)
        if spec.name in self.alternatives:
            self.alternatives[spec.name] = [_factored(a) for a in self.alternatives[spec.name]]
        self.values[spec.symbol] = value
        return value

    def reduce_in_time(self, spec: AnswerSpec, key: str) -> sympy.Expr:
        """The answer in its variables; with ``t`` among them and a coordinate not, along the motion.

        r in terms of r₀, ω and t is r₀ cosh ωt: the coordinates (and velocities) are replaced by
        the motion from [initial] in closed form (:mod:`grader.mechanics.motion`), where it has one
        in elementary functions. Otherwise the error says both what the answer still depends on
        and why the motion has no closed form.
        """
        target = self.target(spec)
        if target & (set(self._dependent_positions()) | set(self._dependent_velocities())):
            return self._in_dependent_positions(spec, target, key)
        try:
            return self.reduce(spec.expr, target, key)
        except SceneError as first:
            if spec.in_terms_of is None or self.scene.time not in target:
                raise
            from grader.mechanics.motion import motion_in_time

            try:
                motion = motion_in_time(self, key)
            except SceneError as refused:
                # The whole motion has no closed form, but the answer may need only cyclic coordinates
                # whose momenta give their motion alone (the centre of mass of two pucks on a spring).
                from grader.mechanics.motion import cyclic_motion_in_time

                cyclic = cyclic_motion_in_time(self)
                if cyclic:
                    value = self.reduce(spec.expr, target | self.state_symbols() | self.parameters, key)
                    along = human_form(value.xreplace(cyclic))
                    if not along.free_symbols & (self.state_symbols() - target):
                        return self.reduce(along, target, key)
                # Both: what the answer still depends on, and why the motion gives no closed form.
                raise SceneError(self.scene.source, key, f"{first.problem}; {refused.problem}") from None
            # Every parameter meanwhile: R in the block's y1 − Rφ cancels only along the motion.
            value = self.reduce(spec.expr, target | self.state_symbols() | self.parameters, key)
            return self.reduce(human_form(value.xreplace(motion)), target, key)

    def _dependent_positions(self) -> dict[sympy.Symbol, sympy.Expr]:
        """{coordinate: its map Φ(u, t)} for the scene coordinates that are not independent variables."""
        phi = self.reduction.phi
        return {c.symbol: phi[c.symbol] for c in self.scene.coordinates.values()
                if c.symbol in phi and phi[c.symbol] != c.symbol}

    def _dependent_velocities(self) -> dict[sympy.Symbol, sympy.Symbol]:
        """{ċ: c} for the scene coordinates c that are not independent variables."""
        dependent = self._dependent_positions()
        return {c.dot: c.symbol for c in self.scene.coordinates.values() if c.symbol in dependent}

    def _in_dependent_positions(self, spec: AnswerSpec, target: set[sympy.Symbol], key: str) -> sympy.Expr:
        """The answer in a coordinate c the constraints made dependent, for an independent u it leaves out.

        The answer is written in u first, then c = Φ(u) is read back: where Φ(u) itself appears
        (N = m g (3√(R² − x²) − 2R)/R on a sphere, y = √(R² − x²)) it becomes c, and u left over is
        replaced by every solution of Φ(u) = c, which must all give one value (an even function,
        x = ±√(R² − y²)); otherwise the answer is refused, naming the coordinates to ask it in.

        A velocity ċ of such a coordinate stands for the one u̇ it leaves out: ċ = Σ ∂Φ/∂w ẇ + ∂Φ/∂t
        solved for u̇ (on the sphere ẋ = −y ẏ/x), before the positions are read back.
        """
        dependent = self._dependent_positions()
        velocities = {c: d for d, c in self._dependent_velocities().items() if d in target}
        named = [c for c in dependent if c in target] + [d for d in velocities.values()]
        dot_of = {u.symbol: u.dot for u in self.reduction.independent.values()}
        velocity_swaps = {}
        for c, d in velocities.items():
            coordinates = dependent[c].free_symbols & set(dot_of)
            free = [u for u in coordinates if dot_of[u] not in target and u not in velocity_swaps.values()]
            if not free and all(dot_of[u] in target for u in coordinates):
                continue  # ẋ named beside ẏ: the answer in ẋ needs no ẏ
            if len(free) != 1:
                velocity_swaps = None
                break
            velocity_swaps[c] = free[0]
        named_positions = [c for c in dependent if c in target]
        swaps = {}
        for c in named_positions:
            coordinates = dependent[c].free_symbols & self.state_symbols(velocities=False)
            free = [u for u in coordinates if u not in target and u not in swaps.values()]
            if not free and coordinates <= target:
                continue  # x named beside y: the answer in x needs no y
            if len(free) != 1:
                break
            swaps[c] = free[0]
        refusal = SceneError(self.scene.source, f"answers ({spec.name}).in_terms_of",
                             f"cannot be written in {', '.join(str(c) for c in named)}: answers are "
                             f"expressed in {', '.join(self.reduction.independent)} (and their dots)")
        unswapped = [c for c in named_positions if c not in swaps
                     and not (dependent[c].free_symbols & self.state_symbols(velocities=False)) <= target]
        if unswapped or velocity_swaps is None:
            raise refusal
        inner = (target - set(named)) | set(swaps.values()) | set(velocity_swaps.values()) | {
            dot_of[u] for u in velocity_swaps.values()}
        value = self.reduce(spec.expr, inner, key)
        t = self.scene.time
        for c, u in velocity_swaps.items():
            phi = dependent[c]
            others = sum((sympy.diff(phi, w) * dot_of[w] for w in phi.free_symbols & set(dot_of) if w != u),
                         sympy.Integer(0))
            slope = sympy.diff(phi, u)
            if slope == 0:
                raise refusal
            value = value.xreplace({dot_of[u]: (velocities[c] - others - sympy.diff(phi, t)) / slope})
        for c, u in swaps.items():
            value = value.subs(dependent[c], c)
            if u not in value.free_symbols:
                continue
            try:
                solutions = sympy.solve(dependent[c] - c, u)
            except (NotImplementedError, ValueError):
                raise refusal from None
            candidates = [value.xreplace({u: r}) for r in solutions]
            if not candidates or not _one_value(candidates):
                raise refusal
            value = candidates[0]
            # On the branch the scene is on, c = ±√(…) has that sign: |y| is y above a sphere's centre.
            sign = 1 if _is_root(dependent[c]) else -1 if _is_root(-dependent[c]) else 0
            if sign:
                value = value.replace(lambda e: isinstance(e, sympy.Abs) and e.args[0] == c, lambda e: sign * c)
        if value.free_symbols - target:
            raise refusal
        return human_form(value)

    def target(self, spec: AnswerSpec, default_state: bool = True) -> set[sympy.Symbol]:
        """The symbols an answer may keep: its ``in_terms_of``, else parameters, t and the state; for a
        special value (``where``), else the parameters alone (all of them, those [initial] uses too):
        the moment or point the condition names is what the answer is taken at, so the unknown it is
        solved for (t for ``expr = "t"``) is never left in the answer."""
        if spec.in_terms_of is None and spec.where is not None and spec.kind != "small_oscillation":
            return set(self.parameters)
        if spec.in_terms_of is None:
            target = self.parameters | {self.scene.time}
            return target | self.state_symbols() if default_state else target
        target = set()
        allowed = self.parameters | self.state_symbols() | {self.scene.time} | {
            u.ddot for u in self.reduction.independent.values()}
        if spec.where is None and spec.kind in ("expression", "equation"):
            # A coordinate the constraints made dependent (the height y on a sphere whose answers
            # are otherwise in x) is read back through its map (see reduce_in_time), its velocity too.
            allowed = allowed | set(self._dependent_positions()) | set(self._dependent_velocities())
        for name in spec.in_terms_of:
            symbol = self.scene.namespace.symbol(name)
            if symbol not in allowed:
                names = ", ".join(self.reduction.independent)
                raise SceneError(self.scene.source, f"answers ({spec.name}).in_terms_of",
                                 f"'{name}' is not a parameter or an independent variable; answers are "
                                 f"expressed in {names} (and their dots)")
            target.add(symbol)
        return target

    def reduce(self, expr: sympy.Expr, target: set[sympy.Symbol], key: str, readable: bool = True,
               signs: dict | None = None) -> sympy.Expr:
        """``expr`` with dynamics solved, in the independent variables, free of what target excludes.

        ``readable=False``: cancelled (before velocities are eliminated), not tidied
        (:func:`human_form`), for a caller that only
        evaluates it or substitutes into it and tidies the result (tidying an expression in a
        coordinate that is then fixed costs most of a special value). A variable that only tidying
        removes is then left, and is an error as any other. ``signs``: {coordinate name: ±1}, the
        sign of a velocity eliminated at an odd power, instead of the one it starts with (a special
        point reached after the motion has turned back).
        """
        expr = expr.xreplace(self.values)
        keep = {s for s in target if s.name.endswith("ddot")}
        dynamics = {s: v for s, v in self.dynamics.items() if s not in keep}
        expr = expr.xreplace(dynamics)
        expr = self.reduction.to_independent(expr)
        if expr not in self.values.values():
            # (An earlier answer read again, by a condition on it or an answer that is it, is in its
            # readable form already.)
            expr = human_form(expr) if readable else sympy.cancel(expr)
        expr = self._at_rest_along_the_motion(expr, target, readable)
        expr = self.eliminate_velocities(expr, target, key, readable=readable, signs=signs)
        # (The energy that removed a velocity may bring in the resting ones: ṙ² beside m r² θ̇².)
        expr = self._at_rest_along_the_motion(expr, target, readable)
        leftover = expr.free_symbols - target
        hidden = leftover & self.state_symbols(velocities=False)
        if hidden:
            # A coordinate present only through sin² + cos² (the azimuth in a top's pivot force,
            # from a map in Cartesian coordinates) is not a dependence: remove it with the identity.
            tidied = without_hidden_coordinates(expr, list(hidden), thorough=True)
            if tidied is not expr:
                expr = human_form(tidied) if readable else tidied
                leftover = expr.free_symbols - target
        if leftover:
            names = ", ".join(sorted(str(s) for s in leftover))
            wanted = ", ".join(sorted(str(s) for s in target)) or "nothing"
            raise SceneError(self.scene.source, key,
                             f"cannot be written in terms of {wanted}: it still depends on {names}")
        return expr

    def _at_rest_along_the_motion(self, expr: sympy.Expr, target: set[sympy.Symbol], readable: bool) -> sympy.Expr:
        """expr with the coordinates the motion from [initial] leaves at rest at their start, inside
        :func:`along_the_motion` and where it depends on them (and target does not name them)."""
        if not _ALONG_THE_MOTION.get() or not (expr.free_symbols - target) & set(self.resting_coordinates()):
            return expr
        if {u.symbol for u in self.reduction.independent.values()} <= set(self.resting_coordinates()):
            # Every coordinate at rest where nothing accelerates: an equilibrium the motion leaves by the
            # push every search assumes (a body released at the top of a sphere), not a motion at rest.
            return expr
        rest = {s: e for s, e in self.resting_coordinates().items() if s not in target}
        expr = expr.xreplace(rest)
        return human_form(expr) if readable else sympy.cancel(expr)

    def eliminate_velocities(self, expr: sympy.Expr, target: set[sympy.Symbol], key: str,
                             readable: bool = True, signs: dict | None = None) -> sympy.Expr:
        """Remove velocities that target excludes with the first integrals of the motion.

        First the conserved momenta p_c = ∂L_r/∂u̇_c of cyclic coordinates (∂L_r/∂u_c = 0), all
        at once (they are linear in the velocities), then the Jacobi integral h (energy) for one
        velocity more: u̇² from h = h(initial), or u̇ itself, as ±√, where the motion from
        [initial] fixes the sign (or ``signs`` gives it). ``readable=False``: the result not tidied
        (see :meth:`reduce`).
        """
        def tidy(e):
            return human_form(e) if readable else e

        extra = [u for u in self.reduction.independent.values()
                 if u.dot in expr.free_symbols and u.dot not in target]
        if not extra:
            return expr
        momenta = self.momentum_substitution(target, key)
        if momenta:
            expr = sympy.expand(expr.xreplace(momenta))
            # Every velocity left, including those the momenta brought in: the wedge's Ẋ is
            # −m cos α ṡ/(M + m) by momentum, and then ṡ goes by energy.
            extra = [u for u in self.reduction.independent.values()
                     if u.dot in expr.free_symbols and u.dot not in target]
            if not extra:
                return tidy(expr)
            # Not tidied yet: energy comes next, and the result is tidied once at the end.
        if len(extra) > 1:
            cyclic = ", ".join(u.name for u in self.cyclic_coordinates()) or "none"
            raise SceneError(self.scene.source, key,
                             f"{', '.join(u.dot.name for u in extra)} all remain: energy removes one velocity "
                             f"and each conserved momentum one more (cyclic coordinates: {cyclic}); add the "
                             "others to in_terms_of")
        u = extra[0]
        # u̇² readable either way: it is computed once for every answer, and its factors
        # (cos θ − cos θ₀) carry over to where it is substituted.
        squared = self.velocity_squared(u, key, momenta)
        # |A u̇| is √(A² u̇²) for real A: with u̇ = ±√(…) substituted into the bars, sympy wrote
        # |√z| as √(z·conj(z)) wherever it could not show z ≥ 0 (a speed where a ball leaves a loop).
        def even_powers(e):
            return e.replace(lambda p: p.is_Pow and p.base == u.dot and p.exp.is_Integer and p.exp % 2 == 0,
                             lambda p: squared ** (p.exp // 2))

        def bars(e):  # √(A²) with u̇² replaced at once (sympy would write √(u̇²) as |u̇| again)
            inner = even_powers(sympy.expand(e.args[0] ** 2))
            return e if u.dot in inner.free_symbols else sympy.sqrt(inner)

        expr = expr.replace(lambda e: isinstance(e, sympy.Abs) and u.dot in e.free_symbols, bars)
        expr = sympy.expand(expr)
        expr = even_powers(expr)
        if u.dot in expr.free_symbols:
            sign = (signs or {}).get(u.name) or self.motion_sign(u, pushed=True)
            if sign is None:
                raise SceneError(self.scene.source, key,
                                 f"{u.dot.name} appears to an odd power, so its sign is not fixed by energy "
                                 "conservation and the motion from [initial] does not fix it either; add it "
                                 "to in_terms_of")
            # Until the first turning point, u̇ keeps the sign it starts with (or, from rest,
            # the sign of the initial acceleration); a special point reached after it turns back
            # gets its sign from the caller (special_values._at_roots).
            expr = expr.xreplace({u.dot: sign * sympy.sqrt(squared)})
        return tidy(expr)

    def cyclic_coordinates(self) -> list:
        """Independent coordinates the reduced Lagrangian does not depend on."""
        L = self.reduction.lagrangian
        return [u for u in self.reduction.independent.values()
                if u.symbol not in L.free_symbols and u.dot in L.free_symbols]

    def momentum_substitution(self, target: set[sympy.Symbol], key: str) -> dict:
        """Velocities of cyclic coordinates (not in target) from their conserved momenta."""
        equations, unknowns = [], []
        for u in self.cyclic_coordinates():
            if u.dot in target:
                continue
            p = sympy.diff(self.reduction.lagrangian, u.dot)
            p0 = self.reduction.initial_value(p)
            if p0 is None:
                continue
            equations.append(p - p0)
            unknowns.append(u.dot)
        if not equations:
            return {}
        # A momentum is linear in the velocities (T is quadratic in them): one linear system, whose
        # matrix must be invertible, instead of a general solve that has no time bound.
        try:
            matrix, rhs = sympy.linear_eq_to_matrix(equations, unknowns)
        except (sympy.PolynomialError, ValueError):
            return {}
        determinant = sympy.cancel(matrix.det(method="berkowitz"))
        if determinant == 0:
            return {}
        solution = matrix.LUsolve(rhs)
        # Cancelled, not tidied for reading: they are only ever substituted into what is.
        return {v: sympy.factor(sympy.cancel(e)) for v, e in zip(unknowns, solution)}

    def resting_coordinates(self) -> dict:
        """{v: v₀, v̇: 0} for the independent coordinates that the motion from [initial] leaves at rest
        throughout: each starts at rest (v̇₀ = 0) where its acceleration vanishes identically, whatever
        the coordinates not in the set do, once every one in it is at its start. The motion then stays
        on that invariant subset (by uniqueness of the solution), and reduces to the others: an
        elastic pendulum released from rest hanging straight down (θ₀ = 0, θ̇₀ = 0: θ̈ = −(g sin θ +
        2 ṙ θ̇)/r = 0 there) only bounces in r, and energy gives ṙ²(r) with θ = 0.
        """
        cache = self.__dict__.get("_resting")
        if cache is not None:
            return cache
        initial = self.scene.initial
        candidates = {}
        for u in self.reduction.independent.values():
            start, speed = initial.get(u.name), initial.get(u.dot.name)
            if start is None or speed is None or start.free_symbols & self.state_symbols():
                continue
            if self._vanishes(speed):  # (budgeted: [initial] is the instructor's text)
                candidates[u] = start
        changed = True
        while changed and candidates:
            changed = False
            rest = {s: e for u, v0 in candidates.items() for s, e in ((u.symbol, v0), (u.dot, sympy.Integer(0)))}
            for u in list(candidates):
                acceleration = self.reduction.accelerations.get(u.ddot)
                if acceleration is None or not self._vanishes(acceleration.xreplace(rest)):
                    del candidates[u]
                    changed = True
                    break
        result = {s: e for u, v0 in candidates.items() for s, e in ((u.symbol, v0), (u.dot, sympy.Integer(0)))}
        self.__dict__["_resting"] = result
        return result

    @staticmethod
    def _vanishes(expr: sympy.Expr) -> bool:
        """Whether ``expr`` is identically zero (cancelled; simplified under a short budget)."""
        if expr == 0:
            return True
        cancelled = sympy.cancel(sympy.expand_trig(expr)) if expr.free_symbols else expr
        if cancelled == 0:
            return True
        if seen_nonzero(cancelled):
            return False  # simplify would only fail to find 0, slowly
        return budget.attempt(lambda: sympy.simplify(cancelled) == 0, 1.0, fallback=lambda: False)

    def motion_sign(self, u, pushed: bool = False) -> int | None:
        """The sign of u̇ at the start of the motion from [initial], if [initial] fixes it
        (``pushed``: at rest at an equilibrium, +1, the push the roots' search assumes)."""
        from grader.mechanics.special_values import _parameter_points

        velocity = self.scene.initial.get(u.dot.name)
        candidate = velocity
        if velocity is None or velocity == 0:
            acceleration = self.reduction.initial_value(self.reduction.accelerations[u.ddot])
            candidate = acceleration
        if candidate is None:
            return None
        signs = set()
        for point in _parameter_points(self.scene):
            value = complex(sympy.N(candidate.xreplace({s: sympy.Float(v, 30) for s, v in point.items()})))
            if abs(value.imag) > 1e-12:
                return None
            if value.real == 0:
                # At rest at an equilibrium (a disk on top of a cylinder): the infinitesimal push
                # forwards that the roots' search assumes (special_values._direction) and simulation
                # gives, when this is the one coordinate; with others, what moves it is not known.
                if (pushed and velocity is not None and len(self.reduction.independent) == 1
                        and sympy.simplify(candidate) == 0):
                    return 1
                return None
            signs.add(1 if value.real > 0 else -1)
        return signs.pop() if len(signs) == 1 else None

    def velocity_squared(self, u, key: str, momenta: dict | None = None, readable: bool = True) -> sympy.Expr:
        """u̇² from h(u, u̇) = h(initial), with conserved momenta substituted first (computed once).

        ``readable=False``: as solved from the energy, not tidied, for a caller that only evaluates
        it numerically (tidying it is much of the cost, and is then done only if something shows it).
        """
        cache_key = (u.name, tuple(sorted((str(k), str(v)) for k, v in (momenta or {}).items())),
                     _UNIFORM_FORCE.get())
        cache = self.__dict__.setdefault("_squared_cache", {})
        if (cache_key, False) not in cache:
            cache[cache_key, False] = self._velocity_squared(u, key, momenta)
        if not readable:
            return cache.get((cache_key, True), cache[cache_key, False])
        if (cache_key, True) not in cache:
            cache[cache_key, True] = human_form(cache[cache_key, False])
        return cache[cache_key, True]

    def _velocity_squared(self, u, key: str, momenta: dict | None) -> sympy.Expr:
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
        if momenta:
            h = sympy.expand(h.xreplace(momenta))
        others = {v.dot for v in self.reduction.independent.values() if v is not u} & h.free_symbols
        if others and not momenta and _UNIFORM_FORCE.get():
            squared = self._uniformly_forced_squared(u)
            if squared is not None:
                return squared
        poly = sympy.Poly(h, u.dot)
        # The linear term must vanish as a function, not only as written: with a momentum substituted it
        # is a sum of fractions that cancels (a block on a moving cart's track) and sympy leaves it so.
        if poly.degree() != 2 or sympy.cancel(poly.coeff_monomial(u.dot)) != 0:
            raise SceneError(self.scene.source, key,
                             f"the energy is not of the form a·{u.dot.name}² + c, so {u.dot.name} cannot be "
                             "eliminated")
        a, c = poly.coeff_monomial(u.dot ** 2), poly.coeff_monomial(1)
        return (h0 - c) / a

    def _uniformly_forced_squared(self, u) -> sympy.Expr | None:
        """u̇²(u) on the motion from [initial] when every other coordinate s feels a uniform force alone,
        or None.

        Such an s enters L = ½ q̇ᵀ M q̇ − V only through V ∋ −F s, F constant, with constant ṡ ṡ' entries
        E of M and ṡ u̇ entries c(u): a pendulum hung from a block sliding down an incline. Then
        d/dt(E ṡ + c u̇) = F: the momentum p = F t + p₀ that Routh's function keeps adds Fᵀ E⁻¹ c(u) to
        u's equation (its own terms in p cancel), so u moves in the potential V(u) + Fᵀ E⁻¹ ∫c du with the
        inertia a − cᵀ E⁻¹ c, and ½ (a − cᵀ E⁻¹ c) u̇² + V(u) + Fᵀ E⁻¹ ∫c du is conserved (energy, which
        holds ṡ and s, gives no u̇²(u)). On the incline of angle α the pendulum swings as on a free cart
        on level ground under g cos α, about the normal to the incline.
        """
        reduction = self.reduction
        L, t = reduction.lagrangian, self.scene.time
        others = [v for v in reduction.independent.values() if v is not u]
        if t in L.free_symbols or not others:
            return None
        velocities = [u.dot] + [v.dot for v in others]
        constants = self.parameters
        potential = -L.xreplace({d: 0 for d in velocities})
        forces = [sympy.expand(sympy.diff(L, v.symbol)) for v in others]
        if any(not f.free_symbols <= constants for f in forces) or all(f == 0 for f in forces):
            return None  # (no uniform force at all: the others are cyclic, their momenta handle them)
        own = sympy.expand(potential + sum(f * v.symbol for f, v in zip(forces, others)))
        if own.free_symbols & ({v.symbol for v in others} | set(velocities)):
            return None
        n = len(velocities)
        mass = sympy.Matrix(n, n, lambda i, j: sympy.expand(sympy.diff(L, velocities[i], velocities[j])))
        quadratic = (sympy.Matrix([velocities]) * mass * sympy.Matrix(velocities))[0] / 2
        if sympy.expand(L - quadratic + potential) != 0:
            return None  # terms linear in the velocities (or of a higher degree)
        E, c, a = mass[1:, 1:], mass[1:, 0], mass[0, 0]
        if not all(e.free_symbols <= constants for e in E) or \
                not all(e.free_symbols <= constants | {u.symbol} for e in [*c, a]):
            return None
        if sympy.cancel(E.det()) == 0:
            return None
        weights = E.LUsolve(sympy.Matrix(forces))  # E⁻¹ F

        def integral():
            total = sympy.integrate(sympy.expand(sum(w * ci for w, ci in zip(weights, c))), u.symbol)
            return None if total.has(sympy.Integral) else total

        extra = budget.attempt(integral, 2.0, fallback=lambda: None)
        if extra is None:
            return None
        inertia = sympy.cancel(a - (c.T * E.LUsolve(c))[0])
        if inertia == 0:
            return None
        h0 = reduction.initial_value(inertia * u.dot ** 2 / 2 + own + extra)
        if h0 is None:
            return None
        return sympy.cancel(2 * (h0 - own - extra) / inertia)


def _one_value(candidates: list[sympy.Expr]) -> bool:
    """Whether expressions agree at a few generic points (branches of one answer giving one value)."""
    symbols = sorted(set().union(*(c.free_symbols for c in candidates)), key=str)
    for shift in (0.0, 0.23):
        point = {s: sympy.Float(0.31 + 0.17 * i + shift, 30) for i, s in enumerate(symbols)}
        try:
            values = [complex(c.evalf(30, subs=point)) for c in candidates]
        except (TypeError, ValueError):  # zoo, or a value evalf leaves symbolic: not shown to agree
            return False
        if not all(cmath.isfinite(v) for v in values) \
                or any(abs(v - values[0]) > 1e-20 * max(1.0, abs(values[0])) for v in values):
            return False  # a nan compares as agreeing with everything: it shows nothing
    return True


def _is_root(expr: sympy.Expr) -> bool:
    """Whether an expression is a square root (nonnegative wherever it is real)."""
    return isinstance(expr, sympy.Pow) and expr.exp == sympy.S.Half
