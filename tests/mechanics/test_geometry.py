"""The ``[geometry]`` table: a Cartesian map of the bodies, checked like every scene expression."""

from __future__ import annotations

import pytest
import sympy

from grader.mechanics.scene import SceneError, parse_scene

PENDULUM = '''
id = "p"
[parameters]
m = { dimension = "mass", domain = "positive" }
g = { dimension = "acceleration", domain = "positive" }
l = { dimension = "length", domain = "positive" }
[coordinates]
theta = { dimension = "angle" }
[energy]
kinetic = "m/2*l^2*thetadot^2"
potential = "-m*g*l*cos(theta)"
'''


def test_points_bars_and_circles_are_read_as_parsed_expressions():
    scene = parse_scene(PENDULUM + '''
[geometry]
points = { bob = ["l*sin(theta)", "-l*cos(theta)"] }
bars = [["origin", "bob"]]
circles = [{ centre = [0, 0], radius = "l/10" }]
''')
    theta, l = sympy.Symbol("theta", real=True), scene.parameters["l"].symbol
    x, y = scene.geometry.points["bob"]
    assert sympy.simplify(x - l * sympy.sin(theta)) == 0 and sympy.simplify(y + l * sympy.cos(theta)) == 0
    assert scene.geometry.bars == (("origin", "bob"),)
    assert scene.geometry.circles[0].radius == l / 10


def test_a_scene_without_geometry_has_none():
    assert parse_scene(PENDULUM).geometry is None


@pytest.mark.parametrize("table, message", [
    ('points = { bob = ["theta", "0"] }', "geometry.points.bob.x: must be a length"),
    ('points = { bob = ["l*sin(tehta)", "0"] }', "did you mean 'theta'"),
    ('points = { bob = ["l", "0"] }\nbars = [["origin", "bib"]]', "geometry.bars[0]: unknown point 'bib'"),
    ('points = { origin = ["l", "0"] }', "'origin' is the fixed point"),
    ('points = { bob = ["l", "0"] }\ncircles = [{ radius = "m" }]', "geometry.circles[0].radius: must be a length"),
    ('points = { bob = ["l", "0", "0"] }', "geometry"),
    ('pionts = { bob = ["l", "0"] }', "did you mean 'points'"),
    ('points = {}', "name at least one point"),
])
def test_bad_geometry_is_refused_with_the_key_and_the_fix(table, message):
    with pytest.raises(SceneError) as error:
        parse_scene(PENDULUM + "[geometry]\n" + table + "\n")
    assert message in str(error.value)
