"""The reduction to independent variables: a coordinate hidden by sin² + cos² is still cyclic."""

from __future__ import annotations

import random

import numpy
import pytest
import sympy

from grader.mechanics.answers import AnswerEvaluator
from grader.mechanics.lagrange import equations_of_motion
from grader.mechanics.reduction import Reduction
from grader.mechanics.scene import load_scene
from tests.mechanics.conftest import SCENES


def test_the_azimuth_of_a_spherical_pendulum_in_cartesian_coordinates_is_cyclic():
    # x = l sin θ cos φ, y = l sin θ sin φ: the expanded T has φ in sin²φ + cos²φ only.
    scene = load_scene(SCENES / "spherical_pendulum.toml")
    reduction = Reduction(scene)
    phi = scene.parametrization.variables["phi"]
    assert phi.symbol not in reduction.lagrangian.free_symbols
    m, l, g = (scene.namespace.symbol(n) for n in ("m", "l", "g"))
    theta = scene.parametrization.variables["theta"]
    expected = (m * l ** 2 / 2 * (theta.dot ** 2 + sympy.sin(theta.symbol) ** 2 * phi.dot ** 2)
                + m * g * l * sympy.cos(theta.symbol))
    assert sympy.simplify(reduction.lagrangian - expected) == 0
    evaluator = AnswerEvaluator(scene, equations_of_motion(scene))
    assert [u.name for u in evaluator.cyclic_coordinates()] == ["phi"]


def test_a_lagrangian_without_a_hidden_coordinate_is_kept_as_expanded():
    # The double pendulum's cos θ₁ cos θ₂ + sin θ₁ sin θ₂ would shorten, but removes no coordinate.
    scene = load_scene(SCENES / "double_pendulum.toml")
    reduction = Reduction(scene)
    assert reduction.lagrangian == sympy.expand(reduction.to_independent(scene.lagrangian))


def test_an_answer_free_of_a_coordinate_only_through_the_identity_is_not_refused():
    # A top's pivot force from the Schur complement carries sin^3(phi) cos(phi) + sin(phi) cos^3(phi)
    # - sin(phi) cos(phi) (times powers of sin(theta)): zero once sin^2 + cos^2 = 1 is used for both angles.
    from grader.mechanics.lagrange import derive

    d = derive(load_scene(SCENES / "heavy_top.toml"))
    phi = d.scene.namespace.symbol("phi")
    assert phi in d.eom.multipliers["pivotz"].free_symbols
    assert phi not in d.answers["vertical_pivot_force"].free_symbols


def test_a_lagrangian_whose_time_dependence_is_a_total_derivative_has_an_energy_integral():
    """A pendulum in a car accelerating at A: L_r has m A t l cos θ θ̇ + m A² t²/2, which is
    d/dt(m A t l sin θ) − m A l sin θ plus a function of t; the energy in the car's frame,
    m l² θ̇²/2 − m g l cos θ + m A l sin θ, is conserved (it was 'energy is not conserved')."""
    scene = load_scene(SCENES / "pendulum_accelerating_car.toml")
    reduction = Reduction(scene)
    assert scene.time in reduction.lagrangian.free_symbols
    h = reduction.jacobi_integral()
    m, g, l, A = (scene.namespace.symbol(n) for n in ("m", "g", "l", "A"))
    theta = scene.parametrization.variables["theta"]
    expected = (m * l ** 2 * theta.dot ** 2 / 2 - m * g * l * sympy.cos(theta.symbol)
                + m * A * l * sympy.sin(theta.symbol))
    assert sympy.simplify(h - expected) == 0


def test_a_driven_lagrangian_whose_time_dependence_is_not_a_total_derivative_has_none():
    """A pendulum whose string is paid out (l = l0 + v t): no energy integral."""
    scene = load_scene(SCENES / "pendulum_lengthening_string.toml")
    assert Reduction(scene).jacobi_integral() is None


def test_the_time_hidden_by_sin2_plus_cos2_is_removed_from_the_lagrangian():
    """A wire turned at ω in Cartesian coordinates: sin²ωt + cos²ωt in L_r, which is free of t."""
    scene = load_scene(SCENES / "bead_inclined_rotating_wire.toml")
    assert scene.time not in Reduction(scene).lagrangian.free_symbols


CART_PENDULUM = '''
id = "cart_pendulum"
title = "Pendulum hung from a cart free on a smooth floor"
statement = "A bob on a string of length l hangs from a cart of mass M free on a floor."
[parameters]
M = { dimension = "mass", domain = "positive", value = 2.0 }
m = { dimension = "mass", domain = "positive", value = 0.5 }
g = { dimension = "acceleration", domain = "positive", value = 9.81 }
l = { dimension = "length", domain = "positive", value = 0.7 }
[coordinates]
X = { dimension = "length" }
r = { dimension = "length", domain = "positive" }
theta = { dimension = "angle" }
[energy]
kinetic = "M/2*Xdot^2 + m/2*((Xdot + rdot*sin(theta) + r*thetadot*cos(theta))^2 + (r*thetadot*sin(theta) - rdot*cos(theta))^2)"
potential = "-m*g*r*cos(theta)"
[[constraints]]
name = "string"
f = "r - l"
'''


