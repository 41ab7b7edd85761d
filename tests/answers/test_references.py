"""The engine's reference answers check against themselves and agree with the corpus's references."""

import json
from pathlib import Path

import pytest

from grader.answers import check
from grader.answers.reference import ReferenceAnswer
from grader.mechanics.lagrange import derive
from grader.mechanics.scene import load_scene, parse_scene

PROBLEMS = sorted((Path(__file__).parents[2] / "problems").glob("*.toml"))
CORPUS = Path(__file__).parent / "corpus"
CORPUS_REFERENCES = {}
for path in CORPUS.glob("*.jsonl"):
    for line in open(path, encoding="utf-8"):
        item = json.loads(line)
        CORPUS_REFERENCES.setdefault((item["problem"], item["question"]), item["reference"])


@pytest.fixture(scope="module")
def references():
    # Read through the contract, as the service reads them: every scene's output must pass it.
    return {path.stem: [ReferenceAnswer.from_json(r) for r in derive(load_scene(path)).references()]
            for path in PROBLEMS}


def test_every_engine_reference_is_equivalent_to_itself_and_to_the_corpus(references):
    compared = 0
    for problem, refs in references.items():
        for ref in refs:
            v = check(ref.reference, ref.reference, ref.variables, kind=ref.kind, feedback=ref.feedback)
            assert v.verdict == "equivalent", (problem, ref.name, v.reason)
            assert not any("skipped" in n for n in v.parsed["notes"]), (problem, ref.name, v.parsed["notes"])
            ours = CORPUS_REFERENCES.get((problem, ref.name))
            if ours is not None:
                v = check(ref.reference, ours, ref.variables, kind=ref.kind)
                assert v.verdict == "equivalent", (problem, ref.name, ref.reference, ours, v.reason)
                compared += 1
    assert compared >= 20


def test_instructor_feedback_from_scene_files_reaches_the_student(references):
    tension = next(r for r in references["pendulum"] if r.name == "tension")
    v = check(tension.reference, "m g cos(theta)", tension.variables, feedback=tension.feedback)
    assert v.verdict == "not_equivalent" and v.feedback[0]["code"] == "instructor"


def test_a_reference_answer_round_trips_through_its_stored_json(references):
    for refs in references.values():
        for ref in refs:
            assert ReferenceAnswer.from_json(ref.to_json()) == ref


@pytest.mark.parametrize("change, message", [
    ({"kind": "formula"}, "'kind' must be one of"),
    ({"reference": 3}, "'reference' must be a string"),
    ({"variables": {"m": "kg"}}, "'variables' must map names"),
    ({"feedback": [{"expr": "m"}]}, "'feedback' must be a list"),
    ({"feedback_detail": "everything"}, "'feedback_detail' must be one of"),
], ids=["kind", "reference", "variables", "feedback", "detail"])
def test_stored_data_that_breaks_the_contract_is_refused_with_its_key(references, change, message):
    data = dict(references["yoyo"][0].to_json(), **change)
    with pytest.raises(ValueError, match=message):
        ReferenceAnswer.from_json(data)


def test_a_scene_opts_in_to_detailed_feedback_for_all_its_answers():
    source = (Path(__file__).parents[2] / "problems" / "yoyo.toml").read_text()
    detailed = derive(parse_scene(source + '\n[feedback]\ndetail = "full"\n')).references()
    assert {r["feedback_detail"] for r in detailed} == {"full"}
    assert {r["feedback_detail"] for r in derive(parse_scene(source)).references()} == {"kind"}
