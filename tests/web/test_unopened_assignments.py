"""A problem set in an assignment that has not opened yet is hidden from the course's students on
every surface, as the assignment's own page hides its statement until it opens.

The assignment page withheld the statement and the prompts before the opening, but the problem itself
(published in the course: an assignment takes only published problems) was there to read at
/problems/{id}, GET /api/v1/problems/{id}, the problem lists and the live preview: an exam's problem
could be read days before it opened. The rule is the policy's (`grader.web.policy.find_version` and
`visible_versions`); its instructors see it as before, and its students once it opens.
"""

from __future__ import annotations

from datetime import datetime, timedelta, timezone

import pytest

from grader.store.assignments import create_assignment
from grader.store.models import Course
from grader.store.users import create_token
from tests.web.conftest_pages import Clock, accounts, as_instructor, as_student, csrf, problems  # noqa: F401  (fixtures)

OPENS = datetime(2026, 12, 1, 9, 0, tzinfo=timezone.utc)
STATEMENT = "A light string is wound around a solid cylinder"


@pytest.fixture
def exam(app, accounts, problems):
    """MECH's exam over its problem ``mech``, opening at OPENS; the clock a minute before; Ada's token."""
    app.config["CLOCK"] = clock = Clock(OPENS - timedelta(minutes=1))
    with app.extensions["lagrade.db"].write() as session:
        create_assignment(session, session.get(Course, accounts["course"]), slug="exam", title="Exam",
                          problems=["mech"], opens_at=OPENS, due_at=OPENS + timedelta(hours=2))
        from grader.store.models import User

        token = create_token(session, session.get(User, accounts["ada"].id))
    return {"clock": clock, "token": {"Authorization": f"Bearer {token}"}}


def _surfaces(client, page, token):
    """What Ada reads of the problem 'mech' on each surface: (status, whether the statement or the
    problem shows)."""
    api_one = client.get("/api/v1/problems/mech", headers=token)
    api_list = client.get("/api/v1/problems", headers=token)
    page_one = page.get("/problems/mech")
    page_list = page.get("/problems")
    preview = page.post("/preview", json={"problem": "mech", "answer": "tension", "text": "m*g"},
                        headers={"X-CSRF-Token": csrf(page)})
    return {
        "GET /api/v1/problems/mech": api_one.status_code == 200 and STATEMENT in api_one.get_data(as_text=True),
        "GET /api/v1/problems": "mech" in [p["id"] for p in api_list.get_json()["problems"]],
        "GET /problems/mech": page_one.status_code == 200 and STATEMENT in page_one.get_data(as_text=True),
        "GET /problems": 'href="/problems/mech"' in page_list.get_data(as_text=True),
        "POST /preview": preview.status_code == 200,
    }


def test_a_problem_of_an_assignment_not_yet_open_shows_nowhere_until_it_opens(app, client, as_student, exam):
    before = _surfaces(client, as_student, exam["token"])
    assert before == dict.fromkeys(before, False)
    exam["clock"].now = OPENS
    after = _surfaces(client, as_student, exam["token"])
    assert after == dict.fromkeys(after, True)


def test_its_instructor_and_other_courses_problems_are_not_hidden(app, client, as_instructor, as_student, exam):
    assert STATEMENT in as_instructor.get("/instructor/problems/mech/review").get_data(as_text=True)
    assert client.get("/api/v1/problems/yoyo", headers=exam["token"]).status_code == 200  # not in the exam
