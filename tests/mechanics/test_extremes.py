"""Extremes over the motion (grader.mechanics.extremes) when the motion is known in time.

A quantity that the motion makes a periodic function of t takes, over t ≥ 0, the values of one
period: its maximum or minimum is at t = 0 or a stationary point, checked against the closed form
derived by hand and against the function sampled over a period. A quantity not periodic in t is
refused with the reason (over an unbounded time it may have no extreme).
"""

from __future__ import annotations

from pathlib import Path

import pytest
import sympy

from grader.expressions import parse_expression
from grader.mechanics.extremes import _period
from grader.mechanics.lagrange import derive
from grader.mechanics.scene import SceneError, load_scene, parse_scene

PLANK = Path(__file__).resolve().parent / "scenes" / "cylinder_on_oscillating_plank.toml"


@pytest.fixture(scope="module")
def plank():
    return derive(load_scene(PLANK))


@pytest.mark.parametrize("answer, expected", [
    # friction −m A Ω² sin(Ωt)/3: largest at Ωt = 3π/2
    ("largest_friction", "m*A*Omega^2/3"),
    # ẋ = A Ω (cos Ωt − 1)/3: least at Ωt = π
    ("least_velocity", "-2*A*Omega/3"),
    # φ̇ = A Ω (2 cos Ωt + 1)/(3R): largest at the start, t = 0
    ("largest_spin", "A*Omega/R"),
])
def test_an_extreme_of_a_periodic_quantity_in_time_is_the_one_of_a_period(plank, answer, expected):
    want = parse_expression(expected, plank.scene.namespace).expr
    assert sympy.simplify(plank.answers[answer] - want) == 0


def _with_extreme(kind: str, expr: str) -> str:
    text = PLANK.read_text(encoding="utf-8")
    text = text[:text.index("[[answers]]")]
    return text + f'''
[[answers]]
name = "extreme"
kind = "{kind}"
expr = "{expr}"
'''


@pytest.mark.parametrize("kind, expr, words", [
    # x(t) = A (sin Ωt − Ωt)/3 drifts backwards: no minimum over an unbounded time
    ("minimum", "x", "the motion runs away"),
    ("maximum", "x*xdot", "periodic in t"),
    ("minimum", "x + A*Omega*t/3", None),  # = A sin(Ωt)/3: periodic once the drift is taken out
])
def test_a_quantity_not_periodic_in_time_is_refused_with_the_reason(kind, expr, words):
    scene = parse_scene(_with_extreme(kind, expr), "plank.toml")
    if words is None:
        value = derive(scene).answers["extreme"]
        assert sympy.simplify(value + parse_expression("A/3", scene.namespace).expr) == 0
        return
    with pytest.raises(SceneError) as refused:
        derive(scene)
    assert words in str(refused.value)


def test_a_coordinate_with_bounds_the_motion_may_leave_is_refused():
    """x ∈ [−1, 1]: the plank ends; the drifting cylinder rolls off it, so one period says nothing."""
    text = _with_extreme("maximum", "lambda_roll").replace('x = { dimension = "length" }',
                                                           'x = { dimension = "length", domain = [-1, 1] }')
    with pytest.raises(SceneError) as refused:
        derive(parse_scene(text, "plank.toml"))
    assert "bounded domain" in str(refused.value)


t, w, c = sympy.symbols("t omega c", positive=True)


@pytest.mark.parametrize("expr, period", [
    (sympy.sin(w * t), 2 * sympy.pi / w),
    (sympy.sin(w * t) + sympy.cos(3 * w * t / 2 + c), 4 * sympy.pi / w),
    (sympy.tan(2 * w * t) * sympy.cos(w * t), 2 * sympy.pi / w),
    (t * sympy.sin(w * t), None),  # t outside the functions
    (sympy.sin(w * t ** 2), None),  # not linear in t
    (sympy.sin(w * t) + sympy.sin(sympy.sqrt(2) * w * t), None),  # incommensurate
    (c * w, None),  # no t at all
])
def test_the_period_is_found_only_for_sines_and_cosines_of_commensurate_frequencies(expr, period):
    found = _period(expr, t)
    assert (found is None) if period is None else sympy.simplify(found - period) == 0