@pytest.mark.parametrize("source", ["cart_pendulum", "hoop_bead_incline", "cart_cylinder", "offcentre_wheel"])
def test_multipliers_with_cross_terms_in_the_mass_matrix_solve_the_augmented_system(source):
    """With a mass matrix that is not diagonal (a bob hung from a free cart, a bead in a rolling
    hoop), λ comes from k Euler–Lagrange rows rather than from a symbolic M⁻¹ (which took over a
    minute for the hoop); at random states it must equal λ of the full system [M Cᵀ; J 0] solved
    numerically."""
    from grader.mechanics.scene import parse_scene

    scene = (parse_scene(CART_PENDULUM, source="cart.toml") if source == "cart_pendulum"
             else load_scene(SCENES / f"{source}.toml"))
    eom = equations_of_motion(scene)
    reduction = AnswerEvaluator(scene, eom).reduction
    A, b = eom.system
    n = len(scene.coordinates)
    assert not A[:n, :n].is_diagonal()
    rng = random.Random(source)
    for _ in range(3):
        point = {p.symbol: sympy.Float(rng.uniform(0.3, 1.2), 30) for p in scene.parameters.values()}
        for u in reduction.independent.values():
            point[u.symbol], point[u.dot] = (sympy.Float(rng.uniform(-1.0, 1.0), 30) for _ in range(2))
        def numeric(e):
            return float(sympy.sympify(reduction.to_independent(e)).xreplace(point).evalf(30))

        An = numpy.array(A.applyfunc(numeric).tolist(), dtype=float)
        bn = numpy.array(b.applyfunc(numeric).tolist(), dtype=float).ravel()
        lam = numpy.linalg.solve(An, bn)[n:]
        for i, c in enumerate(scene.constraints):
            assert float(reduction.multipliers[c.name].xreplace(point).evalf(30)) == pytest.approx(lam[i], rel=1e-9, abs=1e-9)


@pytest.mark.parametrize("scene, answer, denominator", [
    # The rows' λ keeps the bead's 2M + m sin²(θ + α); the Schur complement spread it over sin α, sin θ.
    ("hoop_bead_incline", "bead_normal_force", "2*M + m*sin(alpha + theta)^2"),
    ("hoop_bead_incline", "friction_force", "2*M + m*sin(alpha + theta)^2"),
    # The Schur complement's λ is free of φ below the line; the rows' had sin(β − φ) cos(β + φ) +
    # sin(β + φ) cos(β − φ) (= sin 2β) there. Read in full it is m(R φ̇² + g cos φ/cos β ±
    # g sin β sin φ/(2 cos²β + 1))/2, where the budget lets the Pythagorean forms be tried.
    ("rod_ends_on_circle", "trailing_end_force",
     "4*(cos(2*beta) + 1)*(cos(2*beta) + 2) or cos(beta)*(2*cos(beta)^2 + 1)"),
    ("rod_ends_on_circle", "leading_end_force",
     "4*(cos(2*beta) + 1)*(cos(2*beta) + 2) or cos(beta)*(2*cos(beta)^2 + 1)"),
    # A diagonal mass matrix and two constraints: the Schur complement's determinant was of degree 4
    # in sines and cosines; the rows share the equation of motion's sin²β + 3 cos β cos θ cos(β − θ).
    ("rod_floor_inclined_wall", "wall_force", "sin(beta)^2 + 3*cos(beta)*cos(theta)*cos(beta - theta)"),
    ("rod_floor_inclined_wall", "floor_force", "sin(beta)^2 + 3*cos(beta)*cos(theta)*cos(beta - theta)"),
    ("rod_floor_inclined_wall", "angular_speed_squared", "l*(sin(beta)^2 + 3*cos(beta)*cos(theta)*cos(beta - theta))"),
    ("rod_floor_inclined_wall", "wall_force_halfway",
     "(sin(beta)^2 + 3*cos(beta)*cos(theta0/2)*cos(beta - theta0/2))^2"),
    # The rows' 2 × 2 block has the determinant sin(β − φ) cos(β + φ) + sin(β + φ) cos(β − φ) = sin 2β;
    # read in full (with m₂ − m₂ cos²β as m₂ sin²β) the answer is over (m₁ + m₂) cos β.
    ("dumbbell_in_circle", "track_force_1", "(m1 + m2)*sin(2*beta) or (m1 + m2)*cos(beta)"),
])
def test_constraint_forces_keep_the_shorter_denominator(derived, scene, answer, denominator):
    """With a mass matrix that has cross terms, or more than one constraint, λ is found both ways
    (Schur complement, Euler–Lagrange rows) and the shorter kept: each answer's denominator is the
    one people write."""
    d = derived(scene)
    _, below = sympy.fraction(sympy.together(d.answers[answer]))
    from grader.expressions import parse_expression

    expected = [parse_expression(one, d.scene.namespace).expr for one in denominator.split(" or ")]
    assert any(sympy.simplify(below / one).is_number for one in expected)
