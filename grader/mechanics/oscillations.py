"""Small oscillations of one coordinate when the others are cyclic (Routh's reduction) or absent
from its equation.

``kind = "small_oscillation"`` in a scene of one degree of freedom is a special value
(:mod:`grader.mechanics.special_values`): ω² = −∂ü/∂u at the equilibrium. With more degrees of
freedom the textbook cases are those where every other coordinate is **cyclic**: the cart of a
pendulum hung from a freely sliding cart, the azimuth of a conical pendulum or of a particle
circling inside a cone. Their momenta p = ∂L_r/∂q̇ are conserved, fixed by ``[initial]``, so
replacing their velocities by the momenta leaves one equation for u alone, ü = f(u, u̇) (Routh's
reduced motion). The frequency is that of f linearised at rest about the equilibrium ``where``
names:

    ω² = −∂f/∂u (u*, u̇ = 0),   f(u*, 0) = 0.

So the pendulum on a cart oscillates with ω² = (M + m) g/(M ℓ), faster than on a fixed support,
and a conical pendulum at θ₀ with ω² = g (1 + 3 cos²θ₀)/(ℓ cos θ₀). The equilibrium is a relative
one when momenta are not zero (the steady conical motion), and it must be one for those momenta:
``where = "theta = theta0"`` is refused if [initial] does not start a steady motion there.

A coordinate that is not cyclic but leaves ü free of itself and its velocity does not matter either:
a pendulum hung from a block sliding down a smooth incline (the block's s enters only through the
uniform force of gravity along the slope) swings about the normal to the incline with
ω² = (M + m) g cos α/(M ℓ), whatever the block does.

Examples
--------
>>> from grader.mechanics.lagrange import derive
>>> from grader.mechanics.scene import load_scene
>>> derive(load_scene("tests/mechanics/scenes/pendulum_sliding_support.toml")).answers["small_oscillation_frequency"]
sqrt(g*(M + m)/(M*l))
"""

from __future__ import annotations

import sympy

from grader.mechanics import budget
from grader.mechanics.scene import AnswerSpec, SceneError
from grader.mechanics.special_values import (
    FREQUENCY_TIDY_S,
    _check_stable,
    _choose_root,
    _essential,
    check_equilibrium,
    _no_leftover,
    frequency_form,
    roots_in_domain,
    solve_for,
    tidied_within,
)

__all__ = ["small_oscillation_with_cyclic_coordinates"]


def small_oscillation_with_cyclic_coordinates(evaluator, spec: AnswerSpec) -> sympy.Expr:
    """ω of small oscillations of ``spec.expr`` about ``spec.where``, the other coordinates cyclic."""
    scene = evaluator.scene
    key = f"answers ({spec.name}).where"
    reduction = evaluator.reduction
    u = next((v for v in reduction.independent.values() if v.symbol == spec.expr), None)
    if u is None:
        raise SceneError(scene.source, f"answers ({spec.name}).expr",
                         "expr must be one of the independent coordinates "
                         f"({', '.join(reduction.independent)}): the one that oscillates")
    others = [v for v in reduction.independent.values() if v is not u]
    cyclic = evaluator.cyclic_coordinates()
    not_cyclic = [v for v in others if v not in cyclic]
    with budget.step("reducing to one coordinate with the conserved momenta", spec.name):
        momenta = evaluator.momentum_substitution(set(), key)
        if not_cyclic:
            # A coordinate the Lagrangian depends on does not matter when ü, the others' accelerations
            # eliminated, is free of it and its velocity: a pendulum hung from a block sliding down an
            # incline (the block's s enters only as the uniform force's potential, ü = f(u, u̇)).
            coupled = {s for v in not_cyclic for s in (v.symbol, v.dot)} | {scene.time}
            full = reduction.accelerations[u.ddot].xreplace(momenta)
            if full.free_symbols & coupled and sympy.cancel(full).free_symbols & coupled:
                names = ", ".join(v.name for v in not_cyclic)
                raise SceneError(scene.source, f"answers ({spec.name}).expr",
                                 f"small oscillations of {u.name} with other degrees of freedom are computed "
                                 "when the others are cyclic (their momenta conserved, Routh's reduction) or "
                                 f"absent from {u.ddot.name} (a block sliding down an incline under a pendulum); "
                                 f"{names} {'is' if len(not_cyclic) == 1 else 'are'} not: the Lagrangian "
                                 f"depends on it, and so does {u.ddot.name}. Normal modes of several coupled "
                                 "coordinates are not computed")
        missing = [v.name for v in others if v in cyclic and v.dot not in momenta]
        if missing:
            raise SceneError(scene.source, key,
                             f"the conserved momenta of {', '.join(missing)} come from [initial]; give the "
                             f"initial values of {', '.join(reduction.independent)} and their velocities")
        rest = {u.dot: 0}
        # ü = f(u) at rest in u, the cyclic velocities written with their momenta.
        acceleration = sympy.cancel(reduction.accelerations[u.ddot].xreplace(momenta).xreplace(rest))
        state = evaluator.state_symbols() - {u.symbol}
        if acceleration.free_symbols & state:
            names = ", ".join(sorted(map(str, acceleration.free_symbols & state)))
            raise SceneError(scene.source, key, f"with the conserved momenta, {u.ddot.name} still depends on {names}")
        stiffness = -sympy.diff(acceleration, u.symbol)
    with budget.step("reducing the condition", spec.name):
        lhs, rhs = spec.where
        everything = evaluator.parameters | evaluator.state_symbols() | {scene.time}
        condition = evaluator.reduce(lhs - rhs, everything, key).xreplace(momenta).xreplace(rest)
        condition = _essential(sympy.cancel(condition))
        if u.symbol not in condition.free_symbols or condition.free_symbols & state:
            raise SceneError(scene.source, key,
                             f"the equilibrium must be a condition on {u.name} alone (at rest in {u.name}, "
                             "the cyclic velocities given by their momenta)")
    with budget.step(f"solving the condition for {u.name}", spec.name):
        roots = roots_in_domain(evaluator, condition, u.symbol, solve_for(condition, u.symbol, scene.source, key))
    with budget.step("evaluating the frequency at the equilibrium", spec.name):
        chosen, *_ = _choose_root(evaluator, spec, condition, u.symbol, roots, stiffness, key)
        check_equilibrium(scene, key, u, acceleration.xreplace({u.symbol: chosen}), chosen, momenta=True)
        # Tidied under a budget: at the root of a cubic (Cardano's) tidying ran past the whole 60 s.
        omega_squared = tidied_within(stiffness.xreplace({u.symbol: chosen}), FREQUENCY_TIDY_S)
        _check_stable(scene, spec, omega_squared)
        # √(g (M + m)/(M l)) as written, rather than sympy's √g·√(M + m)/(√M·√l).
        result = frequency_form(omega_squared)
    return _no_leftover(scene, spec, result, evaluator.target(spec, default_state=False))
