"""The scene file's structure (grader/mechanics/scene_schema.py): every key that exists is known, a
misspelt one is refused with a did-you-mean instead of being silently ignored."""

from __future__ import annotations

from pathlib import Path

import pytest
from jsonschema import Draft202012Validator

from grader.mechanics.scene import SceneError, load_scene, parse_scene
from grader.mechanics.scene_schema import SCENE_SCHEMA, structure_problems

ROOT = Path(__file__).resolve().parents[2]
SCENE_FILES = (sorted(ROOT.glob("problems/*.toml")) + sorted((ROOT / "tests/mechanics/scenes").glob("*.toml"))
               + sorted((ROOT / "tests/mechanics/scenes/not_simulated").glob("*.toml")))
SPHERE = (ROOT / "problems" / "sphere.toml").read_text()
PENDULUM = (ROOT / "problems" / "pendulum.toml").read_text()


def edited(text: str, old: str, new: str) -> str:
    assert old in text, old
    return text.replace(old, new, 1)


def test_the_schema_is_a_valid_draft_2020_12_schema():
    Draft202012Validator.check_schema(SCENE_SCHEMA)


@pytest.mark.parametrize("path", SCENE_FILES, ids=lambda p: p.stem)
def test_every_scene_file_validates(path):
    import tomllib

    assert structure_problems(tomllib.loads(path.read_text())) == []
    assert load_scene(path).id == path.stem


# One misspelt key at every level of a scene file; the message names the table and the key meant.
@pytest.mark.parametrize("text, key, typo, meant", [
    (edited(SPHERE, 'title =', 'titel ='), "", "titel", "title"),
    (edited(SPHERE, 'm = { dimension = "mass", domain', 'm = { dimension = "mass", domian'),
     "parameters.m", "domian", "domain"),
    (edited(SPHERE, 'r = { dimension = "length"', 'r = { dimesion = "length"'), "coordinates.r", "dimesion", "dimension"),
    (edited(SPHERE, 'kinetic =', 'kinteic ='), "energy", "kinteic", "kinetic"),
    (edited(SPHERE, 'kind = "unilateral"', 'knid = "unilateral"'), "constraints[0] (surface)", "knid", "kind"),
    (edited(SPHERE, 'in_terms_of = ["m", "g", "theta"]', 'in_term_of = ["m", "g", "theta"]'),
     "answers[0] (normal_force)", "in_term_of", "in_terms_of"),
    (edited(SPHERE, 'message = "That is', 'mesage = "That is'), "answers[0] (normal_force).feedback[0]",
     "mesage", "message"),
    (edited(PENDULUM, '[parametrization.map]', '[parametrization.mpa]'), "parametrization", "mpa", "map"),
    (edited(PENDULUM, 'theta = { dimension = "angle"', 'theta = { dimensoin = "angle"'),
     "parametrization.variables.theta", "dimensoin", "dimension"),
], ids=["top", "parameter", "coordinate", "energy", "constraint", "answer", "feedback", "parametrization",
        "parametrization-variable"])
def test_a_misspelt_key_is_refused_with_a_did_you_mean(text, key, typo, meant):
    with pytest.raises(SceneError) as caught:
        parse_scene(text, source="upload.toml")
    assert caught.value.key == key
    assert f"unknown key '{typo}'; did you mean '{meant}'?" in str(caught.value)
    assert str(caught.value).startswith("upload.toml: ")


def test_an_unknown_key_with_no_close_match_lists_the_known_keys():
    with pytest.raises(SceneError) as caught:
        parse_scene(edited(SPHERE, 'kinetic =', 'zzz = "1"\nkinetic ='), source="upload.toml")
    assert caught.value.problem == "unknown key 'zzz' (known keys: kinetic, potential)"


