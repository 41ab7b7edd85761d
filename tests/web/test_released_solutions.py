"""Once an assignment's solutions are released, its hand-ins are closed, on every surface.

A release before the close showed every student the worked solution (with their own numbers) while
hand-ins were still accepted: read the solution, hand in its answer, full marks. The rule is the
store's window (`grader.store.assignments.deadline_state`): released solutions close the assignment.
"""

from __future__ import annotations

from datetime import timedelta

import pytest
from sqlalchemy import func, select

from grader.store.models import Submission, User
from grader.store.users import set_password
from tests.web.conftest_pages import PASSWORD, Account, csrf, sign_in
from tests.web.test_api_courses import DUE, OPENS, clock, course, student  # noqa: F401  (fixtures)


def _api(app, client, student):
    headers = student("s-ada")
    return lambda text: client.post("/api/v1/courses/MECH/assignments/hw1/submissions", headers=headers,
                                    json={"problem": "yoyo", "answer": "tension", "text": text})


def _page(app, client, student):
    with app.extensions["lagrade.db"].write() as session:
        ada = session.scalar(select(User).where(User.external_id == "s-ada"))
        set_password(ada, PASSWORD)
        account = Account(ada.id, ada.email, "student")
    page = app.test_client()
    assert sign_in(page, account).status_code == 302
    return lambda text: page.post("/courses/MECH/assignments/hw1/submit",
                                  data={"problem": "yoyo", "answer-tension": text, "csrf_token": csrf(page)})


HAND_INS = {"api": (_api, 409), "page": (_page, 422)}


def _stored(app) -> int:
    with app.extensions["lagrade.db"].read() as session:
        return session.scalar(select(func.count()).select_from(Submission))


@pytest.mark.parametrize("surface", HAND_INS)
@pytest.mark.parametrize("when", [OPENS + timedelta(hours=1), DUE + timedelta(hours=1)], ids=["open", "late"])
def test_no_hand_in_is_accepted_once_the_solutions_are_released(app, client, clock, course, student, surface, when):
    make, refused_status = HAND_INS[surface]
    hand_in = make(app, client, student)
    clock.now = when
    assert hand_in("m*g").status_code in (202, 302)  # the window is open: accepted
    released = client.post("/api/v1/courses/MECH/assignments/hw1/release", headers=course["ine"])
    assert released.status_code == 200 and released.get_json()["state"] == "closed"
    view = client.get("/api/v1/courses/MECH/assignments/hw1", headers=student("s-ada")).get_json()
    assert view["solutions_available"] and view["state"] == "closed"
    before = _stored(app)
    refused = hand_in("g*m/3")  # the released solution's answer
    assert refused.status_code == refused_status
    assert "closed" in refused.get_data(as_text=True)
    assert _stored(app) == before
