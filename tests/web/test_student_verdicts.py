"""What a verdict says to its student: one sentence to act on, each feedback line once, a counterexample
at round values with units and names as math, and never the reference's value."""

from types import SimpleNamespace

import pytest

from grader.answers.equations import _SINGULAR_MIXING
from grader.web.student.verdicts import student_summary, verdict_view

VARIABLES = {"m": {"dimension": "mass", "domain": "positive"}, "g": {"dimension": "acceleration", "domain": "positive"},
             "theta": {"dimension": "angle", "domain": "real"}, "thetadot": {"dimension": "angular_velocity"}}
REFERENCE = {"name": "tension", "prompt": "Tension $T$ in the string", "kind": "expression", "dimension": "force",
             "variables": VARIABLES}


def _submission(verdict=None, status="done", references=(REFERENCE,)):
    version = SimpleNamespace(reference=lambda name: next((r for r in references if r["name"] == name), None))
    return SimpleNamespace(id=7, status=status, answer_name="tension", text="m*g", problem_version=version,
                           verdict=verdict)


def _verdict(verdict="not_equivalent", reason="", feedback=(), counterexample=None, score=0.0):
    return SimpleNamespace(verdict=verdict, reason=reason, feedback=list(feedback), counterexample=counterexample,
                           parsed={"latex": "g m", "notes": []}, score=score)


TECHNICAL = [
    ("equivalent", "a state-independent multiple of the reference at 3 parameter points, to at least 38 digits "
                   "(ball arithmetic)"),
    ("equivalent", "agree at 4 sample points to at least 30 digits (ball arithmetic)"),
    ("not_equivalent", "your equation is the reference multiplied by a factor that depends on the state"),
    ("not_equivalent", "your equation is not the reference multiplied by a factor free of the state: the ratio "
                       "changes between two states (see the counterexample)"),
    ("invalid", "budget exceeded: the time budget ran out while comparing"),
    ("invalid", "could not decide: the equations could not be evaluated reliably"),
    # systems of equations mixed by state-dependent coefficients (grader.answers.equations)
    ("not_equivalent", _SINGULAR_MIXING),
    ("not_equivalent", "your equations are combinations of the reference equations whose mixing matrix depends on "
                       "the state and could not be shown invertible on the whole declared domain"),
    ("not_equivalent", "your equations agree with combinations of the reference equations with state-dependent "
                       "coefficients at every sample point, but that could not be proved"),
]


@pytest.mark.parametrize("kind, reason", TECHNICAL)
def test_a_student_never_reads_the_checkers_technical_account(kind, reason):
    summary = student_summary(kind, reason) or ""
    for word in ("ball arithmetic", "digits", "state-independent", "reference", "budget", "parameter points"):
        assert word not in summary
    if kind != "equivalent":
        assert summary.endswith(".") and summary[0].isupper()


@pytest.mark.parametrize("reason, says", [
    ("your answer differs from the correct one by a constant", "off by a constant term"),
    ("your answer is defined at a point of the domain where the correct one is not", "where the correct answer is "
                                                                                     "undefined"),
    ("budget exceeded: the time budget ran out while comparing", "ran out of time"),
    ("expected 2 equations, got 1", "different number of equations"),
    (_SINGULAR_MIXING, "becomes zero somewhere"),
])
def test_each_reason_reads_as_what_to_do(reason, says):
    kind = "invalid" if reason.startswith("budget") else "not_equivalent"
    assert says in student_summary(kind, reason)


def test_the_verdict_view_keeps_the_technical_reason_apart_for_instructors():
    reason = "agree at 4 sample points to at least 30 digits (ball arithmetic)"
    view = verdict_view(_submission(_verdict("equivalent", reason, score=1.0)))
    assert view["reason"] == reason and view["summary"] is None and view["label"] == "correct"


def test_one_slip_gets_one_feedback_line():
    message = "Check the sign: your answer is the negative of the correct one."
    feedback = [{"code": "sign", "message": message}, {"code": "instructor", "message": message}]
    view = verdict_view(_submission(_verdict(reason="your answer and the correct one differ at the point in the "
                                                     "counterexample", feedback=feedback)))
    assert view["feedback"] == [message] and view["summary"] is None  # the feedback says it: no second line


def test_the_instructors_message_for_a_known_wrong_answer_replaces_the_graders_guess():
    feedback = [{"code": "instructor", "message": "The tension must be less than the weight $mg$."},
                {"code": "factor", "message": "Your answer is off by a constant factor: check the numerical factors."}]
    view = verdict_view(_submission(_verdict(feedback=feedback)))
    assert view["feedback"] == ["The tension must be less than the weight $mg$."]


def test_a_counterexample_shows_the_point_with_units_and_the_students_value_only():
    example = {"values": {"theta": 0.5, "m": 1.0, "g": 2.0}, "answer": 2.1234567, "reference": 0.3333333}
    view = verdict_view(_submission(_verdict(reason="your answer and the correct one differ at the point in the "
                                                     "counterexample", counterexample=example)))
    point = view["point"]
    assert [(x["latex"], x["value"], x["unit"]) for x in point["values"]] == [
        (r"\theta", "0.5", "rad"), ("m", "1", "kg"), ("g", "2", "m/s²")]
    assert (point["answer"], point["unit"], point["kind"]) == ("2.123", "N", "differ")
    assert "0.3333" not in repr(view)


def test_where_the_answer_is_undefined_no_value_is_shown():
    example = {"values": {"m": 0.5}, "answer": "undefined", "reference": 1.5, "note": "division by zero"}
    point = verdict_view(_submission(_verdict(reason="your answer is undefined at a point where the correct one "
                                                      "is defined (division by zero)", counterexample=example)))
    assert point["point"]["kind"] == "undefined" and point["point"]["answer"] is None
    assert "1.5" not in repr(point)


def test_the_history_names_an_answer_by_its_prompt():
    assert verdict_view(_submission(_verdict()))["prompt"] == "Tension $T$ in the string"
    assert verdict_view(_submission(_verdict(), references=()))["prompt"] == "tension"  # an answer since removed


def test_a_submission_that_failed_says_it_is_not_the_students_fault():
    view = verdict_view(_submission(None, status="failed"))
    assert view["label"] == "could not be graded" and "not your fault" in view["summary"]


def test_an_equation_counterexample_says_where_but_no_residual():
    equation = dict(REFERENCE, kind="equation", dimension=None)
    example = {"values": {"theta": 2.0}, "answer": 0.917, "reference": 0.25}
    view = verdict_view(_submission(_verdict(reason="your equation is not the reference multiplied by a factor free "
                                                    "of the state: the ratio changes between two states",
                                             counterexample=example), references=(equation,)))
    assert view["point"]["kind"] == "equation" and view["point"]["answer"] is None
    assert "0.917" not in repr(view["point"]) and "constant multiple" in view["summary"]
