"""The motion in time (grader.mechanics.motion): which motions have q(t) in closed form, the time a
condition holds from the energy quadrature, and what is said for the others.

Each accepted closed form is compared with the one derived by hand (at 30 digits, at two parameter
points) and with a numerical integration of the scene by :mod:`grader.simulate`, which never sees
the engine's equations (it differentiates the scene's T, V and f numerically).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import sympy

from grader.expressions import parse_expression
from grader.mechanics import motion
from grader.mechanics.lagrange import derive
from grader.mechanics.scene import SceneError, parse_scene

ROOT = Path(__file__).resolve().parents[2]
SCENES = Path(__file__).resolve().parent / "scenes"


def scene_text(name: str, *replacements: tuple[str, str]) -> str:
    path = ROOT / name if name.endswith(".toml") else SCENES / f"{name}.toml"
    text = path.read_text(encoding="utf-8")
    for old, new in replacements:
        assert old in text, old
        text = text.replace(old, new)
    return text


def refusal(text: str) -> SceneError:
    with pytest.raises(SceneError) as caught:
        derive(parse_scene(text, "scene.toml"))
    return caught.value


def at(expr: sympy.Expr, point: dict) -> complex:
    return complex(sympy.N(expr.xreplace({s: sympy.Float(point[s.name], 30) for s in expr.free_symbols}), 30))


POINTS = [  # two generic points (the scenes' own values are checked by the simulation below)
    {"m": 0.7, "M": 1.9, "g": 9.81, "L": 1.7, "x0": 0.3, "k": 13.0, "A": 0.2, "Omega": 2.2, "a": 0.3,
     "omega": 2.3, "r0": 0.4, "omega0": 1.3, "G": 1.1, "R": 0.25, "alpha": 0.4, "h": 1.1, "t": 0.7},
    {"m": 1.3, "M": 0.6, "g": 3.0, "L": 0.9, "x0": 0.1, "k": 2.0, "A": 0.05, "Omega": 0.5, "a": 0.1,
     "omega": 0.8, "r0": 1.5, "omega0": 3.1, "G": 0.4, "R": 1.2, "alpha": 1.1, "h": 0.6, "t": 1.3},
]

CASES = [
    # 1. Linear equations. A rope hanging x over a table edge: ẍ = g x/L, from rest at x₀.
    ("chain_off_table", "hanging_length_in_time", "x0*cosh(sqrt(g/L)*t)"),
    ("chain_off_table", "time_to_leave", "sqrt(L/g)*acosh(L/x0)"),
    ("chain_off_table", "speed_when_leaving", "sqrt(g/L)*sqrt(L^2 - x0^2)"),
    # A spring on a support driven as A cos Ωt: ẍ = −ω²(x − A cos Ωt), ω² = k/m, from rest at 0.
    ("spring_driven_support", "displacement_in_time", "A*k/(k - m*Omega^2)*(cos(Omega*t) - cos(sqrt(k/m)*t))"),
    ("spring_driven_support", "drive_force_in_time",
     "-M*A*Omega^2*cos(Omega*t) + k*(A*cos(Omega*t) - A*k/(k - m*Omega^2)*(cos(Omega*t) - cos(sqrt(k/m)*t)))"),
    # Two coupled oscillators: normal modes ω₁ = √(k/m), ω₂ = √(3k/m), beats between them.
    ("coupled_oscillators", "first_in_time", "a/2*(cos(sqrt(k/m)*t) + cos(sqrt(3*k/m)*t))"),
    ("coupled_oscillators", "second_in_time", "a/2*(cos(sqrt(k/m)*t) - cos(sqrt(3*k/m)*t))"),
    # A rod turned at ω in a vertical plane: r̈ = ω² r − g sin ωt (Taylor, Classical Mechanics 7.21).
    ("bead_vertical_rotating_rod", "position_in_time", "r0*cosh(omega*t) + g/(2*omega^2)*(sin(omega*t) - sinh(omega*t))"),
    ("bead_vertical_rotating_rod", "velocity_in_time", "r0*omega*sinh(omega*t) + g/(2*omega)*(cos(omega*t) - cosh(omega*t))"),
    # 2 and 3. A free particle in polar coordinates: φ cyclic, r̈ = r₀⁴ω₀²/r³ once the momentum is
    # used; the energy quadrature t = √(r² − r₀²)/(r₀ω₀) inverts to the straight line.
    ("free_particle_polar", "distance_in_time", "r0*sqrt(1 + omega0^2*t^2)"),
    ("free_particle_polar", "angle_in_time", "atan(omega0*t)"),
    ("free_particle_polar", "time_to_double", "sqrt(3)/omega0"),
    # 3, uniform acceleration seen through a nonlinear change of variables: s = h tan θ.
    ("incline_seen_by_angle", "angle_in_time", "atan(g*sin(alpha)*t^2/(2*h))"),
    ("incline_seen_by_angle", "time_to_half_right_angle", "sqrt(2*h/(g*sin(alpha)))"),
    # 3, time only: radial fall from rest at r₀; t(R) is elementary, r(t) is not.
    ("radial_fall", "time_to_reach", "sqrt(r0^3/(2*G*M))*(sqrt(R/r0*(1 - R/r0)) + acos(sqrt(R/r0)))"),
    ("radial_fall", "speed_at", "sqrt(2*G*M*(1/R - 1/r0))"),
]


@pytest.mark.parametrize("scene, answer, expected", CASES)
def test_closed_forms_equal_the_ones_derived_by_hand(derived, scene, answer, expected):
    d = derived(scene)
    value = d.answers[answer]
    want = parse_expression(expected, d.scene.namespace).expr
    for point in POINTS:
        if scene == "radial_fall" and point["R"] >= point["r0"]:
            continue
        exact = at(want, point)
        assert abs(at(value, point) - exact) < 1e-25 * max(1.0, abs(exact)), (value, want)


@pytest.mark.parametrize("scene, answer, expected", [c for c in CASES if "_in_time" in c[1]])
def test_values_in_time_agree_with_a_numerical_integration(derived, scene, answer, expected):
    from grader.simulate.constrained import simulate
    from grader.simulate.scene_numeric import SceneModel

    d = derived(scene)
    model = SceneModel(d.scene)
    start = model.initial_state()
    run = simulate(model.numeric, start.q, start.qdot, 1.5, sample_times=np.linspace(0.0, 1.5, 7))
    spec = d.scene.answer(answer)
    values = [model.quantities(s) for s in run.samples]
    numeric = [model.evaluate(spec.expr, v) for v in values]
    scale = max(abs(n) for n in numeric)
    for v, n in zip(values, numeric):
        assert abs(model.evaluate(d.answers[answer], v) - n) <= 1e-7 * scale, v["t"]


@pytest.mark.parametrize(
    "scene, answer, condition",
    [("chain_off_table", "time_to_leave", "x = L"), ("free_particle_polar", "time_to_double", "r = 2*r0"),
     ("radial_fall", "time_to_reach", "r = R"), ("incline_seen_by_angle", "time_to_half_right_angle", "theta = pi/4")],
)
def test_times_agree_with_a_numerical_integration(derived, scene, answer, condition):
    """At the engine's t* the simulated motion meets the condition, and not before."""
    from grader.simulate.constrained import simulate
    from grader.simulate.scene_numeric import SceneModel

    d = derived(scene)
    model = SceneModel(d.scene)
    spec = d.scene.answer(answer)
    lhs, rhs = spec.where
    assert f"{lhs} = {rhs}".replace(" ", "") == condition.replace(" ", "")
    moment = model.evaluate(d.answers[answer], {})
    start = model.initial_state()
    times = [0.0, 0.25 * moment, 0.5 * moment, 0.9 * moment, 0.99 * moment, moment]
    run = simulate(model.numeric, start.q, start.qdot, moment, sample_times=times)
    residuals = [model.evaluate(lhs - rhs, model.quantities(s)) for s in run.samples]
    assert abs(residuals[-1]) < 1e-8 * abs(residuals[0])
    assert all(r * residuals[0] > 0 for r in residuals[:-1])