POLE = Path(__file__).resolve().parent / "scenes" / "spherical_pendulum_through_the_pole.toml"
# ż = l sin θ θ̇ with θ̇² = 2g(cos θ − cos θ₀)/l is largest in size at cos θ = (c₀ + √(c₀² + 3))/3
_C = "(cos(theta0) + sqrt(cos(theta0)^2 + 3))/3"
_RISE = f"sqrt(2*g*l*(1 - ({_C})^2)*({_C} - cos(theta0)))"


@pytest.mark.parametrize("answer, expected", [
    # θ̇ ≤ 0 on the way down to the pole, and on the far side θ rises again with θ̇ > 0: the largest θ̇ is
    # the speed at the bottom, 2√(g/l) sin(θ₀/2) (it came out 0 when the motion was taken to end at θ = 0)
    ("thetadot_max", "2*sqrt(g/l)*sin(theta0/2)"),
    # ż rises on the far side as it falls on the near one
    ("rise_rate_max", _RISE),
    ("rise_rate_min", f"-{_RISE}"),
])
@pytest.mark.parametrize("theta0", [0.7, 0.2, 1.4])
def test_a_motion_through_the_pole_of_a_polar_angle_goes_on_up_the_other_side(answer, expected, theta0):
    derivation = derive(load_scene(POLE))
    want = parse_expression(expected, derivation.scene.namespace).expr
    got = derivation.answers[answer]
    numbers = {"g": 9.81, "l": 0.9, "theta0": theta0}
    values = {s: numbers[s.name] for s in got.free_symbols | want.free_symbols}
    assert float(got.xreplace(values)) == pytest.approx(float(want.xreplace(values)), rel=1e-10)


_SADDLE = '''
id = "particle_on_saddle"
title = "Particle on the surface z = (x^2 - y^2)/(2a), launched along x"
statement = "Smooth surface, gravity along -z."
[parameters]
m = { dimension = "mass", domain = "positive", value = 0.3 }
g = { dimension = "acceleration", domain = "positive", value = 9.81 }
a = { dimension = "length", domain = "positive", value = 0.8 }
v0 = { dimension = "velocity", domain = "positive", value = 1.0 }
[coordinates]
x = { dimension = "length" }
y = { dimension = "length" }
z = { dimension = "length" }
[energy]
kinetic = "m/2*(xdot^2 + ydot^2 + zdot^2)"
potential = "m*g*z"
[[constraints]]
name = "surface"
f = "z - (x^2 - y^2)/(2*a)"
[initial]
x = 0
xdot = "v0"
y = 0
ydot = 0
[[answers]]
name = "max_x"
kind = "maximum"
expr = "x"
in_terms_of = ["g", "a", "v0"]
dimension = "length"
'''


@pytest.mark.parametrize("surface", ["z - (x^2 - y^2)/(2*a)", "z - (x^2 + y^2)/(2*a)"])
def test_a_coordinate_left_at_rest_is_out_of_the_energy_before_it_is_solved(surface):
    """Launched along x from the saddle point (or the bottom of a paraboloid), y stays 0 (ÿ ∝ y) and
    x turns back where g x²/a = v₀²: x_max = v₀√(a/g) = 0.28557 (a numerical integration of x, y
    gives 0.2855686). ż² has a cross term x y ẋ ẏ, so energy was not a ẋ² + c until y = ẏ = 0 was put
    in it, and the extreme was refused: 'the motion runs away'."""
    scene = parse_scene(_SADDLE.replace('f = "z - (x^2 - y^2)/(2*a)"', f'f = "{surface}"'), "saddle.toml")
    value = derive(scene).answers["max_x"]
    assert sympy.simplify(value - parse_expression("v0*sqrt(a/g)", scene.namespace).expr) == 0


def test_a_coordinate_that_moves_with_the_one_of_the_extreme_is_named_not_said_to_run_away():
    """Launched off the axis (y₀ = 0.1), y moves too and energy couples ẋ with ẏ: refused, saying so,
    with a SceneError (the private class it was raised as is no part of the message)."""
    scene = parse_scene(_SADDLE.replace("y = 0\n", "y = 0.1\n"), "saddle.toml")
    with pytest.raises(SceneError) as refused:
        derive(scene)
    assert type(refused.value) is SceneError
    assert "couples xdot with ydot" in str(refused.value) and "runs away" not in str(refused.value)


