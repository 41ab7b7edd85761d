"""Numerical motion of a scene.

The independent confirmation of the symbolic engine (the tests' numerical experiment; it never
sees the engine's results):

- :mod:`grader.simulate.lagrangian_numeric`: mass matrix, forces, constraint Jacobian and bias of
  a scene given as numeric callables, by differences at high precision; the KKT solve at one
  instant (:func:`~grader.simulate.lagrangian_numeric.snapshot`).
- :mod:`grader.simulate.manifold`: projecting a state onto the constraints f = 0, ḟ = 0.
- :mod:`grader.simulate.constrained`: integrating the constrained motion, with events
  (:func:`~grader.simulate.constrained.simulate`).
- :mod:`grader.simulate.scene_numeric`: a scene file's expressions as those callables, and its
  named quantities at a state (:class:`~grader.simulate.scene_numeric.SceneModel`).

The product path of ``grader simulate`` (fast, compiled from the scene's expressions):

- :mod:`grader.simulate.compiled`: M, F, J and b of a scene compiled to numpy once; the KKT solve.
- :mod:`grader.simulate.effects`: the effects a scene declares (unilateral, rolling with friction).
- :mod:`grader.simulate.initial`: the ``[initial]`` state completed by the constraints.
- :mod:`grader.simulate.trajectory`: the event-driven integration, trajectory, reactions and events
  (:func:`~grader.simulate.trajectory.simulate_scene`).
- :mod:`grader.simulate.plot`: a trajectory as pictures (:mod:`grader.simulate.pictures`).

Nothing is imported here, so that importing one module does not pay for the others.
"""
