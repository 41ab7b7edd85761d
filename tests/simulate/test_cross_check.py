"""The engine's reaction forces equal the simulation's along the motion, for every scene in problems/.

The engine solves the constrained Euler–Lagrange equations symbolically, once, for q̈ and λ as
functions of the state (:func:`grader.mechanics.lagrange.equations_of_motion`); the product
simulation compiles only M, F, J and b and solves the KKT system numerically at every sample
(:mod:`grader.simulate.compiled`). At every sample where all the scene's constraints hold, each
generalized reaction force Q_ij = λ_i ∂f_i/∂q_j of the engine, evaluated at the simulated state,
must equal the simulation's to 1e-6 relative (relative to the largest |Q| of that scene's run,
so that a force passing through zero is compared on its own scale).

New files in problems/ are picked up automatically; a scene whose run never has all its contacts
holding, or that does not move, fails rather than passing without a comparison.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import sympy

from grader.mechanics.lagrange import equations_of_motion
from grader.mechanics.scene import load_scene
from grader.simulate.compiled import parameter_values
from grader.simulate.trajectory import simulate_scene

PROBLEMS = sorted((Path(__file__).resolve().parents[2] / "problems").glob("*.toml"))
RTOL = 1e-6
# Scenes whose file values do not exercise the constraints: the sphere's body rests on the top
# (an equilibrium) unless pushed; the rough incline's disk slips from the start at its α.
PARAMETERS = {"incline_slipping": {"alpha": 0.5}}
INITIAL = {"sphere": {"thetadot": 0.5}}


@pytest.mark.parametrize("path", PROBLEMS, ids=[p.stem for p in PROBLEMS])
def test_engine_reaction_forces_equal_the_simulation_while_contacts_hold(path):
    scene = load_scene(path)
    motion = simulate_scene(scene, PARAMETERS.get(scene.id), t_end=1.5, samples=31,
                            initial=INITIAL.get(scene.id))
    holding = motion.active.all(axis=1)
    assert holding.sum() >= 10, f"{scene.id}: the constraints hold at only {holding.sum()} samples"
    assert np.ptp(motion.q[holding], axis=0).max() > 1e-3, f"{scene.id}: nothing moves"

    eom = equations_of_motion(scene)
    numbers = {scene.parameters[name].symbol: value
               for name, value in parameter_values(scene, PARAMETERS.get(scene.id)).items()}
    coordinates = list(scene.coordinates.values())
    state = [scene.time] + [c.symbol for c in coordinates] + [c.dot for c in coordinates]
    for i, constraint in enumerate(scene.constraints):
        for j, c in enumerate(coordinates):
            expr = eom.constraint_forces[constraint.name][c.name].xreplace(numbers)
            engine = sympy.lambdify(state, expr, modules="numpy")
            expected = np.array([float(engine(t, *q, *v)) for t, q, v in
                                 zip(motion.t[holding], motion.q[holding], motion.qdot[holding])])
            simulated = motion.forces[holding, i, j]
            scale = max(np.abs(expected).max(), np.abs(simulated).max(), 1e-300)
            assert np.abs(expected - simulated).max() <= RTOL * scale, (
                f"{scene.id}: Q_{constraint.name}_{c.name} differs by {np.abs(expected - simulated).max():.3g} "
                f"(scale {scale:.3g})")
