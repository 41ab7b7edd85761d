"""A hand-in for an assignment is its course's business, on every surface that shows work.

On a problem in no course (shared), an instructor sees the work of the students of the courses they
teach (`grader.web.policy.students_in_view`). Any instructor may enrol an existing account by e-mail:
an instructor of OTHER enrolled Ada (a student of MECH) in OTHER (POST /api/v1/courses/OTHER/members
{"email": "ada@example.org"}) and then read her hand-ins for MECH's homework over the shared yo-yo:
GET /api/v1/submissions/{id}, the problem's grades (JSON, CSV), its instructor page and its export.
A hand-in is now seen by its student, its course's instructors and TAs (and admins) only.
"""

from __future__ import annotations

from datetime import datetime, timedelta, timezone

import pytest
from sqlalchemy import select

from grader.jobs.assignment_submissions import hand_in
from grader.store.assignments import create_assignment
from grader.store.models import Course, Enrolment, User
from grader.store.users import create_token
from tests.web.conftest_pages import _signed_in, accounts  # noqa: F401  (fixtures)

HANDED_IN = "m*g/7"  # Ada's hand-in for MECH's homework (unique on every page)
PRACTICE = "g/5"  # her practice on the same shared problem, which OTHER's instructor may see


@pytest.fixture
def world(app, accounts, yoyo_version):
    """Ada, a student of MECH, enrolled in OTHER too by its instructor; her MECH hand-in and her
    practice on the shared yo-yo; a token for each instructor."""
    from grader.jobs import submit
    from grader.store.models import ProblemVersion

    database = app.extensions["lagrade.db"]
    now = datetime.now(timezone.utc)
    with database.write() as session:
        session.add(Enrolment(user_id=accounts["ada"].id, course_id=accounts["other_course"], role="student"))
        mech = session.get(Course, accounts["course"])
        assignment = create_assignment(session, mech, slug="hw1", title="Homework 1", problems=["yoyo"],
                                       opens_at=now - timedelta(days=1), due_at=now + timedelta(days=1))
        tokens = {key: create_token(session, session.get(User, accounts[key].id)) for key in ("ine", "oth")}
        assignment_id, problem_id = assignment.id, session.get(ProblemVersion, yoyo_version).problem_id
    with database.read() as session:
        ada = session.get(User, accounts["ada"].id)
        version = session.get(ProblemVersion, yoyo_version)
        session.expunge_all()
    handed, _, _ = hand_in(database, user=ada, assignment_id=assignment_id, problem_id=problem_id, answer="tension",
                           text=HANDED_IN, now=now, secret="test-secret")
    practice, _ = submit(database, user=ada, version=version, answer="acceleration", text=PRACTICE)
    return {"tokens": tokens, "handed": handed, "practice": practice}


def _api(app, accounts, world, who, path):
    client = app.test_client()
    return client.get(path.format(**world), headers={"Authorization": f"Bearer {world['tokens'][who]}"})


def _page(app, accounts, world, who, path):
    return _signed_in(app, accounts[who]).get(path)


# Each surface and what shows the hand-in there: the grades have a row per answer (Ada handed in
# "tension" and practised "acceleration"); the page and the export show the texts.
SURFACES = [
    (_api, "/api/v1/problems/yoyo/grades", '"tension"', '"acceleration"'),
    (_api, "/api/v1/problems/yoyo/grades?format=csv", ",tension,", ",acceleration,"),
    (_page, "/instructor/problems/yoyo", HANDED_IN, PRACTICE),
    (_page, "/instructor/problems/yoyo/submissions.csv", HANDED_IN, PRACTICE),
]


@pytest.mark.parametrize("surface, path, hand_in_shows, practice_shows", SURFACES, ids=[s[1] for s in SURFACES])
def test_another_courses_instructor_sees_her_practice_but_not_her_hand_in(app, accounts, world, surface, path,
                                                                          hand_in_shows, practice_shows):
    theirs = surface(app, accounts, world, "oth", path)
    assert theirs.status_code == 200
    body = theirs.get_data(as_text=True)
    assert hand_in_shows not in body and practice_shows in body
    ours = surface(app, accounts, world, "ine", path).get_data(as_text=True)  # MECH's instructor grades it
    assert hand_in_shows in ours and practice_shows in ours


@pytest.mark.parametrize("who, status", [("oth", 404), ("ine", 200)])
def test_a_hand_in_is_read_only_by_its_courses_graders(app, accounts, world, who, status):
    assert _api(app, accounts, world, who, "/api/v1/submissions/{handed}").status_code == status
    assert _api(app, accounts, world, who, "/api/v1/submissions/{practice}").status_code == 200
