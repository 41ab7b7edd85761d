"""Assignment rules: the window (to the second), late days and their cost, attempts per answer,
and what an assignment may be made of."""

from __future__ import annotations

import dataclasses
from datetime import datetime, timedelta, timezone

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from grader.jobs.assignment_submissions import HandInRefused, hand_in
from grader.store.assignments import (AssignmentError, attempts_used, create_assignment, deadline_state, late_days,
                                      late_factor, local_time, solutions_open)
from grader.store.courses import create_course
from grader.store.models import Assignment, User
from grader.store.problems import save_problem
from tests.conftest import YOYO

OPENS = datetime(2026, 12, 1, 9, 0, tzinfo=timezone.utc)
DUE = datetime(2026, 12, 8, 17, 0, tzinfo=timezone.utc)
CLOSES = DUE + timedelta(days=3)
SECOND = timedelta(seconds=1)


def _rules(**overrides) -> Assignment:
    values = dict(opens_at=OPENS.replace(tzinfo=None), due_at=DUE.replace(tzinfo=None),
                  closes_at=CLOSES.replace(tzinfo=None), late_penalty_per_day=0.2, solutions_released=False,
                  time_zone="America/New_York")
    return Assignment(**{**values, **overrides})


@pytest.mark.parametrize("now, state", [
    (OPENS - SECOND, "not_open"), (OPENS, "open"), (DUE, "open"), (DUE + SECOND, "late"),
    (CLOSES, "late"), (CLOSES + SECOND, "closed"),
])
def test_the_window_holds_to_the_second(now, state):
    assert deadline_state(_rules(), now) == state


def test_without_a_close_nothing_is_late_only_closed():
    assert deadline_state(_rules(closes_at=None), DUE + SECOND) == "closed"


@pytest.mark.parametrize("after, days, keeps", [
    (timedelta(0), 0, 1.0), (SECOND, 1, 0.8), (timedelta(days=1), 1, 0.8), (timedelta(days=1) + SECOND, 2, 0.6),
    (timedelta(days=3), 3, 0.4), (timedelta(days=9), 9, 0.0),  # never below nothing
])
def test_each_started_day_late_costs_the_penalty(after, days, keeps):
    assignment = _rules()
    assert late_days(assignment, DUE + after) == days
    assert late_factor(assignment, DUE + after) == pytest.approx(keeps)


@pytest.mark.parametrize("now, released, shown", [
    (CLOSES, False, False), (CLOSES + SECOND, False, True), (OPENS, True, True),
])
def test_solutions_open_at_the_close_or_when_released(now, released, shown):
    assert solutions_open(_rules(solutions_released=released), now) is shown


def test_times_are_shown_in_the_assignments_zone():
    assert local_time(_rules(), DUE.replace(tzinfo=None)).isoformat() == "2026-12-08T12:00:00-05:00"


@pytest.fixture
def course(database):
    with database.write() as session:
        save_problem(session, YOYO)
        save_problem(session, dataclasses.replace(YOYO, slug="draft", source="draft"), published=False)
        return create_course(session, code="MECH", title="Mechanics").id


def _make(database, course_id, **overrides):
    from grader.store.models import Course

    values = dict(slug="hw1", title="Homework 1", problems=["yoyo"], opens_at=OPENS, due_at=DUE, closes_at=CLOSES,
                  late_penalty_per_day=0.2, max_attempts=2)
    with database.write() as session:
        return create_assignment(session, session.get(Course, course_id), **{**values, **overrides}).id


@pytest.mark.parametrize("overrides, words", [
    ({"due_at": OPENS}, "opens before it is due"),
    ({"closes_at": DUE - SECOND}, "closes at or after"),
    ({"closes_at": None}, "late penalty needs a closing time"),
    ({"late_penalty_per_day": 1.5}, "from 0 to 1"),
    ({"max_attempts": 0}, "at least one attempt"),
    # the instructor page passed any digits on: 10**20 was a 500 (SQLite's OverflowError; PostgreSQL's
    # integer column overflows past 2**31 - 1)
    ({"max_attempts": 1001}, "at most 1000"),
    ({"max_attempts": 10**20}, "at most 1000"),
    ({"score_policy": "worst"}, "score policy"),
    ({"problems": []}, "1 to 50 different problems"),
    ({"problems": ["yoyo", "yoyo"]}, "1 to 50 different problems"),
    ({"problems": ["draft"]}, "no published version"),
    ({"opens_at": OPENS.replace(tzinfo=None)}, "needs its offset"),
    ({"time_zone": "Nowhere/Atlantis"}, "not a time zone"),
])
def test_an_assignment_that_makes_no_sense_is_refused(database, course, overrides, words):
    with pytest.raises(AssignmentError, match=words):
        _make(database, course, **overrides)


