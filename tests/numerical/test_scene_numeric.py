"""The scene adapter: a scene file turned into numbers, without the engine.

The numerical experiment is only an independent check if it uses nothing but the instructor's
input; these tests pin that down (no symbolic differentiation or solving, no engine import) and
check that initial states, parametrization variables and answer definitions come out right.
"""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest
import sympy

from grader.mechanics.scene import parse_scene
from grader.simulate.constrained import simulate
from grader.simulate.lagrangian_numeric import snapshot
from grader.simulate.scene_numeric import SceneModel

SPHERE = """
id = "sphere"
[parameters]
m = { dimension = "mass", domain = "positive", value = 0.2 }
g = { dimension = "acceleration", domain = "positive", value = 9.81 }
R = { dimension = "length", domain = "positive", value = 0.8 }
[coordinates]
r = { dimension = "length", domain = "positive" }
theta = { dimension = "angle" }
[energy]
kinetic = "m/2*(rdot^2 + r^2*thetadot^2)"
potential = "m*g*r*cos(theta)"
[[constraints]]
name = "surface"
f = "r - R"
kind = "unilateral"
[initial]
theta = 0
thetadot = 0
[[answers]]
name = "normal_force"
expr = "lambda_surface"
[[answers]]
name = "half_normal_force"
expr = "normal_force/2"
"""

HALF_ATWOOD = """
id = "half_atwood"
[parameters]
m1 = { dimension = "mass", domain = "positive", value = 2.0 }
m2 = { dimension = "mass", domain = "positive" }
g = { dimension = "acceleration", domain = "positive", value = 9.81 }
L = { dimension = "length", domain = "positive", value = 1.5 }
[coordinates]
x = { dimension = "length" }
y = { dimension = "length" }
z = { dimension = "length" }
[energy]
kinetic = "m1/2*(xdot^2 + zdot^2) + m2/2*ydot^2"
potential = "m1*g*z - m2*g*y"
[[constraints]]
name = "string"
f = "x + y - L"
[[constraints]]
name = "table"
f = "z"
[initial]
x = "L/3"
xdot = -0.4
"""

PENDULUM = """
id = "pendulum"
[parameters]
m = { dimension = "mass", domain = "positive", value = 0.5 }
g = { dimension = "acceleration", domain = "positive", value = 9.81 }
l = { dimension = "length", domain = "positive", value = 1.2 }
theta0 = { dimension = "angle", domain = [0.01, 3.1], value = 2.5 }
[coordinates]
x = { dimension = "length" }
y = { dimension = "length" }
[energy]
kinetic = "m/2*(xdot^2 + ydot^2)"
potential = "m*g*y"
[[constraints]]
name = "string"
f = "l^2 - x^2 - y^2"
[parametrization.variables]
theta = { dimension = "angle" }
[parametrization.map]
x = "l*sin(theta)"
y = "-l*cos(theta)"
[initial]
theta = "theta0"
thetadot = 0
"""


def test_callables_reproduce_the_scene_expressions():
    scene = parse_scene(SPHERE)
    model = SceneModel(scene)
    point = {"r": 0.7, "theta": 0.3, "rdot": -0.2, "thetadot": 1.1}
    subs = {s: point.get(s.name, model.values.get(s.name)) for s in scene.kinetic.free_symbols
            | scene.potential.free_symbols | scene.constraints[0].f.free_symbols}
    q, v = [0.7, 0.3], [-0.2, 1.1]
    assert float(model.numeric.kinetic(q, v, 0.0)) == pytest.approx(float(scene.kinetic.evalf(subs=subs)), rel=1e-15)
    assert float(model.numeric.potential(q, 0.0)) == pytest.approx(float(scene.potential.evalf(subs=subs)), rel=1e-15)
    assert float(model.numeric.constraints[0].f(q, 0.0)) == pytest.approx(-0.1, rel=1e-14)
    assert model.numeric.constraints[0].unilateral


