"""Special values by condition: which unknown, which root, and what is said when there is none."""

from __future__ import annotations

import time
from pathlib import Path

import pytest
import sympy

from grader.expressions import parse_expression
from grader.mechanics.lagrange import derive
from grader.mechanics.scene import SceneError, parse_scene
from grader.mechanics.special_values import solve_for

SCENES = Path(__file__).resolve().parent / "scenes"


def scene_text(name: str, *replacements: tuple[str, str]) -> str:
    text = (SCENES / f"{name}.toml").read_text(encoding="utf-8")
    for old, new in replacements:
        assert old in text, old
        text = text.replace(old, new)
    return text


def test_a_cubic_in_sin_theta_is_solved_as_a_polynomial_in_s_quickly():
    """A direct solve of such a cubic in θ could hang for minutes; in S = sin θ it is instant."""
    theta = sympy.Symbol("theta", real=True)
    m1, m2 = sympy.symbols("m1 m2", positive=True)
    condition = 3 * m1 * sympy.sin(theta) ** 3 - 2 * m2 * sympy.sin(theta) + m1 - m2
    start = time.process_time()
    roots = solve_for(condition, theta, "f.toml", "k")
    assert time.process_time() - start < 2.0
    point = {m1: 1.3, m2: 2.1}
    real = [complex(r.evalf(subs=point)) for r in roots]
    real = [v.real for v in real if abs(v.imag) < 1e-12]
    assert len(real) == 4  # two real roots in S, each at θ and π − θ
    for v in real:
        assert abs(float(condition.subs(theta, v).evalf(subs=point))) < 1e-12


def test_the_sign_of_a_steady_orbits_velocity_is_the_one_the_motion_gives():
    """Launched clockwise (φ̇₀ = -ω₀), the steady orbit's φ̇ is the negative root."""
    scene = parse_scene(scene_text("table_hole_orbit", ('phidot = "omega0"', 'phidot = "-omega0"')), "t.toml")
    value = derive(scene).answers["steady_angular_velocity"]
    expected = parse_expression("-sqrt(m2*g/(m1*r))", scene.namespace).expr
    assert sympy.simplify(value - expected) == 0


def test_roots_with_different_values_and_no_motion_to_decide_are_named():
    """Without [initial], θ̈ = 0 holds at 0, π and ±acos(g/(a ω²)), where cos θ differs."""
    text = scene_text("bead_hoop_equilibrium", ("[initial]\ntheta = 0.3\nthetadot = 0\n", ""))
    with pytest.raises(SceneError, match="several roots for theta with different answers") as caught:
        derive(parse_scene(text, "hoop.toml"))
    assert caught.value.key == "answers (equilibrium_cos).where"


def test_small_oscillations_about_an_unstable_equilibrium_are_refused():
    """Spinning faster than √(g/a), the hoop's lowest point is unstable."""
    text = scene_text("bead_hoop_equilibrium",
                      ('kind = "small_oscillation"\nexpr = "theta"\nwhere = "thetaddot = 0"',
                       'kind = "small_oscillation"\nexpr = "theta"\nwhere = "theta = 0"'))
    with pytest.raises(SceneError, match="unstable"):
        derive(parse_scene(text, "hoop.toml"))


def test_a_condition_that_does_not_fix_what_the_answer_needs_is_refused():
    """θ̇ = ω fixes a velocity, but cos θ needs θ (no [initial], so no energy to tie them)."""
    text = scene_text("bead_hoop_equilibrium", ("[initial]\ntheta = 0.3\nthetadot = 0\n", ""),
                      ('where = "thetaddot = 0"\n\n[[answers]]', 'where = "thetadot = omega"\n\n[[answers]]'))
    with pytest.raises(SceneError, match="still depends on theta"):
        derive(parse_scene(text, "hoop.toml"))
