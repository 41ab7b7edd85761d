"""Partial credit: a wrong answer that matches an instructor's feedback entry with a ``score`` earns
that share of the answer's points; the verdict carries it and one rule (verdict.points) scores it."""

import pytest

from grader.answers.checker import check
from grader.answers.verdict import Verdict, points
from grader.jobs.grading import check_request, score

VARIABLES = {"m": {"dimension": "mass", "domain": "positive"}, "g": {"dimension": "acceleration", "domain": "positive"},
             "l": {"dimension": "length", "domain": "positive"}, "theta": {"dimension": "angle", "domain": "real"},
             "thetaddot": {"dimension": "angular_acceleration", "domain": "real", "kind": "acceleration"}}
FEEDBACK = [{"expr": "m*g", "message": "That is the weight.", "score": 0.25},
            {"expr": "m*g/2", "message": "Half the weight: check the moment of inertia."}]


@pytest.mark.parametrize("answer, verdict, partial", [
    ("m g/3", "equivalent", None),          # right: full marks, no partial score
    ("g m", "not_equivalent", 0.25),        # the weight: the instructor gives a quarter
    ("m g/2", "not_equivalent", None),      # a known slip without a score: a message, no points
    ("2 m g", "not_equivalent", None),      # an unknown wrong answer
])
def test_a_matched_entry_gives_its_score(answer, verdict, partial):
    v = check("m*g/3", answer, VARIABLES, feedback=FEEDBACK)
    assert (v.verdict, v.score) == (verdict, partial)
    assert ("score" in v.to_json()) is (partial is not None)


def test_the_feedback_item_says_which_entry_gave_the_score():
    v = check("m*g/3", "m*g", VARIABLES, feedback=FEEDBACK)
    assert {"code": "instructor", "message": "That is the weight.", "score": 0.25} in v.feedback


def test_equations_get_partial_credit_too():
    feedback = [{"expr": "thetaddot = g*sin(theta)/l", "message": "Check the sign of the restoring torque.",
                 "score": 0.5}]
    v = check("thetaddot = -g*sin(theta)/l", "l thetaddot = g sin(theta)", VARIABLES, kind="equation",
              feedback=feedback)
    assert v.verdict == "not_equivalent" and v.score == 0.5


def test_an_accepted_alternative_is_full_marks_not_partial_credit():
    v = check("m*g/3", "m*g", VARIABLES, feedback=FEEDBACK, alternatives=["m*g"])
    assert v.verdict == "equivalent" and v.score is None


@pytest.mark.parametrize("result, earned", [
    ({"verdict": "equivalent"}, 1.0),
    ({"verdict": "equivalent", "score": 0.25}, 1.0),
    ({"verdict": "not_equivalent"}, 0.0),
    ({"verdict": "not_equivalent", "score": 0.25}, 0.25),
    ({"verdict": "not_equivalent", "score": 7}, 1.0),      # clamped: a stored score never exceeds full marks
    ({"verdict": "not_equivalent", "score": True}, 0.0),   # not a number
    ({"verdict": "invalid", "score": 0.5}, 0.0),           # an unreadable answer earns nothing
])
def test_points_and_the_grading_score_are_one_rule(result, earned):
    assert points(result) == earned == score(result)


def test_the_verdict_round_trips_its_score():
    v = Verdict("not_equivalent", "proved", "differs", score=0.5)
    assert Verdict.from_json(v.to_json()).score == 0.5


def test_the_grading_request_carries_a_students_numbers_for_numeric_answers():
    reference = {"name": "w", "prompt": "W", "kind": "numeric", "reference": "g*m", "variables": VARIABLES,
                 "dimension": "kg*m*s^-2", "latex": "", "unit": "N",
                 "parameters": {"m": {"random": {"min": 1, "max": 2, "step": 0.5}}, "g": {"value": 9.81}}}
    request = check_request(reference, "14.7 N", values={"m": 1.5})
    assert request["values"] == {"g": 9.81, "m": 1.5} and request["kind"] == "numeric"
