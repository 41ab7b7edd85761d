"""Scene files are untrusted input: bad ones get an error naming the file, the key and the problem,
and nothing in them is ever executed."""

from __future__ import annotations

from pathlib import Path

import pytest

from grader.mechanics.lagrange import derive
from grader.mechanics.scene import SceneError, load_scene, parse_scene

ROOT = Path(__file__).resolve().parents[2]

SPHERE = (Path(__file__).resolve().parents[2] / "problems" / "sphere.toml").read_text()


def broken(old: str, new: str) -> str:
    assert old in SPHERE, old
    return SPHERE.replace(old, new, 1)


@pytest.mark.parametrize(
    "text, key, problem",
    [
        (broken('kinetic = "m/2*(rdot^2 + r^2*thetadot^2)"', 'kinetic = "m/2*(rdot^2 + r^2*tehtadot^2)"'),
         "energy.kinetic", "did you mean 'thetadot'"),
        (broken('kinetic = "m/2*(rdot^2 + r^2*thetadot^2)"', 'kinetic = "m/2*(rdot^2 + r^2*thetadot^2"'),
         "energy.kinetic", "never closed"),
        (broken('kinetic = "m/2*(rdot^2 + r^2*thetadot^2)"', 'kinetic = "m/2*(rdot^2 + r^2*thetadot)"'),
         "energy.kinetic", "dimensionally inconsistent"),
        (broken('potential = "m*g*r*cos(theta)"', 'potential = "m*g*cos(theta)"'),
         "energy.potential", "not an energy"),
        (broken('f = "r - R"', 'f = "r - theta"'), "constraints[0] (surface).f", "dimensionally inconsistent"),
        (broken('f = "r - R"', 'f = "rdot - 1"'), "constraints[0] (surface).f", "holonomic"),
        (broken('kind = "unilateral"', 'kind = "sometimes"'), "constraints[0] (surface).kind", "bilateral"),
        (broken('dimension = "length", domain = "positive" }\ntheta',
                'dimension = "lenght", domain = "positive" }\ntheta'), "coordinates.r.dimension", "unknown dimension"),
        (broken('in_terms_of = ["m", "g", "theta"]', 'in_terms_of = ["m", "g", "phi"]'),
         "answers[0] (normal_force).in_terms_of", "unknown"),
        (broken('name = "separation_height"', 'name = "normal_force"'), "answers[2] (normal_force).name", "already"),
        (broken('kinetic = "m/2*(rdot^2 + r^2*thetadot^2)"', 'kinetic = "__import__(\'os\').system(\'true\')"'),
         "energy.kinetic", ""),
        (broken('kinetic = "m/2*(rdot^2 + r^2*thetadot^2)"', 'kinetic = "m.__class__"'), "energy.kinetic", ""),
        (broken('id = "sphere"', 'id = "Sphere Problem!"'), "id", "lowercase"),
        (broken('[initial]\ntheta = 0', '[initial]\ntheta = "thetadot"'), "initial.theta", "parameters"),
        (SPHERE + "\n[energy]\n", "", "not valid TOML"),
    ],
    ids=["unknown-name", "syntax", "kinetic-not-energy", "potential-not-energy", "constraint-dimensions",
         "nonholonomic", "constraint-kind", "unknown-dimension", "in-terms-of-unknown", "duplicate-answer",
         "import-attempt", "attribute-access", "bad-id", "initial-uses-state", "toml-syntax"],
)
def test_bad_scene_file_is_rejected_with_file_key_and_problem(text, key, problem):
    with pytest.raises(SceneError) as caught:
        parse_scene(text, source="upload.toml")
    message = str(caught.value)
    assert message.startswith("upload.toml: ")
    assert caught.value.key == key
    assert problem in message


@pytest.mark.parametrize(
    "text, key, problem",
    [
        # A second, equivalent constraint: the Jacobian of the constraints loses rank.
        (broken('[initial]', '[[constraints]]\nname = "again"\nf = "2*r - 2*R"\n\n[initial]'),
         "constraints", "redundant"),
        # A coordinate with no kinetic energy that no constraint ties to the others: the
        # augmented system [M Jᵀ; J 0] is singular, and the message names the coordinate.
        (broken('kinetic = "m/2*(rdot^2 + r^2*thetadot^2)"', 'kinetic = "m/2*rdot^2"'),
         "energy.kinetic", "the coordinate theta has no kinetic energy of its own"),
        # N(theta) needs g: without it in in_terms_of the engine cannot reach the answer.
        (broken('in_terms_of = ["m", "g", "theta"]', 'in_terms_of = ["m", "theta"]'),
         "answers (normal_force)", "still depends on g"),
        # The normal force is never 10 m g, anywhere (cos θ = 4 has no real root).
        (broken('where = "normal_force = 0"', 'where = "normal_force = 10*m*g"'),
         "answers (separation_cos).where", "no real root for theta anywhere"),
        # Energy conservation needs the initial angular velocity.
        (broken('[initial]\ntheta = 0\nthetadot = 0', '[initial]\ntheta = 0'),
         "answers (normal_force)", "[initial]"),
    ],
    ids=["redundant-constraints", "singular-mass-matrix", "in-terms-of-unreachable", "where-unreachable",
         "initial-missing"],
)
def test_scene_the_engine_cannot_solve_gets_a_clear_error(text, key, problem):
    with pytest.raises(SceneError) as caught:
        derive(parse_scene(text, source="upload.toml"))
    assert caught.value.key == key
    assert problem in str(caught.value)