ROD_BOB = '''
id = "rod_bob_drawn"
title = "Bob on a light rod launched from the bottom, the launch speed drawn per student"
[parameters]
m = { dimension = "mass", domain = "positive", value = 1.0 }
g = { dimension = "acceleration", domain = "positive", value = 9.81 }
l = { dimension = "length", domain = "positive", value = 1.0 }
v0 = { dimension = "velocity", domain = "positive", DRAW }
[coordinates]
r = { dimension = "length", domain = "positive" }
phi = { dimension = "angle" }
[energy]
kinetic = "m/2*(rdot^2 + r^2*phidot^2)"
potential = "-m*g*r*cos(phi)"
[[constraints]]
name = "rod"
f = "r - l"
[initial]
phi = 0
phidot = "v0/l"
[[answers]]
name = "least_tension"
kind = "minimum"
expr = "-lambda_rod"
dimension = "force"
'''


def derived(text: str, expected: dict[str, str]) -> None:
    """Derive the scene ``text`` and assert each named answer equals its closed form by hand."""
    derivation = derive(parse_scene(text, "scene.toml"))
    for name, form in expected.items():
        want = parse_expression(form, derivation.scene.namespace).expr
        assert sympy.simplify(derivation.answers[name] - want) == 0, name


@pytest.mark.parametrize("draw, expected", [
    # v0² < 4 g l (v0 < 6.26 here) on every draw: the bob swings back, T = m(g cos φ + v²/l) is least
    # where it turns, v = 0 at cos φ = 1 − v0²/(2 g l)
    ("random = { min = 3.0, max = 6.0, step = 0.5 }", "m*(g - v0^2/(2*l))"),
    # v0² > 4 g l on every draw: it goes over the top, where T = m(v0²/l − 5 g) is least
    ("random = { min = 7.0, max = 9.0, step = 0.5 }", "m*(v0^2/l - 5*g)"),
    ("choices = [7, 8, 10]", "m*(v0^2/l - 5*g)"),
])
def test_an_extreme_drawn_per_student_is_the_closed_form_of_every_draw(draw, expected):
    derived(ROD_BOB.replace("DRAW", draw), {"least_tension": expected})


@pytest.mark.parametrize("draw, named", [
    # some students' bobs go over the top, others swing back: no one closed form is the reference
    ("random = { min = 3.0, max = 9.0, step = 0.5 }", "v0 = 9|v0 = 3"),
    ("choices = [4, 8]", "v0 = 8|v0 = 4"),
])
def test_an_extreme_whose_closed_form_changes_within_the_draws_is_refused_naming_a_draw(draw, named):
    with pytest.raises(SceneError, match=rf"where the minimum lies depends on the parameter values.*({named})"
                                         r".*random ranges"):
        derive(parse_scene(ROD_BOB.replace("DRAW", draw), "rod_bob_drawn.toml"))


@pytest.mark.parametrize("domain, expected", [
    ('domain = [3, 6]', "m*(g - v0^2/(2*l))"),
    ('domain = [7, 9]', "m*(v0^2/l - 5*g)"),
])
def test_an_extreme_in_a_parameter_without_a_number_holds_across_its_declared_interval(domain, expected):
    derived(ROD_BOB.replace('domain = "positive", DRAW', domain), {"least_tension": expected})


@pytest.mark.parametrize("domain", ['domain = "positive"', 'domain = [3, 9]'])
def test_an_extreme_in_a_parameter_without_a_number_whose_closed_form_changes_is_refused(domain):
    # No number for v0: nothing says whether the bob goes over the top; a generic v0 (about 1 m/s)
    # chose the swing back, silently
    with pytest.raises(SceneError, match=r"where the minimum lies depends on the parameter values.*v0 = .*give them "
                                         r"values"):
        derive(parse_scene(ROD_BOB.replace('domain = "positive", DRAW', domain), "rod_bob.toml"))