def test_the_quadrature_gives_the_time_out_and_back_only_on_the_way_out():
    """Thrown outwards at √(GM/r₀) it turns back at 2r₀: r = 3r₀/2 is reached on the way out (the
    quadrature's time), r = 0.9 r₀ only after the turn (refused, with the turning point)."""
    text = scene_text("radial_fall", ("rdot = 0", 'rdot = "sqrt(G*M/r0)"'), ('prompt = "Speed', 'prompt = "Velocity'),
                      ('expr = "-rdot"', 'expr = "rdot"'))
    # R beyond r0 declared: below r0 the velocity there is reached on the way back, with the other sign
    beyond = text.replace('value = 2.0 }', 'value = 2.0, below = "R" }')
    outward = derive(parse_scene(beyond.replace("value = 1.8", "value = 3.0"), "fall.toml"))
    point = {"G": 1.0, "M": 1.0, "r0": 2.0, "R": 3.0}
    # t = ∫ dr/√(2GM/r − GM/r₀) from r₀ to R, numerically.
    from scipy.integrate import quad

    expected, _ = quad(lambda r: 1 / np.sqrt(2 / r - 1 / 2.0), 2.0, 3.0, epsabs=1e-13, epsrel=1e-13)
    assert abs(at(outward.answers["time_to_reach"], point).real - expected) < 1e-9
    problem = refusal(text.replace("value = 1.8", "value = 1.6")).problem
    assert "turns back at r = 4" in problem and "before it reaches the condition" in problem


