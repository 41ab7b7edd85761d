"""Where the bodies of a scene are: the optional ``[geometry]`` table that pictures use.

A scene's energies are written in its generalized coordinates, which say nothing about where to
draw a body. ``[geometry]`` gives the Cartesian map (x right, y up) of the points worth drawing, the
bars between them (a string, a rod) and fixed circles (a sphere, a hoop). Expressions go through our
parser like every other scene expression, and each must be a length. The engine never reads this
table: only the pictures of a simulation do.

.. code-block:: toml

    [geometry]
    points = { body = ["r*sin(theta)", "r*cos(theta)"] }
    bars = [["origin", "body"]]                 # "origin" is (0, 0); or a point's name
    circles = [{ centre = ["0", "0"], radius = "R" }]

Examples
--------
>>> from grader.mechanics.scene import load_scene
>>> geometry = load_scene("problems/sphere.toml").geometry
>>> sorted(geometry.points)
['body']
>>> geometry.points["body"]
(r*sin(theta), r*cos(theta))
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable

import sympy

__all__ = ["Circle", "Geometry", "ORIGIN", "read_geometry"]

ORIGIN = "origin"
_MAX_POINTS = 16


@dataclass(frozen=True)
class Circle:
    centre: tuple[sympy.Expr, sympy.Expr]
    radius: sympy.Expr


@dataclass(frozen=True)
class Geometry:
    """Points (name -> (x, y)), bars between two point names (``origin`` allowed) and circles."""

    points: dict[str, tuple[sympy.Expr, sympy.Expr]]
    bars: tuple[tuple[str, str], ...] = ()
    circles: tuple[Circle, ...] = field(default_factory=tuple)


def read_geometry(table: dict[str, Any], expression: Callable[[str, Any], sympy.Expr],
                  is_length: Callable[[str, sympy.Expr], None],
                  fail: Callable[[str, str], Exception]) -> Geometry | None:
    """Read a ``[geometry]`` table with the scene reader's own ``expression`` parser and checks.

    ``expression(key, text)`` parses in the scene's namespace, ``is_length(key, expr)`` raises when
    an expression is not a length, ``fail(key, problem)`` makes the scene error to raise.
    """
    if not table:
        return None
    raw_points = table.get("points") or {}
    if not raw_points:
        raise fail("geometry.points", "name at least one point to draw, as name = [x, y]")
    if len(raw_points) > _MAX_POINTS:
        raise fail("geometry.points", f"at most {_MAX_POINTS} points")
    points: dict[str, tuple[sympy.Expr, sympy.Expr]] = {}
    for name, pair in raw_points.items():
        if name == ORIGIN:
            raise fail(f"geometry.points.{name}", "'origin' is the fixed point (0, 0); choose another name")
        points[name] = _pair(f"geometry.points.{name}", pair, expression, is_length, fail)
    bars = []
    for i, bar in enumerate(table.get("bars") or []):
        for end in bar:
            if end != ORIGIN and end not in points:
                raise fail(f"geometry.bars[{i}]", f"unknown point '{end}' (points: {', '.join(points)}, origin)")
        bars.append((bar[0], bar[1]))
    circles = []
    for i, circle in enumerate(table.get("circles") or []):
        key = f"geometry.circles[{i}]"
        centre = _pair(f"{key}.centre", circle.get("centre", ["0", "0"]), expression, is_length, fail)
        radius = expression(f"{key}.radius", circle["radius"])
        is_length(f"{key}.radius", radius)
        circles.append(Circle(centre, radius))
    return Geometry(points, tuple(bars), tuple(circles))


def _pair(key, pair, expression, is_length, fail) -> tuple[sympy.Expr, sympy.Expr]:
    if not isinstance(pair, list) or len(pair) != 2:
        raise fail(key, "give [x, y]: two expressions (x to the right, y up)")
    parsed = []
    for axis, text in zip("xy", pair):
        value = expression(f"{key}.{axis}", str(text) if isinstance(text, (int, float)) else text)
        if value != 0:
            is_length(f"{key}.{axis}", value)
        parsed.append(value)
    return parsed[0], parsed[1]
