"""Extreme mass ratios: an Atwood machine with 1e-6 kg against 1e6 kg, and bodies with no mass.

Over a light pulley (y1 + y2 = 0) the heavy mass falls at a = g (m2 − m1)/(m1 + m2) and the string
tension is T = 2 m1 m2 g/(m1 + m2) ≈ 2 m1 g: the KKT system mixes entries 12 orders of magnitude
apart, and the tension, tiny beside the heavy weight, must still come out to 1e-9 relative.
A massless body is handled when a constraint carries it (a massless end of the string: T = 0,
the other falls freely), and refused with a clear error when nothing determines its motion.
"""

from __future__ import annotations

import pytest
from click.testing import CliRunner

from grader.cli import main
from grader.mechanics.scene import parse_scene
from grader.simulate.compiled import SingularDynamics
from grader.simulate.trajectory import simulate_scene

G = 9.81


def atwood(m1: float, m2: float):
    return parse_scene(f'''
id = "atwood"
[parameters]
m1 = {{ dimension = "mass", domain = "nonnegative", value = {m1!r} }}
m2 = {{ dimension = "mass", domain = "nonnegative", value = {m2!r} }}
g = {{ dimension = "acceleration", domain = "positive", value = 9.81 }}
[coordinates]
y1 = {{ dimension = "length" }}
y2 = {{ dimension = "length" }}
[energy]
kinetic = "m1/2*y1dot^2 + m2/2*y2dot^2"
potential = "m1*g*y1 + m2*g*y2"
[[constraints]]
name = "string"
f = "y1 + y2"
[initial]
y1 = 0
y1dot = 0
''', source="atwood.toml")


@pytest.mark.parametrize("m1, m2", [(1e-6, 1e6), (1e6, 1e-6), (1e-6, 1.0)])
def test_tension_and_acceleration_hold_at_extreme_mass_ratios(m1, m2):
    motion = simulate_scene(atwood(m1, m2), t_end=1.0, samples=3)
    tension = 2 * m1 * m2 * G / (m1 + m2)
    assert motion.multipliers[-1, 0] == pytest.approx(tension, rel=1e-9)
    # y1 rises by a t²/2 with a = g (m2 − m1)/(m1 + m2).
    assert motion.q[-1, 0] == pytest.approx(G * (m2 - m1) / (m1 + m2) / 2, rel=1e-9, abs=1e-20)


def test_a_massless_body_on_the_string_is_carried_by_the_constraint():
    motion = simulate_scene(atwood(0.0, 2.0), t_end=1.0, samples=3)
    assert motion.multipliers[-1, 0] == 0.0                  # a massless end needs no tension
    assert motion.q[-1, 1] == pytest.approx(-G / 2, rel=1e-12)  # the other falls freely


FREE_PAIR = parse_scene('''
id = "pair"
[parameters]
m = { dimension = "mass", domain = "nonnegative", value = 1.0 }
mu = { dimension = "mass", domain = "nonnegative", value = 1.0 }
g = { dimension = "acceleration", domain = "positive", value = 9.81 }
[coordinates]
x = { dimension = "length" }
z = { dimension = "length" }
[energy]
kinetic = "m/2*xdot^2 + mu/2*zdot^2"
potential = "mu*g*z"
''', source="pair.toml")


def test_a_massless_body_that_nothing_constrains_is_refused_with_a_clear_error():
    with pytest.raises(SingularDynamics, match="a body without mass"):
        simulate_scene(FREE_PAIR, {"mu": 0.0}, t_end=1.0)


def test_the_command_line_refuses_a_massless_body_in_one_line(tmp_path):
    path = tmp_path / "pair.toml"
    path.write_text(FREE_PAIR.text)
    result = CliRunner().invoke(main, ["simulate", str(path), "--set", "mu=0"])
    assert result.exit_code == 2
    assert len(result.output.strip().splitlines()) == 1 and "without mass" in result.output