HANGING_SPRING = '''
id = "hanging_spring"
title = "Block released from rest on a hanging spring, unstretched"
[parameters]
m = { dimension = "mass", domain = "positive", value = 10.0 }
g = { dimension = "acceleration", domain = "positive", value = 9.81 }
k = { dimension = "stiffness", domain = "positive", value = STIFFNESS }
[coordinates]
x = { dimension = "length" }
[energy]
kinetic = "m/2*xdot^2"
potential = "k/2*x^2 - m*g*x"
[initial]
x = 0
xdot = 0
[[answers]]
name = "lowest"
kind = "maximum"
expr = "x"
dimension = "length"
'''


@pytest.mark.parametrize("stiffness", ["1000.0", "10.0", "1.0", "0.01"])
def test_an_extreme_of_a_length_is_found_whatever_the_length_of_the_swing(stiffness):
    # x swings over [0, 2 m g/k]: 0.2 m, 19.6 m, 196 m, 19.6 km; a swing longer than 2π in its unit was
    # taken for an angle going round ('the motion goes round and round in x')
    derived(HANGING_SPRING.replace("STIFFNESS", stiffness), {"lowest": "2*m*g/k"})


@pytest.mark.parametrize("stiffness", ["1e7", "1e12"])
def test_a_motion_far_shorter_than_a_metre_is_followed_to_where_it_turns(stiffness):
    # m g/k = 9.81 µm and 98 pm: the scan stepped a four-thousandth of a metre and took the first step,
    # past the whole swing, for the motion turning back where it started
    text = HANGING_SPRING.replace("STIFFNESS", stiffness).replace(
        "[[answers]]", '[[answers]]\nname = "rest"\nexpr = "x"\nwhere = "xddot = 0"\n\n[[answers]]', 1)
    derived(text, {"rest": "m*g/k", "lowest": "2*m*g/k"})


@pytest.mark.parametrize("start", [("theta = 0\n", "theta = 0.3\n"), ("thetadot = 0\n", "thetadot = 1.5\n")])
def test_other_coordinates_moving_is_the_reason_before_any_solve_runs(monkeypatch, start):
    # An elastic pendulum released tilted: θ moves as well as r. That was found only after solving for
    # r's stationary points, so a solve that ran out of its budget (a loaded machine) gave its own
    # reason instead, and the same scene was refused differently from one run to the next.
    from grader.mechanics import extremes
    from tests.mechanics.test_red_team_scenes_8 import HANGING

    def out_of_budget(expr, x, source, key):
        raise SceneError(source, key, f"solving the condition for {x} ran out of its budget")

    monkeypatch.setattr(extremes, "solve_for", out_of_budget)
    with pytest.raises(SceneError) as refused:
        derive(parse_scene(HANGING.read_text().replace(*start), "tilted.toml"))
    assert "theta moves as well as r" in str(refused.value)
    assert "ran out of" not in str(refused.value)


def test_an_extreme_whose_stationary_points_cannot_be_solved_names_them_not_a_condition(monkeypatch):
    """The largest ẋ of a bead on an ellipse: solving d(ẋ)/dx = 0 runs out of its budget. The refusal
    names the derivative and suggests a value at a state; 'write the condition in a simpler form'
    (solve_for's advice for a where the instructor wrote) would point at nothing the file has."""
    from grader.mechanics import extremes

    def out_of_budget(condition, x, source, key):
        raise SceneError(source, key, f"solving the condition for {x} ran out of its 3 s budget; "
                                      "write the condition in a simpler form")

    monkeypatch.setattr(extremes, "solve_for", out_of_budget)
    x, a = sympy.symbols("x a", positive=True)
    with pytest.raises(SceneError) as refused:
        extremes._stationary_points(sympy.sqrt(a ** 2 - x ** 2) * x, x, "ellipse.toml", "answers (largest_xdot)")
    assert "d/dx of x*sqrt(a**2 - x**2) is zero" in refused.value.problem
    assert "ran out of its 3 s budget" in refused.value.problem
    assert "in_terms_of with x" in refused.value.problem
    assert "simpler form" not in refused.value.problem