def test_the_quadrature_is_integrated_without_meijer_g_first_and_with_it_when_that_fails(monkeypatch):
    """sympy's integral without Meijer G-functions is tried first; an antiderivative from it that the
    numerical motion does not confirm (here: made 0.1 % too steep) sends the quadrature on to the
    full integral, and the time is still right."""
    integrate, calls = sympy.integrate, []

    def spy(*args, **options):
        calls.append(options)
        result = integrate(*args, **options)
        return result * sympy.Rational(1001, 1000) if options.get("meijerg") is False else result

    monkeypatch.setattr(motion.sympy, "integrate", spy)
    d = derive(parse_scene(scene_text("radial_fall"), "fall.toml"))
    assert calls == [{"meijerg": False}, {}]
    want = parse_expression("sqrt(r0^3/(2*G*M))*(sqrt(R/r0*(1 - R/r0)) + acos(sqrt(R/r0)))", d.scene.namespace).expr
    for point in POINTS:
        if point["R"] < point["r0"]:
            assert abs(at(d.answers["time_to_reach"], point) - at(want, point)) < 1e-25 * abs(at(want, point))


def test_an_inverse_function_mixed_with_its_argument_is_not_handed_to_solve(monkeypatch):
    """t = asin(√(r/r₀)) − √r √(r₀ − r) ... has no inverse in elementary functions: the motion in time is
    refused without asking sympy's solve (which would try for a while), and the time still comes
    from the quadrature."""
    solve, asked = sympy.solve, []

    def spy(*args, **options):
        asked.append(args)
        return solve(*args, **options)

    monkeypatch.setattr(motion.sympy, "solve", spy)
    d = derive(parse_scene(scene_text("radial_fall"), "fall.toml"))
    assert not any(isinstance(a[0], sympy.Eq) and "t" in map(str, a[0].free_symbols) for a in asked)
    assert "time_to_reach" in d.answers
    r = sympy.Symbol("r", positive=True)
    assert motion._transcendental_in(sympy.asin(sympy.sqrt(r)) + r, r) == sympy.asin(sympy.sqrt(r))
    for solvable in (sympy.sqrt(r**2 - 1), sympy.asin(r / 2), sympy.log(r) + r, sympy.atan(r) / 3):
        assert motion._transcendental_in(solvable, r) is None


# -- refusals ---------------------------------------------------------------------------------------------
PENDULUM_ANGLE = '\n[[answers]]\nname = "angle"\nexpr = "theta"\nin_terms_of = ["g", "l", "theta0", "t"]\n'
ASK_INSTEAD = "ask instead for a value at a state"


