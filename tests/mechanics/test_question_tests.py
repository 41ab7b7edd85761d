"""Question tests, randomised parameters, numeric answers and partial credit in scene files.

A scene's ``[[answers.tests]]`` run when the problem is registered; a failing one stops the
registration with what the grader said. Every scene in problems/ carries tests that pass.
"""

from __future__ import annotations

from functools import cache
from pathlib import Path

import pytest

from grader.answers.question_tests import QuestionTestFailure, require_passing, run_question_tests
from grader.answers.randomised import draw_parameters
from grader.jobs.derivation import derive_request
from grader.mechanics.lagrange import derive
from grader.mechanics.references import parameter_specs
from grader.mechanics.scene import SceneError, load_scene, parse_scene

ROOT = Path(__file__).resolve().parents[2]
PROBLEMS = sorted((ROOT / "problems").glob("*.toml"))
RANDOMISED = ROOT / "tests" / "mechanics" / "randomised" / "yoyo_randomised.toml"
YOYO = RANDOMISED.read_text()


@cache
def references(path: Path) -> list[dict]:
    return derive(load_scene(path)).references()


@pytest.mark.parametrize("path", PROBLEMS, ids=[p.stem for p in PROBLEMS])
def test_every_answer_in_problems_has_an_equivalent_and_a_wrong_example(path):
    for reference in references(path):
        expects = {t["expect"] for t in reference.get("tests", [])}
        assert {"equivalent", "not_equivalent"} <= expects, f"{path.name}: {reference['name']} lacks tests"


@pytest.mark.parametrize("path", PROBLEMS, ids=[p.stem for p in PROBLEMS])
def test_every_question_test_in_problems_passes(path):
    results = run_question_tests(references(path))
    assert results and all(r["passed"] for r in results), [r for r in results if not r["passed"]]


def test_the_randomised_scene_passes_its_tests_including_partial_credit_and_units():
    results = {(r["answer_name"], r["answer"]): r for r in run_question_tests(references(RANDOMISED))}
    assert all(r["passed"] for r in results.values())
    # m g for T = m g/3: the instructor's entry gives a quarter of the points.
    assert results[("tension", "m g")]["score"] == 0.25
    assert results[("tension_value", "2.943 N")]["score"] == 0.5
    assert results[("tension_value", "98.1 cN")]["got"] == "equivalent"
    assert results[("tension_value", "0.981")]["got"] == "invalid"  # no unit


def test_registration_stores_the_results_and_the_parameters_students_draw_from():
    reply = derive_request({"source": YOYO, "filename": "yoyo_randomised.toml"})
    assert reply["outcome"] == "ok", reply
    derivation = reply["problem"]["derivation"]
    assert derivation["random_parameters"] == ["R", "m"]
    assert derivation["parameters"]["g"] == {"dimension": "m*s^-2", "value": 9.81}
    assert all(t["passed"] for t in derivation["question_tests"]) and len(derivation["question_tests"]) == 11
    numeric = {r["name"]: r for r in reply["problem"]["references"]}["tension_value"]
    assert (numeric["kind"], numeric["unit"], numeric["weight"]) == ("numeric", "N", 2.0)
    assert numeric["parameters"] == derivation["parameters"]


def test_a_failing_test_stops_the_registration_with_what_the_grader_said():
    wrong = YOYO.replace('answer = "m g/3"\nexpect = "equivalent"', 'answer = "m g/2"\nexpect = "equivalent"', 1)
    assert wrong != YOYO
    reply = derive_request({"source": wrong, "filename": "yoyo.toml"})
    assert reply["outcome"] == "error"
    assert "1 of 11 question tests failed" in reply["message"]
    assert "answers (tension): test 'm g/2' expects equivalent, the grader said not_equivalent" in reply["message"]


def test_a_failing_numeric_test_shows_the_value_the_grader_expected():
    wrong = YOYO.replace('answer = "0.981 N"', 'answer = "0.9 N"', 1)
    with pytest.raises(QuestionTestFailure, match=r"expected 0\.981 in SI units"):
        require_passing(run_question_tests(derive(parse_scene(wrong, source="y.toml")).references()), "y.toml")


def test_a_wrong_expected_score_fails():
    wrong = YOYO.replace("score = 0.5\nvalues", "score = 1.0\nvalues", 1)
    results = run_question_tests(derive(parse_scene(wrong, source="y.toml")).references())
    failed = [r for r in results if not r["passed"]]
    assert [(r["answer"], r["expected_score"], r["score"]) for r in failed] == [("2.943 N", 1.0, 0.5)]


def test_drawn_values_are_on_the_scenes_grid_and_choices():
    specs = parameter_specs(load_scene(RANDOMISED))
    for seed in range(50):
        values = draw_parameters(specs, seed)
        assert 0.1 <= values["m"] <= 0.5 and values["R"] in (0.02, 0.03, 0.04) and values["g"] == 9.81