def test_an_assignment_pins_the_published_version_and_stores_utc(database, course):
    assignment_id = _make(database, course, opens_at=datetime.fromisoformat("2026-12-01T10:00:00+01:00"))
    with database.write() as session:
        save_problem(session, dataclasses.replace(YOYO, source="changed"))  # version 2 comes later
    with database.read() as session:
        assignment = session.get(Assignment, assignment_id)
        assert assignment.opens_at == datetime(2026, 12, 1, 9, 0)
        assert [p.problem_version.number for p in assignment.problems] == [1]


@pytest.fixture
def student(database, course):
    with database.write() as session:
        user = User(role="student", name="Ada")
        session.add(user)
        session.flush()
        session.expunge(user)
        return user


def test_hand_ins_count_per_answer_and_stop_at_the_limit(database, course, student):
    assignment_id = _make(database, course)
    with database.read() as session:
        problem_id = session.get(Assignment, assignment_id).problems[0].problem_id
    send = dict(user=student, assignment_id=assignment_id, problem_id=problem_id, now=OPENS)
    hand_in(database, answer="tension", text="m*g", **send)
    hand_in(database, answer="tension", text="m*g/3", **send)
    again = hand_in(database, answer="tension", text="m*g/3", **send)  # the same text: the same attempt
    assert again[2] is False
    with pytest.raises(HandInRefused, match="No attempts left") as refused:
        hand_in(database, answer="tension", text="m*g/2", **send)
    assert refused.value.reason == "no_attempts_left"
    hand_in(database, answer="acceleration", text="2*g/3", **send)
    with database.read() as session:
        assert attempts_used(session, assignment_id, student.id, problem_id, "tension") == 2
        assert attempts_used(session, assignment_id, student.id, problem_id, "acceleration") == 1


@pytest.mark.parametrize("now, reason", [(OPENS - SECOND, "not_open"), (CLOSES + SECOND, "closed")])
def test_hand_ins_outside_the_window_are_refused_and_store_nothing(database, course, student, now, reason):
    assignment_id = _make(database, course)
    with database.read() as session:
        problem_id = session.get(Assignment, assignment_id).problems[0].problem_id
    with pytest.raises(HandInRefused) as refused:
        hand_in(database, user=student, assignment_id=assignment_id, problem_id=problem_id, answer="tension",
                text="m*g/3", now=now)
    assert refused.value.reason == reason
    with database.read() as session:
        assert attempts_used(session, assignment_id, student.id, problem_id, "tension") == 0


def test_a_late_hand_in_is_stamped_with_the_servers_time(database, course, student):
    assignment_id = _make(database, course)
    with database.read() as session:
        problem_id = session.get(Assignment, assignment_id).problems[0].problem_id
    _, late, _ = hand_in(database, user=student, assignment_id=assignment_id, problem_id=problem_id, answer="tension",
                      text="m*g/3", now=DUE + SECOND)
    assert late == 1


@settings(max_examples=200, deadline=None)
@given(earlier=st.integers(-10 * 86400, 10 * 86400), later=st.integers(0, 3 * 86400),
       penalty=st.floats(0, 1, allow_nan=False))
def test_a_later_hand_in_never_keeps_more_and_every_started_day_counts(earlier, later, penalty):
    assignment = _rules(late_penalty_per_day=penalty)
    first, second = DUE + timedelta(seconds=earlier), DUE + timedelta(seconds=earlier + later)
    assert late_factor(assignment, second) <= late_factor(assignment, first)
    assert 0.0 <= late_factor(assignment, second) <= 1.0
    assert late_days(assignment, first) == max(0, -(-earlier // 86400))  # ceil of the days after due
