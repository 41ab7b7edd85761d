"""Names and Role Provisioning: an instructor fills the course's roster from the LMS (two pages)."""

from __future__ import annotations

from sqlalchemy import select

from grader.store.lti_models import LtiContext
from grader.store.models import Enrolment, User
from tests.web.conftest_pages import form_token
from tests.web.lti_platform import CLAIM, INSTRUCTOR, LEARNER, launch, lms, tool  # noqa: F401

MEMBERS = [
    {"user_id": "teacher-1", "roles": [INSTRUCTOR], "name": "Prof. Noether", "status": "Active"},
    {"user_id": "student-1", "roles": [LEARNER], "name": "Ada Lovelace"},
    {"user_id": "student-2", "roles": ["Learner"], "given_name": "Emmy", "family_name": "Student"},
    {"user_id": "student-3", "roles": [LEARNER], "name": "Gone", "status": "Deleted"},
]


def _instructor(tool, lms):
    client = tool.test_client()
    response, _ = launch(client, lms, {"sub": "teacher-1", CLAIM + "roles": [INSTRUCTOR]})
    assert response.status_code == 302
    return client


def test_a_roster_sync_enrols_every_active_member_in_their_role(tool, lms):
    lms.members = MEMBERS
    client = _instructor(tool, lms)
    page = client.get("/lti/config").get_data(as_text=True)
    assert "Analytical Mechanics" in page and "never synced" in page
    with tool.extensions["lagrade.db"].read() as session:
        context = session.scalar(select(LtiContext))
    response = client.post(f"/lti/contexts/{context.id}/roster", data={"csrf_token": form_token(page)})
    assert response.status_code == 302
    assert "3 members (2 students, 1 instructors), 1 skipped" in client.get("/lti/config").get_data(as_text=True)
    with tool.extensions["lagrade.db"].read() as session:
        rows = session.execute(select(User.name, Enrolment.role).join(Enrolment, Enrolment.user_id == User.id)
                               .where(Enrolment.course_id == context.course_id).order_by(User.name)).all()
    assert rows == [("Ada Lovelace", "student"), ("Emmy Student", "student"), ("Prof. Noether", "instructor")]


def test_a_learner_later_launching_keeps_the_account_the_roster_gave(tool, lms):
    lms.members = MEMBERS
    client = _instructor(tool, lms)
    page = client.get("/lti/config").get_data(as_text=True)
    with tool.extensions["lagrade.db"].read() as session:
        context_id = session.scalar(select(LtiContext.id))
    client.post(f"/lti/contexts/{context_id}/roster", data={"csrf_token": form_token(page)})
    launch(tool.test_client(), lms, {"sub": "student-2", "name": "Emmy Student"})
    with tool.extensions["lagrade.db"].read() as session:
        assert len(session.scalars(select(User).where(User.name == "Emmy Student")).all()) == 1


def test_a_roster_service_that_fails_is_a_502_page(tool, lms):
    client = _instructor(tool, lms)
    page = client.get("/lti/config").get_data(as_text=True)
    with tool.extensions["lagrade.db"].write() as session:
        context = session.scalar(select(LtiContext))
        context.memberships_url = lms.url("/nothing-here")
        context_id = context.id
    response = client.post(f"/lti/contexts/{context_id}/roster", data={"csrf_token": form_token(page)})
    assert response.status_code == 502 and "nothing-here answered 404" in response.get_data(as_text=True)