def test_a_pendulum_has_no_angle_in_time_and_says_why():
    error = refusal(scene_text("problems/pendulum.toml") + PENDULUM_ANGLE)
    assert error.key == "answers (angle)"
    for words in ("still depends on theta", "the motion has no closed form in elementary functions",
                  "thetaddot = -g*sin(theta)/l is nonlinear in theta",
                  "the energy quadrature t = ∫ dtheta/√(2*g*(cos(theta) - cos(theta0))/l) is not an elementary "
                  "function (it is an elliptic integral)", ASK_INSTEAD):
        assert words in error.problem


@pytest.mark.parametrize(
    "scene, addition, words",
    [
        # Chaotic: two coordinates, no cyclic one; energy is one integral for two.
        ("double_pendulum", '\n[[answers]]\nname = "angle"\nexpr = "theta1"\nin_terms_of = ["g", "l1", "t"]\n',
         ["is nonlinear in theta1, theta1dot, theta2 and theta2dot",
          "with 2 coordinates (theta1, theta2) and no conserved momentum, energy alone does not reduce it"]),
        # Driven: θ̈ depends on t, so there is no energy integral.
        ("pendulum_driven_support",
         '\n[[answers]]\nname = "angle"\nexpr = "theta"\nin_terms_of = ["g", "l", "A", "Omega", "t"]\n',
         ["is nonlinear in theta", "depends on t (a driven motion), so energy is not conserved"]),
        # An elementary quadrature without an elementary inverse (r inside asin and outside it, as in
        # Kepler's equation): ask for a time instead.
        ("radial_fall", '\n[[answers]]\nname = "distance"\nexpr = "r"\nin_terms_of = ["G", "M", "r0", "t"]\n',
         ["rddot = -G*M/r**2 is nonlinear in r", "cannot be solved for r(t) in elementary functions",
          "r is both inside asin(sqrt(r)/sqrt(r0)) and outside it",
          'ask for the time at which a condition holds (expr = "t", where = "r = ...")']),
    ],
)
def test_motions_without_a_closed_form_in_time_say_why(scene, addition, words):
    error = refusal(scene_text(scene) + addition)
    assert error.key.startswith("answers (")
    assert "the motion has no closed form in elementary functions" in error.problem
    for w in words:
        assert w in error.problem


def test_a_start_at_rest_on_an_unstable_equilibrium_has_no_quadrature():
    """At rest at the top, θ stays (or, pushed, takes unbounded time to leave): t = ∫ dθ/θ̇ diverges."""
    text = scene_text("problems/pendulum.toml", ('theta = "theta0"', 'theta = "pi"'))
    text = text[:text.index("[[answers]]")]  # the shipped answers are about the release from θ₀
    text += '\n[[answers]]\nname = "fall"\nexpr = "t"\nwhere = "theta = 0"\nin_terms_of = ["g", "l"]\n'
    error = refusal(text)
    assert error.key == "answers (fall).where"
    assert "starts at rest at an equilibrium" in error.problem and "diverges" in error.problem


def test_a_closed_form_the_numerical_integration_does_not_confirm_is_refused(monkeypatch):
    """A wrong closed form (here: every one made 0.1 % too large) never reaches an answer."""
    readable = motion._readable
    monkeypatch.setattr(motion, "_readable", lambda expr: readable(expr) * sympy.Rational(1001, 1000))
    error = refusal(scene_text("chain_off_table"))
    assert error.key == "answers (hanging_length_in_time)"
    assert "disagrees with a numerical integration of the equations of motion" in error.problem
    assert "refused rather than risk a wrong closed form" in error.problem


def test_every_symbolic_step_runs_under_a_budget(monkeypatch):
    """An integral that never finishes is cut off by the budget and the motion refused, not hung."""
    import time

    def forever(*args, **kwargs):
        while True:
            pass

    monkeypatch.setattr(motion.sympy, "integrate", forever)
    start = time.process_time()
    error = refusal(scene_text("radial_fall"))
    assert time.process_time() - start < 30
    assert "is not an elementary function" in error.problem