@pytest.mark.parametrize("text, key, problem", [
    (edited(SPHERE, 'title = "Body sliding off a smooth sphere"', f'title = "{"x" * 201}"'),
     "title", "is 201 characters long; the limit is 200"),  # problem_versions.title is String(200)
    (edited(SPHERE, 'name = "normal_force"', f'name = "{"n" * 65}"'),
     "answers[0].name", "is 65 characters long; the limit is 64"),  # submissions.answer_name is String(64)
    (edited(SPHERE, 'expr = "lambda_surface"', 'expr = ["lambda_surface"]'),
     "answers[0] (normal_force).expr", "must be a string"),
    (edited(SPHERE, 'potential = "m*g*r*cos(theta)"', f'potential = "{"m*" * 2500}g"'),
     "energy.potential", "is 5001 characters long; the limit is 4000"),
    (edited(SPHERE, 'domain = "positive", value = 0.2', 'domain = "positive", value = "0.2"'),
     "parameters.m.value", "must be a number"),
    (edited(SPHERE, 'domain = [-3.1416, 3.1416]', 'domain = [-3.1416]'),
     "coordinates.theta.domain", 'must be a domain: "positive", "nonnegative", "real" or [lo, hi]'),
    (edited(SPHERE, 'kind = "unilateral"', 'kind = "sometimes"'),
     "constraints[0] (surface).kind", 'must be one of "bilateral", "unilateral", "rolling"'),
    (edited(edited(SPHERE, '[[constraints]]', '[[constraint]]'), 'id = "sphere"', 'id = "sphere"\nconstraints = 3'),
     "constraints", "must be a list"),
    (edited(SPHERE, 'expr = "lambda_surface"', 'prompt2 = "x"'), "answers[0] (normal_force)",
     "unknown key 'prompt2'; did you mean 'prompt'?"),  # reported before the missing expr: it comes first
    (edited(SPHERE, 'id = "sphere"', ''), "id", "missing (required)"),
], ids=["title-length", "answer-name-length", "expr-type", "expression-length", "value-type", "domain-shape",
        "enum", "list-type", "file-order", "required"])
def test_structure_errors_name_the_key_and_the_rule(text, key, problem):
    with pytest.raises(SceneError) as caught:
        parse_scene(text, source="upload.toml")
    assert (caught.value.key, caught.value.problem) == (key, problem)


@pytest.mark.parametrize("keys", [
    'kind = "unilateral"\nrestitution = 0.5',
    'kind = "bilateral"\nmu_s = 0.4\nmu_k = "mu"',
], ids=["restitution", "friction"])
def test_effect_keys_read_by_simulation_are_part_of_the_structure(keys):
    import tomllib

    data = tomllib.loads(edited(SPHERE, 'kind = "unilateral"', keys))
    assert structure_problems(data) == []


def test_the_misspelt_key_that_used_to_change_the_answer_is_refused():
    # `in_term_of` was ignored: the engine then chose the default variables and derived another answer.
    text = edited(SPHERE, 'in_terms_of = ["m", "g", "theta"]', 'in_term_of = ["m", "g", "theta"]')
    with pytest.raises(SceneError, match="did you mean 'in_terms_of'"):
        parse_scene(text, source="sphere.toml")


@pytest.mark.parametrize("schema_path, column", [
    (("properties", "title"), "problem_versions.title"),
    (("properties", "id"), "problems.slug"),
    (("properties", "answers", "items", "properties", "name"), "submissions.answer_name"),
])
def test_scene_lengths_fit_the_database_columns_they_are_stored_in(schema_path, column):
    from grader.store.models import Base

    schema = SCENE_SCHEMA
    for key in schema_path:
        schema = schema[key]
    table, name = column.split(".")
    assert schema["maxLength"] <= Base.metadata.tables[table].c[name].type.length


@pytest.mark.parametrize("text", [
    'id = "x"\na = ' + "[" * 5000 + "]" * 5000,
    'id = "x"\na = ' + "{b=" * 2000 + "1" + "}" * 2000,
    'id = "x"\na = ' + "[" * 400 + "]" * 400,  # within tomllib's reach, deep for the schema
], ids=["arrays", "inline-tables", "moderately-deep"])
def test_a_deeply_nested_file_is_a_scene_error(text):
    with pytest.raises(SceneError, match="upload.toml: "):
        parse_scene(text, source="upload.toml")
