"""Numerical motion of a scene, independent of the symbolic engine.

- :mod:`grader.simulate.lagrangian_numeric`: mass matrix, forces, constraint Jacobian and bias of
  a scene given as numeric callables, by differences at high precision; the KKT solve at one
  instant (:func:`~grader.simulate.lagrangian_numeric.snapshot`).
- :mod:`grader.simulate.manifold`: projecting a state onto the constraints f = 0, ḟ = 0.
- :mod:`grader.simulate.constrained`: integrating the constrained motion, with events
  (:func:`~grader.simulate.constrained.simulate`).
- :mod:`grader.simulate.scene_numeric`: a scene file's expressions as those callables, and its
  named quantities at a state (:class:`~grader.simulate.scene_numeric.SceneModel`).

Nothing is imported here, so that importing one module does not pay for the others.
"""