def test_a_root_the_motion_never_reaches_is_refused_saying_where_it_turns_back():
    """Released from rest at θ = 0.6, the pendulum turns back at θ = -0.6 before θ = -1."""
    text = (ROOT / "problems" / "pendulum.toml").read_text()
    for old, new in [('where = "theta = 0"', 'where = "theta = -1"'), ('theta = "theta0"', "theta = 0.6"),
                     ('in_terms_of = ["m", "g", "theta0"]', 'in_terms_of = ["m", "g"]')]:
        assert old in text
        text = text.replace(old, new)
    with pytest.raises(SceneError, match=r"turns back at theta = -0\.6, then turns back at theta = 0\.6 before it reaches") as caught:
        derive(parse_scene(text, source="p.toml"))
    assert caught.value.key == "answers (tension_lowest).where"


def test_missing_file_is_a_scene_error(tmp_path):
    with pytest.raises(SceneError, match="cannot read"):
        load_scene(tmp_path / "nope.toml")


def test_oversized_file_is_refused_before_parsing(tmp_path):
    path = tmp_path / "big.toml"
    path.write_text('id = "big"\n' + "# padding\n" * 40_000)
    with pytest.raises(SceneError, match="larger than"):
        load_scene(path)


@pytest.mark.parametrize("path", sorted((Path(__file__).resolve().parents[2] / "problems").glob("*.toml")),
                         ids=lambda p: p.stem)
def test_every_problem_file_loads(path):
    scene = load_scene(path)
    assert scene.id == path.stem
    assert scene.answers, "a problem without answers grades nothing"


# -- a parametrization may keep scene coordinates as they are --------------------------------------
SLIDING = (ROOT / "tests" / "mechanics" / "scenes" / "pendulum_sliding_support.toml").read_text()


def sliding(old: str, new: str) -> str:
    assert old in SLIDING, old
    return SLIDING.replace(old, new, 1)


def test_a_parametrization_variable_named_like_a_coordinate_keeps_that_coordinate():
    # The cart's X stays as it is next to the pendulum's angle: the same symbols, mapped to itself.
    scene = parse_scene(SLIDING, source="sliding.toml")
    kept = scene.parametrization.variables["X"]
    assert kept is scene.coordinates["X"]
    assert scene.parametrization.mapping[kept.symbol] == kept.symbol
    # Leaving X out of the map means the same.
    assert parse_scene(sliding('X = "X"\nx = ', 'x = '), source="sliding.toml").parametrization.mapping[
        kept.symbol] == kept.symbol


@pytest.mark.parametrize(
    "old, new, key, problem",
    [
        ('X = "X"\nx = ', 'X = "X + l"\nx = ', "parametrization.map.X", "maps to itself"),
        ('X = { dimension = "length" }\ntheta', 'X = { dimension = "angle" }\ntheta',
         "parametrization.variables.X.dimension", "the scene coordinate X it keeps is"),
        ('X = { dimension = "length" }\ntheta', 'X = { dimension = "length", domain = "positive" }\ntheta',
         "parametrization.variables.X.domain", "declare the domain once"),
    ],
    ids=["kept-but-mapped-elsewhere", "kept-with-another-dimension", "kept-with-another-domain"],
)
def test_a_kept_coordinate_must_be_that_coordinate(old, new, key, problem):
    with pytest.raises(SceneError) as caught:
        parse_scene(sliding(old, new), source="sliding.toml")
    assert caught.value.key == key
    assert problem in str(caught.value)


def with_parameter(line: str) -> str:
    """The sphere with one more parameter line after R."""
    anchor = 'R = { dimension = "length", domain = "positive", value = 0.8 }\n'
    assert anchor in SPHERE
    return SPHERE.replace(anchor, anchor + line + "\n", 1)


@pytest.mark.parametrize("line, problem", [
    ('d = { dimension = "length", domain = "positive", value = 0.1, below = "L" }', "must name another parameter"),
    ('d = { dimension = "length", domain = "positive", value = 0.1, below = "d" }', "must name another parameter"),
    ('d = { dimension = "length", domain = "positive", value = 0.1, below = "m" }', "one dimension"),
    ('d = { dimension = "length", domain = "positive", value = 0.9, below = "R" }', "is not below R"),
    ('d = { dimension = "length", domain = "positive", random = { min = 0.9, max = 1.2, step = 0.1 }, below = "R" }',
     "no values"),
])
def test_a_parameter_below_another_must_name_one_of_its_dimension_with_numbers_in_order(line, problem):
    with pytest.raises(SceneError) as caught:
        parse_scene(with_parameter(line), source="upload.toml")
    assert caught.value.key == "parameters.d.below" and problem in str(caught.value)


def test_a_parameter_below_another_is_kept_on_the_scene_and_in_the_references():
    from grader.mechanics.references import parameter_specs

    scene = parse_scene(with_parameter('d = { dimension = "length", domain = "positive", value = 0.1, below = "R" }'),
                        source="upload.toml")
    assert scene.parameters["d"].below == "R"
    assert parameter_specs(scene)["d"]["below"] == "R"