def test_a_start_on_the_bound_of_a_domain_moving_inwards_is_integrated():
    """θ ≥ 0 of a string winding on a post, from θ = 0: the numerical confirmation stopped at t = 0 (the
    bound's event fired on the way in), then compared the closed form past the end of the motion
    (the string wound up, θ̇ → ∞), where it is not real."""
    d = derive(parse_scene(scene_text("puck_winding_on_post"), "puck.toml"))
    expected = parse_expression("(L0 - sqrt(L0^2 - 2*R*v0*t))/R", d.scene.namespace).expr
    assert sympy.simplify(d.answers["angle_in_time"] - expected) == 0


def test_an_undamped_motion_in_time_reads_in_hyperbolic_functions():
    g, w, a, s0, t = sympy.symbols("g omega alpha s0 t", positive=True)
    k, star = w * sympy.sin(a), g * sympy.cos(a) / (w ** 2 * sympy.sin(a) ** 2)
    solved = star + (s0 - star) * (sympy.exp(k * t) + sympy.exp(-k * t)) / 2
    readable = motion._readable(solved)
    assert not readable.has(sympy.exp)
    assert sympy.simplify((readable - solved).rewrite(sympy.exp)) == 0


@pytest.mark.parametrize("scene, answer, expected", [
    # s̈ = g sin α from rest: s = g sin α t²/2
    ("block_incline_time", "distance_in_time", "g*sin(alpha)*t^2/2"),
    # a plank driven as A sin Ωt: ẍ = −A Ω² sin(Ωt)/3 from rest at 0, x = A (sin Ωt − Ωt)/3
    ("cylinder_on_oscillating_plank", "position_in_time", "A*(sin(Omega*t) - Omega*t)/3"),
])
def test_accelerations_of_t_alone_are_integrated_twice_without_dsolve(monkeypatch, scene, answer, expected):
    """u(t) = u₀ + u̇₀ t + ∫∫ ü when ü depends on t and the parameters only (dsolve took 1.4 s on a spool
    rolling down an incline with constant acceleration)."""
    from grader.mechanics.scene import load_scene

    def no_dsolve(*args, **kwargs):
        raise AssertionError("dsolve called for accelerations of t alone")

    monkeypatch.setattr(sympy, "dsolve", no_dsolve)
    scene = load_scene(Path(__file__).resolve().parent / "scenes" / f"{scene}.toml")
    value = derive(scene).answers[answer]
    assert sympy.simplify(value - parse_expression(expected, scene.namespace).expr) == 0


@pytest.mark.parametrize("start, speed, expected", [
    ("0", "0", "g*sin(alpha)*t^2/2"),
    # thrown up the incline from s = d: it turns back at t = v0/(g sin α) and passes d again
    ("d", "-v0", "d - v0*t + g*sin(alpha)*t^2/2"),
    ("-d", "v0", "-d + v0*t + g*sin(alpha)*t^2/2"),
])
def test_a_uniform_acceleration_gives_the_parabola_in_t_without_integrating(monkeypatch, start, speed, expected):
    """u(t) = u₀ + u̇₀ t + ü t²/2 for constant ü, over the readable form of ü, for any start."""
    from grader.mechanics.scene import parse_scene

    text = scene_text("block_incline_time", ("s = 0\nsdot = 0", f"s = \"{start}\"\nsdot = \"{speed}\""),
                      ('d = { dimension = "length", domain = "positive", value = 2.0 }',
                       'd = { dimension = "length", domain = "positive", value = 2.0 }\n'
                       'v0 = { dimension = "velocity", domain = "positive", value = 1.5 }'),
                      ('in_terms_of = ["g", "alpha", "t"]', 'in_terms_of = ["g", "alpha", "t", "d", "v0"]'))
    text = text[:text.index("[[answers]]\nname = \"time_to_slide\"")]

    def no_integral(*args, **kwargs):
        raise AssertionError("a constant acceleration integrated symbolically")

    monkeypatch.setattr(sympy, "integrate", no_integral)
    monkeypatch.setattr(sympy, "dsolve", no_integral)
    scene = parse_scene(text, "scene.toml")
    value = derive(scene).answers["distance_in_time"]
    assert sympy.expand(value - parse_expression(expected, scene.namespace).expr) == 0
