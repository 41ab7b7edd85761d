"""Grading a hand-in for a randomised problem: the worker checks a numeric answer at the student's
own drawn numbers (stored with the hand-in), so each student's right number is right for them only."""

from __future__ import annotations

from datetime import datetime, timezone

import pytest

from grader.jobs import queue
from grader.jobs.assignment_submissions import hand_in
from grader.jobs.grading import check_task
from grader.store.assignments import create_assignment
from grader.store.courses import Member, add_member, create_course
from grader.store.draws import stored_values
from grader.store.problems import save_problem
from tests.web.conftest_pages import InProcessChecker
from tests.web.derive_in_process import derive_in_process

SCENE = "tests/mechanics/randomised/yoyo_randomised.toml"
NOW = datetime(2026, 12, 5, tzinfo=timezone.utc)


@pytest.fixture(scope="module")
def randomised():
    """The randomised yo-yo, derived once (m and R drawn per student, g fixed at 9.81)."""
    from pathlib import Path

    path = Path(__file__).resolve().parents[2] / SCENE
    return derive_in_process(path.read_text(), path.name)


@pytest.fixture
def setting(database, randomised):
    """Course MECH with Ada and Bob, homework hw1 over the randomised yo-yo; returns ids and users."""
    with database.write() as session:
        save_problem(session, randomised)
        course = create_course(session, code="MECH", title="Mechanics")
        students = [add_member(session, course, Member(name, f"{name}@example.org"))[0].user for name in ("ada", "bob")]
        assignment = create_assignment(session, course, slug="hw1", title="Homework 1", problems=[randomised.slug],
                                       opens_at=datetime(2026, 12, 1, tzinfo=timezone.utc),
                                       due_at=datetime(2026, 12, 8, tzinfo=timezone.utc))
        ids = {"assignment": assignment.id, "problem": assignment.problems[0].problem_id}
        for user in students:
            session.expunge(user)
    return ids, students


def _grade(database, checker) -> dict[int, tuple[str, dict | None]]:
    """Grade every queued submission as a worker does; (verdict, the values the task carried) by id."""
    from grader.jobs.grading import score
    from grader.store.models import utcnow

    graded = {}
    while (task := queue.claim(database, "test")) is not None:
        result = check_task(checker, task)
        queue.record(database, task, "test", result, score=score(result), grade_ms=1.0, started_at=utcnow())
        graded[task.submission_id] = (result["verdict"], task.values)
    return graded


def test_each_students_number_is_checked_at_their_own_values(database, setting):
    ids, (ada, bob) = setting
    tensions = {}
    for student in (ada, bob):
        # The draw is made (and stored) with the first hand-in; the right tension is m g / 3 at it.
        hand_in(database, user=student, assignment_id=ids["assignment"], problem_id=ids["problem"],
                answer="acceleration", text="2*g/3", now=NOW, secret="s")
        with database.read() as session:
            values = stored_values(session, ids["assignment"], student.id, ids["problem"])
        tensions[student.id] = (values, values["m"] * values["g"] / 3)
    assert tensions[ada.id][0] != tensions[bob.id][0], "the two students drew the same numbers"
    sent = {}
    for student, other in ((ada, bob), (bob, ada)):
        for whose in (student, other):
            submission_id, _, _ = hand_in(database, user=student, assignment_id=ids["assignment"],
                                       problem_id=ids["problem"], answer="tension_value",
                                       text=f"{tensions[whose.id][1]:.6g} N", now=NOW, secret="s")
            sent[submission_id] = (student.id, whose.id)
    graded = _grade(database, InProcessChecker())
    for submission_id, (student_id, whose_id) in sent.items():
        verdict, values = graded[submission_id]
        assert values == tensions[student_id][0]  # the task carries the student's own numbers
        assert (verdict == "equivalent") is (student_id == whose_id), (student_id, whose_id, verdict)
