"""The augmented system [M Jᵀ; J 0]: solved over polynomial generators, sin² + cos² = 1 used."""

from __future__ import annotations


import pytest
import sympy
from sympy.polys.matrices import DomainMatrix

from grader.mechanics.augmented import _generators, solve_augmented
from grader.mechanics.lagrange import equations_of_motion
from grader.mechanics.scene import load_scene
from tests.mechanics.conftest import SCENES


def test_sympy_builds_no_polynomial_domain_over_a_sine_and_a_cosine_of_one_angle():
    # The fact the generators work around: sin α and cos α together give the slow EX domain.
    a, m = sympy.symbols("alpha m", positive=True)
    assert DomainMatrix.from_Matrix(sympy.Matrix([[m, sympy.sin(a)], [sympy.cos(a), 1]])).domain.is_EX


def test_function_values_and_roots_are_generators_outermost_first():
    x, y, w, t = sympy.symbols("x y omega t")
    root = sympy.sqrt(x ** 2 + y ** 2)
    found = _generators(sympy.Matrix([[sympy.sin(w * t) * root, sympy.cos(sympy.sqrt(x))]]))
    assert set(found) == {sympy.sin(w * t), root, sympy.cos(sympy.sqrt(x))}


def test_a_disk_rolling_down_a_sliding_wedge_is_solved_over_polynomials():
    # Six unknowns over sin α and cos α: 0.6 s on sympy's expression LU, a few ms over generators
    # (timed by grader bench derive, not here).
    scene = load_scene(SCENES / "disk_on_sliding_wedge.toml")
    eom = equations_of_motion(scene)
    m, M, g, alpha = (scene.namespace.symbol(n) for n in ("m", "M", "g", "alpha"))
    expected = -2 * m * g * sympy.sin(alpha) * sympy.cos(alpha) / (3 * M + m + 2 * m * sympy.sin(alpha) ** 2)
    assert sympy.simplify(eom.accelerations["X"] - expected) == 0


def test_the_pythagorean_identity_shortens_what_the_solve_leaves():
    # A slot turning at ω: the denominators m (x² + y²)(sin² ωt + cos² ωt) lose their last factor.
    scene = load_scene(SCENES / "turntable_slot_spring.toml")
    multiplier = equations_of_motion(scene).multipliers["slot"]
    x, y = (scene.namespace.symbol(n) for n in ("x", "y"))
    assert sympy.denom(sympy.together(multiplier)) == sympy.sqrt(x ** 2 + y ** 2)


@pytest.mark.parametrize("entries", [
    [[1, 0], [0, 1]],
    [["m", "sin(alpha)"], ["sin(alpha)", "-cos(alpha)"]],
    [["m", "sqrt(x**2 + 1)"], ["cos(omega*t)", "sin(omega*t)"]],
])
def test_the_solution_solves_the_system(entries):
    A = sympy.Matrix(entries).applyfunc(lambda e: sympy.sympify(e))
    b = sympy.Matrix([sympy.Symbol("g"), 1])
    x = sympy.Matrix(solve_augmented(A, b))
    assert (A * x - b).applyfunc(sympy.simplify) == sympy.zeros(2, 1)