def test_equilibrium_at_rest_gets_a_tiny_push_in_the_named_velocity():
    # On top of the sphere nothing would ever move; r is not in [initial] and follows from r = R.
    start = SceneModel(parse_scene(SPHERE)).initial_state(push=1e-7)
    assert start.pushed == "thetadot"
    np.testing.assert_array_equal(start.q, [0.8, 0.0])
    np.testing.assert_allclose(start.qdot, [0.0, 1e-7], atol=1e-22)


def test_coordinates_missing_from_initial_are_solved_from_the_constraints():
    # x + y = L and z = 0 fix y and z; the string makes ẏ = -ẋ. m2 has no value: the fallback.
    model = SceneModel(parse_scene(HALF_ATWOOD), {"m2": 0.7})
    start = model.initial_state(push=1e-7)
    assert start.pushed is None  # the blocks accelerate: not an equilibrium
    np.testing.assert_allclose(start.q, [0.5, 1.0, 0.0], atol=1e-15)
    np.testing.assert_allclose(start.qdot, [-0.4, 0.4, 0.0], atol=1e-15)
    assert model.values["m2"] == 0.7


def test_a_parameter_without_value_or_fallback_is_an_error():
    with pytest.raises(KeyError, match="m2"):
        SceneModel(parse_scene(HALF_ATWOOD))


def test_parametrization_variables_follow_the_motion():
    # A wide swing from θ0 = 2.5 rad at rest: θ̈ = -(g/l) sin θ and θ̇² = 2 (g/l)(cos θ - cos θ0),
    # with θ recovered from (x, y) alone.
    model = SceneModel(parse_scene(PENDULUM))
    start = model.initial_state()
    np.testing.assert_allclose(start.q, [1.2 * math.sin(2.5), -1.2 * math.cos(2.5)], rtol=1e-15)
    motion = simulate(model.numeric, start.q, start.qdot, 3.0, sample_times=np.linspace(0, 3, 13))
    g_l = 9.81 / 1.2
    for s in motion.samples:
        values = model.quantities(s)
        theta = values["theta"]
        assert theta == pytest.approx(math.atan2(s.q[0], -s.q[1]), abs=1e-12)
        assert values["thetaddot"] == pytest.approx(-g_l * math.sin(theta), rel=1e-9, abs=1e-9)
        assert values["thetadot"] ** 2 == pytest.approx(2 * g_l * (math.cos(theta) - math.cos(2.5)), abs=1e-8)


def test_answer_names_stand_for_their_definitions():
    scene = parse_scene(SPHERE)
    model = SceneModel(scene)
    start = model.initial_state(push=1e-7)
    values = model.quantities(snapshot(model.numeric, start.t, start.q, start.qdot))
    # At the top the normal force is the weight, m g.
    assert model.evaluate(scene.answer("normal_force").expr, values) == pytest.approx(0.2 * 9.81, rel=1e-12)
    assert model.evaluate(scene.answer("half_normal_force").expr, values) == pytest.approx(0.1 * 9.81, rel=1e-12)
    with pytest.raises(KeyError, match="lambda_surface"):
        model.evaluate(scene.answer("normal_force").expr, {})


def test_the_experiment_never_differentiates_or_solves_symbolically(monkeypatch):
    def forbidden(*args, **kwargs):
        raise AssertionError("the numerical experiment must not use symbolic calculus")

    monkeypatch.setattr(sympy.core.function.Derivative, "__new__", forbidden)
    monkeypatch.setattr(sympy, "solve", forbidden)
    monkeypatch.setattr(sympy.solvers.solvers, "solve", forbidden)
    with pytest.raises(AssertionError):
        sympy.diff(sympy.Symbol("x") ** 2, sympy.Symbol("x"))  # the guard is in place

    scene = parse_scene(PENDULUM)
    model = SceneModel(scene)
    start = model.initial_state(push=1e-7)
    motion = simulate(model.numeric, start.q, start.qdot, 0.2, sample_times=[0.2])
    assert model.quantities(motion.samples[0])["thetaddot"] < 0


def test_the_simulation_package_does_not_import_the_engine():
    code = ("import sys, grader.simulate.scene_numeric, grader.simulate.constrained; "
            "print(sorted(m for m in sys.modules if m.startswith('grader.mechanics')))")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert result.stdout.strip() == "[]"
