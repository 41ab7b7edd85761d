"""Feedback on wrong answers: instructor messages and common slips, each earned by an equivalence check."""

import pytest

from grader.answers import check

TENSION = "m*l*thetadot^2 + m*g*cos(theta)"
INSTRUCTOR = [{"expr": "m*g*cos(theta)", "message": "That is the tension of a bob at rest."}]


@pytest.mark.parametrize("answer, code", [
    ("-m*l*thetadot^2 - m*g*cos(theta)", "sign"),
    ("2*m*l*thetadot^2 + 2*m*g*cos(theta)", "factor"),
    ("m*l*thetadot^2/2 + m*g*cos(theta)/2", "factor"),
    ("m*l*thetadot^2 + m*g*sin(theta)", "sin_cos"),
    ("m*l*thetadot^2", "missing_term"),
    ("m*l*thetadot^2 - m*g*cos(theta)", "term_sign"),
    ("m*l*thetadot^2 + m*g*cos(theta) + m*g", "extra_term"),
])
def test_common_slips_in_the_pendulum_tension_are_named(pendulum, answer, code):
    v = check(TENSION, answer, pendulum)
    assert v.verdict == "not_equivalent"
    assert code in [f["code"] for f in v.feedback]


def test_instructor_message_matches_by_equivalence_not_by_text(pendulum):
    v = check(TENSION, "g m cos θ", pendulum, feedback=INSTRUCTOR)
    assert v.feedback[0] == {"code": "instructor", "message": "That is the tension of a bob at rest."}


def test_right_answers_get_no_feedback(pendulum):
    assert check(TENSION, "m(l thetadot^2 + g cos theta)", pendulum, feedback=INSTRUCTOR).feedback == []


def test_rounded_numbers_are_called_close(atwood):
    v = check("m1*m2*g/(3*(m1 + m2))", "0.333333333*m1*m2*g/(m1 + m2)", atwood)
    assert v.verdict == "not_equivalent" and v.feedback[0]["code"] == "close"


def test_a_broken_instructor_entry_is_skipped_with_a_note(pendulum):
    v = check(TENSION, "m*g*cos(theta)", pendulum, feedback=[{"expr": "m*g*cos(", "message": "x"}])
    assert v.verdict == "not_equivalent"
    assert any("feedback entry skipped" in n for n in v.parsed["notes"])


def test_rolling_friction_instructor_message(rolling):
    v = check("beta*m*g*sin(alpha)/(1 + beta)", "m g sin(alpha)/(1+beta)", rolling,
              feedback=[{"expr": "m*g*sin(alpha)/(1 + beta)", "message": "That is m times the acceleration."}])
    assert v.feedback[0]["message"] == "That is m times the acceleration."
