"""A simulated trajectory as pictures: its time plot, and an animation from the scene's ``[geometry]``.

The drawing itself is :mod:`grader.simulate.pictures` (script-free SVG); this module only turns a
:class:`~grader.simulate.trajectory.Trajectory` into what those functions take. The geometry's
expressions were built by our parser from a validated scene, so compiling them with ``lambdify``
is safe.

Examples
--------
>>> from grader.mechanics.scene import load_scene
>>> from grader.simulate.trajectory import simulate_scene
>>> scene = load_scene("problems/sphere.toml")
>>> motion = simulate_scene(scene, t_end=1.0, samples=11, initial={"theta": 0.3})
>>> svg = animation_of(scene, motion, {"m": 0.2, "g": 9.81, "R": 0.8})
>>> svg.startswith("<svg") and "<animate" in svg
True
"""

from __future__ import annotations

from typing import Mapping

import numpy as np
import sympy

from grader.simulate.pictures import Drawing, animation_svg, plot_svg

__all__ = ["animation_of", "plot_of"]


def plot_of(trajectory, title: str = "Motion") -> str:
    """The time plot: coordinates above, each constraint's multiplier below, events marked."""
    data = trajectory.to_json()
    return plot_svg(data["samples"], data["events"], coordinates=list(trajectory.coordinates),
                    reactions=[f"lambda_{c}" for c in trajectory.constraints], title=title)


def animation_of(scene, trajectory, values: Mapping[str, float]) -> str:
    """The motion of the scene's ``[geometry]`` points over the samples, as an SVG animation.

    Raises
    ------
    ValueError
        When the scene has no ``[geometry]``.
    """
    geometry = getattr(scene, "geometry", None)
    if geometry is None:
        raise ValueError(f"{scene.source}: no [geometry] table says where to draw the bodies")
    numbers = {p.symbol: float(values[name]) for name, p in scene.parameters.items()}
    coordinates = [c.symbol for c in scene.coordinates.values()]
    arguments = [scene.time] + coordinates
    points = {}
    for name, (x, y) in geometry.points.items():
        function = sympy.lambdify(arguments, [x.xreplace(numbers), y.xreplace(numbers)], modules="numpy",
                                  dummify=True)
        points[name] = [tuple(float(v) for v in np.broadcast_to(function(t, *q), (2,)))
                        for t, q in zip(trajectory.t, trajectory.q)]
    fixed = {"origin": (0.0, 0.0)}
    bars = [tuple(fixed.get(end, end) for end in bar) for bar in geometry.bars]
    circles = [tuple(float(sympy.N(e.xreplace(numbers))) for e in (*c.centre, c.radius)) for c in geometry.circles]
    drawing = Drawing([float(t) for t in trajectory.t], points, bars, circles)
    return animation_svg(drawing, title=scene.title)
