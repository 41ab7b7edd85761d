"""The engine's reference answers check against themselves and agree with the corpus's references."""

import json
from pathlib import Path

import pytest

from grader.answers import check
from grader.mechanics.lagrange import derive
from grader.mechanics.scene import load_scene

PROBLEMS = sorted((Path(__file__).parents[2] / "problems").glob("*.toml"))
CORPUS = Path(__file__).parent / "corpus"
CORPUS_REFERENCES = {}
for path in CORPUS.glob("*.jsonl"):
    for line in open(path, encoding="utf-8"):
        item = json.loads(line)
        CORPUS_REFERENCES.setdefault((item["problem"], item["question"]), item["reference"])


@pytest.fixture(scope="module")
def references():
    return {path.stem: derive(load_scene(path)).references() for path in PROBLEMS}


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