def test_a_randomised_parameter_stays_symbolic_in_the_engine():
    scene = load_scene(RANDOMISED)
    assert scene.parameters["m"].value is None and scene.parameters["m"].draw == {
        "random": {"min": 0.1, "max": 0.5, "step": 0.05}}
    assert {r["name"]: r["reference"] for r in references(RANDOMISED)}["tension_value"] == "g*m/3"


def broken(old: str, new: str) -> str:
    assert old in YOYO, old
    return YOYO.replace(old, new, 1)


M_RANDOM = 'm = { dimension = "mass", domain = "positive", random = { min = 0.1, max = 0.5, step = 0.05 } }'


@pytest.mark.parametrize("text, key, problem", [
    (broken(M_RANDOM, M_RANDOM.replace("random", "value = 1, random")), "parameters.m",
     "give one of value, random and choices, not value and random"),
    (broken("step = 0.05", "step = 0"), "parameters.m.random.step", "must be positive"),
    (broken("min = 0.1, max = 0.5", "min = 0.5, max = 0.1"), "parameters.m.random", "max is less than min"),
    (broken("min = 0.1", "min = -0.1"), "parameters.m.random.min", "outside the domain"),
    (broken("step = 0.05", "step = 1e-9"), "parameters.m.random.step", "more than a million"),
    (broken("min = 0.1, max = 0.5, step = 0.05", "min = 0.1, max = 0.5"), "parameters.m.random.step",
     "missing (required)"),
    (broken("choices = [0.02, 0.03, 0.04]", "choices = [0.02, -0.03]"), "parameters.R.choices", "outside the domain"),
    (broken("choices = [0.02, 0.03, 0.04]", "choices = []"), "parameters.R.choices", "non-empty"),
    (broken('unit = "N"\n', ""), "answers[3] (tension_value).unit", "missing"),
    (broken('unit = "N"', 'unit = "m"'), "answers[3] (tension_value).unit", "is a length (m), but the answer is a force"),
    (broken('unit = "N"', 'unit = "Nm"'), "answers[3] (tension_value).unit", "energy or torque"),
    (broken('unit = "N"', 'unit = "N"\nkind = "expression"').replace('kind = "numeric"\n', ""),
     "answers[3] (tension_value).unit", 'applies to kind = "numeric" answers only'),
    (broken("relative = 0.01", "relative = -0.01"), "answers[3] (tension_value).tolerance.relative", ">= 0"),
    (broken("relative = 0.01", "sig_figs = 0"), "answers[3] (tension_value).tolerance.sig_figs", "1 to 15"),
    (broken("relative = 0.01", "relativ = 0.01"), "answers[3] (tension_value).tolerance",
     "did you mean 'relative'"),
    (broken("weight = 2", "weight = -2"), "answers[3] (tension_value).weight", ">= 0"),
    (broken("score = 0.25", "score = 1.5"), "answers[2] (tension).feedback[0].score", "from 0 to 1"),
    (broken('expect = "not_equivalent"', 'expect = "wrong"'), "answers[0] (acceleration).tests[1].expect",
     "must be one of"),
    (broken("values = { m = 0.3 }", "values = { mass = 0.3 }"), "answers[3] (tension_value).tests[0].values",
     "'mass' is not a parameter"),
    (broken('kind = "numeric"', 'kind = "number"'), "answers[3] (tension_value).kind", "must be one of"),
])
def test_bad_keys_are_refused_with_the_key_and_the_problem(text, key, problem):
    with pytest.raises(SceneError) as error:
        parse_scene(text, source="yoyo_randomised.toml")
    assert error.value.key == key and problem in error.value.problem, str(error.value)


def test_a_numeric_answer_needs_a_number_for_everything_it_depends_on():
    symbolic_m = broken(M_RANDOM, 'm = { dimension = "mass", domain = "positive" }')
    with pytest.raises(SceneError, match="give m a value, random range or choices"):
        derive(parse_scene(symbolic_m, source="y.toml")).references()


def test_grader_derive_prints_the_tests_and_fails_on_a_failing_one(tmp_path):
    from click.testing import CliRunner

    from grader.cli.derive import derive as derive_cli

    passing = CliRunner().invoke(derive_cli, [str(ROOT / "problems" / "yoyo.toml")])
    assert passing.exit_code == 0, passing.output
    assert "Question tests\n  ok   acceleration: '2g/3' expects equivalent, got equivalent" in passing.output
    failing = tmp_path / "yoyo.toml"
    failing.write_text((ROOT / "problems" / "yoyo.toml").read_text().replace('answer = "2g/3"', 'answer = "g/3"'))
    result = CliRunner().invoke(derive_cli, [str(failing)])
    assert result.exit_code == 4
    assert "FAIL acceleration: 'g/3' expects equivalent, got not_equivalent" in result.output
