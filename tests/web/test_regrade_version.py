"""A regrade grades against the version students see (the newest published), on every surface.

``POST /api/v1/problems/{id}/regrade`` took the newest version of any kind, so an unpublished draft
(unreviewed, its references seen by no student) graded every student's work, while the page's regrade
took the newest published one. Since a problem in no course is managed by every instructor, an
instructor of another course could upload a draft of a shared problem and regrade MECH's students
against it. The rule is now one function, `grader.web.problem_life.regrade_version`.
"""

from __future__ import annotations

import dataclasses

import pytest
from sqlalchemy import select

from grader.jobs import submit
from grader.store.models import ProblemVersion, Submission, User
from grader.store.problems import save_problem
from tests.web.conftest_pages import accounts, as_instructor, csrf  # noqa: F401  (fixtures)


def _api(app, client, as_instructor, make_token):
    _, headers = make_token("instructor")
    return lambda: client.post("/api/v1/problems/yoyo/regrade", headers=headers)


def _page(app, client, as_instructor, make_token):
    return lambda: as_instructor.post("/instructor/problems/yoyo/regrade", data={"csrf_token": csrf(as_instructor)})


SURFACES = {"api": _api, "page": _page}


@pytest.fixture
def draft_over_published(app, accounts, yoyo, yoyo_version):
    """The yo-yo (published, version 1; in no course) with Ada's answer, and a draft version 2 whose
    tension is wrong (m g)."""
    database = app.extensions["lagrade.db"]
    with database.read() as session:
        ada = session.get(User, accounts["ada"].id)
        published = session.get(ProblemVersion, yoyo_version)
        session.expunge_all()
    submission_id, _ = submit(database, user=ada, version=published, answer="tension", text="m*g/3")
    wrong = dataclasses.replace(yoyo, source=yoyo.source + "# draft\n", references=[
        dict(r, reference="g*m") if r["name"] == "tension" else r for r in yoyo.references])
    with database.write() as session:
        draft, _ = save_problem(session, wrong, published=False)
        return {"published": yoyo_version, "draft": draft.id, "submission": submission_id}


@pytest.mark.parametrize("surface", SURFACES)
def test_a_regrade_never_grades_against_a_draft(app, client, as_instructor, make_token, draft_over_published, surface):
    response = SURFACES[surface](app, client, as_instructor, make_token)()
    assert response.status_code in (202, 302)
    if surface == "api":
        assert response.get_json()["version"] == 1
    with app.extensions["lagrade.db"].read() as session:
        submission = session.get(Submission, draft_over_published["submission"])
        assert (submission.grading_round, submission.grading_version_id) == (2, draft_over_published["published"])


def test_the_api_refuses_to_regrade_a_problem_with_no_published_version(app, client, make_token, yoyo):
    with app.extensions["lagrade.db"].write() as session:
        save_problem(session, yoyo, published=False)
    _, headers = make_token("instructor")
    refused = client.post("/api/v1/problems/yoyo/regrade", headers=headers)
    assert refused.status_code == 409 and refused.mimetype == "application/problem+json"
    assert "publish" in refused.get_json()["detail"].lower()
