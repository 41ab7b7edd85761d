"""Fixtures for the page tests: accounts that sign in, a signed-in client per role, CSRF tokens.

Import what a test module uses (``from tests.web.conftest_pages import accounts, as_student``); the
``app``, ``client`` and ``yoyo_version`` fixtures come from ``tests/conftest.py``.
"""

from __future__ import annotations

import dataclasses
import re
from dataclasses import dataclass

import pytest
from flask.testing import FlaskClient

from grader.store.models import Course, Enrolment
from grader.store.problems import save_problem
from grader.store.users import create_user

PASSWORD = "correct horse battery staple"


@dataclass(frozen=True)
class Account:
    id: int
    email: str
    role: str
    password: str = PASSWORD


class Clock:
    """The server's clock (``app.config["CLOCK"]``), set by the test."""

    def __init__(self, now):
        self.now = now

    def __call__(self):
        return self.now


def csrf(client: FlaskClient) -> str:
    """The CSRF token of the client's session, as a form on a page would carry it."""
    with client.session_transaction() as session:
        return session.setdefault("_csrf", "test-csrf-token")


def form_token(html: str) -> str:
    """The CSRF token in a rendered form (proves the page really carries one)."""
    match = re.search(r'name="csrf_token" value="([^"]+)"', html)
    assert match, "the page has no CSRF field"
    return match.group(1)


def sign_in(client: FlaskClient, account: Account):
    page = client.get("/login")
    return client.post("/login", data={"username": account.email, "password": account.password,
                                       "csrf_token": form_token(page.get_data(as_text=True))})


@pytest.fixture
def accounts(app) -> dict[str, Account]:
    """Two students (ada, bob), an instructor (ine) teaching "MECH", an instructor of another course."""
    with app.extensions["lagrade.db"].write() as session:
        made = {}
        for key, role in (("ada", "student"), ("bob", "student"), ("ine", "instructor"), ("oth", "instructor")):
            user = create_user(session, role=role, name=key.capitalize(), email=f"{key}@example.org",
                               password=PASSWORD)
            made[key] = Account(user.id, user.email, role)
        mech, other = Course(code="MECH", title="Mechanics"), Course(code="OTHER", title="Other")
        session.add_all([mech, other])
        session.flush()
        session.add_all([Enrolment(user_id=made["ada"].id, course_id=mech.id, role="student"),
                         Enrolment(user_id=made["bob"].id, course_id=mech.id, role="student"),
                         Enrolment(user_id=made["ine"].id, course_id=mech.id, role="instructor"),
                         Enrolment(user_id=made["oth"].id, course_id=other.id, role="instructor")])
        made["course"] = mech.id
        made["other_course"] = other.id
    return made


def _signed_in(app, account: Account) -> FlaskClient:
    client = app.test_client()
    response = sign_in(client, account)
    assert response.status_code == 302, response.get_data(as_text=True)
    return client


@pytest.fixture
def as_student(app, accounts) -> FlaskClient:
    return _signed_in(app, accounts["ada"])


@pytest.fixture
def as_other_student(app, accounts) -> FlaskClient:
    return _signed_in(app, accounts["bob"])


@pytest.fixture
def as_instructor(app, accounts) -> FlaskClient:
    return _signed_in(app, accounts["ine"])


class InProcessChecker:
    """The real checker without a sandbox child: fast for tests, same verdicts."""

    def run(self, request: dict, budget_s: float | None = None) -> dict:
        from grader.answers.checker import check_request

        return check_request(dict(request, budget_s=budget_s) if budget_s else request)

    def close(self) -> None:
        pass


@pytest.fixture
def checkers(app):
    """Make the app's checker pool (used to group wrong answers) check in this process."""
    app.extensions["lagrade.checkers"].factory = InProcessChecker
    return app


def grade_all(app) -> int:
    """Grade every queued submission now, as a worker would (the real checker, in process)."""
    from grader.jobs import queue
    from grader.jobs.grading import check_task, score
    from grader.store.models import utcnow

    database, checker, graded = app.extensions["lagrade.db"], InProcessChecker(), 0
    while (task := queue.claim(database, "test-worker")) is not None:
        started = utcnow()
        result = check_task(checker, task)
        queue.record(database, task, "test-worker", result, score=score(result), grade_ms=1.0, started_at=started)
        graded += 1
    return graded


@pytest.fixture
def problems(app, accounts, yoyo, yoyo_version) -> dict[str, int]:
    """Besides the yo-yo (published, in no course): copies of it that only some users may see.

    ``mech`` is published in MECH (ada, bob, ine), ``other`` in OTHER (only oth teaches it), and
    ``draft`` is an unpublished problem in no course.
    """
    made = {"yoyo": yoyo_version}
    with app.extensions["lagrade.db"].write() as session:
        for slug, course, published in (("mech", accounts["course"], True), ("other", accounts["other_course"], True),
                                        ("draft", None, False)):
            derived = dataclasses.replace(yoyo, slug=slug, title=f"{slug.capitalize()} problem",
                                          source=f'id = "{slug}"\n')
            version, _ = save_problem(session, derived, published=published)
            version.problem.course_id = course
            made[slug] = version.id
    return made


def submit_answers(client: FlaskClient, slug: str, **texts: str):
    data = {f"answer-{name}": text for name, text in texts.items()}
    return client.post(f"/problems/{slug}/submit", data=dict(data, csrf_token=csrf(client)))
